//! Degree change of tensor-product Bezier surfaces (document 004, eq. (11)–(16)): functions on
//! a plain control net (`bezier_net_*`) and the same operations as methods of [`BezierSurface`].
//!
//! A net of degrees `(n, m)` is a [`Points`] of `(n+1)·(m+1)` points with point `(i, j)` at
//! `data[(i·(m+1) + j)·dim ..]`, `i ∈ 0..=n` along `u` (the paper's `t`) and `j ∈ 0..=m` along `v`
//! (the paper's `τ`). The surface is `p(u, v) = Σ_i Σ_j b_{n,i}(u) b_{m,j}(v) u_ij =
//! B_nᵀ(u) U B_m(v)` (eq. 11).
//!
//! The paper changes both degrees at once with `U' = (H_n E H_{n'}^{-1})ᵀ U (H_m E H_{m'}^{-1})`
//! (eq. 14). The two factors act on different indices, so this is a curve operation along `u`
//! followed by one along `v`:
//! - along `u`, the rows `i` of the net are the control points of one curve of dimension
//!   `(m+1)·dim` (they are contiguous in the flat layout);
//! - along `v`, the same after transposing the net.
//!
//! So every curve kernel of `bezier_degree` applies unchanged, with its stable path and its
//! accuracy. The degree defect along `u` (the number of zero bottom rows of
//! `S = H_nᵀ U H_m`, eq. 15–16) is the defect of that big curve, that is the smallest defect over
//! the column curves `j ↦ (u_0j … u_nj)`; likewise along `v`.

use crate::degree::elevation::{binomials, check_size, elevate};
use crate::degree::monomial::{
    from_monomial_vec, real_degree_monomial_slice, to_monomial_vec, MAX_MONOMIAL_DEGREE,
};
use crate::degree::reduction::{absolute_tolerance, real_degree_and_net, try_reduce_exact};
use crate::error::{check_finite, Error, Result};
use crate::points::Points;
use crate::What;
use crate::{BezierSurface, DEFAULT_DEGREE_TOLERANCE};

/// Checks that `net` holds `(degree_u + 1)·(degree_v + 1)` points.
fn check_net(net: &Points, degree_u: usize, degree_v: usize) -> Result<()> {
    let expected = degree_u
        .checked_add(1)
        .and_then(|a| a.checked_mul(degree_v.checked_add(1)?));
    match expected {
        Some(e) if e == net.len() => Ok(()),
        _ => Err(Error::LengthMismatch {
            what: "control net points ((degree_u + 1) × (degree_v + 1))".into(),
            expected: expected.unwrap_or(usize::MAX),
            got: net.len(),
        }),
    }
}

/// The net with `u` and `v` exchanged: `rows × cols` points to `cols × rows`.
fn transpose(data: &[f64], rows: usize, cols: usize, dim: usize) -> Vec<f64> {
    let mut out = vec![0.0; data.len()];
    for i in 0..rows {
        for j in 0..cols {
            let src = (i * cols + j) * dim;
            let dst = (j * rows + i) * dim;
            out[dst..dst + dim].copy_from_slice(&data[src..src + dim]);
        }
    }
    out
}

/// Applies `op` along `v`: transpose, treat rows as points of dimension `rows·dim`, transpose
/// back. `op` returns the new number of points along `v`.
fn along_v(
    data: &[f64],
    rows: usize,
    cols: usize,
    dim: usize,
    op: impl FnOnce(&[f64], usize) -> Result<Vec<f64>>,
) -> Result<(Vec<f64>, usize)> {
    let t = transpose(data, rows, cols, dim);
    let changed = op(&t, rows * dim)?;
    let new_cols = changed.len() / (rows * dim);
    Ok((transpose(&changed, new_cols, rows, dim), new_cols))
}

/// Monomial coefficients `S = H_nᵀ U H_m` of a Bezier net (document 004 eq. 12), in the same
/// layout: `p(u, v) = Σ_i Σ_j s_ij u^i v^j`. Computed by forward differences in each direction
/// (`s_ij = C(n,i) C(m,j) Δ_u^i Δ_v^j u_00`). As for curves the power basis is ill-conditioned
/// at high degree.
///
/// ```
/// use lekalo::{bezier_net_to_monomial, Points};
/// // the bilinear net (0,0,0) (0,1,0) / (1,0,0) (1,1,1) is p = (u, v, uv)
/// let net = Points::from_3d(&[[0., 0., 0.], [0., 1., 0.], [1., 0., 0.], [1., 1., 1.]])?;
/// let s = bezier_net_to_monomial(&net, 1, 1)?;
/// assert_eq!(s.as_slice(), &[0., 0., 0., 0., 1., 0., 1., 0., 0., 0., 0., 1.]);
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::LengthMismatch`] if `net` does not hold `(degree_u+1)(degree_v+1)` points;
/// [`Error::Degree`] above [`MAX_MONOMIAL_DEGREE`]; [`Error::IllConditioned`] on overflow.
pub fn bezier_net_to_monomial(net: &Points, degree_u: usize, degree_v: usize) -> Result<Points> {
    check_net(net, degree_u, degree_v)?;
    check_monomial_degrees(degree_u, degree_v)?;
    let dim = net.dim();
    let (rows, cols) = (degree_u + 1, degree_v + 1);
    let su = to_monomial_vec(net.as_slice(), cols * dim);
    let (s, _) = along_v(&su, rows, cols, dim, |d, dd| Ok(to_monomial_vec(d, dd)))?;
    finite_net("monomial coefficients", s, dim)
}

/// The Bezier net of degrees `(degree_u, degree_v)` with monomial coefficients `coefficients`
/// (inverse of [`bezier_net_to_monomial`]): `U = H_n^{-T} S H_m^{-1}` (document 004 eq. 12).
///
/// # Errors
/// As [`bezier_net_to_monomial`].
pub fn bezier_net_from_monomial(
    coefficients: &Points,
    degree_u: usize,
    degree_v: usize,
) -> Result<Points> {
    check_net(coefficients, degree_u, degree_v)?;
    check_monomial_degrees(degree_u, degree_v)?;
    let dim = coefficients.dim();
    let (rows, cols) = (degree_u + 1, degree_v + 1);
    let uu = from_monomial_vec(coefficients.as_slice(), cols * dim);
    let (u, _) = along_v(&uu, rows, cols, dim, |d, dd| Ok(from_monomial_vec(d, dd)))?;
    finite_net("control net from monomial coefficients", u, dim)
}

fn check_monomial_degrees(degree_u: usize, degree_v: usize) -> Result<()> {
    let degree = degree_u.max(degree_v);
    if degree > MAX_MONOMIAL_DEGREE {
        return Err(Error::Degree {
            degree,
            reason: format!(
                "monomial (power-basis) conversion is limited to degree {MAX_MONOMIAL_DEGREE}"
            ),
        });
    }
    Ok(())
}

fn finite_net(what: impl Into<What>, data: Vec<f64>, dim: usize) -> Result<Points> {
    let what: What = what.into();
    if check_finite(what, &data).is_err() {
        return Err(Error::IllConditioned {
            reason: format!("{what} overflowed f64"),
        });
    }
    Ok(Points::from_raw(data, dim))
}

/// Raises the degrees of a Bezier net by `by_u` and `by_v` without changing the surface
/// (document 004 eq. 14 with `n' ≥ n`, `m' ≥ m`; the new monomial matrix is `S` padded with zero
/// rows and columns, eq. 15). Each direction uses the convex closed form
/// `C(n,i) C(r,j−i) / C(n+r,j)` of eq. 8. Returns the net of degrees
/// `(degree_u + by_u, degree_v + by_v)`.
///
/// # Errors
/// [`Error::LengthMismatch`] for a net of the wrong size; [`Error::TooLarge`] if the new net
/// is too large to allocate.
pub fn bezier_net_elevate(
    net: &Points,
    degree_u: usize,
    degree_v: usize,
    by_u: usize,
    by_v: usize,
) -> Result<Points> {
    let new_u = degree_u.saturating_add(by_u);
    let new_v = degree_v.saturating_add(by_v);
    bezier_net_change_degree(net, degree_u, degree_v, new_u, new_v, 0.0)
}

/// Real degrees `(n', m')` of a Bezier net (document 004 eq. 16): the degree along `u` is that of
/// the curve whose control points are the rows of the net, found by the stable test of
/// [`BezierCurve::real_degree_with_tolerance`](crate::BezierCurve::real_degree_with_tolerance)
/// (reduce, elevate back, compare within `tolerance ×` the largest absolute coordinate of the
/// net); likewise along `v` with the columns. In exact arithmetic, `n − n'` and `m − m'` are the
/// numbers of zero bottom rows and zero right columns of `S = H_nᵀ U H_m`.
///
/// ```
/// use lekalo::{bezier_net_elevate, bezier_net_real_degrees, Points, DEFAULT_DEGREE_TOLERANCE};
/// let net = Points::from_flat(1, (0..12).map(|i| f64::from(i * i % 7)).collect())?; // degrees (3, 2)
/// let up = bezier_net_elevate(&net, 3, 2, 1, 3)?;
/// assert_eq!(bezier_net_real_degrees(&up, 4, 5, DEFAULT_DEGREE_TOLERANCE)?, (3, 2));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::LengthMismatch`] for a net of the wrong size; [`Error::InvalidArgument`] for a
/// negative or non-finite tolerance.
pub fn bezier_net_real_degrees(
    net: &Points,
    degree_u: usize,
    degree_v: usize,
    tolerance: f64,
) -> Result<(usize, usize)> {
    check_net(net, degree_u, degree_v)?;
    let tol = absolute_tolerance(tolerance, net.as_slice())?;
    let dim = net.dim();
    let (rows, cols) = (degree_u + 1, degree_v + 1);
    let (ru, _) = real_degree_and_net(net.as_slice(), cols * dim, tol, 0);
    let t = transpose(net.as_slice(), rows, cols, dim);
    let (rv, _) = real_degree_and_net(&t, rows * dim, tol, 0);
    Ok((ru, rv))
}

/// Real degrees by the paper's literal rule (document 004 eq. 16): the numbers of zero bottom
/// rows and zero right columns of `S = H_nᵀ U H_m`, where `s_ij` counts as zero when every
/// coordinate is at most `tolerance × max|coordinate| × C(n,i) 2^i × C(m,j) 2^j` (its rounding
/// error scale). Reliable for low degrees (about 15); prefer [`bezier_net_real_degrees`].
///
/// # Errors
/// As [`bezier_net_to_monomial`]; [`Error::InvalidArgument`] for a bad tolerance.
pub fn bezier_net_real_degrees_monomial(
    net: &Points,
    degree_u: usize,
    degree_v: usize,
    tolerance: f64,
) -> Result<(usize, usize)> {
    let s = bezier_net_to_monomial(net, degree_u, degree_v)?;
    let tol = absolute_tolerance(tolerance, net.as_slice())?;
    let dim = net.dim();
    let (rows, cols) = (degree_u + 1, degree_v + 1);
    // A row (column) of S is zero when all its entries are; the v factor of the bound is at
    // most C(m, m/2)·2^m, which is used for the whole row (and vice versa).
    let row_scale = max_binomial_power(degree_v);
    let col_scale = max_binomial_power(degree_u);
    let ru = real_degree_monomial_slice(s.as_slice(), cols * dim, tol * row_scale);
    let t = transpose(s.as_slice(), rows, cols, dim);
    let rv = real_degree_monomial_slice(&t, rows * dim, tol * col_scale);
    Ok((ru, rv))
}

/// `max_j C(m, j) 2^j`.
fn max_binomial_power(m: usize) -> f64 {
    binomials(m)
        .iter()
        .zip(0_i32..)
        .map(|(c, j)| c * 2.0_f64.powi(j))
        .fold(0.0, f64::max)
}

/// Changes the degrees of a Bezier net from `(n, m)` to `(new_u, new_v)` without changing the
/// surface: document 004 eq. 14, `U' = (H_n E H_{n'}^{-1})ᵀ U (H_m E H_{m'}^{-1})`, in all eight
/// combinations of raising, keeping and lowering each degree (and the identity).
///
/// Each direction is a curve operation on the rows (along `u`) or columns (along `v`) of the
/// net, computed in the Bernstein basis as in
/// [`BezierCurve::change_degree_with_tolerance`](crate::BezierCurve::change_degree_with_tolerance):
/// raising by the convex closed form of eq. 8, lowering by the banded least-squares inverse of
/// elevation, accepted only when it reproduces the net within `tolerance ×` its largest
/// absolute coordinate (the zero rows and columns of eq. 16). The `u` direction is done first.
///
/// ```
/// use lekalo::{bezier_net_change_degree, bezier_net_elevate, Error, Points};
/// // document 004, Fig. 5: a net of degrees (4, 3) with one zero bottom row of S
/// let base = Points::from_flat(1, (0..16).map(|i| f64::from(i * 5 % 11)).collect())?; // (3, 3)
/// let net = bezier_net_elevate(&base, 3, 3, 1, 0)?; // (4, 3), real u degree 3
/// let lowered = bezier_net_change_degree(&net, 4, 3, 3, 6, 1e-10)?; // lower u, raise v
/// assert_eq!(lowered.len(), 4 * 7);
/// let e = bezier_net_change_degree(&net, 4, 3, 4, 2, 1e-10).unwrap_err();
/// assert!(matches!(e, Error::DegreeReductionRefused { real_degree: 3, direction: "v direction", .. }));
/// # Ok::<(), lekalo::Error>(())
/// ```
///
/// # Errors
/// [`Error::DegreeReductionRefused`] naming the direction and its real degree;
/// [`Error::LengthMismatch`] for a net of the wrong size; [`Error::InvalidArgument`] for a bad
/// tolerance; [`Error::TooLarge`] if the new net is too large to allocate.
pub fn bezier_net_change_degree(
    net: &Points,
    degree_u: usize,
    degree_v: usize,
    new_u: usize,
    new_v: usize,
    tolerance: f64,
) -> Result<Points> {
    check_net(net, degree_u, degree_v)?;
    let tol = absolute_tolerance(tolerance, net.as_slice())?;
    let dim = net.dim();
    let points = new_u
        .checked_add(1)
        .and_then(|a| a.checked_mul(new_v.checked_add(1)?))
        .unwrap_or(usize::MAX);
    check_size("changed control net", points, dim)?;
    let cols = degree_v + 1;
    let after_u = change_curve(net.as_slice(), cols * dim, new_u, tol, "u direction")?;
    let (data, _) = along_v(&after_u, new_u + 1, cols, dim, |d, dd| {
        change_curve(d, dd, new_v, tol, "v direction")
    })?;
    finite_net("changed control net", data, dim)
}

/// Degree change of the curve with flat points `src` of dimension `dim` to `target`.
fn change_curve(
    src: &[f64],
    dim: usize,
    target: usize,
    tol: f64,
    direction: &'static str,
) -> Result<Vec<f64>> {
    let n = src.len() / dim - 1;
    if target >= n {
        return Ok(elevate(src, dim, target - n));
    }
    if let Some(q) = try_reduce_exact(src, dim, target, tol) {
        return Ok(q);
    }
    let (real, _) = real_degree_and_net(src, dim, tol, target + 1);
    Err(Error::DegreeReductionRefused {
        requested: target,
        real_degree: real,
        direction,
    })
}

impl BezierSurface {
    /// Monomial coefficients `S = H_nᵀ U H_m` in the net layout (document 004 eq. 12); see
    /// [`bezier_net_to_monomial`].
    ///
    /// # Errors
    /// As [`bezier_net_to_monomial`].
    pub fn to_monomial(&self) -> Result<Points> {
        bezier_net_to_monomial(self.control_points(), self.degree_u(), self.degree_v())
    }

    /// Raises the degrees by `by_u` and `by_v` without changing the surface (document 004 eq. 14
    /// and 15); see [`bezier_net_elevate`].
    ///
    /// ```
    /// use lekalo::{BezierSurface, Points};
    /// let net = Points::from_3d(&[[0., 0., 0.], [0., 1., 0.], [1., 0., 0.], [1., 1., 1.]])?;
    /// let s = BezierSurface::new(net, (2, 2))?;
    /// let e = s.elevate_degree(2, 1)?;
    /// assert_eq!((e.degree_u(), e.degree_v()), (3, 2));
    /// assert_eq!(e.eval(0.5, 0.25)?, s.eval(0.5, 0.25)?);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`bezier_net_elevate`].
    pub fn elevate_degree(&self, by_u: usize, by_v: usize) -> Result<BezierSurface> {
        let (n, m) = (self.degree_u(), self.degree_v());
        let net = bezier_net_elevate(self.control_points(), n, m, by_u, by_v)?;
        BezierSurface::new(net, (n + by_u + 1, m + by_v + 1))
    }

    /// Real degrees `(n', m')` with the default tolerance [`DEFAULT_DEGREE_TOLERANCE`]; see
    /// [`bezier_net_real_degrees`].
    #[must_use]
    pub fn real_degrees(&self) -> (usize, usize) {
        bezier_net_real_degrees(
            self.control_points(),
            self.degree_u(),
            self.degree_v(),
            DEFAULT_DEGREE_TOLERANCE,
        )
        .unwrap_or((self.degree_u(), self.degree_v()))
    }

    /// Real degrees `(n', m')` with a relative tolerance; see [`bezier_net_real_degrees`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a negative or non-finite tolerance.
    pub fn real_degrees_with_tolerance(&self, tolerance: f64) -> Result<(usize, usize)> {
        bezier_net_real_degrees(
            self.control_points(),
            self.degree_u(),
            self.degree_v(),
            tolerance,
        )
    }

    /// Changes the degrees to `(new_u, new_v)` without changing the surface (document 004 eq. 14,
    /// all raise/keep/lower combinations), with the default tolerance; see
    /// [`bezier_net_change_degree`].
    ///
    /// # Errors
    /// As [`bezier_net_change_degree`].
    pub fn change_degree(&self, new_u: usize, new_v: usize) -> Result<BezierSurface> {
        self.change_degree_with_tolerance(new_u, new_v, DEFAULT_DEGREE_TOLERANCE)
    }

    /// Changes the degrees to `(new_u, new_v)` without changing the surface, judging degree
    /// defects with `tolerance` relative to the largest absolute coordinate of the net; see
    /// [`bezier_net_change_degree`].
    ///
    /// # Errors
    /// As [`bezier_net_change_degree`].
    pub fn change_degree_with_tolerance(
        &self,
        new_u: usize,
        new_v: usize,
        tolerance: f64,
    ) -> Result<BezierSurface> {
        let net = bezier_net_change_degree(
            self.control_points(),
            self.degree_u(),
            self.degree_v(),
            new_u,
            new_v,
            tolerance,
        )?;
        BezierSurface::new(net, (new_u + 1, new_v + 1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BezierCurve;

    fn rough(count: usize, seed: f64) -> Vec<f64> {
        (0..count)
            .map(|i| {
                let x = ((i as f64) * 12.9898 + seed * 78.233).sin() * 43758.5453;
                8.0 * (x - x.floor()) - 4.0
            })
            .collect()
    }

    /// p(u, v) through two curve evaluations (rows as one big point, then the v curve).
    fn eval(net: &Points, n: usize, m: usize, u: f64, v: f64) -> Vec<f64> {
        let dim = net.dim();
        let rows =
            BezierCurve::new(Points::from_flat((m + 1) * dim, net.as_slice().to_vec()).unwrap())
                .unwrap();
        debug_assert!(rows.degree() == n, "net rows");
        let row = rows.eval(u).unwrap();
        BezierCurve::new(Points::from_flat(dim, row).unwrap())
            .unwrap()
            .eval(v)
            .unwrap()
    }

    fn surface_dev(a: &Points, da: (usize, usize), b: &Points, db: (usize, usize)) -> f64 {
        let mut m = 0.0_f64;
        for k in 0..=12 {
            for l in 0..=12 {
                let (u, v) = (f64::from(k) / 12.0, f64::from(l) / 12.0);
                let pa = eval(a, da.0, da.1, u, v);
                let pb = eval(b, db.0, db.1, u, v);
                for (x, y) in pa.iter().zip(&pb) {
                    m = m.max((x - y).abs());
                }
            }
        }
        m
    }

    #[test]
    fn all_nine_combinations() {
        // a (4, 3) net with real degrees (3, 2), as in the paper's Fig. 5
        let base = Points::from_flat(3, rough(4 * 3 * 3, 0.7)).unwrap();
        let net = bezier_net_elevate(&base, 3, 2, 1, 1).unwrap();
        let scale = net.max_abs();
        assert_eq!(
            bezier_net_real_degrees(&net, 4, 3, 1e-10).unwrap(),
            (3, 2),
            "real degrees"
        );
        assert_eq!(
            bezier_net_real_degrees_monomial(&net, 4, 3, 1e-10).unwrap(),
            (3, 2),
            "paper's zero rows and columns"
        );
        for nu in [3, 4, 6] {
            for nv in [2, 3, 5] {
                let c = bezier_net_change_degree(&net, 4, 3, nu, nv, 1e-10).unwrap();
                assert_eq!(c.len(), (nu + 1) * (nv + 1), "size");
                let d = surface_dev(&net, (4, 3), &c, (nu, nv));
                assert!(d <= 1e-13 * scale, "({nu}, {nv}): {d:e}");
            }
        }
        for (nu, nv, dir, real) in [(2, 3, "u direction", 3), (4, 1, "v direction", 2)] {
            let e = bezier_net_change_degree(&net, 4, 3, nu, nv, 1e-10).unwrap_err();
            assert_eq!(
                e,
                Error::DegreeReductionRefused {
                    requested: if dir == "u direction" { nu } else { nv },
                    real_degree: real,
                    direction: dir
                },
                "refused"
            );
        }
    }

    #[test]
    fn monomial_round_trip_and_bilinear() {
        let net = Points::from_flat(2, rough(4 * 5 * 2, 0.1)).unwrap();
        let s = bezier_net_to_monomial(&net, 3, 4).unwrap();
        let back = bezier_net_from_monomial(&s, 3, 4).unwrap();
        for (a, b) in back.as_slice().iter().zip(net.as_slice()) {
            assert!((a - b).abs() < 1e-12, "round trip");
        }
        // p(u, v) = Σ s_ij u^i v^j at one point
        let (u, v) = (0.3_f64, 0.8_f64);
        let p = eval(&net, 3, 4, u, v);
        for k in 0..2 {
            let mut sum = 0.0;
            for i in 0..=3 {
                for j in 0..=4 {
                    sum += s.as_slice()[(i * 5 + j) * 2 + k]
                        * u.powi(i32::try_from(i).unwrap())
                        * v.powi(i32::try_from(j).unwrap());
                }
            }
            assert!((sum - p[k]).abs() < 1e-12, "monomial value");
        }
    }

    #[test]
    fn bezier_surface_methods() {
        let base = BezierSurface::new(Points::from_flat(2, rough(3 * 4 * 2, 0.3)).unwrap(), (3, 4))
            .unwrap();
        let up = base.elevate_degree(2, 1).unwrap();
        assert_eq!((up.degree_u(), up.degree_v()), (4, 4));
        assert_eq!(up.real_degrees(), (2, 3));
        assert_eq!(up.real_degrees_with_tolerance(1e-10).unwrap(), (2, 3));
        let c = up.change_degree(2, 5).unwrap();
        let scale = base.control_points().max_abs();
        for (u, v) in [(0.0, 0.0), (0.3, 0.9), (0.5, 0.5), (1.0, 0.2)] {
            let (a, b) = (base.eval(u, v).unwrap(), c.eval(u, v).unwrap());
            for (x, y) in a.iter().zip(&b) {
                assert!((x - y).abs() <= 1e-13 * scale, "({u}, {v})");
            }
        }
        assert_eq!(
            up.change_degree(1, 4).unwrap_err(),
            Error::DegreeReductionRefused {
                requested: 1,
                real_degree: 2,
                direction: "u direction"
            }
        );
        let s = base.to_monomial().unwrap();
        assert_eq!(
            s,
            bezier_net_to_monomial(base.control_points(), 2, 3).unwrap()
        );
        assert!(matches!(
            base.change_degree_with_tolerance(2, 3, f64::INFINITY),
            Err(Error::InvalidArgument { .. })
        ));
    }

    #[test]
    fn errors() {
        let net = Points::from_flat(1, rough(12, 0.2)).unwrap();
        assert!(matches!(
            bezier_net_change_degree(&net, 3, 3, 3, 3, 0.0),
            Err(Error::LengthMismatch {
                expected: 16,
                got: 12,
                ..
            })
        ));
        assert!(matches!(
            bezier_net_real_degrees(&net, 3, 2, -1.0),
            Err(Error::InvalidArgument { .. })
        ));
        assert!(matches!(
            bezier_net_elevate(&net, 3, 2, usize::MAX, 0),
            Err(Error::TooLarge { .. })
        ));
        assert!(matches!(
            bezier_net_to_monomial(&Points::from_flat(1, vec![0.0; 1002]).unwrap(), 1001, 0),
            Err(Error::Degree { .. })
        ));
        assert!(matches!(
            bezier_net_from_monomial(&net, usize::MAX, 0),
            Err(Error::LengthMismatch { .. })
        ));
        let big = Points::from_flat(1, vec![1.5e308, -1.5e308, 1.5e308, 0.0]).unwrap();
        assert!(matches!(
            bezier_net_to_monomial(&big, 3, 0),
            Err(Error::IllConditioned { .. })
        ));
    }
}
