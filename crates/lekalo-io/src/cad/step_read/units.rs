//! The length unit of the file, from its unit context, and its factor to millimetres.

use super::parse::Parsed;
use super::{list, num, P};
use crate::error::{IoError, IoResult, Location};

/// The length unit of the file and its factor to millimetres.
///
/// # Errors
/// [`IoError::Syntax`] naming the unit's entity when its factor is zero, negative or beyond the
/// range of a double: such a unit would turn every point into the origin, mirror the geometry
/// or make it infinite.
pub(super) fn length_unit(p: &Parsed<'_>, source: &str) -> IoResult<(String, f64)> {
    // the unit assigned by the (first) global unit context, else any length unit of the file
    let ids = p.instances.ids();
    let from_context = ids.iter().find_map(|id| {
        let context = p.instances.known(id);
        let refs = context.get("GLOBAL_UNIT_ASSIGNED_CONTEXT")?.first()?;
        list(refs)?.iter().find_map(|r| match r {
            P::Ref(u) if p.instances.get(u).is_some_and(|i| i.has("LENGTH_UNIT")) => Some(*u),
            _ => None,
        })
    });
    let unit = from_context.or_else(|| {
        ids.iter()
            .copied()
            .find(|id| p.instances.known(id).has("LENGTH_UNIT"))
    });
    let Some(u) = unit else {
        return Ok(("millimetre (assumed)".to_string(), 1.0));
    };
    // a length unit declared but not readable (an unknown prefix or unit name, a conversion
    // without its measure, a cycle of conversions) is refused: assuming millimetres would scale
    // the geometry silently
    let Some((name, mm)) = unit_factor(p, u, 0) else {
        let mut at = Location::new(source);
        if let Some(i) = p.instances.get(&u) {
            at = at.at_line(i.line());
        }
        return Err(IoError::syntax(
            at,
            format!(
                "entity #{u}: a length unit lekalo cannot read (an SI_UNIT must name METRE with a known prefix or none, a CONVERSION_BASED_UNIT a LENGTH_MEASURE_WITH_UNIT of such a unit); correct the unit, or remove it and the file is read in millimetres"
            ),
        ));
    };
    if !(mm.is_finite() && mm > 0.0) {
        let mut at = Location::new(source);
        if let Some(i) = p.instances.get(&u) {
            at = at.at_line(i.line());
        }
        return Err(IoError::syntax(
            at,
            format!(
                "entity #{u}: the length unit {name} is {} mm; a unit must be a positive finite length, correct its conversion factor",
                crate::fmt_number(mm)
            ),
        ));
    }
    Ok((name, mm))
}

fn unit_factor(p: &Parsed<'_>, id: u64, depth: usize) -> Option<(String, f64)> {
    let inst = p.instances.get(&id)?;
    if let Some(si) = inst.get("SI_UNIT") {
        // `SI_UNIT(prefix, name)`, the prefix `$` or left out
        let prefix = match si.len().checked_sub(2).and_then(|k| si.get(k)) {
            Some(P::Enum(e)) => Some(e.as_str()),
            _ => None,
        };
        let f = match prefix {
            None => 1000.0,
            Some("EXA") => 1e21,
            Some("PETA") => 1e18,
            Some("TERA") => 1e15,
            Some("GIGA") => 1e12,
            Some("MEGA") => 1e9,
            Some("KILO") => 1e6,
            Some("HECTO") => 1e5,
            Some("DECA") => 1e4,
            Some("DECI") => 100.0,
            Some("CENTI") => 10.0,
            Some("MILLI") => 1.0,
            Some("MICRO") => 1e-3,
            Some("NANO") => 1e-6,
            Some("PICO") => 1e-9,
            Some("FEMTO") => 1e-12,
            Some("ATTO") => 1e-15,
            Some(_) => return None,
        };
        // the unit's name, after the prefix: a length unit is the metre
        if !matches!(si.last(), Some(P::Enum(n)) if n == "METRE") {
            return None;
        }
        let name = prefix.map_or_else(
            || "metre".to_string(),
            |p| format!("{}metre", p.to_ascii_lowercase()),
        );
        return Some((name, f));
    }
    if depth > 4 {
        return None;
    }
    let cb = inst.get("CONVERSION_BASED_UNIT")?;
    let name = match cb.first() {
        Some(P::Str(s)) => s.clone(),
        _ => "conversion-based unit".to_string(),
    };
    let P::Ref(m) = cb.get(1)? else { return None };
    let mi = p.instances.get(m)?;
    let measure = mi.records().first()?;
    let value = num(measure.1.first()?)?;
    let P::Ref(base) = measure.1.get(1)? else {
        return None;
    };
    let (_, f) = unit_factor(p, *base, depth + 1)?;
    let mm = value * f;
    Some((format!("{name} ({} mm)", crate::fmt_number(mm)), mm))
}

/// The plane angle unit of the file in radians: the `PLANE_ANGLE_UNIT` of the (first) global
/// unit context, `SI_UNIT(.RADIAN.)` (1) or a conversion-based unit such as `DEGREE`
/// (its `PLANE_ANGLE_MEASURE_WITH_UNIT`, π/180); 1 when the file declares none or the
/// declaration cannot be read.
pub(super) fn plane_angle_unit(p: &Parsed<'_>) -> f64 {
    let ids = p.instances.ids();
    let unit = ids.iter().find_map(|id| {
        let context = p.instances.known(id);
        let refs = context.get("GLOBAL_UNIT_ASSIGNED_CONTEXT")?.first()?;
        list(refs)?.iter().find_map(|r| match r {
            P::Ref(u)
                if p.instances
                    .get(u)
                    .is_some_and(|i| i.has("PLANE_ANGLE_UNIT")) =>
            {
                Some(*u)
            }
            _ => None,
        })
    });
    let factor = unit.and_then(|u| angle_factor(p, u, 0));
    factor.filter(|f| f.is_finite() && *f > 0.0).unwrap_or(1.0)
}

fn angle_factor(p: &Parsed<'_>, id: u64, depth: usize) -> Option<f64> {
    let inst = p.instances.get(&id)?;
    if let Some(si) = inst.get("SI_UNIT") {
        return match si.first() {
            Some(P::Enum(_)) => None,
            _ => Some(1.0),
        };
    }
    if depth > 4 {
        return None;
    }
    let cb = inst.get("CONVERSION_BASED_UNIT")?;
    let P::Ref(m) = cb.get(1)? else { return None };
    let mi = p.instances.get(m)?;
    let measure = mi.records().first()?;
    let value = num(measure.1.first()?)?;
    let P::Ref(base) = measure.1.get(1)? else {
        return None;
    };
    Some(value * angle_factor(p, *base, depth + 1)?)
}
