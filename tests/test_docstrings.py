"""The Examples sections of the runtime docstrings run as doctests: what
``help()`` shows a user must work as shown."""

import doctest

import pytest

import tcarod
from tcarod import _core as core


@pytest.mark.parametrize("obj", [core.Robot.solve], ids=lambda o: o.__qualname__)
def test_runtime_docstring_examples_run(obj: object) -> None:
    doc = obj.__doc__
    assert doc and "Examples\n--------" in doc
    parser = doctest.DocTestParser()
    test = parser.get_doctest(doc, {"tcarod": tcarod}, getattr(obj, "__qualname__", "obj"), None, 0)
    assert test.examples, "no examples"
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    runner.run(test)
    assert runner.failures == 0
