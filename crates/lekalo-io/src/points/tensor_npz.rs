//! NumPy `.npz` archives of tensor-product splines in `N` parameters (`bspline_tensor`,
//! `nurbs_tensor`): one `.npy` member per named array, laid out so that SciPy builds the same
//! B-spline with
//!
//! ```python
//! z = np.load('t.npz')
//! N = len(z['degrees'])
//! s = NdBSpline(tuple(z[f'knots_{d}'] for d in range(N)), z['control_points'], tuple(z['degrees']))
//! ```
//!
//! | member | dtype | shape | meaning |
//! |---|---|---|---|
//! | `degrees.npy` | int64 (float64 with integer values is read too) | `(N,)` | degree `p_d` of each parameter |
//! | `knots_0.npy` … `knots_{N-1}.npy` | float64 | `(n_d + p_d + 1,)` | knot vector of parameter `d` |
//! | `control_points.npy` | float64 | `(n_1, …, n_N)` for scalar values, `(n_1, …, n_N, dim)` otherwise | Euclidean control points, C order (first parameter slowest, as the JSON `control` list) |
//! | `weights.npy` (NURBS only) | float64 | `(n_1, …, n_N)` | positive weights |
//!
//! The curve archive ([`crate::read_npz_curve`]) has `degree` and `knots`; a tensor archive has
//! `degrees` and `knots_0` …, so [`read_npz`] tells them apart by the `degrees` member. Members
//! are stored uncompressed, as `numpy.savez` writes them. Reading checks every member's shape
//! against `degrees` and the knots before the control points are decoded, and never holds more
//! numbers than the archive's bytes. A B-spline reads back bit for bit; a NURBS is held as its
//! homogeneous points `w·P`, so it reads back bit for bit whenever `(w·P) / w · w = w·P` holds
//! (always for weights that are powers of two), as for its JSON.

use std::io::{Cursor, Seek, Write};

use lekalo::{Points, Tensor, TensorBSpline, TensorNurbs};
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

use crate::error::{IoError, IoResult, Location};
use crate::npy::{npy_header, read_array, read_array_shape, write_le};
use crate::npz::{open_archive, read_member, read_npz_curve};
use crate::shape::Shape;

/// Largest degree read from an archive (a larger one is surely a wrong member).
const MAX_DEGREE: f64 = 1.0e6;

/// What a tensor archive must hold, for messages about a missing member.
const NEEDS: &str = "a spline in N parameters needs degrees (N,), knots_0 … knots_{N-1} and \
                     control_points (and weights for NURBS)";

/// The tensor spline `t` as an `.npz` archive (see the module's table of members), made in
/// memory; [`write_npz_tensor`] writes it to a file without holding it.
///
/// ```
/// use lekalo_io::{read_npz_tensor, read_tensor, tensor_to_npz};
/// let t = read_tensor(r#"{"lekalo": 1, "type": "bspline_tensor",
///   "degrees": [1, 1, 1], "knots": [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]],
///   "shape": [2, 2, 2], "control": [[0], [0], [0], [0], [0], [0], [0], [1]]}"#, "t.json")?;
/// let bytes = tensor_to_npz(&t)?;
/// assert_eq!(read_npz_tensor(&bytes, "t.npz")?, t);
/// # Ok::<(), lekalo_io::IoError>(())
/// ```
///
/// # Errors
/// [`IoError::Unsupported`] if the archive cannot be built (an internal failure).
pub fn tensor_to_npz(t: &Tensor) -> IoResult<Vec<u8>> {
    let mut out = Cursor::new(Vec::new());
    write_npz_tensor(t, &mut out).map_err(|e| IoError::Unsupported {
        what: format!("cannot build the .npz archive: {e}"),
    })?;
    Ok(out.into_inner())
}

/// Writes the tensor spline `t` as an `.npz` archive to `w` (the members of
/// [`tensor_to_npz`], byte for byte), each array converted to bytes a chunk at a time straight
/// into its member.
///
/// # Errors
/// The writer's; the archive's (as [`std::io::ErrorKind::Other`]), e.g. a degree too large
/// for an int64.
pub fn write_npz_tensor<W: Write + Seek>(t: &Tensor, w: W) -> std::io::Result<()> {
    let other = |e: &dyn std::fmt::Display| std::io::Error::other(e.to_string());
    let degrees = t
        .degrees()
        .iter()
        .map(|&p| i64::try_from(p).map_err(|_| other(&format!("degree {p} does not fit an int64"))))
        .collect::<std::io::Result<Vec<i64>>>()?;
    let control = t.control_points();
    let mut net = t.shape().to_vec();
    if control.dim() != 1 {
        net.push(control.dim());
    }
    let weights = t.weights();
    let mut z = ZipWriter::new(w);
    let opts = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .large_file(false);
    z.start_file("degrees.npy", opts).map_err(|e| other(&e))?;
    z.write_all(&npy_header("<i8", &[degrees.len()]).map_err(|e| other(&e))?)?;
    for p in &degrees {
        z.write_all(&p.to_le_bytes())?;
    }
    let mut members: Vec<(String, Vec<usize>, &[f64])> = t
        .knots()
        .iter()
        .enumerate()
        .map(|(d, k)| (format!("knots_{d}.npy"), vec![k.len()], k.as_slice()))
        .collect();
    members.push(("control_points.npy".into(), net, control.as_slice()));
    if let Some(wt) = &weights {
        members.push(("weights.npy".into(), t.shape().to_vec(), wt));
    }
    for (name, shape, values) in members {
        z.start_file(name, opts).map_err(|e| other(&e))?;
        z.write_all(&npy_header("<f8", &shape).map_err(|e| other(&e))?)?;
        write_le(&mut z, values)?;
    }
    z.finish().map_err(|e| other(&e))?;
    Ok(())
}

/// Reads an `.npz` archive as a curve ([`crate::read_npz_curve`]) or, if it has a `degrees`
/// member, a tensor spline in `N` parameters ([`read_npz_tensor`]); `source` names the input
/// in messages.
///
/// # Errors
/// Those of [`crate::read_npz_curve`] or [`read_npz_tensor`].
pub fn read_npz(bytes: &[u8], source: &str) -> IoResult<Shape> {
    let z = open_archive(bytes, source)?;
    if z.index_for_name("degrees.npy").is_some() {
        read_npz_tensor(bytes, source).map(Shape::Tensor)
    } else {
        read_npz_curve(bytes, source).map(Shape::Curve)
    }
}

/// Reads a tensor spline in `N` parameters from an `.npz` archive (see the module's table of
/// members); `source` names the input in messages. Every member's shape is checked against
/// `degrees` and the knots before the control points and weights are decoded.
///
/// # Errors
/// [`IoError::Syntax`] naming the file and the member for an archive that is not a zip, a
/// compressed or missing member, a member that is not a valid `.npy` array of the table's dtype,
/// or a shape that disagrees with the others; [`IoError::Invalid`] if the library rejects the
/// spline (knots, weights).
pub fn read_npz_tensor(bytes: &[u8], source: &str) -> IoResult<Tensor> {
    let mut z = open_archive(bytes, source)?;
    let mut member = |name: &str, required: bool| {
        read_member(&mut z, bytes.len(), source, name, required, NEEDS)
    };
    let shape_err =
        |label: &str, what: String| IoError::syntax(Location::new(label).at_field("shape"), what);
    let (label, b) = member("degrees", true)?.unwrap_or_default();
    let (shape, v) = read_array(&b, &label, true)?;
    if shape.len() != 1 || v.is_empty() {
        return Err(shape_err(
            &label,
            format!(
                "degrees must be a 1-D array (N,) with N ≥ 1, one degree per parameter; found shape {shape:?}"
            ),
        ));
    }
    let mut degrees = Vec::with_capacity(v.len());
    for &p in &v {
        if p < 0.0 || p.fract() != 0.0 || p > MAX_DEGREE {
            return Err(IoError::syntax(
                Location::new(&label).at_field("[]"),
                format!("{p} is not a degree: it must be a whole number from 0 to {MAX_DEGREE}"),
            ));
        }
        // a whole number in [0, 1e6]: exact in usize
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        degrees.push(p as usize);
    }
    let mut knots = Vec::with_capacity(degrees.len());
    let mut net = Vec::with_capacity(degrees.len());
    for (d, &p) in degrees.iter().enumerate() {
        let (label, b) = member(&format!("knots_{d}"), true)?.unwrap_or_default();
        let (shape, k) = read_array(&b, &label, false)?;
        if shape.len() != 1 || k.len() < p + 2 {
            return Err(shape_err(
                &label,
                format!(
                    "knots_{d} must be a 1-D array of at least degrees[{d}] + 2 = {} knots; found shape {shape:?}",
                    p + 2
                ),
            ));
        }
        net.push(k.len() - p - 1);
        knots.push(k);
    }
    let (label, b) = member("control_points", true)?.unwrap_or_default();
    let shape = read_array_shape(&b, &label, false)?;
    let dim = if shape.len() == net.len() && shape == net {
        1
    } else if shape.len() == net.len() + 1 && shape[..net.len()] == net[..] && shape[net.len()] > 0
    {
        shape[net.len()]
    } else {
        return Err(shape_err(
            &label,
            format!(
                "control_points has shape {shape:?}; the degrees and knots give a net {net:?}, so it must be {net:?} (scalar values) or {net:?} + (dim,)"
            ),
        ));
    };
    let weights = match member("weights", false)? {
        None => None,
        Some((label, b)) => {
            let shape = read_array_shape(&b, &label, false)?;
            if shape != net {
                return Err(shape_err(
                    &label,
                    format!("weights has shape {shape:?}; it must be the net {net:?}, one weight per control point"),
                ));
            }
            Some(read_array(&b, &label, false)?.1)
        }
    };
    let (_, flat) = read_array(&b, &label, false)?;
    let at = Location::new(source);
    let invalid = |field: &str, error| IoError::Invalid {
        at: at.clone().at_field(field),
        error,
    };
    let control = Points::from_flat(dim, flat).map_err(|e| invalid("control_points", e))?;
    let field_of = |e: &lekalo::Error| match e {
        lekalo::Error::LengthMismatch { .. } | lekalo::Error::TooLarge { .. } => "control_points",
        lekalo::Error::NonPositiveWeight { .. } => "weights",
        _ => "knots",
    };
    match weights {
        None => TensorBSpline::new(degrees, knots, control)
            .map(Tensor::BSpline)
            .map_err(|e| invalid(field_of(&e), e)),
        Some(w) => TensorNurbs::new(degrees, knots, control, &w)
            .map(Tensor::Nurbs)
            .map_err(|e| invalid(field_of(&e), e)),
    }
}

#[cfg(test)]
#[path = "tensor_npz_tests.rs"]
mod tests;
