//! The shape constraints of `lekalo fit`'s options (`--increasing`, `--convex`, `--min`,
//! `--through`, `--integral` …), read into the library's `ShapeConstraints`
//! (`docs/theory/fitting.md#shape-constraints`), for the curve fits and the periodic ones, and
//! the surfaces' (`--increasing=u`, `--min V`, each on a box with `@U0:U1,V0:V1`) into
//! `SurfaceShapeConstraints`.

use anyhow::Result;
use lekalo::fit::{Shape, ShapeConstraints, SurfaceShape, SurfaceShapeConstraints};

use super::args::FitArgs;
use crate::exit::bad_input;
use crate::values::numbers;

/// The shape constraints of the options, in the order of the options' kinds.
pub(super) fn shape_constraints(a: &FitArgs) -> Result<ShapeConstraints> {
    let mut c = ShapeConstraints::new();
    let interval = |text: &str, option: &str| -> Result<Option<(f64, f64)>> {
        if text.is_empty() {
            return Ok(None);
        }
        let ab = numbers(&text.replacen(':', ",", 1), option)?;
        match ab[..] {
            [a, b] => Ok(Some((a, b))),
            // one point: the shape at X only
            [x] => Ok(Some((x, x))),
            _ => bad_input(format!(
                "{option}: \"{text}\" is not an interval A:B or a point X"
            )),
        }
    };
    let kinds: [(&[String], Shape, &str); 4] = [
        (&a.increasing, Shape::Increasing, "--increasing"),
        (&a.decreasing, Shape::Decreasing, "--decreasing"),
        (&a.convex, Shape::Convex, "--convex"),
        (&a.concave, Shape::Concave, "--concave"),
    ];
    for (list, shape, option) in kinds {
        for text in list {
            c = match interval(text, option)? {
                None => c.with(shape),
                Some((lo, hi)) => c.with_on(shape, lo, hi),
            };
        }
    }
    for (list, option) in [(&a.min, "--min"), (&a.max, "--max")] {
        for text in list {
            let (v, on) = text.split_once('@').unwrap_or((text, ""));
            let v = match numbers(v, option)?[..] {
                [v] => v,
                _ => return bad_input(format!("{option}: \"{text}\" is not V, V@A:B or V@X")),
            };
            let shape = if option == "--min" {
                Shape::AtLeast(v)
            } else {
                Shape::AtMost(v)
            };
            c = match interval(on, option)? {
                None => c.with(shape),
                Some((lo, hi)) => c.with_on(shape, lo, hi),
            };
        }
    }
    for (list, order, option) in [(&a.through, 0, "--through"), (&a.slope_at, 1, "--slope-at")] {
        for text in list {
            let parsed = text
                .split_once('=')
                .map(|(x, v)| (numbers(x, option), numbers(v, option)));
            match parsed {
                Some((Ok(x), Ok(v))) if x.len() == 1 && v.len() == 1 => {
                    c = c.with_point(x[0], order, v[0]);
                }
                _ => return bad_input(format!("{option}: \"{text}\" is not X=V")),
            }
        }
    }
    for text in &a.integral {
        let parsed = text.split_once('=').map(|(ab, v)| {
            (
                numbers(&ab.replacen(':', ",", 1), "--integral"),
                numbers(v, "--integral"),
            )
        });
        match parsed {
            Some((Ok(ab), Ok(v))) if ab.len() == 2 && v.len() == 1 => {
                c = c.with_integral(ab[0], ab[1], v[0]);
            }
            _ => return bad_input(format!("--integral: \"{text}\" is not A:B=V")),
        }
    }
    Ok(c)
}

/// The box `U0:U1,V0:V1` of a surface's shape (`@…` of `--increasing=u@…`, `--min V@…`); a
/// range may be one number, a line of the domain.
fn surface_box(text: &str, option: &str) -> Result<((f64, f64), (f64, f64))> {
    let range = |part: &str| -> Option<(f64, f64)> {
        match numbers(&part.replacen(':', ",", 1), option).ok()?[..] {
            [a, b] => Some((a, b)),
            [x] => Some((x, x)),
            _ => None,
        }
    };
    if let Some((u, v)) = text.split_once(',') {
        if let (Some(u), Some(v)) = (range(u), range(v)) {
            return Ok((u, v));
        }
    }
    bad_input(format!(
        "{option}: \"{text}\" is not a box U0:U1,V0:V1 of the surface's domain (e.g. @0:0.5,0:1)"
    ))
}

/// The shape constraints of a surface `z(u, v)` (`--grid NUxNV` or `--scattered`): `--increasing`
/// and `--decreasing` with a direction `=u`, `=v` or `=u,v` (both when bare), `--min V` and
/// `--max V`, each on the whole domain or, after `@U0:U1,V0:V1`, on that box
/// (`docs/theory/fitting.md#shape-constraints-of-surfaces`).
pub(super) fn surface_shape_constraints(a: &FitArgs) -> Result<SurfaceShapeConstraints> {
    let curve_only = [
        (!a.convex.is_empty(), "--convex"),
        (!a.concave.is_empty(), "--concave"),
        (!a.through.is_empty(), "--through"),
        (!a.slope_at.is_empty(), "--slope-at"),
        (!a.integral.is_empty(), "--integral"),
    ];
    if let Some((_, option)) = curve_only.iter().find(|(given, _)| *given) {
        return bad_input(format!(
            "{option} is a shape of curves y(x); a surface keeps --increasing[=u|v], \
             --decreasing[=u|v], --min V and --max V (each with @U0:U1,V0:V1 for a box)"
        ));
    }
    let mut c = SurfaceShapeConstraints::new();
    let add = |c: SurfaceShapeConstraints, shape, on: Option<((f64, f64), (f64, f64))>| match on {
        None => c.with(shape),
        Some((u, v)) => c.with_on(shape, u, v),
    };
    for (list, option) in [
        (&a.increasing, "--increasing"),
        (&a.decreasing, "--decreasing"),
    ] {
        for text in list {
            let (directions, on) = match text.split_once('@') {
                Some((d, b)) => (d, Some(surface_box(b, option)?)),
                None => (text.as_str(), None),
            };
            let words: Vec<&str> = if directions.is_empty() {
                vec!["u", "v"]
            } else {
                directions.split(',').collect()
            };
            for w in words {
                let Ok(d) = lekalo::vocabulary::DIRECTION.parse(w) else {
                    return bad_input(format!(
                        "{option}={text}: a surface is monotone in a direction: write \
                         {option}=u, {option}=v, or {option} alone for both (add \
                         @U0:U1,V0:V1 for a box)"
                    ));
                };
                let shape = if option == "--increasing" {
                    SurfaceShape::Increasing(d.value)
                } else {
                    SurfaceShape::Decreasing(d.value)
                };
                c = add(c, shape, on);
            }
        }
    }
    for (list, option) in [(&a.min, "--min"), (&a.max, "--max")] {
        for text in list {
            let (v, on) = match text.split_once('@') {
                Some((v, b)) => (v, Some(surface_box(b, option)?)),
                None => (text.as_str(), None),
            };
            let v = match numbers(v, option).ok().as_deref() {
                Some(&[v]) => v,
                _ => {
                    return bad_input(format!(
                        "{option}: \"{text}\" is not V or V@U0:U1,V0:V1 (a bound of the \
                         surface's values, everywhere or on a box)"
                    ))
                }
            };
            let shape = if option == "--min" {
                SurfaceShape::AtLeast(v)
            } else {
                SurfaceShape::AtMost(v)
            };
            c = add(c, shape, on);
        }
    }
    Ok(c)
}
