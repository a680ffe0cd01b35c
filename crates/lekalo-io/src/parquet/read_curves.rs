//! Curves from Parquet, as written by the writer.

use std::path::Path;

use arrow_array::cast::AsArray;
use arrow_array::Array;

use super::columns::{Keys, Numbers, RowGroups};
use super::{GroupKey, DEFAULT_KEY};
use crate::error::{IoError, IoResult, Location};
use crate::object::Object;

/// Reads the curves of a Parquet file written by [`ParquetBatchWriter::write_curves`] one row
/// group at a time; `each` gets `(key, curve)` pairs, a row with an `error` or an invalid curve
/// as an error naming its key.
///
/// # Errors
/// As [`read_point_groups`], and for a file without the curve columns.
pub fn read_curve_groups(
    path: &Path,
    key: Option<&str>,
    mut each: impl FnMut(Vec<(GroupKey, IoResult<Object>)>) -> IoResult<()>,
) -> IoResult<()> {
    let key = key.unwrap_or(DEFAULT_KEY);
    let rg = RowGroups::open(path)?;
    let source = rg.source.clone();
    let schema = rg.schema().clone();
    let col = |name: &str| {
        schema.index_of(name).map_err(|_| {
            IoError::syntax(
                Location::new(&source),
                format!("no column `{name}`; a curves file has the columns {key}, type, degree, knots, control and weights (docs/formats.md)"),
            )
        })
    };
    let (ck, ct, cd, ckn, cc, cw) = (
        col(key)?,
        col("type")?,
        col("degree")?,
        col("knots")?,
        col("control")?,
        col("weights")?,
    );
    let ce = schema.index_of("error").ok();
    for g in 0..rg.count() {
        let mut out = Vec::new();
        for batch in rg.read(g)? {
            let bad = |what: &str| {
                IoError::syntax(
                    Location::new(&source).at_field(what),
                    "the column does not have the type of docs/formats.md#parquet-batches",
                )
            };
            let keys = Keys::of(batch.column(ck).as_ref()).ok_or_else(|| bad(key))?;
            let kinds = batch
                .column(ct)
                .as_string_opt::<i32>()
                .ok_or_else(|| bad("type"))?;
            let degrees = Keys::of(batch.column(cd).as_ref())
                .filter(|k| matches!(k, Keys::I32(_) | Keys::I64(_)))
                .ok_or_else(|| bad("degree"))?;
            let knots = batch
                .column(ckn)
                .as_list_opt::<i32>()
                .ok_or_else(|| bad("knots"))?;
            let control = batch
                .column(cc)
                .as_list_opt::<i32>()
                .ok_or_else(|| bad("control"))?;
            let weights = batch
                .column(cw)
                .as_list_opt::<i32>()
                .ok_or_else(|| bad("weights"))?;
            let errors = ce.and_then(|c| batch.column(c).as_string_opt::<i32>());
            for r in 0..batch.num_rows() {
                let k = keys.get(r).ok_or_else(|| {
                    IoError::syntax(Location::new(&source).at_field(key), "a null key")
                })?;
                let at = Location::new(format!("{source}: group {k}"));
                if let Some(e) = errors.filter(|e| e.is_valid(r)) {
                    out.push((
                        k,
                        Err(IoError::syntax(at, format!("no curve: {}", e.value(r)))),
                    ));
                    continue;
                }
                let obj = curve_row(r, kinds, &degrees, knots, control, weights, &at);
                out.push((k, obj));
            }
        }
        if !out.is_empty() {
            each(out)?;
        }
    }
    Ok(())
}

fn floats(a: &dyn Array, at: &Location, what: &str) -> IoResult<Vec<f64>> {
    let n = Numbers::of(a)
        .ok_or_else(|| IoError::syntax(at.clone().at_field(what), "not a list of numbers"))?;
    (0..a.len())
        .map(|i| {
            n.get(i).ok_or_else(|| {
                IoError::syntax(at.clone().at_field(what), format!("value {i} is null"))
            })
        })
        .collect()
}

/// The control points of row `r` of `control` (a list of lists of numbers): their dimension
/// and their coordinates. The inner lists of one row lie end to end in the inner values, so the
/// coordinates are one slice of them, copied at once (no array or vector per point).
fn control_row(
    control: &arrow_array::ListArray,
    r: usize,
    at: &Location,
) -> IoResult<(usize, Vec<f64>)> {
    let bad = |m: String| IoError::syntax(at.clone().at_field("control"), m);
    let inner = control
        .values()
        .as_list_opt::<i32>()
        .ok_or_else(|| bad("not a list of lists of numbers".into()))?;
    let index = |o: i32| usize::try_from(o).unwrap_or(0);
    let outer = control.value_offsets();
    let (p0, p1) = (index(outer[r]), index(outer[r + 1]));
    let offsets = inner.value_offsets();
    let mut dim = None;
    for i in p0..p1 {
        if inner.is_null(i) {
            return Err(bad(format!("point {} is null", i - p0)));
        }
        let len = index(offsets[i + 1]) - index(offsets[i]);
        if let Some(d) = dim.filter(|&d| d != len) {
            return Err(bad(format!(
                "point {} has {len} coordinates, point 0 has {d}",
                i - p0
            )));
        }
        dim = Some(len);
    }
    let (a, b) = (index(offsets[p0]), index(offsets[p1]));
    let values = inner.values();
    let n =
        Numbers::of(values.as_ref()).ok_or_else(|| bad("not a list of lists of numbers".into()))?;
    let d = dim.unwrap_or(0);
    let ctrl = match &n {
        Numbers::F64(x) if x.null_count() == 0 => x.values()[a..b].to_vec(),
        _ => (a..b)
            .map(|j| {
                n.get(j).ok_or_else(|| {
                    let k = j - a;
                    bad(format!(
                        "point {} value {} is null",
                        k / d.max(1),
                        k % d.max(1)
                    ))
                })
            })
            .collect::<IoResult<_>>()?,
    };
    Ok((d, ctrl))
}

fn curve_row(
    r: usize,
    kinds: &arrow_array::StringArray,
    degrees: &Keys<'_>,
    knots: &arrow_array::ListArray,
    control: &arrow_array::ListArray,
    weights: &arrow_array::ListArray,
    at: &Location,
) -> IoResult<Object> {
    let kind = if kinds.is_valid(r) {
        kinds.value(r)
    } else {
        ""
    };
    let (dim, ctrl) = control_row(control, r, at)?;
    let invalid = |field: &str, error| IoError::Invalid {
        at: at.clone().at_field(field),
        error,
    };
    let ctrl = lekalo::Points::from_flat(dim, ctrl).map_err(|e| invalid("control", e))?;
    let degree = || {
        match degrees.get(r) {
            Some(GroupKey::Int(d)) => usize::try_from(d).ok(),
            _ => None,
        }
        .ok_or_else(|| IoError::syntax(at.clone().at_field("degree"), "not a degree"))
    };
    let list = |l: &arrow_array::ListArray, what: &str| {
        if l.is_null(r) {
            Err(IoError::syntax(at.clone().at_field(what), "null"))
        } else {
            floats(l.value(r).as_ref(), at, what)
        }
    };
    match kind {
        "bezier_curve" => lekalo::BezierCurve::new(ctrl)
            .map(Object::Bezier)
            .map_err(|e| invalid("control", e)),
        "bspline_curve" => lekalo::BSplineCurve::new(degree()?, list(knots, "knots")?, ctrl)
            .map(Object::BSpline)
            .map_err(|e| invalid("knots", e)),
        "nurbs_curve" => lekalo::NurbsCurve::new(
            degree()?,
            list(knots, "knots")?,
            ctrl,
            list(weights, "weights")?,
        )
        .map(Object::Nurbs)
        .map_err(|e| invalid("weights", e)),
        other => Err(IoError::syntax(
            at.clone().at_field("type"),
            format!("\"{other}\" is not a curve type; expected bezier_curve, bspline_curve or nurbs_curve"),
        )),
    }
}
