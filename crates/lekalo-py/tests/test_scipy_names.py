"""scipy.interpolate's names that lekalo.scipy does not provide: importing one says what to use
instead and lists what lekalo.scipy provides, and ``hasattr`` stays False for other names."""

import pytest

import lekalo.scipy


@pytest.mark.parametrize(
    "name, advice",
    [
        ("RegularGridInterpolator", "make_ndbspl"),
        ("interp1d", "make_interp_spline(x, y, k=3)"),
        ("interp2d", "RectBivariateSpline"),
        ("griddata", "import it from scipy.interpolate"),
        ("NdPPoly", "import it from scipy.interpolate"),
    ],
)
def test_a_name_outside_the_spline_part_says_what_to_use(name, advice):
    with pytest.raises(ImportError) as e:
        exec(f"from lekalo.scipy import {name}", {})
    text = str(e.value)
    assert text.startswith(f"lekalo.scipy does not provide {name}: "), text
    assert advice in text, text
    for provided in ("BSpline", "make_interp_spline", "CubicSpline", "RectBivariateSpline"):
        assert provided in text, text


def test_other_missing_names_are_plain_attribute_errors():
    assert not hasattr(lekalo.scipy, "no_such_name")
    assert getattr(lekalo.scipy, "no_such_name", None) is None
    for name in lekalo.scipy.__all__:
        assert hasattr(lekalo.scipy, name), name
