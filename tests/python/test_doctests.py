"""tests/python/test_doctests.py — the docstring examples (>>> lines) of the package's public
functions, classes and methods, run as tests with `polydec` and `np` in scope; and every public
function and class of polydec.__all__ (exceptions aside) has one."""

import doctest
import inspect

import numpy as np
import pytest

import polydec


def documented():
    """(qualified name, docstring) of every public function and class and of their public methods
    and properties."""
    out = []
    for name in polydec.__all__:
        obj = getattr(polydec, name)
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            continue
        out.append((name, inspect.getdoc(obj) or ""))
        if inspect.isclass(obj):
            for member, value in vars(obj).items():
                if member.startswith("_"):
                    continue
                if isinstance(value, (classmethod, staticmethod)):
                    value = value.__func__
                if inspect.isfunction(value) or isinstance(value, property):
                    out.append((f"{name}.{member}", inspect.getdoc(value) or ""))
    return out


EXAMPLES = [(name, doc) for name, doc in documented() if ">>>" in doc]


def test_every_public_function_has_an_example():
    missing = [name for name in polydec.__all__
               if not (inspect.isclass(getattr(polydec, name)) and issubclass(getattr(polydec, name), BaseException))
               and ">>>" not in (inspect.getdoc(getattr(polydec, name)) or "")]
    assert missing == []


@pytest.mark.parametrize("name,doc", EXAMPLES, ids=[name for name, _ in EXAMPLES])
def test_docstring_example(name, doc):
    if "import meshio" in doc:
        pytest.importorskip("meshio", reason="meshio is not installed (Debian: python3-meshio)")
    test = doctest.DocTestParser().get_doctest(doc, {"polydec": polydec, "np": np}, name, None, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    failures = []
    runner.run(test, out=failures.append)
    assert runner.failures == 0, "".join(failures)
