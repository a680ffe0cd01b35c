"""``TensorBSpline``: SciPy's ``NdBSpline`` layout, evaluation at points and on grids, partial
derivatives, grid interpolation, and the round trip with SciPy, checked against
``scipy.interpolate.NdBSpline`` and ``make_ndbspl`` in 3 variables."""

import numpy as np
import pytest

import lekalo

interpolate = pytest.importorskip("scipy.interpolate")
if not hasattr(interpolate, "NdBSpline"):
    pytest.skip("scipy.interpolate.NdBSpline needs SciPy >= 1.12", allow_module_level=True)

# public from SciPy 1.18 on; earlier versions (from 1.12) have it in the private module
make_ndbspl = getattr(interpolate, "make_ndbspl", None)
if make_ndbspl is None:
    from scipy.interpolate._ndbspline import make_ndbspl

from scipy.sparse.linalg import spsolve

RTOL = 1e-12


def scipy_interpolant(axes, values, k):
    """``make_ndbspl`` with a direct solve (its default, GCROT(m,k), stops at ~1e-5)."""
    return make_ndbspl(axes, values, k=k, solver=spsolve)


def close(a, b):
    scale = max(1.0, float(np.max(np.abs(b))))
    np.testing.assert_allclose(a, b, rtol=0, atol=RTOL * scale)


def random_spline(rng, trailing=()):
    k = (3, 2, 1)
    t = []
    for p, n in zip(k, (6, 5, 4)):
        inner = np.sort(rng.uniform(0.0, 1.0, n - p - 1))
        t.append(np.concatenate([np.zeros(p + 1), inner, np.ones(p + 1)]))
    c = rng.standard_normal((6, 5, 4) + trailing)
    return tuple(t), c, k


def test_matches_ndbspline_at_points_on_grids_and_in_derivatives():
    rng = np.random.default_rng(7)
    t, c, k = random_spline(rng)
    ours = lekalo.TensorBSpline(t, c, k)
    ref = interpolate.NdBSpline(t, c, k)
    assert ours.ndim == 3 and list(ours.k) == [3, 2, 1]
    x = rng.uniform(0.0, 1.0, (4, 7, 3))
    close(ours(x), ref(x))
    assert ours(x).shape == (4, 7)
    for nu in [(1, 0, 0), (0, 2, 0), (1, 1, 1), (2, 0, 1)]:
        close(ours(x, nu=nu), ref(x, nu=nu))
    axes = [np.linspace(0, 1, 5), np.linspace(0.1, 0.9, 3), np.array([0.0, 0.5, 1.0])]
    g = ours.grid(*axes)
    mesh = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    close(g, ref(mesh))
    close(ours.grid(*axes, nu=(1, 1, 0)), ref(mesh, nu=(1, 1, 0)))


def test_vector_values_and_the_scipy_round_trip_are_bit_for_bit():
    rng = np.random.default_rng(3)
    t, c, k = random_spline(rng, trailing=(2,))
    ref = interpolate.NdBSpline(t, c, k)
    ours = lekalo.TensorBSpline.from_scipy(ref)
    assert ours.c.shape == (6, 5, 4, 2)
    assert np.array_equal(ours.c, ref.c)
    for a in range(3):
        assert np.array_equal(ours.t[a], ref.t[a])
    back = ours.to_scipy()
    assert np.array_equal(back.c, ref.c) and tuple(back.k) == tuple(ref.k)
    x = rng.uniform(0.0, 1.0, (10, 3))
    close(ours(x), ref(x))
    assert ours(x).shape == (10, 2)


def test_interpolate_grid_agrees_with_make_ndbspl():
    xs = np.array([0.0, 0.3, 0.5, 0.9, 1.2, 2.0])
    ys = np.array([-1.0, 0.0, 0.4, 1.0, 2.5])
    zs = np.array([0.0, 1.0, 1.5, 3.0])
    X, Y, Z = np.meshgrid(xs, ys, zs, indexing="ij")
    # a polynomial each spline space holds: both interpolants are that polynomial
    f = lambda x, y, z: x**3 - 2 * x * y + y**2 * z + z**3  # noqa: E731
    values = f(X, Y, Z)
    ours = lekalo.TensorBSpline.interpolate_grid([xs, ys, zs], values, degrees=3)
    ref = scipy_interpolant((xs, ys, zs), values, 3)
    rng = np.random.default_rng(1)
    p = np.stack([rng.uniform(0, 2, 50), rng.uniform(-1, 2.5, 50), rng.uniform(0, 3, 50)], axis=-1)
    close(ours(p), ref(p))
    close(ours(p), f(p[:, 0], p[:, 1], p[:, 2]))
    # any data: both pass through the nodes
    noisy = np.sin(3 * X) * np.cos(Y) + Z
    ours = lekalo.TensorBSpline.interpolate_grid([xs, ys, zs], noisy, degrees=(3, 3, 1))
    ref = scipy_interpolant((xs, ys, zs), noisy, (3, 3, 1))
    nodes = np.stack([X, Y, Z], axis=-1)
    close(ours(nodes), ref(nodes))
    close(ours.grid(xs, ys, zs), noisy)


def test_periodic_and_natural_axes_are_make_interp_spline_along_each_axis():
    # an uneven periodic axis between two not-a-knot ones, values offset by 1e8
    rng = np.random.default_rng(11)
    xs = np.sort(rng.uniform(0.0, 1.0, 7))
    ys = np.concatenate([[0.0], np.sort(rng.uniform(0.0, 2.0 * np.pi, 8)), [2.0 * np.pi]])
    zs = np.linspace(-1.0, 1.0, 6) ** 3
    X, Y, Z = np.meshgrid(xs, ys, zs, indexing="ij")
    values = 1e8 + np.cos(2 * X) * np.sin(Y) + Z * np.cos(Y) ** 2
    c, t = values, []
    for a, (x, bc) in enumerate(zip((xs, ys, zs), (None, "periodic", None))):
        spl = interpolate.make_interp_spline(x, c, k=3, axis=a, bc_type=bc)
        c = np.moveaxis(spl.c, 0, a)
        t.append(spl.t)
    ref = interpolate.NdBSpline(tuple(t), c, 3)
    # lekalo's periodic axis does not repeat its first line: the values stop one short
    ours = lekalo.TensorBSpline.interpolate_grid(
        [xs, ys, zs], values[:, :-1], knots=[t[0], None, t[2]], end=["free", "periodic", "free"]
    )
    p = np.stack([rng.uniform(xs[0], xs[-1], 200), rng.uniform(0.0, 2 * np.pi, 200), rng.uniform(-1, 1, 200)], axis=-1)
    close(ours(p), ref(p))
    # the same spline: SciPy's knots on every axis (the periodic one placed by lekalo) and the
    # coefficients to 1e-12 of the data's scale; its derivatives are then the basis's, whose
    # evaluation is compared with NdBSpline above (derivatives of data offset by 1e8 amplify
    # either side's rounding of the offset by the grid's spacing to the derivative's order)
    for ti, ri in zip(ours.t, t):
        np.testing.assert_array_equal(np.asarray(ti), ri)
    close(np.asarray(ours.c), c)
    # natural cubic ends along every axis are make_interp_spline(bc_type="natural")
    c, t = values, []
    for a, x in enumerate((xs, ys, zs)):
        spl = interpolate.make_interp_spline(x, c, k=3, axis=a, bc_type="natural")
        c = np.moveaxis(spl.c, 0, a)
        t.append(spl.t)
    ours = lekalo.TensorBSpline.interpolate_grid([xs, ys, zs], values, end="natural")
    close(ours(p), interpolate.NdBSpline(tuple(t), c, 3)(p))
    with pytest.raises(lekalo.Error, match="^end: "):
        lekalo.TensorBSpline.interpolate_grid([xs, ys, zs], values, end=["natural", "free"])
    with pytest.raises(lekalo.Error, match="values: shape .*periodic"):
        lekalo.TensorBSpline.interpolate_grid([xs, ys, zs], values, end=["free", "periodic", "free"])


def test_errors_name_the_argument():
    rng = np.random.default_rng(0)
    t, c, k = random_spline(rng)
    s = lekalo.TensorBSpline(t, c, k)
    with pytest.raises(lekalo.Error, match="x: shape"):
        s(np.zeros((4, 2)))
    with pytest.raises(lekalo.Error, match="nu: 2 orders"):
        s(np.zeros((1, 3)), nu=(1, 0))
    with pytest.raises(lekalo.Error, match="axes: 2 parameter lists"):
        s.grid([0.5], [0.5])
    with pytest.raises(lekalo.Error, match="c: axis 1"):
        lekalo.TensorBSpline(t, np.ascontiguousarray(c[:, :4]), k)
    with pytest.raises(lekalo.Error, match="k: 2 degrees"):
        lekalo.TensorBSpline(t, c, (3, 2))
    with pytest.raises(lekalo.Error):
        s(np.array([[0.5, 0.5, 2.0]]))
    bad = c.copy()
    bad[0, 0, 0] = np.nan
    with pytest.raises(lekalo.Error, match="^c: "):
        lekalo.TensorBSpline(t, bad, k)
    unsorted = (t[0][::-1].copy(), t[1], t[2])
    with pytest.raises(lekalo.Error, match="^t: "):
        lekalo.TensorBSpline(unsorted, c, k)
    axes = [np.arange(4.0), np.arange(3.0), np.arange(2.0)]
    with pytest.raises(lekalo.Error, match="values: shape"):
        lekalo.TensorBSpline.interpolate_grid(axes, np.zeros((4, 3, 3)))
    with pytest.raises(lekalo.Error, match="^degrees: "):
        lekalo.TensorBSpline.interpolate_grid(axes, np.zeros((4, 3, 2)), degrees=(3, 3, 3))
    with pytest.raises(lekalo.Error, match="^axes: "):
        lekalo.TensorBSpline.interpolate_grid([axes[0][::-1].copy(), axes[1], axes[2]], np.zeros((4, 3, 2)), degrees=1)


def test_given_knots_and_the_make_ndbspl_drop_in_match_scipy_coefficients():
    from lekalo import scipy as ls

    rng = np.random.default_rng(7)
    axes = [np.sort(rng.uniform(0, 1, n)) + 1e8 * (d == 2) for d, n in enumerate((9, 7, 8))]
    values = rng.standard_normal((9, 7, 8, 2))
    for k in (3, (3, 1, 5)):
        ref = scipy_interpolant(axes, values, k)
        ours = ls.make_ndbspl(axes, values, k=k)
        for a, b in zip(ours.t, ref.t):
            np.testing.assert_array_equal(a, b)
        close(ours.c, ref.c)
        # the native API with the same knots
        native = lekalo.TensorBSpline.interpolate_grid(axes, values, degrees=k, knots=list(ref.t))
        close(native.c, ref.c)
    # None keeps the averaged knots of a direction
    ref = scipy_interpolant(axes, values, 3)
    mixed = lekalo.TensorBSpline.interpolate_grid(axes, values, knots=[None, ref.t[1], None])
    plain = lekalo.TensorBSpline.interpolate_grid(axes, values)
    np.testing.assert_array_equal(mixed.t[0], plain.t[0])
    np.testing.assert_array_equal(mixed.t[1], ref.t[1])
    # complex values: the real and imaginary parts
    z = values[..., 0] + 1j * values[..., 1]
    close(ls.make_ndbspl(axes, z).c, scipy_interpolant(axes, z, 3).c)
    # even degrees: SciPy's mid-point knots (its make_ndbspl documents odd degrees and takes any)
    for k in (2, (4, 2, 1)):
        ref = scipy_interpolant(axes, values, k)
        ours = ls.make_ndbspl(axes, values, k=k)
        for a, b in zip(ours.t, ref.t):
            np.testing.assert_array_equal(a, b)
        close(ours.c, ref.c)


def test_given_knots_errors_name_the_argument():
    axes = [np.arange(6.0), np.arange(5.0)]
    values = np.zeros((6, 5))
    with pytest.raises(lekalo.InputError, match="^knots: 1 entries for 2 variables"):
        lekalo.TensorBSpline.interpolate_grid(axes, values, knots=[None])
    with pytest.raises(lekalo.InputError, match=r"^knots: .*1st direction: 9 knots for 6 values"):
        lekalo.TensorBSpline.interpolate_grid(axes, values, knots=[np.r_[[0.0] * 4, 2.5, [5.0] * 4], None])
    with pytest.raises(lekalo.InputError, match=r"^knots: .*Schoenberg"):
        lekalo.TensorBSpline.interpolate_grid(axes, values, knots=[np.r_[[0.0] * 4, 0.1, 0.2, [5.0] * 4], None])
    with pytest.raises(lekalo.InputError, match=r"^knots\[0\]: "):
        lekalo.TensorBSpline.interpolate_grid(axes, values, knots=[np.r_[[5.0] * 4, 0.1, 0.2, [0.0] * 4], None])


def test_derivative_spline_and_extrapolation_match_scipy():
    rng = np.random.default_rng(3)
    t, c, k = random_spline(rng, trailing=(2,))
    ours = lekalo.TensorBSpline(t, c, k)
    ref = interpolate.NdBSpline(t, c, k)
    x = rng.uniform(0.0, 1.0, (40, 3))
    for nu in ((1, 0, 0), (2, 1, 1), (0, 3, 0)):
        d = ours.derivative(nu)
        assert d.k == [max(p - n, 0) for p, n in zip(k, nu)]
        close(d(x), ref(x, nu=nu))
    # beyond the box: the end polynomials, as SciPy's extrapolate=True
    far = rng.uniform(-0.5, 1.5, (40, 3))
    close(ours(far, extrapolate=True), ref(far))
    with pytest.raises(lekalo.Error):
        ours(far)


def test_design_matrix_times_the_net_is_the_spline():
    # each row the Kronecker product of the basis rows; B @ c is the spline, extrapolated too
    rng = np.random.default_rng(5)
    t = [np.r_[[0.0] * 3, 0.4, [1.0] * 3], np.r_[[-1.0] * 4, 0.0, 0.5, [2.0] * 4]]
    k = [2, 3]
    c = rng.uniform(-1, 1, (4, 6))
    spline = lekalo.TensorBSpline(t, c, k)
    x = np.c_[rng.uniform(-0.2, 1.2, 25), rng.uniform(-1.5, 2.5, 25)]
    data, indices, indptr, shape = lekalo.tensor_design_matrix(x, t, k)
    assert shape == (25, 24)
    assert np.array_equal(indptr, np.arange(26) * 12)
    b = np.zeros(shape)
    for j in range(25):
        b[j, indices[indptr[j]:indptr[j + 1]]] = data[indptr[j]:indptr[j + 1]]
    assert np.abs(b @ c.ravel() - spline(x, extrapolate=True)).max() <= 1e-12
    with pytest.raises(lekalo.InputError, match="x"):
        lekalo.tensor_design_matrix(x, t, k, extrapolate=False)


def ticks_inside(call):
    """Runs ``call`` in a thread while this thread ticks; whether a tick fell in the middle
    fifth of the call: only possible if the call let go of the GIL."""
    import threading
    import time

    span = {}

    def work():
        span["start"] = time.perf_counter()
        call()
        span["end"] = time.perf_counter()

    ticks = []
    worker = threading.Thread(target=work)
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.0005)
    worker.join()
    mid, width = (span["start"] + span["end"]) / 2, (span["end"] - span["start"]) / 10
    return span["end"] - span["start"], any(abs(t - mid) < width for t in ticks)


def test_evaluation_and_construction_release_the_gil():
    import time

    from lekalo import scipy as ls

    rng = np.random.default_rng(2)
    axes = [np.linspace(0.0, 1.0, 40)] * 3
    s = lekalo.TensorBSpline.interpolate_grid(axes, rng.standard_normal((40, 40, 40)))
    nd = ls.NdBSpline(s.t, s.c, 3)

    def sized(make, n0):
        """The argument of ``make`` scaled from ``n0`` so that one call takes about 0.2 s."""
        start = time.perf_counter()
        make(n0)
        took = max(time.perf_counter() - start, 1e-5)
        return min(int(n0 * 0.2 / took) + 1, 40 * n0)

    points = lambda n: rng.uniform(0.0, 1.0, (n, 3))  # noqa: E731
    n = sized(lambda n: s(points(n)), 100_000)
    x = points(n)
    # the grid's size in points, its side the cube root
    cube = lambda m: [np.linspace(0.0, 1.0, round(m ** (1 / 3)) + 1)] * 3  # noqa: E731
    side = round(sized(lambda m: s.grid(*cube(m)), 60 ** 3) ** (1 / 3)) + 1
    fine = [np.linspace(0.0, 1.0, side)] * 3
    big = [np.linspace(0.0, 1.0, 128)] * 3
    table = rng.standard_normal((128, 128, 128))
    for name, call, must in [
        ("TensorBSpline.__call__", lambda: s(x), True),
        ("TensorBSpline.grid", lambda: s.grid(*fine), True),
        ("lekalo.scipy.NdBSpline.__call__", lambda: nd(x), True),
        ("TensorBSpline.interpolate_grid", lambda: lekalo.TensorBSpline.interpolate_grid(big, table), False),
    ]:
        took, ticked = ticks_inside(call)
        # one call, long enough to have a middle the other thread can reach
        if must or took > 0.05:
            assert ticked, f"{name} held the GIL for {took:.3f} s"


_PEAK_CHILD = r"""
import json, sys
import numpy as np
import lekalo.scipy as ls

def status(field):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024

n = int(sys.argv[1])
axes = [np.linspace(0, 1, n)] * 3
values = np.random.default_rng(1).random((n, n, n))
ls.make_ndbspl(axes, values, k=3)  # the library's pages mapped, its pools made
with open("/proc/self/clear_refs", "w") as f:
    f.write("5")
before = status("VmRSS")
spline = ls.make_ndbspl(axes, values, k=3)
print(json.dumps({"extra": status("VmHWM") - before, "input": values.nbytes}))
"""


@pytest.mark.skipif(not __import__("os").path.exists("/proc/self/clear_refs"), reason="Linux's peak reset")
def test_make_ndbspl_peak_memory_is_one_grid_above_the_input(tmp_path):
    # the values are copied once into the array the solves work on, which becomes the
    # coefficients, handed to NumPy without a copy: the peak above the input is one grid (the
    # coefficients), not two (a spline object's and NumPy's copies)
    import json
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-c", _PEAK_CHILD, "96"], capture_output=True, text=True, check=True)
    m = json.loads(out.stdout)
    assert m["extra"] < 1.5 * m["input"], m
