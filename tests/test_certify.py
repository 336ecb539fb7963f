"""symhx.certify against independent references: exact rationals for the conversions, an
mpmath sum at many digits for ``G``, the documented precision schedule of
:func:`certified_sign`, outward rounding checked with exact Arb comparisons, and the space
candidates against an exhaustive exact scan of ``W(k) = Phi(k) Q*(k)`` with Fractions."""

from __future__ import annotations

import math
from fractions import Fraction

import flint
import mpmath
import pytest
from flint import arb, fmpq, fmpz

from symhx.certify import (
    G_arb,
    UndecidedError,
    arb_prec,
    bits_for,
    certified_sign,
    mpf_bounds,
    rel_width_ok,
    space_candidates,
    to_arb,
)
from tests.reference.critical import G_log1p_sum
from tests.reference.distribution import phi_exact


def _exact_equal(ball: arb, fr: Fraction) -> bool:
    """The ball is exact and equals the rational ``fr`` (compared in exact fmpq arithmetic)."""
    if not ball.is_exact():
        return False
    man, exp = ball.mid().man_exp()
    val = Fraction(int(man)) * (Fraction(2) ** int(exp))
    return val == fr


# ------------------------------------------------------------------------------- to_arb
@pytest.mark.parametrize("x, exact", [
    (mpmath.mpf(3) * mpmath.mpf(2) ** 70, Fraction(3 * 2**70)),
    (mpmath.mpf(5) * mpmath.mpf(2) ** 3, Fraction(40)),
    (mpmath.mpf(7), Fraction(7)),
    (mpmath.mpf(3) / mpmath.mpf(2) ** 70, Fraction(3, 2**70)),
    (mpmath.mpf(-5) / 8, Fraction(-5, 8)),
    (mpmath.mpf(0.1), Fraction(0.1)),
])
def test_to_arb_mpf_is_exact(x, exact):
    with arb_prec(64):
        assert _exact_equal(to_arb(x), exact), (x, to_arb(x))


def test_to_arb_ints_and_rationals():
    with arb_prec(64):
        big = -(3**100)  # more bits than the precision: still exact (flint keeps fmpz exact)
        assert _exact_equal(to_arb(big), Fraction(big))
        assert _exact_equal(to_arb(-12345), Fraction(-12345))
        third = to_arb(Fraction(1, 3))
        assert third.contains(arb(fmpq(1, 3))) and third.rad() < arb(2) ** -60
        assert _exact_equal(to_arb(Fraction(-3, 8)), Fraction(-3, 8))

        class Rat:  # any object with integer numerator / denominator
            numerator, denominator = 7, 16

        assert _exact_equal(to_arb(Rat()), Fraction(7, 16))


def test_to_arb_mpf_zero_and_non_finite():
    # regression: man_exp has no sign, so a negative mpf used to come back positive, and
    # inf / nan came back as 0
    with arb_prec(64):
        assert _exact_equal(to_arb(mpmath.mpf(0)), Fraction(0))
        assert to_arb(-mpmath.mpf(2) ** -80) < 0
    for bad in (mpmath.inf, -mpmath.inf, mpmath.nan):
        with pytest.raises(ValueError, match="not a finite number"):
            to_arb(bad)


def test_to_arb_rejects_other_objects():
    class OnlyNumerator:
        numerator = 3

    class OnlyDenominator:
        denominator = 3

    for bad in ("1/2", None, 1.5j, OnlyNumerator(), OnlyDenominator()):
        with pytest.raises(TypeError, match=f"cannot convert {type(bad).__name__} to arb"):
            to_arb(bad)


# ------------------------------------------------------------------------------ bits_for / G
@pytest.mark.parametrize("N, K", [(2, 1), (3, 2), (10, 9), (101, 20), (1000, 999), (5000, 77)])
def test_G_arb_encloses_the_sum(N, K):
    ref = G_log1p_sum(N, K, 120)
    with arb_prec(400):
        g = G_arb(N, K)
    with mpmath.workdps(120):
        lo, hi = mpf_bounds(g, 100)
        assert lo <= ref <= hi
        assert hi - lo <= mpmath.mpf(10) ** -95 * abs(ref)


def test_G_arb_zero_terms_is_exactly_zero():
    for N in (2, 7, 10**40):
        with arb_prec(64):
            g = G_arb(N, 0)
        assert g.is_exact() and g == 0


@pytest.mark.parametrize("N", [10**6, 10**30, 10**100, 10**1000])
@pytest.mark.parametrize("extra", [20, 100])
def test_bits_for_delivers_extra_bits_after_the_cancellation(N, extra):
    # G(N, K) with K ~ sqrt(2N) is O(1) while lgamma(N) ~ N log N: the log2(N log N) bits
    # cancel, and the ball still has relative width below 2**-extra
    K = math.isqrt(2 * N)
    with arb_prec(bits_for(N, extra)):
        g = G_arb(N, K)
    assert abs(g.mid()) > arb("0.5") and g.rad() < abs(g.mid()) * arb(2) ** (-extra)
    # the exact value, for the N where the sum is short enough
    if N <= 10**6:
        ref = G_log1p_sum(N, K, 60)
        with mpmath.workdps(60):
            lo, hi = mpf_bounds(g, 40)
            assert lo <= ref <= hi


def test_bits_for_grows_with_N_and_extra():
    for N in (2, 3, 100, 10**9, 10**300):
        b = bits_for(N, 10)
        # at least log2(N log N) + extra, never absurdly more
        need = math.log2(N) + math.log2(max(math.log(N), 1)) + 10
        assert need <= b <= need + 40, (N, b)
        assert bits_for(N, 30) == b + 20


# ----------------------------------------------------------------------------- certified_sign
def _tiny(exponent: int, sign: int = 1):
    """A ball function for sign * 2**-exponent computed with cancellation: it contains 0 until
    the precision exceeds ~exponent bits. Records the precision of every call."""
    calls: list[int] = []

    def fn() -> arb:
        calls.append(flint.ctx.prec)
        s = arb(2).sqrt()
        return (s + sign * arb(2) ** -exponent) - s

    return fn, calls


def test_certified_sign_doubles_from_start():
    fn, calls = _tiny(300)
    assert certified_sign(fn, start_bits=70, max_bits=10_000) == 1
    assert calls == [70, 140, 280, 560]
    fn, calls = _tiny(300, -1)
    assert certified_sign(fn, start_bits=10, max_bits=10_000) == -1
    assert calls == [64, 128, 256, 512]  # the start is at least 64 bits


def test_certified_sign_is_capped_then_falls_back():
    fn, calls = _tiny(300)
    assert certified_sign(fn, start_bits=100, max_bits=300, exact_fn=lambda: 7) == 7
    assert calls == [100, 200, 300]  # the last step is clipped to max_bits
    fn, calls = _tiny(300)
    assert certified_sign(fn, start_bits=100, max_bits=400) == 1
    assert calls == [100, 200, 400]
    fn, calls = _tiny(1000)
    with pytest.raises(UndecidedError, match="sign not certified at 256 bits"):
        certified_sign(fn, start_bits=64, max_bits=256)
    assert calls == [64, 128, 256]
    # already certified at the start: one evaluation, the fall-back is not called
    fn, calls = _tiny(10)
    assert certified_sign(fn, start_bits=64, max_bits=64, exact_fn=lambda: 1 / 0) == 1
    assert calls == [64]


def test_certified_sign_restores_precision():
    before = flint.ctx.prec
    fn, _ = _tiny(200)
    certified_sign(fn, start_bits=64, max_bits=1024)
    assert flint.ctx.prec == before
    with arb_prec(333):
        assert flint.ctx.prec == 333
    assert flint.ctx.prec == before


# -------------------------------------------------------------------------- mpf_bounds
@pytest.mark.parametrize("dps", [5, 20, 60])
@pytest.mark.parametrize("scale", [1, -1])
def test_mpf_bounds_outward_and_tight(dps, scale):
    # balls with a long midpoint and radii from 0 (exact) to wide
    with arb_prec(2000):
        pi = scale * arb.pi()
        balls = [pi, arb(pi.mid()), arb(pi.mid(), arb(10) ** -(dps + 20)),
                 arb(pi.mid(), arb(10) ** -(dps - 2)), arb(fmpq(scale, 3)) * arb(10) ** -50,
                 arb(fmpz(scale * 12345))]
    for x in balls:
        lo, hi = mpf_bounds(x, dps)
        assert lo <= hi
        with arb_prec(4000):
            alo, ahi = to_arb(lo), to_arb(hi)
            assert alo.is_exact() and ahi.is_exact()
            assert alo <= x.lower() and x.upper() <= ahi  # outward (exact comparisons)
            # rounded to dps + 5 digits: at most one unit of that digit outside the ball
            slack = abs(x.mid()) * arb(10) ** -(dps + 5)
            assert x.lower() - alo <= slack and ahi - x.upper() <= slack, (x, lo, hi)


def test_mpf_bounds_of_exact_small_values_are_exact():
    with arb_prec(64):
        lo, hi = mpf_bounds(arb(3) / 8, 10)
    assert lo == hi == mpmath.mpf(3) / 8


# -------------------------------------------------------------------------- rel_width_ok
def test_rel_width_ok_negative_midpoint_and_boundary():
    with arb_prec(300):
        for dps in (3, 40):
            mid = arb(-7)
            r_ok = abs(mid) * arb(10) ** -dps / 4 * arb("0.999")
            r_bad = abs(mid) * arb(10) ** -dps / 4 * arb("1.001")
            assert rel_width_ok(arb(mid, r_ok), dps)
            assert not rel_width_ok(arb(mid, r_bad), dps)
            assert not rel_width_ok(arb(0, arb(10) ** -500), dps)  # contains 0
            assert rel_width_ok(arb(-2) ** -900, dps)  # exact
            assert not rel_width_ok(arb(mid, r_ok), dps + 1)


# ----------------------------------------------------------------------- space_candidates
CASES = [("eq41", 12, Fraction(1, 7)), ("eq41", 30, Fraction(1, 20)),
         ("eq41", 30, Fraction(3, 40)), ("excess<=2", 25, Fraction(1, 9)),
         ("excess<=3;distinct", 20, Fraction(1, 30)), ("eq41-printed", 40, Fraction(1, 33)),
         ("simple", 5, Fraction(1, 2)), ("simple", 101, Fraction(1, 50)),
         ("excess<=1", 60, Fraction(1, 25)), ("eq41", 9, Fraction(5, 2)),
         # just above p_c = 0.01288...: W dips after k = 1 and rises to its maximum at 20
         ("excess<=0", 101, Fraction(13, 1000)), ("excess<=0;distinct", 101, Fraction(13, 1000)),
         ("excess<=0", 101, Fraction(12, 1000))]


@pytest.mark.parametrize("name, N, p", CASES)
def test_space_candidates_against_exhaustive_scan(name, N, p):
    from symhx.spaces import parse_space

    space = parse_space(name)
    # W(k) = Phi_{N,p}(k) Q*(k): the factorials of eq. (8) times the space's Q*
    W = [phi_exact(N, p, k) * space.Qstar(k, p) for k in range(1, N + 1)]
    argmax = 1 + max(range(N), key=lambda i: W[i])
    tops = sorted({1, 2, argmax - 1, argmax, argmax + 1, N - 1, N} & set(range(1, N + 1)))
    for top in tops:
        got = space_candidates(space, N, p, top)
        want = sorted({top} | {k for k in range(1, N + 1) if W[k - 1] >= W[top - 1]})
        assert got == want, (name, N, p, top)
        assert argmax in got


def test_space_modes_just_above_the_jump():
    # regression: the float64 guess picks k = 1 (W(1) and W(20) agree to ~1e-14) and the scan
    # used to stop at the dip after it, so the mode of excess<=0 (the simple space) was 1
    import symhx
    from symhx.validation import as_fraction

    cp = symhx.critical_point(101, dps=40)
    with mpmath.workdps(80):
        for e in (14, 20, 30):
            p = as_fraction(cp.p * (1 + mpmath.mpf(10) ** -e))
            assert symhx.modes(101, p, space="excess<=0") == symhx.modes(101, p) == (20,)
            p = as_fraction(cp.p * (1 - mpmath.mpf(10) ** -e))
            assert symhx.modes(101, p, space="excess<=0") == (1,)


def test_space_candidates_exact_ties():
    from symhx.spaces import parse_space

    # simple space, N = 5, p = 1/2: Phi(1) = Phi(2) = Phi(3) (an exact three-way tie)
    simple = parse_space("simple")
    for top in (1, 2, 3):
        assert space_candidates(simple, 5, Fraction(1, 2), top) == [1, 2, 3]
    # N = 101, p = 1/50: Phi(50) = Phi(51)
    assert space_candidates(simple, 101, Fraction(1, 50), 50) == [50, 51]
    assert space_candidates(simple, 101, Fraction(1, 50), 51) == [50, 51]


def test_space_candidates_resolve_a_deep_near_tie():
    # p = (1 + 2**-150) / 50 with N = 101: W(51) / W(50) = 1 + 2**-150. The working precision
    # grows with the bits of p's numerator and denominator, so the balls separate the two
    from symhx.spaces import parse_space

    p = Fraction(2**150 + 1, 50 * 2**150)
    for name in ("excess<=0", "excess<=0;distinct"):
        space = parse_space(name)
        W50, W51 = (phi_exact(101, p, k) * space.Qstar(k, p) for k in (50, 51))
        assert W51 > W50
        assert space_candidates(space, 101, p, 51) == [51]
        assert space_candidates(space, 101, p, 50) == [50, 51]
    p = Fraction(2**150 - 1, 50 * 2**150)  # now W(50) / W(51) = 1 / (1 - 2**-150) > 1
    assert space_candidates(parse_space("excess<=0"), 101, p, 50) == [50]


# --------------------------------------------------------------------------- more boundaries
def test_certified_sign_of_an_exact_zero_goes_to_the_integers():
    # a ball [0 +/- 0] is neither > 0 nor < 0: the exact fall-back decides (a tie), however
    # many doublings
    calls = []

    def zero():
        calls.append(flint.ctx.prec)
        return arb(0)

    assert certified_sign(zero, start_bits=64, max_bits=256, exact_fn=lambda: 0) == 0
    assert calls == [64, 128, 256]
    half = arb(fmpq(1, 2), fmpq(1, 2))  # [0, 1]: touches 0, not certified either
    assert certified_sign(lambda: half, start_bits=64, max_bits=64, exact_fn=lambda: 5) == 5
    assert certified_sign(lambda: -half, start_bits=64, max_bits=64, exact_fn=lambda: 5) == 5


def test_certified_sign_message_shows_the_ball():
    x = arb(fmpq(1, 10**12), fmpq(1, 10**10))
    ball = x.str(5, radius=True)
    assert "+/-" in ball
    with pytest.raises(UndecidedError) as info:
        certified_sign(lambda: x, start_bits=64, max_bits=128)
    msg = str(info.value)
    # the precision reached, the ball itself, and the likely cause
    assert "128 bits" in msg and f"ball {ball}" in msg and "exact tie" in msg


def test_rel_width_ok_exact_equality_and_balls_around_one():
    # radius * 4 * 10**dps == |mid| exactly (dyadic radius): not below, so not ok
    for dps in (2, 10):
        with arb_prec(300):
            x0 = arb(1, arb(2) ** -10)
            rad = x0.rad()  # the radius as Arb stores it (a 30-bit mag)
            mid = rad * 4 * arb(10) ** dps
            x = (x0 - x0.mid()) + mid  # exact shifts keep the radius
            assert x.rad() == rad and x.mid() == mid and mid.is_exact()  # exact, as meant
            assert not rel_width_ok(x, dps)
            assert rel_width_ok(x + mid * arb(2) ** -40, dps)
    # a tight ball around 1 (it contains 1, not 0) is fine
    assert rel_width_ok(arb(1, arb(2) ** -100), 20)
    assert rel_width_ok(arb(-1, arb(2) ** -100), 20)


# ------------------------------------------------------------------------------ primitives
def test_certified_sign_on_a_true_tie_and_mpf_bounds_of_sqrt2():
    # a true tie is undecidable by balls: the exact fallback decides, or a clear error
    assert certified_sign(lambda: to_arb(3).sqrt() ** 2 - 3, start_bits=64, max_bits=256,
                          exact_fn=lambda: 0) == 0
    with pytest.raises(UndecidedError):
        certified_sign(lambda: to_arb(3).sqrt() ** 2 - 3, start_bits=64, max_bits=128)
    assert certified_sign(lambda: to_arb(Fraction(1, 3)) - to_arb(mpmath.mpf(1) / 3),
                          start_bits=64, max_bits=64) == 1  # 1/3 > its binary rounding
    with flint.ctx.workprec(300):
        lo, hi = mpf_bounds(flint.arb(2).sqrt(), 40)
    with mpmath.workdps(100):
        assert lo < mpmath.sqrt(2) < hi and (hi - lo) < mpmath.mpf(10) ** -44


def test_rel_width_ok_threshold():
    with flint.ctx.workprec(200):
        for dps in (5, 30):
            mid = flint.arb(3)
            ok = flint.arb(mid, mid * flint.arb(10) ** -dps / 5)   # width 2 r / mid = 0.4e-dps
            bad = flint.arb(mid, mid * flint.arb(10) ** -dps / 3)  # 2 r / mid = 0.67e-dps > 1/4
            assert rel_width_ok(ok, dps) and not rel_width_ok(bad, dps)
            assert rel_width_ok(flint.arb(7), dps) and not rel_width_ok(flint.arb(0, 1), dps)
