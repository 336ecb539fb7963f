"""The contract of every symbolic derivation (:class:`symhx.symbolic.Derivation`): its checks
all pass on the derived result, and each check *on its own* returns False (having run, not
crashed) on a tampered result, so that no check is vacuous.

``tamper`` changes a result while keeping its shape (an equation stays an equation, a tuple a
tuple of the same length, a ``Piecewise`` keeps its conditions), so a check sees a result it can
evaluate and must reject on its merits. A check that verifies a derived object other than the
result, or a property a small change keeps (a sign, a difference from the paper's erratum), is
given a tampered derivation aimed at it.

>>> import sympy as sp
>>> x = sp.Symbol("x")
>>> tamper(sp.Eq(sp.Symbol("y"), x))
Eq(y, x + 1)
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest
import sympy as sp

__all__ = [
    "assert_check_rejects",
    "assert_module_table",
    "assert_verifies",
    "check_indices",
    "contract_tests",
    "module_of",
    "tamper",
    "tamper_part",
    "tamper_result",
    "tamper_rhs",
]


def tamper(result: Any) -> Any:
    """``result`` with its right-hand side changed: ``+ 1``; the first entry of a tuple
    ``2 x + 1``; every branch of a ``Piecewise`` ``+ 1`` (conditions kept)."""
    if isinstance(result, sp.Equality):
        return sp.Eq(result.lhs, tamper(result.rhs), evaluate=False)
    if isinstance(result, sp.Tuple):
        return sp.Tuple(result[0] * 2 + 1, *result[1:])
    if isinstance(result, sp.Piecewise):
        return sp.Piecewise(*[(e + 1, c) for e, c in result.args])
    return result + 1


def tamper_result(d: Any) -> Any:
    """``d`` with its result tampered by :func:`tamper`."""
    return d.with_result(tamper(d.result))


def tamper_part(d: Any, j: int) -> Any:
    """``d`` with one part of its result's right-hand side changed: entry ``j`` of a tuple
    (``2 x + 1``) or branch ``j`` of a ``Piecewise`` (``+ 1``, its condition kept)."""
    r = d.result.rhs
    if isinstance(r, sp.Piecewise):
        new = sp.Piecewise(*[(e + (1 if i == j else 0), c) for i, (e, c) in enumerate(r.args)])
    else:
        new = sp.Tuple(*[x * 2 + 1 if i == j else x for i, x in enumerate(r)])
    return d.with_result(sp.Eq(d.result.lhs, new, evaluate=False))


def tamper_rhs(new: Callable[[Any], Any]) -> Callable[[Any], Any]:
    """A tampering of a derivation ``d`` that replaces the right-hand side of its result by
    ``new(d)`` (for checks that a generic change cannot fail)."""
    def tampered(d: Any) -> Any:
        return d.with_result(sp.Eq(d.result.lhs, new(d), evaluate=False))
    return tampered


def assert_verifies(d: Any) -> None:
    """Every check of ``d`` runs and passes, and ``verify()`` says so."""
    rep = d.report()
    assert rep and all(r.passed for r in rep), [r for r in rep if not r.passed]
    assert d.verify() is True


def assert_check_rejects(d: Any, index: int, tampered: Any) -> None:
    """Check number ``index`` of ``d``, run on its own on the derivation ``tampered``, returns
    False without raising (an exception would only mean it could not run)."""
    check = d.checks[index]
    assert tampered.checks[index] is check
    res = check.run(tampered)
    assert res.error is None, f"{d.label}[{index}] ({check.description}) raised: {res.error}"
    assert res.passed is False, f"{d.label}[{index}] ({check.description}) accepts {tampered}"


def module_of(d: Any) -> str:
    """The module of :mod:`symhx.symbolic` that built ``d`` (its checks are defined there):
    ``"simple"``, ``"jump"``, ``"higher"`` or ``"asymptotic"``."""
    mods = {c.fn.__module__ for c in d.checks}
    assert len(mods) == 1, (d.label, mods)
    return mods.pop().rpartition(".")[2]


def check_indices(checks: dict[str, int]) -> list[tuple[str, int]]:
    """``(label, index)`` of every check of a table ``{label: number of checks}``."""
    return [(label, i) for label, n in checks.items() for i in range(n)]


def assert_module_table(module: str, checks: dict[str, int]) -> None:
    """The table ``{label: number of checks}`` of a test file lists exactly the derivations
    that ``symhx.symbolic.<module>`` builds, with their number of checks (a new derivation or
    check must get its tests)."""
    from symhx.symbolic import derivations

    got = {lab: len(d.checks) for lab, d in derivations().items() if module_of(d) == module}
    assert got == checks


def contract_tests(module: str, checks: dict[str, int],
                   tampers: dict[tuple[str, int], Callable[[Any], Any]] | None = None,
                   slow: frozenset[str] = frozenset()) -> tuple[Callable[..., None], ...]:
    """The three contract tests of the derivations of ``symhx.symbolic.<module>``, for its test
    file to bind at module level (pytest collects them by name)::

        (test_the_table_lists_every_derivation_of_the_module, test_every_derivation_verifies,
         test_each_check_rejects_a_tampered_result) = contract_tests("jump", CHECKS, TAMPER)

    ``checks`` is the file's table ``{label: number of checks}``; ``tampers`` maps
    ``(label, index)`` to a tampering aimed at that check (default :func:`tamper_result`);
    the derivations in ``slow`` are marked ``slow``."""
    from symhx.symbolic import derivation

    aimed = dict(tampers or {})

    def cases(items: list[tuple[Any, ...]]) -> list[Any]:
        return [pytest.param(*c, marks=pytest.mark.slow) if c[0] in slow else pytest.param(*c)
                for c in items]

    def test_the_table_lists_every_derivation_of_the_module() -> None:
        assert_module_table(module, checks)

    @pytest.mark.parametrize("label", cases([(lab,) for lab in checks]))
    def test_every_derivation_verifies(label: str) -> None:
        assert_verifies(derivation(label))

    @pytest.mark.parametrize("label, index", cases(check_indices(checks)))
    def test_each_check_rejects_a_tampered_result(label: str, index: int) -> None:
        d = derivation(label)
        assert_check_rejects(d, index, aimed.get((label, index), tamper_result)(d))

    return (test_the_table_lists_every_derivation_of_the_module, test_every_derivation_verifies,
            test_each_check_rejects_a_tampered_result)
