//! The shape-constraint keyword arguments of the fit functions (`increasing`, `decreasing`,
//! `convex`, `concave`, `min`, `max`, `through`, `slope_at`, `integral`, `periodic`), read into
//! the library's
//! [`ShapeConstraints`] (`docs/theory/fitting.md#shape-constraints`), and those of the surface
//! fits (`increasing="u"`, `min=`, …, each on the whole domain or a box) into
//! [`SurfaceShapeConstraints`]. Conversions only.

use lekalo::fit::{Shape, ShapeConstraints, SurfaceShape, SurfaceShapeConstraints};
use lekalo::vocabulary::DIRECTION;
use pyo3::prelude::*;

use crate::error::bad;
use crate::words::word;

/// The keyword arguments as given (each `None` when absent).
#[derive(Default)]
pub(crate) struct ShapeArgs<'a, 'py> {
    pub(crate) increasing: Option<&'a Bound<'py, PyAny>>,
    pub(crate) decreasing: Option<&'a Bound<'py, PyAny>>,
    pub(crate) convex: Option<&'a Bound<'py, PyAny>>,
    pub(crate) concave: Option<&'a Bound<'py, PyAny>>,
    pub(crate) min: Option<&'a Bound<'py, PyAny>>,
    pub(crate) max: Option<&'a Bound<'py, PyAny>>,
    pub(crate) through: Option<&'a Bound<'py, PyAny>>,
    pub(crate) slope_at: Option<&'a Bound<'py, PyAny>>,
    pub(crate) integral: Option<&'a Bound<'py, PyAny>>,
    pub(crate) periodic: Option<&'a Bound<'py, PyAny>>,
}

impl<'py> ShapeArgs<'_, 'py> {
    /// The constraints: a derivative shape is `True` (the whole domain), an interval `(a, b)`
    /// or a list of intervals (`(x, x)`: at the point `x`); a bound is a number `v` (everywhere),
    /// `(v, a, b)`, `(v, x)` at the point `x`, or a list of those; `through` and `slope_at` are
    /// `(x, v)` or a list of pairs; `integral` is `(a, b, v)` (`∫_a^b y = v`) or a list of
    /// those; `periodic` is a bool.
    pub(crate) fn constraints(&self) -> PyResult<ShapeConstraints> {
        let mut c = ShapeConstraints::new();
        let kinds = [
            (self.increasing, Shape::Increasing, "increasing"),
            (self.decreasing, Shape::Decreasing, "decreasing"),
            (self.convex, Shape::Convex, "convex"),
            (self.concave, Shape::Concave, "concave"),
        ];
        for (arg, shape, name) in kinds {
            let Some(arg) = arg else { continue };
            if let Ok(on) = arg.extract::<bool>() {
                if on {
                    c = c.with(shape);
                }
            } else if let Ok((a, b)) = arg.extract::<(f64, f64)>() {
                c = c.with_on(shape, a, b);
            } else if let Ok(list) = arg.extract::<Vec<(f64, f64)>>() {
                for (a, b) in list {
                    c = c.with_on(shape, a, b);
                }
            } else {
                return Err(bad(format!(
                    "{name}: give True, an interval (a, b) or a list of intervals"
                )));
            }
        }
        for (arg, name) in [(self.min, "min"), (self.max, "max")] {
            let Some(arg) = arg else { continue };
            let bound = |v: f64| {
                if name == "min" {
                    Shape::AtLeast(v)
                } else {
                    Shape::AtMost(v)
                }
            };
            // (v, a, b) on [a, b]; (v, x) at the point x: the interval [x, x]
            let on = |item: &Bound<'py, PyAny>| -> Option<(f64, f64, f64)> {
                if let Ok(t) = item.extract::<(f64, f64, f64)>() {
                    Some(t)
                } else {
                    item.extract::<(f64, f64)>().ok().map(|(v, x)| (v, x, x))
                }
            };
            if let Ok(v) = arg.extract::<f64>() {
                c = c.with(bound(v));
            } else if let Some((v, a, b)) = on(arg) {
                c = c.with_on(bound(v), a, b);
            } else if let Some(list) = arg
                .extract::<Vec<Bound<'py, PyAny>>>()
                .ok()
                .and_then(|items| items.iter().map(on).collect::<Option<Vec<_>>>())
            {
                for (v, a, b) in list {
                    c = c.with_on(bound(v), a, b);
                }
            } else {
                return Err(bad(format!(
                    "{name}: give a number v, (v, a, b) for [a, b], (v, x) at the point x, or a \
                     list of those"
                )));
            }
        }
        for (arg, order, name) in [(self.through, 0, "through"), (self.slope_at, 1, "slope_at")] {
            let Some(arg) = arg else { continue };
            let points = if let Ok(p) = arg.extract::<(f64, f64)>() {
                vec![p]
            } else if let Ok(list) = arg.extract::<Vec<(f64, f64)>>() {
                list
            } else {
                return Err(bad(format!("{name}: give (x, v) or a list of (x, v)")));
            };
            for (x, v) in points {
                c = c.with_point(x, order, v);
            }
        }
        if let Some(arg) = self.integral {
            let list = if let Ok(t) = arg.extract::<(f64, f64, f64)>() {
                vec![t]
            } else if let Ok(list) = arg.extract::<Vec<(f64, f64, f64)>>() {
                list
            } else {
                return Err(bad(
                    "integral: give (a, b, v) for ∫_a^b y dx = v, or a list of those".into(),
                ));
            };
            for (a, b, v) in list {
                c = c.with_integral(a, b, v);
            }
        }
        if let Some(arg) = self.periodic {
            match arg.extract::<bool>() {
                Ok(true) => c = c.with_periodicity(),
                Ok(false) => {}
                Err(_) => return Err(bad("periodic: give True or False".into())),
            }
        }
        Ok(c)
    }
}

/// The shape keyword arguments of the surface fits (`increasing`, `decreasing`, `min`, `max`),
/// as given.
#[derive(Default)]
pub(crate) struct SurfaceShapeArgs<'a, 'py> {
    pub(crate) increasing: Option<&'a Bound<'py, PyAny>>,
    pub(crate) decreasing: Option<&'a Bound<'py, PyAny>>,
    pub(crate) min: Option<&'a Bound<'py, PyAny>>,
    pub(crate) max: Option<&'a Bound<'py, PyAny>>,
}

/// A box `((u0, u1), (v0, v1))` of a surface's domain, or `None` for the whole domain.
type SurfaceBox = Option<((f64, f64), (f64, f64))>;

impl<'py> SurfaceShapeArgs<'_, 'py> {
    /// The constraints (`docs/theory/fitting.md#shape-constraints-of-surfaces`): a monotonicity
    /// is a direction `"u"` or `"v"`, `True` (both directions), `(direction, (u0, u1), (v0, v1))`
    /// on a box, or a list of those; a bound is a number (everywhere), `(v, (u0, u1), (v0, v1))`
    /// on a box, or a list of those.
    pub(crate) fn constraints(&self) -> PyResult<SurfaceShapeConstraints> {
        let mut c = SurfaceShapeConstraints::new();
        let add = |c: SurfaceShapeConstraints, shape, on: SurfaceBox| match on {
            None => c.with(shape),
            Some((u, v)) => c.with_on(shape, u, v),
        };
        for (arg, name) in [
            (self.increasing, "increasing"),
            (self.decreasing, "decreasing"),
        ] {
            let Some(arg) = arg else { continue };
            // one item: a direction, or a direction on a box
            let item = |x: &Bound<'py, PyAny>| -> Option<(String, SurfaceBox)> {
                if let Ok(d) = x.extract::<String>() {
                    Some((d, None))
                } else {
                    let (d, u, v) = x.extract::<(String, (f64, f64), (f64, f64))>().ok()?;
                    Some((d, Some((u, v))))
                }
            };
            let items: Vec<(String, SurfaceBox)> = if let Ok(on) = arg.extract::<bool>() {
                if on {
                    vec![("u".into(), None), ("v".into(), None)]
                } else {
                    vec![]
                }
            } else if let Some(one) = item(arg) {
                vec![one]
            } else if let Some(list) = arg
                .extract::<Vec<Bound<'py, PyAny>>>()
                .ok()
                .and_then(|xs| xs.iter().map(item).collect::<Option<Vec<_>>>())
            {
                list
            } else {
                return Err(bad(format!(
                    "{name}: give a direction \"u\" or \"v\", True for both, (direction, \
                     (u0, u1), (v0, v1)) on a box, or a sequence of those"
                )));
            };
            for (d, on) in items {
                let d = word(&DIRECTION, name, &d)?;
                let shape = if name == "increasing" {
                    SurfaceShape::Increasing(d)
                } else {
                    SurfaceShape::Decreasing(d)
                };
                c = add(c, shape, on);
            }
        }
        for (arg, name) in [(self.min, "min"), (self.max, "max")] {
            let Some(arg) = arg else { continue };
            let item = |x: &Bound<'py, PyAny>| -> Option<(f64, SurfaceBox)> {
                if let Ok(v) = x.extract::<f64>() {
                    Some((v, None))
                } else {
                    let (v, u, w) = x.extract::<(f64, (f64, f64), (f64, f64))>().ok()?;
                    Some((v, Some((u, w))))
                }
            };
            // a list holds boxes: (v, x) is not a pair of bounds
            let boxed = |x: &Bound<'py, PyAny>| item(x).filter(|(_, on)| on.is_some());
            let items = if let Some(one) = item(arg) {
                vec![one]
            } else if let Some(list) = arg
                .extract::<Vec<Bound<'py, PyAny>>>()
                .ok()
                .and_then(|xs| xs.iter().map(boxed).collect::<Option<Vec<_>>>())
            {
                list
            } else {
                return Err(bad(format!(
                    "{name}: give a number (the bound everywhere), (v, (u0, u1), (v0, v1)) on a \
                     box, or a list of boxed bounds"
                )));
            };
            for (v, on) in items {
                let shape = if name == "min" {
                    SurfaceShape::AtLeast(v)
                } else {
                    SurfaceShape::AtMost(v)
                };
                c = add(c, shape, on);
            }
        }
        Ok(c)
    }
}
