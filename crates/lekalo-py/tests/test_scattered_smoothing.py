"""``fit_tensor_scattered_smoothing`` (FITPACK's ``surfit`` in N variables) and the minimal-norm
answer of ``fit_tensor_scattered`` to a rank-deficient system, against SciPy's
``SmoothBivariateSpline``, ``LSQBivariateSpline`` and ``bisplrep`` on the same data: the same
knots, a residual within FITPACK's tolerance of ``s`` (never above it), FITPACK's least-squares
splines and minimal-norm coefficients to rounding, and SciPy's warnings."""

import warnings

import numpy as np
import pytest

import lekalo
import lekalo.scipy as ls

interpolate = pytest.importorskip("scipy.interpolate")


def data(seed, m=200):
    rng = np.random.default_rng(seed)
    x = rng.uniform(0.0, 1.0, m)
    y = rng.uniform(-1.0, 2.0, m)
    z = np.sin(3 * x) * np.cos(2 * y) + 0.05 * rng.standard_normal(m)
    return x, y, z


def quiet(f, *args, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = f(*args, **kw)
    return out, [str(w.message) for w in caught]


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("s", [None, 0.2, 0.5, 2.0])
@pytest.mark.parametrize("k", [(3, 3), (1, 2), (2, 3), (3, 1)])
def test_knots_and_residual_are_fitpacks(seed, s, k):
    x, y, z = data(seed)
    ref, ref_warn = quiet(interpolate.SmoothBivariateSpline, x, y, z, kx=k[0], ky=k[1], s=s)
    ours, our_warn = quiet(ls.SmoothBivariateSpline, x, y, z, kx=k[0], ky=k[1], s=s)
    for a, b in zip(ours.get_knots(), ref.get_knots()):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)
    # SciPy's first call of surfit gives FITPACK too little workspace for a rank-deficient
    # system and calls again with more; when that is still too little its warning is "ier=N"
    # (N > 10) and its coefficients are those of the previous knots: nothing to compare
    scipy_failed = any(w.startswith("ier=") and int(w[4:]) > 10 for w in ref_warn)
    assert len(our_warn) == len(ref_warn) or scipy_failed
    target = len(x) if s is None else s
    fp = ours.get_residual()
    assert abs(fp - ((ours.ev(x, y) - z) ** 2).sum()) <= 1e-10 * max(fp, 1.0)
    xi, yi = np.linspace(0, 1, 9), np.linspace(-1, 2, 7)
    if scipy_failed:
        assert our_warn
    elif abs(ref.get_residual() - target) > 1e-3 * target:
        # a least-squares spline (the polynomial, or FITPACK stopped adding knots): FITPACK's own
        np.testing.assert_allclose(fp, ref.get_residual(), rtol=1e-10)
        np.testing.assert_allclose(ours(xi, yi), ref(xi, yi), rtol=0, atol=1e-10)
    else:
        # FITPACK stops within 0.001·s of s on either side; lekalo within 0.001·s below it
        assert (1 - 1e-3) * target <= fp <= target


def test_native_api_three_variables_and_vector_values():
    rng = np.random.default_rng(7)
    x = rng.uniform(0.0, 1.0, (600, 3))
    y = np.stack([np.sin(2 * x[:, 0]) + x[:, 1] * x[:, 2], x.sum(axis=1) ** 2], axis=-1)
    y += 0.01 * rng.standard_normal(y.shape)
    poly, fp0, p0, rank0, limit0 = lekalo.fit_tensor_scattered_smoothing(x, y, 1e9, [2, 2, 1])
    assert (p0, limit0) == (None, None) and poly.c.shape == (3, 3, 2, 2) and rank0 == 18
    s = 0.3 * fp0
    spline, fp, p, rank, limit = lekalo.fit_tensor_scattered_smoothing(x, y, s, [2, 2, 1], eps=1e-16)
    assert fp <= s and limit is None
    assert abs(fp - ((spline(x) - y) ** 2).sum()) <= 1e-10 * fp
    assert p is None or fp >= (1 - 1e-3) * s
    assert rank == np.prod(spline.c.shape[:3])
    with pytest.raises(lekalo.InputError, match="s"):
        lekalo.fit_tensor_scattered_smoothing(x, y, -1.0)
    with pytest.raises(lekalo.InputError, match="eps"):
        lekalo.fit_tensor_scattered_smoothing(x, y, 1.0, eps=2.0)
    with pytest.raises(lekalo.InputError, match="max_knots"):
        lekalo.fit_tensor_scattered_smoothing(x, y, 1.0, [3, 3, 3], max_knots=[8, 8, 7])


def test_the_knot_bound_is_reported():
    x, y, z = data(3)
    pts = np.stack([x, y], axis=-1)
    _, fp, p, _, limit = lekalo.fit_tensor_scattered_smoothing(pts, z, 1e-6, max_knots=[9, 9])
    assert (p, limit) == (None, "max-knots") and fp > 1e-6


def test_rank_deficiency_is_refused_or_minimal_norm_as_fitpack():
    # points on the diagonal: most control points of the cubic net are undetermined
    x = np.concatenate(list(zip(range(10), range(10)))).astype(float)
    y = np.concatenate(list(zip(range(10), range(1, 11)))).astype(float)
    z = np.concatenate((np.linspace(3, 1, 10), np.linspace(1, 3, 10)))
    tx = np.linspace(0.5, 19.5, 4)
    ty = np.linspace(1.5, 20.5, 4)
    with pytest.warns(UserWarning, match="deficiency=54"):
        ref = interpolate.LSQBivariateSpline(x, y, z, tx, ty, eps=1e-2)
    with pytest.warns(UserWarning, match="deficiency=54"):
        ours = ls.LSQBivariateSpline(x, y, z, tx, ty, eps=1e-2)
    for a, b in zip(ours.get_knots(), ref.get_knots()):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ours.get_coeffs(), ref.get_coeffs(), rtol=0, atol=1e-9)
    np.testing.assert_allclose(ours.get_residual(), ref.get_residual(), rtol=1e-9)
    # lekalo's own API refuses the same system unless asked for the minimal-norm solution
    t = [np.r_[[-4.0] * 4, tx, [24.0] * 4], np.r_[[-4.0] * 4, ty, [25.0] * 4]]
    pts = np.stack([x, y], axis=-1)
    with pytest.raises(lekalo.InputError, match="not determined by the data"):
        lekalo.fit_tensor_scattered(pts, z, t)
    _, _, _, rank = lekalo.fit_tensor_scattered(pts, z, t, eps=1e-16, full_output=True)
    assert rank < 64


@pytest.mark.parametrize("s", [0, 5.0, None])
def test_bisplrep_is_fitpacks(s):
    g = np.linspace(0, 2 * np.pi, 15)
    x, y = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    z = np.sin(x + y) + 0.1 * np.cos(3 * x)
    ref, fp_ref, ier_ref, _ = interpolate.bisplrep(x, y, z, s=s, full_output=1)
    ours, fp, ier, _ = ls.bisplrep(x, y, z, s=s, full_output=1)
    assert ier == ier_ref
    for a, b in zip(ours[:2], ref[:2]):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)
    xi = np.linspace(0, 2 * np.pi, 11)
    atol = 1e-8 if ier_ref <= 0 and abs(fp_ref - (s or 0)) > 1e-3 * (s or 1) else 2e-2
    np.testing.assert_allclose(ls.bisplev(xi, xi, ours), interpolate.bisplev(xi, xi, ref), rtol=0, atol=atol)
    # least squares on FITPACK's knots (task=-1)
    n = {"nxest": len(ref[0]), "nyest": len(ref[1])}
    lsq_ref = interpolate.bisplrep(x, y, z, task=-1, tx=ref[0], ty=ref[1], **n)
    lsq = ls.bisplrep(x, y, z, task=-1, tx=ref[0], ty=ref[1], **n)
    np.testing.assert_allclose(lsq[2], lsq_ref[2], rtol=0, atol=1e-8)
