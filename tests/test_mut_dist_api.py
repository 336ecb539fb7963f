"""The user-facing functions of :mod:`symhx.api` against independent references (issue 16):
dispatch on ``space``, broadcasting over ``p`` and ``k`` / ``q`` (shapes, dtypes, the per-``p``
cache), modes and the critical point.

References: the closed-form simple pmf (factorials, brute-force normaliser) and, for the
higher-order spaces, Burnside circuit counts times ``p**length`` summed per ``k``; the critical
point by an exhaustive scan of ``c_k`` from ``loggamma``.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import symhx
from symhx import api
from symhx.circuits import circuit_count
from symhx.spaces import parse_space, shape_excess
from tests.reference.distribution import pmf_table
from tests.test_frozen_harness import space_weights


def simple_table(N: int, p: Fraction) -> list[Fraction]:
    return pmf_table(N, Fraction(p))


def space_table(N: int, p: Fraction, space: str) -> list[Fraction]:
    w = space_weights(N, p, space)
    g = sum(w)
    return [x / g for x in w]


def ref_table(N: int, p: Fraction, space: str = "simple") -> list[Fraction]:
    return simple_table(N, p) if space == "simple" else space_table(N, p, space)


def cdf(t: list[Fraction], k: int) -> Fraction:
    return sum(t[: max(0, min(k, len(t)))], Fraction(0))


def ppf(t: list[Fraction], q: Fraction) -> int:
    return 0 if q == 0 else next(k for k in range(1, len(t) + 1) if cdf(t, k) >= q)


def moments(t: list[Fraction]) -> tuple[Fraction, Fraction]:
    mu = sum((k * x for k, x in enumerate(t, 1)), Fraction(0))
    return mu, sum(((k - mu) ** 2 * x for k, x in enumerate(t, 1)), Fraction(0))


def mp(x: Fraction) -> mpmath.mpf:
    return mpmath.mpf(x.numerator) / x.denominator


def modes_of(t: list[Fraction]) -> tuple[int, ...]:
    m = max(t)
    return tuple(k for k, x in enumerate(t, 1) if x == m)


SPACES = ["simple", "eq41", "excess<=1;distinct"]


#: under mutation testing the warnings point into mutmut's trampoline (its extra frames)
_UNDER_MUTMUT = "mutmut"


# --------------------------------------------------------------------------- dispatch
@pytest.mark.parametrize("space", SPACES)
def test_every_function_dispatches_on_space(space: str) -> None:
    N, p = 9, Fraction(1, 3)
    t = ref_table(N, p, space)
    mu, var = moments(t)
    assert symhx.pmf(N, p, 3, space=space) == t[2]
    assert symhx.cdf(N, p, 3, space=space) == cdf(t, 3)
    assert symhx.sf(N, p, 3, space=space) == 1 - cdf(t, 3)
    assert symhx.mean(N, p, space=space) == mu
    assert symhx.var(N, p, space=space) == var
    with pytest.warns(DeprecationWarning):
        assert symhx.variance(N, p, space=space, dps=20) == var
    with mpmath.workdps(60):
        assert abs(symhx.std(N, p, space=space, dps=40) - mpmath.sqrt(mp(var))) \
            < mpmath.mpf(10) ** -39 * mpmath.sqrt(mp(var))
        h = -mpmath.fsum(mp(x) * mpmath.log(mp(x)) for x in t)
        assert abs(symhx.entropy(N, p, space=space, dps=40) - h) < mpmath.mpf(10) ** -39
        for name, want in (("logpmf", t[2]), ("logcdf", cdf(t, 3)), ("logsf", 1 - cdf(t, 3))):
            got = getattr(symhx, name)(N, p, 3, space=space, dps=40)
            lw = mpmath.log(mp(want))
            assert abs(got - lw) < mpmath.mpf(10) ** -39 * abs(lw), name
    assert symhx.median(N, p, space=space) == ppf(t, Fraction(1, 2))
    assert symhx.ppf(N, p, "0.3", space=space) == ppf(t, Fraction(3, 10))
    assert symhx.isf(N, p, "0.3", space=space) == ppf(t, Fraction(7, 10)) + (
        1 if cdf(t, ppf(t, Fraction(7, 10))) == Fraction(7, 10) else 0)
    assert symhx.interval(N, p, "0.5", space=space) == (ppf(t, Fraction(1, 4)),
                                                        ppf(t, Fraction(3, 4)))
    assert symhx.modes(N, p, space=space) == modes_of(t)
    assert symhx.mode(N, p, space=space) == modes_of(t)[0]
    d = symhx.distribution_of(N, p, space=space, dps=25)
    assert d.space == parse_space(space).name and d.dps == 25 and d.exact
    assert d.pmf(3) == t[2]
    # a Space object works like its name; weighting= like the suffix
    assert symhx.distribution_of(N, p, space=parse_space(space)).pmf(3) == t[2]
    assert symhx.distribution_of(N, p, space=space.split(";")[0],
                                 weighting=parse_space(space).weighting).pmf(3) == t[2]
    x = symhx.rvs(N, float(p), size=2000, random_state=4, space=space)
    assert x.dtype == np.int64 and 1 <= x.min() and x.max() <= N
    assert abs(x.mean() - float(moments(ref_table(N, Fraction(float(p)), space))[0])) < 0.2
    assert np.array_equal(x, symhx.distribution_of(N, float(p), space=space, dps=None).rvs(
        2000, random_state=4))
    norm = symhx.normaliser(N, p, space=space)
    assert isinstance(norm, Fraction) and norm > 0


def test_normaliser_is_gamma() -> None:
    N, p = 7, Fraction(2, 5)
    gamma = sum(p**k * Fraction(math.factorial(N), k * math.factorial(N - k))
                for k in range(1, N + 1))
    assert symhx.normaliser(N, p) == gamma
    assert math.isclose(symhx.normaliser(N, float(p), dps=None), float(gamma), rel_tol=1e-12)
    got = symhx.normaliser(N, [p, Fraction(1, 2)])
    assert got.dtype == object and got[0] == gamma


def test_bad_space_and_arguments() -> None:
    for bad in (3, None, b"simple"):
        with pytest.raises(TypeError, match="space must be a str"):
            symhx.pmf(5, "0.5", 1, space=bad)
        with pytest.raises(TypeError, match="space"):
            symhx.modes(5, "0.5", space=bad)
    with pytest.raises(ValueError, match="N"):
        symhx.distribution_of(0, "0.5")
    with pytest.raises(ValueError, match="N"):
        symhx.mean(0, ["0.5"])
    with pytest.raises(ValueError, match="N"):
        symhx.pmf(0, ["0.5"], [1])
    with pytest.raises(ValueError, match="N"):
        symhx.modes(0, "0.5")
    with pytest.raises(ValueError, match="dps"):
        symhx.mean(5, ["0.5"], dps=0)
    with pytest.raises(ValueError, match="dps"):
        symhx.pmf(5, ["0.5"], [1], dps=-3)
    with pytest.raises(ValueError, match="space"):
        symhx.pmf(5, ["0.5"], [1], space="nonsense")
    with pytest.raises(ValueError, match="N"):
        symhx.critical_point(1)
    # N = 1 is a valid distribution (X = 1)
    assert symhx.pmf(1, "0.5", 1) == 1 and symhx.mode(1, "0.5") == 1


# --------------------------------------------------------------------------- broadcasting
def test_broadcast_p_and_k_shapes_and_values() -> None:
    N = 8
    ps = [Fraction(1, 10), Fraction(1, 2), Fraction(3)]
    ks = [0, 1, 4, 8, 9]
    grid = symhx.pmf(N, np.array(ps, dtype=object)[:, None], np.array(ks)[None, :])
    assert grid.shape == (3, 5) and grid.dtype == object
    for i, p in enumerate(ps):
        t = simple_table(N, p)
        for j, k in enumerate(ks):
            assert grid[i, j] == (t[k - 1] if 1 <= k <= N else 0), (p, k)
    f = symhx.cdf(N, [float(p) for p in ps], 4, dps=None)
    assert f.shape == (3,) and f.dtype == np.float64
    for i, p in enumerate(ps):
        assert math.isclose(f[i], float(cdf(simple_table(N, Fraction(float(p))), 4)),
                            rel_tol=1e-12)
    s = symhx.sf(N, ps, [[1], [2]])
    assert s.shape == (2, 3)
    for i in range(2):
        for j, p in enumerate(ps):
            assert s[i, j] == 1 - cdf(simple_table(N, p), i + 1)
    # scalar p with an array k: the distribution's own broadcasting
    a = symhx.logpmf(N, 0.5, np.arange(1, 4), dps=None)
    assert a.shape == (3,) and a.dtype == np.float64
    # integer results: int64 for float64, Python ints otherwise
    q = symhx.ppf(N, ps, "1/2", dps=None)
    assert q.dtype == np.int64
    assert q.tolist() == [ppf(simple_table(N, Fraction(float(p))), Fraction(1, 2)) for p in ps]
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
        fr = Fraction(p)
        mu, var = moments(simple_table(N, fr))
        exact = not isinstance(p, float)
        assert isinstance(m[i], Fraction) == exact and isinstance(pm[i], Fraction) == exact
        if exact:
            assert m[i] == mu and v[i] == var
            continue
        with mpmath.workdps(40):
            assert abs(m[i] - mp(mu)) <= mpmath.mpf(10) ** -19 * mp(mu)
            assert abs(v[i] - mp(var)) <= mpmath.mpf(10) ** -19 * mp(var)


def test_unhashable_p_entries() -> None:
    """p entries that cannot be hashed (here numpy 0-d arrays) are cached by identity."""
    ps = np.empty(2, dtype=object)
    ps[0], ps[1] = np.array(0.5), np.array(0.25)
    got = symhx.mean(5, ps, dps=None)
    want = [float(moments(simple_table(5, Fraction(x)))[0]) for x in (0.5, 0.25)]
    assert np.allclose(got, want, rtol=1e-12, atol=0)
    got2 = symhx.pmf(5, ps, 1, dps=None)
    assert np.allclose(got2, [float(simple_table(5, Fraction(x))[0]) for x in (0.5, 0.25)],
                       rtol=1e-12, atol=0)


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
        t = simple_table(N, Fraction(ps[idx]))
        mu, var = moments(t)
        assert math.isclose(means[idx], float(mu), rel_tol=1e-12)
        assert math.isclose(stds[idx], math.sqrt(float(var)), rel_tol=1e-10)
        h = -sum(float(x) * math.log(float(x)) for x in t if float(x) > 0)
        assert math.isclose(ents[idx], h, rel_tol=1e-11)
        assert meds[idx] == meds_mp[idx] == ppf(t, Fraction(1, 2))
    mpm = symhx.mean(N, ps, dps=30)
    assert mpm.dtype == object and isinstance(mpm[0, 0], mpmath.mpf)


def test_mode_and_modes_over_p() -> None:
    N = 101
    ps = np.array([["1/50", 0.02], ["0.01", "1/2"]], dtype=object)
    ms = symhx.modes(N, ps)
    assert ms.shape == (2, 2) and ms.dtype == object
    m = symhx.mode(N, ps)
    assert m.shape == (2, 2) and m.dtype == np.int64
    for idx in np.ndindex(2, 2):
        p = ps[idx]
        fr = Fraction(p)
        want = modes_of(simple_table(N, fr))
        assert ms[idx] == want and m[idx] == want[0], (p, want)
    assert ms[0, 0] == (50, 51) and m[0, 0] == 50  # the tie: the smallest maximiser
    assert symhx.mode(5, "1/2") == 1 and symhx.modes(5, "1/2") == (1, 2, 3)
    assert symhx.mode(101, "1/50", space="eq41") == modes_of(space_table(101, Fraction(1, 50),
                                                                         "eq41"))[0]
    got = symhx.modes(12, ["1/3", 0.25], space="eq41")
    assert got.tolist() == [modes_of(space_table(12, Fraction(1, 3), "eq41")),
                            modes_of(space_table(12, Fraction(0.25), "eq41"))]


# --------------------------------------------------------------------------- critical point
def _scan(N: int, dps: int) -> mpmath.mpf:
    """p_c = min_{k >= 2} c_k, c_k = (k (N-k)! / N!)**(1/(k-1)) (Phi(k) = Phi(1) at p = c_k)."""
    with mpmath.workdps(dps + 20):
        return min(mpmath.exp((mpmath.log(k) + mpmath.loggamma(N - k + 1)
                               - mpmath.loggamma(N)) / (k - 1)) for k in range(2, N + 1))


@pytest.mark.parametrize("N", [2, 5, 30])
def test_critical_point_dps_and_float(N: int) -> None:
    want = _scan(N, 40)
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
    assert modes_of(space_table(N, lo, "eq41")) == (1,)
    assert modes_of(space_table(N, hi, "eq41"))[0] > 1
    assert symhx.critical_point(N, dps=25).p != cp.p  # the space is not ignored


def test_api_names() -> None:
    assert set(api.__all__) >= {"pmf", "mode", "modes", "critical_point", "rvs", "interval"}


# --------------------------------------------------------------------------- survivors of mutation
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
    assert small.dtype == np.int64 and small.tolist() == [50, modes_of(simple_table(101,
                                                                                    p))[0]]


def test_irrational_p_modes_in_every_space() -> None:
    sympy = pytest.importorskip("sympy")
    p_sym = sympy.sqrt(2) / 10
    N = 12
    with mpmath.workdps(50):
        pm = mpmath.sqrt(2) / 10
        for space in ("simple", "eq41"):
            sp = parse_space(space)
            w = []
            for k in range(1, N + 1):
                total = mpmath.mpf(0)
                for shape in sp.shapes:
                    r = len(shape)
                    if k < max(r, 1):
                        continue
                    total += circuit_count(N, (*shape, *(1,) * (k - r))) * pm ** (
                        k + shape_excess(shape))
                w.append(total)
            best = max(w)
            want = tuple(k for k, x in enumerate(w, 1) if x == best)
            assert symhx.modes(N, p_sym, space=space) == want, space
            assert symhx.mode(N, [p_sym], space=space).tolist() == [want[0]]


def test_N_one_with_arrays_of_p() -> None:
    assert symhx.mean(1, ["1/2", 0.5]).tolist() == [1, 1]
    assert symhx.pmf(1, ["1/2", 0.5], [1, 2]).tolist() == [1, 0]
    assert symhx.pmf(1, ["1/2"], 1).tolist() == [1]


def test_bad_entries_in_arrays_are_clear_errors() -> None:
    with pytest.raises(TypeError, match=r"^k must be an integer"):
        symhx.pmf(5, ["0.5"], [True, 1])
    with pytest.raises(TypeError, match=r"^p must be a real"):
        symhx.modes(5, [0.5, True])
    with pytest.raises(TypeError, match=r"^p must be a real"):
        symhx.mean(5, [0.5, (0.1, 0.2)])
    with pytest.raises(TypeError, match=r"^p must be a real"):
        symhx.pmf(5, [0.5, (0.1, 0.2)], 1)


def test_one_distribution_per_distinct_p(monkeypatch: pytest.MonkeyPatch) -> None:
    """The per-p cache: an array with repeated p builds one distribution per distinct value
    (and type)."""
    built: list = []
    real = api._build

    def counting(N, p, sp, dps):  # type: ignore[no-untyped-def]
        built.append(p)
        return real(N, p, sp, dps)

    monkeypatch.setattr(api, "_build", counting)
    got = symhx.mean(20, [0.1, 0.1, "0.1", 0.1], dps=None)
    assert len(built) == 2 and got[0] == got[1] == got[3]
    built.clear()
    got = symhx.cdf(20, [[0.1], [0.1], [0.2]], [1, 2, 3], dps=None)
    assert got.shape == (3, 3) and len(built) == 2
    t = simple_table(20, Fraction(0.2))
    assert math.isclose(got[2, 1], float(cdf(t, 2)), rel_tol=1e-12)


def test_exact_quantiles_are_decided_exactly() -> None:
    """Where q equals a cdf value exactly, the exact path decides (the float64 path would not):
    N = 4, p = 2 has cdf(3) = 1/2; N = 2, p = 3 and N = 2, p = 1/2."""
    t = simple_table(4, Fraction(2))
    assert cdf(t, 3) == Fraction(1, 2)
    assert symhx.median(4, "2") == 3 == ppf(t, Fraction(1, 2))
    assert symhx.median(4, ["2"]).tolist() == [3]
    t2 = simple_table(2, Fraction(1, 2))
    assert symhx.ppf(2, "1/2", "4/5") == ppf(t2, Fraction(4, 5)) == 1
    assert symhx.ppf(2, ["1/2"], "4/5").tolist() == [1]
    t3 = simple_table(2, Fraction(3))
    assert symhx.interval(2, "3", "1/5") == (ppf(t3, Fraction(2, 5)), ppf(t3, Fraction(3, 5)))
    assert symhx.interval(2, "3", "1/5") == (1, 2)


def test_rvs_is_float64_whatever_p() -> None:
    """rvs never builds an exact distribution: N above the exact limit works with an exact p."""
    x = symhx.rvs(200_000, "1/100000", 50, random_state=3)
    assert x.dtype == np.int64 and x.min() >= 1 and x.max() <= 200_000


def test_variance_alias_warns_at_the_caller() -> None:
    with pytest.warns(DeprecationWarning,
                      match=r"^symhx\.variance is deprecated: use symhx\.var") as rec:
        v = symhx.variance(6, 0.5, dps=None)
    assert rec[0].filename == __file__ or _UNDER_MUTMUT in rec[0].filename
    assert type(v) is float
    assert math.isclose(v, float(moments(simple_table(6, Fraction(1, 2)))[1]), rel_tol=1e-12)


def test_interval_honours_dps() -> None:
    """On the mpmath path q is resolved to dps digits: an upper quantile 1e-25 (relative) above
    cdf(k) gives k at dps = 20 and k + 1 at dps = 40."""
    N, pf, k = 12, 0.3, 8
    t = simple_table(N, Fraction(pf))
    hi = cdf(t, k) * (1 + Fraction(1, 10**25))
    assert hi > Fraction(1, 2)
    c = 2 * hi - 1
    lo = ppf(t, (1 - c) / 2)
    assert symhx.interval(N, pf, c, dps=20) == (lo, k)
    assert symhx.interval(N, pf, c, dps=40) == (lo, k + 1)


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
