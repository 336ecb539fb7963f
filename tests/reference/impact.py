"""Independent references for the impact simulation (section 7, eqs. 17-21).

Nothing here imports ``symhx.impact.engine``: every quantity is written out again from the model
(Newton's law, the closed-form free flight, Newton's restitution law) in numpy or mpmath.

* :func:`single_pipe_closed_form`, :func:`ode_free_flight`: one pipe in free flight under its
  forcing, in closed form and by integrating the equation of motion (``mpmath.odefun``);
* :func:`contact_forces`, :func:`stuck_at`: the contact force of every stuck contact from the
  positions of the pipes and the row's forces (Newton's law of the stuck cluster), and which
  contacts are stuck at given times (from a history's STICK / RELEASE events);
* :func:`trig_value`, :func:`trig_root`, :func:`first_root_on_grid`: a trigonometric polynomial
  ``c0 + sum_m a_m cos(F_m t) + b_m sin(F_m t)`` and its roots at 50 digits;
* :func:`independent_impacts`: an event-driven solver of its own (dense sign scan + Anderson at
  60 digits) for elastic / inelastic rows without sticking;
* :func:`brute_min_of_gap`: the minimum of a free gap over a window by a dense scan refined by
  golden sections (eq. 27's free-flight closure, brute force);
* :func:`documented_draw`, :func:`documented_redraws`, :func:`forced_at_zero`: the random row of
  section 7 and its documented non-overlap rule, written out from ``PipeRow.random``'s
  docstring;
* :func:`nearest_binary`, :func:`sqrt2_rounded`: correct rounding in integer arithmetic;
* :func:`count_by_hand`, :func:`documented_bootstrap`, :func:`documented_thresholds_estimate`,
  :func:`mutual_information_by_definition`: the ensemble's counts and statistics written out
  from their documented definitions.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

__all__ = ["brute_min_of_gap", "contact_forces", "count_by_hand", "documented_bootstrap",
           "documented_draw", "documented_redraws", "documented_thresholds_estimate",
           "first_root_on_grid", "force_scale", "forced_at_zero", "independent_impacts",
           "mutual_information_by_definition", "nearest_binary", "ode_free_flight",
           "single_pipe_closed_form", "sqrt2_rounded", "stuck_at", "trig_root", "trig_value"]

STICK_KIND, RELEASE_KIND = 2, 3   # History.kinds values (documented: impact 0, graze 1, ...)


# ----------------------------------------------------------------- stuck contacts
def stuck_at(times: Any, kinds: Any, sites: Any, n: int, ts: Any) -> np.ndarray:
    """``stuck[k, i]``: is contact ``i`` (``0..n``) stuck at time ``ts[k]``, after every event at
    that time (a history's documented convention), from the STICK / RELEASE events."""
    times = np.asarray(times, dtype=float)
    kinds = np.asarray(kinds)
    sites = np.asarray(sites)
    ts = np.asarray(ts, dtype=float)
    out = np.zeros((len(ts), n + 1), dtype=bool)
    sel = np.flatnonzero((kinds == STICK_KIND) | (kinds == RELEASE_KIND))
    for i in range(n + 1):
        ev = sel[sites[sel] == i]
        if len(ev) == 0:
            continue
        state = kinds[ev] == STICK_KIND            # the state after each of these events
        k = np.searchsorted(times[ev], ts, side="right") - 1
        out[:, i] = np.where(k >= 0, state[np.maximum(k, 0)], False)
    return out


def _forces(row: Any, t: np.ndarray) -> np.ndarray:
    """F_j(t) = sum_m alpha_jm cos(Omega_m t) + beta_jm sin(Omega_m t) (eq. 20), shape
    ``(len(t), n)``."""
    Om = np.array([float(w) for w in row.Omega])
    arg = np.outer(t, Om)
    return np.cos(arg) @ np.asarray(row.alpha).T + np.sin(arg) @ np.asarray(row.beta).T


def contact_forces(row: Any, ts: Any, x: Any, stuck: np.ndarray) -> np.ndarray:
    """Contact force ``lambda[k, i]`` of every stuck contact ``i`` at time ``ts[k]`` (NaN where
    contact ``i`` is not stuck), per unit mass of one pipe; ``> 0`` is compressive.

    From Newton's law of the stuck cluster (eq. 19): pipe ``j`` at position ``x_j`` feels the free
    force ``f_j = -omega^2 (x_j - j d) + F_j(t)``.  A cluster touching a wall does not move, so
    the part of it beyond contact ``i`` (away from the wall) must be held by the contact:
    ``lambda_i = -sum_{j > i} f_j`` (left wall) or ``sum_{j <= i} f_j`` (right wall).  A free
    cluster ``lo..hi`` moves with the mean acceleration ``a`` of its pipes, and contact ``i``
    passes on what the pipes left of it do not need: ``lambda_i = sum_{lo <= j <= i} (f_j - a)``.
    """
    ts = np.asarray(ts, dtype=float)
    x = np.asarray(x, dtype=float)
    n = row.n
    om2 = float(row.omega) ** 2
    d = float(row.d)
    f = -om2 * (x - np.arange(1, n + 1) * d) + _forces(row, ts)      # (T, n), pipes 1..n
    out = np.full((len(ts), n + 1), np.nan)
    for k in range(len(ts)):
        st = stuck[k]
        i = 0
        while i <= n:
            if not st[i]:
                i += 1
                continue
            lo = i              # contacts lo..hi-1 stuck: bodies lo..hi (0 and n+1: walls)
            while i <= n and st[i]:
                i += 1
            hi = i
            fj = {j: f[k, j - 1] for j in range(max(lo, 1), min(hi, n) + 1)}
            for c in range(lo, hi):     # contact c joins bodies c and c + 1
                if lo == 0:
                    out[k, c] = -sum(fj[j] for j in range(c + 1, hi + 1))
                elif hi == n + 1:
                    out[k, c] = sum(fj[j] for j in range(lo, c + 1))
                else:
                    a = sum(fj.values()) / len(fj)
                    out[k, c] = sum(fj[j] - a for j in range(lo, c + 1))
    return out


def force_scale(row: Any) -> float:
    """A scale of the contact forces of ``row``: ``omega^2 d (n + 1) + sum |alpha| + |beta|``."""
    return (float(row.omega) ** 2 * float(row.d) * (row.n + 1)
            + float(np.abs(row.alpha).sum() + np.abs(row.beta).sum()))


# ----------------------------------------------------------------- trigonometric polynomials
def trig_value(t: Any, g: Sequence[Any], F: Sequence[Any]) -> mpmath.mpf:
    """``g[0] + sum_m g[1+2m] cos(F_m t) + g[2+2m] sin(F_m t)`` at the current precision."""
    return g[0] + sum(g[1 + 2 * m] * mpmath.cos(f * t) + g[2 + 2 * m] * mpmath.sin(f * t)
                      for m, f in enumerate(F))


def trig_root(g: Sequence[Any], a: Any, b: Any, F: Sequence[Any], dps: int = 50) -> mpmath.mpf:
    """A root of the trigonometric polynomial in ``[a, b]`` (a sign change there) at ``dps``
    digits (mpmath's Anderson solver from the bracket)."""
    with mpmath.workdps(dps):
        return mpmath.findroot(lambda t: trig_value(t, g, F), (mpmath.mpf(a), mpmath.mpf(b)),
                               solver="anderson")


def first_root_on_grid(g: Sequence[Any], F: Sequence[Any], a: float, b: float,
                       n: int = 400) -> mpmath.mpf:
    """First sign change (``> 0`` to ``<= 0``) of the polynomial on a grid of ``n`` steps of
    ``[a, b]``, refined at 50 digits."""
    with mpmath.workdps(50):
        ts = [mpmath.mpf(a) + (mpmath.mpf(b) - a) * k / n for k in range(n + 1)]
        for lo, hi in itertools.pairwise(ts):
            if trig_value(lo, g, F) > 0 >= trig_value(hi, g, F):
                return mpmath.findroot(lambda t: trig_value(t, g, F), (lo, hi),
                                       solver="anderson")
    raise AssertionError("no root on the grid")


# ----------------------------------------------------------------- free flight, brute force
def brute_min_of_gap(g: Sequence[float], om: float, Om: float, horizon: float,
                     step: float = 0.01) -> float:
    """min over ``[0, horizon]`` of ``d + a0 cos + b0 sin (omega t) + a1 cos + b1 sin (Omega t)``
    for ``g = (d, a0, b0, a1, b1)``, by a dense scan refined with a golden-section search around
    the five lowest sampled local minima."""
    d, a0, b0, a1, b1 = g

    def f(t: Any) -> Any:
        return d + a0 * np.cos(om * t) + b0 * np.sin(om * t) + a1 * np.cos(Om * t) + \
            b1 * np.sin(Om * t)

    t = np.arange(0.0, horizon + step, step)
    t[-1] = min(t[-1], horizon)
    y = f(t)
    lo = float(y.min())
    idx = np.flatnonzero((y[1:-1] <= y[:-2]) & (y[1:-1] <= y[2:])) + 1
    for i in idx[np.argsort(y[idx])[:5]]:
        a, b = t[i - 1], t[i + 1]
        for _ in range(60):
            m1, m2 = a + (b - a) * 0.382, a + (b - a) * 0.618
            if f(m1) < f(m2):
                b = m2
            else:
                a = m1
        lo = min(lo, float(f((a + b) / 2)))
    return lo


# ----------------------------------------------------------------- an event-driven solver
def _mp(s: str) -> mpmath.mpf:
    fr = Fraction(s)
    return mpmath.mpf(fr.numerator) / fr.denominator


def _bind(f: Any, i: int) -> Any:
    return lambda s: f(i, s)


def independent_impacts(n: int, omega: str, d: str, r: str, Omega: Sequence[str],
                        alpha: Sequence[Sequence[str]], beta: Sequence[Sequence[str]],
                        x0: Sequence[str], v0: Sequence[str], t_end: str, *, dps: int = 60,
                        step: str = "0.02") -> list[tuple[mpmath.mpf, int]]:
    """Impact times and sites of a row given by decimal strings (their exact rationals), to
    about ``dps`` digits.

    Each pipe is ``j d + P cos(omega (t - t_j)) + Q sin(omega (t - t_j)) + forced_j(t)`` with the
    time measured from its last impact; crossings are found by a sign scan of every gap with
    steps ``step`` plus ``mpmath.findroot`` (Anderson); Newton's law is applied pairwise.  Elastic
    and inelastic impacts without sticking only.
    """
    with mpmath.workdps(dps):
        om, dd, rr, h = _mp(omega), _mp(d), _mp(r), _mp(step)
        Om = [_mp(w) for w in Omega]
        al = [[_mp(a) for a in row] for row in alpha]
        be = [[_mp(b) for b in row] for row in beta]
        T = _mp(t_end)

        def forced(j: int, t: Any) -> tuple[Any, Any]:   # pipe j = 1..n
            x = v = mpmath.mpf(0)
            for i, w in enumerate(Om):
                den = om**2 - w**2
                c, s = mpmath.cos(w * t), mpmath.sin(w * t)
                x += (al[j - 1][i] * c + be[j - 1][i] * s) / den
                v += w * (be[j - 1][i] * c - al[j - 1][i] * s) / den
            return x, v

        state: dict[int, tuple[Any, Any, Any]] = {}   # j -> (t_j, P, Q)

        def set_state(j: int, t: Any, x: Any, v: Any) -> None:
            fx, fv = forced(j, t)
            state[j] = (t, x - j * dd - fx, (v - fv) / om)

        def pos(j: int, t: Any) -> tuple[Any, Any]:
            if j == 0:
                return mpmath.mpf(0), mpmath.mpf(0)
            if j == n + 1:
                return (n + 1) * dd, mpmath.mpf(0)
            tj, P, Q = state[j]
            c, s = mpmath.cos(om * (t - tj)), mpmath.sin(om * (t - tj))
            fx, fv = forced(j, t)
            return j * dd + P * c + Q * s + fx, om * (Q * c - P * s) + fv

        for j in range(1, n + 1):
            set_state(j, mpmath.mpf(0), _mp(x0[j - 1]), _mp(v0[j - 1]))

        def gap(i: int, t: Any) -> Any:
            return pos(i + 1, t)[0] - pos(i, t)[0]

        out: list[tuple[mpmath.mpf, int]] = []
        t = mpmath.mpf(0)
        last = None
        while True:
            best: tuple[Any, int] | None = None
            for i in range(n + 1):
                a = t + (h / 1000 if i == last else 0)
                assert gap(i, a) > 0
                b = a
                while b < T and (best is None or b < best[0]):
                    b2 = min(b + h, T)
                    if gap(i, b2) <= 0:
                        root = mpmath.findroot(_bind(gap, i), (b, b2), solver="anderson")
                        if best is None or root < best[0]:
                            best = (root, i)
                        break
                    b = b2
            if best is None:
                return out
            t, i = best
            out.append((t, i))
            xl, vl = pos(i, t)
            xr, vr = pos(i + 1, t)
            u = vr - vl
            assert u < 0
            if i == 0:
                set_state(1, t, xr, vr - (1 + rr) * u)
            elif i == n:
                set_state(n, t, xl, vl + (1 + rr) * u)
            else:
                set_state(i, t, xl, vl + (1 + rr) * u / 2)
                set_state(i + 1, t, xr, vr - (1 + rr) * u / 2)
            last = i


# ----------------------------------------------------------------- correct rounding, exactly
def nearest_binary(p: int, q: int, prec: int) -> mpmath.mpf:
    """``p/q > 0`` rounded to ``prec`` bits, half to even, in integer arithmetic only."""
    e = p.bit_length() - q.bit_length() - prec
    while True:   # find e with 2**(prec-1) <= p / (q 2**e) < 2**prec
        num, den = (p, q << e) if e >= 0 else (p << -e, q)
        m, rem = divmod(num, den)
        if m >= 1 << prec:
            e += 1
        elif m < 1 << (prec - 1):
            e -= 1
        else:
            break
    if 2 * rem > den or (2 * rem == den and m % 2):
        m += 1
    with mpmath.workprec(prec + 2):
        return mpmath.ldexp(mpmath.mpf(m), e)


def sqrt2_rounded(prec: int) -> mpmath.mpf:
    """sqrt(2) correctly rounded to ``prec`` bits: ``sqrt(2) 2**(prec-1)`` lies in
    ``[2**(prec-1), 2**prec)``, its floor is ``isqrt(2 * 4**(prec-1))`` (no ties: irrational)."""
    import math

    m = math.isqrt(2 << (2 * (prec - 1)))
    if (2 * m + 1) ** 2 < 8 << (2 * (prec - 1)):
        m += 1
    with mpmath.workprec(prec + 2):
        return mpmath.ldexp(mpmath.mpf(m), -(prec - 1))


# ----------------------------------------------------------------- PipeRow.random, written out
def forced_at_zero(row: Any) -> tuple[np.ndarray, np.ndarray]:
    """Forced displacement and velocity at ``t = 0`` (eq. 21) from the row's own amplitudes:
    ``sum_i alpha_ji / (omega^2 - Omega_i^2)`` and ``sum_i Omega_i beta_ji / (omega^2 -
    Omega_i^2)``."""
    Om = np.array([float(w) for w in row.Omega])
    den = row.omega**2 - Om**2
    return (row.alpha / den).sum(axis=1), (row.beta * Om / den).sum(axis=1)


def documented_draw(n: int, sigma: float, seed: Any, *, omega: float = 1.0, d: float = 1.0,
                    Omega: Sequence[Any] = (1.4142135623730951,), sigma0: float | None = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The documented draw of ``PipeRow.random`` when no pipe needs a redraw: the forcing
    ``alpha, beta ~ N(0, sigma^2)`` first, then ``(alpha_0j, beta_0j) ~ N(0, sigma0^2)`` pipe by
    pipe, from one generator.  Returns ``(alpha, beta, free)`` with ``free[j] = (alpha_0j,
    beta_0j)``."""
    rng = np.random.default_rng(seed)
    Om = tuple(float(w) for w in Omega)
    s0 = sigma if sigma0 is None else sigma0
    k = len(Om)
    alpha = rng.normal(0.0, sigma, size=(n, k)) if sigma > 0 else np.zeros((n, k))
    beta = rng.normal(0.0, sigma, size=(n, k)) if sigma > 0 else np.zeros((n, k))
    free = [rng.normal(0.0, s0, size=2) if s0 > 0 else (0.0, 0.0) for _ in range(n)]
    return alpha, beta, np.array(free, dtype=float).reshape(n, 2)


def documented_redraws(n: int, sigma: float, seed: Any, sigma0: float, max_redraws: int, *,
                       d: float = 1.0, omega: float = 1.0,
                       Omega: Sequence[float] = (1.4142135623730951,)) -> Any:
    """The documented non-overlap rule of ``PipeRow.random``, written out from its docstring: per
    forcing up to 100 passes over the pipes from the left, each pipe at most ``max_redraws``
    draws per pass, at most ``min(20 max_redraws, 400 n)`` draws per forcing; at most 10
    forcings.  Returns ``(alpha, beta, x0, v0)`` or None (no row)."""
    rng = np.random.default_rng(seed)
    Om = np.array(Omega)
    den = omega**2 - Om**2
    right = (n + 1) * d
    for _ in range(10):
        alpha = rng.normal(0.0, sigma, size=(n, len(Om)))
        beta = rng.normal(0.0, sigma, size=(n, len(Om)))
        f0, fv0 = (alpha / den).sum(axis=1), (beta * Om / den).sum(axis=1)
        left = min(20 * max_redraws, 400 * n)
        for _ in range(100):
            x0, v0, prev = [], [], 0.0
            for j in range(n):
                placed = False
                for _ in range(min(max_redraws, left)):
                    left -= 1
                    a0, b0 = rng.normal(0.0, sigma0, size=2)
                    xj = (j + 1) * d + a0 + f0[j]
                    if prev < xj < right:
                        placed = True
                        break
                if not placed:
                    break
                x0.append(xj)
                v0.append(omega * b0 + fv0[j])
                prev = xj
            else:
                return alpha, beta, np.array(x0), np.array(v0)
            if left <= 0:
                break
    return None


# ----------------------------------------------------------------- ensembles, by hand
def count_by_hand(times: Any, sites: Any, kinds: Any, n: int, t_transient: float
                  ) -> dict[str, Any]:
    """One run of an ensemble counted from its full event history: the impacts (kinds impact 0
    and stick 2) in the window ``t >= t_transient``, their distinct sites, the pipes touching
    them (gap ``s`` lies between pipe ``s`` and ``s + 1``; 0 and n + 1 are walls), the sites hit
    at any time, and the window's sequence of sites."""
    hits = [(int(s), float(t)) for t, s, k in zip(times, sites, kinds, strict=True)
            if int(k) in (0, 2)]
    window = [s for s, t in hits if t >= t_transient]
    where = set(window)
    pipes = {j for s in where for j in (s, s + 1) if 1 <= j <= n}
    return dict(pipes=len(pipes), sites=len(where), impacts=len(window), events=len(times),
                where=where, ever={s for s, _ in hits}, seqs=window)


def documented_bootstrap(h: np.ndarray, seed: Any, boot: int) -> dict[str, Any]:
    """The documented bootstrap of a histogram: ``boot`` multinomial resamples from
    ``default_rng(seed)``; the 2.5 / 97.5 % percentiles of the resampled means and
    (nearest-rank) modes, the standard deviation of the modes and the fraction of resampled
    modes equal to the histogram's own (smallest) mode."""
    rng = np.random.default_rng(seed)
    k = int(h.sum())
    samples = rng.multinomial(k, h / k, size=boot)
    means = samples @ np.arange(len(h)) / k
    modes = np.array([int(np.flatnonzero(s == s.max())[0]) for s in samples])
    mode = int(np.flatnonzero(h == h.max())[0])
    return dict(mean_ci=np.percentile(means, [2.5, 97.5]).tolist(),
                mode_ci=np.percentile(modes, [2.5, 97.5], method="nearest").astype(int).tolist(),
                mode_se=float(np.std(modes, ddof=1)), mode_prob=float(np.mean(modes == mode)))


def documented_thresholds_estimate(sig: Sequence[float], hists: Sequence[np.ndarray], level: int,
                                   min_kept: int) -> tuple[float, float, float]:
    """The three threshold estimates of ``symhx.impact.ensemble.thresholds`` as documented,
    written out independently: (mode threshold, half-row crossing of the mean, steepest mean)."""
    import math

    ok = [h.sum() >= min_kept for h in hists]
    mode = math.nan
    for j in reversed(range(len(sig))):
        if not ok[j] or int(np.argmax(hists[j])) < level:
            break
        mode = sig[j]
    pts = [(s, (h * np.arange(len(h))).sum() / h.sum()) for s, h, k in zip(sig, hists, ok,
                                                                           strict=True) if k]
    target = (len(hists[0]) - 1) / 2
    half = math.nan
    for (s0, m0), (s1, m1) in itertools.pairwise(pts):
        if m0 < target <= m1:
            half = s0 + (target - m0) / (m1 - m0) * (s1 - s0)
            break
    allpts = [(s, (h * np.arange(len(h))).sum() / h.sum() if k else None)
              for s, h, k in zip(sig, hists, ok, strict=True)]
    slopes = []
    for (s0, m0), (s1, m1) in itertools.pairwise(allpts):
        slopes.append((m1 - m0) / (s1 - s0) if m0 is not None and m1 is not None else -math.inf)
    if not slopes or max(slopes) == -math.inf:
        return mode, half, math.nan
    j = int(np.argmax(slopes))
    return mode, half, (sig[j] + sig[j + 1]) / 2


def mutual_information_by_definition(a: Sequence[int], b: Sequence[int], size: int) -> float:
    """Mutual information (nats) of the pooled pairs ``(a[i], b[i])``, by its definition."""
    import math

    n = len(a)
    out = 0.0
    for x in range(size):
        for y in range(size):
            pxy = sum(1 for u, v in zip(a, b, strict=True) if u == x and v == y) / n
            if pxy:
                px = sum(1 for u in a if u == x) / n
                py = sum(1 for v in b if v == y) / n
                out += pxy * math.log(pxy / (px * py))
    return out


# ----------------------------------------------------------------- one pipe in free flight
def single_pipe_closed_form(t: Any, t0: Any, x0: Any, v0: Any, *, omega: Any = 1, d: Any = 1,
                            j: int = 1, alpha: Sequence[Any] = (), beta: Sequence[Any] = (),
                            Omega: Sequence[Any] = ()) -> tuple[mpmath.mpf, mpmath.mpf]:
    """Position and velocity at ``t`` of pipe ``j`` in free flight from ``(x0, v0)`` at ``t0``
    under ``x'' = -omega^2 (x - j d) + sum_i alpha_i cos(Omega_i t) + beta_i sin(Omega_i t)``
    (eq. 19), in closed form at the current mpmath precision: the free oscillation about
    ``j d`` plus the forced response ``(alpha cos + beta sin) / (omega^2 - Omega^2)``."""
    om, dd = mpmath.mpf(omega), mpmath.mpf(d)
    t, t0 = mpmath.mpf(t), mpmath.mpf(t0)

    def forced(s: Any) -> tuple[Any, Any]:
        x = v = mpmath.mpf(0)
        for a, b, w in zip(alpha, beta, Omega, strict=True):
            a, b, w = mpmath.mpf(a), mpmath.mpf(b), mpmath.mpf(w)
            den = om**2 - w**2
            x += (a * mpmath.cos(w * s) + b * mpmath.sin(w * s)) / den
            v += w * (b * mpmath.cos(w * s) - a * mpmath.sin(w * s)) / den
        return x, v

    fx0, fv0 = forced(t0)
    P, Q = mpmath.mpf(x0) - j * dd - fx0, (mpmath.mpf(v0) - fv0) / om
    c, s = mpmath.cos(om * (t - t0)), mpmath.sin(om * (t - t0))
    fx, fv = forced(t)
    return j * dd + P * c + Q * s + fx, om * (Q * c - P * s) + fv


def ode_free_flight(t: Any, t0: Any, x0: Any, v0: Any, *, omega: Any = 1, d: Any = 1, j: int = 1,
                    alpha: Sequence[Any] = (), beta: Sequence[Any] = (),
                    Omega: Sequence[Any] = (), dps: int = 30) -> tuple[mpmath.mpf, mpmath.mpf]:
    """The same free flight as :func:`single_pipe_closed_form`, by integrating the equation of
    motion (eq. 19) with mpmath's Taylor-series ODE solver (``mpmath.odefun``) at ``dps``
    digits: a check that uses no closed form at all."""
    with mpmath.workdps(dps):
        om2, dd = mpmath.mpf(omega) ** 2, mpmath.mpf(d)
        terms = [(mpmath.mpf(a), mpmath.mpf(b), mpmath.mpf(w))
                 for a, b, w in zip(alpha, beta, Omega, strict=True)]

        def rhs(s: Any, y: Any) -> list[Any]:
            force = sum(a * mpmath.cos(w * s) + b * mpmath.sin(w * s) for a, b, w in terms)
            return [y[1], -om2 * (y[0] - j * dd) + force]

        sol = mpmath.odefun(rhs, mpmath.mpf(t0), [mpmath.mpf(x0), mpmath.mpf(v0)])
        x, v = sol(mpmath.mpf(t))
        return +x, +v
