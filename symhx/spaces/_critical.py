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

Algorithm (seed, then verify; ``N`` up to a few 10**6: the float64 seed uses arrays of length N,
memory ~ ``8 (m + 4) N`` bytes):

1. seed (decides nothing): float64 ``c_k`` for every k by a vectorised safeguarded Newton
   iteration; ``best`` = its argmin; its root refined with mpmath at ``dps`` + guard digits;
2. bracket: exact binary rationals ``p_lo < p_hi`` (relative gap ``~10**-(dps+3)``) with
   ``h_best(p_lo) < 0 < h_best(p_hi)`` proved by Arb balls; ``p_bounds = (p_lo, p_hi)``;
3. exclusion, by Arb balls: ``W(k)/W(1)`` at ``p_hi`` is built as a running product of the exact
   ratios ``W(k+1)/W(k) = p (N-k) k/(k+1) Q*(k+1)/Q*(k)``, and every ``k != best`` with
   ``W(k) < W(1)`` has ``c_k > p_hi``. The product stops at the first ``k > r_max`` where
   ``W(k) < W(1)`` and ``rho(k) = p (N-k) (k+m)/(k+1-r_max) < 1`` (exact rationals): ``rho`` is
   non-increasing and bounds every later ratio (mediant inequality on the non-negative
   polynomial coefficients of ``Q*``), so ``W`` decreases from there on;
4. the few ``k`` the product cannot exclude are decided by high-precision Arb signs of
   ``h_k(p_hi)`` and ``h_k(p_lo)``; roots inside the bracket are checked for an exact rational
   tie with integer arithmetic (:func:`symhx.spaces.compare_weights`), else the precision is
   raised.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from symhx._mpctx import export, mp
from symhx._numeric import G_mp, check_dps, check_N, digits_of
from symhx.certify import (
    G_arb,
    UndecidedError,
    arb_prec,
    bits_for,
    certified_sign,
    mpf_bounds,
    to_arb,
)
from symhx.critical import CriticalPoint, discriminant_root, discriminant_root_q
from symhx.spaces._classes import Space, parse_space
from symhx.spaces._dist import compare_weights, log_U_table
from symhx.validation import DEFAULT_DPS, DEFAULT_SPACE, as_fraction

__all__ = ["critical_point", "root_estimates"]

#: initial half-width of the float64 bracket of ``log(N c_k)`` in :func:`root_estimates`
#: (doubled, up to 20 times, on a side that does not bracket the root)
ROOT_BRACKET = 40.0

#: a lone argmin k (no tie) is still tried as an exact rational root c_k while
#: ``k * N.bit_length()`` is below this many bits: the exact comparison of the polynomial
#: weights costs about that size squared, and past it a rational c_k (none is known for k >= 3)
#: is not worth the time -- p_c is then returned as a certified ball only
RATIONAL_TRY_BITS = 200_000


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
    lo = np.full(len(ks), -ROOT_BRACKET)
    hi = np.full(len(ks), ROOT_BRACKET)
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


# --------------------------------------------------------------------------- mpmath stage
# (in the calling thread's context at its working precision: see symhx._mpctx)
def _log_Q_mp(sp: Space, k: int, p: Any) -> Any:
    ctx = mp()
    U = sp.U(k)
    if sp.weighting == "distinct":
        return ctx.log(sum(U))
    total = ctx.mpf(0)
    pe = ctx.mpf(1)
    for u in U:
        if u:
            total += pe * u
        pe *= p
    return ctx.log(total)


def _h_mp(sp: Space, N: int, k: int, s: Any) -> Any:
    ctx = mp()
    p = ctx.exp(s) / N
    return ((k - 1) * s + G_mp(N, k - 1) - ctx.log(k) + _log_Q_mp(sp, k, p)
            - _log_Q_mp(sp, 1, p))


def _dh_mp(sp: Space, N: int, k: int, s: Any) -> Any:
    ctx = mp()
    if sp.weighting == "distinct":
        return ctx.mpf(k - 1)
    p = ctx.exp(s) / N

    def mean_excess(j: int) -> Any:
        U = sp.U(j)
        num = den = ctx.mpf(0)
        for e, u in enumerate(U):
            t = p**e * u
            num += e * t
            den += t
        return num / den

    return (k - 1) + mean_excess(k) - mean_excess(1)


def _h_arb(sp: Space, N: int, k: int, fr: Fraction) -> Any:
    """Ball of ``h_k(p) = log W(k) - log W(1)`` at the exact rational ``p = fr``:
    ``(k-1) log(N p) + G(N, k-1) - log k + log Qnum(k) - log Qnum(1)``."""
    a, b = fr.numerator, fr.denominator
    return ((k - 1) * (to_arb(fr) * to_arb(N)).log() + G_arb(N, k - 1) - to_arb(k).log()
            + to_arb(sp.Qnum(k, a, b)).log() - to_arb(sp.Qnum(1, a, b)).log())


def _sign_h(sp: Space, N: int, k: int, fr: Fraction, bits: int) -> int:
    """Certified sign of ``h_k(fr)`` (0 only if an exact comparison finds a tie)."""
    return certified_sign(lambda: _h_arb(sp, N, k, fr), start_bits=bits, max_bits=8 * bits,
                          exact_fn=lambda: compare_weights(sp, N, fr, 1, k))


def _unexcluded(sp: Space, N: int, fr: Fraction, best: int) -> list[int]:
    """Every ``k != best`` that the running Arb product cannot prove to have ``W(k) < W(1)`` at
    ``p = fr`` (so every other k has ``c_k > fr``); see the module docstring, step 3."""
    a, b = fr.numerator, fr.denominator
    m, R = sp.max_excess, sp.max_parts
    out: list[int] = []
    bits = 96 + 2 * N.bit_length() + a.bit_length() + b.bit_length()
    with arb_prec(bits):
        pa = to_arb(fr)
        one = to_arb(1)
        ratio = one
        qprev = to_arb(sp.Qnum(1, a, b))
        for k in range(1, N):
            qk1 = to_arb(sp.Qnum(k + 1, a, b))
            ratio = ratio * pa * ((N - k) * k) / (k + 1) * qk1 / qprev
            qprev = qk1
            kk = k + 1  # ratio = W(kk) / W(1)
            below = ratio < one
            if not below and kk != best:
                out.append(kk)
            if (below and kk > R and kk > best
                    and fr * (N - kk) * (kk + m) < kk + 1 - R):
                break
    return out


def _root_mp(sp: Space, N: int, k: int, s0: float, wp: int) -> Any:
    """``log(N c_k)`` to ``wp`` digits by Newton's method from ``s0`` (this thread's context)."""
    ctx = mp()
    with ctx.workdps(wp):
        if sp.weighting == "distinct":
            c = (G_mp(N, k - 1) - ctx.log(k) + _log_Q_mp(sp, k, 1) - _log_Q_mp(sp, 1, 1))
            return -c / (k - 1)
        s = ctx.mpf(s0)
        for _ in range(100):
            step = _h_mp(sp, N, k, s) / _dh_mp(sp, N, k, s)
            s -= step
            if abs(step) < ctx.mpf(10) ** (-wp + 3) * max(1, abs(s)):
                break
        return s


def _try_rational(sp: Space, N: int, s: Any, ks: list[int], wp: int) -> Fraction | None:
    """``p = e**s / N`` as an exact rational at which every k in ks ties with 1, or None."""
    ctx = mp()
    with ctx.workdps(wp):
        p = ctx.exp(s) / N
        man, exp = p.man_exp
    approx = Fraction(man) * Fraction(2) ** exp
    cand = approx.limit_denominator(10 ** max(4, wp // 3))
    if cand <= 0:
        return None
    with ctx.workdps(wp):
        if abs(ctx.mpf(cand.numerator) / cand.denominator - p) > abs(p) * ctx.mpf(10) ** (
                -wp + 8):
            return None
    try:
        if all(compare_weights(sp, N, cand, 1, k) == 0 for k in ks):
            return cand
    except UndecidedError:
        return None
    return None


def _bracket(sp: Space, N: int, s: Any, dps: int, wp: int) -> tuple[Fraction, Fraction]:
    """Exact binary rationals ``p_lo < e**s/N < p_hi``, relative gap ``~ 10**-(dps+3)``."""
    ctx = mp()
    with ctx.workdps(wp):
        p = ctx.exp(s) / N
        eps = ctx.mpf(10) ** (-(dps + 3))
        lo, hi = p * (1 - eps), p * (1 + eps)
    flo, fhi = as_fraction(lo), as_fraction(hi)
    assert flo is not None and fhi is not None
    return flo, fhi


def critical_point(N: int, *, space: str | Space = DEFAULT_SPACE, dps: int = DEFAULT_DPS,
                   weighting: str | None = None) -> CriticalPoint:
    """Where the mode of X over ``space`` leaves 1 (the first jump), for any ``N >= 2``.

    Parameters
    ----------
    N : int
        Vertices, ``2 <= N``; the float64 seed uses arrays of length N, so ``N`` up to a few
        10**6.
    space : str or Space
        See :func:`symhx.spaces.parse_space`; ``"simple"`` is delegated to
        :func:`symhx.critical.critical_point`.
    dps : int
        Digits of ``p``, ``q`` and the relative width of ``p_bounds``.
    weighting : str, optional
        ``"length"`` or ``"distinct"`` (instead of a ``;distinct`` suffix).

    Returns
    -------
    symhx.critical.CriticalPoint
        ``p = min_{k>=2} c_k``, ``q = N p - 1``, ``k_before = 1``, ``k_after`` the mode just
        above ``p``, ``argmins`` all k with ``c_k = p``, ``p_exact`` when rational,
        ``p_bounds`` a rigorous enclosure (Arb). ``p_d`` is the *simple* space's discriminant
        root (eq. 16), kept for reference only: it has no meaning for the other spaces.

    >>> cp = critical_point(101, space="eq41", dps=20)
    >>> cp.k_before, cp.k_after
    (1, 23)
    >>> cp.p_bounds[0] < cp.p_bounds[1]
    True
    """
    sp = parse_space(space, weighting)
    N = check_N(N)
    d = check_dps(dps)
    assert d is not None
    dps = d
    if sp.base == "simple":
        from symhx.critical import critical_point as simple_cp

        return simple_cp(N, dps=dps)
    s_all = root_estimates(sp, N)  # float64 seed: decides nothing
    best = int(np.argmin(s_all)) + 2
    guard = 15 + 2 * digits_of(N)
    wp = dps + guard
    roots: dict[int, Any] = {}

    def root(k: int) -> Any:
        if k not in roots:
            roots[k] = _root_mp(sp, N, k, float(s_all[k - 2]), wp)
        return roots[k]

    bits = bits_for(N, int(wp * 3.33) + 32)
    evaluations = 0
    for _ in range(N):  # each pass either certifies or strictly lowers c_best
        p_lo, p_hi = _bracket(sp, N, root(best), dps, wp)
        evaluations += 2
        if not (_sign_h(sp, N, best, p_lo, bits) < 0 < _sign_h(sp, N, best, p_hi, bits)):
            raise UndecidedError(f"could not bracket c_{best} for N={N}, space={sp.name}")
        argmins, lower = [best], None
        for k in _unexcluded(sp, N, p_hi, best):
            evaluations += 1
            if _sign_h(sp, N, k, p_hi, bits) < 0:
                continue  # c_k > p_hi
            evaluations += 1
            if _sign_h(sp, N, k, p_lo, bits) >= 0:  # c_k <= p_lo < c_best: a better k
                lower = k
                break
            argmins.append(k)  # c_k inside the bracket: an exact tie or closer than it
        if lower is None:
            break
        best = lower
    else:  # pragma: no cover - c_best strictly decreases, so at most N passes
        raise UndecidedError(f"no certified argmin for N={N}, space={sp.name}")
    argmins.sort()
    p_exact = None
    if len(argmins) > 1:
        p_exact = _try_rational(sp, N, root(best), argmins, wp)
        if p_exact is None:
            raise UndecidedError(f"c_k for k in {argmins} agree to {dps + 3} digits but no "
                                 f"exact rational tie was found (N={N}, {sp.name})")
    elif best * N.bit_length() < RATIONAL_TRY_BITS:
        p_exact = _try_rational(sp, N, root(best), [best], wp)
    # the mode just above p_c: the tied k whose h_k grows fastest (largest k if equal)
    ctx = mp()
    with ctx.workdps(wp):
        slopes = {k: _dh_mp(sp, N, k, root(best)) for k in argmins}
        k_after = max(argmins, key=lambda k: (slopes[k], k))
    with arb_prec(int(wp * 3.33) + 64 + N.bit_length()):
        if p_exact is not None:
            p_lo = p_hi = p_exact
        pb = (mpf_bounds(to_arb(p_lo), dps)[0], mpf_bounds(to_arb(p_hi), dps)[1])
        qb = (mpf_bounds(to_arb(N * p_lo - 1), dps)[0], mpf_bounds(to_arb(N * p_hi - 1), dps)[1])
    with ctx.workdps(wp):
        if p_exact is not None:
            pw = ctx.mpf(p_exact.numerator) / p_exact.denominator
            qw = ctx.mpf(N * p_exact.numerator - p_exact.denominator) / p_exact.denominator
        else:
            pw = ctx.exp(root(best)) / N
            qw = ctx.expm1(root(best))
    p, q = export(pw, dps), export(qw, dps)
    pb = (min(pb[0], p), max(pb[1], p))
    qb = (min(qb[0], q), max(qb[1], q))
    return CriticalPoint(
        N=N, p=p, q=q, k_before=1, k_after=k_after, argmins=tuple(argmins),
        p_d=discriminant_root(N, dps=dps), p_exact=p_exact, dps=dps, p_bounds=pb,
        q_bounds=qb, q_d=discriminant_root_q(N, dps=dps), sign_evaluations=evaluations,
    )
