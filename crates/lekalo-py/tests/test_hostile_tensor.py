"""Hostile input against the tensor-spline paths of the Python package: arrays whose views are
far larger than their memory, absurd degrees, empty axes; each is an exception with lekalo's
message, never an abort of the interpreter (docs/robustness.md)."""

import re
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import lekalo
from lekalo import _lekalo
from lekalo.scipy import make_ndbspl


def _run_limited(code: str) -> subprocess.CompletedProcess:
    """``code`` in a fresh interpreter limited to 3 GB of address space, so that an allocation
    the arguments ask for fails there (an abort would not take the test runner with it)."""
    prelude = "import resource\nresource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))\n"
    return subprocess.run(
        [sys.executable, "-c", prelude + textwrap.dedent(code)], capture_output=True, text=True, timeout=300
    )


def test_a_broadcast_view_beyond_the_size_limit_is_refused_before_its_copy():
    # 8e9 values behind 8 bytes of memory: a strided view is copied in C order to be read
    values = np.broadcast_to(0.0, (2000, 2000, 2000))
    axes = [np.linspace(0, 1, 2000)] * 3
    with pytest.raises(lekalo.InputError, match=r"values: .*not C-contiguous.*8000000000 values.*size limit"):
        _lekalo.fit_tensor_grid(axes, values, [np.r_[0.0, 0, 1, 1]] * 3, 1)


def test_a_broadcast_view_the_memory_cannot_hold_raises_memory_error_not_an_abort():
    # 1.7e9 values (13.8 GB) are under the size limit: the copy's reservation fails
    r = _run_limited(
        """
        import numpy as np
        from lekalo import _lekalo
        values = np.broadcast_to(0.0, (1200, 1200, 1200))
        try:
            _lekalo.fit_tensor_grid([np.linspace(0, 1, 1200)] * 3, values, [np.r_[0.0, 0, 1, 1]] * 3, 1)
        except MemoryError as e:
            print("MemoryError:", e)
        """
    )
    assert r.returncode == 0, r.stderr[-2000:]
    assert "MemoryError: values: cannot reserve memory for a C-order copy of 1728000000 values" in r.stdout, r.stdout


def test_a_size_refusal_names_the_argument_once_without_the_class_name():
    t = np.r_[[0.0] * 4, 0.5, [1.0] * 4]
    with pytest.raises(lekalo.InputError) as e:
        _lekalo.tensor_grid_values([t] * 3, np.zeros((5, 5, 5)), 3, [np.linspace(0, 1, 100_000)] * 3)
    assert str(e.value).startswith("axes: output: size 1000000000000000 is too large"), str(e.value)
    assert "InputError" not in str(e.value)


def test_make_ndbspl_refuses_a_huge_degree_and_an_empty_axis_by_name():
    x = np.linspace(0, 1, 5)
    # not-a-knot knots of degree 2^40 + 1 were allocated first (a MemoryError without a message)
    with pytest.raises(lekalo.InputError, match=r"degree 1099511627777 is not allowed here.*5 values"):
        make_ndbspl((x, x, x), np.zeros((5, 5, 5)), k=2**40 + 1)
    # an empty axis raised IndexError from the knots' construction
    with pytest.raises(lekalo.InputError, match=r"grid values in a direction .*need at least 2, got 0"):
        make_ndbspl((x, x, np.array([])), np.zeros((5, 5, 0)))


def test_jax_tensor_eval_refuses_zero_variables():
    pytest.importorskip("jax")
    from jax_support import x64  # noqa: F401
    import jax

    import lekalo.jax as lj

    old = jax.config.jax_enable_x64
    jax.config.update("jax_enable_x64", True)
    try:
        with pytest.raises(lekalo.InputError, match="degrees is empty"):
            lj.tensor_bspline_eval([], np.zeros(()), np.zeros((4, 0)), [])
    finally:
        jax.config.update("jax_enable_x64", old)


@pytest.mark.parametrize("nu", [[-1, 0], [0, -5], [2**64, 0], [0, 2**70]])
def test_negative_and_huge_derivative_orders_are_lekalos_error_not_overflow(nu):
    # `nu` was read as unsigned integers: -1 raised OverflowError ("can't convert negative int
    # to unsigned") from PyO3 instead of lekalo's error naming the entry
    t = np.r_[[0.0] * 3, 0.5, [1.0] * 3]
    s = lekalo.TensorBSpline([t, t], np.zeros((4, 4)), 2)
    at = np.array([[0.3, 0.6]])
    bad = "nu[0]" if nu[0] != 0 else "nu[1]"
    pattern = rf"^{re.escape(bad)} must be a whole number 0, 1, 2, \.\.\., got"
    for call in (
        lambda: s(at, nu=nu),
        lambda: s.grid([0.3], [0.6], nu=nu),
        lambda: s.derivative(nu),
        lambda: _lekalo.tensor_values([t, t], np.zeros((4, 4)), 2, at, nu),
        lambda: _lekalo.tensor_grid_values([t, t], np.zeros((4, 4)), 2, [[0.3], [0.6]], nu),
    ):
        with pytest.raises(lekalo.InputError, match=pattern):
            call()


def test_a_huge_but_representable_derivative_order_is_refused_or_zero_not_a_crash():
    t = np.r_[[0.0] * 3, 0.5, [1.0] * 3]
    s = lekalo.TensorBSpline([t, t], np.ones((4, 4)), 2)
    try:
        v = s(np.array([[0.3, 0.6]]), nu=[2**62, 0])
    except lekalo.InputError as e:
        assert "nu" in str(e) or "derivative" in str(e), str(e)
    else:
        assert np.all(v == 0), v


@pytest.mark.parametrize(
    "args, pattern",
    [
        (([0, 0.5, 1], -1), r"^order must be a whole number"),
        (([0, 0.5, 1], 3, [-1]), r"^continuity\[0\] must be a whole number"),
    ],
)
def test_pp_space_counts_are_lekalos_error_not_overflow(args, pattern):
    with pytest.raises(lekalo.InputError, match=pattern):
        lekalo.PpSpace(*args)


def test_pp_jump_indices_are_lekalos_error_not_overflow():
    c = lekalo.BSplineCurve(2, [0, 0, 0, 0.5, 1, 1, 1], [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]])
    f = lekalo.PiecewisePolynomial.from_bspline(c)
    for i, j, name in ((-1, 0, "i"), (1, -1, "j"), (2**70, 0, "i")):
        with pytest.raises(lekalo.InputError, match=rf"^{name} must be a whole number"):
            f.jump(i, j)
