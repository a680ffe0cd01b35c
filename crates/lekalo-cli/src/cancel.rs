//! Interruption: SIGINT, SIGTERM and SIGHUP set a cancel flag that long computations check
//! through [`lekalo::Progress`], so the command stops between two units of work, its
//! temporary output is removed and it exits with `128 +` the signal number (130 for Ctrl-C,
//! 143 for SIGTERM). Work that does not check the flag is stopped by the handler itself after
//! [`GRACE`], with the same clean-up and exit code.

use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
use std::time::Duration;

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

// The two flags below are the only process-wide state of the CLI, and must be: the signal
// thread sets them, and the handler's exit after [`GRACE`] reads them, outside any command's
// `Context`.

/// Set when a stopping signal arrives.
static CANCEL: AtomicBool = AtomicBool::new(false);
/// The signal that set [`CANCEL`].
static SIGNAL: AtomicI32 = AtomicI32::new(0);

/// How long the command may take to stop by itself after a signal before the handler removes
/// the temporary files and exits.
pub(crate) const GRACE: Duration = Duration::from_millis(700);

/// Starts the thread that waits for SIGINT, SIGTERM and SIGHUP.
pub(crate) fn install() {
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    let _ = std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                SIGNAL.store(sig, Ordering::SeqCst);
                CANCEL.store(true, Ordering::SeqCst);
                std::thread::sleep(GRACE);
                exit_interrupted();
            }
        });
}

/// The cancel flag given to the library's long computations.
pub(crate) fn flag() -> &'static AtomicBool {
    &CANCEL
}

/// The exit code of an interrupted run (`128 +` the signal), or `None` if no signal came.
pub(crate) fn exit_code() -> Option<u8> {
    if !CANCEL.load(Ordering::SeqCst) {
        return None;
    }
    u8::try_from(128 + SIGNAL.load(Ordering::SeqCst)).ok()
}

/// Removes the temporary files of outputs in progress, says so, and exits with the signal's
/// code.
pub(crate) fn exit_interrupted() -> ! {
    let n = lekalo_io::remove_temporary_files();
    crate::output::report(&format!(
        "interrupted{}",
        if n > 0 {
            "; the partial output was removed"
        } else {
            ""
        }
    ));
    std::process::exit(i32::from(exit_code().unwrap_or(130)));
}

/// Runs `f` with a [`lekalo::Progress`] that draws a bar of `what` on standard error (only on a
/// terminal, not with `-q`, and only for `large` work) and carries the cancel flag.
pub(crate) fn with_progress<R>(
    cx: &crate::context::Context,
    what: &str,
    large: bool,
    f: impl FnOnce(&lekalo::Progress<'_>) -> R,
) -> R {
    let bar = if large {
        crate::output::progress(cx, 0)
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_message(what.to_string());
    let report = |done: u64, total: u64| {
        bar.set_length(total);
        bar.set_position(done);
    };
    let progress = lekalo::Progress::new()
        .with_report(&report)
        .with_cancel(flag());
    let r = f(&progress);
    bar.finish_and_clear();
    r
}
