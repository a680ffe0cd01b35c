//! The one-pass reader of CSV and whitespace points files behind [`crate::read_points_with`].
//!
//! The text is scanned once: lines are found with `memchr`, fields are string slices of the
//! line, and every coordinate goes straight into one flat `Vec<f64>` reserved from the size of
//! the first row. Nothing is allocated per line or per point (the only allocations are the
//! header names and the flat buffer), so reading runs at the speed of number parsing. Numbers
//! are parsed by the standard library's `f64::from_str` (the Eisel-Lemire algorithm with an
//! exact fallback), which also defines which texts are numbers for the header rule.
//!
//! The rules are those documented in [`crate::points_in`]: blank and `#` lines skipped, fields
//! split at `,`/`;` when the line has one, else at blanks, each field trimmed; the header rule
//! of [`Header`]; every row as long as the first; every coordinate finite.

use lekalo::Points;
use rayon::prelude::*;

use crate::error::{IoError, IoResult, Location};
use crate::points_in::Header;

/// The fields of one (trimmed, non-empty) line, without allocating.
enum Fields<'a> {
    /// Split at `,` and `;` (found with `memchr2`), each field trimmed; `None` after the last.
    Separated(Option<&'a str>),
    /// Split at runs of white space.
    Blank(std::str::SplitWhitespace<'a>),
}

impl<'a> Fields<'a> {
    fn of(line: &'a str) -> Self {
        if memchr::memchr2(b',', b';', line.as_bytes()).is_some() {
            Fields::Separated(Some(line))
        } else {
            Fields::Blank(line.split_whitespace())
        }
    }
}

impl<'a> Iterator for Fields<'a> {
    type Item = &'a str;
    fn next(&mut self) -> Option<&'a str> {
        match self {
            Fields::Separated(rest) => {
                let r = (*rest)?;
                // `,` and `;` are ASCII, so the split points are character boundaries
                Some(trim(match memchr::memchr2(b',', b';', r.as_bytes()) {
                    Some(i) => {
                        *rest = Some(&r[i + 1..]);
                        &r[..i]
                    }
                    None => {
                        *rest = None;
                        r
                    }
                }))
            }
            Fields::Blank(s) => s.next(),
        }
    }
}

/// `str::trim`, skipped when both ends are visible ASCII (the usual case).
fn trim(s: &str) -> &str {
    match (s.as_bytes().first(), s.as_bytes().last()) {
        (Some(a), Some(z)) if a.is_ascii_graphic() && z.is_ascii_graphic() => s,
        _ => s.trim(),
    }
}

/// The reader's state between lines.
struct Reader<'s> {
    source: &'s str,
    header: Option<Vec<String>>,
    /// The dimension and the line that set it.
    dim: Option<(usize, usize)>,
    data: Vec<f64>,
    /// From this many bytes on, the text after the first point is read in parallel parts.
    parallel_min: usize,
}

impl Reader<'_> {
    /// The name of column `k` (0-based) in messages: the header's, else `k + 1`.
    fn column(&self, k: usize) -> String {
        self.header
            .as_ref()
            .and_then(|h| h.get(k).cloned())
            .unwrap_or_else(|| format!("{}", k + 1))
    }

    fn at(&self, line_no: usize) -> Location {
        Location::new(self.source).at_line(line_no)
    }

    fn wrong_count(&self, line_no: usize, n: usize) -> IoError {
        let (d, first) = self.dim.unwrap_or((0, 0));
        IoError::syntax(
            self.at(line_no),
            format!(
                "{n} fields, but line {first} has {d}; every point needs the same number of coordinates"
            ),
        )
    }

    /// Reserves room for the rows of `rest` (the text after the first data line), estimated
    /// from the lines in its first 64 KiB.
    fn reserve(&mut self, dim: usize, rest: &[u8]) -> IoResult<()> {
        let sample = &rest[..rest.len().min(1 << 16)];
        let lines = memchr::memchr_iter(b'\n', sample).count() + 1;
        let rows = rest.len() / (sample.len() / lines).max(1) + 1;
        let want = rows.saturating_add(rows / 8).saturating_mul(dim);
        self.data.try_reserve(want).map_err(|_| IoError::TooLarge {
            what: format!(
                "{}: cannot reserve memory for about {want} coordinates",
                self.source
            ),
        })
    }

    /// Reads the coordinates of one data line.
    fn row(&mut self, line: &str, line_no: usize) -> IoResult<()> {
        let mut fields = Fields::of(line);
        let start = self.data.len();
        let mut k = 0usize;
        while let Some(f) = fields.next() {
            let parsed = f.parse::<f64>();
            match parsed {
                Ok(v) if v.is_finite() => self.data.push(v),
                _ => {
                    let n = k + 1 + fields.count();
                    if self.dim.is_some_and(|(d, _)| d != n) {
                        return Err(self.wrong_count(line_no, n));
                    }
                    let at = self.at(line_no).at_field(self.column(k));
                    return Err(IoError::syntax(
                        at,
                        if parsed.is_ok() {
                            format!(
                                "\"{f}\" is not finite; every coordinate must be a finite number"
                            )
                        } else {
                            format!("cannot read \"{f}\" as a number")
                        },
                    ));
                }
            }
            k += 1;
        }
        match self.dim {
            Some((d, _)) if d != k => {
                self.data.truncate(start);
                Err(self.wrong_count(line_no, k))
            }
            Some(_) => Ok(()),
            None => {
                self.dim = Some((k, line_no));
                Ok(())
            }
        }
    }
}

/// Below this many bytes after the first point, the rest is read on one thread.
const PARALLEL_MIN: usize = 1 << 22;

/// The `(start, end)` byte ranges of the lines of `text` (`end` before the `\n`).
fn line_ranges(text: &[u8]) -> impl Iterator<Item = (usize, usize)> + '_ {
    let mut start = 0usize;
    std::iter::from_fn(move || {
        if start >= text.len() {
            return None;
        }
        let end = memchr::memchr(b'\n', &text[start..]).map_or(text.len(), |i| start + i);
        let r = (start, end);
        start = end + 1;
        Some(r)
    })
}

impl Reader<'_> {
    /// Reads the data lines of `text`, whose first line is line `first_line`.
    fn lines(&mut self, text: &str, first_line: usize) -> IoResult<()> {
        for (n, (a, b)) in line_ranges(text.as_bytes()).enumerate() {
            // `\n` is ASCII, so both ends are character boundaries
            let line = trim(&text[a..b]);
            if !(line.is_empty() || line.starts_with('#')) {
                self.row(line, first_line + n)?;
            }
        }
        Ok(())
    }

    /// Reads `rest`, the text after the first point (whose line is `line_no`): in parts on all
    /// cores when it is long, the parts' numbers joined in order and the first error in the file
    /// reported with its line.
    fn rest(&mut self, rest: &str, line_no: usize) -> IoResult<()> {
        let Some((dim, _)) = self.dim else {
            return Ok(());
        };
        let threads = rayon::current_num_threads();
        if rest.len() < self.parallel_min || threads < 2 {
            self.reserve(dim, rest.as_bytes())?;
            return self.lines(rest, line_no + 1);
        }
        let bytes = rest.as_bytes();
        let parts = threads * 2;
        let mut cuts = vec![0usize];
        for k in 1..parts {
            let at = (bytes.len() * k / parts).max(*cuts.last().unwrap_or(&0));
            let cut = memchr::memchr(b'\n', &bytes[at..]).map_or(bytes.len(), |i| at + i + 1);
            cuts.push(cut);
        }
        cuts.push(bytes.len());
        let results: Vec<IoResult<Vec<f64>>> = cuts
            .windows(2)
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|w| {
                let mut part = Reader {
                    source: self.source,
                    header: self.header.clone(),
                    dim: self.dim,
                    data: Vec::new(),
                    parallel_min: usize::MAX,
                };
                let text = &rest[w[0]..w[1]];
                part.reserve(dim, text.as_bytes())?;
                part.lines(text, 1)?;
                Ok(part.data)
            })
            .collect();
        let mut total = 0usize;
        for (k, r) in results.iter().enumerate() {
            match r {
                Ok(d) => total += d.len(),
                Err(e) => {
                    // the part's line numbers count from 1 at its start
                    let before = line_no + memchr::memchr_iter(b'\n', &bytes[..cuts[k]]).count();
                    return Err(shift_line(e, before));
                }
            }
        }
        self.data
            .try_reserve_exact(total)
            .map_err(|_| IoError::TooLarge {
                what: format!(
                    "{}: cannot reserve memory for {total} coordinates",
                    self.source
                ),
            })?;
        for d in results.into_iter().flatten() {
            self.data.extend_from_slice(&d);
        }
        Ok(())
    }
}

/// `e` with its line moved down by `by` lines.
fn shift_line(e: &IoError, by: usize) -> IoError {
    match e {
        IoError::Syntax { at, message } => {
            let mut at = at.clone();
            at.line = at.line.map(|l| l + by);
            IoError::syntax(at, message.clone())
        }
        IoError::TooLarge { what } => IoError::TooLarge { what: what.clone() },
        other => IoError::syntax(Location::default(), other.to_string()),
    }
}

/// Reads CSV or whitespace-separated points (the text has no byte-order mark).
pub(crate) fn read_delimited(text: &str, source: &str, header_rule: Header) -> IoResult<Points> {
    read_delimited_from(text, source, header_rule, PARALLEL_MIN)
}

/// [`read_delimited`] with the threshold of the parallel reading given (tests read small texts
/// in parallel parts too).
pub(crate) fn read_delimited_from(
    text: &str,
    source: &str,
    header_rule: Header,
    parallel_min: usize,
) -> IoResult<Points> {
    let mut r = Reader {
        source,
        header: None,
        dim: None,
        data: Vec::new(),
        parallel_min,
    };
    let bytes = text.as_bytes();
    let mut rest_at = bytes.len();
    let mut first_point_line = 0usize;
    for (n, (a, b)) in line_ranges(bytes).enumerate() {
        let line = trim(&text[a..b]);
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if r.header.is_none() {
            let is_header = match header_rule {
                Header::Yes => true,
                Header::No => false,
                Header::Auto => Fields::of(line).all(|f| f.parse::<f64>().is_err()),
            };
            if is_header {
                r.header = Some(Fields::of(line).map(str::to_string).collect());
                continue;
            }
        }
        r.row(line, n + 1)?;
        rest_at = (b + 1).min(bytes.len());
        first_point_line = n + 1;
        break;
    }
    r.rest(&text[rest_at..], first_point_line)?;
    let Some((dim, _)) = r.dim else {
        return Err(IoError::syntax(
            Location::new(source),
            "no points found; write one point per line, e.g. `1.0, 2.0`",
        ));
    };
    Points::from_flat(dim, r.data).map_err(|e| IoError::Invalid {
        at: Location::new(source),
        error: e,
    })
}
