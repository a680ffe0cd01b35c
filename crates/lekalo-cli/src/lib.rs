//! The command line of the lekalo spline kernel, as a library: [`run`] parses an argument
//! vector and carries out the command; the `lekalo` binary (`main.rs`) only installs the
//! signal and panic handlers ([`install_handlers`]) and calls it. The library form lets the
//! fuzz target `cli_args` drive argument parsing and every command in one process.
//!
//! Thin by design: parse arguments, call the library (`lekalo`) and the formats crate
//! (`lekalo-io`), write output. No mathematics here.
//!
//! A request goes down through these modules and never back up:
//!
//! - this file: the argument grammar; [`run`] builds the run's `Context` and calls the command;
//! - `context.rs`: the `Context` (the global options) and the limits it sets;
//! - `cmd/`: one module per subcommand, grouped as the subcommands are; a command reads its
//!   items, does its work on one item, and hands the rest on;
//! - `items.rs`: what a command reads (one object, JSON Lines, CAD curves, a Parquet batch,
//!   points);
//! - `batch/`: the batch runner, given the command's work on one item as a closure;
//! - `output/`: writing results and progress; `report.rs`: `--json` results;
//! - `exit.rs`: error kinds and exit codes; `values.rs`: number lists in options;
//! - `cancel.rs`: signals; `words.rs`: the shared vocabulary and the messages in the options' names;
//! - `demo/`: `lekalo demo`.
//!
//! Exit codes: 0 success; 2 bad input (unreadable or invalid file, bad arguments, a value
//! outside the domain, an output path whose folder does not exist — the message names the file,
//! line and field, or the option); 3 internal failure (writing failed on valid input, e.g. a
//! full disk; rendering failed; a demo check did not reproduce its document);
//! 128 + the signal when interrupted (130 for Ctrl-C, 143 for SIGTERM).

use std::ffi::OsString;
use std::path::PathBuf;

use clap::{Args, CommandFactory, Parser, Subcommand};

mod batch;
mod cancel;
mod cmd;
mod context;
mod demo;
mod exit;
mod items;
mod output;
mod report;
mod values;
mod words;

use context::{Context, HeaderArg, Verbosity};

/// Construct, convert and analyse spline curves and surfaces.
///
/// Objects are read from the versioned JSON format (docs/formats.md) or JSON Lines of many
/// objects; `-` reads standard input. Outputs are written atomically and never over an input.
///
/// Exit codes: 0 success, 2 bad input, 3 internal failure.
#[derive(Parser, Debug)]
#[command(name = "lekalo", version, about, long_about, after_help = EXAMPLES)]
pub(crate) struct Cli {
    /// Print nothing but the results (no progress, no notes).
    #[arg(
        short,
        long,
        global = true,
        help_heading = "Global options",
        conflicts_with = "verbose"
    )]
    quiet: bool,
    /// Print what is read and written, with timings, to standard error.
    #[arg(short, long, global = true, help_heading = "Global options")]
    verbose: bool,
    /// Whether the first line of a CSV or text points file is a header: auto (only if no field
    /// on it is a number), yes or no.
    #[arg(long, global = true, help_heading = "Global options", value_enum, default_value_t = HeaderArg::Auto)]
    header: HeaderArg,
    /// Replace a write-protected output file too (it is refused otherwise, as by a shell's `>`).
    #[arg(long, global = true, help_heading = "Global options")]
    force: bool,
    /// Largest number of samples, knots, intervals or grid points a command may create from its
    /// arguments, and of entities, and of control points and knots together, a STEP or IGES file
    /// may hold (docs/robustness.md).
    #[arg(long, global = true, help_heading = "Global options", value_name = "N", default_value_t = context::DEFAULT_MAX_SIZE)]
    max_size: usize,
    /// Largest input, in bytes, a command reads from one file or from standard input: a file
    /// above it is refused by its size, a pipe or a device (which has no size) once more
    /// arrives (docs/robustness.md).
    #[arg(long, global = true, help_heading = "Global options", value_name = "BYTES", default_value_t = lekalo_io::DEFAULT_MAX_INPUT_BYTES)]
    max_input_bytes: u64,
    /// Highest Bezier degree for the work whose cost grows as the degree squared or cubed:
    /// evaluating, plotting and inspecting Bezier curves, real degree, exact and approximate
    /// reduction (docs/robustness.md).
    #[arg(long, global = true, help_heading = "Global options", value_name = "N", default_value_t = context::DEFAULT_MAX_DEGREE)]
    max_degree: usize,
    /// The key column of a Parquet batch: the column that groups points into point sets, and
    /// the key of each curve (docs/formats.md#parquet-batches).
    #[arg(long, global = true, help_heading = "Global options", value_name = "NAME", default_value = lekalo_io::DEFAULT_KEY)]
    group_column: String,
    #[command(subcommand)]
    command: Command,
}

const EXAMPLES: &str = "\
Examples:
  lekalo demo -o gallery               # the documents' constructions, as an HTML gallery
  lekalo make bspline --control pts.csv --degree 3 -o curve.json
  lekalo info curve.json
  lekalo eval curve.json --samples 5 --derivatives 1 --curvature
  lekalo knots averaged --degree 3 --params 0,5/17,9/17,14/17,1
  lekalo plot curve.json -o curve.svg --basis
  lekalo convert curve.json -o curve.step

Exit codes: 0 success, 2 bad input, 3 internal failure.";

#[derive(Subcommand, Debug)]
enum Command {
    /// Build a curve, surface or spline in N parameters from control points (and knots, weights).
    Make(cmd::make::MakeArgs),
    /// Evaluate points, derivatives and curvature at given parameters or on a uniform sampling.
    Eval(cmd::eval::EvalArgs),
    /// Show degree, knots, domain, bounding box of a curve, surface, pp-form or spline in N parameters (of every object of a batch; with --faces, the faces of a STEP or IGES file).
    Info(cmd::info::InfoArgs),
    /// Build knot vectors (uniform, averaged, from parameters, Curry–Schoenberg) or inspect one.
    Knots(cmd::knots::KnotsArgs),
    /// Convert between formats: JSON, JSON Lines, CSV samples, SVG, PNG, STEP and IGES (both ways), OBJ, NumPy .npz, Parquet.
    Convert(cmd::convert::ConvertArgs),
    /// Plot a curve (control polygon, knots, data points) or its basis functions to SVG/PNG.
    Plot(cmd::plot::PlotArgs),
    /// Run the documents' constructions on built-in data; print a summary table and optionally
    /// write an HTML gallery.
    Demo(DemoArgs),
    /// Interpolate points by a curve (every parametrisation, knot placement, end condition),
    /// a grid by a surface, a function y(x) by a natural or Hermite spline.
    Interpolate(Box<cmd::interpolate::InterpolateArgs>),
    /// Bezier order change: elevate, reduce, real-degree, change (curves and surfaces; B-splines piece by piece).
    Bezier(cmd::bezier::BezierArgs),
    /// Blending: deformation of curves, splines through points, corner smoothing.
    Blend(cmd::blend::BlendArgs),
    /// Exact swept surfaces from curves: revolution about an axis, extrusion, ruled surface.
    Sweep(cmd::sweep::SweepArgs),
    /// Fix parameters: a spline in N parameters in the others, a surface's iso-curve.
    Slice(cmd::slice::SliceArgs),
    /// Piecewise polynomials: pp-form ↔ B-spline, quasi-interpolation.
    Pp(cmd::pp::PpArgs),
    /// Knot operations on curves and surfaces: insert, refine, remove, split, reverse,
    /// reparam, decompose into Bezier pieces, join.
    Knot(cmd::knot::KnotArgs),
    /// Fit points: least squares, smoothing splines, fitting to a tolerance, robust fits;
    /// surfaces through grids and scattered data.
    Fit(Box<cmd::fit_args::FitArgs>),
    /// Length, parameter at length, exact bounding box, curvature extrema and inflections of a
    /// curve; the exact bounding box of a surface.
    Measure(cmd::measure::MeasureArgs),
    /// Closest points on a curve or a surface (single points or batches).
    Project(cmd::project::ProjectArgs),
    /// Intersections of curves, self-intersections, curve–plane; surface–surface and plane
    /// sections of surfaces.
    Intersect(cmd::intersect::IntersectArgs),
    /// The offset of a planar curve at a distance, with its cusps and loops found and trimmed.
    Offset(cmd::offset::OffsetArgs),
    /// A surface as a triangle mesh (OBJ/STL/PLY) or a curve as a polyline, within a tolerance.
    Mesh(cmd::mesh::MeshArgs),
    /// The browser editor: draw, drag and construct curves, backed by a local JSON API.
    Serve(cmd::serve::ServeArgs),
}

/// Arguments of `lekalo demo`.
#[derive(Args, Debug)]
#[command(after_help = "\
Examples:
  lekalo demo                 # print the summary table of every construction and check
  lekalo demo -o gallery      # also write gallery/index.html with SVG and PNG figures
  lekalo demo --only doc000-ends -o gallery      # redraw one entry in the gallery
  lekalo demo --only doc000-ends --json          # its tables and checks as JSON

Exit code 3 if a construction does not reproduce its document's numbers.")]
pub(crate) struct DemoArgs {
    /// Directory for the HTML gallery (created if missing): index.html and one SVG per figure
    /// (`--out` is the same option).
    #[arg(short, long = "output", visible_alias = "out", value_name = "DIR")]
    out: Option<PathBuf>,
    /// Run only the entry of this id (e.g. `doc000-ends`); the summary lists the ids. With
    /// --output, its figures are redrawn and its section of an existing gallery's index.html is
    /// replaced; the other entries stay.
    #[arg(long, value_name = "ID")]
    only: Option<String>,
    #[command(flatten)]
    json: crate::report::JsonFlag,
}

/// The last-resort panic hook (a short report, exit code 3) and the signal handlers (SIGINT,
/// SIGTERM, SIGHUP stop the command cleanly, docs/robustness.md). Called once by the binary
/// before [`run`].
///
/// A closed standard output is not an internal failure: `println!` panics when the reader has
/// gone (`lekalo … | head`), and the command then ends quietly with exit code 0, as a write
/// error on standard output does ([`run`]). Notes on standard error go through
/// `output::report`, which ignores a closed standard error, so that the command still writes its
/// output files (`lekalo demo --out g 2>&1 | head`).
pub fn install_handlers() {
    exit::install_panic_hook();
    cancel::install();
    let internal = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map_or("", String::as_str);
        if is_closed_pipe_panic(message) {
            lekalo_io::remove_temporary_files();
            std::process::exit(0);
        }
        internal(info);
    }));
}

/// True for the panic message of `println!` on a closed pipe (`failed printing to stdout:
/// Broken pipe (os error 32)`). Standard error is left out: a command that stopped there
/// might not have written its output yet, and exit code 0 would hide that.
fn is_closed_pipe_panic(message: &str) -> bool {
    message.starts_with("failed printing to stdout") && message.contains("Broken pipe")
}

/// The whole argument grammar (every subcommand, option and value set) as clap describes it:
/// for help generators, shell completions and the fuzz target that builds hostile command
/// lines from it.
pub fn command() -> clap::Command {
    Cli::command()
}

/// Parses `args` (the program name first) and runs the command; returns the exit code: 0
/// success (and `--help`, `--version`), 2 bad input or bad arguments, 3 internal failure,
/// `128 +` the signal when interrupted.
///
/// The global options (`--quiet`, `--verbose`, `--header`, `--force`, `--max-size`,
/// `--max-input-bytes`, `--max-degree`, `--group-column`) make the [`Context`] of this call, passed to the command;
/// nothing stays from one call to the next, so that one process may run several commands in
/// turn.
pub fn run<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let args: Vec<OsString> = args.into_iter().map(Into::into).collect();
    let words: Vec<String> = args
        .iter()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let cli = match Cli::try_parse_from(&args) {
        Ok(cli) => cli,
        Err(e) => {
            // clap's own report: usage errors on standard error (exit 2), help and version on
            // standard output (exit 0)
            let _ = e.print();
            return u8::try_from(e.exit_code()).unwrap_or(exit::EXIT_BAD_INPUT);
        }
    };
    if !cli.quiet {
        for w in cmd::deprecated::warnings(&words) {
            output::report(&format!("warning: {w}"));
        }
    }
    // whatever this command reads, through any option, no output of it may replace
    lekalo_io::protect_files_read();
    // and no input, endless or not, is read past this
    lekalo_io::limit_input_bytes(cli.max_input_bytes);
    let cx = Context {
        verbosity: if cli.quiet {
            Verbosity::Quiet
        } else if cli.verbose {
            Verbosity::Verbose
        } else {
            Verbosity::Normal
        },
        header: cli.header,
        force: cli.force,
        max_size: cli.max_size,
        max_degree: cli.max_degree,
        group_column: cli.group_column,
    };
    let result = match cli.command {
        Command::Make(a) => cmd::make::run(&a, &cx),
        Command::Eval(a) => cmd::eval::run(&a, &cx),
        Command::Info(a) => cmd::info::run(&a, &cx),
        Command::Knots(a) => cmd::knots::run(&a, &cx),
        Command::Convert(a) => cmd::convert::run(&a, &cx),
        Command::Plot(a) => cmd::plot::run(&a, &cx),
        Command::Demo(a) => demo::run(&cx, a.out.as_deref(), a.only.as_deref(), a.json.json),
        Command::Interpolate(a) => cmd::interpolate::run(&a, &cx),
        Command::Bezier(a) => cmd::bezier::run(&a, &cx),
        Command::Blend(a) => cmd::blend::run(&a, &cx),
        Command::Sweep(a) => cmd::sweep::run(&a, &cx),
        Command::Slice(a) => cmd::slice::run(&a, &cx),
        Command::Pp(a) => cmd::pp::run(&a, &cx),
        Command::Knot(a) => cmd::knot::run(&a, &cx),
        Command::Fit(a) => cmd::fit::run(&a, &cx),
        Command::Measure(a) => cmd::measure::run(&a, &cx),
        Command::Project(a) => cmd::project::run(&a, &cx),
        Command::Intersect(a) => cmd::intersect::run(&a, &cx),
        Command::Offset(a) => cmd::offset::run(&a, &cx),
        Command::Mesh(a) => cmd::mesh::run(&a, &cx),
        Command::Serve(a) => cmd::serve::run(&a, &cx),
    };
    match result {
        Ok(()) => 0,
        Err(e) if exit::is_broken_pipe(&e) => 0,
        Err(_) if cancel::exit_code().is_some() => cancel::exit_interrupted(),
        Err(e) => {
            output::report(&words::message(&e));
            exit::exit_code(&e)
        }
    }
}
