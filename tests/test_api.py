"""The user-facing functions of :mod:`symhx.api` (``symhx.pmf``, ``symhx.mean``, ...):
dispatch on ``space``, broadcasting over ``p`` and ``k`` / ``q`` like scipy.stats (shapes,
dtypes, equal values of different types kept apart), result types, modes, the critical point,
refusals and the deprecated ``symhx.variance``.

References: the closed-form simple pmf (factorials, brute-force normaliser) and, for the
higher-order spaces, Burnside circuit counts times ``p**length`` summed per ``k``
(:func:`tests.reference.spaces.exact_table`); the critical point by an exhaustive scan of
``c_k`` from ``loggamma`` (:func:`tests.reference.critical.critical_by_scan`).
"""

from __future__ import annotations

import math
import os
import warnings
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import symhx
from symhx import api
from symhx.distribution import SimpleDistribution
from symhx.spaces import SpaceDistribution, parse_space
from tests.harness.discrete import check_refusals
from tests.harness.errors import assert_refuses
from tests.reference.critical import critical_by_scan
from tests.reference.distribution import ExactTable, phi_exact, pmf_table, to_mp
from tests.reference.spaces import evaluate, exact_table, weight_poly

SPACES = ["simple", "eq41", "excess<=1;distinct"]


# --------------------------------------------------------------------------- dispatch
@pytest.mark.parametrize("space", SPACES)
def test_every_function_dispatches_on_space(space: str) -> None:
    N, p = 9, Fraction(1, 3)
    t = exact_table(N, p, space)
    mu, var = t.mean, t.var
    assert symhx.pmf(N, p, 3, space=space) == t.pmf[2]
    assert symhx.cdf(N, p, 3, space=space) == t.cdf(3)
    assert symhx.sf(N, p, 3, space=space) == 1 - t.cdf(3)
    assert symhx.mean(N, p, space=space) == mu
    assert symhx.var(N, p, space=space) == var
    with pytest.warns(DeprecationWarning):
        assert symhx.variance(N, p, space=space, dps=20) == var
    with mpmath.workdps(60):
        assert abs(symhx.std(N, p, space=space, dps=40) - mpmath.sqrt(to_mp(var))) \
            < mpmath.mpf(10) ** -39 * mpmath.sqrt(to_mp(var))
        h = t.entropy(60)
        assert abs(symhx.entropy(N, p, space=space, dps=40) - h) < mpmath.mpf(10) ** -39
        for name, want in (("logpmf", t.pmf[2]), ("logcdf", t.cdf(3)), ("logsf", t.sf(3))):
            got = getattr(symhx, name)(N, p, 3, space=space, dps=40)
            lw = mpmath.log(to_mp(want))
            assert abs(got - lw) < mpmath.mpf(10) ** -39 * abs(lw), name
    assert symhx.median(N, p, space=space) == t.ppf(Fraction(1, 2))
    assert symhx.ppf(N, p, "0.3", space=space) == t.ppf(Fraction(3, 10))
    assert symhx.isf(N, p, "0.3", space=space) == t.isf(Fraction(3, 10))
    assert symhx.interval(N, p, "0.5", space=space) == (t.ppf(Fraction(1, 4)),
                                                        t.ppf(Fraction(3, 4)))
    assert symhx.modes(N, p, space=space) == t.modes
    assert symhx.mode(N, p, space=space) == t.modes[0]
    d = symhx.distribution_of(N, p, space=space, dps=25)
    assert d.space == parse_space(space).name and d.dps == 25 and d.exact
    assert d.pmf(3) == t.pmf[2]
    # a Space object works like its name; weighting= like the suffix
    assert symhx.distribution_of(N, p, space=parse_space(space)).pmf(3) == t.pmf[2]
    assert symhx.distribution_of(N, p, space=space.split(";")[0],
                                 weighting=parse_space(space).weighting).pmf(3) == t.pmf[2]
    x = symhx.rvs(N, float(p), size=2000, random_state=4, space=space)
    assert x.dtype == np.int64 and 1 <= x.min() and x.max() <= N
    assert abs(x.mean() - float(exact_table(N, Fraction(float(p)), space).mean)) < 0.2
    assert np.array_equal(x, symhx.distribution_of(N, float(p), space=space, dps=None).rvs(
        2000, random_state=4))
    norm = symhx.normaliser(N, p, space=space)
    assert isinstance(norm, Fraction) and norm > 0


@pytest.mark.parametrize("space", ["simple", parse_space("simple")])
def test_simple_space_gets_the_simple_distribution(space):
    """``space="simple"`` (a name or a parsed Space) builds the eq. 7-8 distribution itself,
    not the general higher-order one; its pmf is p**k N!/(k (N-k)!) normalised (exact)."""
    N, p = 9, Fraction(2, 7)
    d = symhx.distribution_of(N, p, space=space)
    assert type(d) is SimpleDistribution and not isinstance(d, SpaceDistribution)
    assert [d.pmf(k) for k in range(1, N + 1)] == pmf_table(N, p)
    assert type(symhx.distribution_of(N, p, space="eq41")) is SpaceDistribution


def test_excess_zero_and_distinct_suffix_dispatch():
    d = symhx.distribution_of(6, Fraction(1, 4), space="eq41;distinct")
    assert d.space == "eq41;distinct"
    assert symhx.mean(6, Fraction(1, 4), space="excess<=0") == symhx.mean(6, Fraction(1, 4))
    assert symhx.modes(6, Fraction(1, 4), space="eq41") == symhx.spaces.modes(
        6, Fraction(1, 4), space="eq41")


def test_normaliser_is_gamma() -> None:
    N, p = 7, Fraction(2, 5)
    gamma = sum(phi_exact(N, p, k) for k in range(1, N + 1))
    assert symhx.normaliser(N, p) == gamma
    assert math.isclose(symhx.normaliser(N, float(p), dps=None), float(gamma), rel_tol=1e-12)
    got = symhx.normaliser(N, [p, Fraction(1, 2)])
    assert got.dtype == object and got[0] == gamma


def test_normaliser_precision_is_local() -> None:
    """normaliser(..., dps=40) is correct to 40 digits whatever the global precision."""
    old = mpmath.mp.dps
    try:
        mpmath.mp.dps = 15
        got = symhx.normaliser(30, 0.3, dps=40)
        got_space = symhx.normaliser(30, 0.3, space="eq41", dps=40)
    finally:
        mpmath.mp.dps = old
    with mpmath.workdps(80):
        want = to_mp(exact_table(30, Fraction(0.3)).normaliser)
        assert abs(got - want) <= mpmath.mpf(10) ** -39 * want
        want = to_mp(exact_table(30, Fraction(0.3), "eq41").normaliser)
        assert abs(got_space - want) <= mpmath.mpf(10) ** -39 * want


def test_types_follow_p_and_dps() -> None:
    d = symhx.distribution_of(10, "0.3")
    assert isinstance(d.mean(), Fraction) and isinstance(d.std(), mpmath.mpf)
    assert isinstance(symhx.distribution_of(10, 0.3).mean(), mpmath.mpf)
    assert isinstance(symhx.distribution_of(10, "0.3", dps=None).mean(), float)
    assert isinstance(symhx.distribution_of(10, 0.3, dps=None).pmf(3), float)
    with pytest.warns(DeprecationWarning):
        assert d.variance() == d.var()
    with pytest.warns(DeprecationWarning):
        assert symhx.variance(10, "0.3") == d.var()


def test_api_names() -> None:
    assert set(api.__all__) >= {"pmf", "mode", "modes", "critical_point", "rvs", "interval"}


def test_top_level_names_are_the_api_functions() -> None:
    """``symhx.<name>`` (loaded lazily) is the function of :mod:`symhx.api` for every name the
    two share, and ``dir(symhx)`` lists them."""
    shared = set(api.__all__) & set(symhx.__all__)
    assert shared >= {"pmf", "cdf", "mean", "var", "mode", "modes", "distribution_of", "rvs"}
    for name in shared:
        assert getattr(symhx, name) is getattr(api, name), name
    assert shared <= set(dir(symhx))


# --------------------------------------------------------------------------- refusals
def test_bad_input():
    assert_refuses(symhx.mean, 10, 0, arg="p", value="got 0", allowed="> 0")
    assert_refuses(symhx.mean, 10, -0.1, arg="p", value="-0.1", allowed="> 0")
    assert_refuses(symhx.mode, 10, float("nan"), arg="p", value="nan", allowed="finite")
    assert_refuses(symhx.mode, 10, float("inf"), arg="p", value="inf", allowed="finite")
    assert_refuses(symhx.mode, 0, 0.5, arg="N", value="got 0", allowed=">= 1")
    assert_refuses(symhx.mode, 1e10, 0.5, exc=TypeError, arg="N", value="10000000000.0",
                   allowed="an int")
    assert_refuses(symhx.mean, 10, 0.5, dps=0, arg="dps", value="got 0",
                   allowed="an int between 1 and")
    # past the exact limits an exact p is evaluated at its exact rational value (mpf results)
    assert not SimpleDistribution(10**6, Fraction(1, 3)).exact
    assert_refuses(symhx.mean, 10, 0.5, space="no-such-space", arg="space",
                   value="'no-such-space'", allowed=["'simple'", "'eq41'", "'excess<=m'"])


def test_bad_arguments_are_clear_errors() -> None:
    check_refusals(symhx.distribution_of(10, 0.3, dps=20))
    assert_refuses(symhx.distribution_of, 10, 0.3, dps=0, arg="dps", value="got 0",
                   allowed="an int between 1 and")
    assert_refuses(symhx.distribution_of, 10, 0.3, space=3, exc=TypeError, arg="space",
                   value="int 3", allowed="a str")
    assert_refuses(symhx.distribution_of(10**8, 0.3, dps=None).rvs, random_state=1, arg="N",
                   value="N=100000000", allowed="FLOAT_N_LIMIT")
    assert_refuses(symhx.mean, 10, 0.3, space="excess<=1000", arg="m", value="1000",
                   allowed="MAX_EXCESS")


@pytest.mark.parametrize("bad,kind", [(3.5, "float"), (None, "NoneType"), (["eq41"], "list")])
def test_space_of_a_wrong_kind_names_its_type(bad, kind):
    assert_refuses(symhx.distribution_of, 10, 0.1, space=bad, exc=TypeError, arg="space",
                   value=f"got {kind} {bad!r}",
                   allowed=["a str such as 'simple', 'eq41' or 'excess<=3'",
                            "(or a symhx.spaces.Space)"])


def test_bad_space_and_arguments() -> None:
    for bad in (3, None, b"simple"):
        assert_refuses(symhx.pmf, 5, "0.5", 1, space=bad, exc=TypeError, arg="space",
                       value=f"{type(bad).__name__} {bad!r}", allowed="must be a str")
        assert_refuses(symhx.modes, 5, "0.5", space=bad, exc=TypeError, arg="space",
                       value=repr(bad), allowed="a str")
    assert_refuses(symhx.distribution_of, 0, "0.5", arg="N", value="got 0", allowed=">= 1")
    assert_refuses(symhx.mean, 0, ["0.5"], arg="N", value="got 0", allowed=">= 1")
    assert_refuses(symhx.pmf, 0, ["0.5"], [1], arg="N", value="got 0", allowed=">= 1")
    assert_refuses(symhx.modes, 0, "0.5", arg="N", value="got 0", allowed=">= 1")
    assert_refuses(symhx.mean, 5, ["0.5"], dps=0, arg="dps", value="got 0",
                   allowed="an int between 1 and")
    assert_refuses(symhx.pmf, 5, ["0.5"], [1], dps=-3, arg="dps", value="got -3",
                   allowed="an int between 1 and")
    assert_refuses(symhx.pmf, 5, ["0.5"], [1], space="nonsense", arg="space",
                   value="'nonsense'", allowed="'simple'")
    assert_refuses(symhx.critical_point, 1, arg="N", value="got 1", allowed=">= 2")
    # N = 1 is a valid distribution (X = 1)
    assert symhx.pmf(1, "0.5", 1) == 1 and symhx.mode(1, "0.5") == 1


def test_bad_entries_in_arrays_are_clear_errors() -> None:
    assert_refuses(symhx.pmf, 5, ["0.5"], [True, 1], exc=TypeError, arg="k", value="bool True",
                   allowed="an integer")
    assert_refuses(symhx.modes, 5, [0.5, True], exc=TypeError, arg="p", value="bool True",
                   allowed="a real")
    for f, extra in ((symhx.mean, ()), (symhx.pmf, (1,))):
        assert_refuses(f, 5, [0.5, (0.1, 0.2)], *extra, exc=TypeError, arg="p",
                       value="tuple (0.1, 0.2)", allowed="a real")


# --------------------------------------------------------------------------- broadcasting
def test_module_functions_broadcast_like_scipy() -> None:
    ks = np.arange(1, 5)
    got = symhx.pmf(101, 0.02, ks)
    assert got.shape == (4,) and got.dtype == object
    assert all(got[i] == symhx.pmf(101, 0.02, int(k)) for i, k in enumerate(ks))
    f = symhx.pmf(101, 0.02, ks, dps=None)
    assert f.dtype == np.float64
    assert np.allclose(f, [float(x) for x in got], rtol=1e-12, atol=0)
    ps = np.array([0.01, 0.02, 0.05])
    grid = symhx.cdf(50, ps[:, None], np.arange(1, 5)[None, :], dps=None)
    assert grid.shape == (3, 4)
    for i, p in enumerate(ps):
        for j, k in enumerate(range(1, 5)):
            assert grid[i, j] == symhx.distribution_of(50, float(p), dps=None).cdf(k)
    m = symhx.mean(101, ["0.01", 0.02], dps=None)
    assert m.shape == (2,) and m[1] == symhx.mean(101, 0.02, dps=None)
    assert list(symhx.mode(101, ["1/50", 0.02])) == [50, 51]
    assert list(symhx.modes(101, ["1/50", 0.02])) == [(50, 51), (51,)]
    meds = [symhx.median(101, "1/50"), symhx.median(101, "1/100")]
    assert meds[0] != meds[1]  # so that a permuted result cannot pass
    assert symhx.ppf(101, ["1/50", "1/100"], "1/2").tolist() == meds
    assert symhx.ppf(101, ["1/50", "1/100"], "1/2", dps=None).tolist() == meds
    assert symhx.isf(101, "1/50", ["1/10", "9/10"]).tolist() == [
        symhx.distribution_of(101, "1/50").isf(q) for q in ("1/10", "9/10")]


def test_broadcast_p_and_k_shapes_and_values() -> None:
    N = 8
    ps = [Fraction(1, 10), Fraction(1, 2), Fraction(3)]
    ks = [0, 1, 4, 8, 9]
    grid = symhx.pmf(N, np.array(ps, dtype=object)[:, None], np.array(ks)[None, :])
    assert grid.shape == (3, 5) and grid.dtype == object
    for i, p in enumerate(ps):
        t = ExactTable.simple(N, p)
        for j, k in enumerate(ks):
            assert grid[i, j] == t.pmf_at(k), (p, k)
    f = symhx.cdf(N, [float(p) for p in ps], 4, dps=None)
    assert f.shape == (3,) and f.dtype == np.float64
    for i, p in enumerate(ps):
        assert math.isclose(f[i], float(ExactTable.simple(N, Fraction(float(p))).cdf(4)),
                            rel_tol=1e-12)
    s = symhx.sf(N, ps, [[1], [2]])
    assert s.shape == (2, 3)
    for i in range(2):
        for j, p in enumerate(ps):
            assert s[i, j] == 1 - ExactTable.simple(N, p).cdf(i + 1)
    # scalar p with an array k: the distribution's own broadcasting
    a = symhx.logpmf(N, 0.5, np.arange(1, 4), dps=None)
    assert a.shape == (3,) and a.dtype == np.float64
    # integer results: int64 for float64, Python ints otherwise
    q = symhx.ppf(N, ps, "1/2", dps=None)
    assert q.dtype == np.int64
    assert q.tolist() == [ExactTable.simple(N, Fraction(float(p))).ppf(Fraction(1, 2))
                          for p in ps]
    qe = symhx.isf(N, ps, ["0.1", "0.9", "0.5"])
    assert qe.dtype == object and all(type(v) is int for v in qe)
    qf = symhx.isf(N, ps, ["0.1", "0.9", "0.5"], dps=None)
    assert qf.dtype == np.int64 and qf.tolist() == qe.tolist()
    lp = symhx.logsf(N, ps, 2, dps=None)
    assert lp.dtype == np.float64
    lc = symhx.logcdf(N, ps, 2, dps=20)
    assert lc.dtype == object


@given(st.lists(st.sampled_from(["1/2", "0.5", 0.5, 1, 1.0, "1", Fraction(1, 3), 0.25]),
                min_size=1, max_size=6))
@example([1, 1.0, "1"])
@example(["0.5", 0.5, "1/2"])
def test_per_p_cache_keeps_exact_and_float_apart(ps: list) -> None:
    """Equal values of different types are different distributions (exact vs mpmath)."""
    N = 6
    m = symhx.mean(N, ps, dps=20)
    v = symhx.var(N, np.array(ps, dtype=object), dps=20)
    pm = symhx.pmf(N, ps, 2, dps=20)
    for i, p in enumerate(ps):
        t = ExactTable.simple(N, Fraction(p))
        exact = not isinstance(p, float)
        assert isinstance(m[i], Fraction) == exact and isinstance(pm[i], Fraction) == exact
        if exact:
            assert m[i] == t.mean and v[i] == t.var
            continue
        with mpmath.workdps(40):
            assert abs(m[i] - to_mp(t.mean)) <= mpmath.mpf(10) ** -19 * to_mp(t.mean)
            assert abs(v[i] - to_mp(t.var)) <= mpmath.mpf(10) ** -19 * to_mp(t.var)


def test_unhashable_p_entries() -> None:
    """p entries that cannot be hashed (here numpy 0-d arrays) are cached by identity."""
    ps = np.empty(2, dtype=object)
    ps[0], ps[1] = np.array(0.5), np.array(0.25)
    got = symhx.mean(5, ps, dps=None)
    want = [float(ExactTable.simple(5, Fraction(x)).mean) for x in (0.5, 0.25)]
    assert np.allclose(got, want, rtol=1e-12, atol=0)
    got2 = symhx.pmf(5, ps, 1, dps=None)
    assert np.allclose(got2, [float(ExactTable.simple(5, Fraction(x)).pmf[0])
                              for x in (0.5, 0.25)], rtol=1e-12, atol=0)


def test_summaries_over_p() -> None:
    N = 30
    ps = np.array([[0.01, 0.05], [0.1, 0.5]])
    means = symhx.mean(N, ps, dps=None)
    assert means.shape == (2, 2) and means.dtype == np.float64
    stds = symhx.std(N, ps, dps=None)
    ents = symhx.entropy(N, ps, dps=None)
    meds = symhx.median(N, ps, dps=None)
    assert meds.dtype == np.int64 and meds.shape == (2, 2)
    meds_mp = symhx.median(N, ps)
    assert meds_mp.dtype == np.int64
    for idx in np.ndindex(2, 2):
        t = ExactTable.simple(N, Fraction(ps[idx]))
        assert math.isclose(means[idx], float(t.mean), rel_tol=1e-12)
        assert math.isclose(stds[idx], math.sqrt(float(t.var)), rel_tol=1e-10)
        h = -sum(float(x) * math.log(float(x)) for x in t.pmf if float(x) > 0)
        assert math.isclose(ents[idx], h, rel_tol=1e-11)
        assert meds[idx] == meds_mp[idx] == t.ppf(Fraction(1, 2))
    mpm = symhx.mean(N, ps, dps=30)
    assert mpm.dtype == object and isinstance(mpm[0, 0], mpmath.mpf)


def test_N_one_with_arrays_of_p() -> None:
    assert symhx.mean(1, ["1/2", 0.5]).tolist() == [1, 1]
    assert symhx.pmf(1, ["1/2", 0.5], [1, 2]).tolist() == [1, 0]
    assert symhx.pmf(1, ["1/2"], 1).tolist() == [1]


def test_exact_quantiles_are_decided_exactly() -> None:
    """Where q equals a cdf value exactly, the exact path decides (the float64 path would not):
    N = 4, p = 2 has cdf(3) = 1/2; N = 2, p = 3 and N = 2, p = 1/2."""
    t = ExactTable.simple(4, Fraction(2))
    assert t.cdf(3) == Fraction(1, 2)
    assert symhx.median(4, "2") == 3 == t.ppf(Fraction(1, 2))
    assert symhx.median(4, ["2"]).tolist() == [3]
    t2 = ExactTable.simple(2, Fraction(1, 2))
    assert symhx.ppf(2, "1/2", "4/5") == t2.ppf(Fraction(4, 5)) == 1
    assert symhx.ppf(2, ["1/2"], "4/5").tolist() == [1]
    t3 = ExactTable.simple(2, Fraction(3))
    assert symhx.interval(2, "3", "1/5") == (t3.ppf(Fraction(2, 5)), t3.ppf(Fraction(3, 5)))
    assert symhx.interval(2, "3", "1/5") == (1, 2)


def test_interval_honours_dps() -> None:
    """On the mpmath path q is resolved to dps digits: an upper quantile 1e-25 (relative) above
    cdf(k) gives k at dps = 20 and k + 1 at dps = 40."""
    N, pf, k = 12, 0.3, 8
    t = ExactTable.simple(N, Fraction(pf))
    hi = t.cdf(k) * (1 + Fraction(1, 10**25))
    assert hi > Fraction(1, 2)
    c = 2 * hi - 1
    lo = t.ppf((1 - c) / 2)
    assert symhx.interval(N, pf, c, dps=20) == (lo, k)
    assert symhx.interval(N, pf, c, dps=40) == (lo, k + 1)


def test_rvs_is_float64_whatever_p() -> None:
    """rvs never builds an exact distribution: N above the exact limit works with an exact p."""
    x = symhx.rvs(200_000, "1/100000", 50, random_state=3)
    assert x.dtype == np.int64 and x.min() >= 1 and x.max() <= 200_000


# --------------------------------------------------------------------------- modes
def test_mode_and_modes_over_p() -> None:
    N = 101
    ps = np.array([["1/50", 0.02], ["0.01", "1/2"]], dtype=object)
    ms = symhx.modes(N, ps)
    assert ms.shape == (2, 2) and ms.dtype == object
    m = symhx.mode(N, ps)
    assert m.shape == (2, 2) and m.dtype == np.int64
    for idx in np.ndindex(2, 2):
        p = ps[idx]
        want = ExactTable.simple(N, Fraction(p)).modes
        assert ms[idx] == want and m[idx] == want[0], (p, want)
    assert ms[0, 0] == (50, 51) and m[0, 0] == 50  # the tie: the smallest maximiser
    assert symhx.mode(5, "1/2") == 1 and symhx.modes(5, "1/2") == (1, 2, 3)
    assert symhx.mode(101, "1/50", space="eq41") == exact_table(101, Fraction(1, 50),
                                                                "eq41").modes[0]
    got = symhx.modes(12, ["1/3", 0.25], space="eq41")
    assert got.tolist() == [exact_table(12, Fraction(1, 3), "eq41").modes,
                            exact_table(12, Fraction(0.25), "eq41").modes]


def test_modes_huge_N_take_the_simple_route() -> None:
    """modes() of the simple space never tabulates: N = 10**30 is decided at once; the mode m
    satisfies Phi(m+1) <= Phi(m) and Phi(m-1) < Phi(m) (term ratio p (N-k) k / (k+1))."""
    N, p = 10**30, Fraction(1, 2)
    (m,) = symhx.modes(N, "1/2")
    assert p * (N - m) * m / (m + 1) <= 1 < p * (N - m + 1) * (m - 1) / m
    assert symhx.mode(N, "1/2") == m
    arr = symhx.mode(N, ["1/2", "1e-40"])
    assert arr.dtype == object and arr.tolist() == [m, 1]  # m does not fit in int64
    small = symhx.mode(101, ["1/50", "1/2"])
    assert small.dtype == np.int64 and small.tolist() == [
        50, ExactTable.simple(101, p).modes[0]]


def test_mode_array_dtype_at_the_int64_edge() -> None:
    """p = (k + 1) / (k (N - k)) makes Phi(k) = Phi(k + 1) (a tie, smallest maximiser k): with
    k = 2**63 - 1 the modes still fit in int64; with k = 2**63 + 5 they need Python ints."""
    for k, dtype in ((2**63 - 1, np.int64), (2**63 + 5, object)):
        N = 3 * k
        p = Fraction(k + 1, k * (N - k))
        assert p * (N - k) * k / (k + 1) == 1  # the term ratio: an exact tie
        assert symhx.modes(N, p) == (k, k + 1)
        got = symhx.mode(N, [p, "1e-60"])
        assert got.dtype == dtype and got[0] == k, (k, got.dtype)


def test_irrational_p_modes_in_every_space() -> None:
    sympy = pytest.importorskip("sympy")
    p_sym = sympy.sqrt(2) / 10
    N = 12
    with mpmath.workdps(50):
        pm = mpmath.sqrt(2) / 10
        for space in ("simple", "eq41"):
            w = [evaluate(weight_poly(N, space, k), pm) for k in range(1, N + 1)]
            best = max(w)
            want = tuple(k for k, x in enumerate(w, 1) if x == best)
            assert symhx.modes(N, p_sym, space=space) == want, space
            assert symhx.mode(N, [p_sym], space=space).tolist() == [want[0]]


# --------------------------------------------------------------------------- critical point
@pytest.mark.parametrize("N", [2, 5, 30])
def test_critical_point_dps_and_float(N: int) -> None:
    want = critical_by_scan(N, 40)[1]
    cp = symhx.critical_point(N, dps=30)
    with mpmath.workdps(60):
        assert abs(cp.p - want) <= mpmath.mpf(10) ** -29 * want
        assert abs(cp.q - (N * want - 1)) <= mpmath.mpf(10) ** -25 * max(1, abs(N * want - 1))
    cf = symhx.critical_point(N, dps=None)
    assert type(cf.p) is float and type(cf.q) is float and type(cf.p_d) is float
    assert math.isclose(cf.p, float(want), rel_tol=1e-15)
    assert math.isclose(cf.q, float(N * want - 1), rel_tol=1e-13, abs_tol=1e-15)
    assert math.isclose(cf.p_d, float(cp.p_d), rel_tol=1e-15)
    assert cf.k_after == cp.k_after and cf.dps == 20
    # just above p_c the mode leaves 1: an independent check of k_after
    with mpmath.workdps(60):
        above = Fraction(mpmath.nstr(want * (1 + mpmath.mpf(10) ** -12), 40))
    assert symhx.mode(N, above) == cp.k_after


def test_critical_point_of_a_space() -> None:
    N = 12
    cp = symhx.critical_point(N, space="eq41", dps=25)
    cf = symhx.critical_point(N, space="eq41", dps=None)
    assert type(cf.p) is float and math.isclose(cf.p, float(cp.p), rel_tol=1e-15)
    assert cp.dps == 25 and cf.dps == 20
    with mpmath.workdps(40):
        pc = Fraction(mpmath.nstr(cp.p, 30))
        lo, hi = pc * (1 - Fraction(1, 10**8)), pc * (1 + Fraction(1, 10**8))
    assert exact_table(N, lo, "eq41").modes == (1,)
    assert exact_table(N, hi, "eq41").modes[0] > 1
    assert symhx.critical_point(N, dps=25).p != cp.p  # the space is not ignored


# --------------------------------------------------------------------------- deprecated alias
def test_variance_alias_warns_at_the_caller() -> None:
    """``symhx.variance`` warns once (stacklevel 2: at the line that called it, not inside
    symhx or pytest) with its documented message, and returns ``symhx.var``'s value: exact for
    an exact p, a float for ``dps=None``."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        v = symhx.variance(10, Fraction(1, 3))
        vf = symhx.variance(6, 0.5, dps=None)
    assert v == symhx.var(10, Fraction(1, 3))
    assert type(vf) is float
    assert math.isclose(vf, float(ExactTable.simple(6, Fraction(1, 2)).var), rel_tol=1e-12)
    dep = [w for w in caught if issubclass(w.category, DeprecationWarning)]
    assert len(dep) == 2
    if "MUTANT_UNDER_TEST" not in os.environ:  # mutmut's trampoline adds a frame
        assert {w.filename for w in dep} == {__file__}
    assert {str(w.message) for w in dep} == {
        "symhx.variance is deprecated: use symhx.var (scipy's name)"}
