//! `lekalo serve`: the browser editor and its JSON API on a local port (docs/serve.md).

use std::net::{IpAddr, Ipv4Addr, SocketAddr};

use anyhow::{Context, Result};
use clap::Args;

use crate::Verbosity;

/// Arguments of `lekalo serve`.
#[derive(Args, Debug)]
#[command(after_help = "\
The editor and the API answer on http://127.0.0.1:PORT/ (the API under /api/, docs/serve.md).
Only this machine can reach it unless --bind names another address.

Examples:
  lekalo serve                    # http://127.0.0.1:8737/
  lekalo serve --port 0           # a free port, printed
  lekalo serve --open             # and open it in the default browser")]
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
    #[arg(long, value_name = "BYTES", default_value_t = lekalo_serve::Limits::default().body_bytes)]
    max_body: usize,
    /// Longest time for one request, in seconds.
    #[arg(long, value_name = "SECONDS", default_value_t = 10)]
    timeout: u64,
}

pub(crate) fn run(a: &ServeArgs, v: Verbosity) -> Result<()> {
    if !a.bind.is_loopback() {
        eprintln!(
            "warning: listening on {}: other machines can reach the editor and its API; \
             use the default 127.0.0.1 unless you mean it",
            a.bind
        );
    }
    let limits = lekalo_serve::Limits {
        body_bytes: a.max_body,
        timeout: std::time::Duration::from_secs(a.timeout.max(1)),
    };
    let open = a.open;
    lekalo_serve::run(SocketAddr::new(a.bind, a.port), limits, |addr| {
        let url = format!("http://{addr}/");
        // the address is the result of the command: printed even with --quiet
        println!("lekalo serve: listening on {url}");
        if v != Verbosity::Quiet {
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
