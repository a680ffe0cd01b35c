"""lekalo.torch.nurbs_surface_eval and tensor_nurbs_eval: values bit-for-bit lekalo's,
gradients from backward() in every argument (net, weights, parameters, knots) against central
finite differences (relative 1e-7), a batch of nets. Skipped without PyTorch, as test_torch.py
is (docs/differentiable.md, "PyTorch")."""

import numpy as np
import pytest

torch = pytest.importorskip("torch", reason="PyTorch is not installed here; scripts/test-torch.sh runs these tests with it")

import lekalo  # noqa: E402
from lekalo import torch as lt  # noqa: E402

from derivative_checks import assert_rel, central, knot_central  # noqa: E402
from test_torch import grads, t64  # noqa: E402


def test_nurbs_surface_values_and_gradients():
    rng = np.random.default_rng(41)
    ku, kv = np.array([0, 0, 0, 0.4, 1, 1, 1.0]), np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0])
    net, w = rng.uniform(-1, 1, (4, 5, 3)), rng.uniform(0.4, 2.5, (4, 5))
    u, v = np.array([0.1, 0.3, 0.6]), np.array([0.2, 0.45, 0.7])
    vals = lt.nurbs_surface_eval(ku, kv, t64(net), t64(w), t64(u), t64(v), 2, 3)
    assert np.array_equal(vals.detach().numpy(), lekalo.nurbs_surface_jvp(2, 3, ku, kv, net, w, u, v)[0])
    args = [t64(ku), t64(kv), t64(net), t64(w), t64(u), t64(v)]
    (gku, gkv, gn, gw, gu, gv), g = grads(lambda a, b, c, d, e, f: lt.nurbs_surface_eval(a, b, c, d, e, f, 2, 3), *args)

    def plain(ku=ku, kv=kv, net=net, w=w, u=u, v=v):
        return np.sum(lekalo.nurbs_surface_jvp(2, 3, ku, kv, net, w, u, v)[0] * g)

    assert_rel(gn, central(lambda a: plain(net=a), net, 1e-3), "net")
    assert_rel(gw, central(lambda a: plain(w=a), w, 1e-6), "weights")
    assert_rel(gu, central(lambda a: plain(u=a), u, 1e-6), "u")
    assert_rel(gv, central(lambda a: plain(v=a), v, 1e-6), "v")
    assert_rel(gku, knot_central(lambda a: plain(ku=a), ku, 2), "knots_u")
    assert_rel(gkv, knot_central(lambda a: plain(kv=a), kv, 3), "knots_v")
    # a batch of nets with shared weights: the weight gradient sums over the batch
    batch = np.stack([net, -net])
    (gb, gw2), g2 = grads(lambda a, b: lt.nurbs_surface_eval(ku, kv, a, b, u, v, 2, 3), t64(batch), t64(w))
    fd = central(lambda b: sum(np.sum(lekalo.nurbs_surface_jvp(2, 3, ku, kv, batch[i], b, u, v)[0] * g2[i]) for i in range(2)), w, 1e-6)
    assert_rel(gw2, fd, "shared weights")


def test_tensor_nurbs_values_and_gradients():
    rng = np.random.default_rng(43)
    kt = [np.array([0, 0, 0, 0.5, 1, 1, 1.0]), np.array([0, 0, 0.4, 1, 1.0]), np.array([0, 0, 0, 0.6, 1, 1, 1.0])]
    degrees = (2, 1, 2)
    coef, w = rng.uniform(-1, 1, (4, 3, 4, 2)), rng.uniform(0.4, 2.5, (4, 3, 4))
    pts = np.array([[0.1, 0.45, 0.9], [0.3, 0.3, 0.7]])  # off the knots
    vals = lt.tensor_nurbs_eval(kt, t64(coef), t64(w), t64(pts), degrees)
    assert np.array_equal(vals.detach().numpy(), lekalo.TensorNurbs(kt, coef, list(degrees), w)(pts))
    (gc, gw, gx, *gks), g = grads(
        lambda c, ws, x, a, b, d: lt.tensor_nurbs_eval([a, b, d], c, ws, x, degrees),
        t64(coef), t64(w), t64(pts), *[t64(k) for k in kt],
    )

    def plain(kt=kt, coef=coef, w=w, pts=pts):
        return np.sum(lekalo.TensorNurbs(kt, coef, list(degrees), w)(pts) * g)

    assert_rel(gc, central(lambda a: plain(coef=a), coef, 1e-3), "coefficients")
    assert_rel(gw, central(lambda a: plain(w=a), w, 1e-6), "weights")
    assert_rel(gx, central(lambda a: plain(pts=a), pts, 1e-6), "points")
    for a in range(3):
        def one(k, a=a):
            return plain(kt=kt[:a] + [k] + kt[a + 1 :])

        assert_rel(gks[a], knot_central(one, kt[a], degrees[a]), f"knots[{a}]")
