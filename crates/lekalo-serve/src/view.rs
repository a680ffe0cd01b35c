//! The drawing of a curve that every answer carrying a curve returns ([`CurveView`]):
//! samples, control polygon, knots on the curve, and on request the curvature comb and the
//! basis functions, each computed by the library.

use axum::response::Response;
use lekalo::basis::{basis_functions, basis_functions_many};
use lekalo::{KnotVector, Points, Progress};
use lekalo_io::Object;
use serde::{Deserialize, Serialize};

use crate::answer::answer;
use crate::error::{ApiError, ApiResult};
use crate::pool::Job;

/// Most samples of a curve or of the basis panel one request may ask for (the default of
/// [`Limits::max_samples`](crate::Limits::max_samples)).
pub const MAX_SAMPLES: usize = 10_000;

pub(crate) fn default_samples() -> usize {
    400
}

/// What to draw of a curve.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViewOptions {
    /// Samples along the curve (2 ..= [`Limits::max_samples`](crate::Limits::max_samples)).
    #[serde(default = "default_samples")]
    #[serde(deserialize_with = "crate::fields::count")]
    pub samples: usize,
    /// Also the curvature comb (curvature and principal normal at each sample).
    #[serde(default)]
    pub comb: bool,
    /// Samples of each basis function over the domain (none when absent).
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_count")]
    pub basis_samples: Option<usize>,
    /// Parameter at which the active basis functions are reported.
    #[serde(default)]
    #[serde(deserialize_with = "crate::fields::opt_number")]
    pub at: Option<f64>,
}

impl Default for ViewOptions {
    fn default() -> Self {
        ViewOptions {
            samples: default_samples(),
            comb: false,
            basis_samples: None,
            at: None,
        }
    }
}

/// The drawing of a curve: everything the editor paints, computed by the library.
#[derive(Debug, Clone, Serialize)]
pub struct CurveView {
    /// The curve in the CLI's object format (the text of [`Object::to_json_line`]).
    #[serde(serialize_with = "crate::answer::object")]
    pub curve: Object,
    /// Degree.
    pub degree: usize,
    /// Parameter domain `[a, b]`.
    pub domain: [f64; 2],
    /// Sample parameters.
    pub t: Vec<f64>,
    /// Points at `t` (rows).
    #[serde(serialize_with = "crate::answer::rows")]
    pub points: Points,
    /// Control points (rows).
    #[serde(serialize_with = "crate::answer::rows")]
    pub control: Points,
    /// Weights of a NURBS curve.
    pub weights: Option<Vec<f64>>,
    /// The full knot vector (Bezier curves: the equivalent clamped one on `[0, 1]`).
    pub knots: Vec<f64>,
    /// Distinct knots inside the domain (ends included) with multiplicity and point on the curve.
    pub knot_marks: Vec<KnotMark>,
    /// Curvature comb, when asked.
    pub comb: Option<Comb>,
    /// Basis functions, when asked.
    pub basis: Option<BasisView>,
}

impl CurveView {
    /// Bytes to reserve for the view's JSON text: its numbers (an upper bound for most
    /// curves; the buffer grows if a view needs more).
    #[must_use]
    pub fn size_hint(&self) -> usize {
        use crate::answer::NUMBER_BYTES;
        // the curve's text repeats the control points, knots and weights
        let numbers = self.t.len()
            + self.points.as_slice().len()
            + 2 * (self.control.as_slice().len()
                + self.weights.as_ref().map_or(0, Vec::len)
                + self.knots.len())
            + self.knot_marks.len() * (2 + self.points.dim())
            + self
                .comb
                .as_ref()
                .map_or(0, |c| c.curvature.len() * (1 + self.points.dim()))
            + self.basis.as_ref().map_or(0, |b| {
                b.t.len()
                    + 2 * b.active.len()
                    + b.functions
                        .iter()
                        .map(|f| 2 + f.values.len())
                        .sum::<usize>()
            });
        numbers * NUMBER_BYTES + 512
    }
}

/// A knot shown on the curve and on the ruler.
#[derive(Debug, Clone, Serialize)]
pub struct KnotMark {
    /// Knot value.
    pub t: f64,
    /// Multiplicity.
    pub multiplicity: usize,
    /// Point of the curve at the knot.
    pub point: Vec<f64>,
}

/// Curvature comb: `κ` and the unit principal normal at each sample (`null` where `C' = 0`).
#[derive(Debug, Clone, Serialize)]
pub struct Comb {
    /// Curvature `κ ≥ 0` (`lekalo::curvature`).
    pub curvature: Vec<Option<f64>>,
    /// Unit principal normal (towards the centre of curvature).
    pub normal: Vec<Option<Vec<f64>>>,
}

/// The B-spline basis `N_{i,p}` over the knot vector, sampled.
#[derive(Debug, Clone, Serialize)]
pub struct BasisView {
    /// Sample parameters (shared by every function).
    pub t: Vec<f64>,
    /// One entry per basis function: its index, the first sample of its support and the
    /// values from there (zero outside).
    pub functions: Vec<BasisFunction>,
    /// Indices `i` of the functions non-zero at `at` (`span − p ..= span`).
    pub active: Vec<usize>,
    /// Their values at `at`.
    pub active_values: Vec<f64>,
}

/// One basis function's non-zero samples.
#[derive(Debug, Clone, Serialize)]
pub struct BasisFunction {
    /// Index `i` of `N_{i,p}`.
    pub i: usize,
    /// Index of the first sample in `t` with a value.
    pub from: usize,
    /// Values at `t[from..from + values.len()]`.
    pub values: Vec<f64>,
}

/// The drawing of `obj` (see [`CurveView`]) within the default [`Limits`](crate::Limits).
///
/// # Errors
/// Evaluation errors of the library (none for valid curves), a drawing above the limits
/// ([`Limits::check_view`](crate::Limits::check_view)).
pub fn view(obj: &Object, opt: &ViewOptions) -> ApiResult<CurveView> {
    view_in(
        &Job::unbounded(&crate::Limits::default()),
        obj,
        opt,
        "curve",
    )
}

/// The drawing of `obj`, sent in or built from the request field `field`, within the job's
/// limits and stopped by its progress hook: the budget is checked first
/// ([`Limits::check_view`](crate::Limits::check_view)), then the samples, the knot marks and
/// the comb are computed by the library's cancellable batch evaluation.
///
/// # Errors
/// As [`view`]; 504 when the job is cancelled.
pub fn view_in(
    job: &Job<'_>,
    obj: &Object,
    opt: &ViewOptions,
    field: &str,
) -> ApiResult<CurveView> {
    job.limits.check_view(obj, opt, field)?;
    let n = opt.samples;
    let progress = &job.progress;
    let t = obj.uniform_parameters(n);
    let points = eval_batch(obj, &t, progress)?;
    let knots = obj.knots();
    let (a, b) = obj.domain();
    let (marks, multiplicity): (Vec<f64>, Vec<usize>) = knots
        .distinct()
        .into_iter()
        .filter(|&(k, _)| k >= a && k <= b)
        .unzip();
    let at_marks = eval_batch(obj, &marks, progress)?;
    let knot_marks = marks
        .iter()
        .zip(multiplicity)
        .zip(at_marks.iter())
        .map(|((&t, multiplicity), p)| KnotMark {
            t,
            multiplicity,
            point: p.to_vec(),
        })
        .collect();
    let comb = if opt.comb {
        let mut curvature = Vec::with_capacity(n);
        let mut normal = Vec::with_capacity(n);
        // the per-sample derivatives are stopped by the same hook
        let per_step = Progress::items_per_step((obj.degree() as u64 + 1).pow(2));
        for (i, &ti) in t.iter().enumerate() {
            if i % per_step == 0 {
                progress
                    .step("curvature comb", i as u64, n as u64)
                    .map_err(|e| ApiError::lib_or("curve", &e))?;
            }
            let d = obj
                .eval_derivatives(ti, 2)
                .map_err(|e| ApiError::lib_or("curve", &e))?;
            let rows: Vec<&[f64]> = d.iter().collect();
            let (d1, d2) = (rows[1], rows[2]);
            curvature.push(lekalo::curvature(d1, d2));
            normal.push(lekalo::principal_normal(d1, d2));
        }
        Some(Comb { curvature, normal })
    } else {
        None
    };
    let basis = match opt.basis_samples {
        Some(m) => Some(basis_view(&knots, obj.degree(), m, opt.at)?),
        None => None,
    };
    Ok(CurveView {
        curve: obj.clone(),
        degree: obj.degree(),
        domain: [a, b],
        t,
        points,
        control: obj.control_points().into_owned(),
        weights: obj.weights(),
        knots: knots.into_owned().into_vec(),
        knot_marks,
        comb,
        basis,
    })
}

/// The points of `obj` at the sorted parameters `ts`, by the library's batch evaluation (one
/// span search moving forward, no allocation per point).
fn eval_batch(obj: &Object, ts: &[f64], progress: &Progress<'_>) -> ApiResult<Points> {
    let dim = obj.dim();
    let mut out = vec![0.0; ts.len() * dim];
    obj.eval_batch_with_progress(ts, &mut out, progress)
        .map_err(|e| ApiError::lib_or("curve", &e))?;
    Points::from_flat(dim, out).map_err(|e| ApiError::lib_or("curve", &e))
}

/// The basis functions of degree `p` over `knots`, sampled at `m` parameters
/// (`lekalo::basis::basis_functions_many`, P&T A2.2), and those active at `at`.
fn basis_view(knots: &KnotVector, p: usize, m: usize, at: Option<f64>) -> ApiResult<BasisView> {
    let (a, b) = knots.domain(p);
    let count = knots.len().saturating_sub(p + 1);
    let t = lekalo_io::uniform(a, b, m);
    let mut functions: Vec<BasisFunction> = (0..count)
        .map(|i| BasisFunction {
            i,
            from: usize::MAX,
            values: Vec::new(),
        })
        .collect();
    let (spans, values) =
        basis_functions_many(knots, p, &t).map_err(|e| ApiError::lib_or("knots", &e))?;
    for (j, (&span, vals)) in spans.iter().zip(values.chunks_exact(p + 1)).enumerate() {
        for (r, &v) in vals.iter().enumerate() {
            let Some(f) = functions.get_mut(span + r - p) else {
                continue;
            };
            if f.from == usize::MAX {
                f.from = j;
            }
            // fill zeros inside the support (a function can vanish at an interior sample)
            f.values.resize(j - f.from, 0.0);
            f.values.push(v);
        }
    }
    for f in &mut functions {
        if f.from == usize::MAX {
            f.from = 0;
        }
    }
    let (active, active_values) = match at {
        Some(x) => {
            let (span, vals) =
                basis_functions(knots, p, x).map_err(|e| ApiError::lib_or("at", &e))?;
            ((span - p..=span).collect(), vals)
        }
        None => (Vec::new(), Vec::new()),
    };
    Ok(BasisView {
        t,
        functions,
        active,
        active_values,
    })
}

/// The 200 answer of a view.
pub(crate) fn view_answer(v: &CurveView) -> Response {
    answer(v, v.size_hint())
}
