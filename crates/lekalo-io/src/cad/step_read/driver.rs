//! [`read_step`]: the exchange structure parsed, its length unit found, then each geometric
//! entity read or listed as skipped.

use std::collections::HashSet;

use super::entities::{is_bspline_curve, is_bspline_surface, Reader, OTHER_GEOMETRY};
use super::parse::parse;
use super::units::length_unit;
use super::{StepRead, StepSkipped, Why};
use crate::error::{IoError, IoResult};
use crate::shape::Shape;

/// Reads the B-spline and NURBS curves and surfaces of a STEP file. `source` names the file in
/// errors.
///
/// ```
/// use lekalo_io::{read_step, Object, Shape, StepWriter};
/// let c = lekalo::NurbsCurve::circle(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0)?;
/// let mut w = StepWriter::new("circle");
/// w.add_object(&Object::Nurbs(c.clone()))?;
/// let r = read_step(&w.finish("2000-01-01T00:00:00"), "circle.step")?;
/// assert_eq!(r.shapes.len(), 1);
/// assert_eq!(r.shapes[0].1, Shape::Curve(Object::Nurbs(c)));   // bit for bit
/// assert_eq!(r.length_unit, "millimetre");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`IoError::Syntax`] (with the line) when the text is not an exchange structure;
/// [`IoError::Syntax`] naming the entity when a B-spline entity is malformed or rejected by the
/// library's constructor (unsorted knots, wrong counts, non-positive weights).
pub fn read_step(text: &str, source: &str) -> IoResult<StepRead> {
    let parsed = parse(text, source)?;
    let (length_unit, scale) = length_unit(&parsed, source)?;
    let rd = Reader {
        p: &parsed,
        source,
        scale,
    };
    let mut ids: Vec<u64> = parsed.instances.keys().copied().collect();
    ids.sort_unstable();
    let mut shapes = Vec::new();
    let mut skipped = Vec::new();
    let mut trimmed_bases = HashSet::new();
    let mut trimmed = Vec::new();
    // the basis control points all trims may read: four times the instances of the file (each
    // control point is an instance), so that reading stays linear in the file's size
    let mut budget = parsed.instances.len().saturating_mul(4);
    for &id in &ids {
        let inst = &parsed.instances[&id];
        if let Some(r) = inst.get("TRIMMED_CURVE") {
            match rd.trimmed(r, &mut budget) {
                Ok((basis, piece)) => {
                    trimmed_bases.insert(basis);
                    trimmed.push((id, Shape::Curve(piece)));
                }
                Err(reason) => skipped.push(StepSkipped {
                    id,
                    entity: "TRIMMED_CURVE".into(),
                    reason,
                }),
            }
        }
    }
    for &id in &ids {
        let inst = &parsed.instances[&id];
        let bad = |why: Why| {
            IoError::syntax(
                rd.at(id),
                format!("entity #{id} {}: {why}", inst.type_name()),
            )
        };
        if is_bspline_curve(inst) {
            if trimmed_bases.contains(&id) {
                continue;
            }
            match rd.curve(inst) {
                Ok(c) => shapes.push((id, Shape::Curve(c))),
                Err(why) if why.starts_with("implicit knots") => skipped.push(StepSkipped {
                    id,
                    entity: inst.type_name(),
                    reason: why,
                }),
                Err(why) => return Err(bad(why)),
            }
        } else if is_bspline_surface(inst) {
            match rd.surface(inst) {
                Ok(s) => shapes.push((id, Shape::Surface(s))),
                Err(why) if why.starts_with("implicit knots") => skipped.push(StepSkipped {
                    id,
                    entity: inst.type_name(),
                    reason: why,
                }),
                Err(why) => return Err(bad(why)),
            }
        } else if let Some((name, _)) = inst
            .records
            .iter()
            .find(|(n, _)| OTHER_GEOMETRY.contains(&n.as_str()))
        {
            skipped.push(StepSkipped {
                id,
                entity: name.clone(),
                reason: "not a B-spline (lekalo reads B-spline and NURBS curves and surfaces)"
                    .into(),
            });
        }
    }
    shapes.extend(trimmed);
    shapes.sort_by_key(|(id, _)| *id);
    skipped.sort_by_key(|s| s.id);
    Ok(StepRead {
        shapes,
        skipped,
        schema: parsed.schema,
        length_unit,
        scale_to_mm: scale,
    })
}
