"""Helpers shared by the CLI sub-commands: JSON output of exact and mpmath values."""

from __future__ import annotations

import json
from fractions import Fraction
from typing import Any

import mpmath


def jsonable(obj: Any) -> Any:
    """Convert ints, Fractions, mpf and containers into JSON-friendly values.

    Big ints and mpf become decimal strings (so no digit is lost); Fractions become "a/b".
    """
    if isinstance(obj, bool) or obj is None:
        return obj
    if isinstance(obj, int):
        return obj if abs(obj) < 2**53 else str(obj)
    if isinstance(obj, Fraction):
        if obj.denominator == 1:
            return jsonable(obj.numerator)
        return f"{obj.numerator}/{obj.denominator}"
    if isinstance(obj, mpmath.mpf):
        return mpmath.nstr(obj, mpf_digits(obj), strip_zeros=False)
    if isinstance(obj, float):
        return obj
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if hasattr(obj, "as_dict"):
        return jsonable(obj.as_dict())
    return str(obj)


def mpf_digits(x: mpmath.mpf) -> int:
    """Decimal digits carried by the mantissa of ``x`` (at least 17)."""
    bits = x._mpf_[3] if x._mpf_[1] else 53
    return max(15, mpmath.libmp.prec_to_dps(max(bits, 53)))


def dump_json(obj: Any) -> str:
    return json.dumps(jsonable(obj), indent=2)


def mpstr(x: Any, digits: int) -> str:
    """Decimal string of ``x`` with ``digits`` significant digits.

    mpf values are printed from their own mantissa (never re-rounded to the global precision);
    Fractions are printed as decimals with a trailing ``(exact a/b)`` when short enough.
    """
    if isinstance(x, int):
        return str(x)
    if isinstance(x, Fraction):
        if x.denominator == 1:
            return str(x.numerator)
        with mpmath.workdps(digits + 10):
            dec = mpmath.nstr(mpmath.mpf(x.numerator) / x.denominator, digits)
        exact = f"{x.numerator}/{x.denominator}"
        return f"{dec}  (exact {exact})" if len(exact) <= 60 else f"{dec}  (exact rational)"
    if isinstance(x, mpmath.mpf):
        digits = min(digits, mpf_digits(x))
        return mpmath.nstr(x, digits, strip_zeros=False, min_fixed=-5, max_fixed=12)
    return str(x)
