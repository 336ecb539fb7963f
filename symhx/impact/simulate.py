"""``simulate``: one run of a :class:`~symhx.impact.PipeRow`, by either engine."""

from __future__ import annotations

import math
from typing import Any

import mpmath
import numpy as np

from symhx.impact.engine import _Engine, _FloatCtx, _MPCtx
from symhx.impact.history import History
from symhx.impact.model import PipeRow

__all__ = ["default_v_stick", "simulate", "work_dps"]


def work_dps(dps: int) -> int:
    """Working precision of the reference engine for ``dps`` wanted digits: ``2 dps + 10``.

    Doubling makes grazing-type contacts (whose velocity is the square root of the gap's
    rounding) accurate to ``dps`` digits too.
    """
    return 2 * dps + 10


def default_v_stick(row: PipeRow, dps: int | None) -> float:
    """Relative speed below which a compressed contact sticks (chatter ends).

    ``omega d 10**(-dps/2 - 1)``: the position error of sticking at speed ``u`` instead of
    completing the chatter is ``u**2 / |Delta''| ~ 10**-dps``.  Float64 uses ``dps = 10``
    (``1e-6 omega d``): slower bounces last ``2u/|Delta''|`` and their roots are below the
    rounding of the gap, so float64 cannot resolve them anyway.
    """
    digits = 10 if dps is None else dps
    return row.omega * row.d * 10.0 ** (-digits / 2 - 1)


def simulate(
    row: PipeRow,
    t_end: float,
    *,
    dps: int | None = None,
    v_stick: float | None = None,
    max_events: int | None = None,
    engine: str = "auto",
) -> History:
    """Simulate ``row`` on ``[0, t_end]`` with exact flight between contacts (eqs. 17–21).

    Parameters
    ----------
    row : PipeRow
    t_end : float
        Horizon ``> 0``.
    dps : int or None
        ``None``: the float64 engine (C extension; pure-Python fallback if it is not built).
        An int: the mpmath reference engine, working at :func:`work_dps` digits so that impact
        times are correct to about ``dps`` digits (up to the Lyapunov growth of errors).
    v_stick : float, optional
        Chatter threshold (:func:`default_v_stick`).
    max_events : int, optional
        Raise ``RuntimeError`` beyond this many events (guard for huge horizons).
    engine : ``"auto"``, ``"c"`` or ``"python"`` (float64 engine only).

    Returns
    -------
    History

    Examples
    --------
    A single elastic pipe with no force: ``x = 1 + 2 sin t`` reaches the right wall ``x = 2``
    at ``t = pi/6`` exactly.

    >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    >>> h = simulate(row, 1.0, dps=30)
    >>> h.sites.tolist(), h.kind_names(), mpmath.nstr(h.times[0], 20)
    ([1], ['impact'], '0.52359877559829887308')
    >>> with mpmath.workdps(30):
    ...     bool(abs(h.times[0] - mpmath.pi / 6) < 1e-29)
    True
    """
    if not isinstance(row, PipeRow):
        raise ValueError(f"row must be a PipeRow, got {type(row).__name__}")
    try:
        t_end_f = float(t_end)
    except (TypeError, ValueError):
        raise ValueError(f"t_end must be a number, got {t_end!r}") from None
    if not math.isfinite(t_end_f) or t_end_f <= 0:
        raise ValueError(f"t_end must be finite and > 0, got {t_end!r}")
    if dps is not None:
        if isinstance(dps, bool) or not isinstance(dps, int) or dps < 5:
            raise ValueError(f"dps must be None or an int >= 5, got {dps!r}")
    vs = default_v_stick(row, dps) if v_stick is None else float(v_stick)
    if not (math.isfinite(vs) and vs >= 0):
        raise ValueError(f"v_stick must be finite and >= 0, got {v_stick!r}")
    if dps is None:
        if engine in ("auto", "c"):
            from symhx.impact import fast

            if fast.available():
                return fast.simulate_c(row, t_end_f, v_stick=vs, max_events=max_events)
            if engine == "c":
                raise RuntimeError("the C extension symhx.impact._fast is not built")
        elif engine != "python":
            raise ValueError(f"engine must be 'auto', 'c' or 'python', got {engine!r}")
        eng = _Engine(row, _FloatCtx(), v_stick=vs)
        eng.run(t_end_f, max_events=max_events)
        return _history(eng, row, t_end_f, None, None, float)
    wdps = work_dps(dps)
    with mpmath.workdps(wdps):
        eng = _Engine(row, _MPCtx(), v_stick=vs)
        te = mpmath.mpf(t_end)
        eng.run(te, max_events=max_events)
        return _history(eng, row, te, dps, wdps, object)


def _history(eng: _Engine, row: PipeRow, t_end: Any, dps: int | None, wdps: int | None,
             dtype: Any) -> History:
    return History(
        row=row,
        t_end=t_end,
        dps=dps,
        times=np.array(eng.ev_t, dtype=dtype),
        sites=np.array(eng.ev_site, dtype=np.int64),
        kinds=np.array(eng.ev_kind, dtype=np.int8),
        u_before=np.array(eng.ev_u0, dtype=dtype),
        u_after=np.array(eng.ev_u1, dtype=dtype),
        aux=np.array(eng.ev_aux, dtype=dtype),
        _upd_t=eng.upd_t,
        _upd_c=eng.upd_c,
        _freqs=eng.F,
        _wdps=wdps,
    )
