"""The record of one simulation: contact events and the closed-form motion between them."""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass, field
from typing import Any

import mpmath
import numpy as np

from symhx.impact.engine import GRAZE, IMPACT, KIND_NAMES, RELEASE, STICK, EventLog
from symhx.impact.model import PipeRow
from symhx.validation import check_array, to_rational

__all__ = ["GRAZE", "IMPACT", "RELEASE", "STICK", "History"]


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
        x = c[0]
        v = mpmath.mpf(0)
        for m, f in enumerate(F):
            cs, sn = mpmath.cos_sin(f * t)
            a, b = c[1 + 2 * m], c[2 + 2 * m]
            x += a * cs + b * sn
            v += f * (b * cs - a * sn)
        return x, v

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
            raise ValueError(f"t must lie in [0, t_end] = [0, {self.t_end}], got {t!r}")
        if self._wdps is not None:
            with mpmath.workdps(self._wdps):
                t = mpmath.mpf(fr.numerator) / fr.denominator
                return self._state(t, object)
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
        """Positions and velocities at many times at once: arrays of shape ``(len(times), n)``
        (vectorised for the float64 engine; the mpmath engine loops over :meth:`state`).

        >>> from symhx.impact import PipeRow, simulate
        >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[1.0])
        >>> x, v = simulate(row, 2.0).states([0.0, 0.5])
        >>> x.shape, float(x[0, 0])
        ((2, 1), 1.0)
        """
        ts = check_array(times, "times", nonnegative=True, allow_empty=True).ravel()
        if ts.size and ts.max() > float(self.t_end):
            raise ValueError(f"times must lie in [0, t_end] = [0, {self.t_end}], got {ts.max()!r}")
        n = self.row.n
        if self.dps is not None:
            xs = np.empty((ts.size, n), dtype=object)
            vs = np.empty((ts.size, n), dtype=object)
            for k, t in enumerate(ts):
                xs[k], vs[k] = self.state(float(t))
            return xs, vs
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

    def gaps(self, t: Any) -> np.ndarray:
        """Gaps ``Delta_i(t)``, ``i = 0..n`` (eq. 21)."""
        x, _ = self.state(t)
        right = (self.row.n + 1) * (mpmath.mpf(self.row.d) if x.dtype == object else self.row.d)
        full = np.concatenate(([x[0] * 0], x, [right]))
        return full[1:] - full[:-1]

    def energy(self, t: Any) -> Any:
        """Mechanical energy ``sum v^2/2 + omega^2 (x - j d)^2 / 2`` (no forcing work included)."""
        x, v = self.state(t)
        if x.dtype == object:
            with mpmath.workdps(self._wdps):
                om, d = mpmath.mpf(self.row.omega), mpmath.mpf(self.row.d)
                return mpmath.fsum(vj**2 / 2 + om**2 * (xj - (j + 1) * d) ** 2 / 2
                                   for j, (xj, vj) in enumerate(zip(x, v, strict=False)))
        j = np.arange(1, self.row.n + 1) * self.row.d
        return float(np.sum(v**2) / 2 + self.row.omega**2 * np.sum((x - j) ** 2) / 2)

    def impacts_per_site(self, t_from: float = 0.0, kinds: tuple[int, ...] = (IMPACT, STICK)
                         ) -> np.ndarray:
        """Number of events of the given kinds at each site ``0..n`` with time ``>= t_from``."""
        sel = np.isin(self.kinds, kinds) & (self.times.astype(float) >= float(t_from))
        return np.bincount(self.sites[sel], minlength=self.row.n + 1)
