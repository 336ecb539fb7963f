"""The record of one simulation: contact events and the closed-form motion between them."""

from __future__ import annotations

import itertools
import math
from bisect import bisect_right
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np

from symhx._mpctx import export, local, mp
from symhx.impact.engine import GRAZE, IMPACT, KIND_NAMES, RELEASE, STICK, EventLog
from symhx.impact.model import PipeRow, exact_to_mpf
from symhx.validation import InputError, check_array, to_rational

__all__ = ["GRAZE", "IMPACT", "RELEASE", "STICK", "History"]


def _exported(a: np.ndarray) -> np.ndarray:
    """An object array of mpf as mpmath's global type (bit for bit)."""
    out = np.empty(a.shape, dtype=object)
    for idx in np.ndindex(*a.shape):
        out[idx] = export(a[idx])
    return out


@dataclass(eq=False)
class History:
    """Events of a simulation of a :class:`~symhx.impact.PipeRow` up to ``t_end`` (section 7).

    Attributes
    ----------
    times : ndarray
        Event times, non-decreasing (float64 for the fast engine; ``mpmath.mpf`` objects for the
        reference engine, correct to about ``dps`` digits).
    sites : ndarray of int
        Site of each event: gap ``i`` between pipe ``i`` and ``i + 1`` (``0``, ``n``: the walls).
    kinds : ndarray of int
        ``IMPACT`` (0), ``GRAZE`` (1, tangential touch: zero relative velocity, nothing changes),
        ``STICK`` (2, chatter ended: the two bodies move as one), ``RELEASE`` (3, a stuck contact
        opens because its contact force changes sign).
    u_before, u_after : ndarray
        Relative velocity ``Delta_i'`` just before and after the event (``u_after = -r u_before``
        for an impact).
    aux : ndarray
        ``STICK``: estimated accumulation time of the chatter; ``GRAZE``: the gap at the touch.
    row, t_end, dps
        The simulated row, horizon and precision (``None``: float64 engine).

    Use :meth:`state` for positions and velocities at any time in ``[0, t_end]``.
    """

    row: PipeRow
    t_end: Any
    dps: int | None
    times: np.ndarray
    sites: np.ndarray
    kinds: np.ndarray
    u_before: np.ndarray
    u_after: np.ndarray
    aux: np.ndarray
    _log: EventLog = field(repr=False)
    _freqs: list[Any] = field(repr=False)
    _wdps: int | None = field(repr=False, default=None)

    @classmethod
    def from_log(cls, row: PipeRow, t_end: Any, dps: int | None, log: EventLog, freqs: Any,
                 wdps: int | None = None) -> History:
        """The history of a run from its ``symhx.impact.engine.EventLog`` (float64 arrays
        when ``dps`` is None, arrays of mpf at working precision ``wdps`` otherwise)."""
        times, sites, kinds, u0, u1, aux = log.event_arrays(float if dps is None else object)
        # positional: the fields in their declared order (half the cost of keywords)
        return cls(row, t_end, dps, times, sites, kinds, u0, u1, aux, log, list(freqs), wdps)

    def __len__(self) -> int:
        return len(self.times)

    @property
    def impact_mask(self) -> np.ndarray:
        """Boolean mask of the events that are impacts."""
        return self.kinds == IMPACT

    def kind_names(self) -> list[str]:
        """Names of the event kinds, e.g. ``['impact', 'graze', ...]``."""
        return [KIND_NAMES[k] for k in self.kinds]

    def _eval(self, c: Any, t: Any) -> tuple[Any, Any]:
        F = self._freqs
        if self.dps is None:
            x = c[0]
            v = 0.0
            for m, f in enumerate(F):
                cs, sn = math.cos(f * t), math.sin(f * t)
                a, b = c[1 + 2 * m], c[2 + 2 * m]
                x += a * cs + b * sn
                v += f * (b * cs - a * sn)
            return float(x), float(v)
        ctx = mp()   # this thread's context, at the history's working precision (see state)
        x = local(c[0])
        v = ctx.zero
        for m, f in enumerate(F):
            f = local(f)
            cs, sn = ctx.cos_sin(f * t)
            a, b = local(c[1 + 2 * m]), local(c[2 + 2 * m])
            x += a * cs + b * sn
            v += f * (b * cs - a * sn)
        return x, v

    def pieces(self) -> tuple[list[list[Any]], list[Any]]:
        """The closed-form motion between the events: ``(starts, coefs)`` where, for each body
        ``j = 0..n + 1`` (``0`` and ``n + 1`` are the walls), ``starts[j]`` lists the times from
        which it follows each coefficient vector ``coefs[j][k] = [c0, a_0, b_0, a_1, b_1, ...]``
        (``x_j(t) = c0 + sum_m a_m cos(F_m t) + b_m sin(F_m t)``, ``F = (omega, Omega_1, ...)``,
        absolute time; the first piece starts at ``t = 0``).

        >>> from symhx.impact import PipeRow, simulate
        >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
        >>> starts, coefs = simulate(row, 1.0).pieces()
        >>> len(starts[1]), [float(c) for c in coefs[1][0][:3]]   # one impact: two pieces
        (2, [1.0, 0.0, 2.0])
        """
        return self._log.updates()

    def state(self, t: Any) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities of pipes ``1..n`` at time ``t`` (after any event at ``t``).

        >>> from symhx.impact import PipeRow, simulate
        >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[1.0])
        >>> h = simulate(row, 2.0)
        >>> x, v = h.state(0.0)
        >>> float(x[0]), float(v[0])
        (1.0, 1.0)
        """
        fr = to_rational(t, "t")
        if fr is None:
            raise TypeError(f"t must be a rational or float number, got {t!r}")
        end = to_rational(self.t_end, "t_end")  # a rational: t_end was validated
        if end is None or not 0 <= fr <= end:
            raise InputError(f"t must lie in [0, t_end] = [0, {self.t_end}], got {t!r}")
        if self._wdps is not None:
            ctx = mp()   # this thread's own context: safe next to other threads
            with ctx.workdps(self._wdps):
                t = ctx.mpf(fr.numerator) / fr.denominator
                xs, vs = self._state(t, object)
            return _exported(xs), _exported(vs)
        return self._state(float(t), float)

    def _state(self, t: Any, dtype: Any) -> tuple[np.ndarray, np.ndarray]:
        n = self.row.n
        xs = np.empty(n, dtype=dtype)
        vs = np.empty(n, dtype=dtype)
        upd_t, upd_c = self._log.updates()
        for j in range(1, n + 1):
            k = max(bisect_right(upd_t[j], t) - 1, 0)
            xs[j - 1], vs[j - 1] = self._eval(upd_c[j][k], t)
        return xs, vs

    def states(self, times: Any) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities at many times at once: arrays of shape ``(len(times), n)``,
        row ``k`` equal to :meth:`state` at ``times[k]`` (after any event at that time; an event
        time of the history gives the state after its events).  Vectorised for the float64
        engine; the mpmath engine takes every time at its exact value (an mpf event time is not
        rounded to float64) and loops over :meth:`state`.

        >>> from symhx.impact import PipeRow, simulate
        >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[1.0])
        >>> x, v = simulate(row, 2.0).states([0.0, 0.5])
        >>> x.shape, float(x[0, 0])
        ((2, 1), 1.0)
        """
        n = self.row.n
        if self.dps is not None:
            vals = self._exact_times(times)
            xs = np.empty((len(vals), n), dtype=object)
            vs = np.empty((len(vals), n), dtype=object)
            for k, t in enumerate(vals):
                xs[k], vs[k] = self.state(t)
            return xs, vs
        ts = check_array(times, "times", nonnegative=True, allow_empty=True).ravel()
        if ts.size and ts.max() > float(self.t_end):
            raise InputError(f"times must lie in [0, t_end] = [0, {self.t_end}], got {ts.max()!r}")
        F = np.asarray(self._freqs, dtype=float)
        arg = np.outer(ts, F)
        cs, sn = np.cos(arg), np.sin(arg)
        xs = np.empty((ts.size, n))
        vs = np.empty((ts.size, n))
        upd_t, upd_c = self._log.updates()
        for j in range(1, n + 1):
            C = np.asarray(upd_c[j], dtype=float)
            ks = np.maximum(np.searchsorted(np.asarray(upd_t[j], dtype=float), ts,
                                            side="right") - 1, 0)
            c = C[ks]
            a, b = c[:, 1::2], c[:, 2::2]
            xs[:, j - 1] = c[:, 0] + np.sum(a * cs + b * sn, axis=1)
            vs[:, j - 1] = np.sum(F * (b * cs - a * sn), axis=1)
        return xs, vs

    def _exact_times(self, times: Any) -> list[Fraction]:
        """``times`` (a number or a sequence of them, mpf included) as exact Fractions in
        ``[0, t_end]``; the errors name ``times``."""
        if isinstance(times, (str, bytes)):
            raise TypeError(f"times must be a number or an array of numbers, got {times!r}")
        try:
            flat = list(np.ravel(np.asarray(times, dtype=object)))
        except (TypeError, ValueError) as exc:
            raise TypeError(f"times must be a number or an array of numbers ({exc})") from None
        end = to_rational(self.t_end, "t_end")
        out = []
        for t in flat:
            fr = to_rational(t, "times")
            if fr is None:
                raise TypeError(f"times must hold rational or float numbers, got {t!r}")
            if end is None or not 0 <= fr <= end:
                raise InputError(f"times must lie in [0, t_end] = [0, {self.t_end}], got {t!r}")
            out.append(fr)
        return out

    def gaps(self, t: Any) -> np.ndarray:
        """Gaps ``Delta_i(t)``, ``i = 0..n`` (eq. 21)."""
        x, _ = self.state(t)
        if x.dtype != object:
            full = np.concatenate(([0.0], x, [(self.row.n + 1) * self.row.d]))
            return full[1:] - full[:-1]
        ctx = mp()
        with ctx.workdps(self._wdps):
            xl = [ctx.zero, *(local(v) for v in x),
                  (self.row.n + 1) * exact_to_mpf(self.row.exact("d"), ctx)]
            return _exported(np.array([b - a for a, b in itertools.pairwise(xl)],
                                      dtype=object))

    def energy(self, t: Any) -> Any:
        """Mechanical energy ``sum v^2/2 + omega^2 (x - j d)^2 / 2`` (no forcing work included)."""
        x, v = self.state(t)
        if x.dtype == object:
            ctx = mp()
            with ctx.workdps(self._wdps):
                om = exact_to_mpf(self.row.exact("omega"), ctx)
                d = exact_to_mpf(self.row.exact("d"), ctx)
                return export(ctx.fsum(local(vj)**2 / 2 + om**2 * (local(xj) - (j + 1) * d) ** 2 / 2
                                       for j, (xj, vj) in enumerate(zip(x, v, strict=False))))
        j = np.arange(1, self.row.n + 1) * self.row.d
        return float(np.sum(v**2) / 2 + self.row.omega**2 * np.sum((x - j) ** 2) / 2)

    def impacts_per_site(self, t_from: float = 0.0, kinds: tuple[int, ...] = (IMPACT, STICK)
                         ) -> np.ndarray:
        """Number of events of the given kinds at each site ``0..n`` with time ``>= t_from``."""
        sel = np.isin(self.kinds, kinds) & (self.times.astype(float) >= float(t_from))
        return np.bincount(self.sites[sel], minlength=self.row.n + 1)
