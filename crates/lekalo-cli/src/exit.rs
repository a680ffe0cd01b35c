//! How a run ends: the kinds of error (bad input, exit code 2; internal failure, exit code 3),
//! the exit code of an error, and the last-resort panic hook.

use std::io::Write;

use anyhow::Result;
use lekalo_io::IoError;

/// Exit code for bad input.
pub(crate) const EXIT_BAD_INPUT: u8 = 2;
/// Exit code for an internal failure.
pub(crate) const EXIT_INTERNAL: u8 = 3;

/// A problem with the user's input or arguments (exit code 2).
#[derive(Debug)]
pub(crate) struct BadInput(pub(crate) String);

impl std::fmt::Display for BadInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// An internal failure (exit code 3), e.g. a demo check that did not reproduce its document.
#[derive(Debug)]
pub(crate) struct Internal(pub(crate) String);

impl std::fmt::Display for Internal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Internal {}

/// `Err(BadInput)` with a message.
pub(crate) fn bad_input<T>(msg: impl Into<String>) -> Result<T> {
    Err(BadInput(msg.into()).into())
}

/// Exit code of an error: 2 if anything in its chain is the user's input, 3 otherwise.
pub(crate) fn exit_code(e: &anyhow::Error) -> u8 {
    for cause in e.chain() {
        if let Some(io) = cause.downcast_ref::<IoError>() {
            return if io.is_bad_input() {
                EXIT_BAD_INPUT
            } else {
                EXIT_INTERNAL
            };
        }
        if cause.downcast_ref::<BadInput>().is_some()
            || cause.downcast_ref::<lekalo::Error>().is_some()
        {
            return EXIT_BAD_INPUT;
        }
        if cause.downcast_ref::<Internal>().is_some() {
            return EXIT_INTERNAL;
        }
    }
    EXIT_INTERNAL
}

/// True if the error is a write to a closed pipe (`lekalo eval … | head`): the reader has
/// what it wanted, so the command stops quietly.
pub(crate) fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

/// The last-resort handler: a panic prints a short report and exits with code 3 (it is a bug;
/// every input error has its own message); the signal handlers are `cancel`'s.
pub(crate) fn install_panic_hook() {
    std::panic::set_hook(Box::new(|info| {
        lekalo_io::remove_temporary_files();
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        let what = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| (*s).to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        // (written here, not through `output`: a closed standard error is ignored)
        let _ = writeln!(
            std::io::stderr().lock(),
            "internal error{at}: {what}\nThis is a bug in lekalo: please report it with the command and input that caused it."
        );
        std::process::exit(i32::from(EXIT_INTERNAL));
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_codes() {
        assert_eq!(exit_code(&anyhow::anyhow!("plain")), EXIT_INTERNAL);
        let lib: anyhow::Error = lekalo::KnotVector::new(vec![1.0, 0.0]).unwrap_err().into();
        assert_eq!(exit_code(&lib), EXIT_BAD_INPUT);
        let bad: anyhow::Error = bad_input::<()>("x").unwrap_err();
        assert_eq!(exit_code(&bad), EXIT_BAD_INPUT);
    }
}
