"""A slow release must not stream grazes (found by the mutation review of issue 16).

One pipe is stuck to the left wall, and its contact force crosses zero at ``t = atan(p)``, where
it is released. After that, the pipe leaves the wall with a curvature just above rounding. Each
restart of the search then found the touch again about 7e-14 later (the curvature step
``3 (A - tolA) / M3``), never at the same instant. The repeated-touch rule never fired, and the
run recorded grazes until ``max_events`` stopped it. That is more than 10000 events within
3e-7 time units; the touch step is 4e-5.

A touch found again within one touch step now counts as the same touch, as the module
docstring states. The events are then bounded by ``1 + T max(M2 / (2 v_stick),
5 / touch_step)``. The references for the checks are ``atan(p)`` for the release and that
documented bound, evaluated here from the gap's own bounds.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx.impact import GRAZE, RELEASE, PipeRow
from symhx.impact.engine import Engine, FloatContext, MPContext


def _row(p: float) -> PipeRow:
    return PipeRow(1, omega=1.0, d=1.0, Omega=(0.0, 2.0), restitution=0.0,
                   alpha=[[-0.5, -0.5]], beta=[[0.0, -p / 2]], x0=[0.5], v0=[0.0])


@pytest.mark.parametrize("e", [-22, -16, -10])
def test_slow_release_does_not_stream_grazes(e):
    p = 2.0**e
    eng = Engine(_row(p), FloatContext(), v_stick=1e-6)
    eng.stuck[0] = True
    eng.set_motion(0, 1, 0.0, 0.0, 0.0)
    T = 1.0
    eng.run(T, max_events=100_000)
    t, _, k, *_ = eng.log.event_arrays()
    # the force crosses zero with slope ~p: its root is fixed to ~rounding / p
    assert k[0] == RELEASE and abs(t[0] - math.atan(p)) < 1e-14 / p
    # the documented bound at the wall's gap after the release (M2, M3 of its polynomial)
    g = eng.gap_poly(0)
    _, _, _, M2, _, _ = eng.bounds(g)
    bound = 1 + T * max(M2 / (2 * eng.v_stick), 5 / eng.touch_step(g, float(t[0])))
    assert len(t) <= bound
    # and far fewer in fact: a touch cycle (touch, touch again, merge, release, touch) has
    # three grazes, and the next cycle starts a touch step later (the step grows with |t|)
    gz = np.sort(t[k == GRAZE])
    if len(gz) > 3:
        assert np.diff(gz[::3]).min() >= eng.touch_step(g, float(t[0]))
    assert len(t) < 1000, len(t)


def test_slow_release_mp_engine_agrees():
    """The mpmath engine (30 digits) on the same state: the release at atan(p) to 1e-25 / p and
    a bounded number of events as well."""
    p = 2.0**-16
    with mpmath.workdps(30):
        eng = Engine(_row(p), MPContext(), v_stick=mpmath.mpf("1e-6"))
        eng.stuck[0] = True
        z = mpmath.mpf(0)
        eng.set_motion(0, 1, z, z, z)
        eng.run(mpmath.mpf("0.01"), max_events=100_000)
        t = eng.log.event_arrays(dtype=object)[0]
        assert abs(t[0] - mpmath.atan(mpmath.mpf(p))) < mpmath.mpf(10) ** -25 / p
        assert len(t) < 1000
