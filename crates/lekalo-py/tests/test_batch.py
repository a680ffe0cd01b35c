"""The batch API: many curves from flat arrays plus offsets."""

import numpy as np
import pytest
from scipy import interpolate as si

import lekalo

RNG = np.random.default_rng(3)


def ragged(n_curves, lo=4, hi=30, dim=2):
    lengths = RNG.integers(lo, hi, n_curves)
    offsets = lekalo.ragged_offsets(lengths)
    pts = RNG.standard_normal((offsets[-1], dim))
    return pts, offsets


def test_batch_equals_one_by_one():
    pts, off = ragged(200)
    b = lekalo.interpolate_batch(pts, off, 3)
    curves = lekalo.curves_from_batch(b)
    assert len(curves) == 200
    for i in (0, 17, 199):
        one = lekalo.interpolate(pts[off[i]:off[i + 1]], 3)
        assert one == curves[i]
    # round trip through the ragged form
    again = lekalo.curves_to_batch(curves)
    for key in ("knots", "knot_offsets", "control", "control_offsets"):
        assert np.array_equal(again[key], b[key])


def test_batch_independent_of_thread_count():
    pts, off = ragged(500)
    results = [lekalo.interpolate_batch(pts, off, 3, threads=n) for n in (1, 2, 3)]
    for r in results[1:]:
        for key in ("knots", "knot_offsets", "control", "control_offsets"):
            assert np.array_equal(r[key], results[0][key])
    t = np.concatenate([np.linspace(0, 1, 7)] * 500)
    t_off = lekalo.ragged_offsets([7] * 500)
    b = results[0]
    ev = [
        lekalo.evaluate_batch(3, b["knots"], b["knot_offsets"], b["control"], b["control_offsets"], t, t_off, threads=n)
        for n in (1, 2)
    ]
    assert np.array_equal(ev[0], ev[1])
    # evaluation at the chord-length parameters returns the data
    for i in (0, 499):
        p = pts[off[i]:off[i + 1]]
        c = lekalo.curves_from_batch(b)[i]
        assert np.allclose(c(lekalo.parametrize(p)), p, atol=1e-12)
        assert np.array_equal(ev[0][7 * i:7 * i + 7], c(np.linspace(0, 1, 7)))


def test_batch_functions_like_make_interp_spline():
    # y(x) curves: the points are values; uniform parameters are the abscissae linspace(0, 1);
    # the natural cubic (knots at the parameters) is make_interp_spline's bc_type="natural"
    n, m = 50, 20
    x = np.linspace(0, 1, m)
    ys = RNG.standard_normal((n, m))
    b = lekalo.interpolate_batch(ys.reshape(-1, 1), lekalo.ragged_offsets([m] * n), 3, parametrization="uniform", end="natural")
    curves = lekalo.curves_from_batch(b)
    xx = np.linspace(0, 1, 101)
    for i in (0, 49):
        ref = si.make_interp_spline(x, ys[i], k=3, bc_type="natural")
        assert np.allclose(curves[i](xx)[:, 0], ref(xx), atol=1e-11)


@pytest.mark.parametrize(
    "offsets, match",
    [
        ([1, 5], "start at 0"),
        ([0, 5, 3, 10], "non-decreasing"),
        ([0, 5], "last offset"),
        (np.array([0, 10], dtype=np.float64), "not int64"),
        # an int64 array of the wrong shape was refused as "dtype int64 is not int64"
        (np.array([[0, 5], [5, 10]], dtype=np.int64), r"1-D array of offsets, got 2 dimensions \(shape \[2, 2\]\)"),
        (np.array(10, dtype=np.int64), "1-D array of offsets, got 0 dimensions"),
        ([0, 1, 10], "curve 0"),
    ],
)
def test_batch_errors(offsets, match):
    pts = RNG.standard_normal((10, 2))
    with pytest.raises(lekalo.Error, match=match):
        lekalo.interpolate_batch(pts, offsets, 3)


def test_batch_names_the_failing_curve():
    pts = RNG.standard_normal((20, 2))
    pts[13] = np.nan
    with pytest.raises(lekalo.Error, match="finite"):
        lekalo.interpolate_batch(pts, [0, 10, 20], 3)
    pts = RNG.standard_normal((20, 2))
    pts[12] = pts[11]
    pts[13] = pts[11]
    with pytest.raises(lekalo.Error, match=r"curve 1 \(rows 10\.\.20\): points 1 and 2 coincide"):
        lekalo.interpolate_batch(pts, [0, 10, 20], 3)


def test_thread_counts_above_the_machine_are_lowered():
    # threads=2**40 started threads until the machine stopped answering
    pts, off = ragged(20)
    want = lekalo.interpolate_batch(pts, off, 3, threads=1)
    got = lekalo.interpolate_batch(pts, off, 3, threads=2**40)
    for key in ("knots", "knot_offsets", "control", "control_offsets"):
        assert np.array_equal(got[key], want[key])


@pytest.mark.parametrize(
    "lengths, match",
    [
        ([3, 2.5], r"lengths\[1\] is 2\.5: a group length is a whole number"),
        (np.array([1.0, np.nan]), r"lengths\[1\] is nan"),
        ([1, -2], r"lengths\[1\] is -2: every group length must be >= 0"),
        (np.array([4, -1], dtype=np.int64), r"lengths\[1\] is -1"),
        ([2**62, 2**62], r"the total 9223372036854775808 is beyond"),
        (np.array([2**63, 1], dtype=np.uint64), r"is beyond the largest int64 offset"),
        ([2**70], r"is beyond the largest int64 offset"),
        ([True, 2], r"lengths\[0\] is True"),
        (np.zeros((2, 2), dtype=np.int64), r"1-D sequence"),
    ],
)
def test_ragged_offsets_refuses_what_it_cannot_represent(lengths, match):
    # huge lengths wrapped around to negative offsets and 2.5 was silently truncated to 2
    with pytest.raises(lekalo.Error, match=match):
        lekalo.ragged_offsets(lengths)


def test_ragged_offsets_accepts_whole_numbers_of_any_form():
    want = [0, 3, 5, 5]
    assert lekalo.ragged_offsets([3, 2, 0]).tolist() == want
    assert lekalo.ragged_offsets([3.0, 2.0, 0.0]).tolist() == want
    assert lekalo.ragged_offsets(np.array([3, 2, 0], dtype=np.uint8)).tolist() == want
    assert lekalo.ragged_offsets(x for x in (3, 2, 0)).tolist() == want
    assert lekalo.ragged_offsets([]).tolist() == [0]
