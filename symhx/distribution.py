"""The distribution of X, the number of distinct impacts of a circuit, over the simple circuits
(sections 4-5, eqs. 7-8), and the frozen-distribution interface shared by every sample space.

Simple sample space: ``P(X = k) = Phi_{N,p}(k) / Gamma_{N,p}`` with
``Phi_{N,p}(k) = p**k N! / (k (N-k)!)`` and ``Gamma_{N,p} = sum_{j=1}^{N} Phi_{N,p}(j)``.
This module knows nothing of the higher-order spaces (:mod:`symhx.spaces` builds on it); the
user-facing functions that pick a space (``symhx.pmf``, ``symhx.mean``, ...) live in
:mod:`symhx.api`.

Arithmetic
----------
* **Exact** for ``p`` an int, ``Fraction``, sympy ``Rational`` or decimal string: pmf, cdf, sf,
  normaliser, mean and variance are ``Fraction`` (binary splitting; ``N <= EXACT_N_LIMIT``;
  larger N raise ``ValueError`` -- pass a float or mpf ``p`` for the mpmath path).
* **mpmath** otherwise (floats and mpf are converted exactly, then evaluated at ``dps`` digits):
  log space throughout, so nothing overflows; only terms within ``dps`` + guard digits of the
  largest one (of the whole support, or of the summed range for cdf/sf) are summed (``Phi`` is
  decreasing, increasing, decreasing in k, so the significant terms form at most two runs,
  found by bisection).  ``N = 10**6`` runs in a fraction of a second to seconds; the cost grows
  with the width of the distribution (~sqrt(N)), so ``N`` up to ~10**9 is practical for the
  moments and ``N`` of any size for ``pmf``/``logpmf`` near the modes.
* **float64** for ``dps=None``: numpy arrays over the whole support (``N <= FLOAT_N_LIMIT``).
* **mode / modes** are decided exactly for every rational ``p`` (floats and mpf included) and
  any N (``10**100`` too): integer arithmetic locates the local maximum of ``Phi`` and a single
  comparison with ``Phi(1)`` is certified by interval arithmetic (exact integers on a near tie).
  The mode never needs the normaliser.

Ties: ``mode()`` returns the smallest maximiser; ``modes()`` returns all of them, e.g.
``N = 101, p = 1/50`` has modes ``(50, 51)``.

>>> d = SimpleDistribution(4, Fraction(1, 2))
>>> d.pmf(1), d.modes()
(Fraction(16, 39), (1,))
>>> mpmath.nstr(SimpleDistribution(100, 0.02, dps=20).mean(), 20)
'48.930449948267425369'
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from fractions import Fraction
from functools import cached_property
from typing import Any

import mpmath
import numpy as np

from symhx._mpctx import export
from symhx._mpctx import mp as thread_mp
from symhx._numeric import (
    G_mp,
    digits_of,
    mp_value,
)
from symhx.certify import (
    MAX_IRRATIONAL_BITS,
    G_arb,
    arb_prec,
    bits_for,
    certified_sign,
    decide_with_rising_precision,
    rational_bracket,
    real_ball,
    to_arb,
)
from symhx.validation import (
    DEFAULT_DPS,
    check_dps,
    check_int,
    check_N,
    check_p,
    check_real,
    check_seed,
    is_exact_type,
    mpf_to_fraction,
    to_rational,
)

__all__ = [
    "EXACT_N_LIMIT",
    "EXACT_QUANTILE_WORK_LIMIT",
    "EXACT_WORK_LIMIT",
    "FLOAT_N_LIMIT",
    "MP_QUANTILE_N_LIMIT",
    "MP_SUM_N_LIMIT",
    "Distribution",
    "SimpleDistribution",
    "binary_split",
    "simple_modes",
]

#: largest N for exact (Fraction) distributions
EXACT_N_LIMIT = 100_000
#: largest N for the float64 path (``dps=None``) and for :meth:`Distribution.rvs`: both build a
#: float64 table of the whole support (8 bytes per k).  Raise it here if you have the memory.
FLOAT_N_LIMIT = 10_000_000

#: exact (rational) sums are refused when ``N * (bits of N + bits of p's numerator and
#: denominator)`` exceeds this (the binary-splitting integers hold about that many bits):
#: ``mean(20000, "0.1")`` (3.9e5) takes 0.6 s, ``mean(20000, "1e-9")`` (9e5) 2 s,
#: ``mean(10**5, "0.1")`` (2.2e6) 11 s.  Pass p as a float / mpf for the mpmath path.
EXACT_WORK_LIMIT = 500_000
#: the same measure for exact quantiles (``ppf``, ``isf``, ``median``, ``interval``: one exact
#: partial sum per bisection step): ``median(10**4, "0.1")`` (1.8e5) takes 0.9 s.
EXACT_QUANTILE_WORK_LIMIT = 200_000
#: largest N for the sums of the mpmath path (moments, ``pmf``, ``cdf``, ``sf``, logs, ``entropy``):
#: the working precision carries two guard digits per digit of N, so the cost grows like a power
#: of ``log N`` (0.25 s at N = 10**100, 1.6 s at 10**300, minutes at 10**1000).  ``mode`` and
#: ``modes`` are decided without these sums and take any N.
MP_SUM_N_LIMIT = 10**100
#: largest N for the quantiles of the mpmath path (``ppf``, ``isf``, ``median``, ``interval``):
#: a bisection over ``[1, N]`` with one tail sum per step (0.2 s at N = 10**6, 14 s at 10**8).
MP_QUANTILE_N_LIMIT = 10**6

_LN10 = math.log(10)
_LN2 = math.log(2)


def _n_show(N: int) -> str:
    if N < 10**15:
        return str(N)
    e = len(str(N)) - 1
    return f"10**{e}" if N == 10**e else f"~10**{e}"


def _is_array(x: Any) -> bool:
    return isinstance(x, (np.ndarray, list, tuple))


def _check_k_scalar(k: Any) -> int:
    return check_int(k, "k")


def _check_k_array(k: Any) -> np.ndarray:
    """An integer array of ``k`` values (ints of any size are kept as Python ints)."""
    arr = np.asarray(k)
    if arr.dtype == bool:
        raise TypeError(f"k must be integers, got an array of dtype {arr.dtype}")
    if arr.dtype.kind in "iu":
        return arr
    if arr.dtype.kind == "O":
        return np.array([check_int(v, "k") for v in arr.ravel()], dtype=object).reshape(arr.shape)
    raise TypeError(f"k must be integers, got an array of dtype {arr.dtype} "
                    f"(k counts distinct impacts: pass ints, e.g. np.arange(1, N + 1))")


def _check_q(q: Any, name: str = "q") -> Fraction:
    return check_real(q, name, low=0, high=1)


class Distribution:
    """A frozen distribution of X, the number of distinct impacts of a circuit, with the methods
    of :mod:`scipy.stats` frozen discrete distributions.

    Build one with :func:`symhx.distribution_of`.  Attributes: ``N``, ``p`` (as given), ``fr``
    (its exact rational value, ``None`` for a sympy irrational), ``space`` (canonical name),
    ``dps`` (``None`` for float64) and ``exact`` (results are ``Fraction``).

    Result types follow ``p`` and ``dps``:

    * exact ``p`` (int, ``Fraction``, sympy ``Rational``, decimal string) and an int ``dps``:
      ``pmf``, ``cdf``, ``sf``, ``mean``, ``var`` are exact ``Fraction``; values that are not
      rational (logs, ``std``, ``entropy``) are ``mpmath.mpf`` correct to ``dps`` digits;
    * float / mpf ``p`` and an int ``dps``: ``mpmath.mpf`` correct to ``dps`` significant digits
      (tails too: ``sf(k)`` is summed from the terms above ``k``, never ``1 - cdf``, and a
      ``logcdf`` / ``logsf`` near 0 is ``log1p`` of the other tail, so it keeps its digits);
    * ``dps=None``: float64 (numpy), vectorised over ``k`` (relative error about
      ``1e-16 N log N``: the log-weights come from ``gammaln``; ``N <= FLOAT_N_LIMIT``).

    Every method that takes ``k`` or ``q`` also takes an array and returns an array of the same
    shape (object dtype for exact / mpmath values, float64 for ``dps=None``).  Integer results
    (``ppf``, ``isf``, ``median``, ``mode``, ``interval``) are Python ints, decided exactly.
    """

    N: int
    p: Any
    fr: Fraction | None
    space: str
    dps: int | None
    exact: bool
    _guard: int

    def _setup(self, N: Any, p: Any, dps: Any) -> None:
        self.N = check_N(N, minimum=1)
        self.fr, self.p = check_p(p)
        self.dps = check_dps(dps, allow_none=True)
        self.exact = self.dps is not None and is_exact_type(p)
        if self.exact and self.N > EXACT_N_LIMIT:
            raise ValueError(
                f"exact (rational) arithmetic is limited to N <= {EXACT_N_LIMIT} "
                f"(symhx.distribution.EXACT_N_LIMIT); got N={self.N}. Pass p as a float or "
                f"mpmath.mpf for the mpmath path at dps digits, or dps=None for float64.")
        # digits lost by the recurrences and the k, k**2 weights
        self._guard = 10 + 2 * digits_of(self.N)

    def _check_mp_cap(self, what: str, limit: int, name: str) -> None:
        """Refuse (before any work) an mpmath-path computation beyond its documented N limit."""
        if self.N > limit:
            raise ValueError(
                f"{what} on the mpmath path is limited to N <= {_n_show(limit)} "
                f"(symhx.distribution.{name}, a work limit); got N={_n_show(self.N)}. "
                f"Use dps=None (float64, N <= {FLOAT_N_LIMIT}), mode()/modes() (any N) or "
                f"symhx.asymptotic_critical_point for huge N")

    def _check_exact_work(self, what: str, limit: int, name: str) -> None:
        """Refuse (before any work) exact sums whose integers would be too large."""
        assert self.fr is not None
        work = self.N * (self.N.bit_length() + self.fr.numerator.bit_length()
                         + self.fr.denominator.bit_length())
        if work > limit:
            raise ValueError(
                f"{what} in exact rational arithmetic would need ~{work:.2g} bit-terms for "
                f"N={_n_show(self.N)}, p={str(self.fr)[:40]} (documented work limit {limit}, "
                f"symhx.distribution.{name}); pass p as a float or mpmath.mpf for the mpmath "
                f"path at dps digits, or dps=None for float64")

    # ----------------------------------------------------------------- subclass hooks
    @property
    def _exact_moments(self) -> tuple[Fraction, Fraction, Fraction]:  # pragma: no cover
        """Exact ``(sum_k W(k), sum_k k W(k), sum_k k**2 W(k))``."""
        raise NotImplementedError

    @property
    def _mp_moments(self) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:  # pragma: no cover
        """``(normaliser or its log, mean, variance)`` at ``dps`` + guard digits."""
        raise NotImplementedError

    @property
    def normaliser(self) -> Any:  # pragma: no cover - interface
        """The normalising constant ``sum_k W(k)`` (``Gamma_{N,p}`` of eq. 8 when simple)."""
        raise NotImplementedError

    @property
    def log_normaliser(self) -> Any:  # pragma: no cover - interface
        """``log`` of :attr:`normaliser`."""
        raise NotImplementedError

    def _exact_partial(self, k: int) -> Fraction:  # pragma: no cover - interface
        raise NotImplementedError

    def _mp_terms(self, lo: int, hi: int) -> list[tuple[int, mpmath.mpf]]:  # pragma: no cover
        """``[(k, P(X = k))]`` at ``dps + guard`` digits for every ``k`` in ``[lo, hi]`` whose
        probability is within ``dps + guard`` digits of the largest one in ``[lo, hi]``."""
        raise NotImplementedError

    def _float_logw(self) -> np.ndarray:  # pragma: no cover - interface
        """float64 unnormalised ``log W(k)``, ``k = 1..N``."""
        raise NotImplementedError

    def _pmf1(self, k: int) -> Any:  # pragma: no cover - interface
        raise NotImplementedError

    def _logpmf1(self, k: int) -> mpmath.mpf:  # pragma: no cover - interface
        raise NotImplementedError

    def modes(self) -> tuple[int, ...]:  # pragma: no cover - interface
        """All maximisers of ``P(X = k)``, increasing (certified exact for every rational p)."""
        raise NotImplementedError

    # ----------------------------------------------------------------- helpers
    def _round(self, x: Any) -> mpmath.mpf:
        with mpmath.workdps(self.dps or 15):
            return +x

    @property
    def _wdps(self) -> int:
        """The working precision of the mpmath path: ``dps`` + guard digits."""
        assert self.dps is not None, "the mpmath path needs an int dps"
        return self.dps + self._guard

    def _wp(self) -> Any:
        """The working-precision context: ``dps`` + guard digits."""
        return mpmath.workdps(self._wdps)

    def _log_fraction(self, x: Fraction) -> mpmath.mpf:
        """``log x`` of an exact positive fraction to ``dps`` significant digits: ``log1p`` of
        the exact ``x - 1`` near 1 (where log x is tiny: log(num) - log(den) would cancel), else
        the difference of the logs with digits for their size."""
        if x == 0:
            return mpmath.ninf
        dps = self.dps or 15
        d = x - 1
        if abs(d) < Fraction(1, 2):
            with mpmath.workdps(dps + 10):
                v = mpmath.log1p(mpmath.mpf(d.numerator) / d.denominator)
        else:  # |log x| > 0.29: log(num) ~ bits * 0.69 cancels about digits(bits) digits
            bits = max(x.numerator.bit_length(), x.denominator.bit_length())
            with mpmath.workdps(dps + 10 + digits_of(bits)):
                v = mpmath.log(x.numerator) - mpmath.log(x.denominator)
        return self._round(v)

    def _map_k(self, k: Any, one: Callable[[int], Any], table: Callable[[np.ndarray], Any]
               ) -> Any:
        """Apply a per-k function to a scalar or an array of k."""
        if self.dps is None:
            if _is_array(k):
                kk = _check_k_array(k)
                if kk.dtype.kind == "O":  # huge ints: clip into the int64 range first
                    kk = np.array([min(max(int(v), 0), self.N + 1) for v in kk.ravel()],
                                  dtype=np.int64).reshape(kk.shape)
                return table(kk)
            k1 = _check_k_scalar(k)
            return table(np.array(min(max(k1, 0), self.N + 1)))[()]
        if _is_array(k):
            kk = _check_k_array(k)
            out = np.empty(kk.shape, dtype=object)
            for idx, v in np.ndenumerate(kk):
                out[idx] = one(int(v))
            return out
        return one(_check_k_scalar(k))

    def _map_q(self, q: Any, one: Callable[[Fraction], int]) -> Any:
        if _is_array(q):
            arr = np.asarray(q, dtype=object)
            out = np.empty(arr.shape, dtype=object if self.dps is not None else np.int64)
            for idx, v in np.ndenumerate(arr):
                out[idx] = one(_check_q(v))
            return out
        return one(_check_q(q))

    # ----------------------------------------------------------------- float64 path
    @cached_property
    def _ftab(self) -> dict[str, np.ndarray]:
        if self.N > FLOAT_N_LIMIT:
            raise ValueError(
                f"the float64 path (dps=None) and rvs() tabulate the whole support; N={self.N} "
                f"is above symhx.distribution.FLOAT_N_LIMIT={FLOAT_N_LIMIT}. Use an int dps for "
                f"the mpmath path, or raise FLOAT_N_LIMIT if you have the memory.")
        from scipy.special import logsumexp

        lw = self._float_logw()
        lp = lw - logsumexp(lw)
        cum = np.minimum(np.logaddexp.accumulate(lp), 0.0)
        logsf_incl = np.minimum(np.logaddexp.accumulate(lp[::-1])[::-1], 0.0)
        tail = np.append(logsf_incl[1:], -np.inf)
        # near log = 0 an accumulated log is only absolutely accurate: there, log1p of the
        # other tail (accumulated from its own small end) keeps the relative accuracy
        with np.errstate(divide="ignore"):
            logcdf = np.where(cum > -_LN2, np.log1p(-np.exp(tail)), cum)
            logsf = np.where(tail > -_LN2, np.log1p(-np.exp(cum)), tail)
        return {"logpmf": lp, "pmf": np.exp(lp), "logcdf": logcdf, "cdf": np.exp(logcdf),
                "logsf": logsf, "sf": np.exp(logsf), "lognorm": np.array(logsumexp(lw))}

    def _ftake(self, name: str, kk: np.ndarray, below: float, above: float) -> np.ndarray:
        tab = self._ftab[name]
        idx = np.clip(kk, 1, self.N) - 1
        out = np.where(kk < 1, below, tab[idx])
        if name in ("pmf", "logpmf"):
            out = np.where(kk > self.N, above, out)
        else:
            out = np.where(kk >= self.N, above, out)
        return np.asarray(out, dtype=float)

    # ----------------------------------------------------------------- pmf and logpmf
    def pmf(self, k: Any) -> Any:
        """``P(X = k)`` (eq. 7); 0 outside ``1..N``.

        >>> import symhx
        >>> symhx.distribution_of(4, "1/2").pmf(1)
        Fraction(16, 39)
        """
        zero: Any = Fraction(0) if self.exact else mpmath.mpf(0)
        return self._map_k(k, lambda k1: self._pmf1(k1) if 1 <= k1 <= self.N else zero,
                           lambda kk: self._ftake("pmf", kk, 0.0, 0.0))

    def logpmf(self, k: Any) -> Any:
        """``log P(X = k)`` (``-inf`` outside ``1..N``); never underflows."""
        return self._map_k(
            k, lambda k1: self._logpmf1(k1) if 1 <= k1 <= self.N else mpmath.ninf,
            lambda kk: self._ftake("logpmf", kk, -np.inf, -np.inf))

    # ----------------------------------------------------------------- cdf and sf
    def _mp_sum(self, lo: int, hi: int) -> mpmath.mpf:
        """``P(lo <= X <= hi)`` at dps + guard digits (relative accuracy, also in the tails)."""
        with self._wp():
            return mpmath.fsum(w for _, w in self._mp_terms(lo, hi))

    def _cdf1(self, k: int) -> Any:
        if k < 1:
            return Fraction(0) if self.exact else mpmath.mpf(0)
        if k >= self.N:
            return Fraction(1) if self.exact else mpmath.mpf(1)
        if self.exact:
            return self._exact_partial(k) / self._exact_moments[0]
        return self._round(self._mp_sum(1, k))

    def _sf1(self, k: int) -> Any:
        if k < 1:
            return Fraction(1) if self.exact else mpmath.mpf(1)
        if k >= self.N:
            return Fraction(0) if self.exact else mpmath.mpf(0)
        if self.exact:
            return 1 - self._cdf1(k)
        return self._round(self._mp_sum(k + 1, self.N))

    def _logsum1(self, k: int, upper: bool) -> mpmath.mpf:
        if self.exact:
            return self._log_fraction(self._sf1(k) if upper else self._cdf1(k))
        if (upper and k >= self.N) or (not upper and k < 1):
            return mpmath.ninf
        if (upper and k < 1) or (not upper and k >= self.N):
            return mpmath.mpf(0)
        s = self._mp_sum(k + 1, self.N) if upper else self._mp_sum(1, k)
        with self._wp():
            if s > 0.5:  # log s is small: log1p of the other tail, summed directly, keeps
                # its relative accuracy (log of s itself would only be absolutely accurate)
                rest = self._mp_sum(1, k) if upper else self._mp_sum(k + 1, self.N)
                return self._round(mpmath.log1p(-rest))
            return self._round(mpmath.log(s))

    def cdf(self, k: Any) -> Any:
        """``P(X <= k)``; exactly ``1 - sf(k)`` for rational ``p``.

        >>> import symhx
        >>> d = symhx.distribution_of(3, "1/2")
        >>> d.cdf(1), d.sf(1), d.cdf(1) + d.sf(1)
        (Fraction(3, 5), Fraction(2, 5), Fraction(1, 1))
        """
        return self._map_k(k, self._cdf1, lambda kk: self._ftake("cdf", kk, 0.0, 1.0))

    def sf(self, k: Any) -> Any:
        """``P(X > k)``, summed from the upper tail (relative accuracy even when tiny)."""
        return self._map_k(k, self._sf1, lambda kk: self._ftake("sf", kk, 1.0, 0.0))

    def logcdf(self, k: Any) -> Any:
        """``log P(X <= k)`` (never underflows on the mpmath path)."""
        return self._map_k(k, lambda k1: self._logsum1(k1, False),
                           lambda kk: self._ftake("logcdf", kk, -np.inf, 0.0))

    def logsf(self, k: Any) -> Any:
        """``log P(X > k)`` (never underflows on the mpmath path)."""
        return self._map_k(k, lambda k1: self._logsum1(k1, True),
                           lambda kk: self._ftake("logsf", kk, 0.0, -np.inf))

    # ----------------------------------------------------------------- quantiles
    def _ppf1(self, q: Fraction) -> int:
        if q == 0:
            return 0
        if q == 1:
            return self.N
        if self.dps is None:
            cdf = self._ftab["cdf"]
            return min(int(np.searchsorted(cdf, float(q), side="left")), self.N - 1) + 1
        # smallest k with cdf(k) >= q (cdf(N) = 1 >= q); on the mpmath path q is resolved to
        # the dps digits of the cdf: a q within 10**(1 - dps) (relative) of cdf(k) counts as equal
        if self.exact:
            self._check_exact_work("a quantile", EXACT_QUANTILE_WORK_LIMIT,
                                   "EXACT_QUANTILE_WORK_LIMIT")
        else:
            self._check_mp_cap("a quantile", MP_QUANTILE_N_LIMIT, "MP_QUANTILE_N_LIMIT")
        qq = q if self.exact else q * (1 - Fraction(10) ** (1 - self.dps))
        lo, hi = 1, self.N
        while lo < hi:
            mid = (lo + hi) // 2
            if _exact_value(self._cdf1(mid)) >= qq:
                hi = mid
            else:
                lo = mid + 1
        return lo

    def _isf1(self, q: Fraction) -> int:
        if q == 1:
            return 0
        if q == 0:
            return self.N
        if self.dps is None:
            sf = self._ftab["sf"]  # non-increasing: smallest k with sf(k) <= q
            return int(np.searchsorted(-sf, -float(q), side="left")) + 1
        if self.exact:
            self._check_exact_work("a quantile", EXACT_QUANTILE_WORK_LIMIT,
                                   "EXACT_QUANTILE_WORK_LIMIT")
        else:
            self._check_mp_cap("a quantile", MP_QUANTILE_N_LIMIT, "MP_QUANTILE_N_LIMIT")
        qq = q if self.exact else q * (1 + Fraction(10) ** (1 - self.dps))
        lo, hi = 1, self.N
        while lo < hi:
            mid = (lo + hi) // 2
            if _exact_value(self._sf1(mid)) <= qq:
                hi = mid
            else:
                lo = mid + 1
        return lo

    def ppf(self, q: Any) -> Any:
        """Percent point function: the smallest ``k`` with ``cdf(k) >= q`` (``ppf(0) = 0``,
        ``ppf(1) = N``), decided on the exact cdf for exact ``p``.  On the mpmath path ``q`` is
        resolved to the ``dps`` digits of the cdf (a ``q`` within a relative ``10**(1 - dps)``
        of ``cdf(k)`` gives ``k``); on the float64 path it is compared with the float cdf.
        ``q`` is read like ``p`` (``"0.5"`` and ``Fraction(1, 2)`` are exact).

        >>> import symhx
        >>> d = symhx.distribution_of(101, "0.02")
        >>> d.ppf(d.cdf(37)), d.median()
        (37, 50)
        """
        return self._map_q(q, self._ppf1)

    def isf(self, q: Any) -> Any:
        """Inverse survival function: the smallest ``k`` with ``sf(k) <= q``."""
        return self._map_q(q, self._isf1)

    def median(self) -> int:
        """``ppf(1/2)``."""
        return self._ppf1(Fraction(1, 2))

    def interval(self, confidence: Any) -> tuple[int, int]:
        """``(ppf((1 - c)/2), ppf((1 + c)/2))``: an interval holding at least the fraction
        ``c = confidence`` of the mass (scipy's convention)."""
        c = check_real(confidence, "confidence", low=0, high=1)
        return self._ppf1((1 - c) / 2), self._ppf1((1 + c) / 2)

    def support(self) -> tuple[int, int]:
        """``(1, N)``: X takes the values ``1..N``."""
        return 1, self.N

    # ----------------------------------------------------------------- moments
    def mean(self) -> Any:
        """``E[X]``: a Fraction when exact, an mpf to ``dps`` digits, or a float."""
        if self.dps is None:
            t = self._ftab["pmf"]
            return float(np.dot(np.arange(1, self.N + 1, dtype=float), t))
        if self.exact:
            g, m1, _ = self._exact_moments
            return m1 / g
        return self._round(self._mp_moments[1])

    def var(self) -> Any:
        """``Var[X]`` (the mpmath path sums ``(k - mean)**2 P(X=k)``: no cancellation)."""
        if self.dps is None:
            t = self._ftab["pmf"]
            ks = np.arange(1, self.N + 1, dtype=float)
            mu_f = float(np.dot(ks, t))
            return float(np.dot((ks - mu_f) ** 2, t))
        if self.exact:
            g, m1, m2 = self._exact_moments
            mu = m1 / g
            return m2 / g - mu * mu
        return self._round(self._mp_moments[2])

    def std(self) -> Any:
        """``sqrt(var())``: an mpf to ``dps`` digits (float for ``dps=None``)."""
        v = self.var()
        if self.dps is None:
            return math.sqrt(v)
        with mpmath.workdps(self.dps + 10):
            s = mpmath.sqrt(mpmath.mpf(v.numerator) / v.denominator if self.exact else v)
        return self._round(s)

    def variance(self) -> Any:
        """Deprecated alias of :meth:`var`."""
        warnings.warn("Distribution.variance() is deprecated: use var() (scipy's name)",
                      DeprecationWarning, stacklevel=2)
        return self.var()

    def entropy(self) -> Any:
        """Shannon entropy ``-sum_k P(X=k) log P(X=k)`` (nats): mpf with absolute error below
        ``10**-dps`` (float for ``dps=None``)."""
        if self.dps is None:
            lp = self._ftab["logpmf"]
            pm = self._ftab["pmf"]
            return float(-np.sum(np.where(pm > 0, pm * lp, 0.0)))
        terms = self._mp_terms(1, self.N)
        with self._wp():
            h = -mpmath.fsum(w * mpmath.log(w) for _, w in terms if w > 0)
        return self._round(h)

    def mode(self) -> int:
        """The smallest maximiser of ``P(X = k)``."""
        return self.modes()[0]

    # ----------------------------------------------------------------- sampling
    def rvs(self, size: Any = None, random_state: Any = None) -> Any:
        """Random draws of X (inverse transform on the float64 cdf, exact to ~1e-16 in
        probability).  ``random_state``: ``None``, a non-negative int seed or a
        :class:`numpy.random.Generator`; the same seed gives the same draws.  Returns an int
        for ``size=None``, else an int64 array of shape ``size``.

        >>> import symhx
        >>> d = symhx.distribution_of(101, 0.02)
        >>> bool((d.rvs(5, random_state=1) == d.rvs(5, random_state=1)).all())
        True
        """
        if isinstance(random_state, np.random.Generator):
            rng = random_state
        else:
            rng = np.random.default_rng(check_seed(random_state, "random_state"))
        if size is not None:
            shape = (check_int(size, "size", minimum=0),) if not isinstance(size, tuple) \
                else tuple(check_int(s, "size", minimum=0) for s in size)
        cdf = self._ftab["cdf"]
        u = rng.random() if size is None else rng.random(shape)
        idx = np.minimum(np.searchsorted(cdf, u, side="right"), self.N - 1) + 1
        return int(idx) if size is None else idx.astype(np.int64)

    def __repr__(self) -> str:
        return (f"{type(self).__name__}(N={self.N}, p={self.p!r}, space={self.space!r}, "
                f"dps={self.dps}, exact={self.exact})")


# --------------------------------------------------------------------------- exact sums
def binary_split(N: int, a: int, b: int, weight: Callable[[int], tuple[int, int]],
                 stop: int | None = None) -> Fraction:
    """``sum_{j=1}^{stop} w(j) prod_{i=1}^{j} a (N-i+1) / b`` exactly, ``w(j) = num/den``
    (``stop`` defaults to ``N``).

    Haible-Papanikolaou binary splitting: O(M(size) log N) instead of N big-Fraction additions.

    >>> binary_split(3, 1, 1, lambda j: (1, j))  # sum_k N!/(k (N-k)!) for N = 3
    Fraction(8, 1)
    """
    stop = N if stop is None else stop
    if stop < 1:
        return Fraction(0)

    def rec(lo: int, hi: int) -> tuple[int, int, int, int]:
        # returns P, Q, B, T with sum_{j=lo}^{hi-1} w(j) prod_{i=lo}^{j} p_i/q_i = T / (B Q)
        if hi - lo == 1:
            num, den = weight(lo)
            pj = a * (N - lo + 1)
            return pj, b, den, num * pj
        mid = (lo + hi) // 2
        P1, Q1, B1, T1 = rec(lo, mid)
        P2, Q2, B2, T2 = rec(mid, hi)
        return P1 * P2, Q1 * Q2, B1 * B2, B2 * Q2 * T1 + B1 * P1 * T2

    _, Q, B, T = rec(1, stop + 1)
    return Fraction(T, B * Q)


class SimpleDistribution(Distribution):
    """X over the simple circuits (eqs. 7-8). Build it with :func:`symhx.distribution_of`."""

    space = "simple"

    def __init__(self, N: int, p: Any, *, dps: int | None = DEFAULT_DPS) -> None:
        self._setup(N, p, dps)

    # ----------------------------------------------------------------- exact path
    def _split(self, weight: Callable[[int], tuple[int, int]], stop: int | None = None
               ) -> Fraction:
        assert self.fr is not None
        return binary_split(self.N, self.fr.numerator, self.fr.denominator, weight, stop)

    @cached_property
    def _exact_moments(self) -> tuple[Fraction, Fraction, Fraction]:
        self._check_exact_work("summing the distribution", EXACT_WORK_LIMIT, "EXACT_WORK_LIMIT")
        gamma = self._split(lambda j: (1, j))
        m1 = self._split(lambda j: (1, 1))
        m2 = self._split(lambda j: (j, 1))
        return gamma, m1, m2

    def _exact_partial(self, k: int) -> Fraction:
        self._check_exact_work("summing the distribution", EXACT_WORK_LIMIT, "EXACT_WORK_LIMIT")
        return self._split(lambda j: (1, j), k)

    def _phi_exact(self, k: int) -> Fraction:
        assert self.fr is not None
        return self.fr**k * math.perm(self.N, k) / k

    # ----------------------------------------------------------------- float64 path
    def _float_logw(self) -> np.ndarray:
        from scipy.special import gammaln

        N = self.N
        ks = np.arange(1, N + 1, dtype=float)
        return ks * _logp_float(self.p, self.fr) + (gammaln(N + 1.0) - gammaln(N - ks + 1.0)) \
            - np.log(ks)

    # ----------------------------------------------------------------- mpmath path
    def _log_phi(self, k: int) -> mpmath.mpf:
        """log Phi(k) at the working precision (caller sets it)."""
        # log Phi(k) = k log p + log N + lgamma(N) - lgamma(N-k+1) - log k, written without
        # the O(N log N) lgamma terms: lgamma(N) - lgamma(N-k+1) = G(N, k-1) + (k-1) log N
        return (k * self._logp + k * self._logN + _at_global_prec(G_mp, self.N, k - 1) - mpmath.log(k))

    @cached_property
    def _ctx(self) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
        """``(p, log p, log N)`` as mpf at ``dps`` + guard digits."""
        with self._wp():
            pm = _mp_of(self.p, self.fr)
            return pm, mpmath.log(pm), mpmath.log(self.N)

    @property
    def _pm(self) -> mpmath.mpf:
        return self._ctx[0]

    @property
    def _logp(self) -> mpmath.mpf:
        return self._ctx[1]

    @property
    def _logN(self) -> mpmath.mpf:
        return self._ctx[2]

    def _runs_above(self, cut: mpmath.mpf, lo: int, hi: int, shift: mpmath.mpf
                    ) -> list[tuple[int, list[mpmath.mpf]]]:
        """``[(k0, [Phi(k) e**-shift for k = k0, k0+1, ...])]`` over the k in ``[lo, hi]``
        with ``log Phi(k) >= cut`` (at most two runs); working precision set by the caller."""
        N, pm = self.N, self._pm
        runs = []
        for a, b in _significant_ranges(N, self.fr, pm, self._log_phi, cut):
            a, b = max(a, lo), min(b, hi)
            if a > b:
                continue
            w = mpmath.exp(self._log_phi(a) - shift)
            ws = [w]
            for k in range(a, b):
                w = w * pm * (N - k) * k / (k + 1)
                ws.append(w)
            runs.append((a, ws))
        return runs

    def _below(self) -> mpmath.mpf:
        return self._wdps * _LN10 + 2 * mpmath.log(self.N) + 5

    def _compute_runs(self, below: mpmath.mpf) -> tuple[mpmath.mpf, list[tuple[int, list]]]:
        """(log of the largest term, [(k0, [Phi(k)/max for k = k0, k0+1, ...]), ...]) keeping
        every term within ``exp(-below)`` of the largest (at most two runs)."""
        with self._wp():
            top = _candidates(self.N, self.fr, self._pm)
            lmax = max(self._log_phi(k) for k in top)
            return lmax, self._runs_above(lmax - below, 1, self.N, lmax)

    @cached_property
    def _mp_moments(self) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
        self._check_mp_cap("summing the distribution", MP_SUM_N_LIMIT, "MP_SUM_N_LIMIT")
        with self._wp():
            below = self._below()
            lmax, runs = self._compute_runs(below)
            s0 = mpmath.fsum(w for _, ws in runs for w in ws)
            self._pmf_runs = [(k0, [w / s0 for w in ws]) for k0, ws in runs]
            s1 = mpmath.fsum(w * (k0 + i) for k0, ws in runs for i, w in enumerate(ws))
            mu = s1 / s0

            def central(runs: list[tuple[int, list]]) -> mpmath.mpf:
                return mpmath.fsum(w * (k0 + i - mu) ** 2 for k0, ws in runs
                                   for i, w in enumerate(ws))

            # dropped terms contribute < N**3 exp(-below) to the variance numerator; when the
            # variance is tiny (p -> 0: all mass at k = 1) widen the window until that is
            # below the requested relative accuracy of the variance itself
            v = central(runs)
            for _ in range(4):
                if v > 0:
                    lv = mpmath.log(v)
                else:  # one term holds all the kept mass: the variance is ~ its neighbours
                    edge = [k for k0, ws in runs for k in (k0 - 1, k0 + len(ws))
                            if 1 <= k <= self.N]
                    if not edge:
                        break
                    lv = max(self._log_phi(k) for k in edge) - lmax
                need = self._wdps * _LN10 - lv + 3 * mpmath.log(self.N) + 5
                if need <= below:
                    break
                below = need
                _, runs = self._compute_runs(below)
                v = central(runs)
            return lmax + mpmath.log(s0), mu, v / s0

    def _mp_terms(self, lo: int, hi: int) -> list[tuple[int, mpmath.mpf]]:
        log_gamma = self._mp_moments[0]
        with self._wp():
            hump = _hump(self.N, self.fr, self._pm)
            cand = {lo, hi} | ({hump[1]} if hump and lo <= hump[1] <= hi else set())
            lmax = max(self._log_phi(k) for k in cand)
            runs = self._runs_above(lmax - self._below(), lo, hi, log_gamma)
        return [(k0 + i, w) for k0, ws in runs for i, w in enumerate(ws)]

    def _logpmf_raw(self, k: int) -> mpmath.mpf:
        """log P(X = k) at the working precision with guard digits (not rounded: exp() of a
        log rounded to dps digits would lose log10|log P| digits)."""
        log_gamma = self._mp_moments[0]
        with self._wp():
            return self._log_phi(k) - log_gamma

    # ----------------------------------------------------------------- per-k values
    def _pmf1(self, k: int) -> Any:
        if self.exact:
            return self._phi_exact(k) / self._exact_moments[0]
        self._mp_moments  # noqa: B018 - fills the cached, normalised significant terms
        for k0, ws in self._pmf_runs:
            if k0 <= k < k0 + len(ws):
                return self._round(ws[k - k0])
        with self._wp():
            return self._round(mpmath.exp(self._logpmf_raw(k)))

    def _logpmf1(self, k: int) -> mpmath.mpf:
        if self.exact:
            return self._log_fraction(self._pmf1(k))
        return self._round(self._logpmf_raw(k))

    @property
    def normaliser(self) -> Any:
        """``Gamma_{N,p}`` (eq. 8): Fraction when exact, else mpf (float for ``dps=None``;
        may overflow there: see :attr:`log_normaliser`)."""
        if self.dps is None:
            return float(np.exp(self._ftab["lognorm"]))
        if self.exact:
            return self._exact_moments[0]
        with self._wp():
            return self._round(mpmath.exp(self._mp_moments[0]))

    @property
    def log_normaliser(self) -> Any:
        """``log Gamma_{N,p}``."""
        if self.dps is None:
            return float(self._ftab["lognorm"])
        if self.exact:
            return self._log_fraction(self._exact_moments[0])
        return self._round(self._mp_moments[0])

    def modes(self) -> tuple[int, ...]:
        """All maximisers of ``P(X = k)``, increasing (exact for rational ``p``).

        >>> SimpleDistribution(101, "0.02").modes()
        (50, 51)
        """
        return simple_modes(self.N, self.fr, self.p)

    def table(self) -> list[tuple[int, Any]]:
        """``[(k, P(X = k)) for k in 1..N]`` (for plots and moderate N).

        The mpmath path runs the term ratio ``Phi(k+1)/Phi(k) = p (N-k) k/(k+1)`` across the
        whole support from ``P(X = 1)``, with guard digits for the ``N`` roundings.
        """
        if self.dps is None:
            return [(k, float(v)) for k, v in enumerate(self._ftab["pmf"], 1)]
        if self.exact:
            return [(k, self._pmf1(k)) for k in range(1, self.N + 1)]
        N = self.N
        with self._wp():
            w = mpmath.exp(self._logpmf_raw(1))
            pm = self._pm
            out = []
            for k in range(1, N + 1):
                out.append((k, self._round(w)))
                w = w * pm * (N - k) * k / (k + 1)
        return out


def _exact_value(x: Any) -> Fraction:
    """The exact rational value of a Fraction or a (finite) mpf computed here.

    Internal values (a cdf far in its tail can be ~10**-2000000) are converted directly from the
    mantissa and exponent, without the input cap of :func:`symhx.validation.to_rational`.
    """
    if isinstance(x, mpmath.mpf):
        return mpf_to_fraction(x)
    exact = to_rational(x, "value")
    assert exact is not None
    return exact


def _mp_of(p: Any, fr: Fraction | None) -> mpmath.mpf:
    """``p`` at the working precision; a rational with huge numerator/denominator (a tiny
    binary float such as ``mpf('1e-1000000')`` has a 3.3-million-bit denominator) is cut to
    ``prec + 64`` bits of each part first (relative error ``2**-(prec+60)``): converting the
    huge ints to mpf directly takes seconds."""
    if fr is None:
        return _at_global_prec(mp_value, p, None)
    keep = mpmath.mp.prec + 64
    a, b = fr.numerator, fr.denominator
    sa, sb = max(0, a.bit_length() - keep), max(0, b.bit_length() - keep)
    return mpmath.ldexp(mpmath.mpf(a >> sa) / (b >> sb), sa - sb)


def _logp_float(p: Any, fr: Fraction | None) -> float:
    """float64 ``log p`` for any size of numerator and denominator."""
    if fr is not None:
        return math.log(fr.numerator) - math.log(fr.denominator)
    with mpmath.workdps(30):
        return float(mpmath.log(_at_global_prec(mp_value, p, None)))


def _at_global_prec(fn: Callable[..., Any], *args: Any) -> Any:
    """``fn(*args)`` of a thread-context helper (symhx._numeric) run at the precision this
    module's mpmath path has set with ``mpmath.workdps``, returned as a global ``mpf``."""
    ctx = thread_mp()
    with ctx.workprec(mpmath.mp.prec):
        return export(fn(*args))


# --------------------------------------------------------------------------- structure of Phi
def _candidates(N: int, fr: Fraction | None, pm: mpmath.mpf) -> list[int]:
    """Indices that may hold the global maximum of Phi: 1 and the hump's local maximum."""
    hump = _hump(N, fr, pm)
    return [1] if hump is None else sorted({1, hump[0], hump[1]})


def _hump(N: int, fr: Fraction | None, pm: Any) -> tuple[int, int, bool] | None:
    """``(j, j + 1, tie)`` with ``j = floor(k_+)`` when the increasing stretch of Phi contains an
    integer (``f(j) >= 0``, so ``Phi(j+1) >= Phi(j)``; ``tie`` when ``f(j) == 0``); else None.

    ``f_{N,p}(k) b = -a k**2 + (N a - b) k - b`` for ``p = a/b``: all in integers. ``p`` is
    ``fr`` when it is not None; else the exact binary value of the mpf ``pm`` (of any context:
    only its bits are read), the value the mpmath sums work with. (The modes at an irrational
    ``p`` are decided by :func:`_irrational_hump` on rational brackets of ``p`` itself.)

    Since ``f(k)`` increases with ``p`` for every ``0 < k < N``, the larger root ``k_+`` and the
    set ``{k : f(k) >= 0}`` grow with ``p``: the result is a monotone function of ``p``.
    """
    # no increasing stretch unless N p > 1 (A > 0 below): decide p < 1/(2N) from the binary
    # exponent first (a tiny p has a numerator/denominator of millions of bits)
    if fr is not None and fr.numerator * 2 * N < fr.denominator:
        return None
    if fr is None:  # the exact value of the mpf pm: (-1)**sign man 2**exp
        sign, man, exp, bc = pm._mpf_
        if not man or sign or exp + bc < -N.bit_length() - 2:  # p <= 0 or p < 2**mag <= 1/(4N)
            return None
        fr = Fraction(man) * Fraction(2) ** exp
    a, b = fr.numerator, fr.denominator
    A = N * a - b
    disc = A * A - 4 * a * b
    if A <= 0 or disc < 0:
        return None
    s = math.isqrt(disc)
    j = (A + s) // (2 * a)
    # j = floor(r_+), r_+ = (A + sqrt(disc)) / (2a): the isqrt may leave it one short
    lhs = 2 * a * (j + 1) - A
    if lhs <= 0 or lhs * lhs <= disc:
        j += 1
    j = min(j, N - 1)

    def fb(k: int) -> int:
        return -a * k * k + A * k - b

    if j < 1 or fb(j) < 0:
        return None
    return j, j + 1, fb(j) == 0


def _log_ratio_iv(N: int, a: int, b: int, K: int) -> Any:
    """Arb ball of ``log Phi(K+1) - log Phi(1) = K log(N p) + G(N, K) - log(K + 1)`` at the
    rational ``p = a/b`` (inside :func:`symhx.certify.arb_prec`)."""
    return K * ((to_arb(N) * a).log() - to_arb(b).log()) + G_arb(N, K) - to_arb(K + 1).log()


def _log_ratio_ball(N: int, pa: Any, K: int) -> Any:
    """:func:`_log_ratio_iv` with ``p`` known as an Arb ball ``pa`` (an irrational); the result
    contains the value for every point of the ball (inside :func:`symhx.certify.arb_prec`)."""
    return K * (to_arb(N) * pa).log() + G_arb(N, K) - to_arb(K + 1).log()


def _compare_with_one(N: int, fr: Fraction, K: int) -> int:
    """Sign of ``Phi(K+1) - Phi(1)`` at the rational ``p = fr``, certified (exact integers on a
    near tie)."""
    a, b = fr.numerator, fr.denominator

    def exact() -> int:
        lhs = a**K * math.perm(N - 1, K)
        rhs = (K + 1) * b**K
        return (lhs > rhs) - (lhs < rhs)

    start = bits_for(N, a.bit_length() + b.bit_length() + 2 * K.bit_length() + 64)
    return certified_sign(lambda: _log_ratio_iv(N, a, b, K), start_bits=start,
                          max_bits=32 * start, exact_fn=exact)


def _irrational_hump(N: int, lo: Fraction, hi: Fraction) -> tuple[int, int, bool] | str | None:
    """The hump of Phi for every ``p`` in ``[lo, hi]``: :func:`_hump` at both ends when they
    agree (it is monotone in ``p``, so it is then constant on the bracket, and no tie lies
    inside: a tie ``f(j) = 0`` happens at the single rational ``p = (j+1)/(j (N-j))``, which
    would separate the ends), else ``"undecided"``."""
    h_lo, h_hi = _hump(N, lo, None), _hump(N, hi, None)
    if h_lo != h_hi or (h_lo is not None and h_lo[2]):
        return "undecided"
    return h_lo


def _irrational_modes(N: int, p: Any) -> tuple[int, ...]:
    """All maximisers of ``Phi_{N,p}(k)`` at a sympy irrational ``p``, proved for ``p`` itself:
    a rigorous Arb ball of ``p`` (:func:`symhx.certify.real_ball`) gives a rational bracket
    ``[lo, hi]``; the hump is located in integers at both ends (:func:`_irrational_hump`) and
    ``Phi(top)`` is compared with ``Phi(1)`` on the ball; the precision doubles until both are
    decided. A true tie ``Phi(top) = Phi(1)`` (``p**K = (K+1)/perm(N-1, K)`` with an algebraic
    ``p``, e.g. ``N = 9``, ``p = 882**(1/3)/42`` ties ``k = 1`` and ``k = 4``) is never
    separated: :class:`UndecidedError` after ``MAX_IRRATIONAL_BITS`` bits."""
    state: dict[str, Any] = {}

    def attempt(bits: int) -> tuple[int, ...] | None:
        with arb_prec(bits):
            pa = real_ball(p)
            bracket = rational_bracket(pa) if pa > 0 else None
            if bracket is None:
                state["why"] = "p is not enclosed in a finite positive ball"
                return None
            if pa.is_exact():  # p is a dyadic rational written as an expression: exactly
                return simple_modes(N, bracket[0], p)
            hump = _irrational_hump(N, *bracket)
            if isinstance(hump, str):  # "undecided"
                state["why"] = ("p lies within the ball's width of a breakpoint "
                                "(k+1)/(k (N-k)) of the mode")
                return None
            if hump is None:
                return (1,)
            top = hump[1]
            d = _log_ratio_ball(N, pa, top - 1)  # log Phi(top) - log Phi(1)
            if d > 0:
                return (top,)
            if d < 0:
                return (1,)
            state["why"] = (f"Phi(1) and Phi({top}) agree to that precision (a true tie when "
                            f"p**{top - 1} = {top}/perm({N - 1}, {top - 1}))")
            return None

    start = 64 + 2 * N.bit_length()
    return decide_with_rising_precision(
        attempt, start_bits=start, max_bits=MAX_IRRATIONAL_BITS,
        undecided=lambda bits: (
            f"the modes of X at the irrational p={str(p)[:60]} (N={_n_show(N)}) are not "
            f"decided at {bits} bits: {state.get('why', '')}; symhx never guesses a tie: pass "
            f"p as an exact rational (Fraction, sympy Rational or decimal string) to have it "
            f"decided exactly"))


def simple_modes(N: int, fr: Fraction | None, p: Any) -> tuple[int, ...]:
    """All maximisers of ``Phi_{N,p}(k)`` (eq. 8), certified: ``fr`` is ``p``'s exact value;
    ``None`` for a sympy irrational ``p``, decided for ``p`` itself on rigorous Arb balls with
    rising precision (:func:`_irrational_modes`; a true tie raises
    :class:`~symhx.certify.UndecidedError`).

    >>> simple_modes(101, Fraction(1, 50), None)
    (50, 51)
    """
    if fr is None:
        return _irrational_modes(N, p)
    hump = _hump(N, fr, None)
    if hump is None:
        return (1,)
    j, top, tie = hump
    local = (j, top) if tie else (top,)
    if top == 1:  # pragma: no cover - top = j + 1 >= 2
        return (1,)
    s = _compare_with_one(N, fr, top - 1)
    if s > 0:
        return local
    if s == 0:
        return tuple(sorted({1, *local}))
    return (1,)


def _significant_ranges(N: int, fr: Fraction | None, pm: mpmath.mpf,
                        log_phi: Callable[[int], mpmath.mpf], cut: mpmath.mpf
                        ) -> list[tuple[int, int]]:
    """Maximal runs ``[lo, hi]`` of k with ``log Phi(k) >= cut`` (Phi is decreasing on
    ``[1, m]``, increasing on ``[m, j+1]``, decreasing after: at most two runs)."""
    hump = _hump(N, fr, pm)

    def last_above(lo: int, hi: int) -> int:
        # Phi decreasing on [lo, hi], log_phi(lo) >= cut: largest k with log_phi(k) >= cut
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if log_phi(mid) >= cut:
                lo = mid
            else:
                hi = mid - 1
        return lo

    def first_above(lo: int, hi: int) -> int:
        # Phi increasing on [lo, hi], log_phi(hi) >= cut: smallest k with log_phi(k) >= cut
        while lo < hi:
            mid = (lo + hi) // 2
            if log_phi(mid) >= cut:
                hi = mid
            else:
                lo = mid + 1
        return lo

    if hump is None:
        return [(1, last_above(1, N))]
    j, top, _ = hump
    # local minimum m: last k <= j with f(k-1) < 0 ... find by bisection on f's sign:
    # Phi(k+1) < Phi(k) iff f(k) < 0; f < 0 on [1, r_-), f >= 0 on [r_-, j]
    a, b = (fr.numerator, fr.denominator) if fr is not None else _frac(pm)
    A = N * a - b

    def fb(k: int) -> int:
        return -a * k * k + A * k - b

    lo, hi = 1, j
    while lo < hi:  # smallest k in [1, j] with f(k) >= 0
        mid = (lo + hi) // 2
        if fb(mid) >= 0:
            hi = mid
        else:
            lo = mid + 1
    m = lo  # Phi decreasing on [1, m], increasing on [m, top], decreasing on [top, N]
    runs: list[tuple[int, int]] = []
    left_end = last_above(1, m) if log_phi(1) >= cut else 0
    if log_phi(top) >= cut:
        start = first_above(m, top)
        end = last_above(top, N)
        if left_end >= start - 1 and left_end > 0:
            runs.append((1, end))
        else:
            if left_end:
                runs.append((1, left_end))
            runs.append((start, end))
    elif left_end:
        runs.append((1, left_end))
    return runs


def _frac(x: mpmath.mpf) -> tuple[int, int]:
    man, exp = x.man_exp
    f = Fraction(man) * Fraction(2) ** exp
    return f.numerator, f.denominator


# --------------------------------------------------------------------------- deprecated names
_MOVED = ("distribution_of", "pmf", "logpmf", "normaliser", "mean", "variance", "mode", "modes")


def __getattr__(name: str) -> Any:
    """``symhx.distribution.mean`` etc. moved to :mod:`symhx.api` (``symhx.mean``): the old
    names still work, with a DeprecationWarning (a lazy forward, not an import of the upper
    layer at load time)."""
    if name in _MOVED:
        warnings.warn(f"symhx.distribution.{name} moved to symhx.{name} (symhx.api.{name})",
                      DeprecationWarning, stacklevel=2)
        import importlib

        return getattr(importlib.import_module("symhx.api"), name)
    raise AttributeError(f"module 'symhx.distribution' has no attribute {name!r}")
