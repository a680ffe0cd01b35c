//! NumPy `.npz` archives of curves: one `.npy` member per named array, so that
//! `c = np.load('curve.npz')` gives `c['degree']`, `c['knots']`, `c['control_points']` and, for
//! NURBS, `c['weights']`.
//!
//! | member | dtype | shape | meaning |
//! |---|---|---|---|
//! | `degree.npy` | int64 (float64 with an integer value is read too) | `()` | degree `p` |
//! | `knots.npy` | float64 | `(n + p + 1,)` | knot vector |
//! | `control_points.npy` | float64 | `(n, d)` | Euclidean control points, one per row |
//! | `weights.npy` (NURBS only) | float64 | `(n,)` | positive weights |
//!
//! Members are stored uncompressed (as `numpy.savez` writes them); archives of
//! `numpy.savez_compressed` are refused with a message saying so. A Bezier curve is written as
//! the B-spline with knots `0^(p+1) 1^(p+1)` (the same curve, docs/theory/curves.md) and reads
//! back as a B-spline.

use std::io::{Cursor, Read, Seek, Write};

use lekalo::{BSplineCurve, NurbsCurve, Points};
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipArchive, ZipWriter};

use crate::error::{IoError, IoResult, Location};
use crate::npy::{npy_header, read_array, read_npy_points, write_le};
use crate::object::Object;

/// Largest degree read from an archive (a larger one is surely a wrong member, not a curve).
const MAX_DEGREE: f64 = 1.0e6;

/// The curve `obj` as an `.npz` archive (see the module's table of members), made in memory;
/// [`write_npz_curve`] writes it to a file without holding it.
///
/// ```
/// use lekalo_io::{curve_to_npz, read_npz_curve, CurveJson, Object};
/// let obj = Object::from_json_str(
///     r#"{"lekalo":1,"type":"bspline_curve","degree":1,"knots":[0,0,1,1],"control":[[0,0],[1,2]]}"#,
///     "c.json")?;
/// let bytes = curve_to_npz(&obj)?;
/// assert_eq!(read_npz_curve(&bytes, "c.npz")?, obj);
/// # Ok::<(), lekalo_io::IoError>(())
/// ```
///
/// # Errors
/// [`IoError::Unsupported`] if the archive cannot be built (an internal failure).
pub fn curve_to_npz(obj: &Object) -> IoResult<Vec<u8>> {
    let mut out = Cursor::new(Vec::new());
    write_npz_curve(obj, &mut out).map_err(|e| IoError::Unsupported {
        what: format!("cannot build the .npz archive: {e}"),
    })?;
    Ok(out.into_inner())
}

/// Writes the curve `obj` as an `.npz` archive to `w`, each array converted to bytes a chunk at
/// a time straight into its member (no copy of the curve, no archive in memory): the members of
/// [`curve_to_npz`], byte for byte.
///
/// # Errors
/// The writer's; the archive's (as [`std::io::ErrorKind::Other`]), e.g. a degree too large for
/// an int64.
pub fn write_npz_curve<W: Write + Seek>(obj: &Object, w: W) -> std::io::Result<()> {
    let degree = obj.degree();
    let knots = obj.knots();
    let knots = knots.as_slice();
    let control = obj.control_points();
    let control: &Points = &control;
    let weights = obj.weights();
    let other = |e: &dyn std::fmt::Display| std::io::Error::other(e.to_string());
    let degree = i64::try_from(degree)
        .map_err(|_| other(&format!("degree {degree} does not fit an int64")))?;
    let mut members: Vec<(&str, &str, Vec<usize>, &[f64])> = vec![
        ("knots.npy", "<f8", vec![knots.len()], knots),
        (
            "control_points.npy",
            "<f8",
            vec![control.len(), control.dim()],
            control.as_slice(),
        ),
    ];
    if let Some(wt) = &weights {
        members.push(("weights.npy", "<f8", vec![wt.len()], wt));
    }
    let mut z = ZipWriter::new(w);
    let opts = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .large_file(false);
    z.start_file("degree.npy", opts).map_err(|e| other(&e))?;
    z.write_all(&npy_header("<i8", &[]).map_err(|e| other(&e))?)?;
    z.write_all(&degree.to_le_bytes())?;
    for (name, descr, shape, values) in members {
        z.start_file(name, opts).map_err(|e| other(&e))?;
        z.write_all(&npy_header(descr, &shape).map_err(|e| other(&e))?)?;
        write_le(&mut z, values)?;
    }
    z.finish().map_err(|e| other(&e))?;
    Ok(())
}

/// Reads a curve from an `.npz` archive (see the module's table of members); `source` names
/// the input in messages.
///
/// # Errors
/// [`IoError::Syntax`] naming the file and the member for an archive that is not a zip, a
/// compressed or missing member, or a member that is not a valid `.npy` array of the table's
/// dtype and shape; [`IoError::Invalid`] if the library rejects the curve (knots, weights).
pub fn read_npz_curve(bytes: &[u8], source: &str) -> IoResult<Object> {
    let mut z = open_archive(bytes, source)?;
    let needs = "a curve needs degree, knots and control_points (and weights for NURBS)";
    let mut member = |name: &str, required: bool| {
        read_member(&mut z, bytes.len(), source, name, required, needs)
    };
    let shape_err =
        |label: &str, what: &str| IoError::syntax(Location::new(label).at_field("shape"), what);
    let (label, b) = member("degree", true)?.unwrap_or_default();
    let (shape, v) = read_array(&b, &label, true)?;
    let degree = match (shape.len(), v.first()) {
        (0, Some(&p)) | (1, Some(&p)) if v.len() == 1 => p,
        _ => {
            return Err(shape_err(
                &label,
                "degree must be a scalar, e.g. np.int64(3)",
            ))
        }
    };
    if degree < 0.0 || degree.fract() != 0.0 || degree > MAX_DEGREE {
        return Err(IoError::syntax(
            Location::new(&label).at_field("[]"),
            format!("{degree} is not a degree: it must be a whole number from 0 to {MAX_DEGREE}"),
        ));
    }
    // a whole number in [0, 1e6]: exact in usize
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let degree = degree as usize;
    let (label, b) = member("knots", true)?.unwrap_or_default();
    let (shape, knots) = read_array(&b, &label, false)?;
    if shape.len() != 1 {
        return Err(shape_err(&label, "knots must be a 1-D array (k,)"));
    }
    let (label, b) = member("control_points", true)?.unwrap_or_default();
    let control: Points = read_npy_points(&b, &label)?;
    let weights = match member("weights", false)? {
        None => None,
        Some((label, b)) => {
            let (shape, w) = read_array(&b, &label, false)?;
            if shape.len() != 1 {
                return Err(shape_err(&label, "weights must be a 1-D array (n,)"));
            }
            Some(w)
        }
    };
    let at = Location::new(source);
    let obj = match weights {
        None => BSplineCurve::new(degree, knots, control).map(Object::BSpline),
        Some(w) => NurbsCurve::new(degree, knots, control, w).map(Object::Nurbs),
    };
    obj.map_err(|error| IoError::Invalid { at, error })
}

/// The zip archive of an `.npz` file's `bytes`, refused with a named error if it is not a zip
/// or if two members share a name; `source` names the input in messages.
pub(crate) fn open_archive<'a>(
    bytes: &'a [u8],
    source: &str,
) -> IoResult<ZipArchive<Cursor<&'a [u8]>>> {
    let z = ZipArchive::new(Cursor::new(bytes)).map_err(|e| {
        IoError::syntax(
            Location::new(source),
            format!("not a NumPy .npz archive (a zip file): {e}; save the arrays with numpy.savez"),
        )
    })?;
    if let Some(name) = repeated_member(bytes, z.central_directory_start()) {
        let field = name.strip_suffix(".npy").unwrap_or(&name).to_string();
        return Err(IoError::syntax(
            Location::new(source).at_field(field),
            format!(
                "the archive has two members named {name}: NumPy's np.load reads the last, other \
                 zip readers the first; write each array once (numpy.savez(path, name=array, ...))"
            ),
        ));
    }
    Ok(z)
}

/// The bytes of member `name.npy` of the archive `z` (of `total` bytes, the most read), with
/// its label `source: name.npy` for messages; `None` for a missing member that is not
/// `required`. A missing required member is refused naming it and `needs` (what the archive
/// must hold); a compressed or unreadable one naming it.
pub(crate) fn read_member(
    z: &mut ZipArchive<Cursor<&[u8]>>,
    total: usize,
    source: &str,
    name: &str,
    required: bool,
    needs: &str,
) -> IoResult<Option<(String, Vec<u8>)>> {
    let file = format!("{name}.npy");
    let label = format!("{source}: {file}");
    let unreadable = |e: &dyn std::fmt::Display| {
        IoError::syntax(
            Location::new(source).at_field(name),
            format!(
                "cannot read member {file}: {e}; write the archive with numpy.savez (not savez_compressed)"
            ),
        )
    };
    let mut f = match z.by_name(&file) {
        Ok(f) => f,
        Err(zip::result::ZipError::FileNotFound) if !required => return Ok(None),
        Err(zip::result::ZipError::FileNotFound) => {
            return Err(IoError::syntax(
                Location::new(source).at_field(name),
                format!("the archive has no member {file}; {needs}"),
            ))
        }
        Err(e) => return Err(unreadable(&e)),
    };
    let mut out = Vec::new();
    (&mut f)
        .take(u64::try_from(total).unwrap_or(u64::MAX))
        .read_to_end(&mut out)
        .map_err(|e| unreadable(&e))?;
    Ok(Some((label, out)))
}

/// The first name that two entries of the zip central directory starting at byte `start` of
/// `bytes` share (APPNOTE.TXT 4.3.12: signature `PK\x01\x02`, the name's length at byte 28,
/// the extra field's at 30, the comment's at 32, the name at 46). The zip crate keeps one entry
/// per name, so a repeated member is invisible through it. The walk stops at the first record
/// that is not a central directory header; at most one name per 46 bytes of the archive.
fn repeated_member(bytes: &[u8], start: u64) -> Option<String> {
    let u16_at = |p: usize| usize::from(u16::from_le_bytes([bytes[p], bytes[p + 1]]));
    let mut seen = std::collections::HashSet::new();
    let mut p = usize::try_from(start).ok()?;
    while p.checked_add(46).is_some_and(|e| e <= bytes.len()) && bytes[p..p + 4] == *b"PK\x01\x02" {
        let (n, m, k) = (u16_at(p + 28), u16_at(p + 30), u16_at(p + 32));
        let name = bytes.get(p + 46..p + 46 + n)?;
        if !seen.insert(name) {
            return Some(String::from_utf8_lossy(name).into_owned());
        }
        p += 46 + n + m + k;
    }
    None
}

#[cfg(test)]
#[path = "npz_tests.rs"]
mod tests;
