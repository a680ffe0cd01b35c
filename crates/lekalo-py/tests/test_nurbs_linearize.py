"""lekalo.nurbs_surface_linearize and lekalo.tensor_nurbs_linearize: the values bit for bit
the evaluation's, the rational basis rows reproducing them from the net, the partial
derivatives against the JVP kernels, and the weight derivative R (P - S) / w that the rows
give against the JVP kernels' weight tangents. The mathematics is tested in the core
(crates/lekalo/src/derivatives/nurbs_surface.rs, tensor_nurbs.rs)."""

import numpy as np
import pytest

import lekalo

P, Q = 2, 3
DEGREES = (2, 1, 3)


def surface_case():
    rng = np.random.default_rng(41)
    ku = np.array([0, 0, 0, 0.4, 1, 1, 1.0])
    kv = np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0])
    net = rng.uniform(-1, 1, (4, 5, 3))
    w = rng.uniform(0.4, 2.5, (4, 5))
    u = np.array([[0.1, 0.3], [0.6, 1.0]])
    v = np.array([[0.2, 0.5], [0.7, 0.0]])  # a knot and the ends among them
    return ku, kv, net, w, u, v


def test_surface_linearization_holds_the_values_and_the_sparse_jacobian():
    ku, kv, net, w, u, v = surface_case()
    lin = lekalo.nurbs_surface_linearize(P, Q, ku, kv, net, w, u, v)
    values = lekalo.NurbsSurface(P, Q, ku, kv, net, w)(u, v)
    assert np.array_equal(lin["values"], values)
    assert lin["basis"].shape == u.shape + (P + 1, Q + 1)
    assert lin["first_u"].dtype == np.int64 and lin["first_u"].shape == u.shape
    # the rows of the rational basis give the values from the net, and sum to one
    for idx in np.ndindex(u.shape):
        fu, fv = lin["first_u"][idx], lin["first_v"][idx]
        block = net[fu : fu + P + 1, fv : fv + Q + 1]
        r = lin["basis"][idx]
        assert abs(r.sum() - 1) < 1e-14
        assert np.allclose(np.einsum("kl,kld->d", r, block), values[idx], rtol=0, atol=1e-14)
        # d S / d w_kl = R_kl (P_kl - S) / w_kl, against the JVP kernel's weight tangent
        k, l = 1, 2
        dw = np.zeros_like(w)
        dw[fu + k, fv + l] = 1.0
        _, tan = lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u[idx], v[idx], weights_tangent=dw)
        expect = r[k, l] * (block[k, l] - values[idx]) / w[fu + k, fv + l]
        assert np.allclose(tan, expect, rtol=1e-13, atol=1e-15)
    # the partial derivatives are the JVP kernels' parameter tangents
    one = np.ones_like(u)
    _, su = lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u, v, u_tangent=one)
    _, sv = lekalo.nurbs_surface_jvp(P, Q, ku, kv, net, w, u, v, v_tangent=one)
    assert np.allclose(lin["derivatives_u"], su, rtol=1e-14, atol=1e-14)
    assert np.allclose(lin["derivatives_v"], sv, rtol=1e-14, atol=1e-14)


def test_surface_linearization_refuses_points_outside_the_domain():
    ku, kv, net, w, u, v = surface_case()
    with pytest.raises(ValueError, match="outside"):
        lekalo.nurbs_surface_linearize(P, Q, ku, kv, net, w, [1.5], [0.5])


def tensor_case(dim=2):
    rng = np.random.default_rng(43)
    knots = [
        np.array([0, 0, 0, 0.35, 0.6, 1, 1, 1.0]),
        np.array([0, 0, 0.4, 1, 1.0]),
        np.array([0, 0, 0, 0, 0.55, 1, 1, 1, 1.0]),
    ]
    net = rng.uniform(-1, 1, (5, 3, 5, dim))
    w = rng.uniform(0.4, 2.5, (5, 3, 5))
    x = np.array([[0.1, 0.2, 0.3], [0.5, 0.4, 0.8], [1.0, 0.05, 0.45], [0.3, 0.55, 0.0]])
    return knots, net, w, x


def test_tensor_linearization_holds_the_values_and_the_sparse_jacobian():
    knots, net, w, x = tensor_case()
    lin = lekalo.tensor_nurbs_linearize(knots, net, list(DEGREES), w, x)
    values = lekalo.TensorNurbs(knots, net, list(DEGREES), w)(x)
    assert np.array_equal(lin["values"], values)
    assert lin["first"].shape == x.shape and lin["first"].dtype == np.int64
    block_shape = tuple(p + 1 for p in DEGREES)
    assert lin["basis"].shape == (len(x),) + block_shape
    assert lin["partials"].shape == (len(x), 3, 2)
    for r in range(len(x)):
        f = lin["first"][r]
        sl = tuple(slice(f[a], f[a] + DEGREES[a] + 1) for a in range(3))
        basis = lin["basis"][r]
        assert abs(basis.sum() - 1) < 1e-14
        assert np.allclose(np.einsum("ijk,ijkd->d", basis, net[sl]), values[r], atol=1e-14)
        # the weight derivative from the row, against the JVP kernel
        corner = (1, 0, 2)
        dw = np.zeros_like(w)
        at = tuple(f[a] + corner[a] for a in range(3))
        dw[at] = 1.0
        _, tan = lekalo.tensor_nurbs_jvp(knots, net, list(DEGREES), w, x[r : r + 1], None, dw)
        expect = basis[corner] * (net[at] - values[r]) / w[at]
        assert np.allclose(tan[0], expect, rtol=1e-13, atol=1e-15)
    for a in range(3):
        dx = np.zeros_like(x)
        dx[:, a] = 1.0
        _, tan = lekalo.tensor_nurbs_jvp(knots, net, list(DEGREES), w, x, None, None, dx)
        assert np.allclose(lin["partials"][:, a], tan, rtol=1e-14, atol=1e-14)


def test_tensor_linearization_of_a_scalar_function_keeps_the_leading_shape():
    knots, net, w, x = tensor_case()
    lin = lekalo.tensor_nurbs_linearize(knots, net[..., 0], list(DEGREES), w, x.reshape(2, 2, 3))
    assert lin["values"].shape == (2, 2)
    assert lin["partials"].shape == (2, 2, 3)
    assert lin["basis"].shape == (2, 2) + tuple(p + 1 for p in DEGREES)
