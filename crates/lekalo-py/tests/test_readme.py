"""The package README's Python blocks run as written: every ```python block, in order, in one
namespace (later blocks use the names of earlier ones, as a reader following them would)."""

import functools
import re
from pathlib import Path

README = Path(__file__).resolve().parent.parent / "README.md"


def blocks(text):
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


@functools.lru_cache(maxsize=None)
def readme_namespace():
    """The names bound by running the README's blocks in order (run once for the tests)."""
    found = blocks(README.read_text(encoding="utf-8"))
    assert len(found) >= 4, "the README's examples were not found"
    namespace = {"__name__": "readme"}
    for i, code in enumerate(found, 1):
        try:
            exec(compile(code, f"{README.name}, python block {i}", "exec"), namespace)
        except Exception as e:  # the block and the error, not only the traceback
            raise AssertionError(f"README python block {i} failed: {e!r}\n{code}") from e
    return namespace


def test_readme_python_blocks_run():
    readme_namespace()


def test_readme_results_are_what_its_comments_say():
    # the names the blocks bind hold what the comments beside them say
    namespace = readme_namespace()
    np = namespace["np"]
    hits = namespace["hits"]  # the circle of radius 2 cut by the line y = 1
    assert [h["kind"] for h in hits] == ["crossing", "crossing"], hits
    points = sorted(tuple(h["point"]) for h in hits)
    np.testing.assert_allclose(points, [(-np.sqrt(3), 1), (np.sqrt(3), 1)], atol=1e-12)
    branches = namespace["branches"]  # (x−1)(y−1) = 1/2: two open arcs
    assert [(b["kind"], b["closed"]) for b in branches] == [("crossing", False)] * 2, branches
    assert list(namespace["offsets"]) == [0, 50, 130, 195]


def test_blocks_are_found_and_a_broken_one_fails():
    text = "```python\nx = 1\n```\n\n```sh\nls\n```\n```python\ny = x + 1\n```\n"
    assert blocks(text) == ["x = 1\n", "y = x + 1\n"]
    ns = {}
    for b in blocks(text):
        exec(b, ns)
    assert ns["y"] == 2


def _import_error_without(module, blocked):
    """The ImportError of ``import module`` in a fresh interpreter where ``blocked`` is missing
    (as in a venv made by the README's install, which installs no extra)."""
    import subprocess
    import sys

    code = (
        f"import sys; sys.modules[{blocked!r}] = None\n"
        f"try:\n    import {module}\nexcept ImportError as e:\n    print(type(e).__name__, e)\n"
        "else:\n    print('imported')\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return out.stdout.strip()


def test_a_missing_extra_names_an_install_command_that_works():
    # `pip install lekalo[jax]` would ask PyPI; the README installs from the clone
    for module, blocked in [("lekalo.jax", "jax"), ("lekalo.torch", "torch")]:
        message = _import_error_without(module, blocked)
        assert message.startswith("ImportError"), message
        assert f"`pip install {blocked}`" in message, message
        assert f'`pip install "./crates/lekalo-py[{blocked}]"`' in message, message
        assert f'pip install "./crates/lekalo-py[{blocked}]"' in README.read_text(encoding="utf-8")
