"""One scipy-style harness (in the spirit of scipy.special's ``_mptestutils``) for every method
of the frozen distributions of :func:`symhx.distribution_of`.

The reference is independent of the package's distribution code: the weight of ``X = k`` is
summed from Burnside circuit counts (:func:`symhx.circuits.circuit_count`, itself checked against
brute-force enumeration in ``test_circuits.py``) times ``p**length``, exactly in ``Fraction``;
every derived quantity (cdf, sf, moments, quantiles, entropy) is computed from that table by its
definition.  Each case is checked on three paths:

* exact ``p`` (a ``Fraction``): results must be *equal* to the reference;
* float ``p`` at ``dps`` digits: relative error below ``10**(1 - dps)``, compared at ``2 dps``
  (the reference is exact, converted at ``2 dps``);
* ``dps=None`` (float64): relative error below ``1e-11`` (logs: absolute ``1e-11 max(1, |x|)``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from typing import Any

import mpmath
import numpy as np
import pytest

import symhx
from symhx.circuits import circuit_count
from symhx.spaces import parse_space, shape_excess


# --------------------------------------------------------------------------- the reference
def space_weights(N: int, p: Fraction, space: str) -> list[Fraction]:
    """Unnormalised exact weights of X = 1..N in ``space``: Burnside circuit counts of every
    visit pattern of the space, times p to the power of its length (or of k)."""
    sp = parse_space(space)
    w = []
    for k in range(1, N + 1):
        total = Fraction(0)
        for shape in sp.shapes:
            r = len(shape)
            if k < max(r, 1):
                continue
            visits = (*shape, *(1,) * (k - r))
            e = shape_excess(shape)
            wt = p ** (k + e) if sp.weighting == "length" else p**k
            total += circuit_count(N, visits) * wt
        w.append(total)
    return w


@dataclass(frozen=True)
class Case:
    N: int
    p: Fraction  # the exact value; float cases use float(p) and its exact binary value
    space: str

    @cached_property
    def weights(self) -> list[Fraction]:
        return space_weights(self.N, self.p, self.space)

    @cached_property
    def pmf(self) -> list[Fraction]:
        g = sum(self.weights)
        return [x / g for x in self.weights]

    def cdf(self, k: int) -> Fraction:
        return sum(self.pmf[: max(0, min(k, self.N))], Fraction(0))

    def sf(self, k: int) -> Fraction:
        return sum(self.pmf[max(0, min(k, self.N)):], Fraction(0))

    @cached_property
    def mean(self) -> Fraction:
        return sum((k * x for k, x in enumerate(self.pmf, 1)), Fraction(0))

    @cached_property
    def var(self) -> Fraction:
        mu = self.mean
        return sum(((k - mu) ** 2 * x for k, x in enumerate(self.pmf, 1)), Fraction(0))

    def ppf(self, q: Fraction) -> int:
        if q == 0:
            return 0
        return next(k for k in range(1, self.N + 1) if self.cdf(k) >= q)

    def isf(self, q: Fraction) -> int:
        if q == 1:
            return 0
        return next(k for k in range(1, self.N + 1) if self.sf(k) <= q)

    @cached_property
    def modes(self) -> tuple[int, ...]:
        m = max(self.pmf)
        return tuple(k for k, x in enumerate(self.pmf, 1) if x == m)

    def entropy(self, dps: int) -> mpmath.mpf:
        with mpmath.workdps(dps):
            return -mpmath.fsum(_mp(x) * mpmath.log(_mp(x)) for x in self.pmf if x)

    def with_p(self, p: Fraction) -> Case:
        return Case(self.N, p, self.space)


def _mp(x: Fraction) -> mpmath.mpf:
    return mpmath.mpf(x.numerator) / x.denominator


def _log(x: Fraction) -> mpmath.mpf:
    return mpmath.ninf if x == 0 else mpmath.log(x.numerator) - mpmath.log(x.denominator)


# log grids of N and p, every kind of space
NS = (1, 2, 3, 7, 20, 60)
PS = (Fraction(1, 10**6), Fraction(1, 1000), Fraction(1, 50), Fraction(1, 10), Fraction(1, 2),
      Fraction(1), Fraction(3))
SPACES = ("simple", "eq41", "excess<=2", "eq41;distinct", "excess<=1;distinct")
CASES = [Case(N, p, s) for s in SPACES for N in NS for p in PS
         if not (s != "simple" and N == 60 and p in (Fraction(1), Fraction(3)))]
QS = (Fraction(0), Fraction(1, 1000), Fraction(1, 10), Fraction(1, 2), Fraction(9, 10),
      Fraction(999, 1000), Fraction(1))


def _ks(N: int) -> list[int]:
    return sorted({-1, 0, 1, 2, N // 2, N - 1, N, N + 1, N + 7})


def _id(c: Case) -> str:
    return f"{c.space}-N{c.N}-p{c.p}"


# --------------------------------------------------------------------------- comparisons
class Checker:
    """Compares one path (exact / mpmath / float64) with the reference, method by method."""

    def __init__(self, path: str, dps: int | None) -> None:
        self.path, self.dps = path, dps

    def value(self, got: Any, want: Fraction, what: str) -> None:
        if self.path == "exact":
            assert isinstance(got, Fraction) and got == want, (what, got, want)
        elif self.path == "mp":
            assert isinstance(got, mpmath.mpf), (what, type(got))
            with mpmath.workdps(2 * self.dps):
                w = _mp(want)
                assert abs(got - w) <= mpmath.mpf(10) ** (1 - self.dps) * abs(w), (what, got, w)
        else:
            w = float(want)  # may underflow to 0.0 in the deep tails: then so must got
            assert isinstance(got, float), (what, type(got))
            assert math.isclose(got, w, rel_tol=1e-11, abs_tol=1e-300), (what, got, w)

    def log(self, got: Any, want: Fraction, what: str) -> None:
        dps = self.dps or 15
        with mpmath.workdps(2 * dps):
            w = _log(want)
            if w == mpmath.ninf:
                assert got == -math.inf or got == mpmath.ninf, (what, got)
                return
            tol = (mpmath.mpf(10) ** (1 - dps) if self.path != "float" else mpmath.mpf(1e-11))
            assert abs(got - w) <= tol * max(1, abs(w)), (what, got, w)

    def real(self, got: Any, want: mpmath.mpf, what: str, absolute: bool = False) -> None:
        dps = self.dps or 15
        with mpmath.workdps(2 * dps):
            tol = mpmath.mpf(10) ** (1 - dps) if self.path != "float" else mpmath.mpf(1e-11)
            scale = 1 if absolute else abs(want)
            assert abs(mpmath.mpf(got) - want) <= tol * max(scale, mpmath.mpf(10) ** -300), (
                what, got, want)


PATHS = [("exact", 30), ("mp", 25), ("mp", 60), ("float", None)]


def _frozen(case: Case, path: str, dps: int | None) -> tuple[Any, Case]:
    if path == "exact":
        return symhx.distribution_of(case.N, case.p, space=case.space, dps=dps), case
    # floats are taken at their exact binary value: the reference uses that value
    pf = float(case.p)
    return (symhx.distribution_of(case.N, pf, space=case.space, dps=dps),
            case.with_p(Fraction(pf)))


@pytest.mark.parametrize(("path", "dps"), PATHS, ids=[f"{a}{b}" for a, b in PATHS])
@pytest.mark.parametrize("case", CASES, ids=_id)
def test_every_method_against_reference(case: Case, path: str, dps: int | None) -> None:
    d, ref = _frozen(case, path, dps)
    chk = Checker(path, dps)
    N = case.N
    assert d.support() == (1, N)
    for k in _ks(N):
        want = ref.pmf[k - 1] if 1 <= k <= N else Fraction(0)
        chk.value(d.pmf(k), want, f"pmf({k})")
        chk.log(d.logpmf(k), want, f"logpmf({k})")
        chk.value(d.cdf(k), ref.cdf(k), f"cdf({k})")
        chk.value(d.sf(k), ref.sf(k), f"sf({k})")
        chk.log(d.logcdf(k), ref.cdf(k), f"logcdf({k})")
        chk.log(d.logsf(k), ref.sf(k), f"logsf({k})")
        if path == "exact":
            assert d.cdf(k) + d.sf(k) == 1
    chk.value(d.mean(), ref.mean, "mean")
    chk.value(d.var(), ref.var, "var")
    with mpmath.workdps(2 * (dps or 15)):
        chk.real(d.std(), mpmath.sqrt(_mp(ref.var)), "std")
        chk.real(d.entropy(), ref.entropy(2 * (dps or 15)), "entropy", absolute=True)
    assert d.modes() == ref.modes
    assert d.mode() == ref.modes[0]  # the smallest maximiser, also on exact ties
    if path != "float" or N <= 20:  # float64 quantiles can differ where cdf(k) ~ q to 1e-16
        for q in QS:
            if path == "float" and any(abs(float(ref.cdf(j)) - float(q)) < 1e-9
                                       for j in range(1, N + 1)):
                continue
            if path == "float" and any(abs(float(ref.sf(j)) - float(q)) < 1e-9
                                       for j in range(1, N + 1)):
                continue
            assert d.ppf(q) == ref.ppf(q), ("ppf", q)
            assert d.isf(q) == ref.isf(q), ("isf", q)
    if path != "float":
        assert d.median() == ref.ppf(Fraction(1, 2))
        assert d.interval("0.9") == (ref.ppf(Fraction(1, 20)), ref.ppf(Fraction(19, 20)))


@pytest.mark.parametrize(("path", "dps"), [("exact", 30), ("mp", 30)])
@pytest.mark.parametrize("case", [c for c in CASES if c.N in (7, 60)], ids=_id)
def test_ppf_inverts_cdf(case: Case, path: str, dps: int) -> None:
    d, ref = _frozen(case, path, dps)
    for k in range(1, case.N + 1):
        c = d.cdf(k)
        if path == "mp":
            # at dps digits cdf(k - 1) and cdf(k) coincide when P(X = k) < 10**-dps cdf(k):
            # then ppf returns the smaller k, as scipy does
            if ref.pmf[k - 1] < Fraction(1, 10 ** (dps - 3)) * ref.cdf(k):
                continue
            if ref.sf(k) < Fraction(1, 10 ** (dps - 3)):  # cdf(k) rounds to 1: ppf(1) = N
                continue
        assert d.ppf(c) == k, k
    for k in range(1, case.N + 1):
        # isf(sf(k)) == k unless sf(k - 1) = P(X = k) + sf(k) rounds to sf(k) at dps digits
        if path == "mp" and ref.pmf[k - 1] < Fraction(1, 10 ** (dps - 3)) * ref.sf(k - 1):
            continue
        assert d.isf(d.sf(k)) == k, k


def test_exact_cdf_plus_sf_is_one_exactly_on_random_rationals() -> None:
    rng = np.random.default_rng(5)
    for _ in range(30):
        N = int(rng.integers(1, 200))
        p = Fraction(int(rng.integers(1, 10**6)), int(rng.integers(1, 10**7)))
        d = symhx.distribution_of(N, p, space=str(rng.choice(["simple", "eq41"])))
        k = int(rng.integers(0, N + 2))
        assert d.cdf(k) + d.sf(k) == 1


# --------------------------------------------------------------------------- larger N
@pytest.mark.parametrize("space", ["simple", "eq41"])
@pytest.mark.parametrize(("N", "p"), [(10**3, 1e-3), (3 * 10**4, 4e-5), (3 * 10**4, 1e-3)])
def test_large_N_paths_agree(space: str, N: int, p: float) -> None:
    """No Fraction reference at this N: the mpmath path at dps must agree with itself at 2 dps
    to dps digits (tails included), and the float64 path with both to ~1e-9 (gammaln)."""
    lo = symhx.distribution_of(N, p, space=space, dps=20)
    hi = symhx.distribution_of(N, p, space=space, dps=40)
    fl = symhx.distribution_of(N, p, space=space, dps=None)
    m = lo.mode()
    ks = [1, 2, m // 2 + 1, m, m + 5, min(N - 1, 3 * m + 50), N - 1]
    with mpmath.workdps(50):
        for name in ("cdf", "sf", "pmf"):
            for k in ks:
                a, b = getattr(lo, name)(k), getattr(hi, name)(k)
                assert abs(a - b) <= mpmath.mpf(10) ** -19 * abs(b), (name, k, a, b)
                la, lb = getattr(lo, "log" + name)(k), getattr(hi, "log" + name)(k)
                assert abs(la - lb) <= mpmath.mpf(10) ** -19 * max(1, abs(lb)), (name, k)
                lf = getattr(fl, "log" + name)(k)
                assert abs(lf - float(lb)) <= 1e-9 * max(1.0, abs(float(lb))), (name, k)
        for name in ("mean", "var", "entropy"):
            a, b = getattr(lo, name)(), getattr(hi, name)()
            assert abs(a - b) <= mpmath.mpf(10) ** -19 * abs(b), name
            assert abs(getattr(fl, name)() - float(b)) <= 1e-9 * abs(float(b)), name
    assert lo.median() == hi.median() == fl.median()


# --------------------------------------------------------------------------- rvs
def test_rvs_reproducible_and_chi_square() -> None:
    from scipy.stats import chisquare

    case = Case(30, Fraction(1, 20), "eq41")
    d = symhx.distribution_of(case.N, float(case.p), space=case.space, dps=20)
    a = d.rvs(40_000, random_state=123)
    assert np.array_equal(a, d.rvs(40_000, random_state=123))
    assert np.array_equal(a, d.rvs(40_000, random_state=np.random.default_rng(123)))
    assert not np.array_equal(a, d.rvs(40_000, random_state=124))
    assert a.dtype == np.int64 and a.min() >= 1 and a.max() <= case.N
    assert isinstance(d.rvs(random_state=1), int) and d.rvs((2, 3), random_state=1).shape == (2, 3)
    ref = case.with_p(Fraction(float(case.p)))
    expected = np.array([float(x) for x in ref.pmf]) * a.size
    observed = np.bincount(a, minlength=case.N + 1)[1:]
    keep = expected >= 5  # pool the thin tail into one bin
    obs = np.append(observed[keep], observed[~keep].sum())
    exp = np.append(expected[keep], expected[~keep].sum())
    if exp[-1] == 0:
        obs, exp = obs[:-1], exp[:-1]
    exp = exp * obs.sum() / exp.sum()
    assert chisquare(obs, exp).pvalue > 1e-4


def test_rvs_detects_a_wrong_distribution() -> None:
    """The chi-square check above has power: draws from N = 30, p = 0.05 fail against
    p = 0.055 (so a sampler off by a shifted cdf would be caught)."""
    from scipy.stats import chisquare

    d = symhx.distribution_of(30, 0.05, dps=None)
    a = d.rvs(40_000, random_state=123)
    wrong = np.array([float(x) for x in Case(30, Fraction(11, 200), "simple").pmf]) * a.size
    observed = np.bincount(a, minlength=31)[1:]
    keep = wrong >= 5
    obs, exp = observed[keep], wrong[keep]
    exp = exp * obs.sum() / exp.sum()
    assert chisquare(obs, exp).pvalue < 1e-6


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


def test_exact_ties_mode_is_smallest_maximiser() -> None:
    # Phi(50) = Phi(51) exactly for N = 101, p = 1/50; Phi(1) = Phi(2) = Phi(3) for N = 5, p = 1/2
    assert symhx.distribution_of(101, "1/50").mode() == 50
    assert symhx.distribution_of(101, "1/50").modes() == (50, 51)
    assert symhx.distribution_of(5, "1/2").mode() == 1
    assert symhx.distribution_of(5, "1/2", dps=None).mode() == 1
    for c in CASES:
        if len(c.modes) > 1:
            d = symhx.distribution_of(c.N, c.p, space=c.space)
            assert d.mode() == min(c.modes) and d.modes() == c.modes


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


def test_bad_arguments_are_clear_errors() -> None:
    d = symhx.distribution_of(10, 0.3, dps=20)
    with pytest.raises(TypeError, match="k"):
        d.pmf(2.5)
    with pytest.raises(TypeError, match="k"):
        d.cdf(np.array([1.5]))
    with pytest.raises(TypeError, match="k"):
        d.pmf(True)
    with pytest.raises(ValueError, match="q"):
        d.ppf(1.5)
    with pytest.raises(ValueError, match="confidence"):
        d.interval(-0.1)
    with pytest.raises(TypeError, match="random_state"):
        d.rvs(3, random_state=1.5)
    with pytest.raises(ValueError, match="dps"):
        symhx.distribution_of(10, 0.3, dps=0)
    with pytest.raises(TypeError, match="space"):
        symhx.distribution_of(10, 0.3, space=3)
    with pytest.raises(ValueError, match="FLOAT_N_LIMIT"):
        symhx.distribution_of(10**8, 0.3, dps=None).pmf(1)
    with pytest.raises(ValueError, match="MAX_EXCESS"):
        symhx.mean(10, 0.3, space="excess<=1000")


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
        want = _mp(sum(Case(30, Fraction(0.3), "simple").weights))
        assert abs(got - want) <= mpmath.mpf(10) ** -39 * want
        want = _mp(sum(Case(30, Fraction(0.3), "eq41").weights))
        assert abs(got_space - want) <= mpmath.mpf(10) ** -39 * want


def test_class_decomposition_by_excess_precision_is_local() -> None:
    from symhx.spaces import class_decomposition

    old = mpmath.mp.dps
    try:
        mpmath.mp.dps = 15
        got = class_decomposition(30, 0.3, space="excess<=3", dps=40).by_excess
    finally:
        mpmath.mp.dps = old
    ex = class_decomposition(30, Fraction(0.3), space="excess<=3").by_excess
    with mpmath.workdps(80):
        for e, want in ex.items():
            assert abs(got[e] - _mp(want)) <= mpmath.mpf(10) ** -39 * _mp(want), e
