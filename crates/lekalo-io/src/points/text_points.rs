//! The one-pass reader of CSV and whitespace points files behind [`crate::read_points_with`].
//!
//! The text is scanned once, and every coordinate goes straight into one flat buffer sized from
//! the lines of the text ([`row_bound`]); nothing is allocated per line or per point (the only
//! allocations are the header names and the flat buffer), and a long text is read in parts on
//! all cores, each into its own stretch of that buffer. The text comes as bytes: each part is
//! checked as UTF-8 by the thread that parses it, and the lines that bound the parts' rows are
//! counted in parallel too, so that little of the work happens before the parts start.
//!
//! A row in the common layout — numbers separated by single commas, as many as the first
//! row's, then the end of the line — is read by [`plain_row`] without looking for its
//! separators first: `fast_float2::parse_partial` reads each number and says where it ends,
//! and the byte there must be the comma or the line's end.
//! Any other line (blanks, `;`, a comment, a wrong field) goes to the general reader, which finds
//! lines with `memchr`, splits fields as string slices and parses them with the standard
//! library's `f64::from_str`; that parser defines which texts are numbers (for the header rule
//! too) and words every error. Both parsers implement the same Eisel-Lemire algorithm with an
//! exact fallback and give the same `f64` for every text (a property test checks it).
//!
//! The rules are those documented in [`crate::points_in`]: blank and `#` lines skipped, fields
//! split at `,`/`;` when the line has one, else at blanks, each field trimmed; the header rule
//! of [`Header`]; every row as long as the first; every coordinate finite.

use lekalo::Points;
use rayon::prelude::*;

use crate::error::{IoError, IoResult, Location};

/// Whether the first line of a CSV or whitespace points file is a header naming the columns.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Header {
    /// A header if no field on the first line parses as a number.
    #[default]
    Auto,
    /// The first line is a header, whatever it holds.
    Yes,
    /// There is no header: the first line is a point.
    No,
}

/// The fields of one (trimmed, non-empty) line, without allocating.
pub(crate) enum Fields<'a> {
    /// Split at `,` and `;` (found with `memchr2`), each field trimmed; `None` after the last.
    Separated(Option<&'a str>),
    /// Split at runs of white space.
    Blank(std::str::SplitWhitespace<'a>),
}

impl<'a> Fields<'a> {
    pub(crate) fn of(line: &'a str) -> Self {
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

/// The coordinates read so far, in a slice sized before reading: room for every row a text can
/// hold, so that the parts of a long text are read on all cores straight into the one buffer of
/// the result (no vector per part, no copy to join them).
struct Rows<'b> {
    buf: &'b mut [f64],
    len: usize,
}

impl Rows<'_> {
    /// Appends `v`; `false` if the slice is full.
    fn push(&mut self, v: f64) -> bool {
        match self.buf.get_mut(self.len) {
            Some(slot) => {
                *slot = v;
                self.len += 1;
                true
            }
            None => false,
        }
    }

    fn truncate(&mut self, len: usize) {
        self.len = self.len.min(len);
    }
}

/// The most rows of `dim` coordinates that `text` can hold: one a line, and each at least
/// `2 dim` bytes (a digit and a separator or the line's end per coordinate; the last line may
/// lack its `\n`). Also returns the number of lines.
fn row_bound(text: &[u8], dim: usize) -> (usize, usize) {
    let newlines = memchr::memchr_iter(b'\n', text).count();
    let lines = newlines + usize::from(text.last().is_some_and(|&b| b != b'\n'));
    (lines.min((text.len() + 1) / (2 * dim.max(1))), newlines)
}

/// The reader's state between lines.
struct Reader<'s, 'b> {
    source: &'s str,
    header: Option<&'s [String]>,
    /// The dimension and the line that set it.
    dim: Option<(usize, usize)>,
    data: Rows<'b>,
}

impl Reader<'_, '_> {
    /// The name of column `k` (0-based) in messages: the header's, else `k + 1`.
    fn column(&self, k: usize) -> String {
        self.header
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

    /// Reads the coordinates of one data line.
    fn row(&mut self, line: &str, line_no: usize) -> IoResult<()> {
        let mut fields = Fields::of(line);
        let start = self.data.len;
        let mut k = 0usize;
        while let Some(f) = fields.next() {
            let too_many = self.dim.is_some_and(|(d, _)| k >= d);
            let parsed = f.parse::<f64>();
            match parsed {
                Ok(v) if v.is_finite() && !too_many => {
                    if !self.data.push(v) {
                        // the room holds every row of the first row's length (`row_bound`):
                        // only a shorter row, such as one field of a few bytes, runs out of it
                        self.data.truncate(start);
                        let n = k + 1 + fields.count();
                        if self.dim.is_some_and(|(d, _)| d != n) {
                            return Err(self.wrong_count(line_no, n));
                        }
                        return Err(IoError::TooLarge {
                            what: format!(
                                "{}:{line_no}: more coordinates than the text was measured to hold",
                                self.source
                            ),
                        });
                    }
                }
                _ => {
                    self.data.truncate(start);
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

    /// Reads the data lines of `text`, whose first line is line `first_line`: rows in the
    /// common layout by [`plain_row`], any other line by [`Reader::row`].
    fn lines(&mut self, text: &str, first_line: usize) -> IoResult<()> {
        let bytes = text.as_bytes();
        let dim = self.dim.map_or(0, |(d, _)| d);
        let mut at = 0usize;
        let mut line_no = first_line;
        while at < bytes.len() {
            if dim > 0 {
                if let Some(next) = plain_row(bytes, at, dim, &mut self.data) {
                    at = next;
                    line_no += 1;
                    continue;
                }
            }
            let end = memchr::memchr(b'\n', &bytes[at..]).map_or(bytes.len(), |i| at + i);
            // `at` follows a `\n` (or is 0) and `end` is one: both are character boundaries
            let line = trim(&text[at..end]);
            if !(line.is_empty() || line.starts_with('#')) {
                self.row(line, line_no)?;
            }
            at = end + 1;
            line_no += 1;
        }
        Ok(())
    }
}

/// The bytes `a..b` of the whole text `bytes` as UTF-8 text (`a` at the start of a line).
fn utf8<'t>(bytes: &'t [u8], a: usize, b: usize, source: &str) -> IoResult<&'t str> {
    std::str::from_utf8(&bytes[a..b])
        .map_err(|e| crate::atomic::not_utf8(source, bytes, a + e.valid_up_to()))
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

/// `rest` cut at line boundaries into about `parts` pieces of equal length.
fn cut(rest: &[u8], parts: usize) -> Vec<usize> {
    let mut cuts = vec![0usize];
    for k in 1..parts {
        let at = (rest.len() * k / parts).max(*cuts.last().unwrap_or(&0));
        let cut = memchr::memchr(b'\n', &rest[at..]).map_or(rest.len(), |i| at + i + 1);
        cuts.push(cut);
    }
    cuts.push(rest.len());
    cuts.dedup();
    cuts
}

/// A part of the text after the first point: its bytes (checked as UTF-8 by the thread that
/// reads them), where they start in the text, its first line's number and its room.
struct Part<'t, 'b> {
    text: &'t [u8],
    offset: usize,
    first_line: usize,
    room: &'b mut [f64],
}

/// Reads CSV or whitespace-separated points from bytes that should be UTF-8 text (without a
/// byte-order mark): each part is checked as it is read, so a file is never checked whole
/// before the parallel parse starts; text that is not UTF-8 is the error of
/// [`crate::read_input`], at the same byte.
/// The error of a first point `line` that has both `;` and `,`: the mark of decimal commas
/// (`1,5;2,0` is the point (1.5, 2.0) in much of Europe), which would otherwise be read as
/// more coordinates than the file has.
pub(crate) fn decimal_commas(source: &str, line_no: usize, line: &str) -> IoError {
    IoError::syntax(
        Location::new(source).at_line(line_no),
        format!(
            "`{line}` has both `;` and `,`: decimal commas? lekalo reads `.` as the decimal point \
             and `,`, `;` or blanks between coordinates; write `1.5;2.0` or `1.5,2.0`"
        ),
    )
}

/// Whether `line`, the first that is neither blank nor a comment, is a header by `rule`.
fn is_header(line: &str, rule: Header) -> bool {
    match rule {
        Header::Yes => true,
        Header::No => false,
        Header::Auto => Fields::of(line).all(|f| f.parse::<f64>().is_err()),
    }
}

/// The line (counted from 1) of a CSV or whitespace points file that holds point `index`
/// (counted from 0), by the rules of [`read_delimited`]: blank and `#` lines are no points, and
/// the first other line is a header by `header_rule`. `None` past the last point, or at a line
/// that is not UTF-8. Used to name the lines of the points a library error names by index.
pub(crate) fn line_of_point(text: &[u8], header_rule: Header, index: usize) -> Option<usize> {
    let mut rows = line_ranges(text)
        .enumerate()
        .map(|(n, (a, b))| (n + 1, std::str::from_utf8(&text[a..b]).map(trim)))
        .filter(|(_, line)| !matches!(line, Ok(l) if l.is_empty() || l.starts_with('#')));
    let (first_no, first) = rows.next()?;
    let header = is_header(first.ok()?, header_rule);
    std::iter::once((first_no, first))
        .chain(rows)
        .skip(usize::from(header))
        .nth(index)
        .and_then(|(n, line)| line.ok().map(|_| n))
}

pub(crate) fn read_delimited(text: &[u8], source: &str, header_rule: Header) -> IoResult<Points> {
    read_delimited_from(text, source, header_rule, PARALLEL_MIN)
}

/// [`read_delimited`] with the threshold of the parallel reading given (tests read small texts
/// in parallel parts too).
///
/// The header and the first point are read first, which sets the dimension; the rest of the
/// text is then cut at line boundaries (in parts for every core when it is at least
/// `parallel_min` bytes long), one buffer is allocated with room for the most rows each part
/// can hold ([`row_bound`]), and each part is read into its own stretch of it. Parts that held
/// blank or comment lines leave gaps, closed afterwards by moving the following parts down.
pub(crate) fn read_delimited_from(
    bytes: &[u8],
    source: &str,
    header_rule: Header,
    parallel_min: usize,
) -> IoResult<Points> {
    let mut header: Option<Vec<String>> = None;
    let mut first: Option<(&str, usize, usize)> = None; // line, its number, where the rest starts
    for (n, (a, b)) in line_ranges(bytes).enumerate() {
        let line = trim(utf8(bytes, a, b, source)?);
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if header.is_none() && is_header(line, header_rule) {
            header = Some(Fields::of(line).map(str::to_string).collect());
            continue;
        }
        first = Some((line, n + 1, (b + 1).min(bytes.len())));
        break;
    }
    let Some((line, line_no, rest_at)) = first else {
        return Err(IoError::syntax(
            Location::new(source),
            "no points found; write one point per line, e.g. `1.0, 2.0`",
        ));
    };
    if line.contains(';') && line.contains(',') {
        return Err(decimal_commas(source, line_no, line));
    }
    let fields = Fields::of(line).count();
    let rest = &bytes[rest_at..];
    let threads = rayon::current_num_threads();
    let parts = if rest.len() < parallel_min || threads < 2 {
        1
    } else {
        threads * 2
    };
    let cuts = cut(rest, parts);
    // each part's room in rows and its first line's number (the lines counted in parallel)
    let bounds: Vec<(usize, usize)> = cuts
        .par_windows(2)
        .map(|w| row_bound(&rest[w[0]..w[1]], fields))
        .collect();
    let mut rooms = Vec::with_capacity(bounds.len());
    let mut next_line = line_no + 1;
    for (rows, newlines) in bounds {
        rooms.push((rows, next_line));
        next_line += newlines;
    }
    let total = rooms
        .iter()
        .try_fold(1usize, |t, (rows, _)| t.checked_add(*rows))
        .and_then(|rows| rows.checked_mul(fields))
        .ok_or_else(|| IoError::TooLarge {
            what: format!(
                "{source}: cannot reserve memory for the points of {} bytes of text",
                bytes.len()
            ),
        })?;
    // zeroed memory straight from the system (no probe allocated and freed before it, which
    // would make the allocator serve this one from its heap and clear it first): its pages are
    // touched first by the part that fills them, on that part's core. It is at most half a
    // number a byte of the text already held (`row_bound`), and for a plain CSV file the points
    // themselves.
    let mut data = vec![0.0; total];
    let (first_room, mut room) = data.split_at_mut(fields);
    let header = header.as_deref();
    let mut reader = Reader {
        source,
        header,
        dim: None,
        data: Rows {
            buf: first_room,
            len: 0,
        },
    };
    reader.row(line, line_no)?;
    let dim = reader.dim;
    let mut work = Vec::with_capacity(rooms.len());
    for (w, (rows, first_line)) in cuts.windows(2).zip(&rooms) {
        let (mine, after) = std::mem::take(&mut room).split_at_mut(rows * fields);
        room = after;
        work.push(Part {
            text: &rest[w[0]..w[1]],
            offset: rest_at + w[0],
            first_line: *first_line,
            room: mine,
        });
    }
    let read = |p: Part<'_, '_>| -> IoResult<usize> {
        let mut r = Reader {
            source,
            header,
            dim,
            data: Rows {
                buf: p.room,
                len: 0,
            },
        };
        r.lines(
            utf8(bytes, p.offset, p.offset + p.text.len(), source)?,
            p.first_line,
        )?;
        Ok(r.data.len)
    };
    let filled: Vec<IoResult<usize>> = if work.len() > 1 {
        work.into_par_iter().map(read).collect()
    } else {
        work.into_iter().map(read).collect()
    };
    // the first error in the file; then the parts' rows moved down over the gaps
    let mut len = fields;
    let mut start = fields;
    for (f, (rows, _)) in filled.into_iter().zip(&rooms) {
        let f = f?;
        if start != len {
            data.copy_within(start..start + f, len);
        }
        len += f;
        start += rows * fields;
    }
    data.truncate(len);
    Points::from_flat(fields, data).map_err(|e| IoError::Invalid {
        at: Location::new(source),
        error: e,
    })
}

/// Reads the row starting at `at` if it is `dim` finite numbers separated by single commas and
/// ended by `\n`, `\r\n` or the end of `bytes`: appends them to `data` and returns where the
/// next line starts. Returns `None`, with `data` as it was, for any other line; the general
/// reader then reads it with the same result (or its error). A row taken here is one the general
/// reader would read to the same numbers: it has no blanks to trim, no `;`, no `#` in front, and
/// each field is exactly the text `parse_partial` took as one number.
fn plain_row(bytes: &[u8], at: usize, dim: usize, data: &mut Rows<'_>) -> Option<usize> {
    let start = data.len;
    let mut pos = at;
    for k in 0..dim {
        let number = bytes
            .get(pos..)
            .and_then(|rest| fast_float2::parse_partial::<f64, _>(rest).ok());
        let (v, used) = match number {
            Some((v, used)) if used > 0 && v.is_finite() => (v, used),
            _ => {
                data.truncate(start);
                return None;
            }
        };
        if !data.push(v) {
            data.truncate(start);
            return None;
        }
        pos += used;
        if k + 1 < dim {
            if bytes.get(pos) != Some(&b',') {
                data.truncate(start);
                return None;
            }
            pos += 1;
        }
    }
    match (bytes.get(pos), bytes.get(pos + 1)) {
        (None, _) => Some(pos),
        (Some(b'\n'), _) => Some(pos + 1),
        (Some(b'\r'), Some(b'\n')) => Some(pos + 2),
        _ => {
            data.truncate(start);
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// What the general reader makes of one field: `from_str`'s value if finite.
    fn general(field: &str) -> Option<u64> {
        field
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .map(f64::to_bits)
    }

    /// What [`plain_row`] makes of one field: the value if `parse_partial` took all of it.
    fn plain(field: &str) -> Option<u64> {
        let mut buf = [0.0];
        let mut data = Rows {
            buf: &mut buf,
            len: 0,
        };
        plain_row(field.as_bytes(), 0, 1, &mut data)?;
        assert_eq!(data.len, 1, "one field, one number: {field:?}");
        Some(buf[0].to_bits())
    }

    /// `plain_row` of `line` into room for `room` numbers after a 7: where the next line
    /// starts and the numbers it holds then.
    fn plain_line(line: &[u8], at: usize, dim: usize, room: usize) -> (Option<usize>, Vec<f64>) {
        let mut buf = vec![7.0; room + 1];
        let mut data = Rows {
            buf: &mut buf,
            len: 1,
        };
        let next = plain_row(line, at, dim, &mut data);
        let len = data.len;
        buf.truncate(len);
        (next, buf)
    }

    proptest! {
        /// Every text the fast path takes as a number, the standard parser reads to the same
        /// bits: random doubles in both spellings, and strings of number characters.
        #[test]
        fn fast_path_reads_what_from_str_reads(bits in any::<u64>()) {
            let x = f64::from_bits(bits);
            for text in [x.to_string(), format!("{x:e}"), format!("{x:E}"), format!("{x:.3}")] {
                if let Some(v) = plain(&text) {
                    prop_assert_eq!(Some(v), general(&text), "{}", text);
                }
            }
            // the shortest spellings read back exactly, so the fast path takes them all
            for text in [x.to_string(), format!("{x:e}"), format!("{x:E}")] {
                let want = x.is_finite().then_some(x.to_bits());
                prop_assert_eq!(plain(&text), want, "{}", text);
            }
        }

        #[test]
        fn fast_path_takes_nothing_from_str_refuses(
            text in "[-+]?[0-9.eE+_ ]{0,6}[0-9]{0,20}[.]?[0-9eE+-]{0,6}|[-+]?(inf|nan|infinity|NaN)"
        ) {
            if let Some(v) = plain(&text) {
                prop_assert_eq!(Some(v), general(&text), "{:?}", text);
            }
        }

        /// A byte that is not UTF-8 is reported at its place in the text, as the whole-text
        /// check of `read_input` reports it, wherever it falls: in the header, the first point
        /// (both checked line by line) or any of the parts read in parallel (each checked by its
        /// thread), including in place of a line's end.
        #[test]
        fn a_byte_that_is_not_utf8_is_reported_at_its_place(
            rows in 2usize..300,
            header in any::<bool>(),
            place in any::<proptest::sample::Index>(),
            bad in 0x80u8..=0xff,
        ) {
            let mut text = if header { "x, y\n".to_string() } else { String::new() };
            for i in 0..rows {
                text.push_str(&format!("{}.5,{}\n", i, 2 * i));
            }
            let mut bytes = text.into_bytes();
            let at = place.index(bytes.len());
            bytes[at] = bad;
            let want = std::str::from_utf8(&bytes).unwrap_err().valid_up_to();
            // every byte before it is ASCII: the line and column are counted in bytes
            let line = 1 + bytes[..want].iter().filter(|&&b| b == b'\n').count();
            let column = want - bytes[..want].iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1) + 1;
            for parallel_min in [0, usize::MAX] {
                let e = read_delimited_from(&bytes, "p.csv", Header::Auto, parallel_min).unwrap_err();
                let message = format!("p.csv: not UTF-8 text at line {line}, column {column} (byte {want})");
                prop_assert!(e.to_string().contains(&message), "{} (want {})", e, message);
            }
        }

        /// A row of the common layout is taken whole, with the general reader's numbers; a row
        /// with anything else is left whole to the general reader.
        #[test]
        fn plain_rows_or_nothing(
            fields in proptest::collection::vec(any::<f64>(), 1..5),
            end in prop_oneof![Just(""), Just("\n"), Just("\r\n"), Just(" \n"), Just(",\n"), Just(";")],
        ) {
            let line = fields.iter().map(f64::to_string).collect::<Vec<_>>().join(",") + end;
            let (got, data) = plain_line(line.as_bytes(), 0, fields.len(), fields.len());
            let all_finite = fields.iter().all(|v| v.is_finite());
            if all_finite && matches!(end, "" | "\n" | "\r\n") {
                prop_assert_eq!(got, Some(line.len()));
                prop_assert_eq!(&data[1..], &fields[..]);
            } else {
                prop_assert_eq!(got, None);
                prop_assert_eq!(data, vec![7.0]);
            }
        }
    }

    #[test]
    fn unusual_rows_go_to_the_general_reader() {
        for line in [
            "1,2\r",
            " 1,2\n",
            "1, 2\n",
            "1;2\n",
            "1,2,3\n",
            "1\n",
            "#1,2\n",
            "1,,2\n",
            "1e,2\n",
            "1,2e\n",
            "0x1,2\n",
            "1,inf\n",
            "1,1e400\n",
            "1,2 \n",
            "1,2\t\n",
            "\n",
        ] {
            assert_eq!(
                plain_line(line.as_bytes(), 0, 2, 2),
                (None, vec![7.0]),
                "{line:?}"
            );
        }
        let text = b"x\n1.5,-2e-3\r\n4,5";
        assert_eq!(plain_line(text, 2, 2, 2), (Some(13), vec![7.0, 1.5, -2e-3]));
        assert_eq!(plain_line(text, 13, 2, 2), (Some(16), vec![7.0, 4.0, 5.0]));
        // no room for the row: left whole to the general reader
        assert_eq!(plain_line(text, 13, 2, 1), (None, vec![7.0]));
    }

    #[test]
    fn room_for_every_row() {
        assert_eq!(row_bound(b"1,2,3\n4,5,6", 3), (2, 1));
        assert_eq!(row_bound(b"1,2,3\n\n\n\n", 3), (1, 4));
        assert_eq!(row_bound(b"", 2), (0, 0));
        assert_eq!(row_bound(b"1\n2\n3\n", 1), (3, 3));
        // blank and comment lines in every part leave gaps that are closed in order
        let text = "x,y\n0,0\n\n1,1\n# c\n2,2\n\n\n3,3\n4,4\n";
        let p = read_delimited_from(text.as_bytes(), "p.csv", Header::Auto, 0).unwrap();
        assert_eq!(
            p.as_slice(),
            &[0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0]
        );
        let e = read_delimited_from(b"0,0\n\n1,1\n2,2,2\n", "p.csv", Header::Auto, 0)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.csv:4: 3 fields, but line 1 has 2"), "{e}");
    }
}
