"""``fit_tensor_grid`` and ``fit_tensor_scattered``: least squares in N variables with given
knots, against SciPy's ``LSQBivariateSpline`` (N = 2, scattered and gridded data),
``make_lsq_spline`` applied along each axis (N = 3 grids) and a dense least-squares solve of
the design matrix built from ``BSpline.design_matrix`` (N = 3 scattered data, with and without a
second-difference penalty)."""

import numpy as np
import pytest

import lekalo

interpolate = pytest.importorskip("scipy.interpolate")

RTOL = 1e-10


def close(a, b, rtol=RTOL):
    scale = max(1.0, float(np.max(np.abs(b))))
    np.testing.assert_allclose(a, b, rtol=0, atol=rtol * scale)


def clamped(k, inner, lo=0.0, hi=1.0):
    return np.concatenate([np.full(k + 1, lo), np.asarray(inner, float), np.full(k + 1, hi)])


def test_grid_fit_matches_lsqbivariatespline_on_the_grid_points():
    rng = np.random.default_rng(1)
    x = np.sort(rng.uniform(0, 1, 14))
    y = np.sort(rng.uniform(0, 1, 11))
    x[0], x[-1], y[0], y[-1] = 0.0, 1.0, 0.0, 1.0
    z = np.sin(3 * x)[:, None] * np.cos(2 * y)[None, :] + 0.01 * rng.standard_normal((14, 11))
    tx, ty = [0.3, 0.55, 0.8], [0.4, 0.7]
    t = [clamped(3, tx), clamped(2, ty)]
    s = lekalo.fit_tensor_grid([x, y], z, t, k=(3, 2))
    assert s.c.shape == (7, 5)
    X, Y = np.meshgrid(x, y, indexing="ij")
    ref = interpolate.LSQBivariateSpline(X.ravel(), Y.ravel(), z.ravel(), tx, ty, bbox=[0, 1, 0, 1], kx=3, ky=2)
    close(s.c.ravel(), ref.get_coeffs())
    close(s(np.stack([X, Y], axis=-1)), ref.ev(X, Y))


def test_grid_fit_is_make_lsq_spline_along_each_axis_with_vector_values():
    rng = np.random.default_rng(2)
    axes = [np.linspace(0, 1, m) ** 1.3 for m in (12, 9, 10)]
    values = rng.standard_normal((12, 9, 10, 2))
    k = (3, 2, 1)
    t = [clamped(3, [0.35, 0.6]), clamped(2, [0.5]), clamped(1, [0.25, 0.5, 0.75])]
    s = lekalo.fit_tensor_grid(axes, values, t, k=k)
    c = values
    for a in reversed(range(3)):
        # SciPy keeps the fitted axis first in ``c``
        c = np.moveaxis(interpolate.make_lsq_spline(axes[a], c, t[a], k=k[a], axis=a).c, 0, a)
    assert s.c.shape == c.shape == (6, 4, 5, 2)
    close(s.c, c)
    # a degree for every axis at once, and the default cubic
    cubic = [clamped(3, [0.5])] * 3
    close(lekalo.fit_tensor_grid(axes, values, cubic).c, lekalo.fit_tensor_grid(axes, values, cubic, k=3).c)


def test_scattered_fit_matches_lsqbivariatespline_with_weights():
    rng = np.random.default_rng(3)
    pts = rng.uniform(0, 1, (400, 2))
    z = np.exp(-pts[:, 0]) * np.sin(4 * pts[:, 1]) + 0.02 * rng.standard_normal(400)
    w = rng.uniform(0.5, 2.0, 400)
    tx, ty = [0.25, 0.5, 0.75], [0.33, 0.66]
    s, residuals, rss = lekalo.fit_tensor_scattered(
        pts, z, [clamped(3, tx), clamped(3, ty)], k=3, w=w
    )
    # FITPACK minimises Σ (w_k r_k)², lekalo Σ w_k r_k²: FITPACK's weights are their roots
    ref = interpolate.LSQBivariateSpline(pts[:, 0], pts[:, 1], z, tx, ty, w=np.sqrt(w), bbox=[0, 1, 0, 1], kx=3, ky=3)
    close(s.c.ravel(), ref.get_coeffs(), 1e-9)
    fitted = ref.ev(pts[:, 0], pts[:, 1])
    close(residuals, np.abs(fitted - z), 1e-9)
    assert rss == pytest.approx(ref.get_residual(), rel=1e-9)


def design_matrix(x, t, k):
    """Row-wise Kronecker product of the per-axis design matrices (first variable slowest)."""
    rows = None
    for a in range(x.shape[1]):
        d = interpolate.BSpline.design_matrix(x[:, a], t[a], k[a]).toarray()
        rows = d if rows is None else (rows[:, :, None] * d[:, None, :]).reshape(len(x), -1)
    return rows


def test_scattered_fit_in_three_variables_is_the_least_squares_solution():
    rng = np.random.default_rng(4)
    x = rng.uniform(-1, 2, (1500, 3))
    y = np.stack([np.cos(x[:, 0] * x[:, 1]) + x[:, 2] ** 3, x.sum(axis=1)], axis=-1)
    k = (2, 3, 1)
    t = [clamped(2, [0.0, 1.0], -1, 2), clamped(3, [0.5], -1, 2), clamped(1, [-0.5, 0.5, 1.5], -1, 2)]
    s, residuals, rss = lekalo.fit_tensor_scattered(x, y, t, k=k)
    assert s.c.shape == (5, 5, 5, 2) and residuals.shape == (1500,)
    a = design_matrix(x, t, k)
    c, *_ = np.linalg.lstsq(a, y, rcond=None)
    close(s.c.reshape(-1, 2), c, 1e-9)
    assert rss == pytest.approx(float(np.sum((a @ c - y) ** 2)), rel=1e-9)
    # the sum of x lies in the space: its column is reproduced
    close(s(x)[:, 1], y[:, 1], 1e-11)


def second_differences(shape):
    """The second differences of a net of ``shape`` (first variable slowest) along every axis
    with at least three control points, one row each."""
    rows = []
    index = np.arange(int(np.prod(shape))).reshape(shape)
    for a, n in enumerate(shape):
        for j in range(n - 2):
            ids = [np.take(index, j + d, axis=a).ravel() for d in range(3)]
            for i0, i1, i2 in zip(*ids):
                r = np.zeros(index.size)
                r[[i0, i1, i2]] = (1.0, -2.0, 1.0)
                rows.append(r)
    return np.array(rows)


def test_penalty_fills_cells_without_data_in_three_variables():
    rng = np.random.default_rng(6)
    x = rng.uniform(-1, 2, (900, 3))
    x = x[(x[:, 0] < 0.5) | (x[:, 1] < 0.0)]  # nothing in x0 > 0.5, x1 > 0
    y = 1e8 + np.cos(x[:, 0] * x[:, 1]) + x[:, 2] ** 2
    k = (2, 3, 1)
    t = [clamped(2, [0.0, 1.0], -1, 2), clamped(3, [0.5], -1, 2), clamped(1, [-0.5, 0.5, 1.5], -1, 2)]
    with pytest.raises(lekalo.InputError, match="holds 0 data points"):
        lekalo.fit_tensor_scattered(x, y, t, k=k)
    lam = 0.3
    s, residuals, rss = lekalo.fit_tensor_scattered(x, y, t, k=k, penalty=lam)
    # the least squares of the data stacked on sqrt(penalty) times the second differences
    a = np.vstack([design_matrix(x, t, k), np.sqrt(lam) * second_differences(s.c.shape)])
    rhs = np.concatenate([y - 1e8, np.zeros(len(a) - len(y))])
    c, *_ = np.linalg.lstsq(a, rhs, rcond=None)
    # lekalo fits the data as given, offset included: the agreement is bounded by the rounding
    # of the offset (eps·1e8 ≈ 2e-8 a value), so it is measured against the data's scale
    np.testing.assert_allclose(s.c.ravel() - 1e8, c, rtol=0, atol=1e-14 * 1e8)
    close(residuals, np.abs(s(x) - y), 1e-6)
    # two variables: the penalty of the scattered surface fit
    pts = x[:, :2]
    t2 = [clamped(2, [0.0, 1.0], -1, 2), clamped(1, [-0.5, 0.5, 1.5], -1, 2)]
    s2, _, rss2 = lekalo.fit_tensor_scattered(pts, y, t2, k=(2, 1), penalty=lam)
    surf, _, rss_surf = lekalo.fit_surface_scattered(np.column_stack([pts, y]), t2[0], t2[1], (2, 1), penalty=lam)
    close(s2.c.ravel(), np.asarray(surf.control).ravel(), 1e-12)
    with pytest.raises(lekalo.InputError, match="^penalty: "):
        lekalo.fit_tensor_scattered(x, y, t, k=k, penalty=-1.0)
    with pytest.raises(lekalo.InputError, match="^penalty: .*eps"):
        lekalo.fit_tensor_scattered(x, y, t, k=k, penalty=1.0, eps=1e-16)


def test_fit_errors_name_the_argument():
    t = [clamped(1, [0.5])] * 2
    x = np.random.default_rng(5).uniform(0, 1, (50, 2))
    z = x.sum(axis=1)
    with pytest.raises(lekalo.InputError, match="^x: shape"):
        lekalo.fit_tensor_scattered(x.ravel(), z, t, k=1)
    with pytest.raises(lekalo.InputError, match="^t: 1 knot vectors"):
        lekalo.fit_tensor_scattered(x, z, t[:1], k=1)
    with pytest.raises(lekalo.InputError, match="^y: shape"):
        lekalo.fit_tensor_scattered(x, np.zeros(10), t, k=1)
    with pytest.raises(lekalo.InputError, match="^x: .*outside the domain|^x: "):
        lekalo.fit_tensor_scattered(x + 1.0, z, t, k=1)
    with pytest.raises(lekalo.InputError, match="^w: "):
        lekalo.fit_tensor_scattered(x, z, t, k=1, w=-np.ones(50))
    with pytest.raises(lekalo.InputError, match=r"^t\[1\]: "):
        lekalo.fit_tensor_scattered(x, x[:, 0], [t[0], [1.0, 0.0]], k=1)
    # a region without data is named with the control point and its support
    corner = x[(x[:, 0] < 0.5) | (x[:, 1] < 0.5)]
    zc = corner.sum(axis=1)
    with pytest.raises(lekalo.InputError, match=r"control point \[2, 2\] .* \[0.5, 1\] × \[0.5, 1\] holds 0"):
        lekalo.fit_tensor_scattered(corner, zc, t, k=1)
    axes = [np.linspace(0, 1, 6), np.linspace(0, 1, 5)]
    with pytest.raises(lekalo.InputError, match="^values: shape"):
        lekalo.fit_tensor_grid(axes, np.zeros((5, 6)), t, k=1)
    with pytest.raises(lekalo.InputError, match="^k: "):
        lekalo.fit_tensor_grid(axes, np.zeros((6, 5)), t, k=(1, 1, 1))
    with pytest.raises(lekalo.InputError, match="^axes: "):
        lekalo.fit_tensor_grid([np.linspace(1, 0, 6), axes[1]], np.zeros((6, 5)), t, k=1)
