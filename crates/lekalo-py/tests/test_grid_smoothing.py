"""``fit_tensor_grid_smoothing`` (smoothing on grids, FITPACK's ``regrid`` in N directions) and
``TensorBSpline.integral``, against SciPy's ``RectBivariateSpline`` on the same data: the same
knots, a residual within FITPACK's tolerance of ``s`` (never above it), the interpolant and the
polynomial to rounding; and ``lekalo.scipy.RectBivariateSpline`` evaluated, differentiated
and integrated as SciPy's."""

import numpy as np
import pytest

import lekalo
import lekalo.scipy as ls

interpolate = pytest.importorskip("scipy.interpolate")


def data(seed):
    rng = np.random.default_rng(seed)
    x = np.sort(rng.uniform(0.0, 1.0, rng.integers(12, 40)))
    y = np.sort(rng.uniform(0.0, 2.0, rng.integers(12, 30)))
    z = np.sin(3 * x)[:, None] * np.cos(2 * y)[None, :] + 0.05 * rng.standard_normal((x.size, y.size))
    return x, y, z


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("s", [0.01, 0.1, 0.5, 2.0, 10.0])
@pytest.mark.parametrize("k", [(3, 3), (2, 1), (5, 4), (1, 1), (4, 2)])
def test_knots_and_residual_are_fitpacks(seed, s, k):
    x, y, z = data(seed)
    ref = interpolate.RectBivariateSpline(x, y, z, kx=k[0], ky=k[1], s=s)
    spline, fp, p = lekalo.fit_tensor_grid_smoothing([x, y], z, s, list(k))
    tx, ty = ref.get_knots()
    np.testing.assert_array_equal(spline.t[0], tx)
    np.testing.assert_array_equal(spline.t[1], ty)
    # FITPACK stops within 0.001·s of s on either side; lekalo within 0.001·s below it
    assert abs(ref.get_residual() - s) < 1e-3 * s or ref.get_residual() < s
    assert fp <= s
    values = spline.grid(x, y)
    assert abs(fp - ((values - z) ** 2).sum()) <= 1e-12 * max(fp, 1.0)
    if p is None:
        # a least-squares spline (the polynomial or knots already within s): FITPACK's own
        np.testing.assert_allclose(values, ref(x, y), rtol=0, atol=1e-12)
    else:
        assert (1 - 1e-3) * s <= fp


@pytest.mark.parametrize("k", [(3, 3), (2, 4), (1, 5)])
def test_interpolation_is_scipys(k):
    x, y, z = data(5)
    ref = interpolate.RectBivariateSpline(x, y, z, kx=k[0], ky=k[1])
    ours = ls.RectBivariateSpline(x, y, z, kx=k[0], ky=k[1])
    for a, b in zip(ours.get_knots(), ref.get_knots()):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_allclose(ours.get_coeffs(), ref.get_coeffs(), rtol=0, atol=1e-10)
    xi = np.linspace(-0.2, 1.2, 17)  # beyond the box: FITPACK takes the edge
    yi = np.linspace(-0.3, 2.3, 13)
    np.testing.assert_allclose(ours(xi, yi), ref(xi, yi), rtol=0, atol=1e-10)
    np.testing.assert_allclose(ours.ev(xi, yi[:1]), ref.ev(xi, yi[:1]), rtol=0, atol=1e-10)
    for dx, dy in [(1, 0), (0, 1), (1, 1)]:
        if dx < k[0] and dy < k[1]:
            np.testing.assert_allclose(ours(xi, yi, dx=dx, dy=dy), ref(xi, yi, dx=dx, dy=dy), rtol=0, atol=1e-8)
    for box in [(0.1, 0.7, 0.2, 1.9), (0.7, 0.1, -5.0, 5.0), (-1.0, 2.0, -1.0, 3.0)]:
        assert ours.integral(*box) == pytest.approx(ref.integral(*box), abs=1e-12)
    tck = [*ref.get_knots(), ref.get_coeffs(), *k]
    np.testing.assert_allclose(ls.bisplev(xi, yi, tck), interpolate.bisplev(xi, yi, tck), rtol=0, atol=1e-10)


def test_three_directions_and_integral():
    rng = np.random.default_rng(3)
    axes = [np.linspace(0, 1, 11), np.linspace(-1, 1, 9), np.linspace(0, 2, 8)]
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    v = np.sin(2 * X) + Y * Z + 0.01 * rng.standard_normal(X.shape)
    spline, fp, p = lekalo.fit_tensor_grid_smoothing(axes, v, 0.005, [3, 2, 3])
    assert (1 - 1e-3) * 0.005 <= fp <= 0.005 and p is not None
    # ∫∫∫ of the exact x·y·z-free part: the integral of a fit that reproduces a polynomial
    poly, _, _ = lekalo.fit_tensor_grid_smoothing(axes, X * Y * Y + Z, 0.0, 3)
    want = 0.5 * (2 / 3) * 2 + 1 * 2 * 2
    assert poly.integral([(0, 1), (-1, 1), (0, 2)]) == pytest.approx(want, abs=1e-12)


def test_refusals_name_the_argument():
    x, y, z = data(0)
    with pytest.raises(ValueError, match="s"):
        lekalo.fit_tensor_grid_smoothing([x, y], z, -1.0)
    with pytest.raises(ValueError, match="bbox"):
        lekalo.fit_tensor_grid_smoothing([x, y], z, 1.0, bbox=[(0.5, 1.0), (0.0, 2.0)])
    with pytest.raises(ValueError, match="values"):
        lekalo.fit_tensor_grid_smoothing([x, y[1:]], z, 1.0)
