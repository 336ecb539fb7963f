"""Impact simulation of a row of pipes (section 7 of the paper, eqs. 17–21).

* :class:`PipeRow` -- the model and its initial state; :meth:`PipeRow.random` draws it as in the
  paper.
* :func:`simulate` -- exact flight between contacts, certified first-contact search; ``dps=None``
  runs the float64 engine, an int the mpmath reference engine.
* :class:`History` -- the events (impacts, grazes, sticking, release) and the state at any time.
"""

from symhx.impact.engine import GRAZE, IMPACT, KIND_NAMES, RELEASE, STICK
from symhx.impact.history import History
from symhx.impact.model import SQRT2, PipeRow
from symhx.impact.simulate import default_v_stick, simulate, work_dps

__all__ = [
    "GRAZE",
    "IMPACT",
    "KIND_NAMES",
    "RELEASE",
    "SQRT2",
    "STICK",
    "History",
    "PipeRow",
    "default_v_stick",
    "simulate",
    "work_dps",
]
