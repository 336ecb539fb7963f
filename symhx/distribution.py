"""The distribution of X, the number of distinct impacts of a circuit (sections 4-5, eqs. 7-8).

Simple sample space: ``P(X = k) = Phi_{N,p}(k) / Gamma_{N,p}`` with
``Phi_{N,p}(k) = p**k N! / (k (N-k)!)`` and ``Gamma_{N,p} = sum_{j=1}^{N} Phi_{N,p}(j)``.
Other sample spaces (higher-order circuits, section 8) live in :mod:`symhx.spaces`; every function
here takes ``space=``.

Arithmetic
----------
* **Exact** for ``p`` an int, ``Fraction`` or sympy ``Rational``: pmf, normaliser, mean and
  variance are ``Fraction`` (binary splitting; practical up to ``N ~ 10**5``; larger N raise
  ``ValueError`` -- pass a float or mpf ``p`` for the mpmath path).
* **mpmath** otherwise (floats and mpf are converted exactly, then evaluated at ``dps`` digits):
  log space throughout, so nothing overflows; only terms within ``dps`` + guard digits of the
  largest one are summed (``Phi`` is decreasing, increasing, decreasing in k, so the significant
  terms form at most two runs, found by bisection). ``N = 10**6`` runs in a fraction of a second to
  seconds; the cost grows with the width of the distribution (~sqrt(N)), so ``N`` up to ~10**9 is
  practical for ``mean``/``variance`` and ``N`` of any size for ``pmf``/``logpmf`` near the modes.
* **mode / modes** are decided exactly for every rational ``p`` (floats and mpf included) and
  any N (``10**100`` too): integer arithmetic locates the local maximum of ``Phi`` and a single
  comparison with ``Phi(1)`` is certified by interval arithmetic (exact integers on a near tie).
  The mode never needs the normaliser.

Ties: :func:`mode` returns the smallest maximiser; :func:`modes` returns all of them, e.g.
``N = 101, p = 1/50`` has modes ``(50, 51)``.

>>> from fractions import Fraction
>>> pmf(4, Fraction(1, 2), 1)
Fraction(16, 39)
>>> modes(101, Fraction(1, 50))
(50, 51)
>>> mpmath.nstr(mean(100, 0.02, dps=20), 20)
'48.930449948267425369'
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction
from functools import cached_property
from typing import Any

import mpmath

from symhx._numeric import (
    G_mp,
    check_dps,
    check_N,
    check_p,
    digits_of,
    is_exact_type,
    mp_value,
)
from symhx.certify import G_arb, bits_for, certified_sign, to_arb

__all__ = [
    "Distribution",
    "SimpleDistribution",
    "distribution_of",
    "logpmf",
    "mean",
    "mode",
    "modes",
    "normaliser",
    "pmf",
    "variance",
]

#: largest N for exact (Fraction) distributions
EXACT_N_LIMIT = 100_000


class Distribution:
    """Common interface of the distribution of X over a sample space (see :func:`distribution_of`).

    Attributes: ``N``, ``p`` (as given), ``space``, ``dps``, ``exact`` (results are Fractions).
    Methods/properties: ``pmf(k)``, ``logpmf(k)``, ``normaliser``, ``mean``, ``variance``,
    ``mode``, ``modes``, ``support``.
    """

    N: int
    p: Any
    space: str
    dps: int
    exact: bool

    def pmf(self, k: int) -> Any:  # pragma: no cover - interface
        raise NotImplementedError

    def logpmf(self, k: int) -> mpmath.mpf:  # pragma: no cover - interface
        raise NotImplementedError

    # Subclasses provide ``_exact_moments`` = (normaliser, sum k W(k), sum k**2 W(k)) as
    # Fractions, and ``_mp_moments`` = (normaliser or its log, mean, variance) as mpf.
    _exact_moments: tuple[Fraction, Fraction, Fraction]
    _mp_moments: tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]

    def _round(self, x: mpmath.mpf) -> mpmath.mpf:
        with mpmath.workdps(self.dps):
            return +x

    @property
    def support(self) -> range:
        """Values X can take: ``1..N``."""
        return range(1, self.N + 1)

    @property
    def mean(self) -> Any:
        """``E[X]``: a Fraction when exact, else an mpf to ``dps`` digits."""
        if self.exact:
            g, m1, _ = self._exact_moments
            return m1 / g
        return self._round(self._mp_moments[1])

    @property
    def variance(self) -> Any:
        """``Var[X]`` (the mpmath path sums ``(k - mean)**2 P(X=k)``: no cancellation)."""
        if self.exact:
            g, m1, m2 = self._exact_moments
            mu = m1 / g
            return m2 / g - mu * mu
        return self._round(self._mp_moments[2])

    @property
    def modes(self) -> tuple[int, ...]:  # pragma: no cover - interface
        raise NotImplementedError

    @property
    def mode(self) -> int:
        """The smallest maximiser."""
        return self.modes[0]

    def __repr__(self) -> str:
        return (f"{type(self).__name__}(N={self.N}, p={self.p!r}, space={self.space!r}, "
                f"dps={self.dps}, exact={self.exact})")


# --------------------------------------------------------------------------- exact sums
def _binary_split(N: int, a: int, b: int, weight: Callable[[int], tuple[int, int]]
                  ) -> Fraction:
    """``sum_{j=1}^{N} w(j) prod_{i=1}^{j} a (N-i+1) / b`` exactly, ``w(j) = num/den``.

    Haible-Papanikolaou binary splitting: O(M(size) log N) instead of N big-Fraction additions.
    """

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

    _, Q, B, T = rec(1, N + 1)
    return Fraction(T, B * Q)


class SimpleDistribution(Distribution):
    """X over the simple circuits (eqs. 7-8). Build it with :func:`distribution_of`."""

    space = "simple"

    def __init__(self, N: int, p: Any, *, dps: int = 50) -> None:
        self.N = check_N(N, minimum=1)
        self.fr, self.p = check_p(p)
        self.dps = check_dps(dps)
        self.exact = is_exact_type(p)
        if self.exact and self.N > EXACT_N_LIMIT:
            raise ValueError(
                f"exact (rational) arithmetic is limited to N <= {EXACT_N_LIMIT}; got N={self.N}. "
                f"Pass p as a float or mpmath.mpf for the mpmath path at dps digits."
            )
        # digits lost by the recurrences and the k, k**2 weights
        self._guard = 10 + 2 * digits_of(self.N)

    # ----------------------------------------------------------------- exact path
    def _split(self, weight: Callable[[int], tuple[int, int]]) -> Fraction:
        assert self.fr is not None
        return _binary_split(self.N, self.fr.numerator, self.fr.denominator, weight)

    @cached_property
    def _exact_moments(self) -> tuple[Fraction, Fraction, Fraction]:
        gamma = self._split(lambda j: (1, j))
        m1 = self._split(lambda j: (1, 1))
        m2 = self._split(lambda j: (j, 1))
        return gamma, m1, m2

    def _phi_exact(self, k: int) -> Fraction:
        assert self.fr is not None
        return self.fr**k * math.perm(self.N, k) / k

    # ----------------------------------------------------------------- mpmath path
    def _log_phi(self, k: int) -> mpmath.mpf:
        """log Phi(k) at the working precision (caller sets it)."""
        N = self.N
        # log Phi(k) = k log p + log N + lgamma(N) - lgamma(N-k+1) - log k
        #            = k log(N p) + G(N, k-1) - log k + (log N - log N) ... written without
        # the O(N log N) lgamma terms: lgamma(N) - lgamma(N-k+1) = G(N, k-1) + (k-1) log N
        return (k * mpmath.log(self._pm) + (k - 1) * self._logN + self._logN
                + G_mp(N, k - 1) - mpmath.log(k))

    def _compute_runs(self, below: mpmath.mpf) -> tuple[mpmath.mpf, list[tuple[int, list]]]:
        """(log of the largest term, [(k0, [Phi(k)/max for k = k0, k0+1, ...]), ...]) keeping
        every term within ``exp(-below)`` of the largest (at most two runs)."""
        N = self.N
        with mpmath.workdps(self.dps + self._guard):
            self._pm = mp_value(self.p, self.fr)
            self._logN = mpmath.log(N)
            top = _candidates(N, self.fr, self._pm)
            lmax = max(self._log_phi(k) for k in top)
            ks = _significant_ranges(N, self.fr, self._pm, self._log_phi, lmax - below)
            runs = []
            pm = self._pm
            for lo, hi in ks:
                w = mpmath.exp(self._log_phi(lo) - lmax)
                ws = [w]
                for k in range(lo, hi):
                    w = w * pm * (N - k) * k / (k + 1)
                    ws.append(w)
                runs.append((lo, ws))
        return lmax, runs

    @cached_property
    def _mp_moments(self) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
        with mpmath.workdps(self.dps + self._guard):
            ln10 = mpmath.log(10)
            below = (self.dps + self._guard) * ln10 + 2 * mpmath.log(self.N) + 5
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
                need = (self.dps + self._guard) * ln10 - lv + 3 * mpmath.log(self.N) + 5
                if need <= below:
                    break
                below = need
                _, runs = self._compute_runs(below)
                v = central(runs)
            return lmax + mpmath.log(s0), mu, v / s0

    # ----------------------------------------------------------------- public
    def _check_k(self, k: int) -> int:
        if not isinstance(k, int) or isinstance(k, bool):
            raise TypeError(f"k must be an int, got {type(k).__name__}")
        return k

    def pmf(self, k: int) -> Any:
        """``P(X = k)`` (eq. 7): a Fraction when exact, else an mpf; 0 outside ``1..N``."""
        k = self._check_k(k)
        if not 1 <= k <= self.N:
            return Fraction(0) if self.exact else mpmath.mpf(0)
        if self.exact:
            return self._phi_exact(k) / self._exact_moments[0]
        self._mp_moments  # noqa: B018 - fills the cached, normalised significant terms
        for k0, ws in self._pmf_runs:
            if k0 <= k < k0 + len(ws):
                return self._round(ws[k - k0])
        with mpmath.workdps(self.dps + self._guard):
            return self._round(mpmath.exp(self._logpmf_raw(k)))

    def logpmf(self, k: int) -> mpmath.mpf:
        """``log P(X = k)`` as an mpf (``-inf`` outside ``1..N``), never underflows."""
        k = self._check_k(k)
        if not 1 <= k <= self.N:
            return mpmath.ninf
        if self.exact:
            with mpmath.workdps(self.dps + 5):
                pk = self.pmf(k)
                return self._round(mpmath.log(pk.numerator) - mpmath.log(pk.denominator))
        return self._round(self._logpmf_raw(k))

    def _logpmf_raw(self, k: int) -> mpmath.mpf:
        """log P(X = k) at the working precision with guard digits (not rounded: exp() of a
        log rounded to dps digits would lose log10|log P| digits)."""
        log_gamma = self._mp_moments[0]
        with mpmath.workdps(self.dps + self._guard):
            return self._log_phi(k) - log_gamma

    @property
    def normaliser(self) -> Any:
        """``Gamma_{N,p}`` (eq. 8): Fraction when exact, else mpf (may overflow the float
        range; see :attr:`log_normaliser`)."""
        if self.exact:
            return self._exact_moments[0]
        return self._round(mpmath.exp(self._mp_moments[0]))

    @property
    def log_normaliser(self) -> mpmath.mpf:
        """``log Gamma_{N,p}``."""
        if self.exact:
            g = self._exact_moments[0]
            with mpmath.workdps(self.dps + 5):
                return self._round(mpmath.log(g.numerator) - mpmath.log(g.denominator))
        return self._round(self._mp_moments[0])

    @property
    def modes(self) -> tuple[int, ...]:
        """All maximisers of ``P(X = k)``, increasing (exact for rational ``p``)."""
        return _simple_modes(self.N, self.fr, self.p)

    def table(self) -> list[tuple[int, Any]]:
        """``[(k, P(X = k)) for k in 1..N]`` (for plots and moderate N).

        The mpmath path runs the term ratio ``Phi(k+1)/Phi(k) = p (N-k) k/(k+1)`` across the
        whole support from ``P(X = 1)``, with guard digits for the ``N`` roundings.
        """
        if self.exact:
            return [(k, self.pmf(k)) for k in self.support]
        N = self.N
        with mpmath.workdps(self.dps + self._guard):
            w = mpmath.exp(self._logpmf_raw(1))
            pm = mp_value(self.p, self.fr)
            out = []
            for k in range(1, N + 1):
                out.append((k, self._round(w)))
                w = w * pm * (N - k) * k / (k + 1)
        return out


# --------------------------------------------------------------------------- structure of Phi
def _candidates(N: int, fr: Fraction | None, pm: mpmath.mpf) -> list[int]:
    """Indices that may hold the global maximum of Phi: 1 and the hump's local maximum."""
    hump = _hump(N, fr, pm)
    return [1] if hump is None else sorted({1, hump[0], hump[1]})


def _hump(N: int, fr: Fraction | None, pm: mpmath.mpf) -> tuple[int, int, bool] | None:
    """``(j, j + 1, tie)`` with ``j = floor(k_+)`` when the increasing stretch of Phi contains an
    integer (``f(j) >= 0``, so ``Phi(j+1) >= Phi(j)``; ``tie`` when ``f(j) == 0``); else None.

    ``f_{N,p}(k) b = -a k**2 + (N a - b) k - b`` for ``p = a/b``: all in integers.
    """
    if fr is None:  # irrational p: use a rational approximation at the working precision
        man, exp = pm.man_exp
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
    """Arb ball of ``log Phi(K+1) - log Phi(1) = K log(N p) + G(N, K) - log(K + 1)``."""
    return K * ((to_arb(N) * a).log() - to_arb(b).log()) + G_arb(N, K) - to_arb(K + 1).log()


def _compare_with_one(N: int, fr: Fraction, K: int) -> int:
    """Sign of ``Phi(K+1) - Phi(1)``, certified (exact integers on a near tie)."""
    a, b = fr.numerator, fr.denominator

    def exact() -> int:
        lhs = a**K * math.perm(N - 1, K)
        rhs = (K + 1) * b**K
        return (lhs > rhs) - (lhs < rhs)

    start = bits_for(N, a.bit_length() + b.bit_length() + 2 * K.bit_length() + 64)
    return certified_sign(lambda: _log_ratio_iv(N, a, b, K), start_bits=start,
                          max_bits=32 * start, exact_fn=exact)


def _simple_modes(N: int, fr: Fraction | None, p: Any) -> tuple[int, ...]:
    if fr is None:
        with mpmath.workdps(60):
            pm = mp_value(p, None)
        man, exp = pm.man_exp
        fr = Fraction(man) * Fraction(2) ** exp
    hump = _hump(N, fr, mpmath.mpf(0))
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


# --------------------------------------------------------------------------- public functions
def distribution_of(N: int, p: Any, *, space: str = "simple", dps: int = 50) -> Distribution:
    """The distribution of X for ``N`` vertices and impact probability ``p``.

    Parameters
    ----------
    N : int
        Number of vertices (possible impacts), ``N = n + 1`` for ``n`` pipes.
    p : int, Fraction, sympy Rational, float or mpf
        Impact probability, ``p > 0`` (``p > 1`` is accepted but unphysical). Exact types give
        exact results; floats/mpf are taken at their exact binary value and evaluated at ``dps``.
    space : str
        ``"simple"`` (eqs. 7-8) or a higher-order space of :mod:`symhx.spaces`.
    dps : int
        Significant digits of mpmath results.

    >>> d = distribution_of(3, Fraction(1, 2))
    >>> [d.pmf(k) for k in d.support], d.mean
    ([Fraction(3, 5), Fraction(3, 10), Fraction(1, 10)], Fraction(3, 2))
    """
    if space == "simple":
        return SimpleDistribution(N, p, dps=dps)
    from symhx import spaces

    return spaces.distribution(N, p, space=space, dps=dps)


def pmf(N: int, p: Any, k: int, *, space: str = "simple", dps: int = 50) -> Any:
    """``P(X = k)`` (eq. 7). See :func:`distribution_of` for types.

    >>> pmf(2, 1, 2)
    Fraction(1, 3)
    """
    return distribution_of(N, p, space=space, dps=dps).pmf(k)


def logpmf(N: int, p: Any, k: int, *, space: str = "simple", dps: int = 50) -> mpmath.mpf:
    """``log P(X = k)`` as an mpf; works where the pmf underflows.

    >>> float(logpmf(10**6, 0.5, 1)) < -1e6
    True
    """
    return distribution_of(N, p, space=space, dps=dps).logpmf(k)


def normaliser(N: int, p: Any, *, space: str = "simple", dps: int = 50) -> Any:
    """``Gamma_{N,p}`` (eq. 8).

    >>> normaliser(4, 1) == sum(phi for phi in (4, 6, 8, 6))
    True
    """
    return distribution_of(N, p, space=space, dps=dps).normaliser


def mean(N: int, p: Any, *, space: str = "simple", dps: int = 50) -> Any:
    """``E[X]``: Fraction for exact ``p``, else mpf to ``dps`` digits.

    >>> mean(2, Fraction(1, 2))
    Fraction(6, 5)
    """
    return distribution_of(N, p, space=space, dps=dps).mean


def variance(N: int, p: Any, *, space: str = "simple", dps: int = 50) -> Any:
    """``Var[X]``.

    >>> variance(2, Fraction(1, 2))
    Fraction(4, 25)
    """
    return distribution_of(N, p, space=space, dps=dps).variance


def modes(N: int, p: Any, *, space: str = "simple") -> tuple[int, ...]:
    """All maximisers of ``P(X = k)`` (exact for rational ``p``, any N; no normaliser needed).

    >>> modes(5, Fraction(1, 2))
    (1, 2, 3)
    """
    if space != "simple":
        from symhx import spaces

        return spaces.modes(N, p, space=space)
    N = check_N(N, minimum=1)
    fr, p = check_p(p)
    return _simple_modes(N, fr, p)


def mode(N: int, p: Any, *, space: str = "simple") -> int:
    """The mode of X (smallest maximiser), eq. (7); see :func:`modes`.

    >>> mode(101, 0.01), mode(101, 0.013), mode(10**100, Fraction(1, 10**100))
    (1, 21, 1)
    """
    return modes(N, p, space=space)[0]


