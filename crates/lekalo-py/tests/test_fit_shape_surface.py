"""Shape-constrained surface fits from Python: the keyword arguments of fit_surface_grid and
fit_surface_scattered reach the library and return the usual surface; bad arguments and
contradictory bounds raise lekalo.InputError. (The mathematics is tested in the Rust core.)"""

import numpy as np
import pytest

import lekalo

U = np.linspace(0.0, 1.0, 16)
V = np.linspace(0.0, 1.0, 12)
I, J = np.meshgrid(np.arange(16), np.arange(12), indexing="ij")
UU, VV = np.meshgrid(U, V, indexing="ij")
Z = UU + 0.5 * VV**2 + 0.25 * np.sin(9 * UU) + 0.15 * np.sin(1.7 * (7 * I + 3 * J))
TU = [0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1]
TV = [0, 0, 0, 1 / 3, 2 / 3, 1, 1, 1]
FINE = np.linspace(0.0, 1.0, 101)


def dense(s):
    fu, fv = np.meshgrid(FINE, FINE, indexing="ij")
    return s(fu.ravel(), fv.ravel()).reshape(101, 101)


def test_grid_increasing_in_both_directions():
    grid = Z[:, :, None]
    free = lekalo.fit_surface_grid(grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV)
    assert (np.diff(dense(free), axis=0) < 0).any()
    for increasing in (True, ("u", "v"), ["v", "u"]):
        s = lekalo.fit_surface_grid(grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV, increasing=increasing)
        assert isinstance(s, lekalo.BSplineSurface)
        z = dense(s)
        assert (np.diff(z, axis=0) >= -1e-12).all()
        assert (np.diff(z, axis=1) >= -1e-12).all()


def test_grid_one_direction_and_bounds():
    grid = Z[:, :, None]
    s = lekalo.fit_surface_grid(grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV, increasing="u", min=0.0, max=1.2)
    z = dense(s)
    assert (np.diff(z, axis=0) >= -1e-12).all()
    assert z.min() >= -1e-12 and z.max() <= 1.2 + 1e-12
    s = lekalo.fit_surface_grid(-grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV, decreasing="u")
    assert (np.diff(dense(s), axis=0) <= 1e-12).all()


def test_inactive_constraints_change_nothing():
    grid = (UU + VV)[:, :, None]
    free = lekalo.fit_surface_grid(grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV)
    s = lekalo.fit_surface_grid(grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV, increasing=True, min=-1.0)
    np.testing.assert_allclose(dense(s), dense(free), rtol=0, atol=1e-12)


def test_scattered_bounds_and_monotone():
    rng = np.random.default_rng(3)
    u, v = rng.random(300), rng.random(300)
    z = u * (1 - v) + 0.2 * np.sin(31 * np.arange(300))
    data = np.column_stack([u, v, z])
    t = [0, 0, 0, 0, 0.4, 0.7, 1, 1, 1, 1]
    free, _, rss0 = lekalo.fit_surface_scattered(data, t, t)
    s, res, rss = lekalo.fit_surface_scattered(data, t, t, decreasing="v", min=0.0, penalty=1e-3)
    zz = dense(s)
    assert zz.min() >= -1e-12
    assert (np.diff(zz, axis=1) <= 1e-12).all()
    assert res.shape == (300,) and rss >= rss0 - 1e-9


def test_bad_arguments_and_contradictions():
    grid = Z[:, :, None]
    with pytest.raises(lekalo.InputError, match="min 2"):
        lekalo.fit_surface_grid(grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV, min=2.0, max=1.0)
    with pytest.raises(lekalo.InputError, match="increasing"):
        lekalo.fit_surface_grid(grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV, increasing="w")
    with pytest.raises(lekalo.InputError, match="u= and v="):
        lekalo.fit_surface_grid(grid, (6, 5), degree=(2, 2), increasing=True)
    with pytest.raises(lekalo.InputError, match="min"):
        lekalo.fit_surface_grid(grid, degree=(2, 2), u=U, v=V, tu=TU, tv=TV, min="low")


def test_shapes_on_boxes_hold_there_only():
    # a valley in u: falling left of u = 0.4, rising after
    u, v = np.linspace(0.0, 1.0, 21), np.linspace(0.0, 1.0, 11)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    z = (uu - 0.4) ** 2 + 0.3 * vv + 0.08 * np.sin(23 * uu + 5 * vv)
    tu = [0, 0, 0, 1 / 7, 2 / 7, 3 / 7, 4 / 7, 5 / 7, 6 / 7, 1, 1, 1]
    tv = [0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1]
    fit = lambda **kw: lekalo.fit_surface_grid(z[:, :, None], degree=(2, 2), u=u, v=v, tu=tu, tv=tv, **kw)
    fu, fv = np.meshgrid(np.linspace(0.45, 1.0, 56), np.linspace(0.1, 0.9, 41), indexing="ij")
    inside = lambda s: s(fu.ravel(), fv.ravel()).reshape(fu.shape)
    free = fit()
    assert (np.diff(inside(free), axis=0) < -1e-3).any()
    for increasing in (("u", (0.45, 1.0), (0.1, 0.9)), [("u", (0.45, 1.0), (0.1, 0.9))]):
        s = fit(increasing=increasing, min=[(0.05, (0.3, 0.5), (0.0, 1.0))])
        assert (np.diff(inside(s), axis=0) >= -1e-12).all()
        gu, gv = np.meshgrid(np.linspace(0.3, 0.5, 41), FINE, indexing="ij")
        assert s(gu.ravel(), gv.ravel()).min() >= 0.05 - 1e-12
        # left of the box the fit still falls in u, as the data do
        assert s(0.3, 0.5)[0] < s(0.05, 0.5)[0]
    # a box leaving the domain, and a list of unboxed bounds, are refused with the fix
    with pytest.raises(lekalo.InputError, match="leaves the domain"):
        fit(min=(0.0, (0.0, 2.0), (0.0, 1.0)))
    with pytest.raises(lekalo.InputError, match="list of boxed bounds"):
        fit(min=(0.0, 0.5))
    with pytest.raises(lekalo.InputError, match="on a box"):
        fit(increasing=("u", (0.0, 1.0)))


def dense_tensor(s):
    fu, fv = np.meshgrid(FINE, FINE, indexing="ij")
    return s(np.column_stack([fu.ravel(), fv.ravel()])).reshape(101, 101)


def test_grid_smoothing_spline_keeps_shapes():
    free, r0 = lekalo.fit_tensor_grid_smoothing_spline([U, V], Z, lam=[1e-5, 1e-4])
    assert (np.diff(dense_tensor(free), axis=0) < -1e-3).any()
    s, r = lekalo.fit_tensor_grid_smoothing_spline([U, V], Z, lam=[1e-5, 1e-4], increasing="u", max=1.6)
    assert isinstance(s, lekalo.TensorBSpline)
    z = dense_tensor(s)
    assert (np.diff(z, axis=0) >= -1e-12).all()
    assert z.max() <= 1.6 + 1e-12
    # the weights given; the residual rises
    assert r["lam"] == [1e-5, 1e-4]
    assert r["residual"] > r0["residual"]
    assert r["gcv"] is None and r["trace"] is None
    # the residual reported is the spline's at the nodes
    nodes = s(np.column_stack([UU.ravel(), VV.ravel()])).reshape(Z.shape)
    assert r["residual"] == pytest.approx(((nodes - Z) ** 2).sum(), rel=1e-12)


def test_grid_smoothing_inactive_shapes_change_nothing():
    z = 1.0 + UU + UU * VV + 0.3 * VV + 0.003 * np.sin(2.3 * (12 * I + J))
    free, r0 = lekalo.fit_tensor_grid_smoothing_spline([U, V], z, lam=[1e-3, 1e-2])
    s, r = lekalo.fit_tensor_grid_smoothing_spline([U, V], z, lam=[1e-3, 1e-2], increasing=True, min=0.5)
    np.testing.assert_allclose(dense_tensor(s), dense_tensor(free), rtol=0, atol=1e-12)
    assert r["residual"] == r0["residual"]


def test_grid_smoothing_condition_in_shape():
    # a 14 x 10 table, where the weights the condition needs keep the program well enough
    # conditioned to solve
    u, v = np.linspace(0.0, 1.0, 14), np.linspace(0.0, 1.0, 10)
    i, j = np.meshgrid(np.arange(14), np.arange(10), indexing="ij")
    uu, vv = np.meshgrid(u, v, indexing="ij")
    z = uu + 0.5 * vv**2 + 0.25 * np.sin(9 * uu) + 0.15 * np.sin(1.7 * (7 * i + 3 * j))
    _, gcv = lekalo.fit_tensor_grid_smoothing_spline([u, v], z, increasing="u")
    target = 1.3 * gcv["residual"]
    s, r = lekalo.fit_tensor_grid_smoothing_spline([u, v], z, s=target, increasing="u")
    assert abs(r["residual"] - target) <= 1e-3 * target
    assert (np.diff(dense_tensor(s), axis=0) >= -1e-12).all()
    # the weights keep GCV's ratio
    assert r["lam"][0] / r["lam"][1] == pytest.approx(gcv["lam"][0] / gcv["lam"][1], rel=1e-12)


def test_grid_smoothing_heavy_weight_keeps_the_shape():
    # a weight far heavier than the data in v: solved in whitened variables, the shape exact
    s, r = lekalo.fit_tensor_grid_smoothing_spline([U, V], Z, lam=[1e-4, 6e4], increasing="u")
    assert r["lam"] == pytest.approx([1e-4, 6e4], rel=1e-15)
    assert (np.diff(dense_tensor(s), axis=0) >= -1e-12).all()


def test_grid_smoothing_refusals_name_the_argument():
    with pytest.raises(lekalo.InputError, match="lam"):
        lekalo.fit_tensor_grid_smoothing_spline([U, V], Z, lam=0.0, increasing="u")
    with pytest.raises(lekalo.InputError, match="give one"):
        lekalo.fit_tensor_grid_smoothing_spline([U, V], Z, lam=1e-3, s=1.0, increasing="u")
    with pytest.raises(lekalo.InputError, match="s:"):
        lekalo.fit_tensor_grid_smoothing_spline([U, V], Z, s=1.0)
    with pytest.raises(lekalo.InputError, match="give s ≥"):
        lekalo.fit_tensor_grid_smoothing_spline([U, V], Z, s=1e-9, max=0.0)
    w = np.linspace(0, 1, 5)
    with pytest.raises(lekalo.InputError, match="two axes"):
        lekalo.fit_tensor_grid_smoothing_spline([U, V, w], np.zeros((16, 12, 5)), increasing="u")
