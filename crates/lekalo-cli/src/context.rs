//! The context of one run: the global options (`--quiet`/`--verbose`, `--header`, `--force`,
//! `--max-size`, `--max-degree`, `--group-column`), built once from the command line by
//! [`crate::run`] and passed by reference to every command, with the limits they set
//! (docs/robustness.md). The command line keeps no option of a run in process-wide state
//! (the signal flags of `cancel.rs` are the one exception a signal handler needs), so one
//! process may run several commands in turn (the fuzz target does).

use anyhow::Result;
use lekalo_io::Object;

use crate::exit::bad_input;

/// Default of `--max-size`.
pub(crate) const DEFAULT_MAX_SIZE: usize = 10_000_000;

/// Default of `--max-degree`.
pub(crate) const DEFAULT_MAX_DEGREE: usize = 2_000;

/// How much to say on standard error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Verbosity {
    Quiet,
    Normal,
    Verbose,
}

/// `--header`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum HeaderArg {
    /// A header only if no field on the first line is a number.
    Auto,
    /// The first line is a header.
    Yes,
    /// No header.
    No,
}

/// The global options of the command being run.
#[derive(Debug, Clone)]
pub(crate) struct Context {
    /// `--quiet`, `--verbose`.
    pub(crate) verbosity: Verbosity,
    /// `--header`: whether the first line of a CSV or text points file is a header.
    pub(crate) header: HeaderArg,
    /// `--force`: replace a write-protected output file too.
    pub(crate) force: bool,
    /// `--max-size`: the most samples, knots, intervals or grid points made from arguments.
    pub(crate) max_size: usize,
    /// `--max-degree`: the highest Bezier degree for work that grows as its square or cube.
    pub(crate) max_degree: usize,
    /// `--group-column`: the key column of Parquet batches.
    pub(crate) group_column: String,
}

impl Default for Context {
    /// The defaults of the global options.
    fn default() -> Self {
        Context {
            verbosity: Verbosity::Normal,
            header: HeaderArg::Auto,
            force: false,
            max_size: DEFAULT_MAX_SIZE,
            max_degree: DEFAULT_MAX_DEGREE,
            group_column: lekalo_io::DEFAULT_KEY.to_string(),
        }
    }
}

impl Context {
    /// True with `--quiet`: nothing but the results.
    pub(crate) fn is_quiet(&self) -> bool {
        self.verbosity == Verbosity::Quiet
    }

    /// True with `--verbose`: what is read and written, with timings.
    pub(crate) fn is_verbose(&self) -> bool {
        self.verbosity == Verbosity::Verbose
    }

    /// The same options, quiet: for work whose notes would repeat once per item.
    pub(crate) fn quiet(&self) -> Context {
        Context {
            verbosity: Verbosity::Quiet,
            ..self.clone()
        }
    }

    /// The header rule of `--header`.
    pub(crate) fn header_rule(&self) -> lekalo_io::Header {
        match self.header {
            HeaderArg::Auto => lekalo_io::Header::Auto,
            HeaderArg::Yes => lekalo_io::Header::Yes,
            HeaderArg::No => lekalo_io::Header::No,
        }
    }

    /// The options of an atomic write (`--force`).
    pub(crate) fn write_options(&self) -> lekalo_io::WriteOptions {
        lekalo_io::WriteOptions { force: self.force }
    }

    /// `Err(BadInput)` if `n` (given by `option`) is above `--max-size`.
    pub(crate) fn check_size(&self, n: usize, option: &str) -> Result<()> {
        let limit = self.max_size;
        if n > limit {
            return bad_input(format!(
                "{option} {n} is above the size limit {limit}; raise the limit with --max-size {n} if the machine has the memory"
            ));
        }
        Ok(())
    }

    /// `n` given by `option` if it is in `[min, max]`, else `Err(BadInput)` naming the option
    /// and the bound (never a silent clamp). `max` above `--max-size` is lowered to it.
    pub(crate) fn in_range(&self, n: usize, min: usize, max: usize, option: &str) -> Result<usize> {
        if n < min {
            return bad_input(format!("{option} {n}: at least {min} are needed"));
        }
        if max >= self.max_size {
            self.check_size(n, option)?;
        } else if n > max {
            return bad_input(format!(
                "{option} {n} is above {max}, the most this output can use; give at most {max}"
            ));
        }
        Ok(n)
    }

    /// `Err(BadInput)` if a Bezier curve's degree is above `--max-degree` for `what` (work that
    /// grows as the degree squared or cubed).
    pub(crate) fn check_bezier_degree(&self, obj: &Object, what: &str) -> Result<()> {
        let limit = self.max_degree;
        if let Object::Bezier(c) = obj {
            if c.degree() > limit {
                return bad_input(format!(
                    "{what} of a Bezier curve of degree {} is above the degree limit {limit} (its cost grows as the degree squared or faster); raise it with --max-degree {}, or convert the curve to a B-spline of lower degree",
                    c.degree(),
                    c.degree()
                ));
            }
        }
        Ok(())
    }
}

/// Checks that `n` values of `T` can be allocated before a library call allocates them (an
/// allocation failure there would abort the process): `Err` naming `option`.
pub(crate) fn check_memory<T>(n: usize, option: &str) -> Result<()> {
    let mut probe: Vec<T> = Vec::new();
    if probe.try_reserve_exact(n).is_err() {
        return bad_input(format!(
            "{option}: cannot reserve memory for {n} values ({} bytes); lower {option}",
            n.saturating_mul(std::mem::size_of::<T>())
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The limits follow the context they are asked of, not a process-wide setting.
    #[test]
    fn limits_follow_the_context() {
        let small = Context {
            max_size: 10,
            ..Context::default()
        };
        assert!(small.check_size(11, "--samples").is_err());
        assert!(Context::default().check_size(11, "--samples").is_ok());
        assert_eq!(small.in_range(10, 1, usize::MAX, "--samples").unwrap(), 10);
        let e = small.in_range(0, 1, usize::MAX, "--samples").unwrap_err();
        assert!(e.to_string().contains("at least 1"), "{e}");
        let e = Context::default().in_range(9, 1, 8, "--n").unwrap_err();
        assert!(e.to_string().contains("give at most 8"), "{e}");
        assert!(Context::default().quiet().is_quiet());
        assert_eq!(Context::default().group_column, lekalo_io::DEFAULT_KEY);
    }
}
