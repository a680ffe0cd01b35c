"""The option words Python shares with the command line and the editor, and the error kinds.

The canonical words are the library's vocabulary (`lekalo::vocabulary`); the command line's
`--help` lists the same words, and `crates/lekalo-cli` tests them against the same table. Each
word is accepted here; each older Python spelling still works with a DeprecationWarning.
"""

import subprocess
import warnings

import numpy as np
import pytest

import lekalo

Q = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [5.0, 1.0]])

# the canonical words of the vocabulary, as the library defines them
KNOTS = ["auto", "averaged", "uniform", "at-params"]
PARAMETRIZATION = ["uniform", "chord", "centripetal"]
END = ["free", "derivatives", "second", "natural", "periodic"]
RULE = ["first-knot-after", "left-end-of-support", "midpoint", "greville", "first-interval-midpoint"]
KNOT_ROUNDS = ["shared", "refit"]


def quiet(f, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return f(*args, **kwargs)


@pytest.mark.parametrize("word", PARAMETRIZATION)
def test_every_parametrization_word(word):
    quiet(lekalo.interpolate, Q, 3, parametrization=word)


@pytest.mark.parametrize("word", KNOTS)
def test_every_knot_word(word):
    end = {"end": "natural"} if word == "at-params" else {}
    quiet(lekalo.interpolate, Q, 3, knots=word, **end)


@pytest.mark.parametrize("word", END)
def test_every_end_word(word):
    d = {"d_start": [1.0, 0.0], "d_end": [1.0, 0.0]} if word in ("derivatives", "second") else {}
    quiet(lekalo.interpolate, Q, 3, end=word, **d)


@pytest.mark.parametrize("word", RULE)
def test_every_rule_word(word):
    space = lekalo.PpSpace([0.0, 0.5, 0.9, 1.4, 2.1, 2.7, 3.0], 3, [2] * 5)
    quiet(lekalo.quasi_interpolate, space, lambda x, r: np.cos(x) if r == 0 else 0.0, rule=word)


@pytest.mark.parametrize("word", KNOT_ROUNDS)
def test_every_knot_rounds_word(word):
    x = np.linspace(0.0, 1.0, 40)
    quiet(lekalo.make_splrep, x, np.sin(6 * x), s=1e-3, knot_rounds=word)


@pytest.mark.parametrize(
    "kwargs, canonical",
    [
        ({"knots": "at_parameters", "end": "natural"}, "at-params"),
        ({"parametrization": "chord_length"}, "chord"),
        ({"end": "first", "d_start": [1.0, 0.0], "d_end": [1.0, 0.0]}, "derivatives"),
    ],
)
def test_older_spellings_warn_and_name_the_word(kwargs, canonical):
    with pytest.warns(DeprecationWarning, match=canonical):
        lekalo.interpolate(Q, 3, **kwargs)


def test_an_unknown_word_lists_the_words():
    with pytest.raises(lekalo.InputError, match="knots: unknown value \"everywhere\"; use one of 'auto', 'averaged', 'uniform', 'at-params'"):
        lekalo.interpolate(Q, 3, knots="everywhere")


def test_the_cli_offers_the_same_words():
    """`lekalo interpolate --help` lists exactly the vocabulary's words (when the binary is built)."""
    import os
    import shutil

    exe = os.environ.get("LEKALO_BIN") or shutil.which("lekalo")
    if exe is None:
        pytest.skip("no lekalo binary on PATH or in LEKALO_BIN")
    text = subprocess.run([exe, "interpolate", "--help"], capture_output=True, text=True, check=True).stdout
    for words in (KNOTS, PARAMETRIZATION, END):
        for w in words:
            assert f"{w}:" in text or f"{w} " in text, (w, text)
    text = subprocess.run([exe, "fit", "--help"], capture_output=True, text=True, check=True).stdout
    for w in KNOT_ROUNDS:
        assert w in text, (w, text)


def test_error_kinds():
    assert issubclass(lekalo.InputError, lekalo.Error) and issubclass(lekalo.InputError, ValueError)
    assert issubclass(lekalo.NumericalError, lekalo.Error)
    assert issubclass(lekalo.NumericalError, np.linalg.LinAlgError)
    with pytest.raises(lekalo.InputError):
        lekalo.interpolate(np.array([[0.0, np.nan], [1.0, 1.0]]), 1)


# The library's errors carry a typed key of the argument they refuse; the binding writes the
# refusal under the keyword of that argument (one table, `argument` in src/error.rs), never by
# reading the message.
@pytest.mark.parametrize(
    "call, keyword, rest",
    [
        (lambda: lekalo.interpolate(Q, 3, knots="uniform", end="natural"), "knots", "averaged or uniform knots do not go with"),
        (lambda: lekalo.interpolate(Q, 3, end="natural", d_start=[1.0, 0.0]), "d_start/d_end", "end derivatives are used by"),
        (lambda: lekalo.interpolate(Q, 3, end="derivatives", d_start=[1.0, 0.0]), "d_start/d_end", "the end condition derivatives needs"),
    ],
)
def test_a_refused_argument_is_named_by_its_keyword(call, keyword, rest):
    with pytest.raises(lekalo.InputError) as e:
        call()
    message = str(e.value)
    assert message.startswith(f"{keyword}: {rest}"), message
    assert "lekalo::" not in message and "Arg" not in message, message


def test_scattered_fit_options_are_named_by_their_keywords():
    rng = np.random.default_rng(3)
    x = rng.uniform(0.0, 1.0, (60, 2))
    y = np.sin(x[:, 0]) + x[:, 1]
    with pytest.raises(lekalo.InputError, match=r"^eps: "):
        lekalo.fit_tensor_scattered_smoothing(x, y, 0.1, eps=2.0)
    with pytest.raises(lekalo.InputError, match=r"^max_knots: "):
        lekalo.fit_tensor_scattered_smoothing(x, y, 0.1, max_knots=[8])
