//! `lekalo`: the command-line front end of the lekalo spline kernel (the crate's library,
//! `lekalo_cli`, holds the commands).

use std::process::ExitCode;

fn main() -> ExitCode {
    lekalo_cli::install_handlers();
    ExitCode::from(lekalo_cli::run(std::env::args_os()))
}
