"""Conformance checks that any frozen discrete distribution of X on ``1..N`` must pass (the
methods of scipy.stats' frozen discrete distributions, in the spirit of scipy.stats'
``common_tests.py``): the pmf sums to 1, ``cdf`` is the cumulative pmf and ``cdf + sf = 1``, the
logs are the logs of the values (also where those are tiny or near 1), ``ppf`` / ``isf`` invert
``cdf`` / ``sf``, mean, variance, std and entropy agree with the pmf, median and interval come
from ``ppf``, ``rvs`` stays in the support, follows the pmf and is reproducible from its seed,
arrays in give arrays out of the same shape, and bad arguments are refused by name.

Each check takes the frozen object ``d`` and an exact reference
(:class:`tests.reference.distribution.ExactTable`, built from an independent weight formula),
and a :class:`Path` saying how ``d``'s results compare with exact values:

* ``Path.exact(dps)``: rational results must *equal* the reference (logs, std and entropy: within
  ``10**(1 - dps)``, entropy absolutely ``10**-dps``);
* ``Path.mp(dps)``: ``mpf`` results within a relative ``10**(1 - dps)``, compared at
  ``2 dps + 20`` digits (entropy: absolute ``10**-dps``);
* ``Path.float64(rtol=...)``: float64 results within ``rtol`` (logs absolutely
  ``log_tol max(1, |log|)``).

>>> from fractions import Fraction
>>> import symhx
>>> from tests.reference.distribution import ExactTable
>>> d = symhx.distribution_of(5, "1/2")
>>> check_frozen(d, ExactTable.simple(5, Fraction(1, 2)), Path.exact(d.dps))
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

from symhx.validation import DEFAULT_DPS
from tests.harness.errors import assert_refuses
from tests.reference.distribution import ExactTable, log_of, to_mp

__all__ = [
    "NS",
    "PS",
    "QS",
    "Path",
    "check_array_shapes",
    "check_cdf_sf",
    "check_frozen",
    "check_log_tails",
    "check_log_tails_on_path",
    "check_modes",
    "check_moments",
    "check_paths_agree",
    "check_pmf",
    "check_ppf_inverts_cdf",
    "check_quantiles",
    "check_quantiles_at_midpoints",
    "check_refusals",
    "check_rvs",
    "check_table",
    "chi_square_pvalue",
    "frozen_on_path",
    "support_points",
]

#: probabilities at which quantiles are checked by default
QS = (Fraction(0), Fraction(1, 1000), Fraction(1, 10), Fraction(1, 2), Fraction(9, 10),
      Fraction(999, 1000), Fraction(1))


#: log grids of N and p for the conformance tests
NS = (1, 2, 3, 7, 20, 60)
PS = (Fraction(1, 10**6), Fraction(1, 1000), Fraction(1, 50), Fraction(1, 10), Fraction(1, 2),
      Fraction(1), Fraction(3))


def support_points(N: int) -> list[int]:
    """``k`` inside, at the edges of and far outside the support ``1..N``."""
    return sorted({-3, -1, 0, 1, 2, N // 2, N - 1, N, N + 1, N + 7, N + 10**20})


# --------------------------------------------------------------------------- comparisons
@dataclass(frozen=True)
class Path:
    """How the results of one arithmetic path compare with exact values."""

    kind: str  # "exact", "mp" or "float"
    dps: int | None
    rtol: float = 1e-11           # float64 values (pmf, cdf, sf, mean, normaliser)
    log_tol: float | None = None  # float64 logs: absolute, times max(1, |log|) (default rtol)
    var_rtol: float | None = None  # float64 var and std, relative (default rtol)
    std_atol: float = 0.0         # float64 std, absolute
    entropy_atol: float | None = None  # float64 entropy, absolute (default rtol)

    @classmethod
    def exact(cls, dps: int = 30) -> Path:
        return cls("exact", dps)

    @classmethod
    def mp(cls, dps: int) -> Path:
        return cls("mp", dps)

    @classmethod
    def float64(cls, **tolerances: Any) -> Path:
        return cls("float", None, **tolerances)

    @property
    def digits(self) -> int:
        """Digits at which a comparison is made."""
        return 2 * (self.dps or 15) + 20

    @property
    def tol(self) -> mpmath.mpf:
        """The relative accuracy promised: ``10**(1 - dps)``, or ``rtol`` for float64."""
        return mpmath.mpf(10) ** (1 - self.dps) if self.dps else mpmath.mpf(self.rtol)

    def value(self, got: Any, want: Fraction | mpmath.mpf, what: Any = "",
              rtol: float | None = None, abs_tol: float = 1e-300) -> None:
        """A value that is rational when ``p`` is: equal (exact), or within the tolerance."""
        if self.kind == "exact":
            assert isinstance(got, Fraction) and got == want, (what, got, want)
        elif self.kind == "mp":
            assert isinstance(got, mpmath.mpf), (what, type(got))
            with mpmath.workdps(self.digits):
                w = to_mp(want) if isinstance(want, Fraction) else want
                assert abs(got - w) <= self.tol * abs(w), (what, got, w)
        else:
            # float(want) may underflow to 0.0 in the deep tails: then so must got
            w = float(want)
            assert isinstance(got, float), (what, type(got))
            assert math.isclose(got, w, rel_tol=rtol or self.rtol, abs_tol=abs_tol), (what, got, w)

    def log(self, got: Any, want: Fraction | mpmath.mpf, what: Any = "") -> None:
        """``got = log(want)`` for an exact ``want >= 0`` (or an mpf ``want``): absolute error
        ``tol max(1, |log want|)``, ``-inf`` at 0."""
        assert isinstance(got, float if self.kind == "float" else mpmath.mpf), (what, type(got))
        with mpmath.workdps(self.digits):
            w = log_of(want) if isinstance(want, Fraction) else mpmath.log(want)
            if w == mpmath.ninf:
                assert got == -math.inf, (what, got)
                return
            tol = self.tol if self.kind != "float" else mpmath.mpf(self.log_tol or self.rtol)
            assert abs(got - w) <= tol * max(1, abs(w)), (what, got, w)

    def real(self, got: Any, want: mpmath.mpf, what: Any = "", *, rtol: float | None = None,
             atol: Any = 0) -> None:
        """An irrational value: ``|got - want| <= rtol |want| + atol`` (``rtol`` defaults to
        the path's relative accuracy; a zero ``want`` asks for ``|got| <= 1e-300 rtol``)."""
        with mpmath.workdps(self.digits):
            tol = mpmath.mpf(rtol) if rtol is not None else self.tol
            bound = tol * max(abs(want), mpmath.mpf(10) ** -300) + atol
            assert abs(mpmath.mpf(got) - want) <= bound, (what, got, want)


def frozen_on_path(make: Callable[[Any, int | None], Any], p: Fraction, path: Path
                   ) -> tuple[Any, Fraction]:
    """``(d, p_exact)``: the frozen object ``make(p, dps)`` of the path -- the exact ``p`` for
    the exact path, ``float(p)`` otherwise -- and the exact value ``d`` stands for (a float is
    taken at its exact binary value)."""
    if path.kind == "exact":
        return make(p, path.dps), Fraction(p)
    pf = float(p)
    return make(pf, path.dps), Fraction(pf)


# --------------------------------------------------------------------------- per-k methods
def check_pmf(d: Any, ref: ExactTable, path: Path, ks: Iterable[int] | None = None) -> None:
    """``support() == (1, N)``; ``pmf`` and ``logpmf`` at ``ks`` (default
    :func:`support_points`); the pmf over the support (an array call) sums to 1."""
    N = ref.N
    assert d.support() == (1, N)
    for k in support_points(N) if ks is None else ks:
        want = ref.pmf_at(k)
        path.value(d.pmf(k), want, ("pmf", k))
        path.log(d.logpmf(k), want, ("logpmf", k))
    arr = d.pmf(np.arange(1, N + 1))
    assert arr.shape == (N,)
    if path.kind == "exact":
        assert sum(arr, Fraction(0)) == 1
    elif path.kind == "mp":
        with mpmath.workdps(path.digits):
            assert abs(mpmath.fsum(arr) - 1) <= path.tol, mpmath.fsum(arr)
    else:
        assert abs(math.fsum(arr) - 1) <= path.rtol + N * 1e-300, math.fsum(arr)


def check_cdf_sf(d: Any, ref: ExactTable, path: Path, ks: Iterable[int] | None = None) -> None:
    """``cdf``, ``sf``, ``logcdf``, ``logsf`` at ``ks`` against the partial sums of the pmf; on
    the exact path ``cdf(k) + sf(k) == 1`` exactly."""
    for k in support_points(ref.N) if ks is None else ks:
        c, s = ref.cdf(k), ref.sf(k)
        path.value(d.cdf(k), c, ("cdf", k))
        path.value(d.sf(k), s, ("sf", k))
        path.log(d.logcdf(k), c, ("logcdf", k))
        path.log(d.logsf(k), s, ("logsf", k))
        if path.kind == "exact":
            assert d.cdf(k) + d.sf(k) == 1, k


def check_log_tails(d: Any, logs: dict[int, tuple[Any, Any]], tol: Any) -> None:
    """``logcdf`` / ``logsf`` to a *relative* ``tol`` also where the probability is close to 1
    (the log is then tiny: the log of a P with dps digits would only be absolutely accurate);
    ``logs`` maps k to the exact ``(log P(X <= k), log P(X > k))`` (see
    :func:`tests.reference.distribution.tail_logs`), compared at 700 digits."""
    for k, pair in logs.items():
        for name, w in zip(("logcdf", "logsf"), pair, strict=True):
            got = getattr(d, name)(k)
            with mpmath.workdps(700):
                err = abs(mpmath.mpf(got) - w) / abs(w)
            assert err <= tol, (name, k, float(got), mpmath.nstr(w, 8), mpmath.nstr(err, 3))


def check_log_tails_on_path(make: Callable[[Any, int | None], Any], p: Fraction,
                            dps: int | None, logs: dict[int, tuple[Any, Any]]) -> None:
    """:func:`check_log_tails` on one path of ``make(p, dps)``: ``dps = 0`` the exact path at
    the default digits (relative ``1e-14``), an int the mpmath path (``10**(1 - dps)``),
    ``None`` float64 with ``float(p)`` (100x the documented relative error ~1e-16 N log N of
    the gammaln log-weights), whose array form must give the same values."""
    d = make(p, DEFAULT_DPS) if dps == 0 else make(float(p) if dps is None else p, dps)
    N = d.support()[1]
    if dps == 0:
        tol = mpmath.mpf(10) ** -14
    else:
        tol = mpmath.mpf(10) ** (1 - dps) if dps else mpmath.mpf(1e-14 * N * math.log(N))
    check_log_tails(d, logs, tol)
    if dps is None:  # the array form takes the same table
        ks = sorted(logs)
        arr = d.logsf(np.array(ks))
        assert [float(x) for x in arr] == [float(d.logsf(k)) for k in ks]


# --------------------------------------------------------------------------- summaries
def check_moments(d: Any, ref: ExactTable, path: Path) -> None:
    """``mean``, ``var`` (Fractions on the exact path), ``std = sqrt(var)``, ``entropy``
    (absolute ``10**-dps``), ``normaliser`` and ``log_normaliser`` against the reference."""
    path.value(d.mean(), ref.mean, "mean")
    path.value(d.var(), ref.var, "var", rtol=path.var_rtol)
    with mpmath.workdps(path.digits):
        sd = mpmath.sqrt(to_mp(ref.var))
        h = ref.entropy(path.digits)
    if path.kind == "float":
        path.real(d.std(), sd, "std", rtol=path.var_rtol or path.rtol, atol=path.std_atol)
        assert isinstance(d.std(), float) and isinstance(d.entropy(), float)
        path.real(d.entropy(), h, "entropy", rtol=0, atol=path.entropy_atol or path.rtol)
    else:
        assert isinstance(d.std(), mpmath.mpf) and isinstance(d.entropy(), mpmath.mpf)
        path.real(d.std(), sd, "std")
        path.real(d.entropy(), h, "entropy", rtol=0, atol=mpmath.mpf(10) ** -path.dps)
    if path.kind != "float" or math.isfinite(float(ref.normaliser)):
        path.value(d.normaliser, ref.normaliser, "normaliser")
    path.log(d.log_normaliser, ref.normaliser, "log_normaliser")


def check_modes(d: Any, ref: ExactTable) -> None:
    """``modes()`` are every maximiser of the pmf; ``mode()`` the smallest (also on ties)."""
    assert d.modes() == ref.modes, (d.modes(), ref.modes)
    assert d.mode() == ref.modes[0]


def check_table(d: Any, ref: ExactTable, path: Path) -> None:
    """``table()`` lists ``(k, P(X = k))`` for ``k = 1..N``."""
    tab = d.table()
    assert [k for k, _ in tab] == list(range(1, ref.N + 1))
    for k, v in tab:
        path.value(v, ref.pmf[k - 1], ("table", k), abs_tol=0.0)


# --------------------------------------------------------------------------- quantiles
def _near(values: Sequence[float], q: Fraction) -> bool:
    return bool(np.min(np.abs(np.asarray(values) - float(q))) < 1e-9)


def check_quantiles(d: Any, ref: ExactTable, path: Path,
                    qs: Iterable[Fraction] = QS, confidences: Iterable[str] = ("0.8", "0.9")
                    ) -> None:
    """``ppf`` / ``isf`` at ``qs`` (Python ints), their ends ``ppf(0) = 0``, ``ppf(1) = N``,
    ``isf(1) = 0``, ``isf(0) = N``, arrays of ``q``; ``median`` and ``interval`` from the
    reference ``ppf``. On the float64 path a ``q`` within 1e-9 of a cdf (sf) value is skipped
    for ``ppf`` (``isf``): the float cdf decides there; median and interval are not checked."""
    N = ref.N
    cdf_f = [float(ref.cdf(j)) for j in range(1, N + 1)]
    sf_f = [float(ref.sf(j)) for j in range(0, N + 1)]
    flt = path.kind == "float"
    for q in qs:
        if not (flt and _near(cdf_f, q)):
            got = d.ppf(q)
            assert got == ref.ppf(q) and isinstance(got, int), ("ppf", q, got)
        if not (flt and _near(sf_f, q)):
            got = d.isf(q)
            assert got == ref.isf(q) and isinstance(got, int), ("isf", q, got)
    assert d.ppf(0) == 0 and d.ppf(1) == N and d.isf(1) == 0 and d.isf(0) == N
    dtype = np.int64 if flt else object
    qa = d.ppf([Fraction(0), Fraction(1)])
    qi = d.isf([Fraction(1), Fraction(0)])
    assert qa.dtype == dtype and qa.tolist() == [0, N]
    assert qi.dtype == dtype and qi.tolist() == [0, N]
    if flt:
        return
    assert d.ppf([Fraction(1, 2)]).tolist() == [ref.ppf(Fraction(1, 2))]
    assert d.median() == ref.ppf(Fraction(1, 2))
    for c in confidences:
        cf = Fraction(c)
        assert d.interval(c) == (ref.ppf((1 - cf) / 2), ref.ppf((1 + cf) / 2)), c


def check_quantiles_at_midpoints(d: Any, ref: ExactTable, dps: int) -> None:
    """mpmath path: ``ppf`` (``isf``) at the midpoint between consecutive cdf (sf) values gives
    the k between them wherever ``P(X = k)`` and the values are resolvable at ``dps`` digits."""
    tiny = Fraction(1, 10 ** (dps - 4))
    for k in range(1, ref.N + 1):
        pk = ref.pmf[k - 1]
        lo, hi = ref.cdf(k - 1), ref.cdf(k)
        if pk > tiny * hi and 1 - hi > tiny:
            assert d.ppf((lo + hi) / 2) == k, ("ppf", k)
        lo, hi = ref.sf(k), ref.sf(k - 1)
        if pk > tiny * hi and lo > tiny * hi:
            assert d.isf((lo + hi) / 2) == k, ("isf", k)


def check_quantiles_at_exact_ties(d: Any, exact: Any, dps: int, ks: Iterable[int]) -> None:
    """mpmath path: a ``q`` whose resolved target (``q (1 -+ 10**(1 - dps))``) equals
    ``cdf(k)`` (``sf(k)``) exactly gives k whatever the rounding of the sums (a tie reaches the
    target), and one resolution step beyond it gives k + 1.  ``exact`` has the exact ``cdf``
    and ``sf`` (an :class:`ExactTable` or an exact frozen distribution)."""
    eps = Fraction(10) ** (1 - dps)
    for k in ks:
        c, s = exact.cdf(k), exact.sf(k)
        assert isinstance(c, Fraction) and isinstance(s, Fraction)
        assert d.ppf(c / (1 - eps)) == k and d.isf(s / (1 + eps)) == k, ("tie", k)
        assert d.ppf(c * (1 + 2 * eps)) == k + 1 and d.isf(s * (1 - 2 * eps)) == k + 1, ("step", k)


def check_ppf_inverts_cdf(d: Any, ref: ExactTable, dps: int | None) -> None:
    """``ppf(cdf(k)) == k`` and ``isf(sf(k)) == k`` for every k; at ``dps`` digits (``None``:
    exact) except where ``cdf(k - 1)`` and ``cdf(k)`` coincide at that precision
    (``P(X = k) < 10**(3 - dps) cdf(k)``, or ``cdf(k)`` rounds to 1): then ``ppf`` returns the
    smaller k, as scipy does."""
    small = Fraction(1, 10 ** (dps - 3)) if dps else Fraction(0)
    for k in range(1, ref.N + 1):
        if ref.pmf[k - 1] < small * ref.cdf(k) or ref.sf(k) < small:
            continue
        assert d.ppf(d.cdf(k)) == k, ("ppf", k)
    for k in range(1, ref.N + 1):
        if ref.pmf[k - 1] < small * ref.sf(k - 1):
            continue
        assert d.isf(d.sf(k)) == k, ("isf", k)


def check_paths_agree(make: Callable[[int | None], Any], dps: int = 20,
                      float_rtol: float = 1e-9) -> None:
    """Where no exact reference is practical (large N): ``make(dps)`` agrees with
    ``make(2 dps)`` to ``dps`` digits (pmf, cdf, sf and their logs at ``k`` around the mode and
    in both tails; mean, var, entropy, median), and the float64 ``make(None)`` with both to
    ``float_rtol`` (its log-weights come from ``gammaln``)."""
    lo, hi, fl = make(dps), make(2 * dps), make(None)
    N, m = lo.support()[1], lo.mode()
    ks = [1, 2, m // 2 + 1, m, m + 5, min(N - 1, 3 * m + 50), N - 1]
    tol = mpmath.mpf(10) ** (1 - dps)
    with mpmath.workdps(2 * dps + 10):
        for name in ("cdf", "sf", "pmf"):
            for k in ks:
                a, b = getattr(lo, name)(k), getattr(hi, name)(k)
                assert abs(a - b) <= tol * abs(b), (name, k, a, b)
                la, lb = getattr(lo, "log" + name)(k), getattr(hi, "log" + name)(k)
                assert abs(la - lb) <= tol * max(1, abs(lb)), (name, k)
                lf = getattr(fl, "log" + name)(k)
                assert abs(lf - float(lb)) <= float_rtol * max(1.0, abs(float(lb))), (name, k)
        for name in ("mean", "var", "entropy"):
            a, b = getattr(lo, name)(), getattr(hi, name)()
            assert abs(a - b) <= tol * abs(b), name
            assert abs(getattr(fl, name)() - float(b)) <= float_rtol * abs(float(b)), name
    assert lo.median() == hi.median() == fl.median()


# --------------------------------------------------------------------------- arrays
_PER_K = ("pmf", "logpmf", "cdf", "sf", "logcdf", "logsf")


def check_array_shapes(d: Any, path: Path) -> None:
    """Every per-k method maps an array of k (int64, object with huge ints, empty) to an array
    of the same shape, element by element equal to the scalar calls; dtype float64 on the
    float64 path, object otherwise."""
    N = d.support()[1]
    dtype = np.float64 if path.kind == "float" else object
    grids = [np.array([[0, 1], [N, N + 1]]),
             np.array([-1, 0, 1, N, N + 1, 10**30], dtype=object)]
    for name in _PER_K:
        f = getattr(d, name)
        for ks in grids:
            got = f(ks)
            assert got.shape == ks.shape and got.dtype == dtype, (name, got.dtype)
            for idx, k in np.ndenumerate(ks):
                one = f(int(k))
                assert got[idx] == one or (got[idx] != got[idx] and one != one), (name, k)
        for shape in ((0,), (0, 3)):
            got = f(np.empty(shape, dtype=object))
            assert got.shape == shape and got.dtype == dtype, (name, shape, got.dtype)
    q = d.ppf(np.array([[0.0, 1.0]]))
    assert q.shape == (1, 2) and q.tolist() == [[0, N]]


# --------------------------------------------------------------------------- sampling
def chi_square_pvalue(draws: np.ndarray, pmf: Sequence[float]) -> float:
    """Pearson's goodness of fit of integer draws on ``1..N`` to ``pmf`` (floats), the bins
    with fewer than 5 expected draws pooled into one."""
    from scipy.stats import chisquare

    N = len(pmf)
    expected = np.asarray(pmf, dtype=float) * draws.size
    observed = np.bincount(draws, minlength=N + 1)[1:]
    keep = expected >= 5
    obs = np.append(observed[keep], observed[~keep].sum())
    exp = np.append(expected[keep], expected[~keep].sum())
    if exp[-1] == 0:
        obs, exp = obs[:-1], exp[:-1]
    return float(chisquare(obs, exp * obs.sum() / exp.sum()).pvalue)


def check_rvs(d: Any, ref: ExactTable, *, size: int = 30_000, seed: int = 9) -> None:
    """Draws are int64 in ``1..N``, follow the pmf (chi-square p-value above 1e-4), and the
    same seed (an int or a ``Generator`` from it) gives the same draws; ``size=None`` gives an
    int, a tuple size that shape."""
    N = ref.N
    a = d.rvs(size, random_state=seed)
    assert a.dtype == np.int64 and a.shape == (size,)
    assert a.min() >= 1 and a.max() <= N
    assert np.array_equal(a, d.rvs(size, random_state=seed))
    assert np.array_equal(a, d.rvs(size, random_state=np.random.default_rng(seed)))
    if max(ref.pmf) < Fraction(99, 100):
        assert not np.array_equal(a, d.rvs(size, random_state=seed + 1))
    assert chi_square_pvalue(a, [float(x) for x in ref.pmf]) > 1e-4
    x = d.rvs(random_state=3)
    assert isinstance(x, int) and 1 <= x <= N
    assert d.rvs((2, 3), random_state=1).shape == (2, 3)
    assert d.rvs(0, random_state=1).shape == (0,)
    assert d.rvs((0, 3), random_state=1).shape == (0, 3)


# --------------------------------------------------------------------------- refusals
def check_refusals(d: Any) -> None:
    """Bad ``k``, ``q``, ``confidence``, ``size`` and ``random_state`` are refused by name,
    with the value and what is allowed (TypeError for a wrong kind, ValueError out of range)."""
    for bad, shown, allowed in ((2.5, "2.5", "int"), (True, "True", "integer")):
        assert_refuses(d.pmf, bad, exc=TypeError, arg="k", value=shown, allowed=allowed)
    assert_refuses(d.cdf, np.array([1.5]), exc=TypeError, arg="k", value="float64",
                   allowed="integers")
    assert_refuses(d.pmf, np.array([True, False]), exc=TypeError, arg="k", value="bool",
                   allowed="integers")
    for bad in ([1, 2.5], np.array([1.0, 2.0])):  # integral floats too
        assert_refuses(d.pmf, bad, exc=TypeError, arg="k", value="float64", allowed="integers")
    assert_refuses(d.ppf, 1.5, arg="q", value="1.5", allowed="<= 1")
    assert_refuses(d.isf, [0.5, -0.1], arg="q", value="-0.1", allowed=">= 0")
    assert_refuses(d.interval, -0.1, arg="confidence", value="-0.1", allowed=">= 0")
    assert_refuses(d.interval, 1.5, arg="confidence", value="1.5", allowed="<= 1")
    assert_refuses(d.rvs, 3, random_state=1.5, exc=TypeError, arg="random_state",
                   value="1.5", allowed="int")
    assert_refuses(d.rvs, 2, random_state=-1, arg="random_state", value="-1", allowed=">= 0")
    assert_refuses(d.rvs, -1, arg="size", value="-1", allowed=">= 0")
    assert_refuses(d.rvs, (2, -1), arg="size", value="-1", allowed=">= 0")


# --------------------------------------------------------------------------- all of it
def check_frozen(d: Any, ref: ExactTable, path: Path, *, ks: Iterable[int] | None = None,
                 qs: Iterable[Fraction] = QS) -> None:
    """Every value method of ``d`` against ``ref`` on ``path``: pmf, cdf / sf and their logs,
    moments, normaliser, modes, table and quantiles."""
    ks = support_points(ref.N) if ks is None else list(ks)
    check_pmf(d, ref, path, ks)
    check_cdf_sf(d, ref, path, ks)
    check_moments(d, ref, path)
    check_modes(d, ref)
    check_table(d, ref, path)
    check_quantiles(d, ref, path, qs)
