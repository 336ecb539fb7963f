"""The float64 engine: the C extension ``symhx.impact._fast`` (a port of ``engine.py``).

Same model and the same certified search as the reference engine, in float64 (rounding bounds
``64 eps`` times the scale of each quantity).  :func:`count_impacts` is the ensemble kernel: it
records nothing but the number of impacts per site after ``t_from``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from symhx.impact.engine import STICK, Engine, EventLog, FloatContext, default_v_stick
from symhx.impact.history import History
from symhx.impact.model import PipeRow, SimulationError

__all__ = ["available", "count_impacts", "simulate_c", "simulate_python", "source_sha256"]

try:
    from symhx.impact import _fast
except ImportError:  # pragma: no cover - extension not built
    _fast = None  # type: ignore[assignment]


def available() -> bool:
    """True when the C extension is importable.

    >>> isinstance(available(), bool)
    True
    """
    return _fast is not None


def source_sha256() -> str | None:
    """The SHA-256 (hex) of the ``_fast.c`` the loaded C extension was built from (compiled in by
    ``setup.py``), or None when the extension is not built.  The tests compare it with the file
    on disk: a stale extension is reported, never used unnoticed.

    >>> h = source_sha256()
    >>> h is None or len(h) == 64
    True
    """
    return None if _fast is None else str(_fast.source_sha256)


def _call(row: PipeRow, t_end: float, t_from: float, v_stick: float, record: bool,
          max_events: int | None) -> tuple[Any, ...]:
    """One run of the C engine; it builds the row's closed-form arrays itself (bit-identical to
    :func:`~symhx.impact.engine.row_arrays`) from the row's float64 inputs."""
    if _fast is None:
        raise SimulationError("the C extension symhx.impact._fast is not built")
    F = [row.omega, *map(float, row.Omega)]
    alpha, beta = row.alpha, row.beta
    try:
        try:
            out = _fast.run(row.n, row.omega, row.d, row.restitution, v_stick, t_end, t_from,
                            record, max_events or 0, F, alpha, beta, row.x0, row.v0)
        except (BufferError, ValueError):   # not C-contiguous (a Fortran-ordered input array)
            alpha, beta = np.ascontiguousarray(alpha), np.ascontiguousarray(beta)
            out = _fast.run(row.n, row.omega, row.d, row.restitution, v_stick, t_end, t_from,
                            record, max_events or 0, F, alpha, beta, np.ascontiguousarray(row.x0),
                            np.ascontiguousarray(row.v0))
    except RuntimeError as exc:
        raise SimulationError(str(exc)) from None
    return F, out


def simulate_python(row: PipeRow, t_end: float, *, v_stick: float,
                    max_events: int | None = None) -> History:
    """Full history from the pure-Python float64 engine (the fallback and the C port's check)."""
    eng = Engine(row, FloatContext(), v_stick=v_stick)
    eng.run(float(t_end), max_events=max_events)
    return History.from_log(row, float(t_end), None, eng.log, eng.F)


def simulate_c(row: PipeRow, t_end: float, *, v_stick: float, max_events: int | None = None
               ) -> History:
    """Full history from the C engine (used by :func:`symhx.impact.simulate` with dps=None)."""
    t_end = float(t_end)
    F, (_, ev, up, _, coef0) = _call(row, t_end, 0.0, v_stick, True, max_events)
    return History.from_log(row, t_end, None,
                            EventLog.from_buffers(coef0, ev or b"", up or b"", 1 + 2 * len(F)), F)


def count_impacts(row: PipeRow, t_end: float, t_from: float, *, v_stick: float | None = None,
                  max_events: int | None = None) -> tuple[np.ndarray, int]:
    """Impacts (including chatter that ends in sticking) per site ``0..n`` with ``t >= t_from``.

    Returns ``(counts, n_events)`` where ``n_events`` counts the events the run resolved
    (impacts, grazes and releases, as ``max_events`` counts them): a stick that ends an impact
    or a touch is part of that event, though a :class:`~symhx.impact.History` records it on a
    row of its own.  Raises :class:`~symhx.impact.SimulationError` if the run cannot proceed.

    >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    >>> counts, total = count_impacts(row, 10.0, 5.0)
    >>> counts.tolist(), total
    ([3, 2], 10)
    """
    vs = default_v_stick(row, None) if v_stick is None else float(v_stick)
    if _fast is None:
        h = simulate_python(row, t_end, v_stick=vs, max_events=max_events)
        return h.impacts_per_site(t_from), len(h) - int(np.count_nonzero(h.kinds == STICK))
    _, (counts, _, _, nev, _) = _call(row, float(t_end), float(t_from), vs, False, max_events)
    return np.frombuffer(counts, dtype=np.int64).copy(), int(nev)
