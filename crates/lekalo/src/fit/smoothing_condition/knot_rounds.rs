//! Step 2 of [`smoothing_condition`](super::smoothing_condition): the rounds of least squares
//! and knot addition, knots added where the residual is largest (FITPACK `fpcurf`/`fpknot`;
//! `docs/theory/fitting.md#smoothing-condition`).

use super::lsq_pass::{back_substitute, LsqPass, Observations};
use super::{
    check_max_knots, KnotLimit, KnotRounds, Rounds, RoundsStart, RoundsState, SMOOTHING_RTOL,
};
use crate::error::{Error, Result};
use crate::fit::banded::BandedQr;
use crate::fit::progress::Steps;

/// Step 2 of [`smoothing_condition`](super::smoothing_condition): the rounds of least squares
/// and knot addition, each round's knot vector passed to `seen` before its pass, each round a
/// step of `steps`; the end knots at `domain` (checked to hold the data), else at the data's
/// ends; a round's second and later knots placed as `rounds` says. `start` says where the rounds
/// begin ([`RoundsStart`]) and under which [`KnotLimit`]: the rounds add interior knots up to
/// the limit; once there, they end with the least-squares spline for [`KnotLimit::Stop`]
/// (FITPACK `curfit`'s `ier = 1` at `nest`), and for [`KnotLimit::Resume`] go on without it
/// from the knots reached, adding one knot next as a first round does (a second `fpcurf` call
/// with `iopt = 1` and the `ier = 1` of the first, as SciPy's `UnivariateSpline` makes it).
/// Returns where the rounds ended and the [`RoundsState`] a later call goes on from.
#[allow(clippy::too_many_arguments)]
pub(super) fn knot_rounds(
    obs: &Observations,
    k: usize,
    s: f64,
    domain: Option<(f64, f64)>,
    rounds: KnotRounds,
    start: RoundsStart<'_>,
    steps: &Steps<'_, '_>,
    seen: &mut dyn FnMut(&[f64]),
) -> Result<(Rounds<BandedQr>, RoundsState)> {
    let md = obs.sites.len();
    if md < k + 1 {
        return Err(Error::TooFew {
            what: "distinct data parameters for the smoothing condition (degree + 1)".into(),
            min: k + 1,
            got: md,
        });
    }
    let acc = SMOOTHING_RTOL * s;
    // knot counts of the polynomial and of interpolation
    let (nmin, nmax) = (2 * k + 2, md + k + 1);
    let full = nmax - nmin;
    let limit = start.limit();
    let (mut cap, then) = limit_caps(k, limit)?;
    let mut knots = Knots::new(&obs.sites, k, domain);
    let mut tally = Tally {
        fp0: f64::INFINITY,
        fpold: 0.0,
        nplus: 0,
        restart: false,
    };
    if s == 0.0 {
        knots.interpolation(&obs.sites);
    } else if let RoundsStart::Continue(st) = start {
        st.check(&obs.sites, full)?;
        // `curfit` with `iopt = 1` starts over from the polynomial when the last fit had no
        // interior knot or `s ≥ fp0`
        if !st.interior.is_empty() && st.fp0 > s {
            knots.resume_at(&obs.sites, &st.interior);
            tally = Tally {
                fp0: st.fp0,
                fpold: st.fp_before,
                nplus: st.nplus,
                restart: st.restart,
            };
        }
    }
    let mut left = limit;
    let mut pass = LsqPass::new(obs, k);
    loop {
        steps.tick()?;
        let t = knots.vector();
        seen(&t);
        let n = t.len();
        let qr = pass.run(obs, &t);
        let c = back_substitute(&qr)?;
        let fp = qr.rss;
        if n == nmin {
            // FITPACK's `ier = −2`
            tally.fp0 = fp;
            tally.restart = true;
        }
        let fpms = fp - s;
        let at_pass = tally;
        // the state of this pass, `restart` FITPACK's `ier ≠ 0` on return
        let state = |restart| Tally { restart, ..at_pass }.state(&knots.interior, left);
        if accepts_least_squares(fpms, acc) || (fpms < 0.0 && n == nmin) {
            return Ok((Rounds::Done { t, c }, state(tally.restart)));
        }
        if fpms < 0.0 {
            let smooth = Rounds::Smooth {
                t,
                qr,
                fp0: tally.fp0,
                fp_inf: fp,
            };
            return Ok((smooth, state(tally.restart)));
        }
        if n >= nmax {
            // interpolation (FITPACK's `ier = −1`)
            return Ok((Rounds::Done { t, c }, state(true)));
        }
        if knots.count() >= cap {
            if then <= cap {
                // as many knots as allowed (FITPACK's `ier = 1`)
                return Ok((Rounds::Done { t, c }, state(true)));
            }
            // `fpcurf` called again with `iopt = 1` and the `ier = 1` of its stop: it repeats
            // this pass and, `ier` not being 0, adds one knot as in the first round
            cap = then;
            left = KnotLimit::Unlimited;
            tally.restart = true;
        }
        tally.nplus = if std::mem::take(&mut tally.restart) {
            1
        } else {
            next_nplus(tally.nplus, fpms, tally.fpold - fp, acc)
        };
        tally.fpold = fp;
        pass.residuals(obs, &c);
        knots.span_sums(obs, &pass, &t);
        let added = match rounds {
            KnotRounds::Shared => knots.add_up_to(&obs.sites, tally.nplus, full, cap),
            KnotRounds::Refit => knots.add_refitting(obs, &mut pass, tally.nplus, full, cap)?,
        };
        match added {
            Added::Some => {}
            Added::Full => knots.interpolation(&obs.sites),
            // no span can be split without crowding an end: the knots of interpolation, when
            // `cap` allows them
            Added::None if full <= cap => knots.interpolation(&obs.sites),
            Added::None => {
                let st = Tally {
                    restart: false,
                    ..at_pass
                };
                return Ok((Rounds::Done { t, c }, st.state(&knots.interior, left)));
            }
        }
    }
}

/// FITPACK's bookkeeping across the rounds: `fp0` (the polynomial's residual), `fpold` (the
/// residual of the pass before), `nplus` (the knots the last round set out to add) and
/// `ier ≠ 0` (the next round adds one knot, as a first round does).
#[derive(Clone, Copy)]
struct Tally {
    fp0: f64,
    fpold: f64,
    nplus: usize,
    restart: bool,
}

impl Tally {
    /// The [`RoundsState`] of a pass on the interior knots `interior` under `limit`.
    fn state(self, interior: &[f64], limit: KnotLimit) -> RoundsState {
        RoundsState {
            interior: interior.to_vec(),
            fp0: self.fp0,
            fp_before: self.fpold,
            nplus: self.nplus,
            restart: self.restart,
            limit,
        }
    }
}

/// The interior knots the rounds may place under `limit` before they stop, and those they may
/// place after: `(cap, then)`, `usize::MAX` for no bound; `then ≤ cap` when they stop there.
///
/// # Errors
/// [`Error::TooFew`] for a limit below `2·degree + 2` knots.
pub(super) fn limit_caps(degree: usize, limit: KnotLimit) -> Result<(usize, usize)> {
    Ok(match limit {
        KnotLimit::Unlimited => (usize::MAX, usize::MAX),
        KnotLimit::Stop(n) => {
            let cap = check_max_knots(degree, Some(n))?;
            (cap, cap)
        }
        KnotLimit::Resume(n) => (check_max_knots(degree, Some(n))?, usize::MAX),
    })
}

/// What [`Knots::add_up_to`] did.
pub(in crate::fit) enum Added {
    /// Knots were added.
    Some,
    /// The knot count of interpolation is reached.
    Full,
    /// No span holds a distinct parameter strictly inside.
    None,
}

/// The interior knots of the rounds with FITPACK's bookkeeping per span: the residual sum
/// `fpint` and the number of distinct parameters strictly inside, `nrdata`.
#[derive(Clone)]
pub(in crate::fit) struct Knots {
    pub(in crate::fit) k: usize,
    pub(in crate::fit) a: f64,
    pub(in crate::fit) b: f64,
    pub(in crate::fit) interior: Vec<f64>,
    pub(in crate::fit) fpint: Vec<f64>,
    pub(in crate::fit) nrdata: Vec<usize>,
    /// The parameters the spans nearest a clamped end keep strictly inside, `⌊(k − 1)/2⌋`
    /// ([`end_deficit`]); 0 for closed curves, which have no end.
    pub(in crate::fit) end_keep: usize,
}

impl Knots {
    /// No interior knot; the end knots at `domain`, else at the first and last site. The
    /// bookkeeping counts the sites strictly inside, whatever the domain (FITPACK's
    /// `nrdata(1) = m − 2` with `xb ≤ x(1)`, `xe ≥ x(m)`).
    fn new(sites: &[f64], k: usize, domain: Option<(f64, f64)>) -> Self {
        let (a, b) = domain.unwrap_or((sites[0], sites[sites.len() - 1]));
        Knots {
            k,
            a,
            b,
            interior: Vec::new(),
            fpint: vec![0.0],
            nrdata: vec![sites.len().saturating_sub(2)],
            end_keep: k.saturating_sub(1) / 2,
        }
    }

    pub(in crate::fit) fn count(&self) -> usize {
        self.interior.len()
    }

    /// The clamped knot vector.
    fn vector(&self) -> Vec<f64> {
        let k = self.k;
        let mut t = Vec::with_capacity(self.interior.len() + 2 * k + 2);
        t.extend(std::iter::repeat_n(self.a, k + 1));
        t.extend_from_slice(&self.interior);
        t.extend(std::iter::repeat_n(self.b, k + 1));
        t
    }

    /// The knots of interpolation at the distinct parameters (FITPACK's choice for `s = 0`):
    /// the parameters themselves for odd degree, the midpoints for even degree, leaving out
    /// `⌈(k+1)/2⌉`-ish at each end so that there are `sites − k − 1` of them.
    fn interpolation(&mut self, sites: &[f64]) {
        let k = self.k;
        let count = sites.len().saturating_sub(k + 1);
        let j0 = k / 2 + 1;
        self.interior = (0..count)
            .map(|l| {
                let j = j0 + l;
                if k % 2 == 1 {
                    sites[j]
                } else {
                    0.5 * (sites[j] + sites[j - 1])
                }
            })
            .collect();
    }

    /// The interior knots `interior` of an earlier call's rounds, FITPACK's count `nrdata` of
    /// the distinct parameters strictly inside each span taken afresh (the first and last
    /// parameter bounding the end spans, as [`Knots::new`] counts them); `fpint` is computed
    /// by the next round's [`Knots::span_sums`].
    fn resume_at(&mut self, sites: &[f64], interior: &[f64]) {
        self.interior = interior.to_vec();
        let mut bounds = Vec::with_capacity(interior.len() + 2);
        bounds.push(sites[0]);
        bounds.extend_from_slice(interior);
        bounds.push(sites[sites.len() - 1]);
        self.nrdata = bounds
            .windows(2)
            .map(|w| {
                let lo = sites.partition_point(|&u| u <= w[0]);
                let hi = sites.partition_point(|&u| u < w[1]);
                hi.saturating_sub(lo)
            })
            .collect();
        self.fpint = vec![0.0; self.nrdata.len()];
    }

    /// `fpint`: the residual of each span, a point on a knot counting half to each side.
    fn span_sums(&mut self, obs: &Observations, pass: &LsqPass, t: &[f64]) {
        let k = self.k;
        let nk1 = t.len() - k - 1;
        self.fpint.clear();
        let (mut l, mut part) = (k + 1, 0.0);
        for (&u, &term) in obs.x.iter().zip(&pass.res) {
            let new = l < nk1 && u >= t[l];
            if new {
                l += 1;
            }
            part += term;
            if new {
                self.fpint.push(part - 0.5 * term);
                part = 0.5 * term;
            }
        }
        self.fpint.push(part);
    }

    /// Adds up to `nplus` knots (FITPACK `fpknot`, one at a time) while fewer than `full`
    /// and `cap` interior knots: [`Added::Full`] when `full` is reached (the caller places the
    /// knots of interpolation), [`Added::None`] when no span could be split.
    pub(in crate::fit) fn add_up_to(
        &mut self,
        sites: &[f64],
        nplus: usize,
        full: usize,
        cap: usize,
    ) -> Added {
        let before = self.count();
        for _ in 0..nplus {
            if !self.add_one(sites) || self.count() >= full || self.count() >= cap {
                break;
            }
        }
        self.added_since(before, full)
    }

    /// [`Knots::add_up_to`] with the least squares refitted after each knot
    /// ([`KnotRounds::Refit`], SciPy's `generate_knots`): each knot goes to the span whose
    /// residual sum, taken afresh from the fit on the knots so far, is largest, as SciPy places
    /// it, even where the split leaves an end short of parameters, as long as the least
    /// squares on the new knots keeps full rank (every pivot of its triangle above
    /// [`RANK_RTOL`](crate::fit::banded::RANK_RTOL) of the largest); otherwise the knot is
    /// taken back and placed as [`Knots::add_one`] places it, with the guard of the ends. The
    /// bookkeeping of `nrdata` is the same; `fpint` is recomputed instead of shared.
    fn add_refitting(
        &mut self,
        obs: &Observations,
        pass: &mut LsqPass,
        nplus: usize,
        full: usize,
        cap: usize,
    ) -> Result<Added> {
        let before = self.count();
        for _ in 0..nplus {
            let kept = self.clone();
            if !self.add_one_by(&obs.sites, false) {
                break;
            }
            if self.refit(obs, pass).is_err() {
                *self = kept;
                if !self.add_one(&obs.sites) {
                    break;
                }
                self.refit(obs, pass)?;
            }
            if self.count() >= full || self.count() >= cap {
                break;
            }
        }
        Ok(self.added_since(before, full))
    }

    /// The least squares on the current knots, its residual sums per span in `fpint`.
    ///
    /// # Errors
    /// [`Error::SingularSystem`] when the triangle loses rank.
    fn refit(&mut self, obs: &Observations, pass: &mut LsqPass) -> Result<()> {
        let t = self.vector();
        let c = back_substitute(&pass.run(obs, &t))?;
        pass.residuals(obs, &c);
        self.span_sums(obs, pass, &t);
        Ok(())
    }

    /// What adding knots did, from the count `before` and the count of interpolation `full`.
    fn added_since(&self, before: usize, full: usize) -> Added {
        if self.count() >= full {
            Added::Full
        } else if self.count() == before {
            Added::None
        } else {
            Added::Some
        }
    }

    /// Adds one knot at the middle distinct parameter of the span with the largest residual
    /// sum among those with a parameter strictly inside (FITPACK `fpknot`), unless the split
    /// would leave an end short of parameters ([`Knots::end_deficit`] above
    /// [`END_DEFICIT_MAX`]; then the next span). Returns `false` when no span can be split.
    fn add_one(&mut self, sites: &[f64]) -> bool {
        self.add_one_by(sites, true)
    }

    /// [`Knots::add_one`], with the guard of the ends when `guarded`, else SciPy's `fpknot`
    /// (the largest residual sum among the spans with a parameter strictly inside).
    fn add_one_by(&mut self, sites: &[f64], guarded: bool) -> bool {
        let spans = self.nrdata.len();
        // the ends' deficits reach only as far as their walks; a split beyond leaves them
        let (front, back) = (self.end_walk(false), self.end_walk(true));
        let (mut best, mut fpmax, mut begin) = (None, 0.0, 0usize);
        for (j, (&f, &nd)) in self.fpint.iter().zip(&self.nrdata).enumerate() {
            let near_an_end = guarded && (j < front || j + back >= spans);
            if nd > 0 && f > fpmax && (!near_an_end || self.split_keeps_ends(j)) {
                fpmax = f;
                best = Some((j, begin));
            }
            begin += nd + 1;
        }
        let Some((j, begin)) = best else {
            return false;
        };
        let maxpt = self.nrdata[j];
        let ihalf = maxpt / 2 + 1;
        let knot = sites[begin + ihalf];
        self.interior.insert(j, knot);
        self.nrdata[j] = ihalf - 1;
        self.nrdata.insert(j + 1, maxpt - ihalf);
        let am = maxpt as f64;
        self.fpint[j] = fpmax * (ihalf - 1) as f64 / am;
        self.fpint
            .insert(j + 1, fpmax * (maxpt - ihalf) as f64 / am);
        true
    }

    /// How many spans from one end (`back`: the last) [`Knots::end_deficit`] reads.
    fn end_walk(&self, back: bool) -> usize {
        let counts = self.nrdata.iter().copied();
        if back {
            end_deficit(counts.rev(), self.end_keep).1
        } else {
            end_deficit(counts, self.end_keep).1
        }
    }

    /// Whether splitting span `j` as [`Knots::add_one`] does (`nd/2` parameters before the
    /// knot, `nd − nd/2 − 1` after) keeps both ends' deficits within [`END_DEFICIT_MAX`].
    fn split_keeps_ends(&self, j: usize) -> bool {
        let nd = self.nrdata[j];
        let (before, after) = (nd / 2, nd.saturating_sub(nd / 2 + 1));
        let (head, tail) = (&self.nrdata[..j], &self.nrdata[j + 1..]);
        let front = head.iter().copied().chain([before, after]);
        let back = tail.iter().rev().copied().chain([after, before]);
        let front = end_deficit(front.chain(tail.iter().copied()), self.end_keep).0;
        let back = end_deficit(back.chain(head.iter().rev().copied()), self.end_keep).0;
        front <= END_DEFICIT_MAX && back <= END_DEFICIT_MAX
    }
}

/// The largest [`end_deficit`] the knot rounds allow at either end.
const END_DEFICIT_MAX: usize = 1;

/// The Schoenberg–Whitney deficit at a clamped end, and the number of spans read: with `c_r`
/// the distinct parameters strictly inside the `r` spans nearest the end (`counts` in that
/// order), `Σ_r max(0, e − c_r)` over `r` until `c_r ≥ e`, where `e = ⌊(k − 1)/2⌋`.
///
/// Knots sit at parameters, so every span may end up without one strictly inside. A window
/// of `q` B-splines away from the ends still holds `k − 1` parameters more than it has
/// B-splines (the `q + k − 1` knots inside its support), but the window of the B-splines on
/// the `r` spans nearest a clamped end holds only `c_r` more: the end's `k + 1` knots carry
/// one parameter. The knots of interpolation keep `c_r = e`, each B-spline meeting a parameter
/// at a middle knot of its support. Each unit of deficit shifts the B-splines of a window one
/// parameter towards their first knot, where they are small (`1/k!` beside it on equal spans
/// against a peak of 0.55 for `k = 5`), and the least-squares problem's condition grows by the
/// largest root of the Euler–Frobenius polynomial of the shift (about 3.7 for `k = 3`, 23 for
/// `k = 5` at deficit 2) per span. FITPACK's `fpknot` knows no deficit: on data where the
/// residual stays largest near an end it places a knot at every parameter up to the one
/// beside it, and the triangle is singular to rounding. The rounds allow a deficit of
/// [`END_DEFICIT_MAX`] `= 1`, which keeps FITPACK's knots for `k = 3, 4` when one end span is
/// left empty (`docs/theory/fitting.md#smoothing-condition`).
fn end_deficit(counts: impl Iterator<Item = usize>, e: usize) -> (usize, usize) {
    let (mut c, mut deficit, mut read) = (0usize, 0usize, 0usize);
    for nd in counts {
        if c >= e || deficit > END_DEFICIT_MAX {
            break;
        }
        read += 1;
        c += nd;
        deficit += e.saturating_sub(c);
    }
    (deficit, read)
}

/// Whether a round's least-squares fit, whose residual is `s + fpms`, is the answer as it
/// stands: its residual is within `acc = SMOOTHING_RTOL·s` of `s` on either side,
/// `|fp − s| < acc` (FITPACK `fpcurf`, `fppara`, `fpperi`, `fpclos`, `fpregr`, `fpspgr`:
/// `abs(fpms).lt.acc`; SciPy's `generate_knots` alike). Such a fit may lie above `s`, by less
/// than `acc`; with `s = 0` (`acc = 0`) none is.
pub(crate) fn accepts_least_squares(fpms: f64, acc: f64) -> bool {
    fpms.abs() < acc
}

/// FITPACK's number of knots to add next: `min(2·nplus, max(⌊nplus·fpms/decrease⌋,
/// nplus/2, 1))`, doubling when the last round decreased the residual by less than `acc`.
pub(crate) fn next_nplus(nplus: usize, fpms: f64, decrease: f64, acc: f64) -> usize {
    let npl1 = if decrease > acc {
        // FITPACK truncates the real quotient to an integer
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let v = (nplus as f64 * fpms / decrease).min(1e9) as usize;
        v
    } else {
        nplus * 2
    };
    (nplus * 2).min(npl1.max(nplus / 2).max(1))
}

#[cfg(test)]
mod tests {
    use super::end_deficit;

    #[test]
    fn end_deficit_sums_the_missing_parameters_until_the_end_holds_enough() {
        // e = 0 (degree ≤ 2): nothing to keep, nothing read
        assert_eq!(end_deficit([0, 0, 4].into_iter(), 0), (0, 0));
        // enough in the end span
        assert_eq!(end_deficit([3, 0, 0].into_iter(), 2), (0, 1));
        // cubic, one empty end span (FITPACK's knots): deficit 1, enough one span in
        assert_eq!(end_deficit([0, 2, 0].into_iter(), 1), (1, 2));
        // quintic, one parameter in each of the two spans nearest the end: 1, then enough
        assert_eq!(end_deficit([1, 1, 0].into_iter(), 2), (1, 2));
        // quintic, knots at every parameter up to the end: the reading stops once above 1
        assert_eq!(end_deficit([0, 0, 0, 0].into_iter(), 2), (2, 1));
        assert_eq!(end_deficit([1, 0, 0].into_iter(), 2), (2, 2));
    }
}
