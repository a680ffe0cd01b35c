"""The package README's Python blocks run as written: every ```python block, in order, in one
namespace (later blocks use the names of earlier ones, as a reader following them would)."""

import re
from pathlib import Path

README = Path(__file__).resolve().parent.parent / "README.md"


def blocks(text):
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def test_readme_python_blocks_run():
    found = blocks(README.read_text(encoding="utf-8"))
    assert len(found) >= 4, "the README's examples were not found"
    namespace = {"__name__": "readme"}
    for i, code in enumerate(found, 1):
        try:
            exec(compile(code, f"{README.name}, python block {i}", "exec"), namespace)
        except Exception as e:  # the block and the error, not only the traceback
            raise AssertionError(f"README python block {i} failed: {e!r}\n{code}") from e


def test_blocks_are_found_and_a_broken_one_fails():
    text = "```python\nx = 1\n```\n\n```sh\nls\n```\n```python\ny = x + 1\n```\n"
    assert blocks(text) == ["x = 1\n", "y = x + 1\n"]
    ns = {}
    for b in blocks(text):
        exec(b, ns)
    assert ns["y"] == 2
