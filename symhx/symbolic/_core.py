"""Building blocks of the derivation registry: :class:`Derivation`, :class:`Check` and helpers.

A :class:`Derivation` holds a sympy result derived from the definitions, the steps that led to
it (for display), the paper's printed form when there is one, and a list of :class:`Check`
objects. Every check is a function of the derivation *as it stands* (its ``result``), so a
derivation whose result has been tampered with (:meth:`Derivation.with_result`) fails.

Every derivation, check and step carries two texts: a plain one (``description``, for the
terminal and JSON) and a Markdown one with ``$...$`` maths (``text``), which the book and
``symhx derive --latex`` show. Results are typeset by :func:`latex` (sympy's printer with
``psi`` for the digamma function and ``log Gamma`` for ``loggamma``).

Derivations are built on demand: each one is a function registered with :func:`register`
under its label, and the registry (:mod:`symhx.symbolic`) calls it only when that label is asked
for. Shared intermediate results (the quadratic ``f`` of eq. 10, the discriminant, ...) are
cached functions, so a derivation computes exactly what it depends on.

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
from typing import Any, NamedTuple

import sympy as sp
from sympy.printing.latex import LatexPrinter

__all__ = [
    "SPECS",
    "Check",
    "CheckResult",
    "Derivation",
    "N",
    "Spec",
    "Step",
    "k",
    "latex",
    "log_equal",
    "mp_lambdify",
    "p",
    "register",
    "sym_equal",
]

#: The symbols of every result: number of vertices, impact probability, circuit length / number
#: of distinct impacts. All declared positive (``k`` is not declared integer, so that the
#: continuous relaxation uses the same symbol).
N, p, k = sp.symbols("N p k", positive=True)


class _Printer(LatexPrinter):
    """sympy's LaTeX printer with the notation of the book: ``\\psi`` for the digamma function,
    ``\\log\\Gamma`` for ``loggamma``, ``\\exp(x)`` for the exponential of a compound ``x``,
    and the terms of an unevaluated sum in the order given."""

    def _print_polygamma(self, expr: Any, exp: Any = None) -> str:
        n, x = expr.args
        base = r"\psi" if n == 0 else rf"\psi^{{({self._print(n)})}}"
        tex = rf"{base}\left({self._print(x)}\right)"
        return tex if exp is None else rf"{tex}^{{{exp}}}"

    def _print_ExpBase(self, expr: Any, exp: Any = None) -> str:
        # exp(x) of a compound x as \exp(x): a fraction or a W in a superscript of a
        # superscript is too small to read
        arg = expr.args[0]
        if arg.is_Atom or (arg.is_Mul and len(arg.args) == 2 and -1 in arg.args
                           and arg.args[1].is_Atom):
            return super()._print_ExpBase(expr, exp)
        tex = rf"\exp\left({self._print(arg)}\right)"
        return tex if exp is None else rf"{tex}^{{{exp}}}"

    def _print_loggamma(self, expr: Any, exp: Any = None) -> str:
        tex = rf"\log\Gamma\left({self._print(expr.args[0])}\right)"
        return tex if exp is None else rf"\left({tex}\right)^{{{exp}}}"


def latex(expr: Any) -> str:
    r"""LaTeX of a sympy object in the book's notation.

    An equation is printed side by side; a left-hand side built as an *unevaluated* sum keeps
    its terms in the order given (``\Phi(k+1) - \Phi(k)``, not sympy's canonical
    ``-\Phi(k) + \Phi(k+1)``).

    >>> import sympy as sp
    >>> latex(sp.polygamma(0, N + 1))
    '\\psi\\left(N + 1\\right)'
    >>> f = sp.Function("f")
    >>> latex(sp.Eq(sp.Add(f(k + 1), -f(k), evaluate=False), 0))
    'f{\\left(k + 1 \\right)} - f{\\left(k \\right)} = 0'
    """
    printer = _Printer()
    if isinstance(expr, sp.Equality):
        return f"{_side(printer, expr.lhs)} = {printer.doprint(expr.rhs)}"
    return printer.doprint(expr)


def _side(printer: _Printer, expr: Any) -> str:
    if not isinstance(expr, sp.Add):
        return printer.doprint(expr)
    out = ""
    for i, term in enumerate(expr.args):
        neg = term.could_extract_minus_sign()
        body = printer.doprint(-term if neg else term)
        if isinstance(-term if neg else term, sp.Add):
            body = rf"\left({body}\right)"
        out += ("- " if neg else "+ " if i else "") + body + " "
    return out.strip().removeprefix("+ ")


def mp_lambdify(args: Any, expr: Any) -> Callable[..., Any]:
    """``sympy.lambdify(args, expr)`` evaluated in this thread's private mpmath context
    (:func:`symhx._mpctx.mp`): call the result inside ``mp().workdps(...)``, never the global
    ``mpmath.workdps``."""
    from sympy.utilities.lambdify import MPMATH_TRANSLATIONS

    from symhx._mpctx import mp

    ctx = mp()
    names = {name: getattr(ctx, name) for name in dir(ctx) if not name.startswith("_")}
    names.update({sym: getattr(ctx, mpname) for sym, mpname in MPMATH_TRANSLATIONS.items()
                  if hasattr(ctx, mpname)})
    names["mpmath"] = ctx
    return sp.lambdify(args, expr, modules=[names, "mpmath"])


@dataclass(frozen=True)
class CheckResult:
    """Outcome of one :class:`Check`: ``passed`` is True only if the check ran and held.

    ``text`` is the check's Markdown description (``$...$`` maths), as :attr:`Check.text`.
    """

    description: str
    kind: str
    passed: bool
    error: str | None = None
    text: str = ""

    @property
    def markdown(self) -> str:
        """The Markdown description, or the plain one in code font if there is none."""
        return self.text or f"`{self.description}`"


@dataclass(frozen=True)
class Check:
    """One verification of a derivation.

    ``fn(derivation) -> bool`` must compute something from ``derivation.result`` (and possibly
    ``derivation.extra``); ``kind`` is ``"symbolic"``, ``"exact"`` or ``"numeric"`` and
    ``description`` says what was checked and over which range (plain text); ``text`` says the
    same in Markdown with ``$...$`` maths.
    """

    description: str
    kind: str
    fn: Callable[[Derivation], bool]
    text: str = ""

    def run(self, derivation: Derivation) -> CheckResult:
        """Run the check on ``derivation``; an exception counts as a failure (with its message)."""
        try:
            ok = bool(self.fn(derivation))
        except Exception as exc:  # a check that cannot run has not verified anything
            return CheckResult(self.description, self.kind, False,
                               f"{type(exc).__name__}: {exc}", self.text)
        return CheckResult(self.description, self.kind, ok, None, self.text)


class Step(NamedTuple):
    """One step of a derivation: what is done (plain ``text`` and Markdown ``tex``) and the
    sympy object it gives."""

    text: str
    expr: Any
    tex: str = ""

    @property
    def markdown(self) -> str:
        """The Markdown text of the step, or the plain one in code font if there is none."""
        return self.tex or (f"`{self.text}`" if self.text else "")


@dataclass(frozen=True)
class Derivation:
    """A result of the paper (or a new one), derived with sympy, with its verification.

    Attributes
    ----------
    label : str
        The paper's equation label (``"16"``) or a descriptive key for new results
        (``"16-spurious"``, ``"crossing"``).
    description : str
        One line saying what the result is (plain text).
    result : sympy expression or ``Eq``
        The derived result, in the positive symbols ``N``, ``p``, ``k`` of this module.
    checks : tuple of Check
    steps : tuple of Step
        The derivation, step by step (for display in the book).
    paper : sympy object or None
        The paper's printed right-hand side, when there is one (checked, never used to derive).
    extra : dict
        Further derived objects (e.g. the normaliser of eq. 8, the boundary cases of a count).
    section : int
        Section of the paper.
    text : str
        The description in Markdown with ``$...$`` maths (what the book shows).
    """

    label: str
    description: str
    result: Any
    checks: tuple[Check, ...] = ()
    steps: tuple[Step, ...] = ()
    paper: Any = None
    extra: dict[str, Any] = field(default_factory=dict)
    section: int = 0
    text: str = ""

    # ------------------------------------------------------------------ verification
    def report(self) -> list[CheckResult]:
        """Run every check and return their outcomes (nothing is cached)."""
        return [c.run(self) for c in self.checks]

    def verify(self) -> bool:
        """True only if there is at least one check and every check ran and passed.

        >>> from symhx.symbolic import derivation
        >>> derivation("13").verify()
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
    @property
    def markdown(self) -> str:
        """The Markdown description, or the plain one in code font if there is none."""
        return self.text or f"`{self.description}`"

    def latex(self) -> str:
        r"""LaTeX of the result (and of the extra equations, separated by ``\quad``).

        >>> from symhx.symbolic import derivation
        >>> derivation("12").latex()
        'f_{N,p}{\\left(0 \\right)} = -1'
        """
        parts = [latex(self.result)]
        parts += [latex(v) for v in self.extra.values() if isinstance(v, sp.Basic)
                  and isinstance(v, (sp.Eq, sp.Equality))]
        return r",\quad ".join(parts)

    def with_result(self, result: Any) -> Derivation:
        """A copy with another result (the checks then test *that* result)."""
        return dataclasses.replace(self, result=result)

    def as_dict(self, *, verify: bool = False) -> dict[str, Any]:
        """JSON-friendly summary: label, description (plain and Markdown), result (str), LaTeX,
        and optionally the outcome of every check."""
        out: dict[str, Any] = {
            "label": self.label,
            "section": self.section,
            "description": self.description,
            "text": self.markdown,
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


# ---------------------------------------------------------------------- registration
@dataclass(frozen=True)
class Spec:
    """A registered derivation before it is built: its label, section and descriptions, and the
    function that builds the rest (:func:`register`)."""

    label: str
    section: int
    description: str
    text: str
    build: Callable[[], dict[str, Any]]

    def make(self) -> Derivation:
        """Build the derivation (calls :attr:`build`; no caching here)."""
        return Derivation(self.label, self.description, section=self.section, text=self.text,
                          **self.build())


#: every registered derivation, by label, in the order of registration
SPECS: dict[str, Spec] = {}


def register(label: str, section: int, description: str, text: str
             ) -> Callable[[Callable[[], dict[str, Any]]], Callable[[], dict[str, Any]]]:
    """Decorator: register a builder for ``label``. The builder takes no argument and returns
    the keyword arguments of :class:`Derivation` other than label, description, text and section
    (``result``, ``checks``, ``steps``, ``paper``, ``extra``)."""

    def deco(fn: Callable[[], dict[str, Any]]) -> Callable[[], dict[str, Any]]:
        if label in SPECS:  # pragma: no cover - programming error
            raise RuntimeError(f"duplicate derivation label {label!r}")
        SPECS[label] = Spec(label, section, description, text, fn)
        return fn

    return deco


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
