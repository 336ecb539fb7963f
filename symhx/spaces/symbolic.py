"""Closed forms of the class counts as sympy expressions (section 8, eqs. 35-40), and the paper's
printed formulas beside them. sympy is imported inside each function, never at module level.
"""

from __future__ import annotations

import math
from collections import Counter
from typing import Any

from symhx.circuits import necklaces_with_content, normalise_visits
from symhx.spaces._classes import PRINTED_RANGES, check_shape, class_count, printed_count
from symhx.validation import InputError

__all__ = [
    "boundary_table",
    "class_count_symbolic",
    "pattern_count_symbolic",
    "printed_formula",
    "verify_printed_formulas",
]


def pattern_count_symbolic(visits: Any) -> Any:
    """Circuits with visit pattern ``visits`` as a sympy expression in ``N``:
    ``N!/(N-k)! / prod_j c_j! * necklaces(visits)`` (Burnside), exact for every pattern.

    >>> pattern_count_symbolic((2, 2))
    N*(N - 1)
    >>> pattern_count_symbolic((2, 1, 1))
    3*N*(N - 2)*(N - 1)/2
    """
    import sympy as sp

    v = normalise_visits(visits)
    N = sp.Symbol("N", integer=True, positive=True)
    choose = sp.ff(N, len(v))
    for c in Counter(v).values():
        choose /= sp.factorial(c)
    return sp.factor(sp.expand_func(choose * necklaces_with_content(v)))


def class_count_symbolic(shape: Any) -> Any:
    """The count of class ``shape`` as a function of ``N`` and the length ``L`` (the paper's
    ``k``), valid for ``L > sum(shape)`` (at least one vertex visited once):
    ``N!/(N-L+e)! * (L-1)! / ((L-e-r)! C_s S_s)``.

    >>> class_count_symbolic((3,))
    factorial(N)*factorial(L - 1)/(6*factorial(L - 3)*factorial(-L + N + 2))
    """
    import sympy as sp

    s = check_shape(shape)
    N, L = sp.symbols("N L", integer=True, positive=True)
    e, r = sum(x - 1 for x in s), len(s)
    C = math.prod(math.factorial(c) for c in Counter(s).values())
    S = math.prod(math.factorial(x) for x in s)
    return sp.factorial(N) / sp.factorial(N - L + e) * sp.factorial(L - 1) / (
        sp.factorial(L - e - r) * C * S)


def printed_formula(eq: str) -> Any:
    """The paper's printed count (35), (36), (38), (39) or (40) in ``N`` and the length ``L``.

    >>> printed_formula("35")
    (L/2 - 1/2)*factorial(N)/factorial(-L + N + 1)
    """
    import sympy as sp

    N, L = sp.symbols("N L", integer=True, positive=True)
    f = sp.factorial
    forms = {
        "35": sp.Rational(1, 2) * (L - 1) * f(N) / f(N - (L - 1)),
        "36": N,
        "38": sp.Rational(1, 6) * f(L - 1) / f(L - 3) * f(N) / f(N - (L - 2)),
        "39": sp.Rational(1, 24) * f(L - 1) / f(L - 4) * f(N) / f(N - (L - 3)),
        "40": sp.Rational(1, 8) * f(L - 1) / f(L - 4) * f(N) / f(N - (L - 2)),
    }
    if eq not in forms:
        raise InputError(f"eq must be one of {sorted(forms)}, got {eq!r}")
    return forms[eq]


def verify_printed_formulas() -> dict[str, bool]:
    """Each printed formula equals the general class count inside its stated range (sympy
    ``gammasimp`` of the ratio is 1), and (36) equals the Burnside count at ``L = 2``.

    >>> verify_printed_formulas()
    {'35': True, '36': True, '38': True, '39': True, '40': True}
    """
    import sympy as sp

    out = {}
    for eq, (shape, _) in PRINTED_RANGES.items():
        ratio = sp.gammasimp(printed_formula(eq) / class_count_symbolic(shape))
        out[eq] = bool(sp.simplify(ratio) == 1)
    out["36"] = bool(sp.expand(printed_formula("36") - pattern_count_symbolic((2,))) == 0)
    return dict(sorted(out.items()))


def boundary_table(N: Any = None) -> list[dict[str, Any]]:
    """The boundary lengths where the printed formulas fail: class, length, what the formula
    gives there (``words / L``), the true count (Burnside) and the correction.

    With ``N=None`` the entries are sympy expressions in ``N``; with an int, exact numbers.

    >>> [(r["eq"], r["formula"], r["true"]) for r in boundary_table()]
    [('35', N/2, N), ('38', N/3, N), ('39', N/4, N), ('40', 3*N*(N - 1)/4, N*(N - 1))]
    >>> boundary_table(10)[3]["correction"]
    Fraction(45, 2)
    """
    rows = []
    for eq, (shape, _) in PRINTED_RANGES.items():
        L = sum(shape)
        if N is None:
            import sympy as sp

            form = sp.factor(sp.expand_func(printed_formula(eq).subs(
                sp.Symbol("L", integer=True, positive=True), L).rewrite(sp.ff)))
            form = sp.factor(sp.combsimp(form))
            true = pattern_count_symbolic(shape)
            rows.append({"eq": eq, "class": shape, "length": L, "formula": form, "true": true,
                         "correction": sp.factor(true - form)})
        else:
            form = printed_count(eq, N, L, outside="formula")
            true = class_count(N, shape, len(shape))
            rows.append({"eq": eq, "class": shape, "length": L, "formula": form, "true": true,
                         "correction": true - form})
    return rows
