"""The distribution of X, the number of distinct impacts of a circuit, over the simple circuits
(sections 4-5, eqs. 7-8), and the frozen-distribution interface shared by every sample space.

Simple sample space: ``P(X = k) = Phi_{N,p}(k) / Gamma_{N,p}`` with
``Phi_{N,p}(k) = p**k N! / (k (N-k)!)`` and ``Gamma_{N,p} = sum_{j=1}^{N} Phi_{N,p}(j)``.
This module knows nothing of the higher-order spaces (:mod:`symhx.spaces` builds on it); the
user-facing functions that pick a space (``symhx.pmf``, ``symhx.mean``, ...) live in
:mod:`symhx.api`.

Arithmetic
----------
* **Exact** for ``p`` an int, ``Fraction``, sympy ``Rational`` or decimal string, while binary
  splitting is within its work limit (``N (bits of N + bits of p) <= EXACT_WORK_LIMIT``,
  ``N <= EXACT_N_LIMIT``): pmf, cdf, sf, normaliser, mean and variance are ``Fraction``.
  **Beyond it the exact rational p is evaluated on the mpmath path at ``dps`` digits** (results
  are mpf; never the binary neighbour of p): ``mean(10**10, "2e-10", dps=20)`` is
  ``4999999999.0`` to 20 digits of that p.  Quantiles of an exact p beyond
  ``EXACT_QUANTILE_WORK_LIMIT`` use the mpmath-path rule below.
* **mpmath** otherwise (floats and mpf are taken at their exact binary value; sympy irrationals
  at ``dps + digits(N) + 30`` digits): :mod:`symhx.simple_sums` sums the terms *without walking
  them*, for any ``N <= MP_SUM_N_LIMIT = 10**1000`` and any ``p > 0``: short runs of significant
  terms term by term, long ones (width ~ sqrt(N) above the jump, ~1/``|N p - 1|`` below it) by
  Euler-Maclaurin with Gauss-Legendre panels, every error term bounded below ``10**-(dps+guard)``
  of a proved lower bound of the sum (see that module for the bounds).  Everything is relative to
  the largest term, so nothing overflows and ``N p - 1 = 1e-49`` costs no extra digits.  One
  pass gives the normaliser, mean, variance and entropy; ``cdf``/``sf`` sum their own range
  with the digits its size needs (``log Phi`` is needed to absolute accuracy: a range whose terms
  are ``exp(-1e20)`` below the largest term gets 20 more digits, so ``cdf ~ 10**(-10**20)`` at
  N = 10**100 keeps its ``dps`` digits; ``logcdf``/``logsf`` near 0 are ``log1p`` of the other
  tail).  Quantiles: a bracket narrowed by Newton steps on ``sqrt(1 - log C)`` (``C`` the cdf or
  sf, whichever is smaller; linear in k in Gaussian and geometric tails alike), far tails
  decided from bounds without summing; the integer is proved against the sums' error bound, with
  more digits while ``q`` is within it (``q`` is resolved to the ``dps`` digits of the cdf: the
  smallest ``k`` with ``cdf(k) >= q (1 - 10**(1 - dps))``); ``N <= MP_QUANTILE_N_LIMIT =
  10**1000`` (the proof needs ~``dps + digits(N)/2`` digits above the jump, taken at once).
* **float64** for ``dps=None``: numpy arrays over the whole support for ``N <= FLOAT_N_LIMIT``
  (a memory limit of the table; ``log Phi`` from ``gammaln``, ~``1e-16 N log N`` absolute);
  above it, for any N that fits a float, the engine at 17 digits gives one normaliser per
  distribution and ``pmf``/``logpmf`` are numpy over ``k`` (:mod:`symhx.float_terms`,
  ~1e-15 relative in the bulk); ``cdf``/``sf`` and logs are numpy over ``k`` too
  (:mod:`symhx.float_sums`: direct blocks, Gauss-Legendre panels with Euler-Maclaurin ends,
  windows in the far tails; each tail summed from its own end, ~1e-15 relative, logs finite far
  beyond underflow; 1000 distinct ``k`` in ~0.1 s at any N); ``rvs`` still needs the table.
* **mode / modes** are decided exactly for every rational ``p`` (floats and mpf included) and
  any N (``10**100`` too): integer arithmetic locates the local maximum of ``Phi`` and a single
  comparison with ``Phi(1)`` is certified by interval arithmetic (exact integers on a near tie).
  The mode never needs the normaliser.

Costs (2-core machine shared with other work, dps = 50; ``benchmarks/bench_large_n.py``): the
first statistic of an (N, p, dps) costs one full pass, 5-29 ms at N = 10**100 (about 26-29
``critical_point`` calls of the same N above the jump, timed in the same run by
``benchmarks/bench_large_n.py``, up to 84 in the hard case ``N p - 1 ~ N p_c - 1``, where the
head and the hump both weigh) and 0.01-0.26 s at 10**1000 (40-66 calls); the first pass of a
process adds the Gauss-Legendre rules, ~60 ms.  Frozen distributions of
the same (N, p, dps) share that pass, so ``var`` and the normaliser after ``mean`` are free,
``entropy`` is one more pass, and a ``cdf`` then costs one partial sum (6-20 ms at 10**100,
45 ms at 10**1000); a ``cdf``/``sf`` before any full pass sums its tail and the complement
(about one pass: 9-11 ms at 10**100), whose sum serves later partial sums as the normaliser;
a median at dps = 30 takes 0.2 s at 10**100 and ~3 s at 10**1000.

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
import sys
import threading
import warnings
from collections import OrderedDict
from collections.abc import Callable
from fractions import Fraction
from functools import cached_property, lru_cache
from typing import Any

import mpmath
import numpy as np

from symhx._mpctx import export, is_mpf, local, mp
from symhx._numeric import digits_of, mp_value
from symhx.certify import (
    G_arb,
    arb_prec,
    bits_for,
    certified_sign,
    decide_with_rising_precision,
    rational_bracket,
    real_ball,
    to_arb,
)
from symhx.float_sums import FloatSums
from symhx.float_terms import log_phi_diff
from symhx.simple_sums import SimpleSums
from symhx.validation import (
    DEFAULT_DPS,
    InputError,
    check_dps,
    check_int,
    check_N,
    check_p,
    check_real,
    check_seed,
    check_size,
    exact_work_refusal,
    is_exact_type,
    mpf_to_fraction,
    safe_repr,
    show_exact,
    to_rational,
)

__all__ = [
    "EXACT_N_LIMIT",
    "EXACT_QUANTILE_WORK_LIMIT",
    "EXACT_WORK_LIMIT",
    "FLOAT_N_LIMIT",
    "MAX_EXACT_TABLE_N",
    "MAX_TABLE_N",
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
#: largest N for the sums of the mpmath path (moments, ``pmf``, ``cdf``, ``sf``, logs,
#: ``entropy``; :mod:`symhx.simple_sums`): the cost grows with the digits of N (Arb balls of
#: ``log2 N`` bits at every quadrature node), 9-13 ms per pass at N = 10**100 and 0.14-0.18 s
#: at 10**1000 (dps = 50), whatever p, and roughly like dps**2.5 beyond: 0.5-0.8 s at dps 300,
#: 2-4 s at dps 1000, 11-15 s at dps 2000 (N = 10**100 ... 10**1000); ``mode`` and ``modes``
#: take any N.
MP_SUM_N_LIMIT = 10**1000
#: largest N for the quantiles of the mpmath path (``ppf``, ``isf``, ``median``, ``interval``): a
#: Newton search on k (far tails decided from bounds, without summing), then the integer
#: decision proved against the sums' error bound.  Above the jump the cdf moves by only
#: ``~1/sqrt(N)`` per unit of k, so proving ``cdf(k-1) < q <= cdf(k)`` takes about
#: ``dps + digits(N)/2`` digits, which the search takes at once: at dps = 30 a quantile takes
#: 0.01-0.8 s at N = 10**100, ~0.4 s at 10**300 and 1.3-3.3 s above the jump at 10**1000 (sums
#: at ~540 digits; 0.01-0.5 s below it), so the cap is the sums' own, 10**1000.
MP_QUANTILE_N_LIMIT = 10**1000

#: ``table()`` (one row ``(k, P(X = k))`` per k, also ``symhx distribution --table``) on the
#: mpmath path is refused above this N: each row is a pmf at dps digits (10**4 rows at dps = 50
#: take ~4 s); the float64 table (``dps=None``) follows ``FLOAT_N_LIMIT``.
MAX_TABLE_N = 10_000
#: the same for an exact (Fraction) table: row k has ~k log2(N/p) bits, so the table grows like
#: N**2 (2000 rows take ~6 s, 4000 rows ~50 s).
MAX_EXACT_TABLE_N = 2_000

_LN10 = math.log(10)
_LN2 = math.log(2)


def _n_show(N: int) -> str:
    if N < 10**15:
        return str(N)
    if N.bit_length() > 10_000:  # str() would hit Python's 4300-digit limit
        return show_exact(N)
    e = len(str(N)) - 1
    return f"10**{e}" if N == 10**e else f"~10**{e}"


def _p_show(fr: Fraction) -> str:
    """``p`` for a message: its first 40 characters, or 5 significant digits when its digits
    would pass Python's 4300-digit ``str`` limit."""
    if max(fr.numerator.bit_length(), fr.denominator.bit_length()) > 10_000:
        return show_exact(fr)
    return str(fr)[:40]


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

    def _setup(self, N: Any, p: Any, dps: Any, exact_fallback: bool = False) -> None:
        self.N = check_N(N, minimum=1)
        self.fr, self.p = check_p(p)
        self.dps = check_dps(dps, allow_none=True)
        self.exact = self.dps is not None and is_exact_type(p)
        if self.exact and exact_fallback:
            # exact results where binary splitting is within its work limit; beyond it the
            # mpmath path evaluates at the exact rational p (never its binary neighbour)
            assert self.fr is not None
            work = self.N * (self.N.bit_length() + self.fr.numerator.bit_length()
                             + self.fr.denominator.bit_length())
            self.exact = work <= EXACT_WORK_LIMIT and self.N <= EXACT_N_LIMIT
        if self.exact and self.N > EXACT_N_LIMIT:
            raise exact_work_refusal(
                f"exact (rational) arithmetic is limited to N <= {EXACT_N_LIMIT} "
                f"(symhx.distribution.EXACT_N_LIMIT); got N={_n_show(self.N)}")
        # digits lost by the recurrences and the k, k**2 weights
        self._guard = 10 + 2 * digits_of(self.N)

    def _check_mp_cap(self, what: str, limit: int, name: str) -> None:
        """Refuse (before any work) an mpmath-path computation beyond its documented N limit."""
        if self.N > limit:
            raise InputError(
                f"{what} on the mpmath path is limited to N <= {_n_show(limit)} "
                f"(symhx.distribution.{name}, a work limit); got N={_n_show(self.N)}. "
                f"Use mode()/modes() (any N) or symhx.asymptotic_critical_point for huge N")

    def _check_table(self) -> None:
        """Refuse (before any work) a ``table()`` beyond its documented row limit."""
        if self.dps is None:
            limit, name = FLOAT_N_LIMIT, "FLOAT_N_LIMIT"
        elif self.exact:
            limit, name = MAX_EXACT_TABLE_N, "MAX_EXACT_TABLE_N"
        else:
            limit, name = MAX_TABLE_N, "MAX_TABLE_N"
        if self.N > limit:
            head = (f"table() lists one row per k = 1..N: limited to N <= {limit} "
                    f"(symhx.distribution.{name}, a work limit"
                    f"{' of exact rows' if self.exact else ''}); got N={_n_show(self.N)}")
            raise InputError(
                f"{head}. Use pmf(k) on the k you need (an array of k works)"
                f"{', or a float p' if self.exact else ''}",
                cli=f"{head}" + (f"; use --float (mpmath rows up to N = {MAX_TABLE_N})"
                                 if self.exact and self.N <= MAX_TABLE_N else ""))

    def _check_exact_work(self, what: str, limit: int, name: str) -> None:
        """Refuse (before any work) exact sums whose integers would be too large."""
        assert self.fr is not None
        work = self.N * (self.N.bit_length() + self.fr.numerator.bit_length()
                         + self.fr.denominator.bit_length())
        if work > limit:
            raise exact_work_refusal(
                f"{what} in exact rational arithmetic would need ~{work:.2g} bit-terms for "
                f"N={_n_show(self.N)}, p={_p_show(self.fr)} (documented work limit {limit}, "
                f"symhx.distribution.{name})")

    # ----------------------------------------------------------------- subclass hooks
    @property
    def _exact_moments(self) -> tuple[Fraction, Fraction, Fraction]:  # pragma: no cover
        """Exact ``(sum_k W(k), sum_k k W(k), sum_k k**2 W(k))``."""
        raise NotImplementedError

    @property
    def _mp_moments(self) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:  # pragma: no cover
        """``(log normaliser, mean, variance)`` at ``dps`` + guard digits (every space)."""
        raise NotImplementedError

    @property
    def normaliser(self) -> Any:  # pragma: no cover - interface
        """The normalising constant ``sum_k W(k)`` (``Gamma_{N,p}`` of eq. 8 when simple)."""
        raise NotImplementedError

    @property
    def log_normaliser(self) -> Any:  # pragma: no cover - interface
        """``log`` of :attr:`normaliser`."""
        raise NotImplementedError

    @staticmethod
    def _float_exp(log: float) -> float:
        """The float64 :attr:`normaliser` from its log: ``inf`` beyond float64's range (the
        log stays finite), without a warning -- the same in every space."""
        try:
            return math.exp(log)
        except OverflowError:
            return math.inf

    def _exact_partial(self, k: int) -> Fraction:  # pragma: no cover - interface
        raise NotImplementedError

    def _mp_terms(self, lo: int, hi: int) -> list[tuple[int, mpmath.mpf]]:  # pragma: no cover
        """``[(k, P(X = k))]`` at ``dps + guard`` digits for every ``k`` in ``[lo, hi]`` whose
        probability is within ``dps + guard`` digits of the largest one in ``[lo, hi]``."""
        raise NotImplementedError

    def _float_logw(self) -> tuple[np.ndarray, float]:  # pragma: no cover - interface
        """``(log W(k) - shift, shift)``: float64 unnormalised logs, ``k = 1..N``, less a
        constant ``shift`` (a subclass may subtract its largest log before rounding to float64,
        for accuracy); the table adds it back to its log-normaliser."""
        raise NotImplementedError

    def _pmf1(self, k: int) -> Any:  # pragma: no cover - interface
        raise NotImplementedError

    def _logpmf1(self, k: int) -> mpmath.mpf:  # pragma: no cover - interface
        raise NotImplementedError

    def modes(self) -> tuple[int, ...]:  # pragma: no cover - interface
        """All maximisers of ``P(X = k)``, increasing (certified exact for every rational p)."""
        raise NotImplementedError

    def table(self) -> list[tuple[int, Any]]:  # pragma: no cover - interface
        """``[(k, P(X = k)) for k in 1..N]``, refused above the documented row limits
        (``MAX_TABLE_N``, ``MAX_EXACT_TABLE_N``, ``FLOAT_N_LIMIT``)."""
        raise NotImplementedError

    # ----------------------------------------------------------------- helpers
    def _round(self, x: Any) -> mpmath.mpf:
        """``x`` (an mpf of any context) rounded once to ``dps`` digits, as a global mpf."""
        ctx = mp()
        with ctx.workdps(self.dps or 15):
            return export(+local(x))

    def _round_abs(self, x: Any) -> mpmath.mpf:
        """``x`` rounded once to ``dps`` digits after the point (absolute error below
        ``10**-dps``; for the entropy, of size up to ``log N``), as a global mpf."""
        ctx = mp()
        xl = local(x)
        digits = max(0, int(ctx.mag(xl) * 0.30103) + 1) if xl else 0
        with ctx.workdps((self.dps or 15) + digits):
            return export(+xl)

    @property
    def _wdps(self) -> int:
        """The working precision of the mpmath path: ``dps`` + guard digits."""
        assert self.dps is not None, "the mpmath path needs an int dps"
        return self.dps + self._guard

    def _log_fraction(self, x: Fraction) -> mpmath.mpf:
        """``log x`` of an exact positive fraction to ``dps`` significant digits: ``log1p`` of
        the exact ``x - 1`` near 1 (where log x is tiny: log(num) - log(den) would cancel), else
        the difference of the logs with digits for their size."""
        if x == 0:
            return mpmath.ninf
        dps = self.dps or 15
        d = x - 1
        ctx = mp()
        if abs(d) < Fraction(1, 2):
            with ctx.workdps(dps + 10):
                v = ctx.log1p(ctx.mpf(d.numerator) / d.denominator)
        else:  # |log x| > 0.29: log(num) ~ bits * 0.69 cancels about digits(bits) digits
            bits = max(x.numerator.bit_length(), x.denominator.bit_length())
            with ctx.workdps(dps + 10 + digits_of(bits)):
                v = ctx.log(x.numerator) - ctx.log(x.denominator)
        return self._round(v)

    def _map_k(self, k: Any, one: Callable[[int], Any], table: Callable[[np.ndarray], Any]
               ) -> Any:
        """Apply a per-k function to a scalar or an array of k."""
        if self.dps is None:
            if _is_array(k):
                kk = _check_k_array(k)
                if kk.dtype.kind == "O":  # huge ints: clip to [0, N + 1] (int64 if it fits)
                    kk = np.array([min(max(int(v), 0), self.N + 1) for v in kk.ravel()],
                                  dtype=np.int64 if self.N < 2**62 else object
                                  ).reshape(kk.shape)
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
            raise InputError(
                f"the float64 table of the whole support (rvs(), and dps=None where the space "
                f"has no summation engine) is limited to N <= "
                f"symhx.distribution.FLOAT_N_LIMIT={FLOAT_N_LIMIT}; got N={_n_show(self.N)}. "
                f"Use an int dps for the mpmath path, or raise FLOAT_N_LIMIT if you have the "
                f"memory.")
        from scipy.special import logsumexp

        lw, shift = self._float_logw()
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
                "logsf": logsf, "sf": np.exp(logsf), "lognorm": np.array(logsumexp(lw) + shift)}

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
        ctx = mp()
        with ctx.workdps(self._wdps):
            return export(ctx.fsum(w for _, w in self._mp_terms(lo, hi)))

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
        ctx = mp()
        with ctx.workdps(self._wdps):
            if s > 0.5:  # log s is small: log1p of the other tail, summed directly, keeps
                # its relative accuracy (log of s itself would only be absolutely accurate)
                rest = self._mp_sum(1, k) if upper else self._mp_sum(k + 1, self.N)
                return self._round(ctx.log1p(-local(rest)))
            return self._round(ctx.log(local(s)))

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
        # the dps-digit cdf is within a relative 10**-dps of the cdf: the decision allows for
        # that, so a cdf(k) equal to (or just above) the resolved q gives k, never k + 1 by the
        # sign of a rounding error
        slack = 1 if self.exact else 1 + Fraction(10) ** -self.dps
        lo, hi = 1, self.N
        while lo < hi:
            mid = (lo + hi) // 2
            if _exact_value(self._cdf1(mid)) * slack >= qq:
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
        slack = 1 if self.exact else 1 - Fraction(10) ** -self.dps  # as in _ppf1
        lo, hi = 1, self.N
        while lo < hi:
            mid = (lo + hi) // 2
            if _exact_value(self._sf1(mid)) * slack <= qq:
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
        ctx = mp()
        with ctx.workdps(self.dps + 10):
            s = ctx.sqrt(ctx.mpf(v.numerator) / v.denominator if self.exact else local(v))
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
        terms = local(self._mp_terms(1, self.N))
        ctx = mp()
        with ctx.workdps(self._wdps):
            h = -ctx.fsum(w * ctx.log(w) for _, w in terms if w > 0)
        return self._round_abs(h)

    def mode(self) -> int:
        """The smallest maximiser of ``P(X = k)``."""
        return self.modes()[0]

    # ----------------------------------------------------------------- sampling
    def rvs(self, size: Any = None, random_state: Any = None) -> Any:
        """Random draws of X (inverse transform on the float64 cdf, exact to ~1e-16 in
        probability).  ``random_state``: ``None``, a non-negative int seed or a
        :class:`numpy.random.Generator`; the same seed gives the same draws.  Returns an int
        for ``size=None``, else an int64 array of shape ``size`` (at most
        :data:`symhx.validation.MAX_SAMPLE_SIZE` draws per call).

        >>> import symhx
        >>> d = symhx.distribution_of(101, 0.02)
        >>> bool((d.rvs(5, random_state=1) == d.rvs(5, random_state=1)).all())
        True
        """
        if isinstance(random_state, np.random.Generator):
            rng = random_state
        else:
            rng = np.random.default_rng(check_seed(random_state, "random_state"))
        shape = check_size(size)  # at most MAX_SAMPLE_SIZE draws, before any work
        cdf = self._ftab["cdf"]
        u = rng.random() if size is None else rng.random(shape)
        idx = np.minimum(np.searchsorted(cdf, u, side="right"), self.N - 1) + 1
        return int(idx) if size is None else idx.astype(np.int64)

    def __repr__(self) -> str:
        return (f"{type(self).__name__}(N={safe_repr(self.N)}, p={safe_repr(self.p)}, "
                f"space={self.space!r}, dps={self.dps}, exact={self.exact})")


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
        self._setup(N, p, dps, exact_fallback=True)

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
    def _float_logw(self) -> tuple[np.ndarray, float]:
        from scipy.special import gammaln

        N = self.N
        ks = np.arange(1, N + 1, dtype=float)
        return ks * _logp_float(self.p, self.fr) + (gammaln(N + 1.0) - gammaln(N - ks + 1.0)) \
            - np.log(ks), 0.0

    # ----------------------------------------------------------------- mpmath path
    @cached_property
    def _fr_work(self) -> Fraction:
        """``p`` as an exact rational for the summation engine: ``fr`` itself, or for a sympy
        irrational its value at ``dps + digits(N) + 30`` digits (``log Phi(k)`` has condition
        number ``k <= N`` in ``p``)."""
        if self.fr is not None:
            return self.fr
        ctx = mp()
        n = (self.dps or 17) + digits_of(self.N) + 30
        with ctx.workdps(n):
            pm = mp_value(self.p, None)  # a rigorous Arb enclosure's midpoint (no sympy evalf)
        return mpf_to_fraction(export(pm))

    def _engine(self, dps: int | None = None, extra: int = 0) -> SimpleSums:
        """The summation engine of :mod:`symhx.simple_sums` at ``dps`` (default: ``self.dps``)
        relative digits, working with ``extra`` more (see :meth:`_range_engine`)."""
        self._check_mp_cap("summing the distribution", MP_SUM_N_LIMIT, "MP_SUM_N_LIMIT")
        d = self.dps if dps is None else dps
        assert d is not None
        return _shared_engine(self.N, self._fr_work, d, extra)

    @cached_property
    def _mp_moments(self) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
        """``(log Gamma, mean, variance)`` (global mpf with the engine's guard digits)."""
        self._check_mp_cap("summing the distribution", MP_SUM_N_LIMIT, "MP_SUM_N_LIMIT")
        assert self.dps is not None
        moments, self._mp_extra = _shared_moments(self.N, self._fr_work, self.dps)
        return moments

    @property
    def _mp_norm(self) -> tuple[Any, Any]:
        """``(S0, log S0)``, ``S0 = sum_k Phi(k)/Phi(c)`` (global mpf, the engine's digits): from
        the moments' pass if it ran, else from a pass of the weight 1 alone (what a pmf, a
        cdf or the entropy needs costs less than the moments)."""
        got = self.__dict__.get("_mp_extra")
        if got is None:
            eng = self._engine()
            ctx = mp()
            with ctx.workdps(eng.W):
                total = _engine_total(eng)
                got = self.__dict__["_mp_extra"] = export((total, ctx.log(total)))
        return got

    def _mp_sum(self, lo: int, hi: int) -> Any:
        """``P(lo <= X <= hi)`` at the engine's precision (relative accuracy, tails too: a
        range far in a tail is summed with the digits its magnitude needs).  A tail asked for
        before any full pass is summed with its complement (two partial sums cost about one
        pass): their sum is the normaliser, kept on the engine for later partial sums."""
        lo, hi = max(lo, 1), min(hi, self.N)
        first = self._tail_with_complement(lo, hi)
        if first is not None:
            return first[0]
        return self._range_sum(lo, hi)[0]

    def _tail_with_complement(self, lo: int, hi: int, dps: int | None = None
                              ) -> tuple[Any, int] | None:
        """``(P(lo <= X <= hi), working digits)`` for a tail (``lo == 1`` or ``hi == N``) when
        the engine at ``dps`` has no normaliser yet and the tail needs no extra digits: the tail
        and its complement (two partial sums, about one pass), whose sum is kept on the engine
        as the normaliser of later partial sums; else None."""
        eng = self._engine(dps)
        if "_total" in eng.__dict__ or (lo == 1) == (hi == self.N) \
                or self._range_engine(lo, hi, dps) is not eng:
            return None
        ctx = mp()
        rlo, rhi = (hi + 1, self.N) if lo == 1 else (1, lo - 1)
        reng = self._range_engine(rlo, rhi, dps)
        with ctx.workdps(eng.W):
            part = _partial_sum(eng, lo, hi)
            if reng is eng:
                rest = _partial_sum(eng, rlo, rhi)
            else:  # the complement lies far in the other tail: it needs the digits of its
                # |log Phi| (summed by its own engine; same reference c), unless its bound
                # (largest term times length) is already below the sum's error
                if _below_error(reng, rlo, rhi, part, eng.R):
                    rest = ctx.mpf(0)
                else:
                    with ctx.workdps(reng.W):
                        rest_w = export(_partial_sum(reng, rlo, rhi))
                    rest = local(rest_w)
            total = eng.__dict__.setdefault("_total", part + rest)
            return export(part / total), eng.W

    def _logpmf_raw(self, k: int) -> Any:
        """log P(X = k) with the engine's guard digits (not rounded): ``log Phi(k)`` to
        absolute accuracy, with more digits when ``|log Phi(k)/Phi(c)|`` is large."""
        ls0 = local(self._mp_norm[1])
        eng = self._engine()
        ctx = mp()
        big = self._range_engine(k, k)
        if big is not eng:  # more digits for log Phi(k); the normaliser keeps its own (the
            with ctx.workdps(big.W):  # engines of one (N, p) share the reference c)
                return export(big.D(k) - ls0)
        with ctx.workdps(eng.W):
            return export(eng.D(k) - ls0)

    # ----------------------------------------------------------------- per-k values
    def _pmf1(self, k: int) -> Any:
        if self.exact:
            return self._phi_exact(k) / self._exact_moments[0]
        ctx = mp()  # (dps=None never comes here: its pmf is the numpy path of _ftake)
        with ctx.workdps(self._engine().W):
            return self._round(ctx.exp(local(self._logpmf_raw(k))))

    def _logpmf1(self, k: int) -> Any:
        if self.exact:
            return self._log_fraction(self._pmf1(k))
        return self._round(self._logpmf_raw(k))

    def entropy(self) -> Any:
        """Shannon entropy ``-sum_k P(X=k) log P(X=k)`` (nats): mpf with absolute error below
        ``10**-dps`` (float for ``dps=None``): a pass of its own over ``Phi log Phi`` (the
        moments' pass leaves it out: a log per directly summed term and the bounds of ``log``
        weights roughly double that pass), which also sums the normaliser if no pass has."""
        if self.dps is None:
            if self._beyond_table:
                return float(self._float_engine.entropy())
            return super().entropy()
        self._engine()  # the cap
        return self._round_abs(_shared_entropy(self.N, self._fr_work, self.dps))

    @property
    def normaliser(self) -> Any:
        """``Gamma_{N,p}`` (eq. 8): Fraction when exact, else mpf (float for ``dps=None``;
        may overflow there: see :attr:`log_normaliser`)."""
        if self.dps is None:
            return self._float_exp(self.log_normaliser)
        if self.exact:
            return self._exact_moments[0]
        ctx = mp()
        with ctx.workdps(self._engine().W):
            return self._round(ctx.exp(local(self._mp_log_gamma)))

    @property
    def log_normaliser(self) -> Any:
        """``log Gamma_{N,p}``."""
        if self.dps is None:
            if self._beyond_table:
                return float(self._float_engine.log_normaliser)
            return float(self._ftab["lognorm"])
        if self.exact:
            return self._log_fraction(self._exact_moments[0])
        return self._round(self._mp_log_gamma)

    @property
    def _mp_log_gamma(self) -> Any:
        """``log Gamma = log Phi(c) + log S0`` (global mpf, the engine's digits): from the
        moments' pass if it ran, else from the normaliser's pass of weight 1."""
        if "_mp_moments" in self.__dict__:
            return self._mp_moments[0]
        eng = self._engine()
        ls0 = self._mp_norm[1]
        ctx = mp()
        with ctx.workdps(eng.W):
            return export(eng.log_phi_ref() + local(ls0))

    def modes(self) -> tuple[int, ...]:
        """All maximisers of ``P(X = k)``, increasing (exact for rational ``p``).

        >>> SimpleDistribution(101, "0.02").modes()
        (50, 51)
        """
        return simple_modes(self.N, self.fr, self.p)

    def table(self) -> list[tuple[int, Any]]:
        """``[(k, P(X = k)) for k in 1..N]`` (for plots and moderate N: refused above
        ``MAX_TABLE_N``, ``MAX_EXACT_TABLE_N`` for exact rows, ``FLOAT_N_LIMIT`` for
        ``dps=None``)."""
        self._check_table()
        if self.dps is None:
            return [(k, float(v)) for k, v in enumerate(self._ftab["pmf"], 1)]
        return [(k, self._pmf1(k)) for k in range(1, self.N + 1)]

    # ----------------------------------------------------------------- float64 beyond the table
    @property
    def _beyond_table(self) -> bool:
        """The float64 path (``dps=None``) above ``FLOAT_N_LIMIT``: no table of the support;
        moments and quantiles from the 17-digit engine, the rest vectorised."""
        return self.dps is None and self.N > FLOAT_N_LIMIT

    @cached_property
    def _float_engine(self) -> SimpleDistribution:
        """For ``dps=None`` and ``N > FLOAT_N_LIMIT``: the summation engine at 17 digits, its
        results rounded to float64 (no table of the support); refused for an N beyond the
        float64 range (the mean would be inf)."""
        if self.N > sys.float_info.max:
            raise InputError(
                f"the float64 path (dps=None) needs N to fit a float64 (N <= 1.8e308); got "
                f"N={_n_show(self.N)}. Use an int dps for the mpmath path (N <= "
                f"{_n_show(MP_SUM_N_LIMIT)}, symhx.distribution.MP_SUM_N_LIMIT)")
        return SimpleDistribution(self.N, self.p, dps=17)

    def _ftake(self, name: str, kk: np.ndarray, below: float, above: float) -> np.ndarray:
        """float64 values beyond ``FLOAT_N_LIMIT``, vectorised over ``k``: pmf and logpmf from
        :func:`symhx.float_terms.log_phi_diff` minus the engine's log-normaliser (one scalar per
        distribution); cdf, sf and their logs from the lower and upper sums
        ``L(k), U(k)`` of :class:`symhx.float_sums.FloatSums` (no engine work after the
        normaliser's pass): ``cdf = L/(L + U)``, ``sf = U/(L + U)`` (so ``cdf + sf = 1`` to
        rounding, each keeping its relative accuracy in its own tail), and the log forms as
        ``-log1p`` of the other tail's ratio near 0.  ``k < 1`` and ``k >= N`` (``> N`` for
        pmf) give ``below`` and ``above``."""
        if not self._beyond_table:
            return super()._ftake(name, kk, below, above)
        edge = self.N if name in ("pmf", "logpmf") else self.N - 1
        inside = (kk >= 1) & (kk <= edge)
        out = np.where(kk < 1, below, above).astype(float)
        if not inside.any():
            return out
        ks = kk[inside]
        if name in ("pmf", "logpmf"):
            c, lpx, ls0 = self._float_reference
            lv = log_phi_diff(self.N, c, lpx, ks) - ls0
            out[inside] = np.exp(lv) if name == "pmf" else lv
            return out
        lo, up = self._float_sums.log_tails(ks)
        tot = np.logaddexp(lo, up)
        with np.errstate(divide="ignore"):  # near log = 0: -log1p of the other tail's ratio
            logcdf = np.where(lo >= up, -np.log1p(np.exp(np.minimum(up - lo, 0.0))), lo - tot)
            logsf = np.where(up >= lo, -np.log1p(np.exp(np.minimum(lo - up, 0.0))), up - tot)
        val = {"cdf": np.exp(logcdf), "sf": np.exp(logsf), "logcdf": logcdf,
               "logsf": logsf}[name]
        out[inside] = val
        return out

    @cached_property
    def _float_sums(self) -> FloatSums:
        """The float64 partial sums beyond ``FLOAT_N_LIMIT`` (:mod:`symhx.float_sums`),
        relative to the engine's reference ``c``."""
        c, lpx, _ = self._float_reference
        return FloatSums(self.N, self._float_engine._fr_work, c, lpx)

    @cached_property
    def _float_reference(self) -> tuple[int, float, float]:
        """``(c, log(p (N + 1 - c)), log sum_k Phi(k)/Phi(c))`` of the 17-digit engine: what
        the vectorised float64 pmf needs besides ``k``."""
        eng = self._float_engine
        ls0 = eng._mp_norm[1]  # the one pass that gives the normaliser (weight 1)
        c = eng._engine().c
        fr = eng._fr_work
        ctx = mp()
        with ctx.workdps(30):
            lpx = ctx.log(ctx.mpf(fr.numerator) * (self.N + 1 - c)) - ctx.log(fr.denominator)
            return c, float(lpx), float(local(ls0))

    def mean(self) -> Any:
        """``E[X]``: a Fraction when exact, an mpf to ``dps`` digits, or a float."""
        if self._beyond_table:
            return float(self._float_engine.mean())
        return super().mean()

    def var(self) -> Any:
        """``Var[X]`` (one pass of central sums on the mpmath path: no cancellation)."""
        if self._beyond_table:
            return float(self._float_engine.var())
        return super().var()

    # ----------------------------------------------------------------- quantiles (mpmath)
    def _ppf1(self, q: Fraction) -> int:
        if self._beyond_table and 0 < q < 1:
            return int(self._float_engine._ppf1(q))
        if self.dps is None or q in (0, 1) or (self.exact and self._exact_quantiles_ok()):
            return super()._ppf1(q)
        return self._quantile_mp(q * (1 - Fraction(10) ** (1 - self.dps)), upper=False)

    def _isf1(self, q: Fraction) -> int:
        if self._beyond_table and 0 < q < 1:
            return int(self._float_engine._isf1(q))
        if self.dps is None or q in (0, 1) or (self.exact and self._exact_quantiles_ok()):
            return super()._isf1(q)
        return self._quantile_mp(q * (1 + Fraction(10) ** (1 - self.dps)), upper=True)

    def _exact_quantiles_ok(self) -> bool:
        assert self.fr is not None
        work = self.N * (self.N.bit_length() + self.fr.numerator.bit_length()
                         + self.fr.denominator.bit_length())
        return work <= EXACT_QUANTILE_WORK_LIMIT

    def _quantile_mp(self, qq: Fraction, upper: bool) -> int:
        """The smallest ``k`` with ``cdf(k) >= qq`` (``upper``: ``sf(k) <= qq``).

        A bracket ``[lo, hi]`` (the answer in ``(lo, hi]``) that only shrinks, narrowed by
        Newton steps on ``log C(k)`` (``C`` the cdf or sf; its log-slope is ``pmf/C``), by a
        bisection (geometric while ``hi > 4 lo``) when a step leaves the bracket or stalls.  A
        ``k`` far in a tail is decided from bounds, without summing: the largest term ``f_max``
        of the range (a few evaluations of ``log Phi``) gives ``f_max <= C <= len f_max``.  Near
        the answer ``C(k)`` is summed by :mod:`symhx.simple_sums` with the digits its
        magnitude needs (:meth:`_range_engine`), and the final decision ``C(k-1)`` vs ``C(k)``
        is checked against the sums' relative error bound; a margin inside it repeats the
        decision at once with the digits that resolve one unit of ``k`` there (``dps`` plus
        those of ``C/pmf``; at least 20 more, up to ``dps + digits(N) + 40``), so rounding never
        decides the integer: a ``C(k)`` still within ``10**(4 - W)`` of the target with those
        digits is a tie (``q`` built from the exact cdf), which reaches it: ``k``.  About 5-15
        partial sums per quantile."""
        self._check_mp_cap("a quantile", MP_QUANTILE_N_LIMIT, "MP_QUANTILE_N_LIMIT")
        N = self.N
        ctx = mp()
        dps = self.dps or 17
        # the condition at k, on either side: L(k) = P(X <= k) >= tL  <=>  U(k) = 1 - L(k) <= tU
        tL, tU = (1 - qq, qq) if upper else (qq, 1 - qq)
        logt = {side: _flog(ctx, t) for side, t in (("L", tL), ("U", tU))}
        work_dps = dps  # raised while a decision is within rounding of the target

        def far_step(side: str, lc: Any, ledge: Any) -> Any:
            """A Newton step on ``g = sqrt(1 - log V)`` (``V`` = L or U), linear in ``k`` in a
            Gaussian tail (``log V ~ -(k - mu)**2 / (2 var)``) and in a geometric one alike;
            ``d log V/dk = +-pmf/V`` (``lc``, ``ledge``: ``log V`` and ``log pmf`` at the edge,
            mpf with the bits their size needs: far out they are ~N and only their difference
            is small)."""
            if not ctx.isfinite(lc) or not math.isfinite(logt[side]):
                return None
            lc = min(lc, 0)
            ls = ledge - lc
            with ctx.workprec(max(64, ctx.mag(lc) + 64)):
                g, gs = ctx.sqrt(1 - lc), ctx.sqrt(1 - ctx.mpf(logt[side]))
                diff = g - gs
            with ctx.workprec(64):
                slope = ctx.exp(ls)
                if not slope:
                    return None
                return 2 * g * diff / (slope if side == "L" else -slope)

        def ok_of(k: int) -> tuple[bool, Any, bool, int]:
            """(``k`` satisfies the condition, a Newton step or None, the decision is certain,
            the digits that resolve one unit of ``k`` there: ``dps`` plus those of
            ``C/pmf(edge)``) from the smaller side, at ``work_dps`` digits."""
            if k < 1:
                return (tL <= 0, None, True, 0)
            if k >= N:
                return (True, None, True, 0)
            eng = self._engine(work_dps)
            ranges = {"L": (1, k), "U": (k + 1, N)}
            lmax = {sd: eng.log_max(*r) for sd, r in ranges.items()}  # relative to Phi(c)
            side = "L" if lmax["L"] < lmax["U"] else "U"
            lo_, hi_ = ranges[side]
            edge = hi_ if side == "L" else lo_
            # the first sum at these digits: the side and its complement (about one pass),
            # not a full pass for the normaliser and then the side again
            summed = self._tail_with_complement(lo_, hi_, work_dps)
            with ctx.workdps(eng.W):
                ls0 = ctx.log(_engine_total(eng))
            with ctx.workprec(64 + eng.abs_bits(edge, edge)):
                ledge = eng.D(edge) - ls0
                lm = lmax[side] - ls0  # log(largest term / sum)
                ub = lm + math.log(hi_ - lo_ + 1)
            if summed is None and (ub < logt[side] - 1 or lm > logt[side] + 1):  # decided
                small = ub < logt[side] - 1  # by the bounds
                okv = small if side == "U" else not small
                return (okv, far_step(side, ub if small else lm, ledge), True, 0)
            val, W = summed if summed is not None else self._range_sum(lo_, hi_, work_dps)
            with ctx.workdps(W):
                val = local(val)
                t = tL if side == "L" else tU
                target = ctx.mpf(t.numerator) / t.denominator
                okv = bool(val >= target) if side == "L" else bool(val <= target)
                certain = abs(val - target) > abs(target) * ctx.mpf(10) ** (4 - W)
                if val <= 0:
                    return (okv, None, certain, 0)
                lc = ctx.log(val)
                need = dps + int(max(float(lc - ledge), 0) / _LN10) + 10
                if abs(lc - logt[side]) < 0.5:  # linear Newton step at the working precision
                    fk = ctx.exp(eng.D(edge) - ls0)
                    step = (target - val) / fk if side == "L" else (val - target) / fk
                    return (okv, step, certain, need)
            with ctx.workprec(64 + eng.abs_bits(edge, edge)):
                return (okv, far_step(side, lc, ledge), certain, need)

        lo, hi = 0, N  # not ok(lo), ok(hi): the answer is in (lo, hi]
        k = self._quantile_guess(qq, upper)
        top = dps + digits_of(N) + 40
        skip = 0
        last_move = 0  # the size of the previous Newton move
        newton_steps = 0
        for _ in range(8 * N.bit_length() + 64):
            if hi - lo <= 1:
                break
            k = min(max(k, lo + 1), hi - 1)
            okv, step, certain, need = ok_of(k)
            if not certain:  # within rounding of the target: more digits, same k; at once
                # those that resolve one unit of k (~digits(N)/2 above the jump), not a ladder
                # of full passes.  Still within 10**(4 - W) of the target there: a tie (only a
                # q built from the exact cdf makes one), and a tie reaches the target, so k
                # (k - 1 is a whole pmf(k) away, far beyond those digits); never a coin toss of
                # the rounding
                if work_dps >= top:
                    return k
                work_dps = min(top, max(work_dps + 20 + work_dps // 2, need))
                continue
            if okv:
                hi = k
            else:
                lo = k
            if hi - lo <= 1:
                break
            nk = None
            if step is not None and not skip and abs(step) < hi - lo:
                nk = k + int(step)  # exact (nint would round to the context's 53 bits)
                if nk == k:
                    nk = k - 1 if okv else k + 1
                move = abs(nk - k)
                # Newton converges when its moves shrink (one-sided convergence leaves the
                # bracket as wide as it was); moves that do not halve mean a second bump or a
                # flat stretch: bisect
                if newton_steps >= 3 and 2 * move > last_move:
                    nk, skip = None, 1
                last_move = move
            if nk is None or not lo < nk < hi:  # bisect; after a failed Newton step, twice
                skip = 0 if skip else 1
                nk = math.isqrt(max(lo, 1) * hi) if hi > 4 * max(lo, 1) else (lo + hi) // 2
                newton_steps = 0
            else:
                skip = 0
                newton_steps += 1
            k = nk
        return hi

    def _range_engine(self, lo: int, hi: int, dps: int | None = None) -> SimpleSums:
        """The summation engine for a sum over ``[lo, hi]``: ``dps`` relative digits, worked
        with the digits of the largest ``|log Phi(k)/Phi(c)|`` of the range on top (absolute
        accuracy of ``log Phi`` is what a sum's relative accuracy needs; far in a tail at huge
        N it is ~N), so a cdf of ``10**(-10**20)`` keeps its ``dps`` digits; its cuts and
        panels aim at ``dps`` digits only."""
        d = self.dps if dps is None else dps
        assert d is not None
        eng = self._engine(d)
        extra = _extra_digits(eng.log_max(lo, hi))
        return eng if extra == 0 else self._engine(d, extra)

    def _range_sum(self, lo: int, hi: int, dps: int | None = None) -> tuple[Any, int]:
        """``P(lo <= X <= hi)`` (global mpf) at ``dps`` (default: the distribution's) digits
        relative to itself, and the working digits of the engine that summed it."""
        eng = self._range_engine(lo, hi, dps)
        base = self._engine(self.dps if dps is None else dps)
        ctx = mp()
        with ctx.workdps(eng.W):
            s = _partial_sum(eng, lo, hi)
            # the normaliser only divides: its own digits suffice (the extra digits are for
            # the absolute accuracy of log Phi over the range; every engine of one (N, p) has
            # the same reference c, the hump's top or 1)
            if (dps is None or dps == self.dps) and "_total" not in base.__dict__:
                total = local(self._mp_norm[0])  # a pass (of any thread), or one of weight 1
            else:
                total = _engine_total(base)
            return export(s / local(total)), min(eng.R, base.R)

    def _light_head_hump(self) -> tuple[int, Any] | None:
        """``(top, sigma)`` of the hump (the width at its top, 64 bits) when the head is
        provably light (its terms times their number below ``e**-5`` of the top's height
        times the width), else None."""
        top = self.mode()
        eng = self._engine()
        if top <= 1 or eng.c != top:
            return None
        ctx = mp()
        with ctx.workprec(64 + eng.abs_bits(1, top)):
            sig = eng._sigma_at(top)
            head = eng.D(1) + ctx.log(eng.valley())
            return (top, sig) if head < ctx.log(sig) - 5 else None

    def _quantile_guess(self, qq: Fraction, upper: bool) -> int:
        """A start for the Newton iteration: the normal approximation around the hump's top
        with its width (no pass) when the head is provably light (its terms times their number
        below ``e**-5`` of the top's height times the width), else around the mean."""
        from statistics import NormalDist

        ctx = mp()
        top = self.mode()
        mu = var = None
        hump = self._light_head_hump() if "_mp_moments" not in self.__dict__ else None
        if hump is not None:
            mu, var = hump[0], hump[1] ** 2
        if mu is None:
            mu, var = self._mp_moments[1], self._mp_moments[2]
            if top > 1:  # the hump's top is exact; the mean is only dps digits of ~N
                mu = top
        q = min(max(float(qq), 1e-300), 1 - 1e-16)
        z = NormalDist().inv_cdf(q)
        if upper:
            z = -z
        with ctx.workdps(digits_of(self.N) + 20):
            g = local(mu) + z * ctx.sqrt(max(local(var), 0))
            return int(min(max(ctx.nint(g), 1), self.N))

#: frozen distributions of the same (N, p, dps) share the summation engine and its one full
#: pass (``symhx.mean(N, p)`` then ``symhx.var(N, p)`` or ``symhx.cdf(N, p, k)`` sum the
#: hump once).  The one-pass results are exported (global mpf, immutable) and shared by every
#: thread; an engine holds mpf of the context of the thread that built it, so engines are
#: cached per thread.
_SHARED_CACHE_SIZE = 32
_ENGINES = threading.local()


def _shared_engine(N: int, fr: Fraction, dps: int, extra: int = 0) -> SimpleSums:
    """The summation engine of :mod:`symhx.simple_sums` for ``(N, p, dps)`` working with
    ``extra`` more digits (this thread's)."""
    cache = _ENGINES.__dict__.setdefault("lru", OrderedDict())
    key = (N, fr, dps, extra)
    eng = cache.get(key)
    if eng is None:
        hump = _hump(N, fr, None)
        eng = cache[key] = SimpleSums(N, fr, dps, None if hump is None else hump[1], extra)
        while len(cache) > _SHARED_CACHE_SIZE // 4:
            cache.popitem(last=False)
    else:
        cache.move_to_end(key)
    return eng


@lru_cache(maxsize=_SHARED_CACHE_SIZE)
def _shared_moments(N: int, fr: Fraction, dps: int) -> tuple[tuple[Any, Any, Any],
                                                            tuple[Any, Any]]:
    """One pass over the support: ``(log Gamma, mean, variance)`` and ``(Gamma relative to
    the reference term, its log)``, exported with the engine's guard digits."""
    eng = _shared_engine(N, fr, dps)
    ctx = mp()
    with ctx.workdps(eng.W):
        s0, s1, s2 = eng.sums(1, N, (0, 1, 2))
        eng.__dict__.setdefault("_total", s0)  # the normaliser of later partial sums
        r1 = s1 / s0
        log_s0 = ctx.log(s0)
        extra = export((s0, log_s0))
        return export((eng.log_phi_ref() + log_s0, eng.c + r1, s2 / s0 - r1 * r1)), extra


@lru_cache(maxsize=_SHARED_CACHE_SIZE)
def _shared_entropy(N: int, fr: Fraction, dps: int) -> Any:
    """``-sum_k P(k) log P(k) = log S0 - S3/S0`` with ``S3 = sum_k Phi(k)/Phi(c) log(...)``: its
    own pass (exported with the engine's guard digits), which also gives ``S0`` unless the
    moments' pass already has."""
    eng = _shared_engine(N, fr, dps)
    ctx = mp()
    with ctx.workdps(eng.W):
        total = eng.__dict__.get("_total")
        if total is None:
            s0, s3 = eng.sums(1, N, (0, 3))
            eng.__dict__["_total"] = s0
        else:
            s0, s3 = total, eng.sums(1, N, (3,))[0]
        return export(ctx.log(s0) - s3 / s0)


def _flog(ctx: Any, t: Fraction) -> float:
    """``log t`` of a Fraction in ``[0, 1]`` as a float (``-inf`` at 0)."""
    if t <= 0:
        return -math.inf
    with ctx.workprec(64):
        return float(ctx.log(ctx.mpf(t.numerator)) - ctx.log(ctx.mpf(t.denominator)))


def _partial_sum(eng: SimpleSums, lo: int, hi: int) -> Any:
    """``sum_{k=lo}^{hi} Phi(k)/Phi(c)`` at the engine's working precision, from an earlier sum
    of the same engine that shares an end when one is near (the steps of a quantile search
    move one end by a little): the earlier sum plus or minus the stretch between, when the
    stretch is shorter than the range and, if subtracted, under half the earlier sum (so no
    digit is lost); else summed whole.  Sums are cached on the engine (engines are per
    thread)."""
    cache: dict[tuple[int, int], Any] = eng.__dict__.setdefault("_partials", {})
    got = cache.get((lo, hi))
    if got is not None:
        return got
    best = None
    for (a, b), v in cache.items():
        if a == lo and b != hi:
            gap = abs(b - hi)
        elif b == hi and a != lo:
            gap = abs(a - lo)
        else:
            continue
        if gap < hi - lo + 1 and (best is None or gap < best[0]):
            best = (gap, a, b, v)
    total = None
    if best is not None:
        _, a, b, v = best
        if a == lo:  # the same left end: add or remove (b, hi] / (hi, b]
            grow, stretch = (hi > b), ((b + 1, hi) if hi > b else (hi + 1, b))
        else:  # the same right end: [lo, a) / [a, lo)
            grow, stretch = (lo < a), ((lo, a - 1) if lo < a else (a, lo - 1))
        # the digits of |log Phi| the stretch's terms need beyond the engine's
        short = _extra_digits(eng.log_max(*stretch)) > eng.W - eng.R
        light = _log_sum_bound(eng, *stretch) < mp().log(v) - 1  # provably under half the sum
        if _below_error(eng, *stretch, v, eng.R):  # far in a tail, perhaps beyond its digits
            total = v
        elif not short and (grow or light):
            d = eng.sums(*stretch, (0,))[0]
            if grow:
                total = v + d
            elif 2 * d <= v:
                total = v - d
    if total is None:
        total = eng.sums(lo, hi, (0,))[0]
    if len(cache) > 64:
        cache.clear()
    cache[(lo, hi)] = total
    return total


def _extra_digits(log_max: Any) -> int:
    """The digits beyond ``dps`` that a sum whose largest term is ``exp(log_max)`` relative to
    ``Phi(c)`` needs (``log Phi`` to absolute accuracy: the digits of ``|log_max|``)."""
    lm = abs(log_max)
    return 0 if lm < 10 else int(mp().mag(lm) * 0.30103) + 2


def _log_sum_bound(eng: SimpleSums, lo: int, hi: int) -> Any:
    """An upper bound of ``log sum_{k=lo}^{hi} Phi(k)/Phi(c)``: the largest term times the
    number of terms."""
    ctx = mp()
    with ctx.workprec(64 + eng.abs_bits(lo, hi)):
        return eng.log_max(lo, hi) + ctx.log(hi - lo + 1)


def _below_error(eng: SimpleSums, lo: int, hi: int, against: Any, R: int) -> bool:
    """Whether the whole of ``sum_{k=lo}^{hi}`` is provably below ``10**-R e**-10`` of
    ``against`` (a sum of the same reference): it can be left out of it."""
    ctx = mp()
    with ctx.workprec(64 + eng.abs_bits(lo, hi)):
        return _log_sum_bound(eng, lo, hi) < ctx.log(against) - (R * _LN10 + 10)


def _engine_total(eng: SimpleSums) -> Any:
    """``sum_{k=1}^{N} Phi(k)/Phi(c)`` of an engine, at its working precision (cached on the
    engine: engines are per thread)."""
    total = eng.__dict__.get("_total")
    if total is None:
        total = eng.__dict__["_total"] = eng.sums(1, eng.N, (0,))[0]
    return total


def _exact_value(x: Any) -> Fraction:
    """The exact rational value of a Fraction or a (finite) mpf computed here.

    Internal values (a cdf far in its tail can be ~10**-2000000) are converted directly from the
    mantissa and exponent, without the input cap of :func:`symhx.validation.to_rational`.
    """
    if is_mpf(x):
        return mpf_to_fraction(export(x))
    exact = to_rational(x, "value")
    assert exact is not None
    return exact


def _logp_float(p: Any, fr: Fraction | None) -> float:
    """float64 ``log p`` for any size of numerator and denominator."""
    if fr is not None:
        return math.log(fr.numerator) - math.log(fr.denominator)
    ctx = mp()
    with ctx.workdps(30):
        return float(ctx.log(mp_value(p, None)))


# --------------------------------------------------------------------------- structure of Phi
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
        attempt, start_bits=start,
        undecided=lambda bits: (
            f"the modes of X at the irrational p={str(p)[:60]} (N={_n_show(N)}) are not "
            f"decided at {bits} bits: {state.get('why', '')}; symhx never guesses a tie: pass "
            f"p as an exact rational (Fraction, sympy Rational or decimal string) to have it "
            f"decided exactly"))


def simple_modes(N: int, fr: Fraction | None, p: Any) -> tuple[int, ...]:
    """All maximisers of ``Phi_{N,p}(k)`` (eq. 8), certified: ``fr`` is ``p``'s exact value;
    ``None`` for a sympy irrational ``p``, decided for ``p`` itself on rigorous Arb balls with
    rising precision (a true tie raises
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


# --------------------------------------------------------------------------- deprecated names
_MOVED = ("distribution_of", "pmf", "logpmf", "normaliser", "mean", "variance", "mode", "modes")


def __getattr__(name: str) -> Any:
    """``symhx.distribution.mean`` etc. moved to ``symhx.mean`` (defined in :mod:`symhx.api`,
    exported lazily by the package): the old names still work, with a DeprecationWarning.  The
    value is read from the already-loaded package ``symhx`` (its lazy table of public names), so
    this module imports nothing above itself."""
    if name in _MOVED:
        warnings.warn(f"symhx.distribution.{name} moved to symhx.{name} (symhx.api.{name})",
                      DeprecationWarning, stacklevel=2)
        return getattr(sys.modules["symhx"], name)
    raise AttributeError(f"module 'symhx.distribution' has no attribute {name!r}")
