"""``fit_tensor_grid_smoothing_spline`` (the smoothing spline on a grid with a penalty weight per
axis, given or chosen by GCV) and ``tensor_grid_gcv_score``: one axis is ``fit_smoothing``; two
axes are SciPy's ``make_smoothing_spline`` applied along each axis in turn; the weights GCV
chooses score no worse than their neighbours; the arguments are checked by name."""

import numpy as np
import pytest

import lekalo


def grid(seed, shape=(14, 11)):
    """Noisy values on a grid of jittered, well-spread coordinates: each axis's smoothing problem
    is then well conditioned, so that two correct solvers agree to rounding. (With uniform random
    coordinates two of them fall 1e-3 apart, and at a large weight the per-axis problem's
    condition reaches 1e8: SciPy's ``make_smoothing_spline`` and lekalo's own ``fit_smoothing``
    then differ by 2.5e-8 along one axis.)"""
    rng = np.random.default_rng(seed)
    x = (np.arange(shape[0]) + rng.uniform(-0.3, 0.3, shape[0])) / (shape[0] - 1)
    y = -1.0 + 3.0 * (np.arange(shape[1]) + rng.uniform(-0.3, 0.3, shape[1])) / (shape[1] - 1)
    z = np.sin(3 * x)[:, None] * np.cos(y)[None, :] + 0.1 * rng.standard_normal(shape)
    return x, y, z


@pytest.mark.parametrize("lam", [1e-4, 0.3, None])
def test_one_axis_is_the_curve_smoothing_spline(lam):
    rng = np.random.default_rng(3)
    x = np.sort(rng.uniform(0.0, 5.0, 30))
    y = np.stack([np.sin(x), 1e4 + x**2], axis=-1) + 0.05 * rng.standard_normal((30, 2))
    spline, report = lekalo.fit_tensor_grid_smoothing_spline([x], y, lam=lam)
    curve, creport = lekalo.fit_smoothing(x, y, lam=lam)
    assert report["lam"] == [creport["lam"]]
    np.testing.assert_array_equal(spline.c.reshape(-1, 2), curve.control)
    if lam is not None:
        assert lekalo.tensor_grid_gcv_score([x], y, lam) == lekalo.gcv_score(x, y, lam)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("lam", [(1e-3, 1e-2), (0.5, 1e-5), (0.0, 0.1)])
def test_two_axes_are_scipys_smoothing_spline_along_each(seed, lam):
    interpolate = pytest.importorskip("scipy.interpolate")
    x, y, z = grid(seed)
    spline, report = lekalo.fit_tensor_grid_smoothing_spline([x, y], z, lam=list(lam))
    assert report["lam"] == list(lam)

    def along(axis_values, values, l):
        if l == 0.0:
            return values  # interpolation
        return np.stack(
            [interpolate.make_smoothing_spline(axis_values, col, lam=l)(axis_values) for col in values.T],
            axis=1,
        )

    expected = along(y, along(x, z, lam[0]).T, lam[1]).T
    got = spline.grid(x, y)
    assert got.shape == z.shape
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-9 * np.abs(z).max())
    assert report["residual"] == pytest.approx(((got - z) ** 2).sum(), rel=1e-9)


def test_gcv_weights_score_no_worse_than_their_neighbours():
    x, y, z = grid(5, (20, 16))
    spline, report = lekalo.fit_tensor_grid_smoothing_spline([x, y], z)
    lam = report["lam"]
    assert all(l > 0 for l in lam)
    assert lekalo.tensor_grid_gcv_score([x, y], z, lam) == report["gcv"]
    for f0 in (0.5, 1.0, 2.0):
        for f1 in (0.5, 1.0, 2.0):
            score = lekalo.tensor_grid_gcv_score([x, y], z, [lam[0] * f0, lam[1] * f1])
            assert report["gcv"] <= score * (1 + 1e-9)
    # one weight given, the other chosen
    _, half = lekalo.fit_tensor_grid_smoothing_spline([x, y], z, lam=[1e-3, None])
    assert half["lam"][0] == 1e-3 and half["lam"][1] > 0


def test_three_axes_reproduce_multilinear_data():
    x, y, w = np.linspace(0, 1, 6), np.linspace(-1, 1, 5) ** 3, np.linspace(2, 3, 4)
    X, Y, W = np.meshgrid(x, y, w, indexing="ij")
    v = 1e6 + 2 * X - Y * W + 3 * X * Y * W
    spline, _ = lekalo.fit_tensor_grid_smoothing_spline([x, y, w], v, lam=[0.1, 10.0, 1e-3])
    pts = np.array([[0.3, 0.2, 2.5], [0.9, -0.7, 2.1]])
    exact = 1e6 + 2 * pts[:, 0] - pts[:, 1] * pts[:, 2] + 3 * pts.prod(axis=1)
    np.testing.assert_allclose(spline(pts), exact, rtol=1e-13)


def test_arguments_are_named():
    x, y, z = grid(0, (8, 6))
    with pytest.raises(lekalo.InputError, match="lam"):
        lekalo.fit_tensor_grid_smoothing_spline([x, y], z, lam=-1.0)
    with pytest.raises(lekalo.InputError, match="lam: 3 weights for 2 axes"):
        lekalo.fit_tensor_grid_smoothing_spline([x, y], z, lam=[1.0, 1.0, 1.0])
    with pytest.raises(lekalo.InputError, match="lam"):
        lekalo.fit_tensor_grid_smoothing_spline([x, y], z, lam="much")
    with pytest.raises(lekalo.InputError, match="axes"):
        lekalo.fit_tensor_grid_smoothing_spline([x[::-1], y], z, lam=1.0)
    with pytest.raises(lekalo.InputError):
        lekalo.fit_tensor_grid_smoothing_spline([x, y[:2]], z[:, :2], lam=1.0)
    with pytest.raises(lekalo.InputError, match="lam"):
        lekalo.tensor_grid_gcv_score([x, y], z, [1.0, None])
