"""Every docstring example of the installed package runs (the doctests are collected from the
imported modules, so this works for an editable and a regular install alike)."""

import doctest
import importlib
import pkgutil

import pytest

import symhx

MODULES = sorted(
    info.name for info in pkgutil.walk_packages(symhx.__path__, prefix="symhx.")
    if not info.name.endswith("__main__")
)


def test_module_walk_finds_the_core_modules():
    assert "symhx.critical" in MODULES and "symhx.distribution" in MODULES


@pytest.mark.parametrize("name", ["symhx", *MODULES])
def test_docstring_examples_pass(name):
    module = importlib.import_module(name)
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testmod(module, optionflags=flags, report=True)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples failed in {name}"
