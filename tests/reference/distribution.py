"""Independent references for the distribution of X (eqs. 7-8): exact Fractions straight from
the factorials, a table-defined distribution whose every quantity is computed by its definition,
and two mpmath routes that sum the whole support with no window (a downward term-ratio
recurrence, and ``loggamma``).

None of these uses symhx's distribution code.

>>> from fractions import Fraction
>>> t = ExactTable.simple(3, Fraction(1, 2))
>>> t.pmf, t.mean, t.ppf(Fraction(1, 2)), t.modes
((Fraction(3, 5), Fraction(3, 10), Fraction(1, 10)), Fraction(3, 2), 1, (1,))
"""

from __future__ import annotations

import bisect
import itertools
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cache, cached_property
from math import factorial
from typing import Any

import mpmath
from hypothesis import strategies as st


def phi_exact(N: int, p: Fraction, k: int) -> Fraction:
    """Phi_{N,p}(k) straight from eq. (8) with factorials."""
    return Fraction(p) ** k * Fraction(factorial(N), k * factorial(N - k))


def pmf_table(N: int, p: Fraction) -> list[Fraction]:
    w = [phi_exact(N, p, k) for k in range(1, N + 1)]
    g = sum(w)
    return [x / g for x in w]


def brute_modes(N: int, p: Fraction) -> tuple[int, ...]:
    w = [phi_exact(N, p, k) for k in range(1, N + 1)]
    m = max(w)
    return tuple(k for k, x in zip(range(1, N + 1), w, strict=True) if x == m)


# --------------------------------------------------------------------------- exact numbers
def to_mp(x: Fraction | int) -> mpmath.mpf:
    """An exact rational as an mpf at the current precision."""
    x = Fraction(x)
    return mpmath.mpf(x.numerator) / x.denominator


def log_of(x: Fraction) -> mpmath.mpf:
    """``log x`` of an exact non-negative rational at the current precision (``-inf`` at 0)."""
    x = Fraction(x)
    return mpmath.ninf if x == 0 else mpmath.log(x.numerator) - mpmath.log(x.denominator)


def fraction_of(x: mpmath.mpf | float) -> Fraction:
    """The exact rational value of a binary number (an mpf from its mantissa and exponent)."""
    if isinstance(x, float):
        return Fraction(x)
    man, exp = x.man_exp
    return Fraction(int(man)) * Fraction(2) ** int(exp)


# --------------------------------------------------------------------------- a table distribution
@dataclass(frozen=True)
class ExactTable:
    """The distribution on ``1..N`` with the given exact (unnormalised) weights; every quantity
    by its definition: ``cdf`` as partial sums, quantiles by search over them, moments as sums.
    """

    weights: tuple[Fraction, ...]

    @classmethod
    def of(cls, weights: Iterable[Fraction | int]) -> ExactTable:
        return cls(tuple(Fraction(w) for w in weights))

    @classmethod
    def simple(cls, N: int, p: Fraction) -> ExactTable:
        """The simple space of eq. (8): ``Phi_{N,p}(k)``, k = 1..N."""
        return cls(tuple(phi_exact(N, Fraction(p), k) for k in range(1, N + 1)))

    @property
    def N(self) -> int:
        return len(self.weights)

    @cached_property
    def normaliser(self) -> Fraction:
        return sum(self.weights, Fraction(0))

    @cached_property
    def pmf(self) -> tuple[Fraction, ...]:
        g = self.normaliser
        return tuple(w / g for w in self.weights)

    def pmf_at(self, k: int) -> Fraction:
        """``P(X = k)``, 0 outside the support."""
        return self.pmf[k - 1] if 1 <= k <= self.N else Fraction(0)

    @cached_property
    def cumulative(self) -> tuple[Fraction, ...]:
        """``P(X <= k)`` for ``k = 0..N``."""
        return (Fraction(0), *itertools.accumulate(self.pmf))

    def cdf(self, k: int) -> Fraction:
        return self.cumulative[max(0, min(k, self.N))]

    def sf(self, k: int) -> Fraction:
        return self.cumulative[-1] - self.cumulative[max(0, min(k, self.N))]

    @cached_property
    def mean(self) -> Fraction:
        return sum((k * x for k, x in enumerate(self.pmf, 1)), Fraction(0))

    @cached_property
    def var(self) -> Fraction:
        mu = self.mean
        return sum(((k - mu) ** 2 * x for k, x in enumerate(self.pmf, 1)), Fraction(0))

    @cached_property
    def modes(self) -> tuple[int, ...]:
        m = max(self.pmf)
        return tuple(k for k, x in enumerate(self.pmf, 1) if x == m)

    def ppf(self, q: Fraction) -> int:
        """The smallest ``k`` with ``cdf(k) >= q`` (0 for ``q = 0``)."""
        if q == 0:
            return 0
        return bisect.bisect_left(self.cumulative, q)

    def isf(self, q: Fraction) -> int:
        """The smallest ``k`` with ``sf(k) <= q`` (0 for ``q = 1``)."""
        if q == 1:
            return 0
        return next(k for k in range(1, self.N + 1) if self.sf(k) <= q)

    def entropy(self, dps: int) -> mpmath.mpf:
        """``-sum P log P`` at ``dps`` digits."""
        with mpmath.workdps(dps):
            return -mpmath.fsum(to_mp(x) * log_of(x) for x in self.pmf if x)

    def quantile_grid(self, most: int = 50) -> list[Fraction]:
        """``q`` at every cdf value, every midpoint between consecutive ones, 0 and 1 (thinned
        to about 40 points, the top three kept, when there are ``most`` or more)."""
        cdfs = list(self.cumulative)
        mids = [(a + b) / 2 for a, b in itertools.pairwise(cdfs)]
        qs = sorted({Fraction(0), Fraction(1), *cdfs, *mids})
        return qs if len(qs) < most else qs[:: len(qs) // 40] + qs[-3:]


# --------------------------------------------------------------------------- exact tails
@cache
def simple_integer_weights(N: int, p: Fraction) -> tuple[int, ...]:
    """Integers proportional to ``Phi_{N,p}(k)``, k = 1..N: ``a**k b**(N-k) N!/(N-k)! L/k`` for
    ``p = a/b``, ``L = lcm(1..N)`` (no Fraction arithmetic: fast at N = 1000 with a 60-bit p)."""
    p = Fraction(p)
    a, b = p.numerator, p.denominator
    L = math.lcm(*range(1, N + 1))
    return tuple(a**k * b ** (N - k) * math.perm(N, k) * (L // k) for k in range(1, N + 1))


def integer_weights(weights: Sequence[Fraction]) -> list[int]:
    """Exact rational weights as integers over their common denominator."""
    den = math.lcm(*(Fraction(x).denominator for x in weights))
    return [Fraction(x).numerator * (den // Fraction(x).denominator) for x in weights]


def tail_logs(weights: Sequence[int], ks: Iterable[int], digits: int = 700
              ) -> dict[int, tuple[mpmath.mpf, mpmath.mpf]]:
    """``{k: (log P(X <= k), log P(X > k))}`` of the distribution with the given integer weights
    (k = 1..N), exact partial sums, logs at ``digits`` digits (enough for logs down to
    ``10**-(digits - 100)``)."""
    cum = [0, *itertools.accumulate(weights)]
    tot = cum[-1]
    with mpmath.workdps(digits):
        lt = mpmath.log(tot)
        return {k: (mpmath.log(cum[k]) - lt, mpmath.log(tot - cum[k]) - lt) for k in ks}


# --------------------------------------------------------------------------- mpmath references
def pmf_by_downward_ratio(N: int, p: Fraction, dps: int) -> list[mpmath.mpf]:
    """``P(X = k)``, k = 1..N, at ``dps`` digits (plus guard digits for the N steps): the term
    ratio ``Phi(k-1)/Phi(k) = k / (p (N-k+1) (k-1))`` run *downwards* from ``k = N``, every term
    summed (no window)."""
    with mpmath.workdps(dps + 2 * len(str(N)) + 10):
        pm = to_mp(p)
        w = [mpmath.mpf(0)] * (N + 1)
        w[N] = mpmath.mpf(1)  # Phi(k) / Phi(N)
        for k in range(N, 1, -1):
            w[k - 1] = w[k] * k / (pm * (N - k + 1) * (k - 1))
        s = mpmath.fsum(w[1:])
        return [x / s for x in w[1:]]


def pmf_by_loggamma(N: int, pm: mpmath.mpf, digits: int) -> list[mpmath.mpf]:
    """``P(X = k)``, k = 1..N, with ``log Phi(k) = k log p + log N! - log (N-k)! - log k`` from
    ``loggamma`` at ``digits`` digits, every term of the support summed (no window); ``pm`` any
    positive mpf (an irrational p too).  Remembered per ``(N, pm, digits)``."""
    return list(_pmf_by_loggamma(N, pm, digits))


@cache
def _pmf_by_loggamma(N: int, pm: mpmath.mpf, digits: int) -> tuple[mpmath.mpf, ...]:
    with mpmath.workdps(digits):
        lp, lg = mpmath.log(pm), mpmath.loggamma(N + 1)
        logs = [k * lp + lg - mpmath.loggamma(N - k + 1) - mpmath.log(k) for k in range(1, N + 1)]
        top = max(logs)
        w = [mpmath.exp(x - top) for x in logs]
        s = mpmath.fsum(w)
        return tuple(x / s for x in w)


def moments_of(pmf: Sequence[Any]) -> tuple[Any, Any]:
    """``(mean, variance)`` of a pmf on ``1..N`` given as mpf (summed with ``fsum`` at the
    current precision) or Fractions."""
    if all(isinstance(x, Fraction) for x in pmf):
        mu = sum((k * x for k, x in enumerate(pmf, 1)), Fraction(0))
        return mu, sum(((k - mu) ** 2 * x for k, x in enumerate(pmf, 1)), Fraction(0))
    mu = mpmath.fsum(k * x for k, x in enumerate(pmf, 1))
    return mu, mpmath.fsum((k - mu) ** 2 * x for k, x in enumerate(pmf, 1))


# --------------------------------------------------------------------------- hypothesis strategies
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
