"""The user-facing functions with per-site probabilities (issue 30): one class is today's scalar
``p`` bit for bit (every method, space and arithmetic path); several classes go through the class
distribution; ``critical_point(N, weights=...)``."""

from __future__ import annotations

import dataclasses
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np
import pytest

import symhx
from symhx.critical_sites import DirectionCriticalPoint, direction_critical_point
from symhx.site_distribution import SitesDistribution
from symhx.sites import SiteClasses
from tests.harness.errors import assert_refuses
from tests.reference.mp import rel_err
from tests.reference.sites import mode_weights


def same(a: Any, b: Any) -> bool:
    """Bit-for-bit equality: the same type and value (an mpf by its binary tuple)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, mpmath.mpf):
        return a._mpf_ == b._mpf_
    if isinstance(a, np.ndarray):
        return a.dtype == b.dtype and a.shape == b.shape and all(
            same(x, y) for x, y in zip(a.ravel().tolist() if a.dtype != object else a.ravel(),
                                       b.ravel().tolist() if b.dtype != object else b.ravel(),
                                       strict=True))
    if isinstance(a, (tuple, list)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and a != a:
        return b != b
    return bool(a == b)


N = 60
KS = [0, 1, 5, 30, 60]
CALLS = {
    "pmf": lambda q, sp, d: symhx.pmf(N, q, KS, space=sp, dps=d),
    "logpmf": lambda q, sp, d: symhx.logpmf(N, q, KS, space=sp, dps=d),
    "cdf": lambda q, sp, d: symhx.cdf(N, q, KS, space=sp, dps=d),
    "logcdf": lambda q, sp, d: symhx.logcdf(N, q, KS, space=sp, dps=d),
    "sf": lambda q, sp, d: symhx.sf(N, q, KS, space=sp, dps=d),
    "logsf": lambda q, sp, d: symhx.logsf(N, q, KS, space=sp, dps=d),
    "ppf": lambda q, sp, d: symhx.ppf(N, q, ["0.1", "1/2", 0.9], space=sp, dps=d),
    "isf": lambda q, sp, d: symhx.isf(N, q, ["0.1", 0.5], space=sp, dps=d),
    "mean": lambda q, sp, d: symhx.mean(N, q, space=sp, dps=d),
    "var": lambda q, sp, d: symhx.var(N, q, space=sp, dps=d),
    "std": lambda q, sp, d: symhx.std(N, q, space=sp, dps=d),
    "median": lambda q, sp, d: symhx.median(N, q, space=sp, dps=d),
    "entropy": lambda q, sp, d: symhx.entropy(N, q, space=sp, dps=d),
    "normaliser": lambda q, sp, d: symhx.normaliser(N, q, space=sp, dps=d),
    "interval": lambda q, sp, d: symhx.interval(N, q, "0.9", space=sp, dps=d),
    "modes": lambda q, sp, d: symhx.modes(N, q, space=sp),
    "mode": lambda q, sp, d: symhx.mode(N, q, space=sp),
    "rvs": lambda q, sp, d: symhx.rvs(N, q, 5, random_state=1, space=sp),
}


@pytest.mark.parametrize("space", ["simple", "eq41", "excess<=2;distinct"])
@pytest.mark.parametrize("p", ["0.02", Fraction(1, 60), 0.013, mpmath.mpf("0.011")],
                         ids=["str", "Fraction", "float", "mpf"])
@pytest.mark.parametrize("dps", [None, 30])
def test_one_class_gives_bit_identical_results(space, p, dps):
    forms = [SiteClasses((N,), (p,)), SiteClasses((7, N - 7), (p, p)),
             SiteClasses.from_sites([p] * N)]
    for name, call in CALLS.items():
        ref = call(p, space, dps)
        for form in forms:
            assert same(call(form, space, dps), ref), (name, form)
    d_ref = symhx.distribution_of(N, p, space=space, dps=dps)
    for form in (*forms, [p] * N, (p,) * N, np.array([p] * N, dtype=object)):
        d = symhx.distribution_of(N, form, space=space, dps=dps)
        assert type(d) is type(d_ref) and d.exact == d_ref.exact
        assert same(d.pmf(KS), d_ref.pmf(KS)) and same(d.mean(), d_ref.mean())


@pytest.mark.parametrize("N_", [2, 10**6])
def test_one_class_modes_at_any_N(N_):
    for p in ("1/2", 0.3, "1e-6"):
        assert symhx.modes(N_, SiteClasses((N_,), (p,))) == symhx.modes(N_, p)


def test_several_classes_go_through_the_class_distribution():
    sizes, probs = (2, 99), (Fraction(1, 100), Fraction(1, 50))
    sc = SiteClasses(sizes, ("0.01", "1/50"), names=("wall", "pipe"))
    d = symhx.distribution_of(101, sc)
    assert isinstance(d, SitesDistribution) and d.exact and d.space == "simple"
    W = mode_weights(sizes, probs)
    g = sum(W)
    assert list(symhx.pmf(101, sc, [1, 2, 50])) == [W[0] / g, W[1] / g, W[49] / g]
    assert symhx.mean(101, sc) == sum(k * w for k, w in enumerate(W, 1)) / g
    top = max(W)
    assert symhx.modes(101, sc) == tuple(k for k, w in enumerate(W, 1) if w == top)
    binary = SiteClasses(sizes, (0.01, 0.02))  # floats: the mpmath path at dps digits
    m = symhx.mean(101, binary, dps=30)
    exact = symhx.mean(101, SiteClasses(sizes, (Fraction(0.01), Fraction(0.02))))
    assert isinstance(m, mpmath.mpf) and rel_err(m, exact) < mpmath.mpf(10) ** -29
    f = symhx.mean(101, sc, dps=None)
    assert isinstance(f, float) and rel_err(f, symhx.mean(101, sc)) < 1e-14
    assert symhx.distribution_of(4, [1, 1, 2, 2]).modes() == (3, 4)


def test_arrays_of_site_classes_broadcast():
    a = SiteClasses((2, 99), ("0.01", "0.02"))
    b = SiteClasses((2, 99), ("0.02", "0.02"))  # one class: the scalar path
    out = symhx.mean(101, [a, b])
    assert out.dtype == object and out.shape == (2,)
    assert out[0] == symhx.mean(101, a) and out[1] == symhx.mean(101, "0.02")
    got = symhx.pmf(101, np.array([a, b], dtype=object)[:, None], [[1, 2]])
    assert got.shape == (2, 2) and got[1, 0] == symhx.pmf(101, "0.02", 1)
    assert symhx.modes(101, [a, b])[1] == symhx.modes(101, "0.02")


def test_higher_order_spaces_take_classes():
    sc = SiteClasses((3, 7), ("1/4", "1/9"))
    d = symhx.distribution_of(10, sc, space="eq41")
    assert isinstance(d, SitesDistribution) and d.space == "eq41"
    assert sum(d.pmf(k) for k in range(1, 11)) == 1
    assert symhx.modes(10, sc, space="eq41") == d.modes()


def test_critical_point_along_a_direction():
    w = SiteClasses((2, 99), ("1/2", 1))
    cp = symhx.critical_point(101, weights=w, dps=30)
    assert isinstance(cp, DirectionCriticalPoint)
    ref = direction_critical_point(101, w, dps=30)
    assert cp == ref
    assert symhx.critical_point(101, weights=[Fraction(1, 2)] * 2 + [1] * 99, dps=30).p == ref.p
    f = symhx.critical_point(101, weights=w, dps=None)
    assert isinstance(f.p, float) and f.p_d is None and f.k_after == ref.k_after
    one = symhx.critical_point(101, weights=[1] * 101, dps=30)
    base = symhx.critical_point(101, dps=30)
    assert all(getattr(one, fl.name) == getattr(base, fl.name)
               for fl in dataclasses.fields(base) if fl.compare)
    curve = symhx.critical_curve(101, (2, 99), directions=3, dps=15)
    assert curve.k_after == (19, 20, 20)  # argmin of c_k along (3, 1), (2, 2), (1, 3)
    for w in ((3, 1), (2, 2), (1, 3)):  # the argmin of c_k**(k-1) = e_1/((k-1)! e_k) exactly
        W = mode_weights((2, 99), (Fraction(w[0]), Fraction(w[1])))
        with mpmath.workdps(40):
            c = {k: mpmath.root(mpmath.mpf((W[0] / W[k - 1]).numerator)
                                / (W[0] / W[k - 1]).denominator, k - 1) for k in range(2, 60)}
        assert curve.at(w).k_after == min(c, key=c.__getitem__)


def test_refusals():
    sc = SiteClasses((2, 2), (1, 2))
    assert_refuses(symhx.distribution_of, 5, sc, arg="p", value="N = 4", allowed="add up to N")
    assert_refuses(symhx.distribution_of, 5, [0.1] * 4, arg="p", value="sequence of 4",
                   allowed="one probability per site")
    assert_refuses(symhx.mean, 5, sc, arg="p", value="N = 4", allowed="add up to N")
    assert_refuses(symhx.modes, 5, sc, arg="p", value="N = 4", allowed="add up to N")
    assert_refuses(symhx.critical_point, 4, weights=sc, space="eq41", arg="weights",
                   value="'eq41'", allowed="simple")
    assert_refuses(symhx.critical_point, 4, weights=[1, 2], arg="weights",
                   value="sequence of 2", allowed="one probability per site")


GRID_P = ["1e-6", "0.003", "1/7", "0.5", "3", 2.5e-3, 0.31, mpmath.mpf("0.0123")]


@pytest.mark.parametrize("N_", [2, 7, 101, 1000])
def test_one_class_is_the_scalar_on_a_grid(N_):
    ks = [1, 2, N_]
    for p in GRID_P:
        forms = [SiteClasses((N_,), (p,)), SiteClasses((1, N_ - 1), (p, p))]
        for dps in (None, 20):
            for name in ("pmf", "logpmf", "cdf", "logsf"):
                ref = getattr(symhx, name)(N_, p, ks, dps=dps)
                assert all(same(getattr(symhx, name)(N_, f, ks, dps=dps), ref) for f in forms)
            for name in ("mean", "var", "median"):
                ref = getattr(symhx, name)(N_, p, dps=dps)
                assert all(same(getattr(symhx, name)(N_, f, dps=dps), ref) for f in forms), name
        assert all(symhx.modes(N_, f) == symhx.modes(N_, p) for f in forms)


def test_work_limits_are_refused_before_any_work():
    """The documented caps of the class paths, the same through every public route."""
    import time

    from symhx.site_weights import (
        BALL_TABLE_N_LIMIT,
        EXACT_TABLE_BITS_LIMIT,
        SITE_PATTERN_LIMIT,
    )
    from symhx.sites import MAX_SITE_SEQUENCE

    big = BALL_TABLE_N_LIMIT * 10
    row = SiteClasses((2, big - 2), (0.5, 0.02))
    start = time.perf_counter()
    for fn in (symhx.distribution_of, symhx.mean, symhx.modes):
        assert_refuses(fn, big, row, arg="N", value=f"N={big}",
                       allowed=f"BALL_TABLE_N_LIMIT = {BALL_TABLE_N_LIMIT}")
    n = 20_000
    assert_refuses(symhx.distribution_of, n, SiteClasses((2, n - 2), ("0.5", "0.02")),
                   arg="N", value=f"N={n}", allowed="EXACT_TABLE_BITS_LIMIT")
    assert EXACT_TABLE_BITS_LIMIT < 5e9  # the table above would hold ~5e9 bits
    assert_refuses(symhx.pmf, 40, SiteClasses((10,) * 4, ("0.1", "0.2", "0.3", "0.4")), 3,
                   space="excess<=20", arg="space", value="'excess<=20'",
                   allowed=f"SITE_PATTERN_LIMIT = {SITE_PATTERN_LIMIT}")
    assert_refuses(symhx.critical_point, big, weights=SiteClasses((big // 2, big // 2), (1, 2)),
                   arg="N", value=f"N={big}", allowed="BALL_TABLE_N_LIMIT")
    huge = np.broadcast_to(0.5, (MAX_SITE_SEQUENCE + 1,))  # no memory: a view
    assert_refuses(symhx.distribution_of, MAX_SITE_SEQUENCE + 1, huge, arg="p",
                   value=f"{MAX_SITE_SEQUENCE + 1} entries",
                   allowed=f"MAX_SITE_SEQUENCE = {MAX_SITE_SEQUENCE}")
    assert time.perf_counter() - start < 5  # refused before the tables, not after
