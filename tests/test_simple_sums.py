"""The simple-space summation engine (symhx.simple_sums): D(x) for real x against loggamma at
high precision, the significant runs, and sums against every term added."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import pytest

from symhx._mpctx import mp
from symhx.simple_sums import SimpleSums
from tests.reference.distribution_large_n import direct_sums, log_phi_ratio


@pytest.mark.parametrize(("N", "p", "top"), [(100, Fraction(1, 50), 49),
                                             (10**6, Fraction(2, 10**6), 500000),
                                             (10**30, Fraction(3, 10**30), 2 * 10**30 // 3),
                                             (10**6, Fraction(1, 10**6), None)])
def test_D_at_real_points_matches_loggamma(N: int, p: Fraction, top) -> None:
    s = SimpleSums(N, p, 30, top)
    ctx = mp()
    with ctx.workdps(s.W):
        for off in ("0.5", "-37.25", "1234.125", "-4321.75"):
            d = ctx.mpf(off)
            x = s.c + d
            if not 0 < x < N + 1:
                continue
            got = s.D(x, d)
            with mpmath.workdps(2 * len(str(N)) + 80):
                want = log_phi_ratio(N, p, mpmath.mpf(s.c) + mpmath.mpf(off), s.c)
            with mpmath.workdps(60):
                assert abs(mpmath.mpf(got) - want) <= mpmath.mpf(10) ** -40 * max(1, abs(want))
        for k in (1, 2, N):
            with mpmath.workdps(60):
                want = log_phi_ratio(N, p, k, s.c)
                assert abs(mpmath.mpf(s.D(k)) - want) <= mpmath.mpf(10) ** -38 * max(1, abs(want))


def _hump_top(N: int, p: Fraction) -> int | None:
    """The local maximum of Phi beyond k = 1 by the exact term ratio
    r(k) = Phi(k+1)/Phi(k) = p (N - k) k / (k + 1): the first k past the peak of r with r(k) < 1,
    when r reaches 1 at all (a scan in Fractions, independent of the engine)."""
    peak = max(range(1, N), key=lambda k: p * (N - k) * k / (k + 1))
    if p * (N - peak) * peak / (peak + 1) < 1:
        return None
    return next(k for k in range(peak, N + 1) if k == N or p * (N - k) * k / (k + 1) < 1)


@pytest.mark.parametrize(("N", "p", "top"), [(10**5, Fraction(1013, 10**8), None),
                                             (10**5, Fraction(2, 10**5), 50000),
                                             (10**5, Fraction(999, 10**8), None)])
def test_sums_against_every_term(N: int, p: Fraction, top) -> None:
    s = SimpleSums(N, p, 30, _hump_top(N, p))
    ctx = mp()
    with ctx.workdps(s.W):
        s0, s1, s2 = s.sums(1, N, (0, 1, 2))
        mean = s.c + s1 / s0
        var = s2 / s0 - (s1 / s0) ** 2
    _, want_mean, want_var = direct_sums(N, p, 40)
    with mpmath.workdps(60):
        assert abs(mpmath.mpf(mean) / want_mean - 1) < mpmath.mpf(10) ** -30
        assert abs(mpmath.mpf(var) / want_var - 1) < mpmath.mpf(10) ** -29


def test_runs_keep_the_tail_of_a_range() -> None:
    """A range far in the left tail gets its own significant run (relative accuracy)."""
    N = 10**6
    s = SimpleSums(N, Fraction(2, N), 20, 500000)
    runs = s.runs(1, 400000)
    assert runs and runs[-1][1] == 400000
    assert s.runs() == s.runs(1, N)


@pytest.mark.parametrize("dps", [2000, pytest.param(4950, marks=pytest.mark.slow)])
def test_thousands_of_digits_at_moderate_N(dps: int) -> None:
    """log Phi at dps ~5000 needs ~1700 Stirling coefficients (mpmath's Bernoulli numbers took
    11 s of a 13 s pass): the mean at N = 10**4 above the jump at dps against dps + 50."""
    import symhx

    p = 3e-4  # a float: the mpmath path (an exact p would be summed in Fractions)
    a = symhx.distribution_of(10**4, p, dps=dps).mean()
    b = symhx.distribution_of(10**4, p, dps=dps + 50).mean()
    with mpmath.workdps(dps + 80):
        assert abs(a - b) <= abs(b) * mpmath.mpf(10) ** (1 - dps)


def _hard_case(N: int) -> tuple[Fraction, int]:
    """p with N p - 1 = 2 (N p_c - 1) (head and hump both present; the head ~e**-358 of the
    hump's top at N = 10**100) as an exact rational, and the hump's top."""
    import symhx
    from symhx.validation import mpf_to_fraction

    q = symhx.critical_point(N, dps=120).q
    with mpmath.workdps(2 * len(str(N)) + 120):
        p = mpf_to_fraction((1 + 2 * mpmath.mpf(q)) / N)
    return p, symhx.mode(N, p)


def test_a_negligible_head_is_left_out_and_is_negligible() -> None:
    """Near p_c at N = 10**100 the head [1, valley] holds 10**50 terms of ~e**-358 each: the runs
    of the whole support leave it out, and summed on its own (where it is the largest part) it
    is below 10**-(dps + guard) of the total for every weight (sigma**j for (k - c)**j)."""
    N = 10**100
    p, top = _hard_case(N)
    s = SimpleSums(N, p, 30, top)
    runs = s.runs(1, N)
    m = s.valley()
    assert len(runs) == 1 and runs[0][0] > m
    ctx = mp()
    with ctx.workdps(s.W):
        head = s.sums(1, m, (0, 1, 2))
        full = s.sums(1, N, (0, 1, 2))
        sigma2 = full[2] / full[0] - (full[1] / full[0]) ** 2
        eps = ctx.mpf(10) ** -s.R
        assert 0 < head[0] < eps * full[0]
        assert abs(head[1]) < eps * full[0] * ctx.sqrt(sigma2)
        assert head[2] < eps * full[0] * sigma2


def test_dD_near_the_end_of_the_support_at_huge_N() -> None:
    """D'(x) = log p + psi(N + 1 - x) - 1/x at x = N, N - 1 (N + 1 - x = 1, 2) for N = 10**100:
    ``(x - c)/u`` rounds to 1 there, so ``log(1 - d/u)`` must come from ``log(v/u)``."""
    N, p = 10**100, Fraction(2, 10**100)
    s = SimpleSums(N, p, 30, N // 2)
    ctx = mp()
    for x in (N, N - 1, N - 10**6):
        with ctx.workdps(s.W):
            got = s.dD(x)
        with mpmath.workdps(300):
            want = mpmath.log(mpmath.mpf(2) / N) + mpmath.digamma(N + 1 - x) - 1 / mpmath.mpf(x)
            assert abs(mpmath.mpf(got) - want) < mpmath.mpf(10) ** -35 * abs(want)


def test_extra_working_digits_do_not_move_the_cuts() -> None:
    """An engine with extra working digits (a range far in a tail, where |D| ~ 10**99 needs them
    for absolute accuracy) cuts its runs at the level of its relative digits, not of its
    working ones: the cuts are the same with 110 and 160 extra digits."""
    N = 10**100
    import symhx

    p = Fraction(4, N)  # above the jump: [1, 10**50] is far in the hump's left tail
    top = symhx.mode(N, p)
    a = SimpleSums(N, p, 30, top, extra=110)
    b = SimpleSums(N, p, 30, top, extra=160)
    assert a.R == b.R and a.W + 50 == b.W
    ra = a.runs(1, 10**50)
    assert ra == b.runs(1, 10**50)
    (lo, hi), = ra
    # terms grow by ~N p = 4 per step: the run holds (R ln 10 + ln 10**50 + 10)/ln 4 terms
    want = (a.R * math.log(10) + 50 * math.log(10) + 10) / math.log(4)
    assert hi == 10**50 and abs((hi - lo + 1) - want) < 3


@pytest.mark.parametrize("v", [1, 2, 7, 20, 10**4, 10**6, 10**100])
def test_taylor_coefficients_of_lgamma_against_polygamma(v: int) -> None:
    """The coefficients of -lgamma(v - t) are -(-1)**n psi^(n-1)(v)/n!, each to the working
    precision relative to itself (Arb's series carry absolute errors of lgamma(v)'s size:
    the last coefficient is 10**-4000 of it at v = 10**100)."""
    s = SimpleSums(10**6, Fraction(2, 10**6), 40, 500000)
    ctx = mp()
    with ctx.workdps(s.W):
        got = s._lgamma_series(v, 40)
    with mpmath.workdps(s.W + 20):
        for n, g in enumerate(got, 2):
            want = -(-1) ** n * mpmath.polygamma(n - 1, v) / mpmath.factorial(n)
            assert abs(mpmath.mpf(g) - want) <= abs(want) * mpmath.mpf(10) ** (2 - s.W), n


@pytest.mark.parametrize(("N", "p"), [(10**6, Fraction(1, 10**12)), (10**4, Fraction(1, 10**3)),
                                      (2, Fraction(3, 5)), (10**5, Fraction(3, 2))])
def test_short_runs_in_integers_match_every_term(N: int, p: Fraction) -> None:
    """Runs up to direct_terms long are walked in fixed-point integers: the moments of a point
    mass at k = 1 (its variance lives in the terms past the plain cut), of a head, of N = 2
    and of a mass at k = N, against mpmath adding every term (head_sums / direct_sums)."""
    import symhx
    from tests.reference.distribution_large_n import direct_sums, head_sums

    top = symhx.mode(N, p)
    s = SimpleSums(N, p, 30, top if top > 1 else None)
    ctx = mp()
    with ctx.workdps(s.W):
        s0, s1, s2 = s.sums(1, N, (0, 1, 2))
        mean = s.c + s1 / s0
        var = s2 / s0 - (s1 / s0) ** 2
    ref = head_sums(N, p, 60, 400) if N > 10**5 else direct_sums(N, p, 60)
    with mpmath.workdps(60):
        assert abs(mpmath.mpf(mean) / ref[1] - 1) < mpmath.mpf(10) ** -30
        assert abs(mpmath.mpf(var) / ref[2] - 1) < mpmath.mpf(10) ** -29


@pytest.mark.parametrize(("N", "p"), [(60, Fraction(1, 20)), (3000, Fraction(1, 1000)),
                                      (3000, Fraction(1, 10**5)), (20000, Fraction(3, 10**4)),
                                      (2 * 10**5, Fraction(3, 10**5))])
def test_sums_weighted_by_D_against_every_term(N: int, p: Fraction) -> None:
    """Weight 3 (``D(k) = log(Phi(k)/Phi(c))``, the entropy's sum): ``sum f log f`` against
    every term walked by the exact ratio from mpmath's loggamma, above and below the jump and
    through both the term-by-term and (N = 2e5) the Euler-Maclaurin routes.  Above the jump
    the walk covers the mode +- 40 sqrt(mode) (the hump's width is about sqrt(mode); the
    terms outside are below e**-800 of the top)."""
    import symhx

    top = symhx.mode(N, p)
    s = SimpleSums(N, p, 30, top if top > 1 else None)
    ctx = mp()
    with ctx.workdps(s.W):
        s0, s3 = s.sums(1, N, (0, 3))
    a, b = (1, N) if top == 1 else (max(1, top - 40 * math.isqrt(top)),
                                    min(N, top + 40 * math.isqrt(top)))
    with mpmath.workdps(60):
        pm = mpmath.mpf(p.numerator) / p.denominator
        f = mpmath.exp(log_phi_ratio(N, p, a, s.c))
        want0 = want3 = mpmath.mpf(0)
        for k in range(a, b + 1):
            if f:
                want0 += f
                want3 += f * mpmath.log(f)
            f = f * pm * (N - k) * k / (k + 1)
        assert abs(mpmath.mpf(s0) / want0 - 1) < mpmath.mpf(10) ** -30
        # relative to the sum of f times the weight's scale (|D| + 1 over the mass)
        assert abs(mpmath.mpf(s3) - want3) < mpmath.mpf(10) ** -29 * (abs(want3) + want0)
