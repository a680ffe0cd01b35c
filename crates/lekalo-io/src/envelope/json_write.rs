//! The text of a curve's JSON envelope, made fast: numbers formatted by `zmij` straight into a
//! byte buffer (no `Value`, no `String` per number), and long lists (knots, control points)
//! formatted block by block on all cores, the blocks written in order. Memory stays bounded by
//! one round of blocks whatever the curve's size.

use std::io::Write;

use rayon::prelude::*;

/// Items formatted by one task.
pub(crate) const BLOCK: usize = 1 << 14;

/// Appends the text `serde_json` gives `x` (shortest round trip: `1.0`, `0.1`, `1e-7`); the
/// library's objects hold finite numbers only (`null` is `serde_json`'s text for the others).
pub(crate) fn push_json_number(out: &mut Vec<u8>, digits: &mut zmij::Buffer, x: f64) {
    out.extend_from_slice(if x.is_finite() {
        digits.format_finite(x).as_bytes()
    } else {
        b"null"
    });
}

/// Writes `n` items separated by `sep`: `item(out, digits, i)` appends item `i`. `out` holds
/// the text before the list; it is flushed to `w` as it grows past a block's text.
///
/// A long list is formatted in rounds of a few blocks per thread, so memory is bounded by two
/// rounds' text: while this thread writes one round to `w`, a helper thread has the next round
/// formatted on all cores, so the writing (a copy into the page cache) overlaps formatting. The
/// buffers of a round are kept for the round after next, so their memory is touched only once.
pub(crate) fn write_list<F>(
    w: &mut dyn Write,
    out: &mut Vec<u8>,
    n: usize,
    sep: &[u8],
    block: usize,
    item: F,
) -> std::io::Result<()>
where
    F: Fn(&mut Vec<u8>, &mut zmij::Buffer, usize) + Sync,
{
    let block = block.max(1);
    let format = |range: std::ops::Range<usize>, buf: &mut Vec<u8>| {
        let mut digits = zmij::Buffer::new();
        for i in range {
            if i > 0 {
                buf.extend_from_slice(sep);
            }
            item(buf, &mut digits, i);
        }
    };
    if n <= block {
        format(0..n, out);
        return Ok(());
    }
    let per_round = block * 4 * rayon::current_num_threads().max(1);
    // formats items `range` into `bufs`, one block each, on all cores
    let round = |range: std::ops::Range<usize>, bufs: &mut Vec<Vec<u8>>| {
        let starts: Vec<usize> = range.clone().step_by(block).collect();
        bufs.resize_with(starts.len(), Vec::new);
        bufs.par_iter_mut().zip(starts).for_each(|(buf, b)| {
            buf.clear();
            format(b..(b + block).min(range.end), buf);
        });
    };
    let mut ready: Vec<Vec<u8>> = Vec::new();
    let mut next: Vec<Vec<u8>> = Vec::new();
    round(0..per_round.min(n), &mut ready);
    let mut start = per_round.min(n);
    loop {
        let end = (start + per_round).min(n);
        let written = std::thread::scope(|s| {
            let helper = (start < end).then(|| s.spawn(|| round(start..end, &mut next)));
            let written = w.write_all(out).and_then(|()| {
                out.clear();
                ready.iter().try_for_each(|p| w.write_all(p))
            });
            let formatted = helper.map_or(Ok(()), |h| {
                h.join()
                    .map_err(|_| std::io::Error::other("formatting a list of numbers failed"))
            });
            written.and(formatted)
        });
        written?;
        if start >= end {
            return Ok(());
        }
        std::mem::swap(&mut ready, &mut next);
        start = end;
    }
}

/// The pieces of the object envelope's layout: newline, indents of one and two levels, and the
/// space after a colon or comma; all empty when the output is compact.
fn layout(pretty: bool) -> (&'static [u8], &'static [u8], &'static [u8], &'static [u8]) {
    if pretty {
        (b"\n", b"  ", b"    ", b" ")
    } else {
        (b"", b"", b"", b"")
    }
}

/// The envelope of `obj` (see [`crate::Object::write_json`]), lists cut in blocks of `block`
/// items.
pub(crate) fn write_object(
    obj: &crate::Object,
    w: &mut dyn Write,
    pretty: bool,
    block: usize,
) -> std::io::Result<()> {
    let (nl, ind, ind2, sp) = layout(pretty);
    let comma_sp = [b",".as_slice(), sp].concat();
    let mut out: Vec<u8> = Vec::with_capacity(4096);
    let field = |out: &mut Vec<u8>, key: &str, first: bool| {
        if !first {
            out.push(b',');
            out.extend_from_slice(nl);
        }
        out.extend_from_slice(ind);
        out.push(b'"');
        out.extend_from_slice(key.as_bytes());
        out.extend_from_slice(b"\":");
        out.extend_from_slice(sp);
    };
    let numbers = |w: &mut dyn Write, out: &mut Vec<u8>, xs: &[f64]| {
        out.push(b'[');
        write_list(w, out, xs.len(), &comma_sp, block, |o, d, i| {
            push_json_number(o, d, xs[i]);
        })?;
        out.push(b']');
        std::io::Result::Ok(())
    };
    out.push(b'{');
    out.extend_from_slice(nl);
    field(&mut out, "lekalo", true);
    out.extend_from_slice(crate::FORMAT_VERSION.to_string().as_bytes());
    field(&mut out, "type", false);
    out.push(b'"');
    out.extend_from_slice(obj.type_name().as_bytes());
    out.push(b'"');
    let knots = obj.explicit_knots().map(lekalo::KnotVector::as_slice);
    let degree = knots.map(|_| obj.degree());
    let weights = obj.weights();
    if let Some(d) = degree {
        field(&mut out, "degree", false);
        out.extend_from_slice(d.to_string().as_bytes());
    }
    if let Some(k) = knots {
        field(&mut out, "knots", false);
        numbers(w, &mut out, k)?;
    }
    field(&mut out, "control", false);
    out.push(b'[');
    out.extend_from_slice(nl);
    let control = obj.control_points();
    let row_sep = [b",".as_slice(), nl].concat();
    write_list(w, &mut out, control.len(), &row_sep, block, |o, d, i| {
        o.extend_from_slice(ind2);
        o.push(b'[');
        for (k, &x) in control.point(i).iter().enumerate() {
            if k > 0 {
                o.extend_from_slice(&comma_sp);
            }
            push_json_number(o, d, x);
        }
        o.push(b']');
    })?;
    out.extend_from_slice(nl);
    out.extend_from_slice(ind);
    out.push(b']');
    if let Some(weights) = weights {
        field(&mut out, "weights", false);
        numbers(w, &mut out, &weights)?;
    }
    out.extend_from_slice(nl);
    out.push(b'}');
    if pretty {
        out.push(b'\n');
    }
    w.write_all(&out)
}

/// Writes the JSON envelope of the NURBS form of `pieces` (what
/// [`crate::Object::write_json`] writes for `Object::Nurbs(pieces.to_nurbs())`, byte for byte)
/// without holding it: knots, control points and weights are made segment by segment, a round of
/// blocks at a time; `progress` is told `0 … 2m` for `m` segments (control points, then
/// weights) and can cancel between rounds.
///
/// # Errors
/// A write error, or the library's error (e.g. [`lekalo::Error::Cancelled`]) wrapped in an
/// [`std::io::Error`] of kind `Other`.
pub fn write_blend_nurbs_json(
    pieces: &lekalo::BlendSplinePieces<'_>,
    w: &mut dyn Write,
    pretty: bool,
    progress: &lekalo::Progress<'_>,
) -> std::io::Result<()> {
    write_pieces(pieces, w, pretty, BLOCK, progress)
}

/// Formats one segment's homogeneous points.
type SegmentText<'a> = dyn Fn(&mut Vec<u8>, &mut zmij::Buffer, &[f64]) + Sync + 'a;

fn write_pieces(
    pieces: &lekalo::BlendSplinePieces<'_>,
    w: &mut dyn Write,
    pretty: bool,
    block: usize,
    progress: &lekalo::Progress<'_>,
) -> std::io::Result<()> {
    let (nl, ind, ind2, sp) = layout(pretty);
    let comma_sp = [b",".as_slice(), sp].concat();
    let row_sep = [b",".as_slice(), nl].concat();
    let field = |out: &mut Vec<u8>, key: &str| {
        out.push(b',');
        out.extend_from_slice(nl);
        out.extend_from_slice(ind);
        out.push(b'"');
        out.extend_from_slice(key.as_bytes());
        out.extend_from_slice(b"\":");
        out.extend_from_slice(sp);
    };
    let hd = pieces.dim() + 1;
    let m = pieces.segment_count();
    // a segment is `q` rows: blocks of segments as long as blocks of rows
    let seg_block = (block / pieces.degree().max(1)).max(1);
    let total = 2 * m as u64;
    let failed: std::sync::Mutex<Option<lekalo::Error>> = std::sync::Mutex::new(None);
    // segment i's homogeneous points (an empty list after a failure, which is then reported)
    let segment = |i: usize| {
        let mut h = Vec::new();
        if let Err(e) = pieces.segment_control(i, &mut h) {
            if let Ok(mut f) = failed.lock() {
                f.get_or_insert(e);
            }
            h.clear();
        }
        h
    };
    let check = |done: u64| -> std::io::Result<()> {
        if let Some(e) = failed.lock().ok().and_then(|mut f| f.take()) {
            return Err(std::io::Error::other(e));
        }
        progress
            .step("blend spline output", done, total)
            .map_err(std::io::Error::other)
    };
    // every segment, in rounds of `round` segments, each formatted by `item` after a `sep`
    let segments = |w: &mut dyn Write,
                    out: &mut Vec<u8>,
                    sep: &[u8],
                    done: u64,
                    item: &SegmentText<'_>|
     -> std::io::Result<()> {
        let round = seg_block * 4 * rayon::current_num_threads().max(1);
        let mut start = 0;
        while start < m {
            let end = (start + round).min(m);
            if start > 0 {
                out.extend_from_slice(sep);
            }
            write_list(w, out, end - start, sep, seg_block, |o, d, i| {
                item(o, d, &segment(start + i));
            })?;
            start = end;
            check(done + end as u64)?;
        }
        Ok(())
    };
    let mut out: Vec<u8> = Vec::with_capacity(4096);
    out.push(b'{');
    out.extend_from_slice(nl);
    out.extend_from_slice(ind);
    out.extend_from_slice(b"\"lekalo\":");
    out.extend_from_slice(sp);
    out.extend_from_slice(crate::FORMAT_VERSION.to_string().as_bytes());
    field(&mut out, "type");
    out.extend_from_slice(b"\"nurbs_curve\"");
    field(&mut out, "degree");
    out.extend_from_slice(pieces.degree().to_string().as_bytes());
    field(&mut out, "knots");
    out.push(b'[');
    write_list(
        w,
        &mut out,
        pieces.knot_count(),
        &comma_sp,
        block,
        |o, d, j| {
            push_json_number(o, d, pieces.knot(j));
        },
    )?;
    out.push(b']');
    field(&mut out, "control");
    out.push(b'[');
    out.extend_from_slice(nl);
    segments(w, &mut out, &row_sep, 0, &|o, d, h| {
        for (r, p) in h.chunks_exact(hd).enumerate() {
            if r > 0 {
                o.extend_from_slice(&row_sep);
            }
            o.extend_from_slice(ind2);
            o.push(b'[');
            let wgt = p[hd - 1];
            for (k, &x) in p[..hd - 1].iter().enumerate() {
                if k > 0 {
                    o.extend_from_slice(&comma_sp);
                }
                push_json_number(o, d, x / wgt);
            }
            o.push(b']');
        }
    })?;
    out.extend_from_slice(nl);
    out.extend_from_slice(ind);
    out.push(b']');
    field(&mut out, "weights");
    out.push(b'[');
    segments(w, &mut out, &comma_sp, m as u64, &|o, d, h| {
        for (r, p) in h.chunks_exact(hd).enumerate() {
            if r > 0 {
                o.extend_from_slice(&comma_sp);
            }
            push_json_number(o, d, p[hd - 1]);
        }
    })?;
    out.push(b']');
    out.extend_from_slice(nl);
    out.push(b'}');
    if pretty {
        out.push(b'\n');
    }
    w.write_all(&out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use lekalo::{BSplineCurve, NurbsCurve, Points};

    fn text(obj: &crate::Object, pretty: bool, block: usize) -> String {
        let mut bytes = Vec::new();
        write_object(obj, &mut bytes, pretty, block).unwrap();
        String::from_utf8(bytes).unwrap()
    }

    #[test]
    fn blocks_do_not_change_the_text() {
        let n = 40;
        let rows: Vec<[f64; 2]> = (0..n)
            .map(|i| [f64::from(i) * 0.1, 1.0 / f64::from(i + 1)])
            .collect();
        let ctrl = Points::from_2d(&rows).unwrap();
        let mut knots = vec![0.0; 4];
        knots.extend((1..n - 3).map(f64::from));
        knots.extend([f64::from(n - 3); 4]);
        let c = crate::Object::BSpline(BSplineCurve::new(3, knots.clone(), ctrl.clone()).unwrap());
        let weights: Vec<f64> = (0..n).map(|i| 1.0 + f64::from(i) * 1e-7).collect();
        let r = crate::Object::Nurbs(NurbsCurve::new(3, knots, ctrl, weights).unwrap());
        for obj in [&c, &r] {
            for pretty in [true, false] {
                let whole = text(obj, pretty, usize::MAX);
                for block in [1, 3, 7, 16] {
                    assert_eq!(text(obj, pretty, block), whole, "block {block}");
                }
                let back = <crate::Object as crate::CurveJson>::from_json_str(&whole, "t").unwrap();
                assert_eq!(&back, obj, "round trip");
            }
        }
        let head = text(&c, true, 5);
        assert!(
            head.starts_with("{\n  \"lekalo\": 1,\n  \"type\": \"bspline_curve\",\n  \"degree\": 3,\n  \"knots\": [0.0, 0.0, 0.0, 0.0, 1.0, 2.0,"),
            "{head}"
        );
        assert!(
            head.contains("\"control\": [\n    [0.0, 1.0],\n    [0.1, 0.5],\n"),
            "{head}"
        );
    }

    #[test]
    fn blend_pieces_are_written_as_the_whole_nurbs() {
        use lekalo::{
            ArcParametrization, BlendSpline, BlendSplineOptions, BlendSplinePieces, CircularArcs,
            LocalCurves, Parabolas, Progress,
        };
        let rows: Vec<[f64; 2]> = (0..23)
            .map(|i| {
                let a = f64::from(i) * std::f64::consts::TAU / 23.0;
                let r = 1.0 + 0.1 * (3.0 * a).sin();
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        let pts = Points::from_2d(&rows).unwrap();
        let arcs = CircularArcs::new(ArcParametrization::RationalQuadratic);
        let families: [&(dyn LocalCurves + Sync); 2] = [&Parabolas, &arcs];
        for local in families {
            for closed in [false, true] {
                let opts = BlendSplineOptions {
                    closed,
                    ..BlendSplineOptions::default()
                };
                let whole = crate::Object::Nurbs(
                    BlendSpline::new(pts.as_view(), local, opts)
                        .unwrap()
                        .to_nurbs()
                        .unwrap(),
                );
                let pieces =
                    BlendSplinePieces::new(pts.as_view(), local, opts, &Progress::new()).unwrap();
                for pretty in [true, false] {
                    let expected = text(&whole, pretty, usize::MAX);
                    for block in [1, 2, 5, 1000] {
                        let mut bytes = Vec::new();
                        write_pieces(&pieces, &mut bytes, pretty, block, &Progress::new()).unwrap();
                        assert_eq!(
                            String::from_utf8(bytes).unwrap(),
                            expected,
                            "closed {closed} pretty {pretty} block {block}"
                        );
                    }
                }
                let stop = std::sync::atomic::AtomicBool::new(true);
                let e = write_pieces(
                    &pieces,
                    &mut Vec::new(),
                    true,
                    1,
                    &Progress::new().with_cancel(&stop),
                )
                .unwrap_err();
                assert!(e.to_string().contains("cancelled"), "{e}");
            }
        }
    }
}
