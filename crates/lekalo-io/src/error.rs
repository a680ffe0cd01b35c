//! The one error type of the formats crate: every message names the source (file or `<stdin>`),
//! the line and the field when they are known, and says how to fix the input.

use std::fmt;
use std::path::PathBuf;

/// Where in an input a problem is: source name (file path or `<stdin>`), line (1-based) and
/// field, each when known.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Location {
    /// File path, `<stdin>` or another name of the input.
    pub source: String,
    /// 1-based line number.
    pub line: Option<usize>,
    /// Field name (JSON key) or column (`column 2`).
    pub field: Option<String>,
}

impl Location {
    /// A location in `source` with no line or field yet.
    #[must_use]
    pub fn new(source: impl Into<String>) -> Self {
        Location {
            source: source.into(),
            line: None,
            field: None,
        }
    }

    /// The same location at `line`.
    #[must_use]
    pub fn at_line(mut self, line: usize) -> Self {
        self.line = Some(line);
        self
    }

    /// The same location at `field`.
    #[must_use]
    pub fn at_field(mut self, field: impl Into<String>) -> Self {
        self.field = Some(field.into());
        self
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.source)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if let Some(field) = &self.field {
            write!(f, ": field `{field}`")?;
        }
        Ok(())
    }
}

/// Errors of reading and writing lekalo files.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum IoError {
    /// The input is malformed: not JSON, not a number, a missing or unknown field, a wrong
    /// format version.
    #[error("{at}: {message}")]
    Syntax {
        /// Where.
        at: Location,
        /// What is wrong and how to fix it.
        message: String,
    },
    /// The input is well-formed but the library's validating constructor rejected it.
    #[error("{at}: {error}")]
    Invalid {
        /// Where (the field is derived from the kind of error when possible).
        at: Location,
        /// The library's error (part of the message, so not a separate `source`).
        error: lekalo::Error,
    },
    /// An input file could not be read.
    #[error("cannot read {}: {}", .path.display(), read_reason(.error))]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        error: std::io::Error,
    },
    /// The output path cannot be written as given: its folder does not exist or may not be
    /// written in, or it names a folder. The user's input (the reason says the fix: create the
    /// folder, or choose another path), unlike a failure while writing ([`IoError::Write`]).
    #[error("cannot write {}: {reason}", path.display())]
    OutputPath {
        /// The output path as given.
        path: PathBuf,
        /// What is wrong with it and the fix, naming the folder.
        reason: String,
    },
    /// An output file could not be written (the disk is full, the device failed, the rename
    /// failed).
    #[error("cannot write {}: {error}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        error: std::io::Error,
    },
    /// The output path is one of the inputs; lekalo never overwrites its inputs.
    #[error("refusing to write {}: it is an input file; choose another output path", path.display())]
    WouldOverwriteInput {
        /// The path.
        path: PathBuf,
    },
    /// The output file exists and is write-protected (no write permission for anyone); it is
    /// replaced only when the caller says so (`--force` in the CLI), as a shell's `>` refuses.
    #[error("refusing to replace {}: it is write-protected; give --force to replace it, or choose another output path", path.display())]
    WriteProtected {
        /// The path.
        path: PathBuf,
    },
    /// A size declared by the input or the arguments is above a limit, or memory for it could
    /// not be reserved; the message names the limit and the option that raises it.
    #[error("{what}")]
    TooLarge {
        /// What, the limit, and how to raise it.
        what: String,
    },
    /// A count or size of the input is above a limit the caller set and may raise (`limit`):
    /// the message says what, then how to raise it in the command line's words
    /// ([`Limit::option`]); other front ends word the fix in their own vocabulary from the
    /// same fields ([`IoError::message_with`]).
    #[error("{}", .limit.refusal(what, *.raise_to, Limit::option))]
    OverLimit {
        /// What is above the limit, with the input's name, the count and the limit.
        what: String,
        /// The limit.
        limit: Limit,
        /// The smallest value of the limit that admits this input, when it is known.
        raise_to: Option<u64>,
    },
    /// The object cannot be written in the requested format (e.g. a 4-D curve to STEP).
    #[error("{what}")]
    Unsupported {
        /// What and why, with the alternative.
        what: String,
    },
    /// Rendering an SVG to PNG failed (an internal failure, not bad input).
    #[error("rendering failed: {0}")]
    Render(String),
    /// The caller's cancel flag ([`lekalo::Progress::with_cancel`]) stopped a read; nothing of
    /// it is returned.
    #[error("{at}: {what}: cancelled")]
    Cancelled {
        /// The input.
        at: Location,
        /// The work that stopped, e.g. `reading STEP`.
        what: &'static str,
    },
}

impl IoError {
    /// True if the error is the user's input (exit code 2 in the CLI), false for an internal
    /// or environment failure (exit code 3).
    #[must_use]
    pub fn is_bad_input(&self) -> bool {
        match self {
            IoError::Syntax { .. }
            | IoError::Invalid { .. }
            | IoError::Read { .. }
            | IoError::OutputPath { .. }
            | IoError::WouldOverwriteInput { .. }
            | IoError::WriteProtected { .. }
            | IoError::TooLarge { .. }
            | IoError::OverLimit { .. }
            | IoError::Unsupported { .. } => true,
            IoError::Write { .. } | IoError::Render(_) | IoError::Cancelled { .. } => false,
        }
    }

    /// [`IoError::Cancelled`] for a [`lekalo::Progress`] step that reported the cancel flag
    /// (any other error of the step is the same stop).
    pub(crate) fn cancelled(source: &str, e: &lekalo::Error) -> Self {
        IoError::Cancelled {
            at: Location::new(source),
            what: match e {
                lekalo::Error::Cancelled { what } => what,
                _ => "reading",
            },
        }
    }

    /// The message with a limit's option named by `option` (for example Python's keyword,
    /// `max_size`, where the command line says `--max-size`): [`IoError::OverLimit`] worded
    /// from its fields, every other error as its `Display`.
    ///
    /// ```
    /// use lekalo_io::{IoError, Limit};
    /// let e = IoError::OverLimit { what: "c.step: 700 knots".into(), limit: Limit::Size, raise_to: Some(700) };
    /// assert!(e.to_string().ends_with("raise the limit with --max-size 700 if the machine has the memory"));
    /// let python = e.message_with(|l| if l == Limit::Size { "max_size=" } else { "max_input_bytes=" });
    /// assert!(python.ends_with("raise the limit with max_size=700 if the machine has the memory"));
    /// ```
    #[must_use]
    pub fn message_with(&self, option: impl Fn(Limit) -> &'static str) -> String {
        match self {
            IoError::OverLimit {
                what,
                limit,
                raise_to,
            } => limit.refusal(what, *raise_to, option),
            other => other.to_string(),
        }
    }

    pub(crate) fn syntax(at: Location, message: impl Into<String>) -> Self {
        IoError::Syntax {
            at,
            message: message.into(),
        }
    }
}

/// A limit of reading that the caller sets and may raise ([`IoError::OverLimit`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Limit {
    /// The entities, control points and knots of one read (the command line's `--max-size`).
    Size,
    /// The bytes of one input (the command line's `--max-input-bytes`).
    InputBytes,
}

impl Limit {
    /// The command line's option, with the space before its value.
    #[must_use]
    pub fn option(self) -> &'static str {
        match self {
            Limit::Size => "--max-size ",
            Limit::InputBytes => "--max-input-bytes ",
        }
    }

    /// `what`, then how to raise this limit: with `option` naming it, to `raise_to` when known.
    fn refusal(
        self,
        what: &str,
        raise_to: Option<u64>,
        option: impl Fn(Limit) -> &'static str,
    ) -> String {
        format!(
            "{what}; raise the limit with {} {}",
            self.spelled(raise_to, option),
            self.condition()
        )
    }

    /// When raising the limit is the fix.
    fn condition(self) -> &'static str {
        match self {
            Limit::Size => "if the machine has the memory",
            Limit::InputBytes => "if the input is meant to be that large",
        }
    }

    /// The option as `option` names it, with the value `raise_to` when it is known
    /// (`--max-size 700`), as "a larger" option otherwise.
    fn spelled(self, raise_to: Option<u64>, option: impl Fn(Limit) -> &'static str) -> String {
        let name = option(self);
        match raise_to {
            Some(n) => format!("{name}{n}"),
            None => format!("a larger {}", name.trim_end_matches([' ', '='])),
        }
    }
}

/// Result of the formats crate.
pub type IoResult<T> = std::result::Result<T, IoError>;

/// Why an input could not be read, in the user's words with the fix: the operating system's
/// text without its error number for a missing file, a folder or a refused permission, the
/// error's own text (already worded for the user) otherwise.
fn read_reason(error: &std::io::Error) -> String {
    use std::io::ErrorKind;
    match error.kind() {
        ErrorKind::NotFound => "no such file; check the name and the folder (paths are relative to the current folder), or make the file first".into(),
        ErrorKind::IsADirectory => "it is a folder; give a file in it".into(),
        ErrorKind::PermissionDenied => "permission denied; make the file readable (chmod +r) or copy it".into(),
        _ => error.to_string(),
    }
}
