"""symhx.certify's balls, case by case: real_ball on every kind of sympy node it documents
(powers of every exponent kind, zero and sub-unit bases, the less common unary functions,
Min / Max / atan2 written unevaluated, E**x), its refusals, rational_bracket of large
numbers, mpf_bounds' rounding, the space balls against exact Fraction arithmetic and the
documented stopping rule of the candidate scan.

References are independent: sympy's evalf at three times the digits (every ball must contain
it and be tight to ``2**-(bits - 10)``), exact Fractions, exhaustive exact scans."""

from __future__ import annotations

import math
from fractions import Fraction

import flint
import mpmath
import pytest
import sympy
from flint import arb

from symhx import certify
from symhx.certify import (
    UndecidedError,
    arb_prec,
    certified_sign,
    decide_with_rising_precision,
    mpf_bounds,
    rational_bracket,
    real_ball,
    real_sign,
    rel_width_ok,
    space_candidates,
    space_candidates_ball,
    space_q_ball,
    to_arb,
)
from tests.reference.distribution import phi_exact
from tests.reference.irrational import bracket, sympy_value

S = sympy
R = sympy.Rational
NE = dict(evaluate=False)


def _assert_encloses_tightly(expr, bits):
    ref = sympy_value(expr, bits)
    with arb_prec(bits):
        ball = real_ball(expr)
        assert ball.contains(to_arb(ref)), (expr, bits, ball)
        assert ball.rad() <= abs(ball.mid()) * arb(2) ** (10 - bits), (expr, bits, ball)


# sympy keeps these as they are written (evaluate=False where it would rewrite them), so each
# reaches the branch of real_ball that handles its node
NODES = [
    # the less common unary functions
    S.cot(R(1, 3)), S.sec(R(1, 3)), S.csc(2), S.coth(R(1, 2)), S.zeta(3), S.zeta(R(5, 2)),
    S.digamma(R(1, 3), **NE), S.digamma(S.pi, **NE),
    S.Abs(S.Add(S.pi, -4, **NE), **NE), S.Abs(S.sqrt(2), **NE),
    S.floor(S.pi * 100, **NE), S.ceiling(S.E * 7, **NE), S.floor(-S.sqrt(2), **NE),
    # Min / Max: sympy sorts the arguments, the extreme one is first, in the middle or last
    S.Min(S.sqrt(2), S.pi, R(1, 3), **NE), S.Max(S.sqrt(2), S.pi, R(1, 3), **NE),
    S.Min(S.sqrt(2), S.pi, R(7, 2), **NE), S.Max(S.sqrt(2), R(1, 3), R(6, 5), **NE),
    2 * S.Max(-S.pi, -S.E, **NE) + S.Min(S.E, S.pi, S.sqrt(2), **NE),
    # atan2 in the four quadrants (swapping its arguments changes every value)
    S.atan2(S.sqrt(2), -S.pi, **NE), S.atan2(-S.sqrt(2), S.pi, **NE),
    S.atan2(-R(1, 3), -S.E, **NE), S.atan2(S.E, R(1, 7), **NE),
    # E**x written as a power
    S.Pow(S.E, S.sqrt(2), **NE), S.Pow(S.E, R(-7, 3), **NE), S.Pow(S.E, -S.pi, **NE),
    # integer, rational and real exponents, negative ones too; bases above and below 1
    S.Pow(1 + S.sqrt(2), -3, **NE), S.Pow(S.pi, -5, **NE), S.Pow(R(2, 7), -4, **NE),
    S.Pow(S.sqrt(3), R(-2, 5), **NE), S.Pow(R(1, 3), R(1, 2), **NE),
    S.Pow(R(1, 3), R(-5, 4), **NE), S.Pow(S.pi / 4, R(3, 7), **NE),
    S.Pow(R(2, 7), S.sqrt(2), **NE), S.Pow(R(5, 2), -S.pi, **NE),
    S.Pow(S.pi / 5, -S.E, **NE),
    # a rational written unevaluated (a sum of rationals is not a sympy Rational)
    S.Add(R(1, 3), R(1, 6), **NE), S.Mul(R(2, 3), R(9, 7), **NE),
]


@pytest.mark.parametrize("expr", NODES, ids=str)
@pytest.mark.parametrize("bits", [64, 400])
def test_real_ball_encloses_every_documented_node_tightly(expr, bits):
    _assert_encloses_tightly(expr, bits)


def test_real_ball_powers_of_an_exact_zero_base():
    zero_times_pi = S.Mul(0, S.pi, **NE)  # a ball that is exactly 0 without being Integer 0
    with arb_prec(64):
        for expr in (S.Pow(0, 3, **NE), S.Pow(0, R(1, 2), **NE), S.Pow(0, R(3, 2), **NE),
                     S.Pow(0, S.sqrt(2) / 2, **NE), S.Pow(0, S.pi, **NE),
                     S.Pow(zero_times_pi, R(3, 2), **NE), S.Pow(zero_times_pi, 2, **NE)):
            ball = real_ball(expr)
            assert ball.is_exact() and ball.is_zero(), (expr, ball)
        for expr in (S.Pow(0, R(-1, 2), **NE), S.Pow(0, -S.sqrt(2), **NE),
                     S.Pow(zero_times_pi, R(-3, 2), **NE)):
            with pytest.raises(ValueError, match="is not a finite real number") as info:
                real_ball(expr)
            assert str(expr) in str(info.value)
        # 0**0 written irrationally: sympy's value is 1; a refusal is fine, 0 is not
        expr = S.Pow(0, S.Mul(0, S.sqrt(2), **NE), **NE)
        try:
            ball = real_ball(expr)
        except ValueError:
            pass
        else:
            assert ball.contains(1), ball


def test_real_ball_rational_roots_of_perfect_powers_are_exact():
    # a rational exponent a/q goes through a q-th root (exact for perfect powers), not
    # exp(log): 4**(1/2) = 2, 4**(-3/2) = 1/8, 16**(3/4) = 8, exactly
    with arb_prec(64):
        for expr, want in ((S.Pow(4, R(1, 2), **NE), Fraction(2)),
                           (S.Pow(4, R(-3, 2), **NE), Fraction(1, 8)),
                           (S.Pow(16, R(3, 4), **NE), Fraction(8)),
                           (S.Pow(R(1, 4), R(1, 2), **NE), Fraction(1, 2))):
            ball = real_ball(expr)
            assert ball.is_exact(), (expr, ball)
            assert rational_bracket(ball) == (want, want)


@pytest.mark.parametrize("expr", [S.Pow(-8, R(1, 3), **NE), S.Pow(-S.pi, S.sqrt(2), **NE),
                                  S.Pow(S.Add(1, -S.pi, **NE), R(1, 2), **NE)], ids=str)
def test_real_ball_refuses_a_negative_base_to_a_fractional_power_naming_it(expr):
    with arb_prec(64), pytest.raises(ValueError, match="is not a real number") as info:
        real_ball(expr)
    assert str(expr) in str(info.value)


@pytest.mark.parametrize("expr", [S.oo, -S.oo, S.zoo, S.nan, S.I], ids=str)
def test_real_ball_refuses_non_finite_reals_with_a_value_error_naming_them(expr):
    with arb_prec(64), pytest.raises(ValueError, match="is not a finite real number") as info:
        real_ball(expr)
    assert str(expr) in str(info.value)


@pytest.mark.parametrize("expr, name", [
    (S.Si(1), "Si"), (S.sqrt(2) + S.Si(1), "Si"), (S.besselj(1, 2), "besselj"),
    # an integer-valued symbol in an exponent is no number: refused by name, never int(n)
    (S.Pow(2, S.Symbol("n", integer=True), **NE), "Symbol"),
], ids=str)
def test_real_ball_refusal_names_the_function_and_the_part(expr, name):
    part = next(a for a in sympy.preorder_traversal(expr)
                if getattr(getattr(a, "func", None), "__name__", "") == name)
    with arb_prec(64), pytest.raises(TypeError) as info:
        real_ball(expr)
    msg = str(info.value)
    assert f"cannot evaluate {name} " in msg and f"(in {part})" in msg, msg
    assert "exact rational or a float" in msg, msg


def test_to_arb_of_a_sympy_expression_is_its_real_ball():
    expr = S.sqrt(2) * S.pi
    ref = sympy_value(expr, 200)
    with arb_prec(200):
        ball = to_arb(expr)
        assert ball.contains(to_arb(ref)) and ball.rad() < arb(2) ** -185


# ------------------------------------------------------------------ signs and precision
def test_real_sign_starts_at_64_bits_doubles_and_stops_at_max_bits(monkeypatch):
    seen: list[int] = []
    walk = certify.real_ball

    tie = S.Add(S.pi, -S.pi, **NE)
    tiny = S.sqrt(2) - R(14142135623730950488016887242096, 10**31)

    def recording(x):
        if x is tie or x is tiny:  # the whole number, not its parts
            seen.append(flint.ctx.prec)
        return walk(x)

    monkeypatch.setattr(certify, "real_ball", recording)
    with pytest.raises(UndecidedError) as info:
        real_sign(tie, max_bits=256)
    assert seen == [64, 128, 256]
    assert "256 bits" in str(info.value) and "pi" in str(info.value)
    seen.clear()
    assert real_sign(tiny) == 1
    assert seen == [64, 128]  # 1e-32 relative needs more than 64 bits, 128 suffice


def test_decide_with_rising_precision_starts_no_lower_than_64_bits():
    tried: list[int] = []

    def note(bits):
        tried.append(bits)
        return "done" if bits >= 128 else None

    assert decide_with_rising_precision(note, start_bits=10, undecided=str) == "done"
    assert tried == [64, 128]


def test_certified_sign_message_says_what_is_likely_and_why():
    x = arb(0, 1)
    with pytest.raises(UndecidedError) as info:
        certified_sign(lambda: x, start_bits=64, max_bits=64)
    msg = str(info.value)
    assert "an exact tie is likely" in msg and "too large to compare exactly" in msg, msg


# -------------------------------------------------------------------- brackets and bounds
@pytest.mark.parametrize("expr", [10**40 * S.sqrt(2), -(10**40) * S.pi, S.Integer(3) * 2**100,
                                  S.Rational(2**90 + 1, 3)], ids=str)
def test_rational_bracket_of_large_numbers(expr):
    if expr.is_Rational:  # the exact value
        ref_lo = ref_hi = Fraction(int(expr.p), int(expr.q))
    else:
        ref_lo, ref_hi = bracket(expr, 150)
    for bits in (64, 300):
        with arb_prec(bits):
            lo, hi = rational_bracket(real_ball(expr))
        assert lo <= ref_lo and ref_hi <= hi, (expr, bits)
        assert (hi - lo) <= abs(ref_lo) * Fraction(2) ** (10 - bits), (expr, bits)
    if expr.is_Integer:  # exact: the bracket is the integer itself, twice
        with arb_prec(64):
            assert rational_bracket(real_ball(expr)) == (Fraction(int(expr)),) * 2


@pytest.mark.parametrize("dps", [5, 17, 40, 100])
def test_mpf_bounds_are_rounded_to_dps_plus_5_digits(dps):
    # lo <= x <= hi, each rounded (outward) to dps + 5 digits and a guard byte, not the
    # ball's own thousands of bits
    max_bits = int((dps + 5) * math.log2(10)) + 8
    widths = []
    for expr in (S.sqrt(2), S.pi / 7, -S.E * 10**30, S.sqrt(3) / 10**30, S.log(3) - 1):
        ref = sympy_value(expr, 3000)
        with arb_prec(3000):
            ball = real_ball(expr)
        lo, hi = mpf_bounds(ball, dps)
        with mpmath.workdps(1000):
            assert lo <= ref <= hi, (expr, dps)
            assert (hi - lo) <= abs(ref) * mpmath.mpf(10) ** -(dps + 4), (expr, dps)
        for end in (lo, hi):
            widths.append(end._mpf_[3])
            assert end._mpf_[3] <= max_bits, (expr, dps, end._mpf_)
    assert max(widths) >= max_bits - 8  # rounded to about that, not to far fewer digits


def test_rel_width_ok_when_the_midpoint_has_more_bits_than_the_radius():
    # mid = 1 + 2**-200 (exponent -200), radius ~ 2**-50 or 2**-120: the exponents differ
    # by a lot in both directions
    with arb_prec(300):
        mid = arb(1) + arb(2) ** -200
        wide, narrow = arb(mid, arb(2) ** -50), arb(mid, arb(2) ** -120)
        assert wide.mid() == mid and narrow.mid() == mid
    assert not rel_width_ok(wide, 20)   # 4 * 10**20 * 2**-50 ~ 3.6e5 > 1
    assert rel_width_ok(narrow, 20)     # 4 * 10**20 * 2**-120 ~ 3e-16 < 1
    assert rel_width_ok(wide, 13) and not rel_width_ok(wide, 15)  # 2**-50 = 8.9e-16


# ------------------------------------------------------------------------------- spaces
def _space(name):
    from symhx.spaces import parse_space

    return parse_space(name)


@pytest.mark.parametrize("name", ["eq41", "excess<=2", "excess<=3;distinct", "simple",
                                  "eq41-printed"])
@pytest.mark.parametrize("p", [Fraction(3, 8), Fraction(1, 7), Fraction(5, 2)])
def test_space_q_ball_encloses_the_exact_weight(name, p):
    space = _space(name)
    for k in (1, 2, 3, 5, 9, 30):
        exact = space.denominator * space.Qstar(k, p)  # D Q*(k) in Fractions
        with arb_prec(200):
            lo, hi = rational_bracket(space_q_ball(space, k, to_arb(p)))
        assert lo <= exact <= hi, (name, p, k)
        assert hi - lo <= exact * Fraction(2) ** -190, (name, p, k)


def _W(space, N, p):
    return [phi_exact(N, p, k) * space.Qstar(k, p) for k in range(1, N + 1)]


BALL_CASES = [("eq41", 12, Fraction(1, 7)), ("eq41", 30, Fraction(3, 40)),
              ("excess<=2", 25, Fraction(1, 9)), ("excess<=3;distinct", 20, Fraction(1, 30)),
              ("simple", 40, Fraction(1, 13)), ("excess<=1", 60, Fraction(1, 25)),
              ("excess<=0", 101, Fraction(13, 1000)), ("excess<=0", 101, Fraction(12, 1000))]


@pytest.mark.parametrize("name, N, p", BALL_CASES)
def test_space_candidates_ball_of_a_rational_against_exhaustive_scan(name, N, p):
    space = _space(name)
    W = _W(space, N, p)
    argmax = 1 + max(range(N), key=lambda i: W[i])
    for top in sorted({1, argmax, min(argmax + 1, N), N - 1}):
        with arb_prec(300):
            got = space_candidates_ball(space, N, to_arb(p), p, top)
        want = sorted({top} | {k for k in range(1, N + 1) if W[k - 1] >= W[top - 1]})
        assert got == want, (name, N, p, top)


def test_space_candidates_ball_keeps_the_mode_of_every_point_of_a_wide_ball():
    # excess<=0, N = 101: the mode jumps from 1 to 20 at p_c = 0.01288...; a ball over
    # [0.0125, 0.0131] must keep both, and the mode of every rational point inside it
    space = _space("excess<=0")
    lo, hi = Fraction(125, 10000), Fraction(131, 10000)
    with arb_prec(200):
        pa = arb((to_arb(lo) + to_arb(hi)) / 2, (to_arb(hi) - to_arb(lo)) / 2)
        assert pa.contains(to_arb(lo)) and pa.contains(to_arb(hi))
        got = space_candidates_ball(space, 101, pa, hi, 1)
    modes = set()
    for i in range(13):
        p = lo + (hi - lo) * i / 12
        W = _W(space, 101, p)
        modes.add(1 + max(range(101), key=lambda j: W[j]))
    assert {1, 20} <= modes <= set(got), (modes, got)


class _Counting:
    """A space that records the largest k whose Q* the scan asked for."""

    def __init__(self, space):
        self.space, self.max_k = space, 0
        self.max_parts, self.max_excess = space.max_parts, space.max_excess

    def Qnum(self, k, a, b):
        self.max_k = max(self.max_k, k)
        return self.space.Qnum(k, a, b)


STOP_CASES = [("simple", 12, Fraction(1, 7)),  # p (N - k) = 1 exactly at k = 5: no stop there
              ("eq41", 12, Fraction(1, 100)),  # the bound first holds at k = max_parts = 2
              ("eq41", 30, Fraction(3, 40)), ("excess<=2", 25, Fraction(1, 9)),
              ("excess<=3;distinct", 20, Fraction(1, 30)), ("excess<=1", 60, Fraction(1, 25)),
              ("simple", 101, Fraction(1, 50)), ("excess<=0", 101, Fraction(13, 1000)),
              ("eq41", 40, Fraction(1, 45)), ("excess<=2", 80, Fraction(1, 70))]


@pytest.mark.parametrize("name, N, p", STOP_CASES)
def test_space_candidates_scan_stops_where_the_documented_bound_allows(name, N, p):
    # the docstring's rule: stop at the first k > max(top, r) with W(k) < W(top) and
    # rho(k) = p (N - k) max((k + m)/(k + 1 - r), 1) < 1; W and rho exact here
    space = _space(name)
    W = _W(space, N, p)
    m, r = space.max_excess, space.max_parts
    argmax = 1 + max(range(N), key=lambda i: W[i])
    for top in sorted({1, argmax, min(argmax + 1, N)}):
        stop = N
        for k in range(top + 1, N + 1):
            rho = p * (N - k) * max(Fraction(k + m, k + 1 - r), Fraction(1)) if k > r else None
            if W[k - 1] < W[top - 1] and rho is not None and rho < 1:
                stop = k
                break
        counting = _Counting(space)
        got = space_candidates(counting, N, p, top)
        assert counting.max_k == max(stop, top), (name, N, p, top, counting.max_k, stop)
        assert got == sorted({top} | {k for k in range(1, N + 1) if W[k - 1] >= W[top - 1]})
