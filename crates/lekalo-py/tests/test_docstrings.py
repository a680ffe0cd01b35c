"""Every example in a docstring of the package (what ``help(lekalo.interpolate)`` or
``help(lekalo.BlendSpline)`` shows) runs and prints what the docstring says. ``lekalo.jax``
has its own test (``test_jax.py``), as it needs JAX."""

import doctest
import importlib

import pytest

MODULES = [
    "lekalo",
    "lekalo.io",
    "lekalo._batch",
    "lekalo._interop",
    "lekalo.scipy",
    "lekalo.scipy._bspline",
    "lekalo.scipy._interpolate",
    "lekalo.scipy._fitpack",
    "lekalo.scipy._fitpack2",
    "lekalo.scipy._ppoly",
    "lekalo.scipy._cubic",
    "lekalo.scipy._splrep",
    "lekalo.scipy._ndbspline",
    "lekalo.scipy._bivariate",
    "lekalo.scipy._knots",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples_print_what_they_say(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples of {name} fail"


def test_the_native_examples_are_found():
    # lekalo re-exports the native classes and functions; their examples are tested above
    result = doctest.testmod(importlib.import_module("lekalo"))
    assert result.attempted >= 30, result
