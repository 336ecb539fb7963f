"""Impact simulation of a row of pipes (section 7 of the paper, eqs. 17–21).

* :class:`PipeRow` -- the model and its initial state; :meth:`PipeRow.random` draws it as in the
  paper.
* :func:`simulate` -- exact flight between contacts, certified first-contact search; ``dps=None``
  runs the float64 engine, an int the mpmath reference engine.
* :func:`ensemble` -- figures 7 and 8: statistics over random rows, any executor.
* :class:`History` -- the events (impacts, grazes, sticking, release) and the state at any time.
"""

from symhx.impact.engine import GRAZE, IMPACT, KIND_NAMES, RELEASE, STICK, EventKind
from symhx.impact.ensemble import (
    EnsembleResult,
    SigmaStats,
    ensemble,
    free_flight_closure_fraction,
)
from symhx.impact.history import History
from symhx.impact.model import SQRT2, PipeRow, SimulationError
from symhx.impact.simulate import default_v_stick, simulate, work_dps

__all__ = [
    "GRAZE",
    "IMPACT",
    "KIND_NAMES",
    "RELEASE",
    "SQRT2",
    "STICK",
    "EnsembleResult",
    "EventKind",
    "History",
    "PipeRow",
    "SigmaStats",
    "SimulationError",
    "default_v_stick",
    "ensemble",
    "free_flight_closure_fraction",
    "simulate",
    "work_dps",
]
