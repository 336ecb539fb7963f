"""Refusals of :mod:`symhx.certify` quote the expression they refuse, cut to its first 60
characters (a sympy expression can print to megabytes), followed by the reason."""

from __future__ import annotations

import sympy

from symhx import certify

LONG = sum(sympy.sqrt(p) for p in (2, 3, 5, 7, 11, 13, 17, 19, 23))  # prints to 92 characters


def _message(fn, *args) -> str:
    try:
        fn(*args)
    except (ValueError, TypeError, ArithmeticError) as err:
        return str(err)
    raise AssertionError(f"{fn.__name__} did not refuse {args}")


def _quotes_60(msg: str, expr: sympy.Basic, after: str) -> None:
    text = str(expr)
    assert len(text) > 61
    assert text[:60] + after in msg, msg


def test_undecided_sign_quotes_60_characters() -> None:
    zero = sympy.Add(LONG, -LONG, evaluate=False)
    _quotes_60(_message(certify.real_sign, zero), zero, " is not decided at")


def test_negative_base_to_a_fractional_power_quotes_60_characters() -> None:
    expr = sympy.Pow(-LONG, sympy.Rational(1, 3), evaluate=False)
    _quotes_60(_message(certify.real_ball, expr), expr, " is not a real number")


def test_zero_to_a_negative_power_quotes_60_characters() -> None:
    expr = sympy.Pow(sympy.Integer(0), -LONG, evaluate=False)
    _quotes_60(_message(certify.real_ball, expr), expr, " is not a finite real number")


def test_unsupported_function_quotes_60_characters_of_the_expression() -> None:
    expr = sympy.besselj(1, LONG)
    _quotes_60(_message(certify.real_ball, expr), expr, ") as a rigorous real ball")
