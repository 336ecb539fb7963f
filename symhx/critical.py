"""The jump of the mode (section 6): the discriminant root p_d, the critical point p_c, and the
whole mode path k*(p), for any N.

Definitions (simple sample space, eq. 8): ``Phi_{N,p}(k) = p**k N! / (k (N-k)!)``. Then

* ``Phi(k+1) - Phi(k)`` has the sign of ``f_{N,p}(k) = -p k**2 + (N p - 1) k - 1`` (eqs. 9-10);
* ``Phi(k) / Phi(1) = (p / c_k)**(k-1)`` with ``c_k = (k (N-k)! / (N-1)!)**(1/(k-1))``, so the
  mode leaves 1 at ``p_c = min_{k >= 2} c_k`` and lands on the argmin (the largest one if two
  tie, since ``(p/p_c)**(k-1)`` then grows fastest for the larger k);
* ``p_d`` (eq. 16) is where ``f`` first gets real roots: an interior local maximum of ``Phi``
  appears there, but it is not yet global: ``p_c > p_d`` for ``N >= 4``.

Certification. ``s(k) = log(N c_k) = h(k)/(k-1)`` with ``h(k) = log k + lgamma(N-k+1) - lgamma(N)``,
``h(1) = 0``: the slope of the chord of ``h`` from 1 to k. ``h''(k) = psi'(N-k+1) - 1/k**2`` is
strictly increasing, so ``h`` is concave then convex; the chord slope from the left end of such a
function strictly decreases, then strictly increases (where the tangent passes through
``(1, h(1))`` it can only cross upward). Hence ``c_k`` is strictly unimodal in real k, and the
integer argmin is the first ``k`` with ``c_{k+1} >= c_k``: a binary search over signs of
``D(k) = s(k+1) - s(k)``. Each sign is certified by mpmath interval arithmetic with escalating
precision; an interval that still contains 0 is settled exactly in integers
(``c_{k+1} > c_k  <=>  (k+1)**(k-1) (N-1)!/(N-k)! > k**k (N-k)**(k-1)``), which also detects exact
ties (e.g. ``N = 5``: ``c_2 = c_3 = 1/2``). No float guess is ever rounded.

Degenerate small N (DESIGN.md §3.5): ``N = 2`` has ``p_c = 2`` (no jump for ``p`` in (0, 1]);
``N = 3`` has ``p_c = p_d = 1``; ``N = 5`` ties ``Phi(1) = Phi(2) = Phi(3)`` at ``p = 1/2``; for
``N <= 7`` the jump lands on 2 or 3.

>>> cp = critical_point(101, dps=20)
>>> cp.k_before, cp.k_after
(1, 20)
>>> mpmath.nstr(cp.p, 20)
'0.012889115326530578361'
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import mpmath

from symhx._numeric import (
    G_iv,
    G_mp,
    as_fraction,
    certified_sign,
    check_dps,
    check_N,
    digits_of,
    iv_bits_for,
)

__all__ = [
    "CriticalPoint",
    "ModePath",
    "critical_point",
    "discriminant_root",
    "log_c",
    "mode_path",
]

#: exact integer fall-back is used only while the integers have at most this many bits
EXACT_BITS_LIMIT = 4_000_000


def discriminant_root(N: int, *, dps: int = 50) -> mpmath.mpf:
    """``p_d = ((1 + sqrt(N + 1)) / N)**2`` (eq. 16): where ``f_{N,p}`` gets a double root.

    The other root of the discriminant, ``((1 - sqrt(N+1))/N)**2``, gives the double root at
    ``k < 0`` and is irrelevant. ``N p_d - 1 = 2 (1 + sqrt(N + 1)) / N`` exactly, so ``p_d`` is
    computed to ``dps`` significant digits for any N.

    >>> discriminant_root(3)
    mpf('1.0')
    >>> mpmath.nstr(discriminant_root(100, dps=15), 15)
    '0.0122099751242242'
    """
    N = check_N(N)
    dps = check_dps(dps)
    with mpmath.workdps(dps + 10):
        val = ((1 + mpmath.sqrt(N + 1)) / N) ** 2
    with mpmath.workdps(dps):
        return +val


def discriminant_root_q(N: int, *, dps: int = 50) -> mpmath.mpf:
    """``N p_d - 1 = 2 (1 + sqrt(N + 1)) / N`` to ``dps`` digits (no cancellation)."""
    N = check_N(N)
    dps = check_dps(dps)
    with mpmath.workdps(dps + 10):
        val = 2 * (1 + mpmath.sqrt(N + 1)) / N
    with mpmath.workdps(dps):
        return +val


def log_c(N: int, k: int, *, dps: int = 50) -> mpmath.mpf:
    """``log(N c_k) = [log k - G(k-1)] / (k-1)`` with ``G(K) = lgamma(N) - lgamma(N-K) - K log N``.

    ``c_k = (k (N-k)!/(N-1)!)**(1/(k-1))`` is the p at which ``Phi(k) = Phi(1)``. Computed without
    the ``log10(N)``-digit cancellation of the definition (see :mod:`symhx._numeric`).

    >>> mpmath.nstr(log_c(5, 2, dps=10), 10), mpmath.nstr(mpmath.log(mpmath.mpf(5) / 2), 10)
    ('0.9162907319', '0.9162907319')
    """
    N = check_N(N)
    dps = check_dps(dps)
    if not 2 <= k <= N:
        raise ValueError(f"k must satisfy 2 <= k <= N, got k={k}, N={N}")
    with mpmath.workdps(dps + 15):
        val = (mpmath.log(k) - G_mp(N, k - 1)) / (k - 1)
    with mpmath.workdps(dps):
        return +val


# --------------------------------------------------------------------------- certified signs
class _SignOracle:
    """Certified signs of ``D(k) = log c_{k+1} - log c_k`` for one N (caches lgamma(N))."""

    def __init__(self, N: int) -> None:
        self.N = N
        self.start_bits = iv_bits_for(N, 2 * digits_of(N) + 20)
        self.max_bits = 16 * self.start_bits
        self.evaluations = 0

    def _interval(self, iv: Any, k: int) -> Any:
        N = self.N
        s1 = (iv.log(iv.mpf(k + 1)) - G_iv(iv, N, k)) / k
        s0 = (iv.log(iv.mpf(k)) - G_iv(iv, N, k - 1)) / (k - 1)
        return s1 - s0

    def _exact(self, k: int) -> int:
        N = self.N
        bits = k * (max(N, k + 1).bit_length() + 1)
        if bits > EXACT_BITS_LIMIT:
            from symhx._numeric import UndecidedError

            raise UndecidedError(
                f"c_{k + 1} vs c_{k} for N={N}: intervals did not separate and the exact "
                f"comparison needs ~{bits} bits"
            )
        lhs = (k + 1) ** (k - 1) * math.perm(N - 1, k - 1)
        rhs = k**k * (N - k) ** (k - 1)
        return (lhs > rhs) - (lhs < rhs)

    def sign(self, k: int) -> int:
        self.evaluations += 1
        return certified_sign(
            lambda iv: self._interval(iv, k),
            start_bits=self.start_bits,
            max_bits=self.max_bits,
            exact_fn=lambda: self._exact(k),
        )


def _argmin_c(N: int) -> tuple[int, bool, int]:
    """(first integer argmin k* of c_k over 2..N, whether c_{k*+1} ties, sign evaluations)."""
    if N == 2:
        return 2, False, 0
    oracle = _SignOracle(N)
    # bracket [lo, hi]: D(lo - 1) < 0 known (or lo == 2), answer in [lo, hi]; D(N) undefined,
    # so the answer is N when D(k) < 0 for all k in [2, N-1].
    lo, hi = 2, N
    # gallop from an asymptotic guess (k ~ sqrt(N ln N)) to shrink the bracket cheaply
    guess = max(2, min(N - 1, math.isqrt(int(N * max(1.0, math.log(N)))) // 2))
    step = guess
    k = guess
    while lo < hi:
        sk = oracle.sign(k) if k < N else 1
        if sk >= 0:
            hi = k
            break
        lo = k + 1
        step *= 2
        k = min(N, k + step)
    while lo < hi:
        mid = (lo + hi) // 2
        if oracle.sign(mid) >= 0:
            hi = mid
        else:
            lo = mid + 1
    kstar = lo
    tie = kstar < N and oracle.sign(kstar) == 0
    return kstar, tie, oracle.evaluations


def _exact_root(a: Fraction, n: int) -> Fraction | None:
    """``a**(1/n)`` if it is rational, else None (only for moderately sized a)."""
    if n == 1:
        return a
    num, den = a.numerator, a.denominator
    if max(num.bit_length(), den.bit_length()) > 20_000:
        return None
    rn = _iroot(num, n)
    rd = _iroot(den, n)
    if rn is not None and rd is not None:
        return Fraction(rn, rd)
    return None


def _iroot(x: int, n: int) -> int | None:
    if x < 2:
        return x
    r = round(x ** (1.0 / n)) if x.bit_length() < 1000 else _iroot_newton(x, n)
    for cand in (r - 1, r, r + 1):
        if cand >= 0 and cand**n == x:
            return cand
    return None


def _iroot_newton(x: int, n: int) -> int:
    r = 1 << ((x.bit_length() + n - 1) // n)
    while True:
        s = ((n - 1) * r + x // r ** (n - 1)) // n
        if s >= r:
            return r
        r = s


@dataclass(frozen=True)
class CriticalPoint:
    """Where the mode of X leaves 1 (simple sample space).

    Attributes
    ----------
    N : int
        Number of vertices (possible impacts), ``N = n_pipes + 1``.
    p : mpf
        ``p_c = min_{k>=2} c_k`` to ``dps`` digits (may exceed 1: ``N = 2`` gives 2).
    q : mpf
        ``N p_c - 1`` to ``dps`` digits, computed without cancellation (useful for huge N).
    k_before, k_after : int
        The mode just below ``p_c`` (always 1) and just above it (the largest tied argmin).
    argmins : tuple of int
        Every k with ``c_k = p_c`` (two only at an exact tie, e.g. ``N = 5``).
    p_d : mpf
        The discriminant root (eq. 16), for comparison; ``p_d <= p_c``.
    p_exact : Fraction or None
        ``p_c`` exactly when it is rational (e.g. whenever the argmin is 2: ``2/(N-1)``).
    dps : int
        Digits requested.
    """

    N: int
    p: mpmath.mpf
    q: mpmath.mpf
    k_before: int
    k_after: int
    argmins: tuple[int, ...]
    p_d: mpmath.mpf
    p_exact: Fraction | None
    dps: int
    sign_evaluations: int = field(default=0, compare=False, repr=False)

    @property
    def jump(self) -> int:
        """Size of the jump of the mode, ``k_after - k_before``."""
        return self.k_after - self.k_before

    def as_dict(self) -> dict[str, Any]:
        return {
            "N": self.N,
            "p_c": self.p,
            "N_p_c_minus_1": self.q,
            "k_before": self.k_before,
            "k_after": self.k_after,
            "argmins": list(self.argmins),
            "p_d": self.p_d,
            "p_c_exact": self.p_exact,
            "dps": self.dps,
        }


def critical_point(N: int, *, dps: int = 50, space: str = "simple") -> CriticalPoint:
    """The critical probability ``p_c`` at which the mode of X jumps away from 1.

    Parameters
    ----------
    N : int
        Number of vertices (``N = n + 1`` for ``n`` pipes), any ``N >= 2`` (tested to 10**100
        and beyond; cost grows like ``log N`` sign evaluations at ``O(log10 N)`` digits).
    dps : int
        Significant decimal digits of ``p``, ``q`` and ``p_d``.
    space : str
        Sample space; ``"simple"`` here (other spaces: :mod:`symhx.spaces`).

    Returns
    -------
    CriticalPoint

    >>> cp = critical_point(5)
    >>> cp.argmins, cp.k_after, cp.p_exact
    ((2, 3), 3, Fraction(1, 2))
    >>> critical_point(2).p
    mpf('2.0')
    """
    if space != "simple":
        from symhx import spaces

        return spaces.critical_point(N, dps=dps, space=space)
    N = check_N(N)
    dps = check_dps(dps)
    kstar, tie, evals = _argmin_c(N)
    argmins = (kstar, kstar + 1) if tie else (kstar,)
    with mpmath.workdps(dps + 15):
        s = (mpmath.log(kstar) - G_mp(N, kstar - 1)) / (kstar - 1)
        q = mpmath.expm1(s)
        p = mpmath.exp(s) / N
    a = None
    if kstar == 2 or kstar * N.bit_length() < 20_000:
        a = _exact_root(Fraction(kstar, math.perm(N - 1, kstar - 1)), kstar - 1)
    with mpmath.workdps(dps):
        p, q = +p, +q
        if a is not None:
            p = mpmath.mpf(a.numerator) / a.denominator
            q = mpmath.mpf(N * a.numerator - a.denominator) / a.denominator
    return CriticalPoint(
        N=N,
        p=p,
        q=q,
        k_before=1,
        k_after=argmins[-1],
        argmins=argmins,
        p_d=discriminant_root(N, dps=dps),
        p_exact=a,
        dps=dps,
        sign_evaluations=evals,
    )


# --------------------------------------------------------------------------- the mode path
@dataclass(frozen=True)
class ModePath:
    """The mode ``k*(p)`` (smallest maximiser) of the simple-space X as a step function of p.

    ``breakpoints[i] = (p_i, k_left, k_right)``: the mode is ``k_left`` on ``(p_{i-1}, p_i]`` and
    ``k_right`` just above ``p_i`` (at ``p_i`` itself both maximise and the smaller is the mode).
    The first breakpoint is the jump ``p_c`` (an mpf unless rational); the others are
    ``p = (k+1) / (k (N-k))`` (where ``f_{N,p}(k) = 0``, i.e. ``Phi(k+1) = Phi(k)``), exact
    Fractions.
    """

    N: int
    critical: CriticalPoint
    breakpoints: tuple[tuple[Any, int, int], ...]
    p_max: Fraction

    def mode_at(self, p: Any) -> int:
        """The mode at ``p`` read off the path (for ``0 < p <= p_max``)."""
        fr = as_fraction(p)
        if fr is None:
            raise ValueError("mode_at needs a rational (or float/mpf) p")
        k = 1
        for bp, _, right in self.breakpoints:
            if fr > _as_comparable(bp):
                k = right
            else:
                break
        return k

    def as_rows(self) -> list[dict[str, Any]]:
        return [{"p": bp, "k_left": kl, "k_right": kr} for bp, kl, kr in self.breakpoints]


def _as_comparable(bp: Any) -> Any:
    return bp if isinstance(bp, Fraction) else as_fraction(bp)


def mode_path(N: int, *, p_max: Any = 1, dps: int = 50) -> ModePath:
    """Every exact breakpoint of the mode ``k*(p)`` for ``0 < p <= p_max`` (simple space).

    After the jump the mode climbs one step at a time: it moves from ``k`` to ``k + 1`` exactly
    where ``Phi(k+1) = Phi(k)``, ``p = (k + 1)/(k (N - k))`` (eq. 10 with ``f = 0``). These are
    increasing in ``k`` beyond the jump and all exceed ``p_c`` (checked as they are built).

    Parameters
    ----------
    N : int
        Vertices, ``2 <= N``; the list has up to ``N`` entries, so keep ``N`` below ~10**6.
    p_max : number
        Upper end of the p range (default 1).
    dps : int
        Digits of the (irrational) jump point.

    >>> path = mode_path(6)
    >>> [(a, b) for _, a, b in path.breakpoints]
    [(1, 3), (3, 4), (4, 5)]
    >>> [str(p) for p, _, _ in path.breakpoints[1:]]
    ['4/9', '5/8']
    >>> [(a, b) for _, a, b in mode_path(101).breakpoints][:3]
    [(1, 20), (20, 21), (21, 22)]
    """
    N = check_N(N)
    pm = Fraction(p_max)
    cp = critical_point(N, dps=dps)
    pc = cp.p_exact if cp.p_exact is not None else cp.p
    bps: list[tuple[Any, int, int]] = []
    if _as_comparable(pc) > pm:
        return ModePath(N, cp, (), pm)
    bps.append((pc, 1, cp.k_after))
    prev = _as_comparable(pc)
    for k in range(cp.k_after, N):
        pk = Fraction(k + 1, k * (N - k))
        if pk > pm:
            break
        if pk <= prev:
            raise AssertionError(f"mode path not monotone at N={N}, k={k}")  # pragma: no cover
        bps.append((pk, k, k + 1))
        prev = pk
    return ModePath(N, cp, tuple(bps), pm)
