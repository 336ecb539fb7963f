"""Tests for mutants of :mod:`symhx.distribution` that survived the mutation run and change what
a user sees: irrational ``p`` with a hump, two separate runs of significant terms, huge ``N`` with
``p > 1``, the inclusive work limit, argument checks, empty arrays and the warning location.

References, none of which uses symhx's distribution code:

* ``log Phi(k) = k log p + log N! - log (N-k)! - log k`` from ``loggamma`` at twice the precision
  plus 20 digits, with every term of the support summed (no window);
* for ``N = 2**17 - 1`` the same formula in float64 (``math.lgamma``), with a tolerance to match;
* near ``k = N`` for ``p > 1`` the exact ratio ``Phi(N-j) / Phi(N) = p**-j N / ((N-j) j!)``;
* for ``N p < 1`` and huge ``N`` the logarithmic-series limit (corrections ``O(1/N)``).
"""

from __future__ import annotations

import math
import re
import sys
import warnings
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx.distribution as dist
from symhx.distribution import MP_SUM_N_LIMIT, SimpleDistribution

sympy = pytest.importorskip("sympy")


# --------------------------------------------------------------------------- references
def ref_pmf(N: int, pm: mpmath.mpf, dps: int) -> list[mpmath.mpf]:
    """``[P(X = k) for k = 1..N]`` summed over the whole support at ``2 dps + 20`` digits."""
    with mpmath.workdps(2 * dps + 20):
        lp, lg = mpmath.log(pm), mpmath.loggamma(N + 1)
        logs = [k * lp + lg - mpmath.loggamma(N - k + 1) - mpmath.log(k) for k in range(1, N + 1)]
        top = max(logs)
        w = [mpmath.exp(x - top) for x in logs]
        s = mpmath.fsum(w)
        return [x / s for x in w]


def close(got: mpmath.mpf, want: mpmath.mpf, dps: int, what: object) -> None:
    with mpmath.workdps(2 * dps + 20):
        assert abs(got - want) <= mpmath.mpf(10) ** (1 - dps) * abs(want), (what, got, want)


def sympy_mpf(p: object, dps: int) -> mpmath.mpf:
    """A sympy number at ``2 dps + 40`` digits (enough for the references above)."""
    with mpmath.workdps(2 * dps + 40):
        return mpmath.mpf(str(sympy.N(p, 2 * dps + 40)))


def check_sums(d: SimpleDistribution, ref: list[mpmath.mpf], ks: list[int], dps: int) -> None:
    N = d.N
    with mpmath.workdps(2 * dps + 20):
        mu = mpmath.fsum(k * x for k, x in enumerate(ref, 1))
        var = mpmath.fsum((k - mu) ** 2 * x for k, x in enumerate(ref, 1))
        close(d.mean(), mu, dps, "mean")
        close(d.var(), var, dps, "var")
        for k in ks:
            close(d.pmf(k), ref[k - 1], dps, ("pmf", k))
            if k < N:
                close(d.cdf(k), mpmath.fsum(ref[:k]), dps, ("cdf", k))
                close(d.sf(k), mpmath.fsum(ref[k:]), dps, ("sf", k))


# --------------------------------------------------------------------------- irrational p
@pytest.mark.parametrize(("N", "c"), [(200, 2), (1000, 3)])
def test_irrational_p_with_a_hump(N: int, c: int) -> None:
    """p = pi/100 (N = 200) and pi/1000 (N = 1000): the hump search for an irrational p works on
    p's binary value (a wrong exponent or base there loses the rising side of the hump)."""
    dps = 20
    p = sympy.pi / 10**c
    d = SimpleDistribution(N, p, dps=dps)
    assert d.fr is None
    ref = ref_pmf(N, sympy_mpf(p, dps), dps)
    best = max(range(1, N + 1), key=lambda k: ref[k - 1])
    ks = sorted({1, 2, 3, N // 10, N // 4, N // 3, N // 2, best - 20, best - 3, best, best + 3,
                 best + 20, N - 1, N})
    check_sums(d, ref, ks, dps)
    with mpmath.workdps(2 * dps + 20):
        for k in (1, best, N):
            lw = mpmath.log(ref[k - 1])
            assert abs(d.logpmf(k) - lw) <= mpmath.mpf(10) ** (1 - dps) * abs(lw), k
    assert d.modes() == (best,)


def test_irrational_p_cdf_high_on_the_rising_side() -> None:
    """N = 5000, p = pi/5000 (mode 3408): cdf(3000) is ~1e-23 and every significant term lies
    above N/2; without the hump (irrational p taken for N p < 1) a bisection over [1, N] from
    k = 1 finds only P(X = 1) and the cdf comes out ~1e-1004."""
    N, dps = 5000, 15
    p = sympy.pi / N
    d = SimpleDistribution(N, p, dps=dps)
    ref = ref_pmf(N, sympy_mpf(p, dps), dps)
    with mpmath.workdps(2 * dps + 20):
        for k in (2600, 3000, 3300, 3400):
            close(d.cdf(k), mpmath.fsum(ref[:k]), dps, ("cdf", k))
            close(d.sf(k), mpmath.fsum(ref[k:]), dps, ("sf", k))


def test_irrational_p_with_N_p_just_above_one() -> None:
    """N = 2**17 - 1, p = 0.382 pi / N (N p = 1.2, mode 21849): the hump exists although p is
    below 2**-(bits of N) + 2; taking it for 'no hump' makes cdf(21845) ~1e-891 instead of
    ~0.4965.  Reference in float64 (relative error ~1e-10 here)."""
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


# --------------------------------------------------------------------------- two runs
@pytest.mark.parametrize("k", range(540, 560))
def test_tail_sums_with_two_runs_of_significant_terms(k: int) -> None:
    """N = 1000, p = 0.0017, dps = 15: for sf(k) near k = 549 the terms within the working
    precision of the largest one in [k+1, N] form two runs, {1} and a hump run (Phi(1) is just
    above the cut, the valley at k = 2, 3 just below).  Both runs must be kept and summed."""
    N, dps = 1000, 15
    d = SimpleDistribution(N, 0.0017, dps=dps)
    ref = _ref_1000()
    with mpmath.workdps(2 * dps + 20):
        close(d.sf(k), mpmath.fsum(ref[k:]), dps, ("sf", k))
        close(d.cdf(k), mpmath.fsum(ref[:k]), dps, ("cdf", k))
        close(d.logsf(k), mpmath.log(mpmath.fsum(ref[k:])), dps, ("logsf", k))


_REF_1000: list[list[mpmath.mpf]] = []


def _ref_1000() -> list[mpmath.mpf]:
    if not _REF_1000:
        _REF_1000.append(ref_pmf(1000, mpmath.mpf(0.0017), 15))
    return _REF_1000[0]


# --------------------------------------------------------------------------- guard digits
@pytest.mark.parametrize(("N", "p"), [(10**15, 0.5), (10**20, 2.0), (10**30, 10.0)])
def test_logpmf_near_N_for_huge_N_keeps_every_digit(N: int, p: float) -> None:
    """For p >= 1/2 the mass sits at k = N - j, j small, and log Phi(k) ~ N log(N p) is huge:
    the guard digits (two per digit of N) must cover its cancellation against log Gamma.
    Reference: P(X = N - j) from the exact ratio p**-j N / ((N - j) j!), j < 300."""
    dps = 15
    d = SimpleDistribution(N, p, dps=dps)
    with mpmath.workdps(60):
        pm = mpmath.mpf(p)
        w = [pm ** -j / mpmath.factorial(j) * N / (N - j) for j in range(300)]
        s = mpmath.fsum(w)
        for j in (0, 1, 5, 20):
            want = w[j] / s
            close(d.pmf(N - j), want, dps, ("pmf", j))
            lw = mpmath.log(want)
            assert abs(d.logpmf(N - j) - lw) <= mpmath.mpf(10) ** (1 - dps) * abs(lw), j


# --------------------------------------------------------------------------- limits, checks
def test_sum_limit_is_inclusive() -> None:
    """N = MP_SUM_N_LIMIT itself is summed (the message says N <= limit).  N p = 0.1 (float p):
    the logarithmic series, mean = l / ((1 - l) (-log(1 - l))), up to O(1/N)."""
    N = MP_SUM_N_LIMIT
    d = SimpleDistribution(N, 1e-101, dps=15)
    with mpmath.workdps(40):
        lam = N * mpmath.mpf(1e-101)
        want = lam / ((1 - lam) * -mpmath.log1p(-lam))
    close(d.mean(), want, 15, "mean")
    with pytest.raises(ValueError, match=r"^summing the distribution on the mpmath path is "
                                         r"limited to N <= 10\*\*100 "):
        SimpleDistribution(N + 1, 1e-101, dps=15).mean()


def test_N_below_one_is_refused() -> None:
    """N counts vertices: N = 0 and N = -3 are refused with check_int's message."""
    for N in (0, -3):
        with pytest.raises(ValueError, match=rf"^N must be >= 1, got {N}$"):
            SimpleDistribution(N, "1/2")


@pytest.mark.parametrize("c", [-0.5, "-1/3", Fraction(-1, 10**9)])
def test_interval_refuses_a_negative_confidence(c: object) -> None:
    """A negative confidence would give reversed ppf bounds: refused like c > 1."""
    d = SimpleDistribution(20, "1/10")
    with pytest.raises(ValueError, match=f"^{re.escape(f'confidence must be >= 0, got {c!r}')}$"):
        d.interval(c)


def test_float_path_empty_object_array() -> None:
    """An empty object-dtype array of k on the float64 path gives an empty float64 array (an
    empty list without an int64 dtype would be float64 and could not index the table)."""
    d = SimpleDistribution(10, 0.3, dps=None)
    for shape in ((0,), (0, 3)):
        k = np.empty(shape, dtype=object)
        for f in (d.pmf, d.logpmf, d.cdf, d.sf, d.logcdf, d.logsf):
            got = f(k)
            assert got.shape == shape and got.dtype == np.float64, f
    got = d.cdf(np.array([10**30, -5, 3], dtype=object))
    want = [1.0, 0.0, float(sum(Fraction(0.3) ** j * math.perm(10, j) / j for j in range(1, 4))
                            / sum(Fraction(0.3) ** j * math.perm(10, j) / j
                                  for j in range(1, 11)))]
    assert got.dtype == np.float64 and np.allclose(got, want, rtol=1e-13, atol=0)


# --------------------------------------------------------------------------- warnings
def test_deprecation_warnings_name_the_calling_line() -> None:
    """variance() and the moved module attributes warn at the line that called them, not one
    frame further up (inside pytest).  Under mutation testing mutmut's trampoline is the caller
    of both: they must then still name the same frame."""
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        *_, line = (SimpleDistribution(3, "1/2").variance(), dist.mean, sys._getframe().f_lineno)
    assert [r.category for r in rec] == [DeprecationWarning, DeprecationWarning]
    where = {(r.filename, r.lineno) for r in rec}
    if hasattr(dist, "_mutmut_mutated"):  # the trampoline calls the warning functions
        assert len(where) == 1, where
    else:
        assert where == {(__file__, line)}
