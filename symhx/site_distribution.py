"""The distribution of X when the impact sites have their own probabilities (several classes).

``P(X = k) = W(k) / sum_j W(j)`` with ``W(k)`` the total weight of the circuits of the sample
space with ``k`` distinct sites, each circuit weighted by the product of its sites' probabilities
(:mod:`symhx.site_weights`: ``W(k) = (k-1)! e_k(p_1..p_N)`` for simple circuits, eq. 8
generalised; visit patterns for the spaces of section 8).  One class is the scalar ``p`` of
eq. (7), handled by :class:`symhx.distribution.SimpleDistribution` /
:class:`symhx.spaces.SpaceDistribution` (``symhx.api`` dispatches): this class is for two or
more classes of distinct probability.

Arithmetic (the frozen-distribution contract of :class:`symhx.distribution.Distribution`):

* **exact** (every class probability of an exact type, int ``dps``): ``Fraction`` results from an
  exact integer table of ``W(k)`` (refused beyond
  :data:`symhx.site_weights.EXACT_TABLE_BITS_LIMIT` bits);
* **mpmath** (a float or mpf among the probabilities, taken at its exact binary value): every
  ``W(k)`` as an Arb ball of relative radius ``10**-(dps + guard)``, summed in mpmath;
  ``N <= symhx.site_weights.BALL_TABLE_N_LIMIT``;
* **float64** (``dps=None``): ``log W(k)`` from 60-bit balls;
* **modes**: exact for exact probabilities (integer comparisons); otherwise proved by Arb balls
  of the weights at doubling precision, with the exact rational table (floats are binary
  rationals) deciding a tie.

>>> from symhx.sites import SiteClasses
>>> d = SitesDistribution(3, SiteClasses((1, 2), ("1/2", "1/3")))
>>> [d.pmf(k) for k in (1, 2, 3)], d.modes()
([Fraction(21, 31), Fraction(8, 31), Fraction(2, 31)], (1,))
"""

from __future__ import annotations

from fractions import Fraction
from functools import cached_property
from typing import Any

import mpmath
import numpy as np
from flint import arb

from symhx import site_weights as _sw  # its work limits, read when called (raised there)
from symhx._mpctx import export, mp
from symhx._numeric import digits_of
from symhx.certify import UndecidedError, arb_prec
from symhx.distribution import Distribution
from symhx.site_weights import (
    SIMPLE,
    ball_weights,
    check_pattern_work,
    exact_table_bits,
    exact_weights,
)
from symhx.sites import SiteClasses, show_int
from symhx.validation import (
    DEFAULT_DPS,
    InputError,
    check_dps,
    check_N,
    exact_work_refusal,
    safe_repr,
)

__all__ = ["MODES_MAX_BITS", "SitesDistribution", "site_modes"]

#: the Arb precision of :func:`site_modes` doubles from 64 bits up to this many before the exact
#: rational table decides (a tie, or two weights closer than ``2**-MODES_MAX_BITS``)
MODES_MAX_BITS = 4096


def _arb_to_mpf(x: arb, prec: int) -> Any:
    """The midpoint of ``x`` rounded to ``prec`` bits, as a global mpf."""
    man, exp = x.mid().man_exp()
    raw = mpmath.libmp.from_man_exp(int(man), int(exp), prec, "n")
    return mpmath.mp.make_mpf(raw)


def _check_N_fits(N: int, what: str) -> None:
    if N > _sw.BALL_TABLE_N_LIMIT:
        raise InputError(
            f"{what} with several site classes tabulates every k = 1..N; N={show_int(N)} is "
            f"above the documented work limit symhx.site_weights.BALL_TABLE_N_LIMIT = "
            f"{_sw.BALL_TABLE_N_LIMIT} (one class, a scalar p, has no such limit)")


def site_modes(N: int, classes: SiteClasses, space: Any = SIMPLE) -> tuple[int, ...]:
    """All maximisers of ``W(k)`` (``P(X = k)``) for site classes over ``space``, increasing:
    exact integer comparisons for exact probabilities, else Arb balls at doubling precision with
    the exact rational table (floats at their binary value) on a near tie.

    >>> site_modes(3, SiteClasses((1, 2), ("1/2", "1/3")))
    (1,)
    >>> site_modes(4, SiteClasses((2, 2), (1, 2)))   # W = 6, 13, 24, 24: a tie
    (3, 4)
    """
    N = check_N(N, minimum=1)
    if classes.N != N:
        raise InputError(f"the site classes hold {classes.N} sites, but N = {show_int(N)}")
    if classes.exact:
        nums, _ = exact_weights(classes, space)
        top = max(nums)
        return tuple(k for k, w in enumerate(nums, 1) if w == top)
    _check_N_fits(N, "modes")
    bits = 64
    while bits <= MODES_MAX_BITS:
        w = ball_weights(classes, space, prec=bits)
        with arb_prec(bits + 64):
            best = max(range(N), key=lambda i: w[i].mid())
            lo = w[best].lower()
            # a ball reaching the top ball's lower end may hold the maximum; only a single
            # such candidate decides (dropping the candidates proved below another could never
            # leave one: the top ball and the one with the highest lower end both stay)
            cand = [i for i in range(N) if not w[i].upper() < lo]
            if len(cand) == 1:
                return (cand[0] + 1,)
        bits *= 2
    if exact_table_bits(classes) > _sw.EXACT_TABLE_BITS_LIMIT:
        raise UndecidedError(
            f"the largest weights of X agree to {MODES_MAX_BITS} bits (N={show_int(N)}, "
            f"{classes!r}) and the exact table would exceed "
            f"symhx.site_weights.EXACT_TABLE_BITS_LIMIT: an exact tie is likely")
    exact = SiteClasses(classes.sizes, classes.values, classes.names)  # exact binary values
    nums, _ = exact_weights(exact, space)
    top = max(nums)
    return tuple(k for k, x in enumerate(nums, 1) if x == top)


class SitesDistribution(Distribution):
    """X with per-site probabilities in two or more classes (see the module docstring).

    Build it with :func:`symhx.distribution_of` (``p=SiteClasses(...)`` or a sequence of N
    per-site probabilities).  Attributes as :class:`symhx.distribution.Distribution`, with
    ``p`` the :class:`~symhx.sites.SiteClasses`, ``fr`` ``None`` and ``classes`` the classes.
    """

    def __init__(self, N: int, classes: SiteClasses, space: Any = SIMPLE, *,
                 dps: int | None = DEFAULT_DPS) -> None:
        self.N = check_N(N, minimum=1)
        if not isinstance(classes, SiteClasses):
            raise TypeError(f"classes must be a symhx.SiteClasses, got "
                            f"{type(classes).__name__} {classes!r}")
        if classes.N != self.N:
            raise InputError(f"the site classes hold {classes.N} sites, but N = {self.N}")
        self.classes = classes
        self.p = classes
        self.fr = None
        self.dps = check_dps(dps, allow_none=True)
        self.exact = self.dps is not None and classes.exact
        self.sample_space = space
        self.space = space.name
        self._guard = 10 + 2 * digits_of(self.N)
        check_pattern_work(space, len(classes))
        if self.exact:
            bits = exact_table_bits(classes)
            if bits > _sw.EXACT_TABLE_BITS_LIMIT:
                raise exact_work_refusal(
                    f"exact (rational) arithmetic with site classes would hold ~{bits:.2g} bits"
                    f" for N={self.N} (documented work limit symhx.site_weights."
                    f"EXACT_TABLE_BITS_LIMIT = {_sw.EXACT_TABLE_BITS_LIMIT:.2g})",
                    values="the probabilities as floats or mpf")
        else:
            _check_N_fits(self.N, "the distribution of X")

    def _check_exact_work(self, what: str, limit: int, name: str) -> None:
        """The exact table was checked against its limit when the distribution was built."""

    # ----------------------------------------------------------------- exact path
    @cached_property
    def _exact_table(self) -> tuple[list[int], int, list[int]]:
        nums, den = exact_weights(self.classes, self.sample_space)
        cum = []
        s = 0
        for x in nums:
            s += x
            cum.append(s)
        return nums, den, cum

    @cached_property
    def _exact_moments(self) -> tuple[Fraction, Fraction, Fraction]:
        nums, den, cum = self._exact_table
        m1 = sum(k * x for k, x in enumerate(nums, 1))
        m2 = sum(k * k * x for k, x in enumerate(nums, 1))
        return Fraction(cum[-1], den), Fraction(m1, den), Fraction(m2, den)

    def _exact_partial(self, k: int) -> Fraction:
        _, den, cum = self._exact_table
        return Fraction(cum[min(k, self.N) - 1], den) if k >= 1 else Fraction(0)

    # ----------------------------------------------------------------- mpmath path
    @property
    def _prec(self) -> int:
        return int(self._wdps * 3.33) + 16

    @cached_property
    def _mp_table(self) -> list[Any]:
        """``W(k)``, ``k = 1..N``, as global mpf at ``dps`` + guard digits (from Arb balls of
        relative radius below the working precision)."""
        balls = ball_weights(self.classes, self.sample_space, prec=self._prec)
        return [_arb_to_mpf(x, self._prec) for x in balls]

    @cached_property
    def _mp_moments(self) -> tuple[Any, Any, Any]:
        ctx = mp()
        w = self._mp_table
        with ctx.workdps(self._wdps):
            s0 = ctx.fsum(w)
            mu = ctx.fdiv(ctx.fsum(ctx.fmul(k, x) for k, x in enumerate(w, 1)), s0)
            var = ctx.fdiv(ctx.fsum(ctx.fmul((k - mu) ** 2, x) for k, x in enumerate(w, 1)),
                           s0)
            return export(s0), export(mu), export(var)

    def _mp_terms(self, lo: int, hi: int) -> list[tuple[int, Any]]:
        s0 = self._mp_moments[0]
        ctx = mp()
        w = self._mp_table
        lo, hi = max(lo, 1), min(hi, self.N)
        with ctx.workdps(self._wdps):
            return [(k, export(ctx.fdiv(w[k - 1], s0))) for k in range(lo, hi + 1)]

    def _rounded(self, x: Any) -> Any:
        ctx = mp()
        with ctx.workdps(self.dps or 15):
            return export(ctx.mpf(x))

    # ----------------------------------------------------------------- float64 path
    def _float_logw(self) -> tuple[np.ndarray, float]:
        """``(log W(k) - top, top)``, ``top`` the largest ``log W(k)``: the logs relative to the
        largest weight, subtracted before rounding to float64 (an absolute log of size L would
        carry L * 2**-53 of error into every probability)."""
        balls = ball_weights(self.classes, self.sample_space, prec=60)
        with arb_prec(80):
            logs = [x.log() for x in balls]
            top = max(logs, key=lambda y: y.mid()).mid()
            return np.array([float((y - top).mid()) for y in logs]), float(top)

    # ----------------------------------------------------------------- per-k values
    def _pmf1(self, k: int) -> Any:
        if self.exact:
            nums, _, cum = self._exact_table
            return Fraction(nums[k - 1], cum[-1])
        s0 = self._mp_moments[0]
        ctx = mp()
        with ctx.workdps(self._wdps):
            v = ctx.fdiv(self._mp_table[k - 1], s0)
        return self._rounded(v)

    def _logpmf1(self, k: int) -> Any:
        if self.exact:
            return self._log_fraction(self._pmf1(k))
        s0 = self._mp_moments[0]
        ctx = mp()
        with ctx.workdps(self._wdps):
            v = ctx.log(self._mp_table[k - 1]) - ctx.log(s0)
        return self._rounded(v)

    @property
    def normaliser(self) -> Any:
        """``sum_k W(k)``: eq. (8)'s ``Gamma_{N,p}`` with per-site probabilities (float for
        ``dps=None``; may overflow there: see :attr:`log_normaliser`)."""
        if self.dps is None:
            return self._float_exp(self.log_normaliser)
        if self.exact:
            return self._exact_moments[0]
        return self._rounded(self._mp_moments[0])

    @property
    def log_normaliser(self) -> Any:
        """``log`` of :attr:`normaliser`."""
        if self.dps is None:
            return float(self._ftab["lognorm"])
        if self.exact:
            return self._log_fraction(self._exact_moments[0])
        ctx = mp()
        with ctx.workdps(self._wdps):
            v = ctx.log(self._mp_moments[0])
        return self._rounded(v)

    def modes(self) -> tuple[int, ...]:
        """All maximisers of ``P(X = k)``, increasing (certified; see :func:`site_modes`)."""
        return site_modes(self.N, self.classes, self.sample_space)

    def table(self) -> list[tuple[int, Any]]:
        """``[(k, P(X = k)) for k in 1..N]``."""
        if self.dps is None:
            return [(k, float(v)) for k, v in enumerate(self._ftab["pmf"], 1)]
        return [(k, self._pmf1(k)) for k in range(1, self.N + 1)]

    def __repr__(self) -> str:
        return (f"SitesDistribution(N={safe_repr(self.N)}, p={self.classes!r}, "
                f"space={self.space!r}, dps={self.dps}, exact={self.exact})")
