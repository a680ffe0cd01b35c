"""``lekalo.TensorNurbs``, the rational tensor-product spline in N variables, and its knot
derivatives ``lekalo.tensor_nurbs_knot_jvp`` / ``_vjp``: the values against the quotient of two
``TensorBSpline``s (numerator ``w c``, denominator ``w``), two variables against
``NurbsSurface``, unit weights against the B-spline, the grid against the points, partial
derivatives against central differences, the knot kernels against central differences in the
interior knots and by the adjoint identity, and the errors naming the argument."""

import numpy as np
import pytest

import lekalo

K = (2, 3, 1)


def case(trailing=(2,)):
    rng = np.random.default_rng(29)
    t = [
        np.array([0, 0, 0, 0.3, 0.7, 1, 1, 1.0]),
        np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0]),
        np.array([0, 0, 0.4, 1, 1.0]),
    ]
    shape = tuple(len(tk) - k - 1 for tk, k in zip(t, K))
    c = rng.uniform(-1, 1, shape + trailing)
    w = rng.uniform(0.3, 3.0, shape)
    x = rng.uniform(0.02, 0.98, (6, 3))
    return t, c, w, x


def quotient(t, c, w, x):
    """``Σ N w c / Σ N w`` by two B-splines."""
    extra = (slice(None),) * 3 + (None,) * (c.ndim - 3)
    num = lekalo.TensorBSpline(t, c * w[extra], list(K))(x)
    den = lekalo.TensorBSpline(t, w, list(K))(x)
    return num / den.reshape(den.shape + (1,) * (num.ndim - den.ndim))


def test_values_are_the_quotient_of_the_homogeneous_splines():
    t, c, w, x = case()
    r = lekalo.TensorNurbs(t, c, list(K), w)
    assert r.ndim == 3 and r.k == list(K)
    np.testing.assert_allclose(r(x), quotient(t, c, w, x), rtol=0, atol=1e-13)
    np.testing.assert_allclose(r.w, w, rtol=0, atol=1e-15)
    np.testing.assert_allclose(r.c, c, rtol=0, atol=1e-14)
    assert [tuple(a) for a in r.t] == [tuple(a) for a in t]
    assert r.domain == [(0.0, 1.0)] * 3
    h = r.homogeneous()
    assert isinstance(h, lekalo.TensorBSpline) and h(x).shape == (6, 3)
    # scalar values keep no trailing axis; a point per leading index
    s = lekalo.TensorNurbs(t, c[..., 0], K, w)
    assert s(x).shape == (6,) and s(x.reshape(2, 3, 3)).shape == (2, 3)


def test_two_variables_are_the_nurbs_surface_and_unit_weights_the_bspline():
    t, c, w, x = case(trailing=(3,))
    t2, c2, w2 = t[:2], c[:, :, 0, :], w[:, :, 0]
    r = lekalo.TensorNurbs(t2, c2, [2, 3], w2)
    s = lekalo.NurbsSurface(2, 3, t2[0], t2[1], c2, w2)
    np.testing.assert_allclose(r(x[:, :2]), s(x[:, 0], x[:, 1]), rtol=0, atol=1e-13)
    b = lekalo.TensorBSpline(t, c, list(K))
    one = lekalo.TensorNurbs.from_bspline(b)
    np.testing.assert_allclose(one(x), b(x), rtol=0, atol=1e-14)
    np.testing.assert_array_equal(one.w, np.ones(w.shape))


def test_grid_and_partials():
    t, c, w, _ = case()
    r = lekalo.TensorNurbs(t, c, K, w)
    axes = [np.linspace(0, 1, 4), np.linspace(0.1, 0.9, 3), np.array([0.0, 0.5, 1.0])]
    g = r.grid(*axes)
    assert g.shape == (4, 3, 3, 2)
    pts = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    np.testing.assert_allclose(g, r(pts), rtol=0, atol=1e-13)
    x = np.array([[0.2, 0.6, 0.3], [0.8, 0.25, 0.7]])
    h = 1e-6
    for a in range(3):
        e = np.zeros(3)
        e[a] = h
        fd = (r(x + e) - r(x - e)) / (2 * h)
        nu = [0, 0, 0]
        nu[a] = 1
        np.testing.assert_allclose(r(x, nu=nu), fd, rtol=0, atol=1e-7 * max(1, np.abs(fd).max()))
    np.testing.assert_array_equal(r(x, nu=[0, 0, 0]), r(x))


def test_knot_kernels_match_central_differences():
    t, c, w, x = case()
    rng = np.random.default_rng(31)
    dks = [rng.uniform(-1, 1, tk.shape) for tk in t]
    values, tangent = lekalo.tensor_nurbs_knot_jvp(t, c, K, w, x, dks)
    np.testing.assert_allclose(values, lekalo.TensorNurbs(t, c, K, w)(x), rtol=0, atol=1e-13)
    h = 1e-6
    fd = np.zeros_like(tangent)
    for a, (tk, k) in enumerate(zip(t, K)):
        mask = np.zeros(len(tk), bool)
        mask[k + 1 : len(tk) - k - 1] = True
        step = np.where(mask, dks[a], 0.0)
        up = [tt + (step * h if b == a else 0) for b, tt in enumerate(t)]
        down = [tt - (step * h if b == a else 0) for b, tt in enumerate(t)]
        fd += (lekalo.TensorNurbs(up, c, K, w)(x) - lekalo.TensorNurbs(down, c, K, w)(x)) / (2 * h)
    np.testing.assert_allclose(tangent, fd, rtol=0, atol=1e-7 * max(1, np.abs(fd).max()))
    g = rng.uniform(-1, 1, values.shape)
    gks = lekalo.tensor_nurbs_knot_vjp(t, c, K, w, x, g)
    assert isinstance(gks, tuple) and [gk.shape for gk in gks] == [tk.shape for tk in t]
    lhs = np.sum(tangent * g)
    rhs = sum(gk @ dk for gk, dk in zip(gks, dks))
    assert abs(lhs - rhs) <= 1e-12 * np.sum(np.abs(tangent * g))
    # the weights matter: the B-spline of the same coefficients moves differently
    _, plain = lekalo.tensor_bspline_knot_jvp(t, c, K, x, dks)
    assert np.abs(tangent - plain).max() > 1e-3


def test_errors_name_the_argument():
    t, c, w, x = case()
    with pytest.raises(lekalo.InputError, match="w: shape"):
        lekalo.TensorNurbs(t, c, K, w[:, :, :1])
    with pytest.raises(lekalo.InputError, match="w"):
        lekalo.TensorNurbs(t, c, K, -w)
    with pytest.raises(lekalo.InputError, match="c: axis 0"):
        lekalo.TensorNurbs(t, c[1:], K, w[1:])
    r = lekalo.TensorNurbs(t, c, K, w)
    with pytest.raises(lekalo.InputError, match="x: shape"):
        r(x[:, :2])
    with pytest.raises(lekalo.InputError, match="nu: 2 orders"):
        r(x, nu=[1, 0])
    with pytest.raises(lekalo.InputError, match="axes: 2 parameter lists"):
        r.grid([0.5], [0.5])
    with pytest.raises(ValueError, match="outside"):
        r(x + 1.0)
    with pytest.raises(lekalo.InputError, match="t_tangent: 2 entries for 3 variables"):
        lekalo.tensor_nurbs_knot_jvp(t, c, K, w, x, [None, None])
    with pytest.raises(lekalo.InputError, match="cotangent"):
        lekalo.tensor_nurbs_knot_vjp(t, c, K, w, x, np.zeros((len(x), 3)))


def test_knot_insertion_and_slicing_keep_the_spline():
    t, c, w, x = case()
    r = lekalo.TensorNurbs(t, c, list(K), w)
    for axis, at, times in [(0, 0.3, 1), (1, 0.21, 3), (2, 0.9, 1)]:
        q = r.insert_knot(at, axis, times=times)
        assert isinstance(q, lekalo.TensorNurbs)
        assert q.c.shape[axis] == c.shape[axis] + times and q.c.shape[3:] == (2,)
        assert np.count_nonzero(q.t[axis] == at) == np.count_nonzero(t[axis] == at) + times
        np.testing.assert_allclose(q(x), r(x), rtol=0, atol=1e-13)
    # a slice is the spline with the fixed values put in, and stays rational
    p = r.slice([None, 0.62, None])
    assert isinstance(p, lekalo.TensorNurbs) and p.ndim == 2
    full = np.c_[x[:, 0], np.full(len(x), 0.62), x[:, 2]]
    np.testing.assert_allclose(p(x[:, [0, 2]]), r(full), rtol=0, atol=1e-13)
    one = r.slice([0.1, None, 0.8])
    np.testing.assert_allclose(
        one(x[:, 1:2]), r(np.c_[np.full(len(x), 0.1), x[:, 1], np.full(len(x), 0.8)]),
        rtol=0, atol=1e-13,
    )
    # the B-spline's slice and insertion: the same along the homogeneous net
    b = lekalo.TensorBSpline(t, c, list(K))
    np.testing.assert_allclose(b.slice([None, 0.62, None])(x[:, [0, 2]]), b(full),
                               rtol=0, atol=1e-14)
    np.testing.assert_allclose(b.insert_knot(0.5, 2, times=1)(x), b(x), rtol=0, atol=1e-14)
    for bad, says in [
        (lambda: r.insert_knot(0.5, 3), "axis"),
        (lambda: r.insert_knot(0.5, -1), "axis"),
        (lambda: r.insert_knot(0.5, 1, times=4), "times"),
        (lambda: r.slice([0.5, None]), "fixed"),
        (lambda: r.slice([0.5, 0.5, 0.5]), "fixed"),
        (lambda: b.slice([1.5, None, None]), "fixed"),
    ]:
        with pytest.raises(lekalo.InputError, match=says):
            bad()


def test_extrapolation_continues_numerator_and_weight():
    t, c, w, x = case()
    r = lekalo.TensorNurbs(t, c, list(K), w)
    out = x + np.array([0.5, -0.6, 0.3])
    with pytest.raises(lekalo.InputError, match="outside the domain"):
        r(out)
    # inside the domain the same bits; outside the quotient of the continued homogeneous spline
    assert np.array_equal(r(x, extrapolate=True), r(x))
    h = r.homogeneous()(out, extrapolate=True)
    np.testing.assert_allclose(r(out, extrapolate=True), h[:, :2] / h[:, 2:], rtol=1e-13)
    # partial derivatives outside: central differences of the continued values
    e = 1e-6
    for nu in ([1, 0, 0], [0, 1, 0], [0, 0, 1]):
        d = np.array(nu) * e
        fd = (r(out + d, extrapolate=True) - r(out - d, extrapolate=True)) / (2 * e)
        np.testing.assert_allclose(r(out, nu=nu, extrapolate=True), fd, rtol=1e-6, atol=1e-6)
    assert np.array_equal(r(x, nu=[1, 1, 0], extrapolate=True), r(x, nu=[1, 1, 0]))
