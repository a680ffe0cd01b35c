"""lekalo.torch: values bit-for-bit lekalo's, gradients from backward() against central finite
differences (relative 1e-7), batches of control points and data sets, and the errors for what
is not supported. Skipped without PyTorch, which the project's test command does not install
(docs/differentiable.md, "PyTorch"); `scripts/test-torch.sh` installs it in an environment of
its own and runs this file and test_torch_nurbs_nets.py."""

import numpy as np
import pytest

torch = pytest.importorskip("torch", reason="PyTorch is not installed here; scripts/test-torch.sh runs these tests with it")

import lekalo  # noqa: E402
from lekalo import torch as lt  # noqa: E402

from derivative_checks import assert_rel, central, knot_central  # noqa: E402


def t64(a, grad=True):
    return torch.tensor(np.asarray(a, dtype=float), dtype=torch.float64, requires_grad=grad)


def grads(f, *args):
    """Gradients of sum(f(*args) * weights) with respect to args, and the weights."""
    out = f(*args)
    g = torch.sin(torch.arange(out.numel(), dtype=torch.float64)).reshape(out.shape)
    return torch.autograd.grad((out * g).sum(), args), g.numpy()


def curve_case(dim=3):
    rng = np.random.default_rng(7)
    knots = np.array([0, 0, 0, 0, 0.3, 0.55, 1, 1, 1, 1.0])
    return knots, rng.uniform(-1, 1, (6, dim)), np.array([0.05, 0.2, 0.41, 0.5, 0.7, 0.93])


def test_curve_values_and_gradients():
    knots, ctrl, u = curve_case()
    c, t = t64(ctrl), t64(u)
    vals = lt.bspline_eval(knots, c, t, 3)
    assert np.array_equal(vals.detach().numpy(), lekalo.bspline_curve_jvp(3, knots, ctrl, u)[0])
    (gc, gu), g = grads(lambda a, b: lt.bspline_eval(knots, a, b, 3), c, t)
    plain = lambda a, b: np.sum(lekalo.bspline_curve_jvp(3, knots, a, b)[0] * g)  # noqa: E731
    assert_rel(gc, central(lambda a: plain(a, u), ctrl, 1e-3), "control points")
    assert_rel(gu, central(lambda b: plain(ctrl, b), u, 1e-6), "u")
    # a batch of curves at shared parameters: the parameter gradient sums over the batch
    batch = np.stack([ctrl, -2 * ctrl])
    (gb, gu2), g2 = grads(lambda a, b: lt.bspline_eval(knots, a, b, 3), t64(batch), t64(u))
    for i in range(2):
        pi = lambda a: np.sum(lekalo.bspline_curve_jvp(3, knots, a, u)[0] * g2[i])  # noqa: E731
        assert_rel(gb[i], central(pi, batch[i], 1e-3), "batched control points")
    fd = central(lambda b: sum(np.sum(lekalo.bspline_curve_jvp(3, knots, batch[i], b)[0] * g2[i]) for i in range(2)), u, 1e-6)
    assert_rel(gu2, fd, "shared u")


def test_nurbs_surface_and_tensor_gradients():
    knots, ctrl, u = curve_case()
    w = np.array([1.0, 0.5, 2.0, 1.5, 0.8, 1.2])
    (gc, gw, gu), g = grads(lambda a, b, c: lt.nurbs_eval(knots, a, b, c, 3), t64(ctrl), t64(w), t64(u))
    plain = lambda a, b, c: np.sum(lekalo.nurbs_curve_jvp(3, knots, a, b, c)[0] * g)  # noqa: E731
    assert_rel(gw, central(lambda b: plain(ctrl, b, u), w, 1e-6), "weights")
    assert_rel(gc, central(lambda a: plain(a, w, u), ctrl, 1e-3), "NURBS control points")
    rng = np.random.default_rng(11)
    ku, kv = np.array([0, 0, 0, 0.4, 1, 1, 1.0]), np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1.0])
    net, su, sv = rng.uniform(-1, 1, (4, 5, 3)), np.array([0.1, 0.3, 0.6]), np.array([0.2, 0.45, 0.7])
    (gn, gsu, gsv), g = grads(lambda a, b, c: lt.bspline_surface_eval(ku, kv, a, b, c, 2, 3), t64(net), t64(su), t64(sv))
    plain = lambda a, b, c: np.sum(lekalo.bspline_surface_jvp(2, 3, ku, kv, a, b, c)[0] * g)  # noqa: E731
    assert_rel(gn, central(lambda a: plain(a, su, sv), net, 1e-3), "net")
    assert_rel(gsv, central(lambda c: plain(net, su, c), sv, 1e-6), "v")
    kt = [np.array([0, 0, 0, 0.5, 1, 1, 1.0])] * 3
    coef, pts = rng.uniform(-1, 1, (4, 4, 4, 2)), np.array([[0.1, 0.45, 0.9], [0.3, 0.3, 0.7]])  # off the knots
    (gk, gx), g = grads(lambda a, b: lt.tensor_bspline_eval(kt, a, b, (2, 2, 2)), t64(coef), t64(pts))
    plain = lambda a, b: np.sum(lekalo.TensorBSpline(kt, a, [2, 2, 2])(b) * g)  # noqa: E731
    assert_rel(gk, central(lambda a: plain(a, pts), coef, 1e-3), "tensor coefficients")
    assert_rel(gx, central(lambda b: plain(coef, b), pts, 1e-6), "tensor points")


def test_nurbs_and_tensor_knot_gradients():
    """The knots of nurbs_eval and tensor_bspline_eval: gradients the library's knot VJP, the
    interior knots' against central differences, the end knots' zero."""
    knots, ctrl, u = curve_case()
    w = np.array([1.0, 0.5, 2.0, 1.5, 0.8, 1.2])
    batch = np.stack([ctrl, -2 * ctrl])
    (gk, gc), g = grads(lambda k, c: lt.nurbs_eval(k, c, w, u, 3), t64(knots), t64(batch))
    plain = lambda k: sum(np.sum(lekalo.nurbs_curve_jvp(3, k, batch[i], w, u)[0] * g[i]) for i in range(2))  # noqa: E731
    assert_rel(gk, knot_central(plain, knots, 3), "NURBS knots, batch summed")
    assert np.all(gk.numpy()[:4] == 0.0) and np.all(gk.numpy()[6:] == 0.0)
    want = sum(lekalo.nurbs_curve_knot_vjp(3, knots, batch[i], w, u, np.ascontiguousarray(g[i])) for i in range(2))
    assert_rel(gk, want, "NURBS knots, the kernel")
    rng = np.random.default_rng(12)
    kt = [np.array([0, 0, 0, 0.5, 1, 1, 1.0]), np.array([0, 0, 0.4, 1, 1.0]), np.array([0, 0, 0, 0.6, 1, 1, 1.0])]
    degrees = (2, 1, 2)
    coef, pts = rng.uniform(-1, 1, (4, 3, 4, 2)), np.array([[0.1, 0.45, 0.9], [0.3, 0.3, 0.7]])  # off the knots
    gks, g = grads(lambda a, b, c: lt.tensor_bspline_eval([a, b, c], coef, pts, degrees), *[t64(k) for k in kt])
    for a in range(3):
        def plain(k, a=a):
            moved = kt[:a] + [k] + kt[a + 1 :]
            return np.sum(lekalo.TensorBSpline(moved, coef, list(degrees))(pts) * g)

        assert_rel(gks[a], knot_central(plain, kt[a], degrees[a]), f"tensor knots[{a}]")
    want = lekalo.tensor_bspline_knot_vjp(kt, coef, list(degrees), pts, g)
    for a in range(3):
        assert_rel(gks[a], want[a], f"tensor knots[{a}], the kernel")
    # the knots of one variable alone, the others constants
    (g1,), g = grads(lambda b: lt.tensor_bspline_eval([kt[0], b, kt[2]], coef, pts, degrees), t64(kt[1]))
    assert_rel(g1, lekalo.tensor_bspline_knot_vjp(kt, coef, list(degrees), pts, g)[1], "one variable's knots")


def test_fit_gradients():
    rng = np.random.default_rng(3)
    x = np.sort(rng.uniform(0, 1, 30))
    x[0], x[-1] = 0.0, 1.0
    y = np.stack([np.sin(3 * x), np.cos(2 * x)], axis=-1)
    t = np.array([0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1.0])
    w = rng.uniform(0.5, 2, 30)
    out = lt.fit_least_squares(t64(y, False), x, t, 3, w=w)
    assert np.array_equal(out.numpy(), lekalo.fit_least_squares(y, x, t, 3, w=w)[0].control)
    (gq,), g = grads(lambda q: lt.fit_least_squares(q, x, t, 3, w=w), t64(y))
    plain = lambda q: np.sum(lekalo.fit_least_squares(q, x, t, 3, w=w)[0].control * g)  # noqa: E731
    assert_rel(gq, central(plain, y, 1e-3), "least squares, data")
    batch = np.stack([y, y[::-1]])
    (gb,), g = grads(lambda q: lt.fit_smoothing(x, q, w, 1e-3), t64(batch))
    for i in range(2):
        pi = lambda q: np.sum(lekalo.fit_smoothing(x, q, w, 1e-3)[0].control * g[i])  # noqa: E731
        assert_rel(gb[i], central(pi, batch[i], 1e-3), "smoothing, batched data")


def test_fit_least_squares_knot_gradients():
    """The knots of fit_least_squares: the gradient lekalo.least_squares_knot_vjp's, summed over
    a batch of data sets, against central differences in the interior knots."""
    rng = np.random.default_rng(4)
    x = rng.permutation(np.linspace(0, 1, 30))
    y = np.stack([np.sin(3 * x), np.cos(2 * x)], axis=-1) + 0.05 * rng.standard_normal((30, 2))
    t = np.array([0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1.0])
    w = rng.uniform(0.5, 2, 30)
    batch = np.stack([y, 2 * y[::-1] - 1])
    (gq, gt), g = grads(lambda q, k: lt.fit_least_squares(q, x, k, 3, w=w), t64(batch), t64(t))

    def plain(k):
        return sum(np.sum(lekalo.fit_least_squares(batch[i], x, k, 3, w=w)[0].control * g[i]) for i in range(2))

    assert_rel(gt, knot_central(plain, t, 3), "least-squares knots, batch summed")
    assert np.all(gt.numpy()[:4] == 0.0) and np.all(gt.numpy()[6:] == 0.0)
    for i in range(2):
        pi = lambda q: np.sum(lekalo.fit_least_squares(q, x, t, 3, w=w)[0].control * g[i])  # noqa: E731
        assert_rel(gq[i], central(pi, batch[i], 1e-3), "least squares, data beside the knots")


def test_fit_backward_applies_the_forward_factorisation(monkeypatch):
    """A fit's backward pass applies the map its forward pass factored (`factors=`), with the
    bits of the VJP kernels that factor again; values bit-for-bit the fits'."""
    x = np.linspace(0, 1, 25) ** 1.1
    y = np.stack([np.sin(3 * x), np.cos(2 * x)], axis=-1)
    t = np.array([0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1.0])
    calls = []
    for name in ("least_squares_vjp", "smoothing_vjp"):
        real = getattr(lekalo._lekalo, name)

        def spy(*a, _real=real, _name=name, **kw):
            calls.append((_name, kw.get("factors") is not None))
            return _real(*a, **kw)

        monkeypatch.setattr(lekalo._lekalo, name, spy)
    batch = np.stack([y, 2 * y + 1])
    for fit, plain, vjp in (
        (
            lambda q: lt.fit_least_squares(q, x, t, 3),
            lambda q: lekalo.fit_least_squares(q, x, t, 3)[0].control,
            lambda g: lekalo._lekalo.least_squares_vjp(3, t, x, g),
        ),
        (
            lambda q: lt.fit_smoothing(x, q, None, 1e-3),
            lambda q: lekalo.fit_smoothing(x, q, None, 1e-3)[0].control,
            lambda g: lekalo._lekalo.smoothing_vjp(x, 1e-3, g),
        ),
    ):
        out = fit(t64(batch, False))
        for i in range(2):
            assert np.array_equal(out[i].numpy(), plain(batch[i]))
        calls.clear()
        (gq,), g = grads(fit, t64(batch))
        assert calls and all(factored for _, factored in calls), calls
        for i in range(2):
            assert np.array_equal(gq[i].numpy(), vjp(np.ascontiguousarray(g[i])))


def test_bad_input_says_so():
    knots, ctrl, u = curve_case()
    with pytest.raises(lekalo.InputError, match="float64"):
        lt.bspline_eval(knots, torch.tensor(ctrl, dtype=torch.float32), u, 3)
    # the knots of the evaluations and of the least-squares fit may ask for their gradient, the
    # fits' parameters and weights may not
    with pytest.raises(lekalo.InputError, match="parameters"):
        lt.fit_least_squares(t64(ctrl), t64(u), knots, 3)
    with pytest.raises(lekalo.InputError, match="lam > 0"):
        lt.fit_smoothing(u, t64(ctrl))


def test_the_docs_example_runs():
    """The PyTorch example of docs/differentiable.md (a ```text block there, since the docs'
    python blocks run without torch) runs as written."""
    import re
    from pathlib import Path

    doc = Path(__file__).resolve().parents[3] / "docs" / "differentiable.md"
    section = doc.read_text(encoding="utf-8").split("## PyTorch", 1)[1]
    code = re.search(r"^```text\n(.*?)^```", section, flags=re.S | re.M).group(1)
    namespace = {"__name__": "docs"}
    exec(compile(code, str(doc), "exec"), namespace)
    assert namespace["ctrl"].grad.shape == (5, 2)
