"""The simple-space distribution at large N (issue 27): every statistic against independent
references (exact Fractions, direct sums, sums from the Poisson side), dps against 2 dps over
N = 1e2 ... 1e1000 and p/p_c in {0.5, 0.999, 1.001, 2, 10} (with N p - 1 of the order of
N p_c - 1), and the identities cdf + sf = 1, ppf(cdf(k)) = k, mean/var = moments of the pmf."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx
from symhx.distribution import MP_QUANTILE_N_LIMIT
from symhx.validation import mpf_to_fraction
from tests.reference.distribution_large_n import (
    critical_p,
    direct_sums,
    head_sums,
    poisson_side_sums,
)
from tests.reference.mp import rel_err


def _close(got, want, digits: float, what) -> None:
    with mpmath.workdps(200):
        if isinstance(want, Fraction):
            want = mpmath.mpf(want.numerator) / want.denominator
        err = abs(mpmath.mpf(got) - want) / abs(want)
    assert err <= mpmath.mpf(10) ** -digits, (what, got, want, err)


@pytest.mark.parametrize("N", [40, 700, 2000])
def test_mpmath_path_agrees_with_exact_fractions(N: int) -> None:
    """A float p (mpmath path) against the exact path at the same exact binary value."""
    for r in (Fraction(1, 2), Fraction(1), Fraction(3, 2), Fraction(5)):
        pf = float(critical_p(N) * r)
        exact = symhx.distribution_of(N, Fraction(pf))
        d = symhx.distribution_of(N, pf, dps=30)
        for name in ("mean", "var"):
            want = getattr(exact, name)()
            _close(getattr(d, name)(), want, 29, (N, r, name))
        k = exact.median()
        c = exact.cdf(k)
        _close(d.cdf(k), c, 29, (N, r, "cdf"))
        s = exact.sf(k + 3)
        _close(d.sf(k + 3), s, 29, (N, r, "sf"))
        assert d.median() == k


def test_direct_sum_at_N_1e5() -> None:
    """Near p_c (head and hump both weigh) and at 2 p_c, against every term added."""
    N = 10**5
    for r in (Fraction(1001, 1000), Fraction(2)):
        p = critical_p(N) * r
        d = symhx.distribution_of(N, p, dps=25)
        _, mean, var = direct_sums(N, p, 30)
        _close(d.mean(), mean, 24, ("mean", r))
        _close(d.var(), var, 24, ("var", r))


@pytest.mark.parametrize("e", [20, 100, 1000])
def test_poisson_side_reference_at_huge_N(e: int) -> None:
    """1/p = 400 at N = 10**e: the terms k = N - j, j <~ 700, summed from the top."""
    N = 10**e
    p = Fraction(1, 400)
    d = symhx.distribution_of(N, p, dps=40)
    _, mean, var = poisson_side_sums(N, p, 60, 1200)
    _close(d.mean(), mean, 39, "mean")
    _close(d.var(), var, 39, "var")


@pytest.mark.parametrize("e", [20, 100, 1000])
def test_head_reference_at_huge_N(e: int) -> None:
    """N p = 0.9: the log-series head, every term up to k = 2000."""
    N = 10**e
    p = Fraction(9, 10 * N)
    d = symhx.distribution_of(N, p, dps=40)
    _, mean, var = head_sums(N, p, 60, 2000)
    _close(d.mean(), mean, 39, "mean")
    _close(d.var(), var, 39, "var")


_GRID = [(e, r) for e in (2, 6, 10, 100, 1000)
         for r in (Fraction(1, 2), Fraction(999, 1000), Fraction(1001, 1000), Fraction(2),
                   Fraction(10))]


def _q_scaled(e: int, s: str) -> Fraction:
    """p with N p - 1 = s (N p_c - 1)."""
    N = 10**e
    cp = symhx.critical_point(N, dps=80)
    with mpmath.workdps(2 * e + 80):
        return mpf_to_fraction((1 + mpmath.mpf(s) * cp.q) / N)


@pytest.mark.slow
@pytest.mark.parametrize(("e", "r"), _GRID + [(e, s) for e in (6, 100, 1000)
                                               for s in ("q0.5", "q2")])
def test_dps_against_twice_dps(e: int, r) -> None:
    """Mean, var, entropy and the cdf at the median (at the mode beyond the quantile limit)
    agree with a run at 2 dps to dps digits (errors in units of 10**-dps below 1)."""
    N = 10**e
    p = _q_scaled(e, r[1:]) if isinstance(r, str) else critical_p(N) * r
    dps = 30
    lo = symhx.distribution_of(N, p, dps=dps)
    hi = symhx.distribution_of(N, p, dps=2 * dps)
    for name in ("mean", "var", "std"):
        a, b = getattr(lo, name)(), getattr(hi, name)()
        assert rel_err(a, b) <= 10.0 ** -dps, (name, a, b)
    with mpmath.workdps(2 * dps):
        assert abs(lo.entropy() - hi.entropy()) <= mpmath.mpf(10) ** -dps
    # the median within the quantile limit, else the (exact) mode: where the mass is
    k = lo.median() if N <= MP_QUANTILE_N_LIMIT else lo.mode()
    for name in ("cdf", "sf", "logcdf", "pmf"):
        a, b = getattr(lo, name)(k), getattr(hi, name)(k)
        assert rel_err(a, b) <= 10.0 ** -dps, (name, a, b)


@pytest.mark.parametrize("N", [300, 10**4])
def test_cdf_sf_ppf_identities(N: int) -> None:
    d = symhx.distribution_of(N, float(critical_p(N) * Fraction(3, 2)), dps=30)
    with mpmath.workdps(40):
        for k in (1, 2, d.median() - 7, d.median(), N - 1):
            c, s = d.cdf(k), d.sf(k)
            assert abs(c + s - 1) <= mpmath.mpf(10) ** -29
            if mpmath.mpf(10) ** -20 < c < 1 - mpmath.mpf(10) ** -25:
                assert d.ppf(c) == k


def test_moments_are_those_of_the_pmf() -> None:
    N = 400
    d = symhx.distribution_of(N, float(critical_p(N) * 2), dps=30)
    with mpmath.workdps(45):
        pm = [d.pmf(k) for k in range(1, N + 1)]
        mu = mpmath.fsum(k * w for k, w in enumerate(pm, 1))
        var = mpmath.fsum((k - mu) ** 2 * w for k, w in enumerate(pm, 1))
        assert abs(mpmath.fsum(pm) - 1) < mpmath.mpf(10) ** -28
        assert rel_err(d.mean(), mu) < 1e-28 and rel_err(d.var(), var) < 1e-27


def test_exact_p_at_large_N_uses_the_exact_rational() -> None:
    """'2e-10' is exactly 1/5e9: mean = N - 1/p + O(1/N) = 4999999999 to 20 digits, while the
    float 2e-10 (its binary neighbour) gives a different 20-digit value."""
    exact = symhx.mean(10**10, "2e-10", dps=20)
    flt = symhx.mean(10**10, 2e-10, dps=20)
    ref = poisson_side_sums(10**10, Fraction(1, 5 * 10**9), 30, 0)  # noqa: F841 - shape only
    with mpmath.workdps(40):
        assert abs(exact - 4999999999) < mpmath.mpf(10) ** -8
        assert abs(flt - exact) > mpmath.mpf(10) ** -10


@pytest.mark.slow
def test_quantiles_at_huge_N_are_integers_that_bracket_q() -> None:
    """The median at N = 1e25 is the smallest k with cdf(k) >= q (1 - 10**(1 - dps)) (the
    documented resolution), checked at twice the digits."""
    N = 10**25
    dps = 30
    d = symhx.distribution_of(N, critical_p(N) * 2, dps=dps)
    k = d.median()
    hi = symhx.distribution_of(N, critical_p(N) * 2, dps=2 * dps)
    with mpmath.workdps(2 * dps):
        qq = (1 - mpmath.mpf(10) ** (1 - dps)) / 2
        assert hi.cdf(k - 1) < qq <= hi.cdf(k)


def test_float_path_beyond_the_table() -> None:
    N = 10**12
    p = float(critical_p(N) * 3)
    m = symhx.mean(N, [p, 2 * p], dps=None)
    ref = [symhx.mean(N, v, dps=30) for v in (p, 2 * p)]
    for a, b in zip(m, ref, strict=True):
        assert abs(a / float(b) - 1) < 1e-14
    k = int(float(ref[0]))
    got = symhx.pmf(N, p, [k, k + 10**5], dps=None)
    want = [symhx.pmf(N, p, kk, dps=30) for kk in (k, k + 10**5)]
    for a, b in zip(got, want, strict=True):
        assert abs(a / float(b) - 1) < 1e-13


@pytest.mark.parametrize("e", [8, 10, 15, 100, 300])
@pytest.mark.parametrize("r", [Fraction(1, 2), Fraction(1001, 1000), Fraction(10)])
def test_float_pmf_beyond_the_table_is_vectorised_and_accurate(e: int, r: Fraction) -> None:
    """dps=None past FLOAT_N_LIMIT: logpmf over an array of k (bulk, far tails, both ends)
    within 1e-13 (1 + |logpmf|) of the 40-digit mpmath path, the pmf its exp; cdf over an
    array with repeated k equals cdf of each k."""
    N = 10**e
    p = float(critical_p(N) * r)
    fl = symhx.distribution_of(N, p, dps=None)
    mp40 = symhx.distribution_of(N, p, dps=40)
    top = fl.mode()
    width = int(mpmath.sqrt(1 / mpmath.mpf(p))) if top > 1 else 10**3
    ks = sorted({min(max(top + o, 1), N) for o in (0, 1, -1, width, -width, 30 * width,
                                                     -30 * width)} | {1, 2, N})
    arr = np.array(ks, dtype=object if e > 18 else np.int64)
    lv = fl.logpmf(arr)
    pv = fl.pmf(arr)
    for k, a, b in zip(ks, lv, pv, strict=True):
        want = mp40.logpmf(k)
        assert abs(a - want) <= 1e-13 * (1 + abs(want)), (k, a, want)
        assert b == math.exp(a)
    few = np.array(ks[:3] + ks[:3], dtype=arr.dtype)
    assert list(fl.cdf(few)) == [fl.cdf(int(k)) for k in few]


@pytest.mark.slow
@pytest.mark.parametrize(("e", "r", "dps"), [(1000, Fraction(999, 1000), 300),
                                         (20, Fraction(2), 1000)])
def test_high_precision_sums_near_and_above_the_jump(e: int, r: Fraction, dps: int) -> None:
    """Hundreds of digits at huge N: the head below the jump (a log-series over ~1e6 terms,
    where a panel bound on the disc |x| <= R was e**1300 too large) and the hump at dps 1000
    (panels need more than 256 nodes); mean at dps against dps + 30."""
    N = 10**e
    p = critical_p(N) * r
    a = symhx.distribution_of(N, p, dps=dps).mean()
    b = symhx.distribution_of(N, p, dps=dps + 30).mean()
    assert rel_err(a, b, dps=dps + 60) <= mpmath.mpf(10) ** (1 - dps)


def test_float_quantiles_beyond_the_table() -> None:
    """dps=None past FLOAT_N_LIMIT: ppf and isf are the integers where the 40-digit cdf/sf
    cross q at float resolution (q (1 -+ 1e-16)); q = 0 and 1 give the ends of the support."""
    N = 10**8
    p = float(critical_p(N) * 3)
    fl = symhx.distribution_of(N, p, dps=None)
    ref = symhx.distribution_of(N, p, dps=40)
    with mpmath.workdps(60):
        for q in (Fraction(1, 1000), Fraction(1, 2)):
            qm = mpmath.mpf(q.numerator) / q.denominator
            k = fl.isf(q)
            assert isinstance(k, int) and ref.sf(k) <= qm * (1 + 1e-16) < ref.sf(k - 1), q
            k = fl.ppf(q)
            assert isinstance(k, int) and ref.cdf(k - 1) < qm * (1 - 1e-16) <= ref.cdf(k), q
    assert (fl.isf(0), fl.isf(1), fl.ppf(0), fl.ppf(1)) == (N, 0, 0, N)


def test_float_path_beyond_the_table_at_the_ends_of_the_support() -> None:
    """dps=None past FLOAT_N_LIMIT with the mass at the top (p = 0.9: P(X = N) ~ 0.3):
    outside 1..N the pmf is 0 and its log -inf, cdf(N - 1) = 1 - pmf(N), sf(N) = 0."""
    N = 10**8 + 1
    d = symhx.distribution_of(N, 0.9, dps=None)
    ref = symhx.distribution_of(N, 0.9, dps=30)
    ks = np.array([0, -3, N + 1, N + 5])
    assert list(d.pmf(ks)) == [0.0] * 4
    assert list(d.logpmf(ks)) == [-np.inf] * 4
    top = float(ref.pmf(N))
    assert top > 0.1
    assert abs(d.cdf(N - 1) - (1 - top)) <= 1e-14
    assert abs(d.pmf(N) - top) <= 1e-14 * top
    assert d.cdf(0) == 0.0 and d.sf(N) == 0.0 and d.logsf(N) == -np.inf


def test_sums_beyond_the_limit_are_refused() -> None:
    from symhx.distribution import MP_SUM_N_LIMIT
    from tests.harness.errors import assert_refuses

    d = symhx.distribution_of(MP_SUM_N_LIMIT * 10, 0.5, dps=15)
    assert_refuses(d.mean, arg="N", value="10**1001", allowed="MP_SUM_N_LIMIT")
    from symhx.distribution import MP_QUANTILE_N_LIMIT

    d = symhx.distribution_of(MP_QUANTILE_N_LIMIT + 1, 0.5, dps=15)
    assert_refuses(d.median, arg="N", allowed="MP_QUANTILE_N_LIMIT")


def test_slow_head_below_the_jump_at_huge_N() -> None:
    """p_c read at 40 digits sits just below 1/N at N = 1e100 (N p - 1 = -5e-42): no hump, a
    log-series head ~1e43 terms long.  The tail bound 1/(1 - N p) must use the exact 1 - N p."""
    N = 10**100
    p = symhx.critical_point(N, dps=40).p
    a = symhx.distribution_of(N, p, dps=25).mean()
    b = symhx.distribution_of(N, p, dps=50).mean()
    assert rel_err(a, b) <= 1e-25


def test_cdf_and_sf_add_to_one_just_past_the_hump_top_at_huge_N() -> None:
    """A range starting one past the hump's top ([k + 1, N], k the mode; the slope of log Phi
    there is ~1e-99 and at N it is huge) still finds the whole decreasing side of the hump:
    sf(k + j) + cdf(k + j) = 1 and sf of the mode is about one half (the hump is symmetric to
    leading order)."""
    N = 10**100
    d = symhx.distribution_of(N, critical_p(N) * 10, dps=30)
    k = d.mode()
    with mpmath.workdps(60):
        for j in (0, 1, 2, 10, 10**40):
            assert abs(d.cdf(k + j) + d.sf(k + j) - 1) <= mpmath.mpf(10) ** -29, j
        assert abs(d.sf(k) - mpmath.mpf(1) / 2) < 0.01


def test_float_path_refuses_an_N_beyond_the_float64_range() -> None:
    """dps=None returns float64: an N that does not fit one (the mean would be inf) is refused
    by name; N = 10**300 still answers (mean = N - 2 to float64 for p = 0.5)."""
    from tests.harness.errors import assert_refuses

    d = symhx.distribution_of(10**1000, 0.5, dps=None)
    for method in (d.mean, d.var, d.entropy):
        assert_refuses(method, arg="N", value="N=10**1000", allowed="float64")
    assert symhx.distribution_of(10**300, 0.5, dps=None).mean() == 1e300


def _random_cases(seed: int, n: int) -> list[tuple[int, str, int, str, object]]:
    """(N, p/p_c, dps, method, argument) drawn over N = 10**2 ... 10**1000 (and N = 10**e + 1,
    + 7), p/p_c = 1e-6 ... 1e6 and p of order 1, dps 15 ... 50, k in the head, around the mode
    and over the whole support, q in the bulk and far out."""
    import random

    rng = random.Random(seed)
    out = []
    for _ in range(n):
        e = rng.choice([2, 3, 5, 8, 12, 20, 50, 100, 300, 1000])
        N = 10**e + (rng.choice([0, 0, 1, 7]) if e < 1000 else 0)
        r = rng.choice(["1e-6", "1e-3", "0.5", "0.999", "0.99999", "1.00001", "1.001", "1.1",
                        "2", "10", "1e3", "1e6", "p=1/2", "p=3"])
        dps = rng.choice([15, 17, 20, 30, 50])
        meth = rng.choice(["pmf", "cdf", "sf", "logcdf", "logsf", "logpmf", "mean", "var",
                           "entropy", "ppf", "isf"])
        if meth in ("ppf", "isf") and e > 300:  # the reference would need ~530 digits
            meth = "cdf"
        if meth in ("ppf", "isf"):
            arg: object = rng.choice([Fraction(1, 2), Fraction(1, 10**rng.randint(1, 40)),
                                      1 - Fraction(1, 10**rng.randint(1, 12))])
        else:
            u = rng.random()
            arg = (rng.randint(1, 10**6), "mode", rng.randint(-10**(e // 2 + 1),
                                                                10**(e // 2 + 1)),
                   u ** rng.choice([1, 3, 10]))[rng.randrange(3)]
            if arg == "mode":
                arg = ("mode", rng.randint(-10**(e // 2 + 1), 10**(e // 2 + 1)))
            elif isinstance(arg, int) and not 1 <= arg:
                arg = 1
        out.append((N, r, dps, meth, arg))
    return out


@pytest.mark.slow
@pytest.mark.parametrize("case", _random_cases(2026, 200), ids=lambda c: f"{c[3]}-{c[1]}-{c[2]}")
def test_random_cases_against_twice_the_digits(case) -> None:
    """Every method on seeded random (N, p, dps, k or q) against a run at 2 dps + 5; a quantile
    against the cdf at twice the digits (the smallest k that reaches the resolved q)."""
    N, r, dps, meth, arg = case
    with mpmath.workdps(2 * len(str(N)) + 120):
        p = mpmath.mpf(r[2:]) if r.startswith("p=") else \
            mpmath.mpf(critical_p(N).numerator) / critical_p(N).denominator * mpmath.mpf(r)
    lo = symhx.distribution_of(N, p, dps=dps)
    hi = symhx.distribution_of(N, p, dps=2 * dps + 5)
    if isinstance(arg, tuple):
        arg = min(max(lo.mode() + arg[1], 1), N)
    if meth in ("mean", "var", "entropy"):
        a, b = getattr(lo, meth)(), getattr(hi, meth)()
    elif meth in ("ppf", "isf"):
        k = getattr(lo, meth)(arg)
        q = arg * (1 - Fraction(10) ** (1 - dps)) if meth == "ppf" else \
            arg * (1 + Fraction(10) ** (1 - dps))
        # one unit of k moves the cdf by ~1/sqrt(N) of it: the reference resolves that
        ref_dps = dps + len(str(N)) // 2 + 30
        hi = symhx.distribution_of(N, p, dps=ref_dps)
        with mpmath.workdps(ref_dps + 20):
            qm = mpmath.mpf(q.numerator) / q.denominator
            if meth == "ppf":
                assert hi.cdf(k) >= qm and (k == 1 or hi.cdf(k - 1) < qm)
            else:
                assert hi.sf(k) <= qm and (k == 1 or hi.sf(k - 1) > qm)
        return
    else:
        if isinstance(arg, float):
            arg = max(1, min(N, int(mpmath.mpf(N) * mpmath.mpf(arg))))
        a, b = getattr(lo, meth)(arg), getattr(hi, meth)(arg)
    with mpmath.workdps(3 * dps + 40):
        if meth.startswith("log") or meth == "entropy":
            if mpmath.isinf(b):
                assert a == b
            else:
                assert abs(a - b) <= mpmath.mpf(10) ** -dps * max(1, abs(b)), (a, b)
        else:
            assert abs(a - b) <= mpmath.mpf(10) ** (1 - dps) * abs(b), (a, b)
