"""tests/python/test_readme.py — every ```python block of README.md run as it is, in a temporary
folder that holds the `mesh.obj` the blocks read (a generated hexagon sphere), so the README's
Python cannot drift from the module; a traceback names README.md's line."""

import pathlib
import re

import pytest

import polydec

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def python_blocks():
    """(first line number, code) of each ```python block of README.md."""
    text = README.read_text(encoding="utf-8")
    return [(text.count("\n", 0, m.start(1)) + 1, m.group(1))
            for m in re.finditer(r"^```python\n(.*?)^```", text, re.S | re.M)]


def test_readme_has_python_blocks():
    assert python_blocks()


@pytest.mark.parametrize("index", range(len(python_blocks())))
def test_readme_python_block(index, tmp_path, monkeypatch):
    line, code = python_blocks()[index]
    monkeypatch.chdir(tmp_path)
    polydec.write_mesh("mesh.obj", *polydec.hex_sphere(2))
    exec(compile("\n" * (line - 1) + code, str(README), "exec"), {"__name__": "readme"})
