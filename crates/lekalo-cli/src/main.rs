//! `lekalo`: command-line front end of the lekalo spline kernel.
//!
//! Thin by design: parse arguments, call the library, write output. No mathematics here.

use anyhow::Result;
use clap::{Parser, Subcommand};

mod demo;

/// Construct, convert and analyse spline curves and surfaces.
#[derive(Parser, Debug)]
#[command(name = "lekalo", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run the built-in constructions of the five documents and print their key numbers.
    ///
    /// Example: `lekalo demo`
    Demo,
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Demo => demo::run(&mut std::io::stdout().lock()),
    }
}
