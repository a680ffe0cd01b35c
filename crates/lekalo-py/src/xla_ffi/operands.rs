//! What every handler does with its operands before it calls a kernel, written once: the
//! leading batch axes shared by all buffers ([`Batch`]) and a batch element's slice of a buffer,
//! the `with_<kind>` flags of a derivative target, and the split of a JVP target's arguments
//! (residuals, then one tangent a present kind) and of a VJP target's results (one cotangent a
//! present kind).

use super::abi::{Call, In, Out};

/// The leading batch axes of a call (the layout of `vmap_method="broadcast_all"`: every buffer
/// has the same leading axes, then its own core axes), fixed by its first buffer.
pub(super) struct Batch<'a> {
    dims: &'a [i64],
    /// The number of batch elements (1 without batch axes).
    pub(super) count: usize,
}

/// `Π dims`, `None` for a negative dimension or an overflow.
fn product(dims: &[i64]) -> Option<usize> {
    dims.iter()
        .try_fold(1usize, |acc, &x| acc.checked_mul(usize::try_from(x).ok()?))
}

impl<'a> Batch<'a> {
    /// The batch axes of `dims`, a buffer (`what`) with `core` trailing axes.
    pub(super) fn of(what: &str, dims: &'a [i64], core: usize) -> Result<Self, String> {
        let lead = dims
            .len()
            .checked_sub(core)
            .ok_or_else(|| format!("{what} has rank {}, fewer than {core}", dims.len()))?;
        let dims = &dims[..lead];
        let count = product(dims).ok_or("bad batch dimensions")?;
        Ok(Batch { dims, count })
    }

    /// The size of one batch element of a buffer (`what`) with `core` trailing axes, after
    /// checking that its leading axes are the batch's.
    pub(super) fn size(&self, what: &str, dims: &[i64], core: usize) -> Result<usize, String> {
        let lead = self.dims.len();
        if dims.len() != lead + core || dims[..lead] != *self.dims {
            return Err(format!(
                "{what} has shape {dims:?}; the leading (batch) axes must be {:?}, followed by \
                 {core} axes",
                self.dims
            ));
        }
        product(&dims[lead..]).ok_or_else(|| format!("{what}: bad dimensions {dims:?}"))
    }

    /// Checks that a buffer (`what`) with `core` trailing axes has the batch's leading axes and
    /// elements of `size` numbers (a tangent or cotangent shaped as its primal).
    pub(super) fn expect(
        &self,
        what: &str,
        dims: &[i64],
        core: usize,
        size: usize,
    ) -> Result<(), String> {
        let got = self.size(what, dims, core)?;
        if got != size {
            return Err(format!(
                "{what} has shape {dims:?}: {got} numbers a batch element, expected {size}"
            ));
        }
        Ok(())
    }
}

/// Element `b` of a batch of elements of `size` numbers.
pub(super) fn element(data: &[f64], size: usize, b: usize) -> &[f64] {
    &data[b * size..(b + 1) * size]
}

/// Element `b` of a batch of elements of `size` numbers, to be written.
pub(super) fn element_mut(data: &mut [f64], size: usize, b: usize) -> &mut [f64] {
    &mut data[b * size..(b + 1) * size]
}

/// The size of the last axis of a buffer (`what`, e.g. `(n, dim)` control points): the
/// dimension of the points.
pub(super) fn last_axis(what: &str, dims: &[i64]) -> Result<usize, String> {
    dims.last()
        .and_then(|&d| usize::try_from(d).ok())
        .ok_or_else(|| format!("{what} of shape {dims:?}: the last axis holds the coordinates"))
}

/// The message for a call whose number of arguments or results is not the target's.
pub(super) fn count_error(what: &str, want: usize, got: usize) -> String {
    format!("expected {want} {what}, got {got} (lekalo.jax and its native module disagree)")
}

/// The batch of a target's residuals and each one's element size (`names`: each residual's
/// name and core axes, in order), after checking their count.
pub(super) fn batch_sizes<'a>(
    res: &[In<'a>],
    names: &[(&str, usize)],
) -> Result<(Batch<'a>, Vec<usize>), String> {
    if res.len() != names.len() {
        return Err(count_error("arguments", names.len(), res.len()));
    }
    let batch = Batch::of(names[0].0, res[0].dims, names[0].1)?;
    let sizes = res
        .iter()
        .zip(names)
        .map(|(a, &(name, core))| batch.size(name, a.dims, core))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((batch, sizes))
}

/// The flag `with_<kind>` of a derivative target, `name` its attribute name (false when
/// absent: the values target has none).
pub(super) fn flag(call: &Call<'_>, name: &str) -> bool {
    call.attr(name).is_ok_and(|v| v != 0)
}

/// The flags `with_<kind>` of a derivative target, `names` the attribute names ([`flag`]).
pub(super) fn flags<const K: usize>(call: &Call<'_>, names: [&str; K]) -> [bool; K] {
    names.map(|name| flag(call, name))
}

/// The integer attribute `name` as a count (a degree, a number of variables).
pub(super) fn count_attr(call: &Call<'_>, name: &str) -> Result<usize, String> {
    let v = call.attr(name)?;
    usize::try_from(v).map_err(|_| format!("{name} must be >= 0, got {v}"))
}

/// A JVP target's arguments: the first `residuals` (the primal operands), then one tangent for
/// each present kind, in the order of the kinds; `None` for an absent one.
pub(super) fn tangents<'c, 'a, const K: usize>(
    args: &'c [In<'a>],
    residuals: usize,
    present: [bool; K],
) -> Result<(&'c [In<'a>], [Option<&'c In<'a>>; K]), String> {
    let (res, tangents) = tangents_of(args, residuals, &present)?;
    let tangents = tangents
        .try_into()
        .map_err(|_| count_error("kinds", K, present.len()))?;
    Ok((res, tangents))
}

/// [`tangents`] for a number of kinds known at run time (one a direction of a tensor spline).
pub(super) fn tangents_of<'c, 'a>(
    args: &'c [In<'a>],
    residuals: usize,
    present: &[bool],
) -> Result<(&'c [In<'a>], Vec<Option<&'c In<'a>>>), String> {
    let want = residuals + present.iter().filter(|&&p| p).count();
    if args.len() != want {
        return Err(count_error("arguments", want, args.len()));
    }
    let (res, rest) = args.split_at(residuals);
    let mut rest = rest.iter();
    let tangents = present
        .iter()
        .map(|&p| if p { rest.next() } else { None })
        .collect();
    Ok((res, tangents))
}

/// A VJP target's results: one cotangent for each present kind, in the order of the kinds;
/// `None` for an absent one.
pub(super) fn cotangents<'c, 'a, const K: usize>(
    rets: &'c mut [Out<'a>],
    present: [bool; K],
) -> Result<[Option<&'c mut Out<'a>>; K], String> {
    cotangents_of(rets, &present)?
        .try_into()
        .map_err(|_| count_error("kinds", K, present.len()))
}

/// [`cotangents`] for a number of kinds known at run time.
pub(super) fn cotangents_of<'c, 'a>(
    rets: &'c mut [Out<'a>],
    present: &[bool],
) -> Result<Vec<Option<&'c mut Out<'a>>>, String> {
    let want = present.iter().filter(|&&p| p).count();
    if rets.len() != want {
        return Err(count_error("results", want, rets.len()));
    }
    let mut rest = rets.iter_mut();
    Ok(present
        .iter()
        .map(|&p| if p { rest.next() } else { None })
        .collect())
}

/// The one result of a values or JVP target.
pub(super) fn single<'c, 'a>(rets: &'c mut [Out<'a>]) -> Result<&'c mut Out<'a>, String> {
    match rets {
        [one] => Ok(one),
        _ => Err(count_error("results", 1, rets.len())),
    }
}
