"""The first jump of the mode over a higher-order sample space.

For ``k >= 2`` let ``h_k(p) = log W(k) - log W(1)``. With ``W(k) = Phi_{N,p}(k) Q*(k)``,

``P_k(p) = p * (W(k) - W(1)) / (N p)`` is a polynomial in ``p`` whose coefficients are
``-N b_e`` at degree ``e`` (``N b_e`` circuits at ``k = 1``: one vertex visited ``e+1`` times,
``b_e`` = 1, or 0 where the printed space drops it) and ``+a_k(e)`` at degree ``k - 1 + e``, where
``a_k(e)`` counts the circuits of the space with ``k`` distinct vertices and excess ``e``. Every
space here contains the class ``(e+1,)`` for each excess level ``e`` it has, and for ``k >= 2``
that class alone has ``k C(N, k) (k+e-1)! / ((k-1)! (e+1)!) >= k C(N, k) >= N`` members; so
coefficients at overlapping degrees are ``a_k - N b >= 0`` and the signs change exactly
once: by Descartes' rule ``h_k`` has exactly one positive root ``c_k``, negative below it and
positive above. (With the ``;distinct`` weighting ``h_k`` is ``(k-1) log p`` plus a constant.)

Hence, as for the simple space, the mode is 1 exactly for ``p < p_c = min_{k>=2} c_k`` and jumps
to an argmin at ``p_c`` (if several ``c_k`` tie, to the one whose ``h_k`` grows fastest).

Algorithm (any ``N`` up to ~10**6, memory ~ ``8 (m + 4) N`` bytes):

1. float64: every ``c_k``, ``k = 2..N``, by a vectorised safeguarded Newton iteration in
   ``s = log(N p)`` (bracketed, so it cannot miss the single root);
2. candidates: the ``k`` with ``h_k(s_min + 1e-9) >= -margin`` (margin > 100x the float64 error
   of ``h``); every other ``k`` provably has ``c_k > p_c``;
3. mpmath: each candidate's root at ``dps`` + guard digits; the ordering of the best against the
   others certified by interval arithmetic at the ends of a tiny certified bracket of the best
   root; near-equal roots are checked for an exact rational tie with integer arithmetic.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

from symhx._numeric import (
    G_iv,
    G_mp,
    UndecidedError,
    check_dps,
    check_N,
    digits_of,
    iv_bits_for,
    iv_prec,
)
from symhx.critical import CriticalPoint, discriminant_root
from symhx.spaces._classes import Space, parse_space
from symhx.spaces._dist import compare_weights, log_U_table, screen_margin

__all__ = ["critical_point", "root_estimates"]


# --------------------------------------------------------------------------- float64 stage
def root_estimates(space: Space | str, N: int) -> np.ndarray:
    """float64 ``log(N c_k)`` for ``k = 2..N`` (index ``k - 2``).

    >>> s = root_estimates("eq41", 10)
    >>> int(np.argmin(s)) + 2   # the jump of eq. (41) for N = 10 lands on k = 5
    5
    """
    from scipy.special import gammaln

    sp = parse_space(space)
    N = check_N(N)
    lu = log_U_table(sp, N)
    ks = np.arange(2, N + 1, dtype=float)
    G = gammaln(float(N)) - gammaln(N - ks + 1.0) - (ks - 1.0) * math.log(N)
    base = G - np.log(ks)
    es = np.arange(sp.max_excess + 1, dtype=float)
    logN = math.log(N)

    def logQ(col: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        # log Q*(k) (up to the common log D) and the mean excess, for columns col at s
        if sp.weighting == "length":
            t = col + es[:, None] * (s - logN)
        else:
            t = col
        top = t.max(axis=0)
        w = np.exp(t - top)
        sw = w.sum(axis=0)
        return top + np.log(sw), (w * es[:, None]).sum(axis=0) / sw

    lu_k = lu[:, 1:]
    lu_1 = lu[:, :1]
    if sp.weighting == "distinct":
        q1, _ = logQ(lu_1, np.zeros(1))
        qk, _ = logQ(lu_k, np.zeros(len(ks)))
        return -(base + qk - q1) / (ks - 1.0)

    def h(s: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        qk, ek = logQ(lu_k[:, idx], s)
        q1, e1 = logQ(lu_1, s)
        kk = ks[idx] - 1.0
        return kk * s + base[idx] + qk - q1, kk + ek - e1

    every = np.arange(len(ks))
    lo = np.full(len(ks), -40.0)
    hi = np.full(len(ks), 40.0)
    for _ in range(20):
        hl, _ = h(lo, every)
        bad = hl >= 0
        if not bad.any():
            break
        lo = np.where(bad, 2 * lo, lo)
    for _ in range(20):
        hh, _ = h(hi, every)
        bad = hh <= 0
        if not bad.any():
            break
        hi = np.where(bad, 2 * hi, hi)
    s = np.clip(-base / (ks - 1.0), lo, hi)  # the simple-space root as a start
    act = every
    for _ in range(300):
        sa, la, ha = s[act], lo[act], hi[act]
        hv, dh = h(sa, act)
        la = np.where(hv < 0, sa, la)
        ha = np.where(hv > 0, sa, ha)
        with np.errstate(divide="ignore", invalid="ignore"):
            new = sa - hv / dh
        inside = (new > la) & (new < ha) & np.isfinite(new)
        new = np.where(inside, new, 0.5 * (la + ha))
        done = (np.abs(new - sa) <= 1e-13 * np.maximum(1.0, np.abs(sa))) | (hv == 0)
        s[act], lo[act], hi[act] = new, la, ha
        act = act[~done]
        if not len(act):
            break
    return s


def _float_h_at(sp: Space, N: int, s: float) -> np.ndarray:
    """float64 ``h_k(s)`` for ``k = 2..N``."""
    from scipy.special import gammaln

    lu = log_U_table(sp, N)
    ks = np.arange(2, N + 1, dtype=float)
    G = gammaln(float(N)) - gammaln(N - ks + 1.0) - (ks - 1.0) * math.log(N)
    es = np.arange(sp.max_excess + 1, dtype=float)
    t = lu + es[:, None] * (s - math.log(N)) if sp.weighting == "length" else lu
    top = t.max(axis=0)
    logQ = top + np.log(np.exp(t - top).sum(axis=0))
    return (ks - 1.0) * s + G - np.log(ks) + logQ[1:] - logQ[0]


# --------------------------------------------------------------------------- mpmath stage
def _log_Q_mp(sp: Space, k: int, p: Any) -> Any:
    U = sp.U(k)
    if sp.weighting == "distinct":
        return mpmath.log(sum(U))
    total = mpmath.mpf(0)
    pe = mpmath.mpf(1)
    for u in U:
        if u:
            total += pe * u
        pe *= p
    return mpmath.log(total)


def _h_mp(sp: Space, N: int, k: int, s: Any) -> Any:
    p = mpmath.exp(s) / N
    return ((k - 1) * s + G_mp(N, k - 1) - mpmath.log(k) + _log_Q_mp(sp, k, p)
            - _log_Q_mp(sp, 1, p))


def _dh_mp(sp: Space, N: int, k: int, s: Any) -> Any:
    if sp.weighting == "distinct":
        return mpmath.mpf(k - 1)
    p = mpmath.exp(s) / N

    def mean_excess(j: int) -> Any:
        U = sp.U(j)
        num = den = mpmath.mpf(0)
        for e, u in enumerate(U):
            t = p**e * u
            num += e * t
            den += t
        return num / den

    return (k - 1) + mean_excess(k) - mean_excess(1)


def _h_iv(iv: Any, sp: Space, N: int, k: int, s: Any) -> Any:
    si = iv.mpf(s)
    p = iv.exp(si) / N

    def logQ(j: int) -> Any:
        U = sp.U(j)
        if sp.weighting == "distinct":
            return iv.log(iv.mpf(sum(U)))
        total = iv.mpf(0)
        for e, u in enumerate(U):
            if u:
                total += p**e * iv.mpf(u)
        return iv.log(total)

    return (k - 1) * si + G_iv(iv, N, k - 1) - iv.log(iv.mpf(k)) + logQ(k) - logQ(1)


def _sign_iv(sp: Space, N: int, k: int, s: Any, bits: int) -> int:
    with iv_prec(bits) as iv:
        x = _h_iv(iv, sp, N, k, s)
    if x.a > 0:
        return 1
    if x.b < 0:
        return -1
    return 0


def _root_mp(sp: Space, N: int, k: int, s0: float, wp: int) -> Any:
    with mpmath.workdps(wp):
        if sp.weighting == "distinct":
            c = (G_mp(N, k - 1) - mpmath.log(k) + _log_Q_mp(sp, k, 1) - _log_Q_mp(sp, 1, 1))
            return -c / (k - 1)
        s = mpmath.mpf(s0)
        for _ in range(100):
            step = _h_mp(sp, N, k, s) / _dh_mp(sp, N, k, s)
            s -= step
            if abs(step) < mpmath.mpf(10) ** (-wp + 3) * max(1, abs(s)):
                break
        return s


def _try_rational(sp: Space, N: int, s: Any, ks: list[int], wp: int) -> Fraction | None:
    """``p = e**s / N`` as an exact rational at which every k in ks ties with 1, or None."""
    with mpmath.workdps(wp):
        p = mpmath.exp(s) / N
        man, exp = p.man_exp
    approx = Fraction(man) * Fraction(2) ** exp
    cand = approx.limit_denominator(10 ** max(4, wp // 3))
    if cand <= 0:
        return None
    with mpmath.workdps(wp):
        if abs(mpmath.mpf(cand.numerator) / cand.denominator - p) > abs(p) * mpmath.mpf(10) ** (
                -wp + 8):
            return None
    try:
        if all(compare_weights(sp, N, cand, 1, k) == 0 for k in ks):
            return cand
    except UndecidedError:
        return None
    return None


def critical_point(N: int, *, dps: int = 50, space: str | Space = "eq41",
                   weighting: str | None = None) -> CriticalPoint:
    """Where the mode of X over ``space`` leaves 1 (the first jump), for any ``N >= 2``.

    Parameters
    ----------
    N : int
        Vertices, ``2 <= N``; float64 arrays of length N are used, so ``N`` up to a few 10**6.
    dps : int
        Digits of ``p``, ``q``.
    space : str
        See :func:`symhx.spaces.parse_space`; ``"simple"`` is delegated to
        :func:`symhx.critical.critical_point`.
    weighting : str, optional
        ``"length"`` or ``"distinct"`` (instead of a ``;distinct`` suffix).

    Returns
    -------
    symhx.critical.CriticalPoint
        ``p = min_{k>=2} c_k``, ``q = N p - 1``, ``k_before = 1``, ``k_after`` the mode just
        above ``p``, ``argmins`` all k with ``c_k = p``, ``p_exact`` when rational. ``p_d`` is
        the *simple* space's discriminant root (eq. 16), kept for reference only: it has no
        meaning for the other spaces.

    >>> cp = critical_point(101, space="eq41", dps=20)
    >>> cp.k_before, cp.k_after
    (1, 23)
    """
    sp = parse_space(space, weighting)
    N = check_N(N)
    dps = check_dps(dps)
    if sp.base == "simple":
        from symhx.critical import critical_point as simple_cp

        return simple_cp(N, dps=dps)
    s_all = root_estimates(sp, N)
    kmin = int(np.argmin(s_all)) + 2
    s_min = float(s_all[kmin - 2])
    hv = _float_h_at(sp, N, s_min + 1e-9 * max(1.0, abs(s_min)))
    margin = screen_margin(N)
    cands = sorted({kmin, *(int(i) + 2 for i in np.nonzero(hv >= -margin)[0])})
    guard = 15 + 2 * digits_of(N)
    wp = dps + guard
    roots = {k: _root_mp(sp, N, k, float(s_all[k - 2]), wp) for k in cands}
    best = min(cands, key=lambda k: roots[k])
    with mpmath.workdps(wp):
        eps = mpmath.mpf(10) ** (-(dps + guard // 2)) * max(1, abs(roots[best]))
        s_lo, s_hi = roots[best] - eps, roots[best] + eps
    bits = iv_bits_for(N, wp + 10)
    if not (_sign_iv(sp, N, best, s_lo, bits) < 0 < _sign_iv(sp, N, best, s_hi, bits)):
        raise UndecidedError(f"could not bracket c_{best} for N={N}, space={sp.name}")
    argmins = [best]
    for k in cands:
        if k == best:
            continue
        sg = _sign_iv(sp, N, k, s_hi, bits)
        if sg < 0:
            continue  # c_k > s_hi >= c_best
        # c_k is within eps of c_best: an exact tie, or closer than the working precision
        with mpmath.workdps(wp):
            close = abs(roots[k] - roots[best]) <= 4 * eps
        if close:
            argmins.append(k)
            continue
        raise UndecidedError(f"ordering of c_{k} and c_{best} not certified (N={N})")
    argmins.sort()
    p_exact = None
    if len(argmins) > 1:
        p_exact = _try_rational(sp, N, roots[best], argmins, wp)
        if p_exact is None:
            raise UndecidedError(f"c_k for k in {argmins} agree to {dps + guard // 2} digits "
                                 f"but no exact rational tie was found (N={N}, {sp.name})")
    elif best * N.bit_length() < 200_000:
        p_exact = _try_rational(sp, N, roots[best], [best], wp)
    # the mode just above p_c: the tied k whose h_k grows fastest (largest k if equal)
    with mpmath.workdps(wp):
        slopes = {k: _dh_mp(sp, N, k, roots[best]) for k in argmins}
        k_after = max(argmins, key=lambda k: (slopes[k], k))
        s = roots[best]
        if p_exact is not None:
            p = mpmath.mpf(p_exact.numerator) / p_exact.denominator
            q = mpmath.mpf(N * p_exact.numerator - p_exact.denominator) / p_exact.denominator
        else:
            p = mpmath.exp(s) / N
            q = mpmath.expm1(s)
    with mpmath.workdps(dps):
        p, q = +p, +q
    return CriticalPoint(
        N=N, p=p, q=q, k_before=1, k_after=k_after, argmins=tuple(argmins),
        p_d=discriminant_root(N, dps=dps), p_exact=p_exact, dps=dps,
        sign_evaluations=len(cands),
    )
