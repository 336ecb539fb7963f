"""The mpmath path of the simple distribution keeps ``dps`` significant digits: against exact
Fractions of the float's binary value, against sums over the whole support at twice the digits,
at huge N, tiny p, 300 digits, irrational p and long mantissas.

References, none of which uses symhx's distribution code (see
:mod:`tests.reference.distribution`): the factorial form in exact Fractions; the term ratio run
downwards from ``k = N`` at ``2 dps + 20`` digits; ``log Phi(k)`` from ``loggamma`` at ``2 dps +
20`` digits with every term summed; near ``k = N`` for ``p > 1`` the exact ratio
``Phi(N-j) / Phi(N) = p**-j N / ((N-j) j!)``.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import pytest

import symhx
from symhx.distribution import SimpleDistribution
from tests.harness.discrete import Path
from tests.reference.distribution import (
    ExactTable,
    fraction_of,
    moments_of,
    pmf_by_downward_ratio,
    pmf_by_loggamma,
    to_mp,
)


def _check_sums(d: SimpleDistribution, ref: list[mpmath.mpf], ks: list[int], dps: int) -> None:
    """mean, var, pmf, cdf and sf of ``d`` within ``10**(1 - dps)`` of a pmf summed in full."""
    path = Path.mp(dps)
    with mpmath.workdps(2 * dps + 20):
        mu, var = moments_of(ref)
        path.value(d.mean(), mu, "mean")
        path.value(d.var(), var, "var")
        for k in ks:
            path.value(d.pmf(k), ref[k - 1], ("pmf", k))
            if k < d.N:
                path.value(d.cdf(k), mpmath.fsum(ref[:k]), ("cdf", k))
                path.value(d.sf(k), mpmath.fsum(ref[k:]), ("sf", k))


def _sympy_value(p: object, dps: int) -> mpmath.mpf:
    """A sympy number at ``2 dps + 40`` digits (enough for the references above)."""
    import sympy

    with mpmath.workdps(2 * dps + 40):
        return mpmath.mpf(str(sympy.N(p, 2 * dps + 40)))


# --------------------------------------------------------------------------- against exact
@pytest.mark.parametrize("N", [2, 3, 4, 5, 17, 100, 101, 1000])
@pytest.mark.parametrize("p", [1e-300, 1e-3, 0.02, 0.3, 1.0])
def test_mpmath_path_matches_exact(N, p):
    """Floats are exact binary rationals: the exact path is an independent route."""
    if p == 1e-300 and N > 200:
        pytest.skip("exact reference with a 2**-1000 denominator is too slow at this N")
    exact = symhx.distribution_of(N, Fraction(p))
    d = symhx.distribution_of(N, p, dps=40)
    tol = mpmath.mpf(10) ** -38
    with mpmath.workdps(60):
        for got, want in [(d.mean(), exact.mean()), (d.var(), exact.var())]:
            want = to_mp(want)
            assert abs(got - want) <= tol * abs(want) + mpmath.mpf(10) ** -300, (got, want)
        for k in {1, 2, max(1, N // 2), N}:
            want = exact.pmf(k)
            lw = mpmath.log(want.numerator) - mpmath.log(want.denominator)
            assert abs(d.logpmf(k) - lw) <= tol * max(1, abs(lw))


@pytest.mark.parametrize("dps", [15, 60])
def test_variance_of_a_point_mass(dps: int) -> None:
    """p -> 0: all mass at k = 1 and var X = P(X=2) (1 + O(p)); the window must widen until the
    tiny variance is itself accurate to dps digits."""
    N = 11
    path = Path.mp(dps)
    for pf in (1e-20, 1e-200):
        t = ExactTable.simple(N, Fraction(pf))
        d = symhx.distribution_of(N, pf, dps=dps)
        path.value(d.var(), t.var, ("var", pf))
        path.value(d.mean(), t.mean, ("mean", pf))
        path.value(d.sf(1), t.sf(1), ("sf", pf))
        path.value(d.pmf(N), t.pmf[-1], ("pmf N", pf))


def test_three_hundred_digits() -> None:
    """At 300 digits (guard digits cut by a few would show)."""
    N, pf, dps = 120, 0.021, 300
    t = ExactTable.simple(N, Fraction(pf))
    d = symhx.distribution_of(N, pf, dps=dps)
    path = Path.mp(dps)
    path.value(d.mean(), t.mean)
    path.value(d.var(), t.var)
    for k in (1, 20, 100, N):
        path.value(d.pmf(k), t.pmf[k - 1], k)
        path.value(d.sf(k - 1) if k > 1 else d.cdf(1), t.sf(k - 1) if k > 1 else t.pmf[0], k)


def test_p_with_a_long_mantissa() -> None:
    """An mpf p carrying 1300 bits (its exact value has a huge numerator and denominator) is cut
    to the working precision before use: results match the exact value's reference."""
    with mpmath.workdps(400):
        pm = mpmath.mpf(1) / 3 + mpmath.mpf(10) ** -350
    N, dps = 9, 25
    d = symhx.distribution_of(N, pm, dps=dps)
    t = ExactTable.simple(N, fraction_of(pm))
    Path.mp(dps).value(d.mean(), t.mean, "mean")
    for k in (1, 5, N):
        Path.mp(dps).value(d.pmf(k), t.pmf[k - 1], k)


# --------------------------------------------------------------------------- against full sums
@pytest.mark.parametrize(("N", "pf"), [(100, 0.02), (1000, 0.0021), (1000, 1e-4), (1000, 0.9),
                                       (5000, 5e-4), (5000, 1e-6), (300, 0.0101)])
def test_large_N_against_downward_recurrence(N: int, pf: float) -> None:
    """N up to 5000 against every term summed at 2 dps + 20 digits, tails included (the
    package keeps only the terms within dps + guard digits of the largest)."""
    dps = 30
    path = Path.mp(dps)
    ref = pmf_by_downward_ratio(N, Fraction(pf), 2 * dps + 20)
    d = symhx.distribution_of(N, pf, dps=dps)
    m = d.mode()
    with mpmath.workdps(2 * dps + 20):
        assert max(ref) == ref[m - 1]
        ks = sorted({min(k, N) for k in (1, 2, 3, m // 2 + 1, m, m + 1, m + 7, 3 * m + 40)}
                    | {N - 1, N})
        cum = [mpmath.mpf(0)]
        for x in ref:
            cum.append(cum[-1] + x)
        for k in ks:
            path.value(d.pmf(k), ref[k - 1], ("pmf", k))
            path.log(d.logpmf(k), ref[k - 1], ("logpmf", k))
            if k < N:
                up = mpmath.fsum(ref[k:])
                path.value(d.sf(k), up, ("sf", k))
                path.log(d.logsf(k), up, ("logsf", k))
                path.value(d.cdf(k), cum[k], ("cdf", k))
                path.log(d.logcdf(k), cum[k], ("logcdf", k))
        mu, var = moments_of(ref)
        # terms < 10**-(2 dps + 20) change h by < N 10**-(dps + 10) (x log(1/x) < sqrt(x))
        h = -mpmath.fsum(x * mpmath.log(x) for x in ref if x > mpmath.mpf(10) ** (-2 * dps - 20))
        path.value(d.mean(), mu, "mean")
        path.value(d.var(), var, "var")
        path.value(d.std(), mpmath.sqrt(var), "std")
        assert abs(d.entropy() - h) <= mpmath.mpf(10) ** -dps
        med = next(k for k in range(1, N + 1) if cum[k] >= mpmath.mpf(1) / 2)
    assert d.median() == med


@pytest.mark.parametrize("dps", [15, 50, 200])
def test_precision_follows_dps(dps):
    N, p = 10**4, mpmath.mpf("0.0003")
    lo = symhx.mean(N, p, dps=dps)
    hi = symhx.mean(N, p, dps=2 * dps)
    with mpmath.workdps(2 * dps):
        assert abs(lo - hi) <= mpmath.mpf(10) ** (1 - dps) * abs(hi)


def test_huge_N_log_space():
    N = 10**6
    d = symhx.distribution_of(N, 2.5e-6, dps=30)
    d2 = symhx.distribution_of(N, 2.5e-6, dps=60)
    with mpmath.workdps(60):
        assert abs(d.mean() - d2.mean()) <= mpmath.mpf(10) ** -28 * d2.mean()
        assert abs(d.var() - d2.var()) <= mpmath.mpf(10) ** -28 * d2.var()
    assert 1 <= d.mean() <= N
    # the pmf underflows a float but not the log-pmf
    assert d.logpmf(N) < -1e5 and mpmath.isfinite(d.logpmf(N))
    assert float(mpmath.exp(d.logpmf(N))) == 0.0
    # logpmf(k+1) - logpmf(k) = log(p (N-k) k / (k+1))  (ratio of eq. 8 terms)
    k = 1234
    with mpmath.workdps(40):
        want = mpmath.log(mpmath.mpf(2.5e-6) * (N - k) * k / (k + 1))
        assert abs((d2.logpmf(k + 1) - d2.logpmf(k)) - want) < mpmath.mpf(10) ** -28


def test_tiny_p_all_mass_at_one():
    N, p = 1000, 1e-300
    d = symhx.distribution_of(N, p, dps=30)
    with mpmath.workdps(40):
        # P(X=2)/P(X=1) = p (N-1)/2
        assert mpmath.almosteq(d.logpmf(2) - d.logpmf(1), mpmath.log(mpmath.mpf(p) * (N - 1) / 2),
                               rel_eps=mpmath.mpf(10) ** -25)
    assert abs(d.mean() - 1) < 1e-290 and d.mode() == 1


@pytest.mark.parametrize(("N", "p"), [(10**15, 0.5), (10**20, 2.0), (10**30, 10.0)])
def test_logpmf_near_N_for_huge_N_keeps_every_digit(N: int, p: float) -> None:
    """For p >= 1/2 the mass sits at k = N - j, j small, and log Phi(k) ~ N log(N p) is huge:
    the guard digits (two per digit of N) must cover its cancellation against log Gamma.
    Reference: P(X = N - j) from the exact ratio p**-j N / ((N - j) j!), j < 300."""
    dps = 15
    d = SimpleDistribution(N, p, dps=dps)
    path = Path.mp(dps)
    with mpmath.workdps(60):
        pm = mpmath.mpf(p)
        w = [pm ** -j / mpmath.factorial(j) * N / (N - j) for j in range(300)]
        s = mpmath.fsum(w)
        for j in (0, 1, 5, 20):
            want = w[j] / s
            path.value(d.pmf(N - j), want, ("pmf", j))
            lw = mpmath.log(want)
            assert abs(d.logpmf(N - j) - lw) <= mpmath.mpf(10) ** (1 - dps) * abs(lw), j


# --------------------------------------------------------------------------- irrational p
def test_sympy_irrational_p_on_the_mpmath_path() -> None:
    """An irrational p (no exact rational value) runs the hump search on a binary
    approximation: every method against the pmf summed at sqrt(2)/10."""
    sympy = pytest.importorskip("sympy")
    N, dps = 40, 30
    d = symhx.distribution_of(N, sympy.sqrt(2) / 10, dps=dps)
    assert d.fr is None and not d.exact
    path = Path.mp(dps)
    with mpmath.workdps(3 * dps):
        ref = pmf_by_loggamma(N, mpmath.sqrt(2) / 10, 3 * dps)
        for k in (1, 2, 3, 5, 6, 20, N):
            path.value(d.pmf(k), ref[k - 1], k)
            path.value(d.sf(k - 1) if k > 1 else d.cdf(1), mpmath.fsum(ref[k - 1:]) if k > 1
                       else ref[0], ("tail", k))
        mu, var = moments_of(ref)
        path.value(d.mean(), mu, "mean")
        path.value(d.var(), var, "var")
        best = max(range(1, N + 1), key=lambda k: ref[k - 1])
    assert d.mode() == best and symhx.mode(N, sympy.sqrt(2) / 10) == best


def test_sympy_irrational_p_on_the_float64_path() -> None:
    sympy = pytest.importorskip("sympy")
    N = 25
    d = symhx.distribution_of(N, sympy.sqrt(2) / 10, dps=None)
    with mpmath.workdps(40):
        pm = mpmath.sqrt(2) / 10
        w = [pm**k * mpmath.factorial(N) / (k * mpmath.factorial(N - k)) for k in range(1, N + 1)]
        s = mpmath.fsum(w)
        for k in (1, 4, 12, N):
            assert math.isclose(d.pmf(k), float(w[k - 1] / s), rel_tol=1e-12), k
        assert math.isclose(d.log_normaliser, float(mpmath.log(s)), rel_tol=1e-13)


@pytest.mark.parametrize(("N", "c"), [(200, 2), (1000, 3)])
def test_irrational_p_with_a_hump(N: int, c: int) -> None:
    """p = pi/100 (N = 200) and pi/1000 (N = 1000): the hump search for an irrational p works on
    p's binary value (a wrong exponent or base there loses the rising side of the hump)."""
    sympy = pytest.importorskip("sympy")
    dps = 20
    p = sympy.pi / 10**c
    d = SimpleDistribution(N, p, dps=dps)
    assert d.fr is None
    ref = pmf_by_loggamma(N, _sympy_value(p, dps), 2 * dps + 20)
    best = max(range(1, N + 1), key=lambda k: ref[k - 1])
    ks = sorted({1, 2, 3, N // 10, N // 4, N // 3, N // 2, best - 20, best - 3, best, best + 3,
                 best + 20, N - 1, N})
    _check_sums(d, ref, ks, dps)
    with mpmath.workdps(2 * dps + 20):
        for k in (1, best, N):
            lw = mpmath.log(ref[k - 1])
            assert abs(d.logpmf(k) - lw) <= mpmath.mpf(10) ** (1 - dps) * abs(lw), k
    assert d.modes() == (best,)


def test_irrational_p_cdf_high_on_the_rising_side() -> None:
    """N = 5000, p = pi/5000 (mode 3408): cdf(3000) is ~1e-23 and every significant term lies
    above N/2; without the hump (irrational p taken for N p < 1) a bisection over [1, N] from
    k = 1 finds only P(X = 1) and the cdf comes out ~1e-1004."""
    sympy = pytest.importorskip("sympy")
    N, dps = 5000, 15
    p = sympy.pi / N
    d = SimpleDistribution(N, p, dps=dps)
    ref = pmf_by_loggamma(N, _sympy_value(p, dps), 2 * dps + 20)
    path = Path.mp(dps)
    with mpmath.workdps(2 * dps + 20):
        for k in (2600, 3000, 3300, 3400):
            path.value(d.cdf(k), mpmath.fsum(ref[:k]), ("cdf", k))
            path.value(d.sf(k), mpmath.fsum(ref[k:]), ("sf", k))


def test_irrational_p_with_N_p_just_above_one() -> None:
    """N = 2**17 - 1, p = 0.382 pi / N (N p = 1.2, mode 21849): the hump exists although p is
    below 2**-(bits of N) + 2; taking it for 'no hump' makes cdf(21845) ~1e-891 instead of
    ~0.4965.  Reference in float64 (``math.lgamma``, relative error ~1e-10 here)."""
    sympy = pytest.importorskip("sympy")
    N = 2**17 - 1
    p = sympy.pi * sympy.Rational(382, 1000 * N)
    d = SimpleDistribution(N, p, dps=15)
    lp = math.log(float(sympy.N(p, 30)))
    lg = math.lgamma(N + 1)
    logs = [k * lp + lg - math.lgamma(N - k + 1) - math.log(k) for k in range(1, N + 1)]
    top = max(logs)
    w = [math.exp(x - top) for x in logs]
    total = math.fsum(w)
    for k in (21000, 21845, 22500):
        want = math.fsum(w[:k]) / total
        assert math.isclose(float(d.cdf(k)), want, rel_tol=1e-8), k
        assert math.isclose(float(d.sf(k)), math.fsum(w[k:]) / total, rel_tol=1e-8), k
