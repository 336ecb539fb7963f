"""Building blocks of the derivation registry: :class:`Derivation`, :class:`Check` and helpers.

A :class:`Derivation` holds a sympy result derived from the definitions, the steps that led to
it (for display), the paper's printed form when there is one, and a list of :class:`Check`
objects. Every check is a function of the derivation *as it stands* (its ``result``), so a
derivation whose result has been tampered with (:meth:`Derivation.with_result`) fails.

Check kinds
-----------
``"symbolic"``
    an identity proved by sympy for symbolic ``N``, ``p``, ``k`` (positive symbols);
``"exact"``
    exact integer / rational arithmetic over a stated finite range (used where sympy cannot
    prove a factorial identity for symbolic arguments, and as an independent cross-check against
    :mod:`symhx.circuits` and brute-force enumeration);
``"numeric"``
    a high-precision (mpmath) comparison, used only for transcendental results (LambertW).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

__all__ = ["Check", "CheckResult", "Derivation", "N", "k", "log_equal", "p", "sym_equal"]

#: The symbols of every result: number of vertices, impact probability, circuit length / number
#: of distinct impacts. All declared positive (``k`` is not declared integer, so that the
#: continuous relaxation uses the same symbol).
N, p, k = sp.symbols("N p k", positive=True)


@dataclass(frozen=True)
class CheckResult:
    """Outcome of one :class:`Check`: ``passed`` is True only if the check ran and held."""

    description: str
    kind: str
    passed: bool
    error: str | None = None


@dataclass(frozen=True)
class Check:
    """One verification of a derivation.

    ``fn(derivation) -> bool`` must compute something from ``derivation.result`` (and possibly
    ``derivation.extra``); ``kind`` is ``"symbolic"``, ``"exact"`` or ``"numeric"`` and
    ``description`` says what was checked and over which range.
    """

    description: str
    kind: str
    fn: Callable[[Derivation], bool]

    def run(self, derivation: Derivation) -> CheckResult:
        try:
            ok = bool(self.fn(derivation))
        except Exception as exc:  # a check that cannot run has not verified anything
            return CheckResult(self.description, self.kind, False, f"{type(exc).__name__}: {exc}")
        return CheckResult(self.description, self.kind, ok)


@dataclass(frozen=True)
class Derivation:
    """A result of the paper (or a new one), derived with sympy, with its verification.

    Attributes
    ----------
    label : str
        The paper's equation label (``"16"``) or a descriptive key for new results
        (``"16-spurious"``, ``"crossing"``).
    description : str
        One line saying what the result is.
    result : sympy expression or ``Eq``
        The derived result, in the positive symbols ``N``, ``p``, ``k`` of this module.
    steps : tuple of (str, sympy object)
        The derivation, step by step (for display in the book).
    paper : sympy object or None
        The paper's printed right-hand side, when there is one (checked, never used to derive).
    extra : dict
        Further derived objects (e.g. the normaliser of eq. 8, the boundary cases of a count).
    checks : tuple of Check
    section : int
        Section of the paper.
    """

    label: str
    description: str
    result: Any
    checks: tuple[Check, ...] = ()
    steps: tuple[tuple[str, Any], ...] = ()
    paper: Any = None
    extra: dict[str, Any] = field(default_factory=dict)
    section: int = 0

    # ------------------------------------------------------------------ verification
    def report(self) -> list[CheckResult]:
        """Run every check and return their outcomes (nothing is cached)."""
        return [c.run(self) for c in self.checks]

    def verify(self) -> bool:
        """True only if there is at least one check and every check ran and passed.

        >>> from symhx.symbolic import derivations
        >>> derivations()["13"].verify()
        True
        """
        results = self.report()
        return bool(results) and all(r.passed for r in results)

    @property
    def verification_kinds(self) -> tuple[str, ...]:
        """The kinds of check used, e.g. ``("symbolic", "exact")``."""
        return tuple(dict.fromkeys(c.kind for c in self.checks))

    @property
    def verified_by(self) -> str:
        """Human-readable summary of how the result is verified (kinds and ranges)."""
        return "; ".join(f"[{c.kind}] {c.description}" for c in self.checks)

    # ------------------------------------------------------------------ display
    def latex(self) -> str:
        r"""LaTeX of the result (and of the extra equations, separated by ``\quad``)."""
        parts = [sp.latex(self.result)]
        parts += [sp.latex(v) for v in self.extra.values() if isinstance(v, sp.Basic)
                  and isinstance(v, (sp.Eq, sp.Equality))]
        return r",\quad ".join(parts)

    def with_result(self, result: Any) -> Derivation:
        """A copy with another result (the checks then test *that* result)."""
        return dataclasses.replace(self, result=result)

    def as_dict(self, *, verify: bool = False) -> dict[str, Any]:
        """JSON-friendly summary: label, description, result (str), LaTeX, and optionally checks."""
        out: dict[str, Any] = {
            "label": self.label,
            "section": self.section,
            "description": self.description,
            "result": sp.sstr(self.result),
            "latex": self.latex(),
            "kinds": list(self.verification_kinds),
        }
        if verify:
            rep = self.report()
            out["verified"] = bool(rep) and all(r.passed for r in rep)
            out["checks"] = [dataclasses.asdict(r) for r in rep]
        return out

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self.latex()}$"

    def __str__(self) -> str:
        return f"({self.label}) {self.description}: {sp.sstr(self.result)}"


# ---------------------------------------------------------------------- helpers
def sym_equal(a: Any, b: Any) -> bool:
    """Prove ``a == b`` with sympy (several simplifiers tried; False if none proves it).

    Works for rational functions, radicals and factorial / gamma ratios with symbolic arguments.

    >>> from sympy import factorial
    >>> sym_equal(factorial(N) / factorial(N - 1), N)
    True
    >>> sym_equal(N + 1, N)
    False
    """
    a, b = sp.sympify(a), sp.sympify(b)
    d = a - b
    if d == 0:
        return True
    for simp in (sp.expand, sp.cancel, _gamma_simp, sp.simplify):
        try:
            if simp(d) == 0:
                return True
        except Exception:  # pragma: no cover - simplifier failure just means "not proved"
            continue
    if b != 0:
        try:
            if _gamma_simp(a / b) == 1:
                return True
        except Exception:  # pragma: no cover
            pass
    return False


def log_equal(a: Any, b: Any) -> bool:
    """Prove ``a == b`` for *positive* ``a``, ``b`` by comparing expanded logarithms.

    Robust for products of powers with symbolic exponents (``(x**(1/(k-1)))**(k-1)``), where
    the result of ``powdenest`` depends on sympy's term order. Only valid when both sides are
    positive (the caller states why).

    >>> log_equal((N**(1/(k - 1)))**(k - 1), N)
    True
    """
    la = sp.expand(sp.expand_log(sp.log(sp.sympify(a)), force=True))
    lb = sp.expand(sp.expand_log(sp.log(sp.sympify(b)), force=True))
    return sym_equal(la, lb)


def _gamma_simp(e: Any) -> Any:
    e = sp.sympify(e).rewrite(sp.gamma)
    return sp.simplify(sp.gammasimp(e))


def rhs(d: Derivation) -> Any:
    """Right-hand side of ``d.result`` (or the result itself if it is not an equation)."""
    r = d.result
    return r.rhs if isinstance(r, sp.Equality) else r


def all_exact(pairs: Iterable[tuple[Any, Any]]) -> bool:
    """True if every pair is equal as exact rationals.

    ``got`` must evaluate (without any floating point) to a sympy Rational; ``want`` is an int,
    a :class:`fractions.Fraction` or a sympy Rational. Anything inexact counts as a failure.
    """
    from fractions import Fraction

    for got, want in pairs:
        g = sp.sympify(got)
        if not g.is_Rational:
            g = sp.simplify(g) if g.is_number and not g.atoms(sp.Float) else g
            if not g.is_Rational:
                return False
        if isinstance(want, Fraction):
            want = sp.Rational(want.numerator, want.denominator)
        if g != sp.sympify(want):
            return False
    return True
