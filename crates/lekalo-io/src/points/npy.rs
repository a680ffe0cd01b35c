//! NumPy `.npy` files: an `(n, d)` or `(n,)` float64 array as points in, sample tables out.
//!
//! The format (numpy's `NEP 1`, "A simple file format for NumPy arrays") is a 6-byte magic
//! `\x93NUMPY`, a version `major.minor` (1.0, 2.0 or 3.0), the header length (`u16` little-endian
//! for 1.0, `u32` for 2.0 and 3.0), a header that is a Python dict literal
//! `{'descr': '<f8', 'fortran_order': False, 'shape': (n, d), }` padded with spaces to a
//! multiple of 64 bytes and ending in `\n`, then the raw array data.
//!
//! Written by hand rather than with a crate: the whole format is these few lines, and reading it
//! here lets every malformed file (bad magic, truncated header, a dtype that is not float64, a
//! 3-D shape, data shorter than the shape, NaN) give an error that names the file and the header
//! field, as every other reader of this crate does; only float64 arrays are read or written, so
//! a general dtype layer would add a dependency and nothing the points need.
//!
//! Reading accepts `'<f8'` and `'>f8'` (either endianness), C and Fortran order, shapes `(n, d)`
//! and `(n,)` (one coordinate per point). Writing produces version 1.0, `'<f8'`, C order: what
//! `np.save` writes, read back by `np.load` bit for bit.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use lekalo::Points;

use crate::error::{IoError, IoResult, Location};
use crate::samples::SampleTable;

/// The magic bytes at the start of every `.npy` file.
const MAGIC: &[u8; 6] = b"\x93NUMPY";

/// Bytes per float64 element.
const F8: usize = 8;

/// The parsed header of a float64 (or, for `.npz` integer scalars, int64) `.npy` file.
#[derive(Debug, Clone, PartialEq, Eq)]
struct NpyHeader {
    big_endian: bool,
    /// `'<i8'` / `'>i8'` rather than float64 (accepted only where the caller allows it).
    integer: bool,
    fortran: bool,
    shape: Vec<usize>,
    /// Offset of the array data from the start of the file.
    data_start: usize,
}

fn err(source: &str, field: &str, message: impl Into<String>) -> IoError {
    IoError::syntax(Location::new(source).at_field(field), message)
}

/// Reads an `(n, d)` or `(n,)` float64 `.npy` array from `bytes` as `n` points of dimension `d`
/// (1 for `(n,)`); `source` names the input in messages.
///
/// ```
/// let bytes = lekalo_io::npy_bytes(2, 2, &[0.0, 0.0, 3.0, 4.0]).unwrap();
/// let p = lekalo_io::read_npy_points(&bytes, "pts.npy").unwrap();
/// assert_eq!(p.point(1), &[3.0, 4.0]);
/// let e = lekalo_io::read_npy_points(b"PK\x03\x04", "pts.npy").unwrap_err();
/// assert!(e.to_string().starts_with("pts.npy: field `magic`"), "{e}");
/// ```
///
/// # Errors
/// [`IoError::Syntax`] naming the file and the field (`magic`, `version`, `header`, `descr`,
/// `fortran_order`, `shape`, `data`, or the element `[i, j]`) for a file that is not `.npy`, a
/// truncated or malformed header, a dtype other than float64, a shape that is not 1-D or 2-D or
/// is empty, data shorter or longer than the shape says, or a value that is not finite;
/// [`IoError::Invalid`] if the library rejects the points.
pub fn read_npy_points(bytes: &[u8], source: &str) -> IoResult<Points> {
    let (shape, flat) = read_array(bytes, source, false)?;
    points_of(&shape, flat, source)
}

/// Reads a float64 `.npy` array of any shape: the shape and the elements in C (row-major)
/// order (a Fortran-ordered file is reordered), every one finite; e.g. a grid of values
/// `(m_1, …, m_N[, d])`.
///
/// # Errors
/// As [`read_npy_points`], except that any shape is accepted.
pub fn read_npy_array(bytes: &[u8], source: &str) -> IoResult<(Vec<usize>, Vec<f64>)> {
    read_array(bytes, source, false)
}

/// The points of an array of `shape` whose elements (C order) are `flat`.
fn points_of(shape: &[usize], flat: Vec<f64>, source: &str) -> IoResult<Points> {
    let d = match shape[..] {
        [_, d] => d,
        [_] => 1,
        _ => {
            return Err(err(
                source,
                "shape",
                format!(
                    "shape {} is not (n, d) or (n,); points are a 2-D array, one row per point",
                    Value::Tuple(shape.to_vec()).describe()
                ),
            ))
        }
    };
    if flat.is_empty() {
        return Err(err(
            source,
            "shape",
            format!(
                "shape {} holds no points; at least one point with one coordinate is needed",
                Value::Tuple(shape.to_vec()).describe()
            ),
        ));
    }
    Points::from_flat(d, flat).map_err(|e| IoError::Invalid {
        at: Location::new(source),
        error: e,
    })
}

/// Reads a float64 `.npy` array of any shape (int64 too if `integer` is allowed): its shape and
/// its elements in C (row-major) order, every one finite.
pub(crate) fn read_array(
    bytes: &[u8],
    source: &str,
    integer: bool,
) -> IoResult<(Vec<usize>, Vec<f64>)> {
    let h = parse_header(bytes, source, integer)?;
    let data = &bytes[h.data_start..];
    let mut flat = room_for(&h, data.len(), source)?;
    decode(&h, data, &mut flat);
    finish(h, flat, source)
}

/// The shape an `.npy` file's header declares (float64, or int64 too if `integer` is allowed),
/// read from the header alone: a caller checks it against other arrays before [`read_array`]
/// decodes the data.
pub(crate) fn read_array_shape(bytes: &[u8], source: &str, integer: bool) -> IoResult<Vec<usize>> {
    Ok(parse_header(bytes, source, integer)?.shape)
}

/// An empty vector with room for the elements of the array of header `h`, after checking that
/// the file's `data_len` bytes after the header are exactly those elements.
fn room_for(h: &NpyHeader, data_len: usize, source: &str) -> IoResult<Vec<f64>> {
    let count = h
        .shape
        .iter()
        .try_fold(1usize, |acc, &k| acc.checked_mul(k))
        .filter(|c| c.checked_mul(F8).is_some());
    let Some(count) = count else {
        return Err(err(
            source,
            "shape",
            format!(
                "shape {} is too large to address",
                Value::Tuple(h.shape.clone()).describe()
            ),
        ));
    };
    if data_len != count * F8 {
        return Err(err(
            source,
            "data",
            format!(
                "the header's shape {} needs {} bytes of {} data, the file has {}; the file is truncated or its header is wrong",
                Value::Tuple(h.shape.clone()).describe(),
                count * F8,
                if h.integer { "int64" } else { "float64" },
                data_len
            ),
        ));
    }
    let mut flat = Vec::new();
    flat.try_reserve_exact(count)
        .map_err(|_| IoError::TooLarge {
            what: format!("{source}: cannot reserve memory for {count} numbers"),
        })?;
    Ok(flat)
}

/// Appends the elements in `data` (whole elements, in file order) to `flat`: one pass of 8-byte
/// loads (`chunks_exact` compiles to plain loads, and to a copy on a little-endian machine).
fn decode(h: &NpyHeader, data: &[u8], flat: &mut Vec<f64>) {
    let decode = |b: &[u8]| -> f64 {
        let b: [u8; F8] = b.try_into().unwrap_or([0; F8]);
        match (h.integer, h.big_endian) {
            (false, false) => f64::from_le_bytes(b),
            (false, true) => f64::from_be_bytes(b),
            // int64 is read for small integers such as a degree; the caller checks the range
            #[allow(clippy::cast_precision_loss)]
            (true, false) => i64::from_le_bytes(b) as f64,
            #[allow(clippy::cast_precision_loss)]
            (true, true) => i64::from_be_bytes(b) as f64,
        }
    };
    flat.extend(data.chunks_exact(F8).map(decode));
}

/// The shape and the C-order elements of the array of header `h` whose elements in file order
/// are `flat`; an error naming the first element that is not finite.
fn finish(h: NpyHeader, mut flat: Vec<f64>, source: &str) -> IoResult<(Vec<usize>, Vec<f64>)> {
    if h.fortran && h.shape.len() > 1 {
        flat = fortran_to_c(&flat, &h.shape);
    }
    // the index of the first value that is not finite, only when there is one
    if let Some(e) = flat.iter().position(|v| !v.is_finite()) {
        let mut at = Vec::with_capacity(h.shape.len());
        let mut rest = e;
        for &n in h.shape.iter().rev() {
            at.push((rest % n).to_string());
            rest /= n;
        }
        at.reverse();
        return Err(err(
            source,
            &format!("[{}]", at.join(", ")),
            format!(
                "{} is not finite; every value must be a finite number",
                flat[e]
            ),
        ));
    }
    Ok((h.shape, flat))
}

/// The C-order (last index fastest) copy of `f`, the elements of an array of `shape` in Fortran
/// order (first index fastest): C element `(i_0, …, i_{r-1})` is Fortran element
/// `i_0 + n_0 (i_1 + n_1 (…))`.
fn fortran_to_c(f: &[f64], shape: &[usize]) -> Vec<f64> {
    let rank = shape.len();
    let mut index = vec![0usize; rank];
    let mut out = Vec::with_capacity(f.len());
    for _ in 0..f.len() {
        let k = index
            .iter()
            .zip(shape)
            .rev()
            .fold(0, |acc, (&i, &n)| acc * n + i);
        out.push(f[k]);
        // next C-order index
        for r in (0..rank).rev() {
            index[r] += 1;
            if index[r] < shape[r] {
                break;
            }
            index[r] = 0;
        }
    }
    out
}

/// Bytes of a `.npy` file read at a time: the header (all but the longest) and then the data
/// in pieces of this size, decoded as they come, so the file is never held whole in memory.
const READ_CHUNK: usize = 1 << 16;

/// Reads a `.npy` points file from `path` (see [`read_npy_points`]); returns the points and the
/// name used in messages. The data are decoded as they are read, a cache-sized piece at a time.
///
/// # Errors
/// [`IoError::Read`] if the file cannot be read; otherwise as [`read_npy_points`].
pub fn read_npy_file(path: &Path) -> IoResult<(Points, String)> {
    let name = path.display().to_string();
    let read_err = |error| IoError::Read {
        path: PathBuf::from(path),
        error,
    };
    let mut f = std::fs::File::open(path).map_err(read_err)?;
    crate::atomic::note_read(path);
    let len = f.metadata().map_err(read_err)?.len();
    let len = usize::try_from(len).unwrap_or(usize::MAX);
    let mut head = Vec::with_capacity(READ_CHUNK.min(len));
    (&mut f)
        .take(READ_CHUNK as u64)
        .read_to_end(&mut head)
        .map_err(read_err)?;
    let h = match parse_header(&head, &name, false) {
        Ok(h) => h,
        // a header longer than the first piece: the file read whole
        Err(_) if head.len() < len => {
            head.clear();
            std::io::Seek::rewind(&mut f).map_err(read_err)?;
            f.read_to_end(&mut head).map_err(read_err)?;
            return Ok((read_npy_points(&head, &name)?, name));
        }
        Err(e) => return Err(e),
    };
    let data_len = len.saturating_sub(h.data_start);
    let mut flat = room_for(&h, data_len, &name)?;
    // the data in the first piece, then the rest piece by piece (whole elements each)
    let first = &head[h.data_start.min(head.len())..];
    let whole = first.len() - first.len() % F8;
    decode(&h, &first[..whole], &mut flat);
    let mut piece = first[whole..].to_vec();
    let mut left = data_len - whole;
    while left > 0 {
        let want = left.min(READ_CHUNK);
        let have = piece.len();
        piece.resize(want, 0);
        f.read_exact(&mut piece[have..]).map_err(read_err)?;
        decode(&h, &piece, &mut flat);
        left -= want;
        piece.clear();
    }
    let (shape, flat) = finish(h, flat, &name)?;
    Ok((points_of(&shape, flat, &name)?, name))
}

fn parse_header(bytes: &[u8], source: &str, integer: bool) -> IoResult<NpyHeader> {
    if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
        return Err(err(
            source,
            "magic",
            "not a NumPy .npy file: it does not start with \\x93NUMPY; save the array with numpy.save",
        ));
    }
    let Some(&[major, minor]) = bytes.get(6..8) else {
        return Err(err(
            source,
            "version",
            "the file ends inside the header (no version)",
        ));
    };
    let (len_bytes, utf8) = match (major, minor) {
        (1, 0) => (2, false),
        (2 | 3, 0) => (4, major == 3),
        _ => {
            return Err(err(
                source,
                "version",
                format!(
                "format version {major}.{minor} is not supported; versions 1.0, 2.0 and 3.0 are"
            ),
            ))
        }
    };
    let start = 8 + len_bytes;
    let Some(len_field) = bytes.get(8..start) else {
        return Err(err(
            source,
            "header",
            "the file ends inside the header (no header length)",
        ));
    };
    let len = len_field
        .iter()
        .rev()
        .fold(0usize, |acc, &b| (acc << 8) | usize::from(b));
    let Some(raw) = start.checked_add(len).and_then(|end| bytes.get(start..end)) else {
        return Err(err(
            source,
            "header",
            format!(
                "the header is {len} bytes long but the file ends after {} bytes; the file is truncated",
                bytes.len().saturating_sub(start)
            ),
        ));
    };
    let text = if utf8 {
        std::str::from_utf8(raw).ok()
    } else {
        raw.is_ascii()
            .then(|| std::str::from_utf8(raw).ok())
            .flatten()
    };
    let Some(text) = text else {
        return Err(err(source, "header", "the header is not text"));
    };
    let entries = parse_dict(text).map_err(|m| err(source, "header", m))?;
    let get = |key: &str| {
        entries
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v)
            .ok_or_else(|| err(source, key, format!("the header has no '{key}' entry")))
    };
    let (big_endian, is_int) = match get("descr")? {
        Value::Str(s) if s == "<f8" => (false, false),
        Value::Str(s) if s == ">f8" => (true, false),
        Value::Str(s) if integer && s == "<i8" => (false, true),
        Value::Str(s) if integer && s == ">i8" => (true, true),
        other => {
            return Err(err(
                source,
                "descr",
                format!(
                "dtype {} is not float64; save the array as float64 (arr.astype(numpy.float64))",
                other.describe()
            ),
            ))
        }
    };
    let fortran = match get("fortran_order")? {
        Value::Bool(b) => *b,
        other => {
            return Err(err(
                source,
                "fortran_order",
                format!("{} is not True or False", other.describe()),
            ))
        }
    };
    let shape = match get("shape")? {
        Value::Tuple(s) => s.clone(),
        other => {
            return Err(err(
                source,
                "shape",
                format!("shape {} is not a tuple of sizes", other.describe()),
            ))
        }
    };
    Ok(NpyHeader {
        big_endian,
        integer: is_int,
        fortran,
        shape,
        data_start: start + len,
    })
}

/// A value of the header dict.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Value {
    Str(String),
    Bool(bool),
    Tuple(Vec<usize>),
    /// Anything else (a list-of-fields dtype, a number, None), kept as written.
    Other(String),
}

impl Value {
    fn describe(&self) -> String {
        match self {
            Value::Str(s) => format!("'{s}'"),
            Value::Bool(b) => if *b { "True" } else { "False" }.to_string(),
            Value::Tuple(v) => {
                let items: Vec<String> = v.iter().map(ToString::to_string).collect();
                if items.len() == 1 {
                    format!("({},)", items[0])
                } else {
                    format!("({})", items.join(", "))
                }
            }
            Value::Other(s) => s.clone(),
        }
    }
}

/// Parses the header's dict literal `{'key': value, …}` with string keys and values that are
/// strings, `True`/`False`, tuples of integers, or anything else kept as text.
fn parse_dict(text: &str) -> Result<Vec<(String, Value)>, String> {
    let s = text.trim();
    let inner = s
        .strip_prefix('{')
        .and_then(|r| r.strip_suffix('}'))
        .ok_or_else(|| format!("the header is not a dict literal {{…}}: {s:?}"))?;
    let mut out = Vec::new();
    let mut rest = inner.trim_start();
    while !rest.is_empty() {
        let (key, r) =
            parse_str(rest).ok_or_else(|| format!("expected a quoted key at {rest:?}"))?;
        let r = r
            .trim_start()
            .strip_prefix(':')
            .ok_or_else(|| format!("expected ':' after '{key}'"))?
            .trim_start();
        let (value, r) =
            parse_value(r).ok_or_else(|| format!("cannot read the value of '{key}'"))?;
        let r = r.trim_start();
        rest = match r.strip_prefix(',') {
            Some(r) => r.trim_start(),
            None if r.is_empty() => r,
            None => return Err(format!("expected ',' or '}}' after the value of '{key}'")),
        };
        if out.iter().any(|(k, _)| *k == key) {
            // Python keeps the last of repeated keys in a dict literal, and NumPy's own reader
            // then refuses or accepts by that one; no writer repeats a key, so refuse it
            return Err(format!(
                "the key '{key}' appears twice; a .npy header names each key once, save the array again with numpy.save"
            ));
        }
        out.push((key, value));
    }
    Ok(out)
}

/// A quoted string (`'…'` or `"…"`, no escapes: numpy's keys and dtypes need none) and the rest.
fn parse_str(s: &str) -> Option<(String, &str)> {
    let q = s.chars().next().filter(|c| *c == '\'' || *c == '"')?;
    let body = &s[1..];
    let end = body.find(q)?;
    Some((body[..end].to_string(), &body[end + 1..]))
}

fn parse_value(s: &str) -> Option<(Value, &str)> {
    if let Some((v, r)) = parse_str(s) {
        return Some((Value::Str(v), r));
    }
    if let Some(r) = s.strip_prefix("True") {
        return Some((Value::Bool(true), r));
    }
    if let Some(r) = s.strip_prefix("False") {
        return Some((Value::Bool(false), r));
    }
    if let Some(r) = s.strip_prefix('(') {
        let end = r.find(')')?;
        let items: Option<Vec<usize>> = r[..end]
            .split(',')
            .map(str::trim)
            .filter(|t| !t.is_empty())
            .map(|t| t.trim_end_matches('L').parse().ok())
            .collect();
        return Some((Value::Tuple(items?), &r[end + 1..]));
    }
    // Anything else (e.g. a structured dtype `[('x', '<f8')]`): up to the bracket-balanced
    // next comma, kept as text for the message.
    let mut depth = 0i32;
    for (i, c) in s.char_indices() {
        match c {
            '[' | '(' | '{' => depth += 1,
            ']' | ')' | '}' => depth -= 1,
            ',' if depth == 0 => return Some((Value::Other(s[..i].trim().to_string()), &s[i..])),
            _ => {}
        }
        if depth < 0 {
            return None;
        }
    }
    Some((Value::Other(s.trim().to_string()), ""))
}

/// A version 1.0, `'<f8'`, C-order `.npy` file of a `rows` × `cols` array whose elements are
/// `data` in row-major order (what `np.save` writes for a float64 array).
///
/// ```
/// let b = lekalo_io::npy_bytes(1, 2, &[1.5, -2.0]).unwrap();
/// assert_eq!(&b[..8], b"\x93NUMPY\x01\x00");
/// assert_eq!(b.len() % 64, 16 % 64, "header padded to 64 bytes, then 16 data bytes");
/// ```
///
/// # Errors
/// [`IoError::Unsupported`] if `data` does not hold `rows * cols` numbers.
pub fn npy_bytes(rows: usize, cols: usize, data: &[f64]) -> IoResult<Vec<u8>> {
    if rows.checked_mul(cols) != Some(data.len()) {
        return Err(IoError::Unsupported {
            what: format!(
                "a {rows} x {cols} array needs {} numbers, {} were given",
                rows.saturating_mul(cols),
                data.len()
            ),
        });
    }
    write_npy("<f8", &[rows, cols], &le_bytes(data))
}

/// The little-endian bytes of `v`, 8 a number, in one pre-sized buffer (a copy on a
/// little-endian machine).
pub(crate) fn le_bytes(v: &[f64]) -> Vec<u8> {
    let mut out = Vec::with_capacity(v.len() * F8);
    for x in v {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out
}

/// Numbers converted to bytes by [`write_le`] at a time (64 KiB, held in the cache).
const LE_CHUNK: usize = 8192;

/// Writes the little-endian bytes of `v` to `w` a cache-sized chunk at a time, so that a large
/// array is never copied whole.
pub(crate) fn write_le(w: &mut dyn Write, v: &[f64]) -> std::io::Result<()> {
    let mut bytes = Vec::with_capacity(LE_CHUNK.min(v.len()) * F8);
    for chunk in v.chunks(LE_CHUNK) {
        bytes.clear();
        for x in chunk {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
        w.write_all(&bytes)?;
    }
    Ok(())
}

/// The header of a version 1.0, C-order `.npy` file of dtype `descr` and `shape`: magic,
/// version, length and the dict padded so that the data start at a multiple of 64 bytes.
pub(crate) fn npy_header(descr: &str, shape: &[usize]) -> IoResult<Vec<u8>> {
    let shape = Value::Tuple(shape.to_vec()).describe();
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    // magic (6) + version (2) + length (2) + header + '\n' is a multiple of 64
    let unpadded = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    let Ok(len) = u16::try_from(header.len()) else {
        return Err(IoError::Unsupported {
            what: format!("a header for shape {shape} is too long"),
        });
    };
    let mut out = Vec::with_capacity(10 + header.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&[1, 0]);
    out.extend_from_slice(&len.to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    Ok(out)
}

/// A version 1.0, C-order `.npy` file of dtype `descr` and `shape` holding the little-endian
/// element bytes `raw`.
pub(crate) fn write_npy(descr: &str, shape: &[usize], raw: &[u8]) -> IoResult<Vec<u8>> {
    let mut out = npy_header(descr, shape)?;
    out.reserve_exact(raw.len());
    out.extend_from_slice(raw);
    Ok(out)
}

impl SampleTable {
    /// The table as a `.npy` file: an `(rows, columns)` float64 array in the column order of
    /// [`SampleTable::header`] (`t`, coordinates, derivatives, curvature), undefined values
    /// (the curvature where `C' = 0`) as NaN, NumPy's missing value.
    ///
    /// # Errors
    /// [`IoError::Unsupported`] if the rows are not all as long as the header.
    pub fn to_npy(&self) -> IoResult<Vec<u8>> {
        let cols = self.header.len();
        let mut data = Vec::with_capacity(self.rows.len() * cols);
        for row in &self.rows {
            if row.len() != cols {
                return Err(IoError::Unsupported {
                    what: format!("a row of {} values under {cols} columns", row.len()),
                });
            }
            data.extend(row.iter().map(|v| v.unwrap_or(f64::NAN)));
        }
        npy_bytes(self.rows.len(), cols, &data)
    }
}

#[cfg(test)]
#[path = "npy_tests.rs"]
mod tests;
