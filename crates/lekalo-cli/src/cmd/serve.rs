//! `lekalo serve`: the browser editor and its JSON API on a local port (docs/serve.md).

use std::net::{IpAddr, Ipv4Addr, SocketAddr};

use std::time::Duration;

use anyhow::{Context as _, Result};
use clap::Args;
use lekalo_serve::Limits;

use crate::context::Context;

/// Arguments of `lekalo serve`.
#[derive(Args, Debug)]
#[command(after_help = "\
The editor and the API answer on http://127.0.0.1:PORT/ (the API under /api/, docs/serve.md).
Only this machine can reach it unless --bind names another address.

Computations run on --workers threads, --queue more wait, and any further request gets 503
with Retry-After; a computation past --deadline is stopped and answered with 504, while
/api/health and the editor's files are answered throughout. Each request is checked against
--max-degree, --max-samples, --max-points and --max-work before anything is computed (400
naming the field and the option).

Examples:
  lekalo serve                    # http://127.0.0.1:8737/
  lekalo serve --port 0           # a free port, printed
  lekalo serve --open             # and open it in the default browser
  lekalo serve --max-degree 256 --deadline 30   # higher degrees, more time per request")]
pub(crate) struct ServeArgs {
    /// TCP port (0 picks a free one).
    #[arg(long, default_value_t = 8737)]
    port: u16,
    /// Address to listen on. Anything but a loopback address exposes the editor and its API
    /// to the network (a warning is printed).
    #[arg(long, value_name = "ADDR", default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    bind: IpAddr,
    /// Open the editor in the default browser once the server listens.
    #[arg(long)]
    open: bool,
    /// Largest request body in bytes.
    #[arg(long, value_name = "BYTES", default_value_t = Limits::default().body_bytes)]
    max_body: usize,
    /// Longest time for one request, in seconds, reading its body included (408 after it).
    #[arg(long, value_name = "SECONDS", default_value_t = 10)]
    timeout: u64,
    /// Longest time for one computation, in seconds, waiting for a worker included: it is then
    /// stopped and answered with 504. Keep it below --timeout.
    #[arg(long, value_name = "SECONDS", default_value_t = Limits::default().deadline.as_secs_f64(),
          value_parser = seconds)]
    deadline: f64,
    /// Computations that run at once [default: the number of CPUs].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    workers: Option<u32>,
    /// Computations that may wait for a worker; one more gets 503 with Retry-After.
    #[arg(long, value_name = "N", default_value_t = Limits::default().queue)]
    queue: usize,
    /// Connections served at once; beyond them a connection gets only the editor's page and
    /// /api/health, and every computing route 503 with Retry-After.
    #[arg(long, value_name = "N", default_value_t = Limits::default().connections,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..))]
    max_connections: usize,
    /// Highest degree of a curve a request sends or asks for.
    #[arg(long, value_name = "P", default_value_t = Limits::default().max_degree)]
    max_degree: usize,
    /// Most samples of a drawing (curve, basis panel, quasi-interpolation error).
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_samples)]
    max_samples: usize,
    /// Most points a request sends or asks for (data, control points, breakpoints).
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_points)]
    max_points: usize,
    /// Most work of one request, in evaluations × (degree + 1)².
    #[arg(long, value_name = "OPS", default_value_t = Limits::default().max_work)]
    max_work: u64,
}

/// A positive, finite number of seconds (at most a day).
fn seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(s) if s > 0.0 && s <= 86_400.0 => Ok(s),
        _ => Err(format!("{text:?}: give a number of seconds in (0, 86400]")),
    }
}

pub(crate) fn run(a: &ServeArgs, cx: &Context) -> Result<()> {
    if !a.bind.is_loopback() {
        eprintln!(
            "warning: listening on {}: other machines can reach the editor and its API; \
             use the default 127.0.0.1 unless you mean it",
            a.bind
        );
    }
    let defaults = Limits::default();
    let limits = Limits {
        body_bytes: a.max_body,
        timeout: Duration::from_secs(a.timeout.max(1)),
        deadline: Duration::from_secs_f64(a.deadline),
        workers: a.workers.map_or(defaults.workers, |w| w as usize),
        queue: a.queue,
        connections: a.max_connections,
        max_degree: a.max_degree,
        max_samples: a.max_samples,
        max_points: a.max_points,
        max_work: a.max_work,
    };
    let open = a.open;
    lekalo_serve::run(SocketAddr::new(a.bind, a.port), limits, |addr| {
        let url = format!("http://{addr}/");
        // the address is the result of the command: printed even with --quiet
        println!("lekalo serve: listening on {url}");
        if !cx.is_quiet() {
            eprintln!("press Ctrl-C to stop");
        }
        if open {
            open_browser(&url);
        }
    })
    .with_context(|| format!("cannot listen on {}:{}", a.bind, a.port))
}

fn open_browser(url: &str) {
    let (cmd, args): (&str, Vec<&str>) = if cfg!(target_os = "macos") {
        ("open", vec![url])
    } else if cfg!(windows) {
        ("cmd", vec!["/C", "start", "", url])
    } else {
        ("xdg-open", vec![url])
    };
    if let Err(e) = std::process::Command::new(cmd).args(&args).spawn() {
        eprintln!("note: could not open a browser ({cmd}: {e}); open {url} yourself");
    }
}
