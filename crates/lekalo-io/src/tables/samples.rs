//! Tables of samples of a curve: parameter, point, derivatives, curvature, torsion; written as
//! CSV or JSON.

use serde_json::{Map, Value};

use crate::analysis::curvature;
use crate::object::Object;
use lekalo::torsion;

/// From this many parameters on, a sample table is evaluated on all cores.
const PARALLEL_ROWS: usize = 4096;

/// Rows of CSV formatted by one task.
const CSV_BLOCK: usize = 1 << 13;

/// What to compute at each parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SampleSpec {
    /// Highest derivative order (0 = points only).
    pub derivatives: usize,
    /// Add the curvature column (needs derivatives up to order 2, computed internally).
    pub curvature: bool,
    /// Add the torsion column ([`lekalo::torsion`]; 3-D curves only, derivatives up to order 3
    /// computed internally).
    pub torsion: bool,
}

/// A table of samples: column names and rows of numbers (`None` where undefined, e.g. the
/// curvature where `C' = 0`, the torsion where the curvature is zero).
#[derive(Debug, Clone, PartialEq)]
pub struct SampleTable {
    /// Column names: `t`, `x`, `y`, …, `d1x`, …, `curvature`, `torsion`.
    pub header: Vec<String>,
    /// One row per parameter.
    pub rows: Vec<Vec<Option<f64>>>,
}

/// Coordinate names of CSV columns: `x, y, z` up to 3-D, `x1 … xd` above.
pub fn coord_names(dim: usize) -> Vec<String> {
    if dim <= 3 {
        ["x", "y", "z"][..dim]
            .iter()
            .map(|s| s.to_string())
            .collect()
    } else {
        (1..=dim).map(|k| format!("x{k}")).collect()
    }
}

/// Evaluates `obj` at every parameter of `ts`.
///
/// # Errors
/// [`lekalo::Error::ParameterOutOfDomain`] for a parameter outside the domain;
/// [`lekalo::Error::Dimension`] for the torsion of a curve that is not 3-D.
pub fn sample_table(obj: &Object, ts: &[f64], spec: SampleSpec) -> lekalo::Result<SampleTable> {
    let dim = obj.dim();
    if spec.torsion && dim != 3 {
        return Err(lekalo::Error::Dimension {
            what: "curve for torsion".into(),
            expected: 3,
            got: dim,
        });
    }
    let names = coord_names(dim);
    let mut header = vec!["t".to_string()];
    header.extend(names.iter().cloned());
    for k in 1..=spec.derivatives {
        header.extend(names.iter().map(|n| format!("d{k}{n}")));
    }
    if spec.curvature {
        header.push("curvature".into());
    }
    if spec.torsion {
        header.push("torsion".into());
    }
    let order = if spec.torsion {
        spec.derivatives.max(3)
    } else if spec.curvature {
        spec.derivatives.max(2)
    } else {
        spec.derivatives
    };
    let row = |t: f64| -> lekalo::Result<Vec<Option<f64>>> {
        let d = obj.eval_derivatives(t, order)?;
        let mut row = Vec::with_capacity(1 + (spec.derivatives + 1) * dim + 2);
        row.push(Some(t));
        for k in 0..=spec.derivatives {
            row.extend(d.point(k).iter().map(|v| Some(*v)));
        }
        if spec.curvature {
            row.push(curvature(d.point(1), d.point(2)));
        }
        if spec.torsion {
            row.push(torsion(d.point(1), d.point(2), d.point(3)));
        }
        Ok(row)
    };
    // long samplings on all cores, rows in order; an error is then looked for again in order,
    // so that the first parameter outside the domain is the one reported
    let parallel = (ts.len() >= PARALLEL_ROWS)
        .then(|| {
            use rayon::prelude::*;
            ts.par_iter()
                .map(|&t| row(t))
                .collect::<lekalo::Result<Vec<_>>>()
                .ok()
        })
        .flatten();
    let rows = match parallel {
        Some(rows) => rows,
        None => ts
            .iter()
            .map(|&t| row(t))
            .collect::<lekalo::Result<Vec<_>>>()?,
    };
    Ok(SampleTable { header, rows })
}

impl SampleTable {
    /// CSV with a header line; undefined values are empty fields. Numbers are written in the
    /// shortest form that reads back to the same `f64` ([`crate::fmt_number`]: exponent
    /// notation below 1e-5 and from 1e16 on).
    #[must_use]
    pub fn to_csv(&self) -> String {
        let mut bytes = Vec::new();
        // writing into a Vec cannot fail, and the text is ASCII
        let _ = self.write_csv(&mut bytes, true);
        String::from_utf8(bytes).unwrap_or_default()
    }

    /// Writes the CSV of [`SampleTable::to_csv`] to `w`, the header line only if `header`, so
    /// that a long sampling can be written chunk by chunk. Rows are formatted with no
    /// allocation per number, in blocks on all cores, and the blocks handed to `w` in order
    /// (memory bounded by one round of blocks, see `json_write::write_list`).
    ///
    /// # Errors
    /// The writer's.
    pub fn write_csv(&self, w: &mut dyn std::io::Write, header: bool) -> std::io::Result<()> {
        let mut out = Vec::with_capacity(4096);
        if header {
            out.extend_from_slice(self.header.join(",").as_bytes());
            out.push(b'\n');
        }
        crate::json_write::write_list(
            w,
            &mut out,
            self.rows.len(),
            b"",
            CSV_BLOCK,
            |out, digits, r| {
                for (i, v) in self.rows[r].iter().enumerate() {
                    if i > 0 {
                        out.push(b',');
                    }
                    if let Some(x) = v {
                        crate::numfmt::push_number(out, digits, *x);
                    }
                }
                out.push(b'\n');
            },
        )?;
        w.write_all(&out)
    }

    /// JSON: an array of objects keyed by the column names (`null` where undefined).
    #[must_use]
    pub fn to_json(&self) -> Value {
        Value::Array(
            self.rows
                .iter()
                .map(|row| {
                    let m: Map<String, Value> = self
                        .header
                        .iter()
                        .zip(row)
                        .map(|(h, v)| (h.clone(), v.map_or(Value::Null, Value::from)))
                        .collect();
                    Value::Object(m)
                })
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lekalo::{BSplineCurve, Points};

    #[test]
    fn lecture_samples() {
        let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
        let c = Object::BSpline(
            BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap(),
        );
        let spec = SampleSpec {
            derivatives: 1,
            curvature: true,
            torsion: false,
        };
        let t = sample_table(&c, &[1.0, 1.5], spec).unwrap();
        assert_eq!(t.header, ["t", "x", "y", "d1x", "d1y", "curvature"]);
        // on [1,2): P = (t²/2 + 1, −t² + 4t − 1), P' = (t, 4 − 2t), P'' = (1, −2)
        let csv = t.to_csv();
        assert!(
            csv.starts_with("t,x,y,d1x,d1y,curvature\n1,1.5,2,1,2,"),
            "{csv}"
        );
        let k = t.rows[1][5].unwrap();
        let (d1, d2) = ([1.5f64, 1.0], [1.0f64, -2.0]);
        let expect = (d1[0] * d2[1] - d1[1] * d2[0]).abs() / (d1[0].hypot(d1[1])).powi(3);
        assert!((k - expect).abs() < 1e-14, "{k} vs {expect}");
        let j = t.to_json();
        assert_eq!(j[1]["x"], Value::from(2.125));
        assert!(sample_table(&c, &[2.5], spec).is_err());
        assert_eq!(coord_names(4), ["x1", "x2", "x3", "x4"]);
    }
    #[test]
    fn torsion_column_matches_the_query_curve_and_needs_3d() {
        // a cubic that leaves its osculating plane: C(t) = (t, t², t³) on [0, 1] as a Bezier
        // curve, τ(t) = 3 / (9t⁴ + 9t² + 1)
        let third = 1.0 / 3.0;
        let ctrl = Points::from_flat(
            3,
            vec![
                0.0,
                0.0,
                0.0,
                third,
                0.0,
                0.0,
                2.0 * third,
                third,
                0.0,
                1.0,
                1.0,
                1.0,
            ],
        )
        .unwrap();
        let c = Object::BSpline(
            BSplineCurve::new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], ctrl).unwrap(),
        );
        let spec = SampleSpec {
            derivatives: 0,
            curvature: true,
            torsion: true,
        };
        let ts = [0.0, 0.25, 0.5, 1.0];
        let table = sample_table(&c, &ts, spec).unwrap();
        assert_eq!(table.header, ["t", "x", "y", "z", "curvature", "torsion"]);
        for (row, &t) in table.rows.iter().zip(&ts) {
            let exact = 3.0 / (9.0 * t.powi(4) + 9.0 * t * t + 1.0);
            let tau = row[5].unwrap();
            assert!(
                (tau - exact).abs() < 1e-13 * exact.max(1.0),
                "τ({t}) = {tau} vs {exact}"
            );
        }
        // a 2-D curve has no torsion: a precise error, not a column of blanks
        let flat = Object::BSpline(
            BSplineCurve::new(
                1,
                vec![0.0, 0.0, 1.0, 1.0],
                Points::from_2d(&[[0.0, 0.0], [1.0, 1.0]]).unwrap(),
            )
            .unwrap(),
        );
        let err = sample_table(&flat, &[0.5], spec).unwrap_err();
        assert!(err.to_string().contains("torsion"), "{err}");
        // a straight 3-D line: curvature 0, torsion undefined
        let line = Object::BSpline(
            BSplineCurve::new(
                1,
                vec![0.0, 0.0, 1.0, 1.0],
                Points::from_flat(3, vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0]).unwrap(),
            )
            .unwrap(),
        );
        let t = sample_table(&line, &[0.5], spec).unwrap();
        assert_eq!(t.rows[0][4], Some(0.0));
        assert_eq!(t.rows[0][5], None);
        assert!(t.to_csv().ends_with(",0,\n"), "{}", t.to_csv());
    }
}
