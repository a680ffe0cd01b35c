//! Transformation matrices (entity 124, IGES 5.3 §4.21): `x ↦ R x + T`, given by the twelve
//! parameters `R11 R12 R13 T1 R21 R22 R23 T2 R31 R32 R33 T3`. An entity whose directory entry
//! points at one (field 7) is defined in the matrix's coordinates; a matrix may point at another
//! in turn, which is applied after it: `R = R₂ R₁`, `T = R₂ T₁ + T₂`. Forms 0 and 1 (a rotation,
//! or one with a reflection, and a translation) are read; forms 10–12 (finite-element
//! coordinate systems) place nothing a curve or surface uses and are refused.

use std::collections::HashMap;

use lekalo::Points;

use super::fields::{count, fields, real};
use crate::cad::motion::Motion;
use crate::shape::Shape;

/// Chains of matrices longer than this are refused (a file could make them cyclic).
const MAX_CHAIN: usize = 16;

/// One entity 124 of the file.
pub(super) struct Matrix {
    motion: Result<Motion, String>,
    /// The directory entry of the matrix applied after this one (0 for none).
    then: u64,
}

/// The entities 124 of the directory section `d` (two records an entity) with their parameters
/// from the section `p`, by the sequence number of their directory entry. The translations are
/// in the file's unit and become millimetres by `unit_mm`. A matrix that cannot be read is kept
/// with the reason, given to the entities that use it.
pub(super) fn matrices(
    d: &[(usize, &str)],
    p: &[(usize, &str)],
    delim: char,
    record: char,
    unit_mm: f64,
) -> HashMap<u64, Matrix> {
    let field = |s: &str, k: usize| s.get(8 * k..8 * k + 8).unwrap_or("").trim().to_string();
    let mut out = HashMap::new();
    for pair in d.chunks_exact(2) {
        let ((_, a), (_, b)) = (pair[0], pair[1]);
        if field(a, 0) != "124" {
            continue;
        }
        let Some(seq) = a.get(73..80).and_then(|s| s.trim().parse::<u64>().ok()) else {
            continue;
        };
        let then = count(&field(a, 6)).unwrap_or(0) as u64;
        let form = field(b, 4);
        let motion = if matches!(form.as_str(), "" | "0" | "1") {
            let start = count(&field(a, 1)).unwrap_or(0);
            let n = count(&field(b, 3)).unwrap_or(0);
            let lines = start
                .checked_sub(1)
                .and_then(|s| p.get(s..s.checked_add(n)?));
            match lines {
                Some(lines) if n > 0 => {
                    let body: String = lines
                        .iter()
                        .map(|(_, l)| l.get(..64).unwrap_or(l))
                        .collect();
                    let f = fields(&body, delim, record);
                    let v: Option<Vec<f64>> =
                        (1..=12).map(|k| f.get(k).and_then(|s| real(s))).collect();
                    match v {
                        Some(v) if v.iter().all(|x| x.is_finite()) => {
                            let r = [0, 1, 2].map(|i| [v[4 * i], v[4 * i + 1], v[4 * i + 2]]);
                            let t = [0, 1, 2].map(|i| v[4 * i + 3] * unit_mm);
                            Ok(Motion::affine(r, t))
                        }
                        _ => Err(format!(
                            "its transformation matrix D{seq} does not have 12 finite numbers (R11 R12 R13 T1 … T3)"
                        )),
                    }
                }
                _ => Err(format!(
                    "its transformation matrix D{seq} points outside the parameter data section"
                )),
            }
        } else {
            Err(format!(
                "its transformation matrix D{seq} is of form {form}, a finite-element coordinate system, not a placement"
            ))
        };
        out.insert(seq, Matrix { motion, then });
    }
    out
}

/// The map of the matrix at directory entry `at` followed by the ones it points at, or why it
/// cannot be applied: a pointer at something that is not an entity 124, a matrix that cannot
/// be read, matrices that point back at one of the chain (named in order, `D5 → D7 → D5`) or
/// a chain longer than [`MAX_CHAIN`].
pub(super) fn chain(matrices: &HashMap<u64, Matrix>, mut at: u64) -> Result<Motion, String> {
    let mut total = Motion::IDENTITY;
    let mut path: Vec<u64> = Vec::new();
    let named = |ids: &[u64]| {
        ids.iter()
            .map(|d| format!("D{d}"))
            .collect::<Vec<_>>()
            .join(" → ")
    };
    loop {
        if let Some(k) = path.iter().position(|&d| d == at) {
            path.push(at);
            return Err(format!(
                "its transformation matrices form a cycle, {}: each matrix must point at the \
                 one applied after it, or at none (0)",
                named(&path[k..])
            ));
        }
        if path.len() >= MAX_CHAIN {
            return Err(format!(
                "its transformation matrices are chained more than {MAX_CHAIN} deep ({} → …)",
                named(&path[..4])
            ));
        }
        let Some(m) = matrices.get(&at) else {
            return Err(format!(
                "its transformation matrix pointer D{at} is not an entity 124"
            ));
        };
        total = total.then(m.motion.as_ref().map_err(Clone::clone)?);
        if m.then == 0 {
            return Ok(total);
        }
        path.push(at);
        at = m.then;
    }
}

/// `shape` in the coordinates of the map `m`: its control points mapped (weights and knots
/// kept), which maps the curve or surface exactly (affine invariance).
pub(super) fn moved(shape: Shape, m: &Motion) -> lekalo::Result<Shape> {
    let map = |pts: &Points| -> lekalo::Result<Points> {
        let mut data = pts.as_slice().to_vec();
        for p in data.chunks_exact_mut(pts.dim()) {
            m.point(p);
        }
        Points::from_flat(pts.dim(), data)
    };
    Ok(match shape {
        Shape::Curve(c) => Shape::Curve(c.with_control_points(map(&c.control_points())?)?),
        Shape::Surface(s) => Shape::Surface(s.with_control_points(map(&s.control_points())?)?),
        other => other,
    })
}
