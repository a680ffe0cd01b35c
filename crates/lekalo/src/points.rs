//! Flat, point-major storage of points of any dimension.
//!
//! A set of `n` points in `dim` dimensions is one `Vec<f64>` laid out as
//! `x0 y0 z0 x1 y1 z1 …` (point-major), plus the runtime dimension. This is the layout of
//! tinyspline and of SciPy's `(n, dim)` coefficient arrays: contiguous, cheap for millions of
//! points, and directly mappable to files. A surface control net of `nu × nv` points stores point
//! `(i, j)` at `data[(i * nv + j) * dim ..]`.
//!
//! Typed constructors ([`Points::from_2d`], [`Points::from_3d`]) and accessors
//! ([`Points::point2`], [`Points::point3`]) are conveniences at the edges.

use crate::{Arg, What};
use serde::{Deserialize, Serialize};

use crate::error::{check_finite, Error, Result, MAX_SCALARS};

/// Owned points of dimension `dim`, stored flat and point-major.
///
/// Invariants (checked by every constructor): `dim ≥ 1`, `data.len()` a multiple of `dim`,
/// every coordinate finite. An empty set is allowed here; constructors of curves check counts.
///
/// ```
/// use lekalo::Points;
/// let p = Points::from_2d(&[[0.0, 1.0], [2.0, 3.0]]).unwrap();
/// assert_eq!(p.len(), 2);
/// assert_eq!(p.dim(), 2);
/// assert_eq!(p.point(1), &[2.0, 3.0]);
/// assert_eq!(p.as_slice(), &[0.0, 1.0, 2.0, 3.0]);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "PointsRepr", into = "PointsRepr")]
pub struct Points {
    data: Vec<f64>,
    dim: usize,
}

/// Serialised form of [`Points`]: `{"dim": 2, "data": [x0, y0, x1, y1]}`.
#[derive(Serialize, Deserialize)]
struct PointsRepr {
    dim: usize,
    data: Vec<f64>,
}

impl TryFrom<PointsRepr> for Points {
    type Error = Error;
    fn try_from(r: PointsRepr) -> Result<Self> {
        Points::from_flat(r.dim, r.data)
    }
}

impl From<Points> for PointsRepr {
    fn from(p: Points) -> Self {
        PointsRepr {
            dim: p.dim,
            data: p.data,
        }
    }
}

impl Points {
    /// Points of dimension `dim` from flat point-major data `x0 y0 … x1 y1 …` (the storage
    /// order of [`Points`]). For fixed small dimensions [`Points::from_2d`] and
    /// [`Points::from_3d`] take arrays; [`Points::from_rows`] takes rows of any equal length.
    ///
    /// ```
    /// use lekalo::Points;
    /// let p = Points::from_flat(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 2.0])?;
    /// assert_eq!((p.len(), p.dim()), (3, 2));
    /// assert_eq!(p.point(1), &[1.0, 2.0]);
    /// # Ok::<(), lekalo::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::Dimension`] if `dim == 0` or `data.len()` is not a multiple of `dim`;
    /// [`Error::NonFinite`] for NaN or infinite coordinates; [`Error::TooLarge`] past
    /// [`MAX_SCALARS`](crate::MAX_SCALARS).
    pub fn from_flat(dim: usize, data: Vec<f64>) -> Result<Self> {
        if dim == 0 {
            return Err(Error::Dimension {
                what: "points".into(),
                expected: 1,
                got: 0,
            });
        }
        if data.len() > MAX_SCALARS {
            return Err(Error::TooLarge {
                what: "point data".into(),
                size: data.len(),
                max: MAX_SCALARS,
            });
        }
        if data.len() % dim != 0 {
            return Err(Error::Dimension {
                what: "point data (length is not a multiple of the dimension)".into(),
                expected: dim,
                got: data.len(),
            });
        }
        check_finite("point coordinates", &data)?;
        Ok(Points { data, dim })
    }

    /// Points from flat point-major data: [`Points::from_flat`] with the arguments the other
    /// way round.
    ///
    /// # Errors
    /// As [`Points::from_flat`].
    #[deprecated(note = "use Points::from_flat(dim, data)")]
    pub fn new(data: Vec<f64>, dim: usize) -> Result<Self> {
        Points::from_flat(dim, data)
    }

    /// Points from rows of any equal length.
    ///
    /// # Errors
    /// [`Error::TooFew`] for no rows; [`Error::Dimension`] if rows differ in length or are
    /// empty; [`Error::NonFinite`].
    pub fn from_rows<R: AsRef<[f64]>>(rows: &[R]) -> Result<Self> {
        let first = rows.first().ok_or(Error::TooFew {
            what: "points".into(),
            min: 1,
            got: 0,
        })?;
        let dim = first.as_ref().len();
        let mut data = Vec::with_capacity(dim * rows.len());
        for row in rows {
            let row = row.as_ref();
            if row.len() != dim {
                return Err(Error::Dimension {
                    what: "point rows (all rows must have the same length)".into(),
                    expected: dim,
                    got: row.len(),
                });
            }
            data.extend_from_slice(row);
        }
        Points::from_flat(dim, data)
    }

    /// Planar points.
    ///
    /// # Errors
    /// [`Error::NonFinite`].
    pub fn from_2d(points: &[[f64; 2]]) -> Result<Self> {
        Points::from_flat(2, points.iter().flatten().copied().collect())
    }

    /// Spatial points.
    ///
    /// # Errors
    /// [`Error::NonFinite`].
    pub fn from_3d(points: &[[f64; 3]]) -> Result<Self> {
        Points::from_flat(3, points.iter().flatten().copied().collect())
    }

    /// Trusted constructor for internal results whose invariants hold by construction.
    pub(crate) fn from_raw(data: Vec<f64>, dim: usize) -> Self {
        debug_assert!(dim > 0 && data.len() % dim == 0, "bad raw point data");
        Points { data, dim }
    }

    /// `n` points of dimension `dim`, all zero (internal buffers).
    pub(crate) fn zeros(n: usize, dim: usize) -> Self {
        Points::from_raw(vec![0.0; n * dim], dim)
    }

    /// Number of points.
    #[must_use]
    pub fn len(&self) -> usize {
        self.data.len() / self.dim
    }

    /// True if there are no points.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// Dimension of every point.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Coordinates of point `i`.
    ///
    /// # Panics
    /// If `i >= self.len()` (an index error in the caller's code, as with slices).
    #[must_use]
    pub fn point(&self, i: usize) -> &[f64] {
        &self.data[i * self.dim..(i + 1) * self.dim]
    }

    /// Mutable coordinates of point `i`.
    ///
    /// Writing a non-finite value breaks the finiteness invariant; this accessor is crate-private.
    pub(crate) fn point_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.data[i * self.dim..(i + 1) * self.dim]
    }

    /// Point `i` as `[x, y]`, or `None` if the dimension is not 2 or `i` is out of range.
    #[must_use]
    pub fn point2(&self, i: usize) -> Option<[f64; 2]> {
        (self.dim == 2 && i < self.len()).then(|| [self.data[2 * i], self.data[2 * i + 1]])
    }

    /// Point `i` as `[x, y, z]`, or `None` if the dimension is not 3 or `i` is out of range.
    #[must_use]
    pub fn point3(&self, i: usize) -> Option<[f64; 3]> {
        (self.dim == 3 && i < self.len()).then(|| {
            let k = 3 * i;
            [self.data[k], self.data[k + 1], self.data[k + 2]]
        })
    }

    /// Iterator over the points as slices.
    pub fn iter(&self) -> std::slice::ChunksExact<'_, f64> {
        self.data.chunks_exact(self.dim)
    }

    /// The flat coordinate array.
    #[must_use]
    pub fn as_slice(&self) -> &[f64] {
        &self.data
    }

    /// Borrowed view.
    #[must_use]
    pub fn as_view(&self) -> PointsRef<'_> {
        PointsRef {
            data: &self.data,
            dim: self.dim,
        }
    }

    /// The flat coordinate vector.
    #[must_use]
    pub fn into_vec(self) -> Vec<f64> {
        self.data
    }

    /// Axis-aligned bounding box as `(min, max)` corner coordinates; `None` when empty.
    #[must_use]
    pub fn bounding_box(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        let mut it = self.iter();
        let first = it.next()?;
        let (mut lo, mut hi) = (first.to_vec(), first.to_vec());
        for p in it {
            for k in 0..self.dim {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        Some((lo, hi))
    }

    /// Largest absolute coordinate (0 when empty): the data's scale, used for relative
    /// tolerances.
    #[must_use]
    pub fn max_abs(&self) -> f64 {
        self.data.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
    }

    /// Length of the bounding-box diagonal (0 when empty or a single point): the data's
    /// extent, used for tolerances that must not depend on an offset of the data.
    #[must_use]
    pub fn extent(&self) -> f64 {
        match self.bounding_box() {
            Some((lo, hi)) => lo
                .iter()
                .zip(&hi)
                .map(|(a, b)| (b - a) * (b - a))
                .sum::<f64>()
                .sqrt(),
            None => 0.0,
        }
    }
}

/// Homogeneous coordinates `(w·P, w)` of points with weights: the representation in which a
/// NURBS is a B-spline one dimension up (P&T §4.2).
///
/// # Errors
/// [`Error::LengthMismatch`] if there is not one weight per point; [`Error::NonFinite`] for a
/// non-finite weight or an overflowing `w·P`; [`Error::NonPositiveWeight`] for a weight `≤ 0`.
pub(crate) fn homogenize(points: &Points, weights: &[f64]) -> Result<Points> {
    if weights.len() != points.len() {
        return Err(Error::LengthMismatch {
            what: What::of(Arg::Weights, "weights (one per control point)"),
            expected: points.len(),
            got: weights.len(),
        });
    }
    check_finite(Arg::Weights, weights)?;
    if let Some(index) = weights.iter().position(|&w| w <= 0.0) {
        return Err(Error::NonPositiveWeight {
            index,
            weight: weights[index],
        });
    }
    let dim = points.dim();
    let mut h = Vec::with_capacity(points.len() * (dim + 1));
    for (p, &w) in points.iter().zip(weights) {
        h.extend(p.iter().map(|x| x * w));
        h.push(w);
    }
    Points::from_flat(dim + 1, h)
}

/// Homogeneous coordinates with unit weights, `(P, 1)`.
pub(crate) fn with_unit_weights(points: &Points) -> Points {
    let dim = points.dim();
    let mut h = Vec::with_capacity(points.len() * (dim + 1));
    for p in points.iter() {
        h.extend_from_slice(p);
        h.push(1.0);
    }
    Points::from_raw(h, dim + 1)
}

/// Checks that homogeneous points have dimension ≥ 2 and positive weights (last coordinate).
///
/// # Errors
/// [`Error::Dimension`], [`Error::NonPositiveWeight`].
pub(crate) fn check_homogeneous(h: &Points) -> Result<()> {
    let hd = h.dim();
    if hd < 2 {
        return Err(Error::Dimension {
            what: "homogeneous control points (dim + 1 for the weight)".into(),
            expected: 2,
            got: hd,
        });
    }
    for (index, p) in h.iter().enumerate() {
        let weight = p[hd - 1];
        if weight <= 0.0 {
            return Err(Error::NonPositiveWeight { index, weight });
        }
    }
    Ok(())
}

/// The weights (last coordinates) of homogeneous points.
pub(crate) fn weights_of(h: &Points) -> Vec<f64> {
    let hd = h.dim();
    h.iter().map(|p| p[hd - 1]).collect()
}

/// Euclidean points `(w·P) / w` of homogeneous points.
pub(crate) fn dehomogenize(h: &Points) -> Points {
    let hd = h.dim();
    let mut out = Vec::with_capacity(h.len() * (hd - 1));
    for p in h.iter() {
        let w = p[hd - 1];
        out.extend(p[..hd - 1].iter().map(|x| x / w));
    }
    Points::from_raw(out, hd - 1)
}

/// Borrowed flat point-major points (see [`Points`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointsRef<'a> {
    data: &'a [f64],
    dim: usize,
}

impl<'a> PointsRef<'a> {
    /// A view of flat point-major data of dimension `dim`, validated like
    /// [`Points::from_flat`] (no copy).
    ///
    /// # Errors
    /// As [`Points::from_flat`].
    pub fn from_flat(dim: usize, data: &'a [f64]) -> Result<Self> {
        if dim == 0 || data.len() % dim != 0 {
            return Err(Error::Dimension {
                what: "point data (length is not a multiple of the dimension)".into(),
                expected: dim.max(1),
                got: data.len(),
            });
        }
        check_finite("point coordinates", data)?;
        Ok(PointsRef { data, dim })
    }

    /// A view of values of dimension 1 whose finiteness the caller checks where it reads them
    /// (naming the argument they were given as), so that they are not read twice.
    pub(crate) fn values(data: &'a [f64]) -> Self {
        PointsRef { data, dim: 1 }
    }

    /// A view of flat point-major data: [`PointsRef::from_flat`] with the arguments the other
    /// way round.
    ///
    /// # Errors
    /// As [`PointsRef::from_flat`].
    #[deprecated(note = "use PointsRef::from_flat(dim, data)")]
    pub fn new(data: &'a [f64], dim: usize) -> Result<Self> {
        PointsRef::from_flat(dim, data)
    }

    /// Number of points.
    #[must_use]
    pub fn len(&self) -> usize {
        self.data.len() / self.dim
    }

    /// True if there are no points.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// Dimension of every point.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Coordinates of point `i` (panics on an out-of-range index, as slices do).
    #[must_use]
    pub fn point(&self, i: usize) -> &'a [f64] {
        &self.data[i * self.dim..(i + 1) * self.dim]
    }

    /// Iterator over the points as slices.
    pub fn iter(&self) -> std::slice::ChunksExact<'a, f64> {
        self.data.chunks_exact(self.dim)
    }

    /// The flat coordinate array.
    #[must_use]
    pub fn as_slice(&self) -> &'a [f64] {
        self.data
    }

    /// Owned copy.
    #[must_use]
    pub fn to_owned(&self) -> Points {
        Points::from_raw(self.data.to_vec(), self.dim)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The constructors kept for code written against the old argument order build the same
    /// points and refuse the same data.
    #[test]
    #[allow(deprecated)]
    fn deprecated_constructors_match_from_flat() {
        let data = vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        assert_eq!(
            Points::new(data.clone(), 3).unwrap(),
            Points::from_flat(3, data.clone()).unwrap(),
            "Points::new"
        );
        assert_eq!(
            PointsRef::new(&data, 2).unwrap(),
            PointsRef::from_flat(2, &data).unwrap(),
            "PointsRef::new"
        );
        assert!(
            matches!(Points::new(data.clone(), 4), Err(Error::Dimension { .. })),
            "Points::new refuses a length that is not a multiple of the dimension"
        );
        assert!(
            matches!(PointsRef::new(&data, 0), Err(Error::Dimension { .. })),
            "PointsRef::new refuses dimension 0"
        );
    }

    #[test]
    fn rejects_bad_data() {
        assert!(matches!(
            Points::from_flat(0, vec![1.0]),
            Err(Error::Dimension { .. })
        ));
        assert!(matches!(
            Points::from_flat(2, vec![1.0, 2.0, 3.0]),
            Err(Error::Dimension { .. })
        ));
        assert!(matches!(
            Points::from_flat(2, vec![1.0, f64::NEG_INFINITY]),
            Err(Error::NonFinite { index: 1, .. })
        ));
        assert!(matches!(
            Points::from_rows(&[vec![1.0, 2.0], vec![1.0]]),
            Err(Error::Dimension { .. })
        ));
        let none: [Vec<f64>; 0] = [];
        assert!(matches!(
            Points::from_rows(&none),
            Err(Error::TooFew { .. })
        ));
    }

    #[test]
    fn typed_access_and_box() {
        let p = Points::from_3d(&[[1.0, -2.0, 3.0], [0.0, 5.0, -1.0]]).unwrap();
        assert_eq!(p.point3(1), Some([0.0, 5.0, -1.0]));
        assert_eq!(p.point2(0), None);
        assert_eq!(p.point3(2), None);
        let (lo, hi) = p.bounding_box().unwrap();
        assert_eq!(lo, vec![0.0, -2.0, -1.0]);
        assert_eq!(hi, vec![1.0, 5.0, 3.0]);
        assert_eq!(p.max_abs(), 5.0);
        assert!((p.extent() - (1.0f64 + 49.0 + 16.0).sqrt()).abs() < 1e-15);
    }

    #[test]
    fn serde_round_trip_validates() {
        let p = Points::from_2d(&[[1.0, 2.0]]).unwrap();
        let s = serde_json::to_string(&p).unwrap();
        assert_eq!(s, r#"{"dim":2,"data":[1.0,2.0]}"#);
        let q: Points = serde_json::from_str(&s).unwrap();
        assert_eq!(p, q);
        assert!(serde_json::from_str::<Points>(r#"{"dim":2,"data":[1.0]}"#).is_err());
    }
}
