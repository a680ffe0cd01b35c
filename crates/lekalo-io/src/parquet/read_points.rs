//! Point sets from Parquet, in the long or the lists layout.

use std::path::Path;

use arrow_array::cast::AsArray;
use arrow_array::{Array, ArrayRef, RecordBatch};
use arrow_schema::DataType;

use super::columns::{Keys, Numbers, RowGroups};
use super::{GroupKey, PointGroup, DEFAULT_KEY};
use crate::error::{IoError, IoResult, Location};

/// The layout of a point-set file, found from its schema.
struct Layout {
    key: usize,
    coords: Vec<(usize, String)>,
    lists: bool,
}

fn layout(schema: &arrow_schema::Schema, key: &str, source: &str) -> IoResult<Layout> {
    let at = Location::new(source);
    let names: Vec<&str> = schema.fields().iter().map(|f| f.name().as_str()).collect();
    let k = names.iter().position(|n| *n == key).ok_or_else(|| {
        IoError::syntax(
            at.clone(),
            format!(
                "no key column `{key}` (columns: {}); name the column that groups the points with --group-column",
                names.join(", ")
            ),
        )
    })?;
    if !matches!(
        schema.field(k).data_type(),
        DataType::Int64 | DataType::Int32 | DataType::Utf8 | DataType::LargeUtf8
    ) {
        return Err(IoError::syntax(
            at.at_field(key),
            format!(
                "the key column is {}; it must be an integer or a string",
                schema.field(k).data_type()
            ),
        ));
    }
    let numeric = |t: &DataType| {
        matches!(
            t,
            DataType::Float64 | DataType::Float32 | DataType::Int64 | DataType::Int32
        )
    };
    let mut coords = Vec::new();
    let mut lists = None;
    for (i, f) in schema.fields().iter().enumerate() {
        if i == k {
            continue;
        }
        let is_list = match f.data_type() {
            t if numeric(t) => false,
            DataType::List(inner) | DataType::LargeList(inner) if numeric(inner.data_type()) => {
                true
            }
            other => {
                return Err(IoError::syntax(
                    at.clone().at_field(f.name()),
                    format!("the column is {other}, not numbers; every column other than the key `{key}` is a coordinate (double, float or integer, or a list of them)"),
                ))
            }
        };
        if lists.is_some_and(|l| l != is_list) {
            return Err(IoError::syntax(
                at.clone().at_field(f.name()),
                "the coordinate columns mix numbers and lists; use one row per point (numbers) or one row per group (lists)",
            ));
        }
        lists = Some(is_list);
        coords.push((i, f.name().clone()));
    }
    if coords.is_empty() {
        return Err(IoError::syntax(
            at,
            format!("no coordinate columns besides the key `{key}`"),
        ));
    }
    Ok(Layout {
        key: k,
        coords,
        lists: lists.unwrap_or(false),
    })
}

/// A group being gathered in the long layout (it may go on in the next row group).
struct Open {
    key: GroupKey,
    data: Vec<f64>,
    error: Option<IoError>,
}

impl Open {
    fn finish(self, dim: usize) -> PointGroup {
        let points = match self.error {
            Some(e) => Err(e),
            None => lekalo::Points::from_flat(dim, self.data).map_err(|error| IoError::Invalid {
                at: Location::new(format!("group {}", self.key)),
                error,
            }),
        };
        (self.key, points)
    }
}

/// Reads the point sets of a Parquet file a batch of rows at a time (a few MiB, within a row
/// group), calling `each` with the groups completed by each batch (a group running on into
/// the next batch or row group is passed with the batch where it ends). `key` names the key column ([`DEFAULT_KEY`] if `None`).
///
/// # Errors
/// [`IoError::Read`] if the file cannot be opened; [`IoError::Syntax`] for a file that is not
/// Parquet, a missing key column, a column that is not numeric, or a null key; errors of
/// `each`. A group's own problems are in its [`PointGroup`].
pub fn read_point_groups(
    path: &Path,
    key: Option<&str>,
    mut each: impl FnMut(Vec<PointGroup>) -> IoResult<()>,
) -> IoResult<()> {
    let key = key.unwrap_or(DEFAULT_KEY);
    let rg = RowGroups::open(path)?;
    let source = rg.source.clone();
    let lay = layout(rg.schema(), key, &source)?;
    let dim = lay.coords.len();
    let mut seen = std::collections::HashSet::new();
    let mut open: Option<Open> = None;
    let mut row0 = 0usize; // rows before the current batch
    let last = rg.count().checked_sub(1);
    for g in 0..rg.count() {
        let mut batches = rg.read(g)?.peekable();
        while let Some(batch) = batches.next() {
            let batch = batch?;
            let mut done = Vec::new();
            let keys = Keys::of(batch.column(lay.key).as_ref()).ok_or_else(|| {
                IoError::syntax(
                    Location::new(&source).at_field(key),
                    "unreadable key column",
                )
            })?;
            let numbers: Vec<Option<Numbers<'_>>> = lay
                .coords
                .iter()
                .map(|(c, _)| Numbers::of(batch.column(*c).as_ref()))
                .collect();
            if let Some(r) = keys.first_null() {
                return Err(IoError::syntax(
                    Location::new(&source).at_field(key),
                    format!(
                        "row {}: the key is null; every row needs a key",
                        row0 + r + 1
                    ),
                ));
            }
            let mut r = 0;
            while r < batch.num_rows() {
                let k = keys.get(r).ok_or_else(|| {
                    IoError::syntax(Location::new(&source).at_field(key), "unreadable key")
                })?;
                if lay.lists {
                    let mut o = Open {
                        key: k,
                        data: Vec::new(),
                        error: None,
                    };
                    o.error = read_list_row(&batch, &lay, r, &mut o.data, &source, &o.key).err();
                    done.push(o.finish(dim));
                    r += 1;
                    continue;
                }
                // the rows r..end have the key k: one group, or the part of one in this batch
                let end = keys.run_end(r);
                if open.as_ref().is_none_or(|o| o.key != k) {
                    if let Some(o) = open.take() {
                        done.push(o.finish(dim));
                    }
                    let mut o = Open {
                        key: k.clone(),
                        data: Vec::new(),
                        error: None,
                    };
                    if !seen.insert(k) {
                        o.error = Some(IoError::syntax(
                            Location::new(format!("{source}: group {}", o.key)),
                            format!("appears again at row {}; the rows of a group must be consecutive (sort the file by `{key}`)", row0 + r + 1),
                        ));
                    }
                    open = Some(o);
                }
                if let Some(o) = open.as_mut().filter(|o| o.error.is_none()) {
                    let at = || Location::new(format!("{source}: group {}", o.key));
                    let rows = Rows {
                        numbers: &numbers,
                        names: &lay.coords,
                        range: r..end,
                        row0,
                    };
                    o.error = rows.append_to(&mut o.data, at).err();
                }
                r = end;
            }
            row0 += batch.num_rows();
            if Some(g) == last && batches.peek().is_none() {
                if let Some(o) = open.take() {
                    done.push(o.finish(dim));
                }
            }
            if !done.is_empty() {
                each(done)?;
            }
        }
    }
    // a last row group without rows
    if let Some(o) = open.take() {
        each(vec![o.finish(dim)])?;
    }
    Ok(())
}

/// Consecutive rows of one group in the long layout.
struct Rows<'a, 'b> {
    /// The coordinate columns (`None`: not numbers).
    numbers: &'a [Option<Numbers<'b>>],
    /// The coordinate columns' indices and names.
    names: &'a [(usize, String)],
    /// The rows in the batch.
    range: std::ops::Range<usize>,
    /// The rows of the file before the batch.
    row0: usize,
}

impl Rows<'_, '_> {
    /// Appends the rows' coordinates to `data` (point-major). Columns of doubles without
    /// nulls are interleaved from their slices and checked at once; otherwise, or if a number
    /// is not finite, value by value, so that the error names the first bad value's row and
    /// column (`at` the group's location).
    fn append_to(&self, data: &mut Vec<f64>, at: impl Fn() -> Location) -> IoResult<()> {
        let start = data.len();
        let range = self.range.clone();
        data.reserve(range.len() * self.numbers.len());
        let slices: Option<Vec<&[f64]>> = self
            .numbers
            .iter()
            .map(|n| {
                n.as_ref()
                    .and_then(Numbers::as_f64s)
                    .map(|v| &v[range.clone()])
            })
            .collect();
        if let Some(slices) = slices {
            match slices.as_slice() {
                [x, y, z] => {
                    for ((x, y), z) in x.iter().zip(*y).zip(*z) {
                        data.extend_from_slice(&[*x, *y, *z]);
                    }
                }
                _ => {
                    for i in 0..range.len() {
                        data.extend(slices.iter().map(|s| s[i]));
                    }
                }
            }
            if data[start..].iter().all(|v| v.is_finite()) {
                return Ok(());
            }
            data.truncate(start);
        }
        for r in range {
            for ((_, name), n) in self.names.iter().zip(self.numbers) {
                match n.as_ref().and_then(|n| n.get(r)) {
                    Some(v) if v.is_finite() => data.push(v),
                    v => {
                        return Err(IoError::syntax(
                            at().at_field(name.clone()),
                            format!(
                                "row {}: {}; every coordinate must be a finite number",
                                self.row0 + r + 1,
                                v.map_or("null".to_string(), |v| v.to_string())
                            ),
                        ))
                    }
                }
            }
        }
        Ok(())
    }
}

/// The points of row `r` in the lists layout, appended to `data`.
fn read_list_row(
    batch: &RecordBatch,
    lay: &Layout,
    r: usize,
    data: &mut Vec<f64>,
    source: &str,
    key: &GroupKey,
) -> IoResult<()> {
    let at = || Location::new(format!("{source}: group {key}"));
    let mut cols = Vec::with_capacity(lay.coords.len());
    let mut len = None;
    for (c, name) in &lay.coords {
        let col = batch.column(*c);
        let list: ArrayRef = if let Some(l) = col.as_list_opt::<i32>() {
            if l.is_null(r) {
                return Err(IoError::syntax(
                    at().at_field(name.clone()),
                    "the list is null",
                ));
            }
            l.value(r)
        } else if let Some(l) = col.as_list_opt::<i64>() {
            if l.is_null(r) {
                return Err(IoError::syntax(
                    at().at_field(name.clone()),
                    "the list is null",
                ));
            }
            l.value(r)
        } else {
            return Err(IoError::syntax(at().at_field(name.clone()), "not a list"));
        };
        match len {
            Some((n, ref first)) if n != list.len() => {
                return Err(IoError::syntax(
                    at().at_field(name.clone()),
                    format!(
                        "{} values, but `{first}` has {n}; every coordinate list of a group needs the same length",
                        list.len()
                    ),
                ))
            }
            None => len = Some((list.len(), name.clone())),
            Some(_) => {}
        }
        cols.push((list, name));
    }
    let n = len.map_or(0, |(n, _)| n);
    data.reserve(n * cols.len());
    let nums: Vec<(Numbers<'_>, &String)> = cols
        .iter()
        .map(|(l, name)| {
            Numbers::of(l.as_ref())
                .map(|x| (x, *name))
                .ok_or_else(|| IoError::syntax(at().at_field((*name).clone()), "not numbers"))
        })
        .collect::<IoResult<_>>()?;
    for i in 0..n {
        for (x, name) in &nums {
            match x.get(i) {
                Some(v) if v.is_finite() => data.push(v),
                v => {
                    return Err(IoError::syntax(
                        at().at_field((*name).clone()),
                        format!(
                            "value {i} is {}; every coordinate must be a finite number",
                            v.map_or("null".to_string(), |v| v.to_string())
                        ),
                    ))
                }
            }
        }
    }
    Ok(())
}
