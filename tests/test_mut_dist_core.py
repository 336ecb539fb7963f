"""Every method of the simple frozen distribution against independent references (issue 16).

References, none of which uses symhx's distribution code:

* exact: the closed form ``Phi(k) = p**k N! / (k (N-k)!)`` (factorials) normalised by its
  brute-force sum, every derived quantity (cdf, sf, moments, quantiles, modes) by definition;
* mpmath: the pmf by the term ratio run *downwards* from ``k = N`` (``log Phi(N)`` from
  ``loggamma``) at ``2 dps + 20`` digits, with no window: every term is summed;
* float64 checks against the exact table converted once.

Ties and boundaries are explicit strategies: ``p = (k + 1) / (k (N - k))`` makes
``Phi(k) = Phi(k + 1)`` exactly, ``p = 2 / (N - 1)`` ties ``Phi(1)`` with ``Phi(2)``,
``(N, p) = (t**2 + 2 t, 1/t**2)`` is a double root of ``f_{N,p}``, ``p = 1 / (2N)`` the edge of
the hump test, N = 1, 2, 3, 5, 10**k, p near 0 and 1.
"""

from __future__ import annotations

import bisect
import itertools
import math
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import symhx
from symhx.distribution import SimpleDistribution, binary_split, simple_modes

#: under mutation testing the warnings point into mutmut's trampoline (its extra frames)
_UNDER_MUTMUT = "mutmut"


# --------------------------------------------------------------------------- references
def phi(N: int, p: Fraction, k: int) -> Fraction:
    return Fraction(p) ** k * Fraction(math.factorial(N), k * math.factorial(N - k))


def table(N: int, p: Fraction) -> list[Fraction]:
    w = [phi(N, p, k) for k in range(1, N + 1)]
    g = sum(w)
    return [x / g for x in w]


def brute_modes(N: int, p: Fraction) -> tuple[int, ...]:
    w = [phi(N, p, k) for k in range(1, N + 1)]
    m = max(w)
    return tuple(k for k, x in enumerate(w, 1) if x == m)


_CUM: dict[int, tuple[list[Fraction], list[Fraction]]] = {}


def _cum(t: list[Fraction]) -> list[Fraction]:
    """Partial sums ``[P(X <= k) for k = 0..N]`` of a table (memoised per table object)."""
    hit = _CUM.get(id(t))
    if hit is None or hit[0] is not t:
        c = [Fraction(0)]
        for x in t:
            c.append(c[-1] + x)
        hit = _CUM[id(t)] = (t, c)
    return hit[1]


def cdf_ref(t: list[Fraction], k: int) -> Fraction:
    return _cum(t)[max(0, min(k, len(t)))]


def sf_ref(t: list[Fraction], k: int) -> Fraction:
    c = _cum(t)
    return c[-1] - c[max(0, min(k, len(t)))]


def ppf_ref(t: list[Fraction], q: Fraction) -> int:
    if q == 0:
        return 0
    return bisect.bisect_left(_cum(t), q)  # smallest k with cdf(k) >= q


def isf_ref(t: list[Fraction], q: Fraction) -> int:
    if q == 1:
        return 0
    return next(k for k in range(1, len(t) + 1) if sf_ref(t, k) <= q)


def mp_of(x: Fraction) -> mpmath.mpf:
    return mpmath.mpf(x.numerator) / x.denominator


def log_of(x: Fraction) -> mpmath.mpf:
    return mpmath.ninf if x == 0 else mpmath.log(x.numerator) - mpmath.log(x.denominator)


def mp_table(N: int, p: Fraction, dps: int) -> list[mpmath.mpf]:
    """P(X = k), k = 1..N, at ``dps`` digits: ratio recurrence downwards from k = N."""
    with mpmath.workdps(dps + 2 * len(str(N)) + 10):
        pm = mp_of(p)
        w = [mpmath.mpf(0)] * (N + 1)
        w[N] = mpmath.mpf(1)  # Phi(k) / Phi(N)
        for k in range(N, 1, -1):  # Phi(k-1) / Phi(k) = k / (p (N - k + 1) (k - 1))
            w[k - 1] = w[k] * k / (pm * (N - k + 1) * (k - 1))
        s = mpmath.fsum(w[1:])
        return [x / s for x in w[1:]]


def close(got: Any, want: Any, dps: int, what: Any = "") -> None:
    """``got`` (an mpf rounded to dps digits) within 10**(1 - dps) relative of ``want``."""
    assert isinstance(got, mpmath.mpf), (what, type(got))
    with mpmath.workdps(2 * dps + 20):
        w = mp_of(want) if isinstance(want, Fraction) else want
        assert abs(got - w) <= mpmath.mpf(10) ** (1 - dps) * abs(w), (what, got, w)


def close_log(got: Any, want: Any, dps: int, what: Any = "") -> None:
    with mpmath.workdps(2 * dps + 20):
        w = log_of(want) if isinstance(want, Fraction) else want
        if w == mpmath.ninf:
            assert got == mpmath.ninf or got == -math.inf, (what, got)
            return
        assert abs(got - w) <= mpmath.mpf(10) ** (1 - dps) * max(1, abs(w)), (what, got, w)


# --------------------------------------------------------------------------- strategies
@st.composite
def tie_cases(draw: Any) -> tuple[int, Fraction]:
    """``(N, p)`` with ``Phi(k) == Phi(k + 1)`` exactly for some ``1 <= k < N``."""
    N = draw(st.sampled_from([2, 3, 5, 10]) | st.integers(2, 40))
    k = draw(st.integers(1, N - 1))
    return N, Fraction(k + 1, k * (N - k))


@st.composite
def boundary_cases(draw: Any) -> tuple[int, Fraction]:
    N = draw(st.sampled_from([1, 2, 3, 5, 10]) | st.integers(1, 40))
    kind = draw(st.sampled_from(["small", "near1", "edge", "one-tie", "double", "big"]))
    if kind == "small":
        return N, Fraction(1, 10 ** draw(st.integers(1, 30)))
    if kind == "near1":
        return N, 1 - Fraction(1, 10 ** draw(st.integers(1, 30)))
    if kind == "edge":  # p = 1/(2N) and its neighbours: the hump test's first cut
        return N, Fraction(1, 2 * N) + draw(st.sampled_from([-1, 0, 1])) * Fraction(1, 10**9)
    if kind == "one-tie" and N >= 2:  # Phi(1) == Phi(2)
        return N, Fraction(2, N - 1) if N > 1 else Fraction(1)
    if kind == "double":  # f_{N,p} has a double root at k = t
        t = draw(st.integers(1, 5))
        return t * t + 2 * t, Fraction(1, t * t)
    return N, Fraction(draw(st.integers(1, 40)), draw(st.integers(1, 40)))


small_cases = tie_cases() | boundary_cases() | st.tuples(
    st.integers(1, 30), st.fractions(Fraction(1, 10**4), 3).filter(lambda x: x > 0))


def _ks(N: int) -> list[int]:
    return sorted({-3, 0, 1, 2, N // 2, N - 1, N, N + 1, N + 10**20})


def _qs(t: list[Fraction]) -> list[Fraction]:
    """q at every cdf value, every midpoint between consecutive ones, and 0, 1."""
    cdfs = [cdf_ref(t, k) for k in range(0, len(t) + 1)]
    mids = [(a + b) / 2 for a, b in itertools.pairwise(cdfs)]
    qs = sorted({Fraction(0), Fraction(1), *cdfs, *mids})
    return qs if len(qs) < 50 else qs[:: len(qs) // 40] + qs[-3:]


# --------------------------------------------------------------------------- exact path
@given(small_cases)
@example((1, Fraction(1, 2)))
@example((2, Fraction(2)))  # Phi(1) = Phi(2)
@example((3, Fraction(1)))  # double root at 1: modes (1, 2)
@example((5, Fraction(1, 2)))  # modes (1, 2, 3)
@example((8, Fraction(1, 4)))  # double root at 2, but Phi(1) is larger
@example((101, Fraction(1, 50)))  # modes (50, 51)
@example((10, Fraction(1, 20)))  # p = 1/(2N) exactly
def test_exact_every_method(case: tuple[int, Fraction]) -> None:
    N, p = case
    t = table(N, p)
    d = symhx.distribution_of(N, p, dps=30)
    assert d.exact and d.N == N and d.fr == p and d.support() == (1, N)
    for k in _ks(N):
        want = t[k - 1] if 1 <= k <= N else Fraction(0)
        got = d.pmf(k)
        assert isinstance(got, Fraction) and got == want, k
        assert d.cdf(k) == cdf_ref(t, k) and isinstance(d.cdf(k), Fraction)
        assert d.sf(k) == sf_ref(t, k) and isinstance(d.sf(k), Fraction)
        close_log(d.logpmf(k), want, 30, ("logpmf", k))
        close_log(d.logcdf(k), cdf_ref(t, k), 30, ("logcdf", k))
        close_log(d.logsf(k), sf_ref(t, k), 30, ("logsf", k))
    ks = np.array([[0, 1], [N, N + 1]])
    arr = d.pmf(ks)
    assert arr.shape == (2, 2) and arr.dtype == object
    assert arr.tolist() == [[0, t[0]], [t[-1], 0]]
    mu = sum((k * x for k, x in enumerate(t, 1)), Fraction(0))
    var = sum(((k - mu) ** 2 * x for k, x in enumerate(t, 1)), Fraction(0))
    assert d.mean() == mu and isinstance(d.mean(), Fraction)
    assert d.var() == var and isinstance(d.var(), Fraction)
    gamma = sum(phi(N, p, k) for k in range(1, N + 1))
    assert d.normaliser == gamma
    with mpmath.workdps(80):
        if var:
            close(d.std(), mpmath.sqrt(mp_of(var)), 30, "std")
        else:
            assert d.std() == 0
        close_log(d.log_normaliser, gamma, 30, "log_normaliser")
        h = -mpmath.fsum(mp_of(x) * log_of(x) for x in t)
        assert abs(d.entropy() - h) <= mpmath.mpf(10) ** -29, ("entropy", d.entropy(), h)
    modes = brute_modes(N, p)
    assert d.modes() == modes
    assert d.mode() == modes[0]  # the smallest maximiser, ties included
    assert d.table() == list(enumerate(t, 1))
    for q in _qs(t):
        assert d.ppf(q) == ppf_ref(t, q), ("ppf", q)
        assert d.isf(q) == isf_ref(t, q), ("isf", q)
    assert d.median() == ppf_ref(t, Fraction(1, 2))
    assert d.interval("0.8") == (ppf_ref(t, Fraction(1, 10)), ppf_ref(t, Fraction(9, 10)))
    qa = d.ppf([Fraction(0), Fraction(1, 2), Fraction(1)])
    assert qa.tolist() == [0, ppf_ref(t, Fraction(1, 2)), N] and qa.dtype == object


@given(tie_cases())
@example((101, Fraction(1, 50)))
@example((3, Fraction(1)))
def test_ties_every_path(case: tuple[int, Fraction]) -> None:
    """The frozen ``mode`` property is the smallest tied maximiser on every path (exact, mpmath
    and float64 p); a float p is taken at its binary value (often no longer a tie)."""
    N, p = case
    modes = brute_modes(N, p)
    assert phi(N, p, modes[0]) == max(phi(N, p, k) for k in range(1, N + 1))
    for dps in (30, None):
        d = symhx.distribution_of(N, p, dps=dps)
        assert d.modes() == modes and d.mode() == modes[0]
    pf = float(p)
    fmodes = brute_modes(N, Fraction(pf))
    for dps in (30, None):
        d = symhx.distribution_of(N, pf, dps=dps)
        assert d.modes() == fmodes and d.mode() == fmodes[0]
    assert simple_modes(N, p, None) == modes
    with mpmath.workdps(40):
        pm = mpmath.mpf(p.numerator) / p.denominator
    assert symhx.mode(N, pm) == brute_modes(N, Fraction(*_ratio(pm)))[0]


def _ratio(x: mpmath.mpf) -> tuple[int, int]:
    f = Fraction(int(x.man)) * Fraction(2) ** int(x.exp)
    return f.numerator, f.denominator


def test_known_multi_ties() -> None:
    # ties involving Phi(1): found by brute force over small N and p = a/b
    found = []
    for N in range(2, 13):
        for b in range(1, 13):
            for a in range(1, 3 * b + 1):
                p = Fraction(a, b)
                if p.denominator != b:
                    continue
                m = brute_modes(N, p)
                if len(m) > 1:
                    found.append((N, p, m))
                    assert symhx.modes(N, p) == m
                    d = symhx.distribution_of(N, p)
                    assert d.modes() == m and d.mode() == m[0]
    assert any(m[0] == 1 and len(m) == 3 for _, _, m in found)  # (5, 1/2): (1, 2, 3)
    assert any(m[0] == 1 and len(m) == 2 for _, _, m in found)
    assert any(m[0] > 1 for _, _, m in found)


# --------------------------------------------------------------------------- mpmath path
MP_CASES = [(1, 0.5), (2, 0.5), (2, 2.0), (3, 1.0), (5, 0.5), (7, 1e-300), (10, 1e-5),
            (10, 0.05), (10, 1 - 2.0**-40), (10, 3.0), (30, 0.1), (24, 0.25)]


@pytest.mark.parametrize("dps", [20, 45])
@pytest.mark.parametrize(("N", "pf"), MP_CASES)
def test_mp_every_method(N: int, pf: float, dps: int) -> None:
    p = Fraction(pf)
    t = table(N, p)
    d = symhx.distribution_of(N, pf, dps=dps)
    assert not d.exact and d.dps == dps
    for k in _ks(N):
        want = t[k - 1] if 1 <= k <= N else Fraction(0)
        if want:
            close(d.pmf(k), want, dps, ("pmf", k))
        else:
            assert d.pmf(k) == 0 and isinstance(d.pmf(k), mpmath.mpf)
        close_log(d.logpmf(k), want, dps, ("logpmf", k))
        for name, ref in (("cdf", cdf_ref(t, k)), ("sf", sf_ref(t, k))):
            got = getattr(d, name)(k)
            if ref:
                close(got, ref, dps, (name, k))
            else:
                assert got == 0 and isinstance(got, mpmath.mpf), (name, k)
            close_log(getattr(d, "log" + name)(k), ref, dps, ("log" + name, k))
    mu = sum((k * x for k, x in enumerate(t, 1)), Fraction(0))
    var = sum(((k - mu) ** 2 * x for k, x in enumerate(t, 1)), Fraction(0))
    close(d.mean(), mu, dps, "mean")
    if var:
        close(d.var(), var, dps, "var")
        with mpmath.workdps(2 * dps + 20):
            close(d.std(), mpmath.sqrt(mp_of(var)), dps, "std")
    else:
        assert d.var() == 0
    gamma = sum(phi(N, p, k) for k in range(1, N + 1))
    close(d.normaliser, gamma, dps, "normaliser")
    close_log(d.log_normaliser, gamma, dps, "log_normaliser")
    with mpmath.workdps(2 * dps + 20):
        h = -mpmath.fsum(mp_of(x) * log_of(x) for x in t if x)
        assert abs(d.entropy() - h) <= mpmath.mpf(10) ** -dps, ("entropy", d.entropy(), h)
    assert d.modes() == brute_modes(N, p) and d.mode() == brute_modes(N, p)[0]
    tab = d.table()
    assert [k for k, _ in tab] == list(range(1, N + 1))
    for (k, got), want in zip(tab, t, strict=True):
        close(got, want, dps, ("table", k))
    # quantiles at the midpoints between resolvable cdf values
    for k in range(1, N + 1):
        lo, hi = cdf_ref(t, k - 1), cdf_ref(t, k)
        if t[k - 1] > Fraction(1, 10 ** (dps - 4)) * hi and 1 - hi > Fraction(1, 10 ** (dps - 4)):
            assert d.ppf((lo + hi) / 2) == k, ("ppf", k)
        lo, hi = sf_ref(t, k), sf_ref(t, k - 1)
        if t[k - 1] > Fraction(1, 10 ** (dps - 4)) * hi and lo > Fraction(1, 10 ** (dps - 4)) * hi:
            assert d.isf((lo + hi) / 2) == k, ("isf", k)
    assert d.ppf(0) == 0 and d.ppf(1) == N and d.isf(1) == 0 and d.isf(0) == N
    assert d.median() == ppf_ref(t, Fraction(1, 2))
    arr = d.cdf([1, N])
    assert arr.dtype == object and isinstance(arr[0], mpmath.mpf)


def test_mp_quantiles_resolve_q_to_dps_digits() -> None:
    """A q within a relative 10**(1 - dps) of cdf(k) counts as equal to it (documented), and
    one a little further does not."""
    N, pf, dps = 12, 0.3, 20
    t = table(N, Fraction(pf))
    d = symhx.distribution_of(N, pf, dps=dps)
    for k in (2, 5, 8):
        c, s = cdf_ref(t, k), sf_ref(t, k)
        assert d.ppf(c * (1 + Fraction(1, 10**25))) == k
        assert d.ppf(c * (1 + Fraction(1, 10**15))) == k + 1
        assert d.isf(s * (1 - Fraction(1, 10**25))) == k
        assert d.isf(s * (1 - Fraction(1, 10**15))) == k + 1
        assert d.ppf(c * (1 - Fraction(1, 10**15))) == k
        assert d.isf(s * (1 + Fraction(1, 10**15))) == k


@pytest.mark.parametrize(("N", "pf"), [(100, 0.02), (1000, 0.0021), (1000, 1e-4), (1000, 0.9),
                                       (5000, 5e-4), (5000, 1e-6), (300, 0.0101)])
def test_mp_large_N_against_downward_recurrence(N: int, pf: float) -> None:
    """N up to 10**4 against every term summed at 2 dps + 20 digits, tails included (the
    package keeps only the terms within dps + guard digits of the largest)."""
    dps = 30
    ref = mp_table(N, Fraction(pf), 2 * dps + 20)
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
            close(d.pmf(k), ref[k - 1], dps, ("pmf", k))
            close_log(d.logpmf(k), mpmath.log(ref[k - 1]), dps, ("logpmf", k))
            if k < N:
                up = mpmath.fsum(ref[k:])
                close(d.sf(k), up, dps, ("sf", k))
                close_log(d.logsf(k), mpmath.log(up), dps, ("logsf", k))
                close(d.cdf(k), cum[k], dps, ("cdf", k))
                close_log(d.logcdf(k), mpmath.log(cum[k]), dps, ("logcdf", k))
        mu = mpmath.fsum(k * x for k, x in enumerate(ref, 1))
        var = mpmath.fsum((k - mu) ** 2 * x for k, x in enumerate(ref, 1))
        # terms < 10**-(2 dps + 20) change h by < N 10**-(dps + 10) (x log(1/x) < sqrt(x))
        h = -mpmath.fsum(x * mpmath.log(x) for x in ref if x > mpmath.mpf(10) ** (-2 * dps - 20))
        close(d.mean(), mu, dps, "mean")
        close(d.var(), var, dps, "var")
        close(d.std(), mpmath.sqrt(var), dps, "std")
        assert abs(d.entropy() - h) <= mpmath.mpf(10) ** -dps
        med = next(k for k in range(1, N + 1) if cum[k] >= mpmath.mpf(1) / 2)
    assert d.median() == med


@pytest.mark.parametrize("dps", [15, 60])
def test_mp_variance_of_a_point_mass(dps: int) -> None:
    """p -> 0: all mass at k = 1 and var X = P(X=2) (1 + O(p)); the window must widen until the
    tiny variance is itself accurate to dps digits."""
    N = 11
    for pf in (1e-20, 1e-200):
        t = table(N, Fraction(pf))
        mu = sum((k * x for k, x in enumerate(t, 1)), Fraction(0))
        var = sum(((k - mu) ** 2 * x for k, x in enumerate(t, 1)), Fraction(0))
        d = symhx.distribution_of(N, pf, dps=dps)
        close(d.var(), var, dps, ("var", pf))
        close(d.mean(), mu, dps, ("mean", pf))
        close(d.sf(1), sf_ref(t, 1), dps, ("sf", pf))
        close(d.pmf(N), t[-1], dps, ("pmf N", pf))


def test_mp_precision_high_dps() -> None:
    """At 300 digits (guard digits cut by a few would show)."""
    N, pf, dps = 120, 0.021, 300
    t = table(N, Fraction(pf))
    d = symhx.distribution_of(N, pf, dps=dps)
    mu = sum((k * x for k, x in enumerate(t, 1)), Fraction(0))
    var = sum(((k - mu) ** 2 * x for k, x in enumerate(t, 1)), Fraction(0))
    close(d.mean(), mu, dps)
    close(d.var(), var, dps)
    for k in (1, 20, 100, N):
        close(d.pmf(k), t[k - 1], dps, k)
        close(d.sf(k - 1) if k > 1 else d.cdf(1), sf_ref(t, k - 1) if k > 1 else t[0], dps, k)


# --------------------------------------------------------------------------- float64 path
@given(small_cases)
@example((1, Fraction(1, 2)))
@example((5, Fraction(1, 2)))
@example((10, Fraction(1, 10**20)))
def test_float_every_method(case: tuple[int, Fraction]) -> None:
    N, p0 = case
    pf = float(p0)
    p = Fraction(pf)
    t = table(N, p)
    d = symhx.distribution_of(N, pf, dps=None)
    assert d.dps is None and not d.exact
    for k in _ks(N):
        want = t[k - 1] if 1 <= k <= N else Fraction(0)
        for name, ref in (("pmf", want), ("cdf", cdf_ref(t, k)), ("sf", sf_ref(t, k))):
            got = getattr(d, name)(k)
            assert isinstance(got, float), name
            assert math.isclose(got, float(ref), rel_tol=1e-12, abs_tol=1e-300), (name, k)
            lg = getattr(d, "log" + name)(k)
            if ref == 0:
                assert lg == -math.inf
            else:
                lw = float(log_of(ref))
                assert abs(lg - lw) <= 1e-12 * max(1.0, abs(lw)), ("log" + name, k, lg, lw)
    kk = np.array([-1, 0, 1, N, N + 1, 10**30], dtype=object)
    got = d.pmf(kk)
    assert got.dtype == np.float64
    assert np.allclose(got, [0, 0, float(t[0]), float(t[-1]), 0, 0], rtol=1e-12, atol=0)
    cd = d.cdf(np.array([0, N, N + 1, 10**30], dtype=object))
    assert cd.tolist() == [0.0, 1.0, 1.0, 1.0]
    mu = sum((k * x for k, x in enumerate(t, 1)), Fraction(0))
    var = sum(((k - mu) ** 2 * x for k, x in enumerate(t, 1)), Fraction(0))
    assert math.isclose(d.mean(), float(mu), rel_tol=1e-12)
    assert math.isclose(d.var(), float(var), rel_tol=1e-9, abs_tol=1e-300)
    assert math.isclose(d.std(), math.sqrt(float(var)), rel_tol=1e-9, abs_tol=1e-150)
    gamma = sum(phi(N, p, k) for k in range(1, N + 1))
    assert math.isclose(d.normaliser, float(gamma), rel_tol=1e-12)
    assert math.isclose(d.log_normaliser, float(log_of(gamma)), rel_tol=1e-12, abs_tol=1e-12)
    with mpmath.workdps(40):
        h = float(-mpmath.fsum(mp_of(x) * log_of(x) for x in t if x))
    assert abs(d.entropy() - h) <= 1e-12
    modes = brute_modes(N, p)
    assert d.modes() == modes and d.mode() == modes[0]
    tab = d.table()
    assert [k for k, _ in tab] == list(range(1, N + 1))
    assert all(math.isclose(v, float(w), rel_tol=1e-12) for (_, v), w in zip(tab, t, strict=True))
    cdf_f = np.array([float(cdf_ref(t, j)) for j in range(1, N + 1)])
    sf_f = np.array([float(sf_ref(t, j)) for j in range(0, N + 1)])
    for q in _qs(t):
        if np.min(np.abs(cdf_f - float(q))) >= 1e-9:
            assert d.ppf(q) == ppf_ref(t, q) and isinstance(d.ppf(q), int), ("ppf", q)
        if np.min(np.abs(sf_f - float(q))) >= 1e-9:
            assert d.isf(q) == isf_ref(t, q), ("isf", q)
    assert d.ppf(0) == 0 and d.ppf(1) == N and d.isf(1) == 0 and d.isf(0) == N
    qa = d.isf([Fraction(1), Fraction(0)])
    assert qa.dtype == np.int64 and qa.tolist() == [0, N]


# --------------------------------------------------------------------------- sampling
def _chisquare_pvalue(obs: np.ndarray, exp: np.ndarray) -> float:
    from scipy.special import chdtrc

    stat = float(np.sum((obs - exp) ** 2 / exp))
    return float(chdtrc(len(obs) - 1, stat))


def test_rvs_against_exact_pmf() -> None:

    N, pf = 12, 0.25
    t = table(N, Fraction(pf))
    for dps in (20, None):
        d = symhx.distribution_of(N, pf, dps=dps)
        a = d.rvs(30_000, random_state=9)
        assert a.dtype == np.int64 and a.shape == (30_000,)
        assert a.min() == 1 and a.max() <= N
        obs = np.bincount(a, minlength=N + 1)[1:]
        exp = np.array([float(x) for x in t]) * a.size
        keep = exp >= 5
        o = np.append(obs[keep], obs[~keep].sum())
        e = np.append(exp[keep], exp[~keep].sum())
        if e[-1] == 0:
            o, e = o[:-1], e[:-1]
        assert _chisquare_pvalue(o, e * o.sum() / e.sum()) > 1e-4
    d = symhx.distribution_of(N, pf, dps=None)
    assert np.array_equal(d.rvs((3, 4), random_state=5),
                          d.rvs((3, 4), random_state=np.random.default_rng(5)))
    assert d.rvs((3, 4), random_state=5).shape == (3, 4)
    x = d.rvs(random_state=3)
    assert isinstance(x, int) and 1 <= x <= N
    assert d.rvs(0, random_state=1).shape == (0,)
    # the largest value is reachable: u just below 1 maps to N
    top = symhx.distribution_of(2, 100.0, dps=None)  # P(X = 2) ~ 1
    assert top.rvs(50, random_state=1).tolist() == [2] * 50
    one = symhx.distribution_of(1, 0.5, dps=None)
    assert one.rvs(5, random_state=2).tolist() == [1] * 5


# --------------------------------------------------------------------------- exact sums
@given(st.integers(0, 25), st.integers(1, 9), st.integers(1, 9), st.integers(-1, 30))
def test_binary_split_against_direct_sum(N: int, a: int, b: int, stop: int) -> None:
    def w(j: int) -> tuple[int, int]:
        return j * j + 1, 2 * j + 3

    want = Fraction(0)
    prod = Fraction(1)
    for j in range(1, min(stop, N) + 1):
        prod *= Fraction(a * (N - j + 1), b)
        want += Fraction(*w(j)) * prod
    assert binary_split(N, a, b, w, min(stop, N)) == want
    full = sum((Fraction(*w(j)) * Fraction(a, b) ** j * math.perm(N, j)
                for j in range(1, N + 1)), Fraction(0))
    assert binary_split(N, a, b, w) == full


# --------------------------------------------------------------------------- errors and limits
def test_limits_and_errors() -> None:
    from symhx import distribution as dist

    with pytest.raises(ValueError, match="EXACT_N_LIMIT"):
        SimpleDistribution(dist.EXACT_N_LIMIT + 1, "0.5")
    SimpleDistribution(dist.EXACT_N_LIMIT, "0.5")  # the limit itself is allowed
    big = SimpleDistribution(dist.MP_QUANTILE_N_LIMIT + 1, 0.5, dps=15)
    with pytest.raises(ValueError, match="MP_QUANTILE_N_LIMIT"):
        big.ppf("0.5")
    with pytest.raises(ValueError, match="MP_QUANTILE_N_LIMIT"):
        big.isf("0.5")
    assert big.ppf(0) == 0 and big.isf(0) == big.N  # trivial quantiles need no sums
    huge = SimpleDistribution(10**120, 0.5, dps=15)
    with pytest.raises(ValueError, match=r"MP_SUM_N_LIMIT.*10\*\*120"):
        huge.pmf(5)
    with pytest.raises(ValueError, match=r"~10\*\*120"):
        SimpleDistribution(10**120 + 1, 0.5, dps=15).mean()
    with pytest.raises(ValueError, match="FLOAT_N_LIMIT"):
        SimpleDistribution(dist.FLOAT_N_LIMIT + 1, 0.5, dps=None).mean()
    with pytest.raises(ValueError, match="FLOAT_N_LIMIT"):
        SimpleDistribution(dist.FLOAT_N_LIMIT + 1, 0.5).rvs(random_state=1)
    with pytest.raises(ValueError, match="EXACT_QUANTILE_WORK_LIMIT"):
        SimpleDistribution(20000, "0.1").isf("0.5")
    with pytest.raises(ValueError, match="EXACT_WORK_LIMIT"):
        SimpleDistribution(40000, "0.1").pmf(3)
    d = SimpleDistribution(10, 0.3, dps=20)
    with pytest.raises(TypeError, match="k"):
        d.pmf(np.array([True, False]))
    with pytest.raises(TypeError, match="k"):
        d.pmf(np.array([1.0, 2.0]))
    with pytest.raises(TypeError, match="k"):
        d.pmf([1, 2.5])
    with pytest.raises(ValueError, match="q"):
        d.isf([0.5, -0.1])
    with pytest.raises(ValueError, match="size"):
        d.rvs(-1)
    with pytest.raises(ValueError, match="size"):
        d.rvs((2, -1))
    assert "SimpleDistribution(N=10, p=0.3, space='simple', dps=20, exact=False)" == repr(d)


def test_work_measure_is_the_documented_one() -> None:
    """N (bits of N + bits of p's numerator and denominator) against EXACT_WORK_LIMIT: just
    inside and just outside."""
    from symhx import distribution as dist

    def work(N: int, p: Fraction) -> int:
        return N * (N.bit_length() + p.numerator.bit_length() + p.denominator.bit_length())

    p = Fraction(1, 3)
    inside = max(N for N in range(10_000, 40_000, 7) if work(N, p) <= dist.EXACT_WORK_LIMIT)
    assert SimpleDistribution(inside, p)._check_exact_work("x", dist.EXACT_WORK_LIMIT,
                                                           "EXACT_WORK_LIMIT") is None
    with pytest.raises(ValueError, match="EXACT_WORK_LIMIT"):
        SimpleDistribution(inside + 7, p)._check_exact_work("x", dist.EXACT_WORK_LIMIT,
                                                            "EXACT_WORK_LIMIT")
    q = Fraction(1, 2)
    N = max(n for n in range(1000, 20_000) if work(n, q) <= dist.EXACT_QUANTILE_WORK_LIMIT)
    SimpleDistribution(N, q)._check_exact_work("q", dist.EXACT_QUANTILE_WORK_LIMIT, "E")
    with pytest.raises(ValueError, match=str(dist.EXACT_QUANTILE_WORK_LIMIT)):
        SimpleDistribution(N + 1, q)._check_exact_work("q", dist.EXACT_QUANTILE_WORK_LIMIT,
                                                       "E")


def test_moved_names_forward_with_a_warning() -> None:
    import symhx.distribution as dist

    with pytest.warns(DeprecationWarning, match=r"symhx\.mean"):
        f = dist.mean
    assert f(3, "1/2") == Fraction(3, 2)
    with pytest.raises(AttributeError, match="no_such"):
        dist.no_such  # noqa: B018
    with pytest.warns(DeprecationWarning, match="var"):
        assert SimpleDistribution(3, "1/2").variance() == table_var(3, Fraction(1, 2))


def table_var(N: int, p: Fraction) -> Fraction:
    t = table(N, p)
    mu = sum((k * x for k, x in enumerate(t, 1)), Fraction(0))
    return sum(((k - mu) ** 2 * x for k, x in enumerate(t, 1)), Fraction(0))


class _FixedUniforms(np.random.Generator):
    """A Generator whose ``random()`` returns chosen values (to hit cdf values exactly)."""

    def __init__(self, values: list[float]) -> None:
        super().__init__(np.random.PCG64(0))
        self.values = np.array(values, dtype=float)

    def random(self, size: Any = None, dtype: Any = None, out: Any = None) -> Any:
        return self.values[0] if size is None else np.resize(self.values, size)


def test_rvs_inverse_transform_at_exact_cdf_values() -> None:
    """X = smallest k with u < cdf(k): u equal to cdf(k) gives k + 1; u just below 1 gives N
    even where the float cdf ends below 1 (N = 2, p = 0.05 ends at 1 - 2**-52)."""
    d = symhx.distribution_of(4, "1/3", dps=None)
    exact_hits = [float(d.cdf(k)) for k in range(1, 4)]
    assert d.rvs(3, random_state=_FixedUniforms(exact_hits)).tolist() == [2, 3, 4]
    u1 = float(np.nextafter(1.0, 0.0))
    for N, pf in ((2, 0.05), (3, 0.5), (7, 2.0)):
        e = symhx.distribution_of(N, pf, dps=None)
        assert e.rvs(random_state=_FixedUniforms([u1])) == N
        assert e.rvs(2, random_state=_FixedUniforms([u1])).tolist() == [N, N]
        assert e.rvs(random_state=_FixedUniforms([0.0])) == 1


def test_rvs_argument_errors_name_the_argument() -> None:
    d = symhx.distribution_of(5, 0.3, dps=None)
    with pytest.raises(ValueError, match=r"\bsize\b"):
        d.rvs(-1)
    with pytest.raises(ValueError, match=r"\bsize\b"):
        d.rvs((2, -1))
    assert d.rvs((0, 3), random_state=1).shape == (0, 3)
    with pytest.raises(ValueError, match=r"\brandom_state\b"):
        d.rvs(2, random_state=-1)
    with pytest.raises(TypeError, match=r"^random_state\b"):
        d.rvs(2, random_state=1.5)


def test_messages_show_huge_N() -> None:
    """Error messages write N as digits below 10**15, else as 10**e or ~10**e."""
    cases = {10**15 - 1: "N=999999999999999", 10**15: "N=10**15", 10**15 + 1: "N=~10**15",
             2 * 10**16: "N=~10**16", 10**7: "N=10000000"}
    for N, shown in cases.items():
        d = SimpleDistribution(N, 0.5, dps=15)
        with pytest.raises(ValueError) as err:
            d.ppf("0.5")
        msg = str(err.value)
        assert shown + "." in msg or shown + " " in msg or msg.endswith(shown), (N, msg)
        assert "N <= 10**6" not in msg or "MP_QUANTILE_N_LIMIT" in msg
        assert "limited to N <= 1000000 " in msg


def test_exact_work_boundary_is_inclusive() -> None:
    """work == EXACT_WORK_LIMIT is allowed, one more is refused (N = 20000, p = 1/256:
    20000 * (15 + 1 + 9) = 500000)."""
    from symhx import distribution as dist

    p = Fraction(1, 256)
    assert 20000 * (20000 .bit_length() + 1 + 9) == dist.EXACT_WORK_LIMIT
    d = SimpleDistribution(20000, p)
    d._check_exact_work("x", dist.EXACT_WORK_LIMIT, "EXACT_WORK_LIMIT")  # no error
    with pytest.raises(ValueError, match=r"^summing the distribution in exact .*"
                                         r"symhx\.distribution\.EXACT_WORK_LIMIT"):
        SimpleDistribution(20001, p).cdf(3)
    with pytest.raises(ValueError, match=r"^summing the distribution in exact .*"
                                         r"symhx\.distribution\.EXACT_WORK_LIMIT"):
        SimpleDistribution(20001, p).pmf(3)


def test_deprecations_point_at_the_caller() -> None:
    import symhx.distribution as dist

    with pytest.warns(DeprecationWarning,
                      match=r"^Distribution\.variance\(\) is deprecated: use var\(\)") as rec:
        SimpleDistribution(3, "1/2").variance()
    assert rec[0].filename == __file__ or _UNDER_MUTMUT in rec[0].filename
    with pytest.warns(DeprecationWarning, match=r"^symhx\.distribution\.mode moved") as rec:
        dist.mode  # noqa: B018
    assert rec[0].filename == __file__ or _UNDER_MUTMUT in rec[0].filename


def test_sympy_irrational_p_on_the_mpmath_path() -> None:
    """An irrational p (no exact rational value) runs the hump search on a binary
    approximation: every method against the downward recurrence at sqrt(2)/10."""
    sympy = pytest.importorskip("sympy")
    N, dps = 40, 30
    d = symhx.distribution_of(N, sympy.sqrt(2) / 10, dps=dps)
    assert d.fr is None and not d.exact
    with mpmath.workdps(3 * dps):
        pm = mpmath.sqrt(2) / 10
        w = [pm**k * mpmath.factorial(N) / (k * mpmath.factorial(N - k)) for k in range(1, N + 1)]
        s = mpmath.fsum(w)
        ref = [x / s for x in w]
        for k in (1, 2, 3, 5, 6, 20, N):
            close(d.pmf(k), ref[k - 1], dps, k)
            close(d.sf(k - 1) if k > 1 else d.cdf(1), mpmath.fsum(ref[k - 1:]) if k > 1
                  else ref[0], dps, ("tail", k))
        mu = mpmath.fsum(k * x for k, x in enumerate(ref, 1))
        close(d.mean(), mu, dps, "mean")
        close(d.var(), mpmath.fsum((k - mu) ** 2 * x for k, x in enumerate(ref, 1)), dps, "var")
        best = max(range(1, N + 1), key=lambda k: ref[k - 1])
    assert d.mode() == best and symhx.mode(N, sympy.sqrt(2) / 10) == best


def test_float_arrays_far_outside_the_support() -> None:
    d = symhx.distribution_of(5, 0.5, dps=None)
    t = table(5, Fraction(0.5))
    got = d.pmf(np.array([-100, -6, 1, 5, 6, 100]))
    assert got.dtype == np.float64
    assert got.tolist()[:2] == [0.0, 0.0] and got.tolist()[4:] == [0.0, 0.0]
    assert math.isclose(got[2], float(t[0]), rel_tol=1e-12)
    assert d.cdf(np.array([-100, 100])).tolist() == [0.0, 1.0]
    assert d.sf(np.array([-100, 100])).tolist() == [1.0, 0.0]
    assert d.logsf(np.array([-100, 100])).tolist() == [0.0, -math.inf]


def test_exact_work_message_shows_p_cut_to_40_characters() -> None:
    p = Fraction(1, 3**100)
    assert len(str(p)) > 41
    with pytest.raises(ValueError) as err:
        SimpleDistribution(5000, p).mean()
    assert f"N=5000, p={str(p)[:40]} (documented work limit 500000," in str(err.value)


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


@pytest.mark.parametrize("dps", [20, 50])
def test_mp_logs_of_certain_events_are_exactly_zero(dps: int) -> None:
    for N, pf in ((1, 0.5), (6, 0.3), (40, 0.07)):
        d = symhx.distribution_of(N, pf, dps=dps)
        assert d.logcdf(N) == 0 and d.logcdf(N + 5) == 0
        assert d.logsf(0) == 0 and d.logsf(-3) == 0
        assert d.logsf(N) == mpmath.ninf and d.logcdf(0) == mpmath.ninf
        assert d.cdf(N) == 1 and d.sf(0) == 1 and d.sf(N) == 0 and d.cdf(0) == 0


def _fraction_of(x: mpmath.mpf) -> Fraction:
    man, exp = x.man_exp
    return Fraction(int(man)) * Fraction(2) ** int(exp)


@pytest.mark.parametrize("dps", [20, 30])
def test_mp_quantile_resolution_is_exactly_ten_to_one_minus_dps(dps: int) -> None:
    """The documented resolution: ppf gives k when q <= cdf(k) (1 + 10**(1 - dps)) and isf
    gives k when q >= sf(k) (1 - 10**(1 - dps)), against the returned (rounded) cdf / sf
    values; half the resolution inside counts as equal, twice outside does not."""
    N, pf = 12, 0.3
    d = symhx.distribution_of(N, pf, dps=dps)
    eps = Fraction(10) ** (1 - dps)
    for k in (3, 6, 9):
        c, s = _fraction_of(d.cdf(k)), _fraction_of(d.sf(k))
        assert d.ppf(c * (1 + eps / 2)) == k and d.ppf(c * (1 + 2 * eps)) == k + 1
        assert d.isf(s * (1 - eps / 2)) == k and d.isf(s * (1 - 2 * eps)) == k + 1


def test_exact_quantiles_have_no_tolerance() -> None:
    """Exact p: q a relative 10**-40 away from cdf(k) / sf(k) moves the quantile."""
    d = symhx.distribution_of(12, "0.3", dps=30)
    t = table(12, Fraction(3, 10))
    tiny = Fraction(1, 10**40)
    for k in (3, 6, 9):
        assert d.ppf(cdf_ref(t, k) * (1 + tiny)) == k + 1
        assert d.ppf(cdf_ref(t, k)) == k
        assert d.isf(sf_ref(t, k) * (1 - tiny)) == k + 1
        assert d.isf(sf_ref(t, k)) == k


def test_quantile_limit_messages() -> None:
    big = SimpleDistribution(10**6 + 1, 0.5, dps=15)
    for method in (big.ppf, big.isf):
        with pytest.raises(ValueError, match=r"^a quantile on the mpmath path is limited to "
                                             r"N <= 1000000 \(symhx\.distribution\."
                                             r"MP_QUANTILE_N_LIMIT, a work limit\)"):
            method("0.5")
    ex = SimpleDistribution(20000, "0.1")
    for method in (ex.ppf, ex.isf):
        with pytest.raises(ValueError, match=r"^a quantile in exact rational arithmetic .*"
                                             r"symhx\.distribution\.EXACT_QUANTILE_WORK_LIMIT\)"):
            method("0.5")
    with pytest.raises(ValueError, match=r"^a quantile in exact"):
        ex.median()


def test_object_k_arrays_keep_their_shape_and_name_k() -> None:
    d = symhx.distribution_of(6, 0.4, dps=20)
    t = table(6, Fraction(0.4))
    k = np.array([[1, 2], [6, 10**30]], dtype=object)
    got = d.pmf(k)
    assert got.shape == (2, 2)
    close(got[1, 0], t[5], 20)
    assert got[1, 1] == 0
    f = symhx.distribution_of(6, 0.4, dps=None).cdf(k)
    assert f.shape == (2, 2) and f[1, 1] == 1.0
    with pytest.raises(TypeError, match=r"^k must be an int"):
        d.pmf(np.array([1, 2.5], dtype=object))


def test_q_is_checked_like_a_probability() -> None:
    d = symhx.distribution_of(6, 0.4, dps=20)
    for bad in (1.5, "2", Fraction(101, 100)):
        with pytest.raises(ValueError, match=r"^q must be <= 1"):
            d.ppf(bad)
    with pytest.raises(ValueError, match=r"^q must be >= 0"):
        d.isf(-0.25)
    with pytest.raises(TypeError, match=r"^q must be a real number, got bool"):
        d.ppf([0.5, True])
    with pytest.raises(ValueError, match=r"^q must be <= 1"):
        d.isf([0.5, 1.5])
    with pytest.raises(ValueError, match=r"^confidence must be <= 1"):
        d.interval(1.5)


@given(st.integers(2, 60), st.fractions(Fraction(1, 200), 3).filter(lambda x: x > 0))
@example(5, Fraction(1, 2))
@example(101, Fraction(1, 50))
@example(40, Fraction(3, 40))
@example(101, Fraction(1, 80))  # a hump (tie 16/17) below Phi(1): the mode is 1
@example(60, Fraction(1, 40))  # the hump wins
def test_modes_decided_by_the_exact_fallback_alone(N: int, p: Fraction) -> None:
    """The comparison of Phi(top) with Phi(1) falls back to exact integers when interval
    arithmetic cannot certify its sign (an exact tie): forcing that fallback everywhere must
    give the brute-force modes too."""
    import symhx.distribution as dist

    calls = []

    def exact_only(fn: Any, *, start_bits: int, max_bits: int, exact_fn: Any = None) -> int:
        calls.append(start_bits)
        assert exact_fn is not None and start_bits >= 64 and max_bits >= start_bits
        return exact_fn()

    real = dist.certified_sign
    dist.certified_sign = exact_only
    try:
        got = simple_modes(N, p, None)
    finally:
        dist.certified_sign = real
    assert got == brute_modes(N, p)


def test_mp_binary_exact_tie_far_above_phi_one() -> None:
    """N = 2049, p = 2**-10 (exact in binary): Phi(1024) = Phi(1025) exactly, ~e**390 above
    Phi(1); the lower tail below the hump is still summed to dps digits."""
    N, pf, dps = 2049, 2.0**-10, 20
    assert Fraction(pf) * (N - 1024) * 1024 / 1025 == 1  # the exact tie
    d = symhx.distribution_of(N, pf, dps=dps)
    assert d.modes() == (1024, 1025) and d.mode() == 1024
    ref = mp_table(N, Fraction(pf), 2 * dps + 20)
    with mpmath.workdps(2 * dps + 20):
        for k in (1, 10, 500, 1024):
            c = mpmath.fsum(ref[:k])
            close(d.cdf(k), c, dps, ("cdf", k))
            close_log(d.logcdf(k), mpmath.log(c), dps, ("logcdf", k))
        close(d.sf(1030), mpmath.fsum(ref[1030:]), dps, "sf")
        close(d.pmf(1025), ref[1024], dps, "pmf")


def test_certain_events_need_no_sums() -> None:
    """cdf(k >= N) = 1 and sf(k >= N) = 0 are answered without summing (any N)."""
    d = SimpleDistribution(10**120, 0.5, dps=15)
    assert d.cdf(10**120) == 1 and d.sf(10**120) == 0 and d.cdf(10**121) == 1
    assert d.logcdf(10**120) == 0 and d.logsf(10**120) == mpmath.ninf
    assert d.cdf(0) == 0 and d.sf(0) == 1


def test_float_entropy_with_underflowing_pmf() -> None:
    """dps=None: pmf values that underflow to 0.0 contribute nothing (not nan, not 1)."""
    N, pf = 3000, 1e-4
    d = symhx.distribution_of(N, pf, dps=None)
    assert d.pmf(N) == 0.0  # underflows
    ref = mp_table(N, Fraction(pf), 30)
    with mpmath.workdps(30):
        h = -mpmath.fsum(x * mpmath.log(x) for x in ref if x > mpmath.mpf(10) ** -40)
    assert abs(d.entropy() - float(h)) <= 1e-16 * N * math.log(N) * float(h)  # documented


def test_float_ppf_near_one_stays_in_the_support() -> None:
    """N = 2, p = 0.05: the float cdf ends at 1 - 2**-52; q = 1 - 2**-53 lies above it and
    must still give N (not N + 1)."""
    q = float(np.nextafter(1.0, 0.0))
    for N, pf in ((2, 0.05), (3, 0.5), (20, 0.3)):
        d = symhx.distribution_of(N, pf, dps=None)
        assert d.ppf(q) == N and d.ppf([q]).tolist() == [N]


def test_mp_p_with_a_long_mantissa() -> None:
    """An mpf p carrying 1300 bits (its exact value has a huge numerator and denominator) is cut
    to the working precision before use: results match the exact value's reference."""
    with mpmath.workdps(400):
        pm = mpmath.mpf(1) / 3 + mpmath.mpf(10) ** -350
    N, dps = 9, 25
    d = symhx.distribution_of(N, pm, dps=dps)
    t = table(N, _fraction_of(pm))
    mu = sum((k * x for k, x in enumerate(t, 1)), Fraction(0))
    close(d.mean(), mu, dps, "mean")
    for k in (1, 5, N):
        close(d.pmf(k), t[k - 1], dps, k)


def test_mp_sums_work_at_their_limit() -> None:
    """N = MP_SUM_N_LIMIT itself is allowed: with j = N - X the weights are ~ (1/p)**j / j!
    (Poisson), so E[X] = N - 1/p up to O(1/N)."""
    from symhx import distribution as dist

    N = dist.MP_SUM_N_LIMIT
    with mpmath.workdps(130):
        p = mpmath.mpf(1) / 10
    m = SimpleDistribution(N, p, dps=110).mean()
    with mpmath.workdps(130):
        assert abs(m - (N - 1 / p)) < mpmath.mpf(10) ** -8
