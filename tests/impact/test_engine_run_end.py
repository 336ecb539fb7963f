"""``Engine.run(t_end, max_events)``: an event exactly at ``t_end`` belongs to the run, one just
after does not; ``max_events`` allows exactly that many events and refuses one more, naming
itself. One pipe bouncing elastically between the walls (x0 = d, v0 = 2): its impacts come at
``t = pi/6 + k pi/3`` (the free motion ``x = 1 + 2 sin t`` meets a wall at ``|x - 1| = 1``)."""

from __future__ import annotations

import math

import mpmath
import pytest

from symhx.impact import PipeRow, SimulationError
from symhx.impact.engine import Engine, FloatContext, MPContext


def _row():
    return PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])


def _times(t_end, ctx=None, max_events=None):
    ctx = ctx or FloatContext()
    eng = Engine(_row(), ctx, v_stick=1e-6)
    eng.run(t_end, max_events=max_events)
    return list(eng.log.event_arrays(object)[0])


def test_impacts_are_at_the_closed_form_times():
    times = _times(10.0)
    assert len(times) == 10
    for k, t in enumerate(times):
        assert t == pytest.approx(math.pi / 6 + k * math.pi / 3, rel=1e-14)


@pytest.mark.parametrize("k", [0, 2])
def test_an_event_exactly_at_t_end_is_recorded_and_none_beyond(k):
    te = _times(10.0)[k]
    assert _times(te)[-1] == te and len(_times(te)) == k + 1
    before = math.nextafter(te, 0.0)
    assert len(_times(before)) == k


def test_an_event_exactly_at_t_end_is_recorded_by_the_mpmath_engine():
    mc = MPContext()
    with mc.workdps(30):
        te = _times(mc.num(3), mc)[2]
        got = _times(te, mc)
        assert len(got) == 3 and got[-1] == te
        assert abs(te - (mc.mp.pi / 6 + 2 * mc.mp.pi / 3)) < mpmath.mpf(10) ** -25
        assert len(_times(te - te * mc.eps * 4, mc)) == 2


def test_max_events_allows_exactly_that_many():
    assert len(_times(10.0, max_events=10)) == 10
    for m in (9, 0):
        with pytest.raises(SimulationError, match=rf"more than max_events={m} events"):
            _times(10.0, max_events=m)
