""":class:`symhx.validation.InputError`: the one type of every refusal of symhx (a ``ValueError``
subclass, so ``except ValueError`` still catches it), exported as ``symhx.InputError``."""

from __future__ import annotations

import ast
import math
from fractions import Fraction
from pathlib import Path

import pytest
import sympy

import symhx
from symhx import validation as V
from symhx.validation import InputError

SOURCE = Path(symhx.__file__).parent
#: below the conversion layer (it cannot import InputError); symhx.validation maps what these
#: raise for a user's input to InputError
BELOW_VALIDATION = {"certify.py", "_mpctx.py"}


def test_input_error_is_a_value_error_exported_from_symhx():
    assert issubclass(InputError, ValueError) and not issubclass(InputError, TypeError)
    assert symhx.InputError is InputError and "InputError" in symhx.__all__
    with pytest.raises(ValueError):  # old callers' except ValueError still catches it
        V.check_int("2.5", "N")


@pytest.mark.parametrize("call", [
    lambda: V.check_int("2.5", "N"),
    lambda: V.check_int(1, "N", minimum=2),
    lambda: V.check_int("1__0", "N"),
    lambda: V.check_int("1e100001", "N"),
    lambda: V.check_dps(0),
    lambda: V.check_dps(V.MAX_DPS + 1),
    lambda: V.to_rational(math.nan),
    lambda: V.to_rational("1/0"),
    lambda: V.to_rational("abc"),
    lambda: V.check_p(-1),
    lambda: V.check_p(sympy.sqrt(2) - sympy.sqrt(3)),
    lambda: V.check_p(sympy.Mul(sympy.I, sympy.I, -1, evaluate=False)),  # certify's ValueError
    lambda: V.check_real(2, "x", high=1),
    lambda: V.check_choice("c", "mode", ["a", "b"]),
    lambda: V.check_array([1.0, -1.0], "x", positive=True),
    lambda: V.check_array([Fraction(10) ** 400], "x"),
    lambda: V.check_seed(-1),
])
def test_every_refusal_of_the_conversion_layer_is_an_input_error(call):
    with pytest.raises(InputError):
        call()


def test_a_wrong_kind_of_object_is_still_a_type_error():
    for call in (lambda: V.check_int(True, "N"), lambda: V.check_dps(2.5),
                 lambda: V.to_rational(object())):
        with pytest.raises(TypeError) as info:
            call()
        assert not isinstance(info.value, InputError)


@pytest.mark.parametrize("call", [
    lambda: symhx.phi(0, 1),
    lambda: symhx.pmf(0, 101, "0.02"),
    lambda: symhx.critical_point(1),
    lambda: symhx.impact_probability(-1.0),
    lambda: symhx.sigma_for_impact_probability(2),
    lambda: symhx.PipeRow.random(2, 1.0, seed=1, restitution=2),
    lambda: symhx.parse_space("bogus"),
])
def test_refusals_of_every_layer_are_input_errors(call):
    with pytest.raises(InputError):
        call()


def _raises_plain_value_error(tree: ast.AST) -> list[int]:
    """Lines of ``raise ValueError(...)`` / ``return ValueError(...)`` (not a re-raise)."""
    lines = []
    for node in ast.walk(tree):
        value = node.exc if isinstance(node, ast.Raise) else \
            node.value if isinstance(node, ast.Return) else None
        if isinstance(value, ast.Call) and isinstance(value.func, ast.Name) \
                and value.func.id == "ValueError":
            lines.append(node.lineno)
    return sorted(lines)


def test_no_module_above_the_conversion_layer_raises_a_plain_value_error():
    """A refusal raised as a plain ValueError would be reported by the CLI as a bug."""
    found = {}
    for path in sorted(SOURCE.rglob("*.py")):
        if path.name in BELOW_VALIDATION and path.parent == SOURCE:
            continue
        lines = _raises_plain_value_error(ast.parse(path.read_text()))
        if lines:
            found[str(path.relative_to(SOURCE))] = lines
    assert not found, f"raise InputError (symhx.validation) instead of ValueError: {found}"


def test_the_source_scan_finds_a_plain_value_error():
    tree = ast.parse("def f(x):\n    if x:\n        raise ValueError('x')\n"
                     "    raise InputError('y')\n\ndef g():\n    return ValueError('z')\n")
    assert _raises_plain_value_error(tree) == [3, 7]
