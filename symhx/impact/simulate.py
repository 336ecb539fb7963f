"""``simulate``: one run of a :class:`~symhx.impact.PipeRow`, by either engine."""

from __future__ import annotations

import math
from typing import Any

from symhx._mpctx import export
from symhx.impact import fast
from symhx.impact import model as _model  # MAX_EVENTS, MAX_HORIZON: read when called
from symhx.impact.engine import V_STICK_FLOAT64, Engine, MPContext, default_v_stick, work_dps
from symhx.impact.history import History
from symhx.impact.model import PipeRow, SimulationError, check_horizon
from symhx.validation import InputError, check_choice, check_dps, check_int, check_real

__all__ = ["default_v_stick", "simulate", "work_dps"]

_FLOAT_ENGINES = ("auto", "c", "python")
#: below ``MAX_HORIZON * _HORIZON_SAFE`` the float64 product ``omega * t_end`` (relative error
#: <= 2**-53) certainly has an exact value <= MAX_HORIZON; at or above it the exact ``Fraction``
#: check decides (the cap is read at the call, so a changed ``symhx.impact.model.MAX_HORIZON``
#: reaches this fast path too)
_HORIZON_SAFE = 1 - 2.0**-50


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
    t_end : number
        Horizon ``> 0`` (exact for the mpmath engine like every row input), with
        ``omega * t_end <= MAX_HORIZON`` (``symhx.impact.model``; longer spans are refused).
    dps : int or None
        ``None``: the float64 engine (C extension; pure-Python fallback if it is not built).
        An int in ``[1, MAX_DPS]``: the mpmath reference engine, working at :func:`work_dps`
        digits from the row's exact inputs, so that impact times are correct to about ``dps``
        digits (up to the Lyapunov growth of errors).
    v_stick : float, optional
        Chatter threshold ``> 0`` (:func:`default_v_stick`): a contact slower than this sticks.
        ``0`` is refused: without sticking an inelastic chatter never ends (infinitely many
        impacts in finite time).
    max_events : int, optional
        Raise :class:`~symhx.impact.SimulationError` beyond this many events (guard for huge
        horizons); at most and by default ``MAX_EVENTS`` (``symhx.impact.model``).
    engine : ``"auto"``, ``"c"`` or ``"python"`` (float64 engine only).

    Returns
    -------
    History

    Examples
    --------
    A single elastic pipe with no force: ``x = 1 + 2 sin t`` reaches the right wall ``x = 2``
    at ``t = pi/6`` exactly.

    >>> import mpmath
    >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    >>> h = simulate(row, 1.0, dps=30)
    >>> h.sites.tolist(), h.kind_names(), mpmath.nstr(h.times[0], 20)
    ([1], ['impact'], '0.52359877559829887308')
    >>> with mpmath.workdps(30):
    ...     bool(abs(h.times[0] - mpmath.pi / 6) < 1e-29)
    True
    """
    if not isinstance(row, PipeRow):
        raise TypeError(f"row must be a PipeRow, got {type(row).__name__} {row!r:.60}")
    if (dps is None and v_stick is None and max_events is None and engine.__class__ is str
            and engine in _FLOAT_ENGINES and t_end.__class__ is float
            and 0.0 < t_end * row.omega < _model.MAX_HORIZON * _HORIZON_SAFE):
        # the common float64 call, validated without Fractions: a float t_end > 0 whose
        # omega * t_end is clearly inside MAX_HORIZON (the rounded product cannot cross it)
        vs = row.omega * row.d * V_STICK_FLOAT64   # = default_v_stick(row, None)
        if engine != "python" and fast.available():
            return fast.simulate_c(row, t_end, v_stick=vs, max_events=_model.MAX_EVENTS)
        if engine == "c":
            raise SimulationError("the C extension symhx.impact._fast is not built")
        return fast.simulate_python(row, t_end, v_stick=vs, max_events=_model.MAX_EVENTS)
    t_end_x = check_horizon(t_end, "t_end", row.omega)
    t_end_f = float(t_end_x)
    dps = check_dps(dps, allow_none=True)
    engine = check_choice(engine, "engine", ("auto", "c", "python"))
    if max_events is None:
        max_events = _model.MAX_EVENTS
    else:
        max_events = check_int(max_events, "max_events", minimum=1)
        if max_events > _model.MAX_EVENTS:
            raise InputError(f"max_events must be <= {_model.MAX_EVENTS} (a recorded history "
                             "of that many events needs gigabytes; the cap "
                             f"symhx.impact.model.MAX_EVENTS), got {max_events}")
    vs_x: Any
    if v_stick is None:
        vs_x = default_v_stick(row, dps)
    else:
        # 0 would disable sticking: an inelastic chatter is then an infinite sequence of ever
        # faster impacts (Zeno) that no engine can finish, so v_stick must be > 0
        vs_x = check_real(v_stick, "v_stick", low=0, low_open=True)
    if dps is None:
        try:
            vs = float(vs_x)
        except OverflowError:
            vs = math.inf
        if not 0 < vs < math.inf:
            raise InputError(f"v_stick = {v_stick!r} is outside the float64 range (> 0, finite) "
                             "of the float64 engine: give a positive float64 number, or use dps")
    if dps is None:
        if engine in ("auto", "c"):
            if fast.available():
                return fast.simulate_c(row, t_end_f, v_stick=vs, max_events=max_events)
            if engine == "c":
                raise SimulationError("the C extension symhx.impact._fast is not built")
        return fast.simulate_python(row, t_end_f, v_stick=vs, max_events=max_events)
    wdps = work_dps(dps)
    mc = MPContext()   # this thread's own mpmath context: threads never share a precision
    with mc.workdps(wdps):
        eng = Engine(row, mc, v_stick=mc.num(vs_x))
        te = mc.num(t_end_x)
        eng.run(te, max_events=max_events)
    # the history leaves the call: its numbers become mpmath's global type (bit for bit)
    return History.from_log(row, export(te), dps, eng.log.exported(), export(eng.F), wdps)
