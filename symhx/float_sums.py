"""float64 partial sums of ``Phi_{N,p}(i)/Phi(c)`` over ``i <= k`` and ``i > k``, vectorised over
``k``, at any ``N`` that fits a float (eqs. 7-8): what ``cdf``, ``sf``, ``logcdf`` and ``logsf``
of the float64 path need beyond the table, with numpy and scipy only.

``f(x) = Phi(x)/Phi(c) = exp(D(x))`` with ``D`` from :func:`symhx.float_terms.log_phi_diff_real`
(Loader's form, absolute error ~``1e-16 (1 + |x - c| |log(p (N+1-c))| + |D|)``).  ``Phi``
decreases on ``[1, m]``, increases on ``[m, t]`` and decreases on ``[t, N]`` (``m``, ``t`` from
the quadratic ``p (N - k) k = k + 1`` in exact integers); each of these *runs* is monotone.

Plan (one structure per distribution, then every ``k`` by table look-ups and one small
Gauss-Legendre rule):

1. *Coordinates.*  A real point is an integer anchor (``0``, ``c`` or ``N + 1``, whichever is
   nearest) plus a float offset ``s``, so ``x``, ``x - c`` and ``N + 1 - x`` are each known to
   float relative accuracy (``N + 1 - x`` can be 3 while ``N`` is ``1e300``).
2. *Panels.*  Each run is cut where ``D`` crosses ``D_max - j LEVEL_STEP`` (``LEVEL_STEP = 6``
   nats; ``D_max`` the run's own maximum) down to ``D_max - COVER`` (``COVER = 800`` nats), at
   powers of 2 of the distance to ``0`` and ``N + 1`` (so no panel comes closer to a
   singularity of ``log Gamma`` than its own length), at ``x = 40``, ``N + 1 - x = 40`` and
   where ``|D'| = SLOPE_MAX = 0.3``.  Panels where ``|D'| > SLOPE_MAX`` or within 40 of an end
   are *summed directly* (at most ``6/0.3 + 1`` terms each); the others are *integrated*: a
   20-point Gauss-Legendre rule per panel (``D`` changes by at most 6 nats and the panel stays
   a factor 2 away from the singularities: error ``< 1e-20`` of the panel), cumulative panel
   sums in log-sum-exp form, and Euler-Maclaurin end corrections to order ``f^{(11)}`` at the
   ends of each smooth stretch and at ``k`` (``D^{(j)}`` from ``psi`` and ``polygamma``; the
   remainder is ``<= 2 (|D'|/(2 pi))**12 <= 1e-15`` of the stretch when ``|D'| <= 0.3``).
3. *Beyond the cover* (terms below ``exp(-800)`` of their run's maximum) a ``k`` sums a *window*
   of its own in the direction where ``f`` decreases, up to where ``D`` has fallen by 45 nats
   (Newton on ``D``): directly (at most ``WINDOW_DIRECT`` terms) or by Euler-Maclaurin with 12
   Gauss-Legendre panels.  Such a window's run total (the far part of a run) is one window too.
4. *Tails.*  ``log sum_{i<=k} f(i)`` is the log-sum-exp of the whole pieces left of ``k`` (from
   the left) and of ``k``'s own piece up to ``k``; ``log sum_{i>k} f(i)`` likewise from the
   right.  All terms are positive and each tail is accumulated from its own end, so both keep
   their relative accuracy however small they are (``logsf = -1e5`` is as accurate as
   ``sf = 0.3``).  The normaliser is their sum: ``cdf = L/(L + U)``, ``sf = U/(L + U)``.

5. *Scale.*  Every log is kept relative to ``Phi(c) 2**E`` (``E`` from the hump's width, then
   re-centred on the total), the width of a panel entering as an exact ``ldexp``: a log of
   size 345 (the hump's width at ``N = 1e300``) would keep only ``6e-14`` absolute.  Logs
   beyond ``-1.8e308`` (possible only for ``N`` near ``1e308``) are ``-inf``.

Error: ~``1e-15`` relative in each tail from the quadrature and EM terms, plus the error of
``D`` itself (~``1e-16 |D|``, so relative ``~1e-16 |log tail|`` far in a tail; the log forms are
good to ``~1e-15 (1 + |value|)`` absolute).  Measured against the mpmath engine at 30 digits,
the log-series and Poisson laws and every term summed: below ``5e-16`` (relative, or
``(1 + |log|)`` absolute) from ``N = 1e7`` to ``1.7e308``.  Cost: the structure takes
8000-25000 evaluations of ``D`` (10-100 ms); each distinct ``k`` then costs 30-170
evaluations, vectorised (1000 ``k``: 0.02-0.1 s).

>>> from fractions import Fraction
>>> import numpy as np
>>> N, p = 10**10, Fraction(2, 10**10)
>>> fs = FloatSums(N, p, N // 2, float(np.log(2 * (N // 2 + 1) / N)))
>>> lo, up = fs.log_tails(np.array([N // 2]))
>>> bool(abs(np.exp(lo[0] - np.logaddexp(lo[0], up[0])) - 0.5) < 1e-4)
True
"""

from __future__ import annotations

import bisect
import itertools
import math
from fractions import Fraction
from typing import Any

import numpy as np
from numpy.polynomial.legendre import leggauss

from symhx.float_terms import log_phi_diff_real, log_ratio

__all__ = ["COVER", "LEVEL_STEP", "SLOPE_MAX", "WINDOW_DIRECT", "FloatSums"]

#: runs are built (panels, direct blocks) down to this many nats below their maximum
COVER = 800.0
#: the change of ``D`` allowed across one panel (nats)
LEVEL_STEP = 6.0
#: where ``|D'|`` exceeds this, terms are summed one by one (Euler-Maclaurin needs a smooth run)
SLOPE_MAX = 0.3
#: within this distance of ``0`` and ``N + 1`` the terms are summed one by one
_EDGE = 40.0
#: nats a far-tail window runs down from its first term
_WINDOW_DROP = 45.0
#: a window of at most this many terms is summed directly
WINDOW_DIRECT = 600
_WINDOW_PANELS = 12
#: a direct block never holds more terms than this (steep runs have at most ~20 per panel)
_DIRECT_MAX = 100_000
#: Euler-Maclaurin order M: corrections with f', f''', ..., f^{(2M-1)}
_EM_M = 6
_GL_X, _GL_W = leggauss(20)
_GL_X = 0.5 * (_GL_X + 1.0)  # on [0, 1]
_GL_W = 0.5 * _GL_W
#: B_{2j} / (2j)!, j = 1..M
_EM_COEF = np.array([1 / 6, -1 / 30, 1 / 42, -1 / 30, 5 / 66, -691 / 2730]) / np.array(
    [math.factorial(2 * j) for j in range(1, _EM_M + 1)], dtype=float)


def _turns(N: int, fr: Fraction) -> tuple[int, int]:
    """``(m, t)``: ``Phi`` decreases on ``[1, m]``, increases on ``[m, t]``, decreases on
    ``[t, N]`` (``m = t`` when it never increases), in exact integers: ``Phi(k+1) >= Phi(k)``
    iff ``F(k) = -a k**2 + (N a - b) k - b >= 0`` for ``p = a/b``."""
    a, b = fr.numerator, fr.denominator
    A = N * a - b
    disc = A * A - 4 * a * b
    if A <= 0 or disc < 0:
        return N, N
    r = math.isqrt(disc)

    def F(k: int) -> int:
        return -a * k * k + A * k - b

    hi = (A + r) // (2 * a) + 2
    while hi > 0 and F(hi) < 0:
        hi -= 1
    lo = max(1, (A - r) // (2 * a) - 2)
    while lo <= hi and F(lo) < 0:
        lo += 1
    hi = min(hi, N - 1)
    if lo > hi or hi < 1:
        return N, N
    return lo, hi + 1


def _ln2_residual(E: int, shift: float) -> float:
    """``E log 2 - shift`` for the float ``shift`` nearest ``E log 2`` (exact rational
    arithmetic on a 40-digit ``log 2``)."""
    ln2 = Fraction("0.6931471805599453094172321214581765680755")
    return float(E * ln2 - Fraction(shift))


class _Seg:
    """Points ``x = A + sigma s`` (``s >= 0`` a float) for one anchor ``A`` of ``0, c, N+1``."""

    def __init__(self, N: int, c: int, A: int, sigma: int) -> None:
        self.A, self.sigma = A, sigma
        self.ax = float(A)
        self.dc = float(A - c)
        self.yy = float(N + 1 - A)

    def s_of(self, k: int) -> float:
        return float((k - self.A) * self.sigma)

    def k_of(self, s: float) -> int:
        return self.A + self.sigma * int(s)


class FloatSums:
    """Lower and upper partial sums of ``f(i) = Phi(i)/Phi(c)`` (eq. 7) in float64, vectorised
    over ``k`` (see the module docstring for the method and its error).

    Parameters
    ----------
    N : int
        Number of impacts, ``2 <= N <= 1.8e308``.
    fr : Fraction
        ``p > 0`` (exact; it places the turning points of ``Phi``).
    c : int
        The reference index of the terms, ``1 <= c <= N``.
    log_px : float
        ``log(p (N + 1 - c))`` to float accuracy.
    """

    def __init__(self, N: int, fr: Fraction, c: int, log_px: float) -> None:
        self.N, self.c, self.lpx = N, c, log_px
        self.u = float(N + 1 - c)
        m, t = _turns(N, fr)
        # runs: (lo, hi, decreasing?) in x order; max at lo when decreasing, at hi otherwise
        runs: list[tuple[int, int, bool]] = []
        if m > 1:
            runs.append((1, m, True))
        if t > m:
            runs.append((m, t, False))
        if t < N:
            runs.append((t, N, True))
        self._runs = runs
        # anchors: 0 on [1, c/2], c on [c/2, c + u/2], N + 1 beyond
        u = N + 1 - c
        b1, b3 = max(1, c // 2), min(N, c + u // 2)
        self._segs = [_Seg(N, c, 0, 1), _Seg(N, c, c, -1), _Seg(N, c, c, 1),
                      _Seg(N, c, N + 1, -1)]
        self._seg_cuts = [(1, b1, 0), (b1, c, 1), (c, b3, 2), (b3, N, 3)]
        # the sums are kept relative to Phi(c) 2**E (E ~ log2 of the hump's width), so that
        # logs near the bulk are O(1) and keep ~1e-16 absolute (a log ~ 345 would keep 6e-14)
        E = 0
        if 1 < c < N:
            curv = 1 / u + (0.5 / u) / u - (1 / c) / c  # -D''(c) ~ psi'(N + 1 - c) - 1/c**2
            if curv > 0:
                E = max(0, min(1000, round(0.5 * (math.log2(2 * math.pi) - math.log2(curv)))))
        self.E = E
        self.shift = E * math.log(2)
        self._rho = _ln2_residual(E, self.shift)
        self._build()

    # ------------------------------------------------------------------ evaluation of D
    def _seg_of(self, k: int) -> int:
        for lo, hi, i in self._seg_cuts:
            if lo <= k <= hi:
                return i
        raise AssertionError(k)  # pragma: no cover

    def _xdy(self, seg: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, ...]:
        ax = np.array([g.ax for g in self._segs])[seg]
        dc = np.array([g.dc for g in self._segs])[seg]
        yy = np.array([g.yy for g in self._segs])[seg]
        sg = np.array([float(g.sigma) for g in self._segs])[seg]
        return ax + sg * s, dc + sg * s, yy - sg * s

    def _D(self, seg: np.ndarray, s: np.ndarray) -> np.ndarray:
        x, d, y = self._xdy(seg, s)
        with np.errstate(over="ignore", invalid="ignore"):
            v = log_phi_diff_real(self.c, self.lpx, self.u, x, d, y)
        return np.where(np.isnan(v), -np.inf, v)  # beyond -1.8e308 (N ~ 1e308 only)

    def _derivs(self, seg: np.ndarray, s: np.ndarray, order: int) -> list[np.ndarray]:
        """``[D'(x), D''(x), ..., D^{(order)}(x)]`` (derivatives in ``x``)."""
        from scipy.special import digamma, polygamma

        x, d, y = self._xdy(seg, s)
        big = y >= 15
        yb = np.where(big, y, 15.0)
        inv = 1 / yb
        inv2 = inv * inv
        ser = -0.5 * inv - inv2 * (1 / 12 - inv2 * (1 / 120 - inv2 / 252))  # psi(y) - log y
        ys = np.where(big, 1.0, y)
        small = digamma(ys) - np.log(ys)
        with np.errstate(divide="ignore", invalid="ignore"):
            log_py = self.lpx + log_ratio(y, np.full_like(y, self.u), d)
        out = [np.nan_to_num(log_py + np.where(big, ser, small) - 1 / x, nan=0.0)]
        with np.errstate(over="ignore", under="ignore"):
            for j in range(2, order + 1):
                sign = 1.0 if j % 2 == 0 else -1.0
                out.append(sign * (math.factorial(j - 1) / x**j - polygamma(j - 1, y)))
        return out

    def _em_end(self, seg: np.ndarray, s: np.ndarray, upper: bool) -> np.ndarray:
        """``log`` of the Euler-Maclaurin end coefficient ``1/2 +- sum_j B_2j/(2j)! f^(2j-1)/f``
        (``+`` at the upper end of a run in x, ``-`` at its lower end)."""
        n = 2 * _EM_M - 1
        der = self._derivs(seg, s, n)
        tau = [der[j - 1] / math.factorial(j) for j in range(1, n + 1)]
        e = [np.ones_like(s)]
        for k in range(1, n + 1):
            e.append(sum(j * tau[j - 1] * e[k - j] for j in range(1, k + 1)) / k)
        corr = sum(_EM_COEF[j - 1] * math.factorial(2 * j - 1) * e[2 * j - 1]
                   for j in range(1, _EM_M + 1))
        return np.log(0.5 + corr if upper else 0.5 - corr)

    def _gl(self, seg: np.ndarray, sa: np.ndarray, sb: np.ndarray) -> np.ndarray:
        """``log int f dx`` over ``s`` in ``[sa, sb]`` of each segment (20-point rule)."""
        h = (sb - sa)[:, None]
        nodes = sa[:, None] + h * _GL_X[None, :]
        segs = np.broadcast_to(seg[:, None], nodes.shape)
        lv = self._D(segs.ravel(), nodes.ravel()).reshape(nodes.shape)
        top = lv.max(axis=1)
        with np.errstate(divide="ignore"):
            return top + np.log(np.ldexp(np.abs(h[:, 0]), -self.E)
                                * (np.exp(lv - top[:, None]) @ _GL_W)) + self._rho

    # ------------------------------------------------------------------ the structure
    def _bisect(self, seg: np.ndarray, sa: np.ndarray, sb: np.ndarray,
                fun: Any) -> np.ndarray:
        """Points where ``fun(seg, s)`` changes sign between ``sa`` and ``sb`` (arrays)."""
        fa = fun(seg, sa)
        lo, hi = sa.astype(float), sb.astype(float)  # lo < hi; fun changes sign in between
        for _ in range(200):
            base = np.maximum(lo, 1.0)
            mid = np.where(hi / 4 > base, np.sqrt(base) * np.sqrt(hi), lo + 0.5 * (hi - lo))
            fm = fun(seg, mid)
            same = np.sign(fm) == np.sign(fa)
            lo = np.where(same, mid, lo)
            hi = np.where(same, hi, mid)
            if np.all(hi - lo <= 4e-16 * np.maximum(hi, 1.0)):
                break
        return 0.5 * (lo + hi)

    def _build(self) -> None:
        N = self.N
        panels: list[tuple[int, int, float, float, bool, bool]] = []  # seg, run, sl, sr, cov, sm
        self._run_max: list[float] = []
        cuts = sorted({1, N, *(v for lo, hi, _ in self._seg_cuts for v in (lo, hi))})
        for ri, (lo, hi, dec) in enumerate(self._runs):
            top = lo if dec else hi
            ts = self._seg_of(top)
            dmax = float(self._D(np.array([ts]), np.array([self._segs[ts].s_of(top)]))[0])
            self._run_max.append(dmax)
            pts = sorted({lo, hi, *(v for v in cuts if lo < v < hi)})
            for a, b in itertools.pairwise(pts):
                si = next(i for l2, h2, i in self._seg_cuts if l2 <= a and b <= h2)
                panels.extend(self._sub_panels(si, ri, a, b, dmax))
        self._make_items(panels)
        # re-centre the logs when the sum is far from Phi(c) 2**E (a head spread over many
        # decades of x: the hump's width is not the scale then); the panels stay
        tot = float(np.logaddexp.reduce([it["total"] for it in self._items]))
        if abs(tot) > 2 and np.isfinite(tot):
            self.E += round(tot / math.log(2))
            self.shift = self.E * math.log(2)
            self._rho = _ln2_residual(self.E, self.shift)
            self._make_items(panels)

    def _sub_panels(self, si: int, ri: int, a: int, b: int, dmax: float
                    ) -> list[tuple[int, int, float, float, bool, bool]]:
        """Panels of the part ``[a, b]`` (integers, one anchor) of run ``ri``, in x order."""
        g = self._segs[si]
        s_a, s_b = g.s_of(a), g.s_of(b)
        lo_s, hi_s = min(s_a, s_b), max(s_a, s_b)
        if hi_s == lo_s:
            return []
        da, db = self._D(np.array([si, si]), np.array([lo_s, hi_s]))
        cand = [lo_s, hi_s]
        levels = dmax - LEVEL_STEP * np.arange(1, int(COVER / LEVEL_STEP) + 2)
        inside = levels[(levels > min(da, db)) & (levels < max(da, db))]
        if inside.size:
            n = inside.size
            segs = np.full(n, si)
            lv = inside

            def fl(sg: np.ndarray, s: np.ndarray) -> np.ndarray:
                return self._D(sg, s) - lv

            cand += list(self._bisect(segs, np.full(n, lo_s), np.full(n, hi_s), fl))
        # powers of two of x and of N + 1 - x (no panel closer to 0 or N + 1 than its
        # length), and the edges x = 40, N + 1 - x = 40 of the direct sums
        marks = [1 << e for e in range(max(a.bit_length() - 1, 0), b.bit_length() + 1)]
        marks.append(int(_EDGE))
        ys = [self.N + 1 - v for v in marks]
        cand += [g.s_of(v) for v in marks + ys if a < v < b]
        pts = np.unique(np.array(cand))
        # where |D'| crosses SLOPE_MAX
        d1 = self._derivs(np.full(pts.size, si), pts, 1)[0]
        sgn = np.sign(np.abs(d1) - SLOPE_MAX)
        ch = np.nonzero(sgn[:-1] * sgn[1:] < 0)[0]
        if ch.size:
            def fs(sg: np.ndarray, s: np.ndarray) -> np.ndarray:
                return np.abs(self._derivs(sg, s, 1)[0]) - SLOPE_MAX

            extra = self._bisect(np.full(ch.size, si), pts[ch], pts[ch + 1], fs)
            pts = np.unique(np.concatenate([pts, extra]))
        mid = 0.5 * (pts[:-1] + pts[1:])
        segm = np.full(mid.size, si)
        dm = self._D(segm, mid)
        d1m = self._derivs(segm, mid, 1)[0]
        x, _, y = self._xdy(segm, mid)
        cov = dm >= dmax - COVER
        smooth = (np.abs(d1m) <= SLOPE_MAX) & (x >= _EDGE) & (y >= _EDGE)
        out = [(si, ri, float(pts[j]), float(pts[j + 1]), bool(cov[j]), bool(smooth[j]))
               for j in range(mid.size)]
        if g.sigma < 0:  # x order
            out = [(s_, r_, b_, a_, c_, m_) for s_, r_, a_, b_, c_, m_ in reversed(out)]
        return out

    def _make_items(self, panels: list[tuple[int, int, float, float, bool, bool]]) -> None:
        """Group the panels into items that own consecutive integers: ``direct`` (terms),
        ``em`` (panels + end corrections) and ``far`` (beyond the cover: windows)."""
        groups: list[list[tuple[int, int, float, float, bool, bool]]] = []
        for pnl in panels:
            key = (pnl[1], pnl[4], pnl[4] and pnl[5])
            if groups and (groups[-1][0][1], groups[-1][0][4],
                           groups[-1][0][4] and groups[-1][0][5]) == key:
                groups[-1].append(pnl)
            else:
                groups.append([pnl])
        items: list[dict[str, Any]] = []
        prev_hi = 0
        for grp in groups:
            si_r, ri = grp[-1][0], grp[-1][1]
            g_r = self._segs[si_r]
            s_end = grp[-1][3]
            s_int = math.floor(s_end) if g_r.sigma > 0 else math.ceil(s_end)
            hi = g_r.A + g_r.sigma * s_int
            hi = min(max(hi, prev_hi), self.N)
            if grp is groups[-1]:
                hi = self.N
            lo = prev_hi + 1
            if hi < lo:
                continue
            prev_hi = hi
            cov, smooth = grp[0][4], grp[0][5]
            if not cov:
                kind = "far"
            elif (smooth and hi - lo > 64) or hi - lo > _DIRECT_MAX:
                kind = "em"
            else:
                kind = "direct"
            items.append({"kind": kind, "lo": lo, "hi": hi, "run": ri, "panels": grp})
        self._items = items
        self._los = [it["lo"] for it in items]
        for it in items:
            getattr(self, "_fill_" + it["kind"])(it)
        tot = np.array([it["total"] for it in items])
        self._prefix = np.concatenate([[-np.inf], np.logaddexp.accumulate(tot)])
        self._suffix = np.concatenate([np.logaddexp.accumulate(tot[::-1])[::-1], [-np.inf]])

    def _int_points(self, ks: list[int]) -> tuple[np.ndarray, np.ndarray]:
        seg = np.array([self._seg_of(k) for k in ks], dtype=int)
        s = np.array([self._segs[i].s_of(k) for i, k in zip(seg, ks, strict=True)])
        return seg, s

    def _fill_direct(self, it: dict[str, Any]) -> None:
        ks = np.arange(it["hi"] - it["lo"] + 1)
        if self.N < 2**53:
            lv = self._D_int(it["lo"] + ks) - self.shift
        else:
            seg, s0 = self._int_points([it["lo"]])
            sg = self._segs[int(seg[0])].sigma
            lv = self._D(np.full(ks.size, seg[0]), s0[0] + sg * ks.astype(float)) - self.shift
        it["cum"] = np.logaddexp.accumulate(lv)
        it["rcum"] = np.concatenate([np.logaddexp.accumulate(lv[::-1])[::-1], [-np.inf]])
        it["total"] = float(it["cum"][-1])

    def _D_int(self, ks: np.ndarray) -> np.ndarray:
        from symhx.float_terms import log_phi_diff

        return log_phi_diff(self.N, self.c, self.lpx, ks)

    def _fill_em(self, it: dict[str, Any]) -> None:
        grp = it["panels"]
        # panel ends in s of each panel's own segment, first and last snapped to lo and hi
        seg = np.array([p[0] for p in grp])
        sl = np.array([p[2] for p in grp])
        sr = np.array([p[3] for p in grp])
        # the item owns lo..hi: panel parts left of lo or right of hi (slivers of a panel
        # narrower than the rounding to integers) are cut off
        for j in range(len(grp)):
            g = self._segs[int(seg[j])]
            s_lo = g.s_of(it["lo"])
            if (sl[j] - s_lo) * g.sigma >= 0:
                break
            sl[j] = s_lo if (sr[j] - s_lo) * g.sigma > 0 else sr[j]
        for j in range(len(grp) - 1, -1, -1):
            g = self._segs[int(seg[j])]
            s_hi = g.s_of(it["hi"])
            if (s_hi - sr[j]) * g.sigma >= 0:
                break
            sr[j] = s_hi if (s_hi - sl[j]) * g.sigma > 0 else sl[j]
        it["seg"], it["sl"], it["sr"] = seg, sl, sr
        li = self._gl(seg, sl, sr)
        it["pcum"] = np.concatenate([[-np.inf], np.logaddexp.accumulate(li)])
        it["psuf"] = np.concatenate([np.logaddexp.accumulate(li[::-1])[::-1], [-np.inf]])
        ends_seg, ends_s = self._int_points([it["lo"], it["hi"]])
        fe = self._D(ends_seg, ends_s) - self.shift
        it["elo"] = fe[0] + self._em_end(ends_seg[:1], ends_s[:1], False)[0]
        it["ehi"] = fe[1] + self._em_end(ends_seg[1:], ends_s[1:], True)[0]
        it["total"] = float(np.logaddexp.reduce([it["pcum"][-1], it["elo"], it["ehi"]]))

    def _fill_far(self, it: dict[str, Any]) -> None:
        dec = self._runs[it["run"]][2]
        start = it["lo"] if dec else it["hi"]
        it["total"] = float(self._windows([start], [it["hi"] if dec else it["lo"]])[0])

    # ------------------------------------------------------------------ windows
    def _windows(self, starts: list[int], bounds: list[int]) -> np.ndarray:
        """``log sum f(i)`` from each ``start`` towards ``bound`` (inclusive), ``f`` decreasing
        that way: until ``D`` has fallen by ``_WINDOW_DROP`` nats."""
        seg, s0 = self._int_points(starts)
        d0 = self._D(seg, s0)
        if not np.all(np.isfinite(d0)):  # a first term beyond -1.8e308 (N ~ 1e308): so is
            out = np.full(len(starts), -np.inf)  # the window's log
            ok = np.nonzero(np.isfinite(d0))[0]
            if ok.size:
                out[ok] = self._windows([starts[i] for i in ok], [bounds[i] for i in ok])
            return out
        sig = np.array([self._segs[i].sigma for i in seg], dtype=float)
        step = np.array([1.0 if b >= a else -1.0 for a, b in zip(starts, bounds, strict=True)])
        e = step * sig  # direction in s
        span = np.array([float(abs(b - a)) for a, b in zip(starts, bounds, strict=True)])
        g = np.abs(self._derivs(seg, s0, 1)[0])
        # Newton for the point where D = d0 - drop, from the linear guess, kept in the span
        w = np.minimum(span, _WINDOW_DROP / np.maximum(g, 1e-300))
        for _ in range(40):
            phi = self._D(seg, s0 + e * w) - (d0 - _WINDOW_DROP)  # > 0: not reached yet
            gw = np.abs(self._derivs(seg, s0 + e * w, 1)[0])
            nw = np.clip(w + phi / np.maximum(gw, 1e-300), np.maximum(w / 4, 0.0),
                         4 * w + 10)
            nw = np.minimum(nw, span)
            done = np.all(np.abs(nw - w) <= 1e-9 * np.maximum(w, 1.0))
            w = nw
            if done:
                break
        w = np.minimum(np.ceil(np.nan_to_num(w, nan=0.0)), span)
        out = np.empty(len(starts))
        direct = (w <= WINDOW_DIRECT) | (g > SLOPE_MAX)
        wd = np.where(direct, np.minimum(w, 4 * WINDOW_DIRECT), 0.0)
        bucket = np.ceil(np.log2(wd + 2)).astype(int)  # rows of similar length together
        for bk in np.unique(bucket[direct]):
            idx = np.nonzero(direct & (bucket == bk))[0]
            n = int(wd[idx].max()) + 1
            j = np.arange(n, dtype=float)
            pts = s0[idx, None] + e[idx, None] * np.minimum(j[None, :], w[idx, None])
            lv = self._D(np.broadcast_to(seg[idx, None], pts.shape).ravel(),
                         pts.ravel()).reshape(pts.shape) - self.shift
            lv = np.where(j[None, :] <= w[idx, None], lv, -np.inf)
            out[idx] = np.logaddexp.reduce(lv, axis=1)
        if (~direct).any():
            idx = np.nonzero(~direct)[0]
            P = _WINDOW_PANELS
            fr = np.arange(P + 1) / P
            a = s0[idx, None] + e[idx, None] * w[idx, None] * fr[None, :-1]
            b = s0[idx, None] + e[idx, None] * w[idx, None] * fr[None, 1:]
            sg = np.broadcast_to(seg[idx, None], a.shape).ravel()
            li = self._gl(sg, np.minimum(a, b).ravel(), np.maximum(a, b).ravel())
            li = np.logaddexp.reduce(li.reshape(a.shape), axis=1)
            s1 = s0[idx] + e[idx] * w[idx]
            upper_first = step[idx] < 0  # the start is the upper end in x
            c0 = np.where(upper_first, self._em_end(seg[idx], s0[idx], True),
                          self._em_end(seg[idx], s0[idx], False))
            c1 = np.where(upper_first, self._em_end(seg[idx], s1, False),
                          self._em_end(seg[idx], s1, True))
            out[idx] = np.logaddexp.reduce(
                [li, d0[idx] + c0 - self.shift, self._D(seg[idx], s1) + c1 - self.shift],
                axis=0)
        return out

    # ------------------------------------------------------------------ queries
    def log_tails(self, k: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(log sum_{i<=k} f(i), log sum_{i>k} f(i)) - shift`` for integers
        ``1 <= k <= N - 1`` (an array of ints, Python ints for ``N > 2**63``),
        ``f(i) = Phi(i)/Phi(c)`` (the attribute ``shift = E log 2`` keeps the logs of the bulk
        near 0).

        Returns
        -------
        tuple of numpy.ndarray
            The two logs, shaped like ``k``.
        """
        kk = np.asarray(k)
        flat = [int(v) for v in kk.ravel()]
        uniq = sorted(set(flat))
        low = np.empty(len(uniq))
        upp = np.empty(len(uniq))
        where = [bisect.bisect_right(self._los, v) - 1 for v in uniq]
        groups: dict[str, list[int]] = {"direct": [], "em": [], "far": []}
        for qi, ii in enumerate(where):
            groups[self._items[ii]["kind"]].append(qi)
        for qi in groups["direct"]:
            it = self._items[where[qi]]
            j = uniq[qi] - it["lo"]
            low[qi] = np.logaddexp(self._prefix[where[qi]], it["cum"][j])
            upp[qi] = np.logaddexp(self._suffix[where[qi] + 1], it["rcum"][j + 1])
        if groups["em"]:
            self._em_queries(groups["em"], uniq, where, low, upp)
        if groups["far"]:
            self._far_queries(groups["far"], uniq, where, low, upp)
        pos = {v: i for i, v in enumerate(uniq)}
        ix = np.array([pos[v] for v in flat], dtype=int).reshape(kk.shape)
        return low[ix], upp[ix]

    def _em_queries(self, qs: list[int], uniq: list[int], where: list[int], low: np.ndarray,
                    upp: np.ndarray) -> None:
        n = len(qs)
        seg_j, s_j, sl = np.zeros(n, int), np.zeros(n), np.zeros(n)
        seg_j1, s_j1, sr = np.zeros(n, int), np.zeros(n), np.zeros(n)
        cum, suf, elo, ehi = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
        last = np.zeros(n, bool)
        for i, q in enumerate(qs):
            k, it = uniq[q], self._items[where[q]]
            j = self._panel_of(it, k)
            seg_j[i] = it["seg"][j]
            s_j[i] = self._segs[seg_j[i]].s_of(k)
            sl[i], cum[i], elo[i] = it["sl"][j], it["pcum"][j], it["elo"]
            if k < it["hi"]:
                j1 = self._panel_of(it, k + 1)
                seg_j1[i] = it["seg"][j1]
                s_j1[i] = self._segs[seg_j1[i]].s_of(k + 1)
                sr[i], suf[i], ehi[i] = it["sr"][j1], it["psuf"][j1 + 1], it["ehi"]
            else:
                last[i] = True
                seg_j1[i], s_j1[i], sr[i] = seg_j[i], s_j[i], s_j[i]
        qa = np.array(qs)
        wi = np.array([where[q] for q in qs])
        # lower: panels before j, then [sl_j, k], + f(lo) E-(lo) + f(k) E+(k)
        part = np.where(sl == s_j, -np.inf,
                        self._gl(seg_j, np.minimum(sl, s_j), np.maximum(sl, s_j)))
        fk = self._D(seg_j, s_j) + self._em_end(seg_j, s_j, True) - self.shift
        low[qa] = np.logaddexp.reduce([self._prefix[wi], cum, part, elo, fk], axis=0)
        # upper: [k + 1, sr_j1], then panels after j1, + f(k+1) E-(k+1) + f(hi) E+(hi)
        part = np.where((sr == s_j1) | last, -np.inf,
                        self._gl(seg_j1, np.minimum(sr, s_j1), np.maximum(sr, s_j1)))
        fk1 = np.where(last, -np.inf,
                       self._D(seg_j1, s_j1) + self._em_end(seg_j1, s_j1, False)
                       - self.shift)
        ehi = np.where(last, -np.inf, ehi)
        suf = np.where(last, -np.inf, suf)
        upp[qa] = np.logaddexp.reduce([self._suffix[wi + 1], suf, part, fk1, ehi], axis=0)

    def _panel_of(self, it: dict[str, Any], k: int) -> int:
        """Index of the panel of an em item that contains the integer ``k``."""
        # panels are in x order; compare in x through each panel's own segment
        segs, sr = it["seg"], it["sr"]
        lo, hi = 0, len(sr) - 1
        while lo < hi:
            mid = (lo + hi) // 2
            g = self._segs[int(segs[mid])]
            if g.s_of(k) * g.sigma <= sr[mid] * g.sigma:  # k <= right end of panel mid
                hi = mid
            else:
                lo = mid + 1
        return lo

    def _far_queries(self, qs: list[int], uniq: list[int], where: list[int],
                     low: np.ndarray, upp: np.ndarray) -> None:
        for q in qs:
            low[q], upp[q] = -np.inf, -np.inf
        dec_q = [q for q in qs if self._runs[self._items[where[q]]["run"]][2]]
        inc_q = [q for q in qs if not self._runs[self._items[where[q]]["run"]][2]]
        if dec_q:  # upper: a window from k + 1 to the item's end; lower: everything before
            st = [uniq[q] + 1 for q in dec_q]
            bd = [self._items[where[q]]["hi"] for q in dec_q]
            ok = [i for i, (a, b) in enumerate(zip(st, bd, strict=True)) if a <= b]
            win = np.full(len(dec_q), -np.inf)
            if ok:
                win[ok] = self._windows([st[i] for i in ok], [bd[i] for i in ok])
            for i, q in enumerate(dec_q):
                low[q] = self._prefix[where[q]]
                upp[q] = np.logaddexp(win[i], self._suffix[where[q] + 1])
        if inc_q:  # lower: a window from k down to the item's start
            win = self._windows([uniq[q] for q in inc_q],
                                [self._items[where[q]]["lo"] for q in inc_q])
            for i, q in enumerate(inc_q):
                low[q] = np.logaddexp(self._prefix[where[q]], win[i])
                upp[q] = self._suffix[where[q] + 1]
