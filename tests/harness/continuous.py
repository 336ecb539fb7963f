"""Conformance checks that every continuous distribution object must pass (scipy-style methods
``pdf, cdf, sf, logcdf, logsf, mean, var, std, rvs``, float64 by default and mpmath with
``dps=``).

:func:`check_continuous` runs all of them on one object at the thresholds given:

* the density is ``>= 0`` and integrates to the cdf: ``int_a^b pdf = cdf(b) - cdf(a)`` on
  consecutive thresholds (Gauss-Legendre of the object's own density, which is smooth there);
* ``cdf + sf = 1``, ``cdf`` non-decreasing;
* ``logcdf``/``logsf`` are the logs of the small tail with relative accuracy (where the tail is
  below 1/2) and ``log1p(-other tail)`` where it is above 1/2, so both tails keep their digits;
* ``mean = int_0^inf sf`` and ``E[X**2] = int_0^inf 2 t sf(t) dt`` by quadrature of the object's
  own tail (support on ``[0, inf)``);
* ``rvs`` is reproducible for a seed, differs between seeds, has the right mean and variance
  (within 6 standard errors) and passes a Kolmogorov-Smirnov test against the cdf;
* array in, array out (shape kept, each entry the scalar call, empty in empty out, a Python
  float for a scalar);
* refusals: non-finite ``x``, bad ``dps``, bad ``size`` and ``random_state`` are errors that name
  the argument (:func:`tests.harness.errors.assert_refuses`).

The mpmath checks (``dps=...``) run on a few of the thresholds (they cost more).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from typing import Any

import mpmath
import numpy as np

from tests.harness.errors import assert_refuses

__all__ = ["check_continuous"]

EPS = float(np.finfo(float).eps)


def _gl(f: Any, a: float, b: float, n: int = 48) -> float:
    """Gauss-Legendre of ``f`` (vectorised) on ``[a, b]`` in 8 panels."""
    x, w = np.polynomial.legendre.leggauss(n)
    edges = np.linspace(a, b, 9)
    tot = 0.0
    for lo, hi in itertools.pairwise(edges):
        h, m = 0.5 * (hi - lo), 0.5 * (hi + lo)
        tot += h * float(np.dot(w, f(m + h * x)))
    return tot


def _check_float(dist: Any, xs: np.ndarray, rtol: float) -> None:
    pdf, cdf, sf = dist.pdf(xs), dist.cdf(xs), dist.sf(xs)
    logcdf, logsf = dist.logcdf(xs), dist.logsf(xs)
    assert np.all(pdf >= 0), "pdf < 0"
    assert np.all((cdf >= 0) & (cdf <= 1) & (sf >= 0) & (sf <= 1)), "cdf/sf outside [0, 1]"
    assert np.all(np.diff(cdf[np.argsort(xs)]) >= 0), "cdf decreases"
    assert np.all(np.abs(cdf + sf - 1) <= 8 * EPS), "cdf + sf != 1"
    for x, c, s, lc, ls in zip(xs, cdf, sf, logcdf, logsf, strict=True):
        for small, other, lg, name in ((c, s, lc, "logcdf"), (s, c, ls, "logsf")):
            if small <= 0.5:
                if small >= 1e-300:   # a normal float: its log to the relative accuracy asked
                    want = math.log(small)
                    assert abs(lg - want) <= rtol * (1 + abs(want)), (name, x, lg, want)
                else:   # underflowed: the log is finite far below, or -inf only if exact 0
                    assert lg <= math.log(1e-300), (name, x, lg)
            else:
                want = math.log1p(-other)
                assert abs(lg - want) <= rtol * abs(want) + 8 * EPS * abs(want) + 1e-300, (
                    name, x, lg, want)
    # the density integrates to the cdf between consecutive thresholds
    srt = np.sort(xs[xs >= 0])
    for a, b in itertools.pairwise(srt):
        if b <= a:
            continue
        integral = _gl(dist.pdf, float(a), float(b))
        diff = float(dist.cdf(float(b)) - dist.cdf(float(a)))
        if diff > 1e-12:   # both tails tiny: nothing to compare
            assert abs(integral - diff) <= 1e-9 * diff + 1e-15, ("int pdf", a, b, integral, diff)


def _check_moments(dist: Any, upper: float) -> None:
    mean, var = float(dist.mean()), float(dist.var())
    assert mean > 0 and var > 0
    assert abs(float(dist.std()) - math.sqrt(var)) <= 4 * EPS * math.sqrt(var)
    m1 = _gl(dist.sf, 0.0, upper, 64)
    m2 = _gl(lambda t: 2 * t * dist.sf(t), 0.0, upper, 64)
    assert abs(m1 - mean) <= 1e-10 * mean, ("mean", m1, mean)
    assert abs(m2 - m1 * m1 - var) <= 1e-9 * (var + mean * mean), ("var", m2 - m1 * m1, var)


def _check_rvs(dist: Any, n: int, seed: int) -> None:
    from scipy import stats

    r = dist.rvs(size=n, random_state=seed)
    assert isinstance(r, np.ndarray) and r.shape == (n,)
    assert np.array_equal(r, dist.rvs(size=n, random_state=seed)), "same seed, other draws"
    assert np.array_equal(r, dist.rvs(size=n, random_state=np.random.default_rng(seed)))
    assert not np.array_equal(r, dist.rvs(size=n, random_state=seed + 1)), "seed ignored"
    assert isinstance(dist.rvs(random_state=seed), float)
    assert dist.rvs(size=(2, 3), random_state=seed).shape == (2, 3)
    assert dist.rvs(size=0, random_state=seed).shape == (0,)
    mean, var = float(dist.mean()), float(dist.var())
    assert np.all(r > 0)
    assert abs(r.mean() - mean) <= 6 * math.sqrt(var / n), ("sample mean", r.mean(), mean)
    m4 = float(np.mean((r - r.mean()) ** 4))
    assert abs(r.var() - var) <= 6 * math.sqrt(max(m4 - var * var, 0.0) / n) + 1e-12, (
        "sample var", r.var(), var)
    assert stats.kstest(r[:5000], dist.cdf).pvalue > 1e-4, "KS test"


def _check_arrays(dist: Any, xs: np.ndarray) -> None:
    grid = np.resize(xs, (2, 3)) if xs.size >= 1 else np.zeros((2, 3))
    for name in ("pdf", "cdf", "sf", "logcdf", "logsf"):
        fn = getattr(dist, name)
        out = fn(grid)
        assert isinstance(out, np.ndarray) and out.shape == (2, 3), name
        for idx in np.ndindex(grid.shape):
            one = fn(float(grid[idx]))
            assert isinstance(one, float), name
            assert out[idx] == one or (math.isnan(one) and math.isnan(out[idx])), (name, idx)
        assert fn(np.array([])).shape == (0,), name
        assert fn(np.empty((0, 2))).shape == (0, 2), name
        assert fn(list(grid[0])).shape == (3,), name


def _check_refusals(dist: Any) -> None:
    for name in ("pdf", "cdf", "sf", "logcdf", "logsf"):
        fn = getattr(dist, name)
        assert_refuses(fn, math.nan, arg="x", value="nan", allowed="finite")
        assert_refuses(fn, [1.0, math.inf], arg="x", value="inf", allowed="finite")
        assert_refuses(fn, 1.0, dps=True, exc=TypeError, arg="dps")
        assert_refuses(fn, 1.0, dps=0, arg="dps", value="0")
    for bad, exc in ((-1, ValueError), (2.5, TypeError), ((2, -1), ValueError), ("3", TypeError),
                     (True, TypeError)):
        assert_refuses(dist.rvs, bad, exc=exc, arg="size")
    assert_refuses(dist.rvs, 3, random_state="seed", exc=(TypeError, ValueError),
                   arg="random_state")


def _check_mp(dist: Any, xs: Sequence[float], dps: int) -> None:
    tol = mpmath.mpf(10) ** (-dps)
    for x in xs:
        xf = float(x)
        cdf, sf = dist.cdf(xf, dps=dps), dist.sf(xf, dps=dps)
        pdf = dist.pdf(xf, dps=dps)
        assert isinstance(cdf, mpmath.mpf) and isinstance(pdf, mpmath.mpf)
        assert pdf >= 0
        with mpmath.workdps(dps + 10):
            assert abs(cdf + sf - 1) <= 2 * tol, ("mp cdf + sf", x)
            for small, other, name in ((cdf, sf, "logcdf"), (sf, cdf, "logsf")):
                lg = getattr(dist, name)(xf, dps=dps)
                want = mpmath.log(small) if small <= 0.5 else mpmath.log1p(-other)
                assert abs(lg - want) <= 2 * tol * max(1, abs(want)), (name, x)
            # the float64 values agree with the mpmath ones
            for name, v in (("cdf", cdf), ("sf", sf), ("pdf", pdf)):
                fv = getattr(dist, name)(xf)
                if v > 1e-290:
                    assert abs(fv / v - 1) < 1e-12, ("float vs mp", name, x, fv, v)
    mean, var = dist.mean(dps=dps), dist.var(dps=dps)
    with mpmath.workdps(dps + 10):
        assert abs(mean / mpmath.mpf(dist.mean()) - 1) < 1e-14
        assert abs(var / mpmath.mpf(dist.var()) - 1) < 1e-14


def check_continuous(dist: Any, xs: Sequence[float], *, upper: float, rtol: float = 1e-13,
                     dps: int | None = 20, mp_points: int = 3, rvs_size: int = 20_000,
                     seed: int = 20240517) -> None:
    """Run every conformance check on the distribution object ``dist`` (support ``[0, inf)``).

    ``xs``: thresholds reaching both tails and the body (include values ``<= 0`` to check the
    support's edge); ``upper``: a point beyond which the tail no longer contributes to the
    moments at double precision; ``rtol``: the relative accuracy asked of the logs; ``dps``:
    the precision of the mpmath checks on ``mp_points`` of the thresholds (``None``: skip).
    """
    arr = np.asarray(xs, dtype=float)
    _check_float(dist, arr, rtol)
    _check_moments(dist, upper)
    _check_rvs(dist, rvs_size, seed)
    _check_arrays(dist, arr)
    _check_refusals(dist)
    if dps is not None:
        pos = [float(x) for x in arr if x > 0]
        pick = [pos[i] for i in np.linspace(0, len(pos) - 1, min(mp_points, len(pos))).astype(int)]
        _check_mp(dist, pick, dps)
