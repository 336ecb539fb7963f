"""The distribution of X over a higher-order sample space (``symhx.spaces._dist``): values on the
exact path, the mpmath path (direct and float-screened, its runs of significant terms and its
fixed-point weights), the float64 path and the float64 tables behind the screen.

References, none of them the package's class tables (:mod:`tests.reference.spaces`): explicit
closed walks up to rotation for small N, giving each circuit's class and k, hence the weight
polynomial of ``X = k``; Burnside's count of each visit pattern for larger N (itself checked
against the walks below); FKM enumeration circuit by circuit; exact ``Fraction`` arithmetic for
pmfs, moments and cdfs; mpmath comparisons at more than twice the claimed digits.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx
import symhx.spaces._dist as dist
from symhx.distribution import SimpleDistribution
from symhx.spaces import SpaceDistribution, distribution, modes, parse_space
from symhx.validation import mpf_to_fraction
from tests.harness.discrete import (
    Path,
    check_cdf_sf,
    check_frozen,
    check_log_tails_on_path,
    check_moments,
    check_pmf,
)
from tests.harness.errors import assert_refuses
from tests.reference.distribution import ExactTable, integer_weights, tail_logs, to_mp
from tests.reference.spaces import (
    log_U_exact,
    pmf_by_enumeration,
    space_weights,
    walk_polys,
    weight_poly,
    weight_polys,
    weights_at,
)

SPACES = ["eq41", "eq41-printed", "excess<=1", "excess<=2", "excess<=3"]


def _check_mp(d, W: list[Fraction], dps: int, ks) -> None:
    """pmf, cdf, sf and their logs at ``ks``, moments, entropy and normaliser of an mpmath-path
    distribution within ``10**(1 - dps)`` of the exact weights ``W``."""
    ref, path = ExactTable.of(W), Path.mp(dps)
    assert not d.exact and d.dps == dps
    check_pmf(d, ref, path, ks)
    check_cdf_sf(d, ref, path, ks)
    check_moments(d, ref, path)


def _close(got, ref: Fraction | mpmath.mpf, dps: int) -> bool:
    """|got - ref| <= 10**(1 - dps) |ref|, decided at 2 dps + 30 digits."""
    with mpmath.workdps(2 * dps + 30):
        r = to_mp(ref) if isinstance(ref, Fraction) else ref
        return abs(got - r) <= mpmath.mpf(10) ** (1 - dps) * abs(r)


# --------------------------------------------------------------------------- walks vs Burnside
@pytest.mark.parametrize("base", SPACES)
def test_burnside_polynomials_equal_the_walks(base):
    """The two references agree: Burnside's count of each visit pattern and explicit walks."""
    for N in (1, 2, 3, 4):
        for w in ("length", "distinct"):
            assert walk_polys(N, base, w) == weight_polys(N, base, w), (base, N, w)


# --------------------------------------------------------------------------- exact path
P_EXACT = [Fraction(1, 3), Fraction(1), Fraction(5, 2), Fraction(1, 1000), Fraction(999, 1000)]


@pytest.mark.parametrize("base", SPACES)
@pytest.mark.parametrize("weighting", ["length", "distinct"])
def test_exact_distribution_against_walks(base, weighting):
    for N in (1, 2, 3, 4):
        poly = walk_polys(N, base, weighting)
        for p in P_EXACT:
            W = weights_at(poly, p)
            d = distribution(N, p, space=base, weighting=weighting)
            assert isinstance(d, SpaceDistribution) and d.exact
            ref = ExactTable.of(W)
            check_frozen(d, ref, Path.exact(d.dps), ks=range(0, N + 2))
            for k in range(0, N + 2):
                assert d.weight_exact(k) == (W[k - 1] if 1 <= k <= N else 0)
            assert modes(N, p, space=base, weighting=weighting) == ref.modes


def test_exact_larger_n_against_burnside():
    """N = 9 and 23 (beyond the walks): pmf, moments, cdf and modes from Burnside counts."""
    for base, w, N, p in (("eq41", "length", 9, Fraction(2, 7)),
                          ("eq41-printed", "length", 23, Fraction(1, 19)),
                          ("excess<=3", "distinct", 23, Fraction(3, 40)),
                          ("excess<=2", "length", 23, Fraction(7, 5))):
        W = weights_at(weight_polys(N, base, w), p)
        g = sum(W)
        d = distribution(N, p, space=base, weighting=w)
        assert d.normaliser == g
        assert [v for _, v in d.table()] == [x / g for x in W]
        assert d.mean() == sum(k * x for k, x in enumerate(W, 1)) / g
        assert d.cdf(N // 2) == sum(W[:N // 2]) / g
        top = max(W)
        assert d.modes() == tuple(k for k, x in enumerate(W, 1) if x == top)


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=0", "excess<=2", "excess<=3"])
@pytest.mark.parametrize("weighting", ["length", "distinct"])
def test_pmf_against_enumeration(space, weighting):
    """pmf, mean, variance and modes against circuits listed one by one (FKM), N = 2..5."""
    for N in (2, 3, 4, 5):
        for p in (Fraction(1, 3), Fraction(3, 2)):
            d = distribution(N, p, space=space, weighting=weighting)
            ref = pmf_by_enumeration(N, p, space, weighting)
            got = {k: d.pmf(k) for k in range(1, d.N + 1)}
            assert got == ref, (space, N, p)
            assert sum(got.values()) == 1
            mu = sum(k * v for k, v in ref.items())
            assert d.mean() == mu
            assert d.var() == sum((k - mu) ** 2 * v for k, v in ref.items())
            top = max(ref.values())
            assert modes(N, p, space=space, weighting=weighting) == tuple(
                k for k in sorted(ref) if ref[k] == top)


def test_pmf_sums_to_one_exactly_n100():
    for space in ("eq41", "eq41-printed", "excess<=5", "excess<=2;distinct"):
        d = distribution(100, Fraction(1, 70), space=space)
        assert sum(v for _, v in d.table()) == 1


def test_small_p_puts_all_mass_on_one():
    for space in ("eq41", "eq41-printed", "excess<=6", "excess<=3;distinct"):
        prev = Fraction(0)
        for j in (3, 6, 12, 24):
            v = distribution(50, Fraction(1, 10**j), space=space).pmf(1)
            assert prev < v < 1
            prev = v
        assert 1 - prev < Fraction(1, 10**20)
        assert modes(50, Fraction(1, 10**6), space=space) == (1,)


def test_simple_space_distribution_keeps_dps():
    """``distribution(..., space="simple", dps=30)`` is the mpmath SimpleDistribution at 30 digits
    (a float p is taken at its exact binary value): checked against exact Fractions."""
    N, p = 12, 0.3
    d = distribution(N, p, space="simple", dps=30)
    assert isinstance(d, SimpleDistribution) and d.dps == 30
    t = ExactTable.simple(N, Fraction(p))
    for k in (1, 5, 12):
        got = d.pmf(k)
        assert isinstance(got, mpmath.mpf)
        with mpmath.workdps(60):
            assert abs(got / to_mp(t.pmf[k - 1]) - 1) < mpmath.mpf(10) ** -29, k


def test_space_distribution_refuses_an_unparsed_space():
    assert_refuses(dist.SpaceDistribution, 5, Fraction(1, 3), "eq41", exc=TypeError,
                   arg="space", value="got str 'eq41'",
                   allowed=["a parsed symhx.spaces.Space", "(use parse_space)"])


# --------------------------------------------------------------------------- mpmath path
@pytest.mark.parametrize("base,w", [("eq41", "length"), ("eq41-printed", "length"),
                                    ("excess<=3", "length"), ("excess<=2", "distinct"),
                                    ("eq41-printed", "distinct")])
def test_mpmath_path_against_exact_binary_value(base, w):
    N = 40
    poly = weight_polys(N, base, w)
    for p, dps in ((0.03, 20), (0.7, 45), (1.5, 30)):
        W = weights_at(poly, Fraction(p))
        d = distribution(N, p, space=base, weighting=w, dps=dps)
        _check_mp(d, W, dps, range(1, N + 1))
        table = d.table()
        g = sum(W)
        assert [k for k, _ in table] == list(range(1, N + 1))
        assert all(_close(v, W[k - 1] / g, dps) for k, v in table)
    with mpmath.workdps(60):
        pm = mpmath.mpf(1) / 37
    d = distribution(N, pm, space=base, weighting=w, dps=50)
    _check_mp(d, weights_at(poly, mpf_to_fraction(pm)), 50, (1, 2, 3, 20, 40))


def test_mpmath_matches_exact_and_higher_precision():
    """N = 100, p = 3/200 as a float at 30 digits and as an 80-digit mpf at 60 digits, against
    the exact distribution of each one's binary value."""
    for space in ("eq41", "excess<=6", "eq41-printed;distinct"):
        p = Fraction(3, 200)
        lo = distribution(100, float(p), space=space, dps=30)  # 3/200 is not a float: close
        with mpmath.workdps(80):
            p_hi = mpmath.mpf(3) / 200
        hi = distribution(100, p_hi, space=space, dps=60)
        ex = distribution(100, mpf_to_fraction(p_hi), space=space)  # its exact binary value
        ex_f = distribution(100, Fraction(float(p)), space=space)
        for k in (1, 2, 17, 40, 100):
            with mpmath.workdps(40):
                assert abs(lo.pmf(k) - to_mp(ex_f.pmf(k))) <= mpmath.mpf(10) ** -28 * abs(
                    lo.pmf(k))
        with mpmath.workdps(80):
            exact_mean = to_mp(ex.mean())
            assert abs(hi.mean() - exact_mean) < mpmath.mpf(10) ** -57 * exact_mean
            exact_var = to_mp(ex.var())
            assert abs(hi.var() - exact_var) < mpmath.mpf(10) ** -55 * exact_var
        with mpmath.workdps(30):
            assert mpmath.almosteq(lo.logpmf(3), mpmath.log(lo.pmf(3)), 1e-25)


@pytest.mark.parametrize("dps", [None, 0, 15, 40])  # 0: the exact path
def test_log_tails_near_probability_one(dps):
    """N = 200, p = 1/40 in eq. (41): ``logcdf`` / ``logsf`` to ``dps`` significant digits
    (float64: 100x the documented relative error) also near probability 1."""
    N, p = 200, Fraction(1, 40)
    ks = sorted({1, 2, 3, N // 2, N - 3, N - 2, N - 1})
    logs = tail_logs(integer_weights(space_weights(N, p, "eq41")), ks)
    check_log_tails_on_path(lambda q, dps: symhx.distribution_of(N, q, space="eq41", dps=dps),
                            p, dps, logs)


def test_large_n_runs():
    d = distribution(10**4, 0.001, space="excess<=3", dps=20)
    assert 1 <= d.mean() <= 10**4
    m = modes(10**4, 0.001, space="excess<=3")
    lw = [d.logpmf(k) for k in range(m[0] - 2, m[0] + 3)]
    assert max(lw) == lw[2]
    e = distribution(3000, Fraction(1, 300), space="eq41")
    assert abs(float(e.mean()) - float(distribution(3000, 1 / 300, space="eq41", dps=20).mean())
               ) < 1e-3


def test_sympy_irrational_p():
    sympy = pytest.importorskip("sympy")
    p = sympy.sqrt(2) / 40
    N, base = 30, "eq41"
    with mpmath.workdps(200):
        pr = mpf_to_fraction(mpmath.sqrt(2) / 40)
    W = weights_at(weight_polys(N, base), pr)
    d = distribution(N, p, space=base, dps=30)
    _check_mp(d, W, 30, (1, 2, 10, 30))
    want = tuple(k for k, x in enumerate(W, 1) if x == max(W))
    assert modes(N, p, space=base) == want
    with pytest.raises(ValueError, match="irrational"):  # never read at a fixed precision
        dist._rational(p, None)
    with pytest.raises(ValueError, match="irrational"):
        d.weight_exact(3)
    assert d.modes() == want and d.mode() == want[0]
    g = sum(W)
    f64 = distribution(N, p, space=base, dps=None)
    assert all(abs(f64.pmf(k) - float(W[k - 1] / g)) <= 1e-10 * float(W[k - 1] / g)
               for k in (1, 5, 30))
    cd = symhx.spaces.class_decomposition(N, p, space=base, dps=30)
    with mpmath.workdps(60):
        assert _close(mpmath.fsum(cd.joint[s][4] for s in cd.shapes), W[4] / g, 30)


def test_terms_accurate_to_the_working_precision():
    """The fixed-point Q* of the recurrence: every W(k) to ~wdps digits (large U_e(k) at
    large k, where too few fractional bits would show)."""
    for base, w in (("excess<=4", "length"), ("eq41", "distinct")):
        N, p = 400, 0.3
        d = distribution(N, p, space=base, weighting=w, dps=20)
        terms = d._terms
        for k in (1, 2, 3, 5, 150, 399, 400):
            ref = weights_at({k: weight_poly(N, base, k, w)}, Fraction(p))[0]
            assert _close(terms[k], ref, d._wdps - 3), (base, k)


# --------------------------------------------------------------------------- screened path
@pytest.fixture
def screened(monkeypatch):
    """Force the N > DIRECT_LIMIT (float-screened) mpmath path at small N."""
    monkeypatch.setattr(dist, "DIRECT_LIMIT", 10)


@pytest.mark.parametrize("base,w", [("eq41", "length"), ("excess<=3", "length"),
                                    ("eq41-printed", "distinct"), ("excess<=1", "distinct")])
def test_screened_path_against_exact(screened, base, w):
    N = 80
    poly = weight_polys(N, base, w)
    for p, dps in ((1 / 800, 15), (0.4, 25), (0.004, 20)):
        fr = Fraction(p)
        W = weights_at(poly, fr)
        g = sum(W)
        d = distribution(N, p, space=base, weighting=w, dps=dps)
        # the screen keeps exactly the k within the documented cut of the largest weight
        with mpmath.workdps(40):
            lw = [mpmath.log(to_mp(x)) for x in W]
            cut = max(lw) - d._wdps * mpmath.log(10) - 20
        kept = [k for k in range(1, N + 1) if lw[k - 1] >= cut + 1e-6]
        dropped = [k for k in range(1, N + 1) if lw[k - 1] < cut - 1e-6]
        runs = d._runs()
        inside = {k for lo, hi in runs for k in range(lo, hi + 1)}
        assert set(kept) <= inside and not (set(dropped) & inside), (p, runs)
        assert all(lo <= hi for lo, hi in runs)
        assert dropped, "the test needs weights below the screen"
        _check_mp(d, W, dps, (kept[0], kept[-1], dropped[0], dropped[-1],
                              (kept[0] + kept[-1]) // 2))
        table = dict(d.table())
        for k in range(1, N + 1):
            if k in inside:
                assert _close(table[k], W[k - 1] / g, dps)
            else:
                assert table[k] == 0


def test_runs_split_at_gaps(monkeypatch):
    """A screen with two separate bands gives two runs, and W(k) restarts correctly after the
    gap (values against exact weights)."""
    N, base = 60, "eq41"
    monkeypatch.setattr(dist, "DIRECT_LIMIT", 10)
    fake = np.full(N, -1e6)
    fake[0:5] = 0.0       # k = 1..5
    fake[19:23] = 0.0     # k = 20..23
    fake[40] = -5.0       # k = 41
    monkeypatch.setattr(dist, "log_W_float", lambda sp, n, lp: fake.copy())
    d = distribution(N, 0.05, space=base, dps=20)
    assert d._runs() == [(1, 5), (20, 23), (41, 41)]
    W = weights_at(weight_polys(N, base), Fraction(0.05))
    terms = d._terms
    assert sorted(terms) == [1, 2, 3, 4, 5, 20, 21, 22, 23, 41]
    for k, v in terms.items():
        assert _close(v, W[k - 1], d._wdps - 2), k


def test_run_starting_at_two(monkeypatch):
    """A run that starts at k = 2 gets Phi(2) from its closed form, not N p."""
    N, base = 40, "excess<=2"
    monkeypatch.setattr(dist, "DIRECT_LIMIT", 10)
    fake = np.full(N, -1e6)
    fake[1:6] = 0.0       # k = 2..6
    monkeypatch.setattr(dist, "log_W_float", lambda sp, n, lp: fake.copy())
    d = distribution(N, 0.125, space=base, dps=20)
    assert d._runs() == [(2, 6)]
    W = weights_at(weight_polys(N, base), Fraction(0.125))
    assert sorted(d._terms) == [2, 3, 4, 5, 6]
    for k, v in d._terms.items():
        assert _close(v, W[k - 1], d._wdps - 2), k


def test_direct_path_lists_every_k(monkeypatch):
    """N <= DIRECT_LIMIT: every W(k) by the recurrence (no k left out, even at 10**-200)."""
    N, p, base = 80, 1 / 800, "eq41"
    W = weights_at(weight_polys(N, base), Fraction(p))
    g = sum(W)
    for limit, complete in ((N, True), (N - 1, False)):
        monkeypatch.setattr(dist, "DIRECT_LIMIT", limit)
        d = distribution(N, p, space=base, dps=15)
        assert (d._runs() == [(1, N)]) == complete
        assert (sorted(d._terms) == list(range(1, N + 1))) == complete
        table = d.table()
        assert all(v > 0 for _, v in table) == complete
        assert _close(table[-1][1], W[-1] / g, 15) == complete
        # cdf and sf by the k listed in [lo, hi]; in the far tail as accurate either way
        assert _close(d.sf(N - 3), sum(W[N - 3:]) / g, 15)


def test_screened_sympy_irrational(screened):
    """The fallback W(k) of a k below the screen (not among the stored terms), for a sympy
    irrational p: pmf and logpmf evaluate W(k) from p itself (there is no exact rational).
    Against exact Fractions at a 200-digit rational stand-in for p."""
    sympy = pytest.importorskip("sympy")
    N, base, dps = 60, "eq41", 20
    d = distribution(N, sympy.sqrt(2) / 400, space=base, dps=dps)
    assert N not in d._terms
    with mpmath.workdps(200):
        pr = mpf_to_fraction(mpmath.sqrt(2) / 400)
    W = weights_at(weight_polys(N, base), pr)
    assert _close(d.pmf(N), W[-1] / sum(W), dps)
    with mpmath.workdps(60):
        ref = mpmath.log(to_mp(W[-1])) - mpmath.log(to_mp(sum(W)))
        assert abs(d.logpmf(N) - ref) <= mpmath.mpf(10) ** (1 - dps) * abs(ref)


# --------------------------------------------------------------------------- float64 path
def test_float64_path_against_exact():
    for base, w in (("eq41", "length"), ("excess<=2", "distinct")):
        N, p = 40, 0.05
        W = weights_at(weight_polys(N, base, w), Fraction(p))
        g = sum(W)
        d = distribution(N, p, space=base, weighting=w, dps=None)
        for k in range(1, N + 1):
            ref = float(W[k - 1] / g)
            assert abs(d.pmf(k) - ref) <= 1e-10 * ref
        assert abs(d.normaliser - float(g)) <= 1e-10 * float(g)
        assert abs(d.log_normaliser - math.log(g)) <= 1e-12 * max(1.0, abs(math.log(g)))
        assert [k for k, _ in d.table()] == list(range(1, N + 1))
        assert all(abs(v - float(W[k - 1] / g)) <= 1e-10 * float(W[k - 1] / g)
                   for k, v in d.table())


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=0", "excess<=4",
                                   "excess<=3;distinct"])
def test_log_U_table_against_exact_logs(space, monkeypatch):
    monkeypatch.setattr(dist, "_LOGU", {})
    sp = parse_space(space)
    for K in (3, 40, 7, 200):  # grows the cache (doubling), then reads a prefix of it
        tab = dist.log_U_table(sp, K)
        assert tab.shape == (sp.max_excess + 1, K)
        ref = log_U_exact(sp, K)
        for k in range(1, K + 1):
            for e in range(sp.max_excess + 1):
                want = ref[e, k - 1]
                if want == -np.inf:
                    assert tab[e, k - 1] == -np.inf
                else:
                    assert abs(tab[e, k - 1] - want) <= 1e-13 * max(1, want)


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=3", "eq41;distinct"])
def test_log_W_float_against_exact(space):
    sp = parse_space(space)
    for N, p in ((30, Fraction(1, 7)), (30, Fraction(5, 2)), (2000, Fraction(1, 1500))):
        lw = dist.log_W_float(sp, N, dist._logp_float(p))
        assert lw.shape == (N,)
        with mpmath.workdps(40):
            for k in sorted({1, 2, 3, 4, 5, N // 3, N - 1, N}):
                ref = mpmath.log(to_mp(weights_at({k: weight_poly(N, space, k)}, p)[0]))
                assert abs(lw[k - 1] - ref) < 1e-8 * max(1, abs(ref)), (N, k)


def test_logp_float_of_huge_fractions():
    fr = Fraction(3**700, 2**1200)  # beyond the float range in both parts
    with mpmath.workdps(30):
        ref = 700 * mpmath.log(3) - 1200 * mpmath.log(2)
    assert abs(dist._logp_float(fr) - ref) < 1e-12 * abs(ref)
