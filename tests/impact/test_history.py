"""``symhx.impact.history.History``: the state at any time (after every event at that time),
many times at once, gaps, energy and the closed-form pieces of a run, in both arithmetics."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx.impact import IMPACT, STICK, PipeRow, simulate
from tests.harness.errors import assert_refuses
from tests.reference.impact import ode_free_flight

SQ2 = (math.sqrt(2),)


def one_pipe(x0, v0, *, r=1.0, d=1.0, Omega=SQ2, alpha=0.0):
    return PipeRow(1, d=d, restitution=r, Omega=Omega, alpha=[[alpha]], beta=[[0.0]],
                   x0=[x0], v0=[v0])


def test_states_vectorised_equals_state():
    row = PipeRow.random(15, 0.5, seed=3, restitution=0.5, Omega=(0.37, 2.1))
    h = simulate(row, 20.0)
    ts = np.linspace(0.0, 20.0, 41)
    x, v = h.states(ts)
    for k, t in enumerate(ts):
        xs, vs = h.state(t)
        np.testing.assert_allclose(x[k], xs, rtol=0, atol=1e-12)
        np.testing.assert_allclose(v[k], vs, rtol=0, atol=1e-12)


@pytest.mark.parametrize("kw", [{}, {"engine": "python"}, {"dps": 20}])
@pytest.mark.parametrize("r", [0.0, 0.5, 1.0])
def test_states_at_event_times_are_the_states_after_the_events(r, kw):
    # at an event time, states(times) gives what state(t) gives: the motion after every event
    # at that time.  Independent check of "after": the relative velocity of the site of the
    # last event of each instant is that event's u_after (impacts: -r u, sticks: 0)
    row = PipeRow.random(8, 0.6, seed=3, restitution=r)
    t_end = 20.0 if "dps" not in kw else 10.0
    h = simulate(row, t_end, **kw)
    assert len(h) > 10
    x, v = h.states(h.times)
    one = [h.state(t) for t in h.times]
    if "dps" in kw:    # one code path, every time at its exact value: equal
        assert all((x[k] == o[0]).all() and (v[k] == o[1]).all() for k, o in enumerate(one))
    xs = np.array([o[0] for o in one], dtype=float)
    vs = np.array([o[1] for o in one], dtype=float)
    np.testing.assert_allclose(np.asarray(x, float), xs, rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.asarray(v, float), vs, rtol=0, atol=1e-12)
    times = np.asarray(h.times, dtype=float)
    checked = 0
    for e in range(len(h)):
        last_of_instant = e + 1 == len(h) or times[e + 1] != times[e]
        if not last_of_instant or h.kinds[e] not in (IMPACT, STICK):
            continue
        s = int(h.sites[e])
        vel = np.concatenate(([0.0], np.asarray(v[e], float), [0.0]))   # walls at rest
        if h.kinds[e] == STICK and not (0 < s < row.n):
            continue   # a wall body: both sides at rest by construction
        assert abs((vel[s + 1] - vel[s]) - float(h.u_after[e])) < 1e-9, (e, h.kind_names()[e])
        checked += 1
    assert checked > 3


def test_state_between_events_solves_the_equation_of_motion():
    # a forced pipe (two frequencies, omega and d not 1): between two events its state is the
    # solution of eq. 19 from the state after the first one, integrated here by mpmath's ODE
    # solver (no closed form); both engines
    row = PipeRow(1, omega=1.3, d=0.8, restitution=0.7, Omega=(0.45, 2.1), alpha=[[0.3, -0.2]],
                  beta=[[0.1, 0.25]], x0=[0.5], v0=[1.4])
    force = dict(omega=1.3, d=0.8, alpha=[0.3, -0.2], beta=[0.1, 0.25], Omega=[0.45, 2.1])
    for kw, tol in (({}, 1e-12), ({"dps": 25}, 1e-18)):
        h = simulate(row, 12.0, **kw)
        assert len(h) >= 3
        ta, tb = h.times[1], h.times[2]     # event times as they are (mpf: exact)
        x0, v0 = h.state(ta)                 # the state after the event at ta
        with mpmath.workdps(40):
            t = (ta + tb) / 2
        x, v = h.state(t)
        xr, vr = ode_free_flight(t, ta, x0[0], v0[0], dps=22, **force)
        assert abs(x[0] - xr) < tol and abs(v[0] - vr) < tol


def test_state_continuity_and_energy_single_pipe():
    h = simulate(one_pipe(1.0, 2.0), 10.0, dps=25)
    for t in h.times:
        x, _v = h.state(t)
        assert min(abs(x[0]), abs(x[0] - 2)) < mpmath.mpf(10) ** -25
    e0 = h.energy(0)
    assert abs(h.energy(9.9) - e0) < mpmath.mpf(10) ** -25


def test_states_of_the_mpmath_engine_are_mpmath_numbers_at_working_precision():
    h = simulate(one_pipe(1.0, 2.0), 3.0, dps=30)
    x, v = h.state(1.0)
    assert isinstance(x[0], mpmath.mpf) and isinstance(v[0], mpmath.mpf)
    with mpmath.workdps(80):     # x = 1 + cos(t - pi/6) - sqrt(3) sin(t - pi/6) after pi/6
        ref = 1 + mpmath.cos(1 - mpmath.pi / 6) - mpmath.sqrt(3) * mpmath.sin(1 - mpmath.pi / 6)
        assert abs(x[0] - ref) < mpmath.mpf(10) ** -30
    xs, _ = h.states([0.25, 1.0])
    assert xs.dtype == object and xs[1, 0] == x[0]


def test_gaps_and_energy_use_the_exact_row():
    # the reference engine's gaps add up to the wall distance (n + 1) d of the exact d = 7/10
    row = PipeRow(2, d="0.7", restitution="0.9", Omega=("0.5",), alpha=[["0.1"], ["-0.2"]],
                  beta=[["0"], ["0.05"]], x0=["0.5", "1.5"], v0=["0.3", "-0.4"])
    h = simulate(row, "3", dps=40)
    for t in ("0", "1.3", "3"):
        g = h.gaps(t)
        assert len(g) == 3 and all(isinstance(x, mpmath.mpf) for x in g)
        with mpmath.workdps(60):
            assert abs(sum(g) - mpmath.mpf(21) / 10) < mpmath.mpf(10) ** -40
    # float64: the same identity to rounding
    hf = simulate(row, 3.0)
    assert abs(hf.gaps(1.3).sum() - 2.1) < 1e-14
    # energy of the unforced part at t = 0: v^2 / 2 + omega^2 (x - j d)^2 / 2 with the exact d
    with mpmath.workdps(60):
        ref = (mpmath.mpf(3) ** 2 / 200 + mpmath.mpf(4) ** 2 / 200
               + (mpmath.mpf(5) / 10 - mpmath.mpf(7) / 10) ** 2 / 2
               + (mpmath.mpf(15) / 10 - mpmath.mpf(14) / 10) ** 2 / 2)
        assert abs(h.energy(0) - ref) < mpmath.mpf(10) ** -40


def test_pieces_are_the_closed_form_motion():
    # one elastic pipe x = 1 + 2 sin t: one piece before the impact at pi/6, one after; the
    # second gives x = 1 + cos(t - pi/6) - sqrt(3) sin(t - pi/6) (mirror reflection)
    h = simulate(one_pipe(1.0, 2.0), 1.0)
    starts, coefs = h.pieces()
    assert len(starts) == 3 and starts[0] == [0.0] and starts[2] == [0.0]   # the walls
    assert starts[1][0] == 0.0 and abs(starts[1][1] - math.pi / 6) < 1e-15
    c = np.asarray(coefs[1][1], dtype=float)
    t = 0.8
    x = c[0] + c[1] * math.cos(t) + c[2] * math.sin(t) + c[3] * math.cos(math.sqrt(2) * t)
    x += c[4] * math.sin(math.sqrt(2) * t)
    ts = math.pi / 6
    assert abs(x - (1 + math.cos(t - ts) - math.sqrt(3) * math.sin(t - ts))) < 1e-14


def test_bad_state_time():
    h = simulate(PipeRow.random(2, 0.1, seed=0), 1.0)
    assert_refuses(h.state, float("nan"), arg="t", value="nan", allowed="finite")
    for t in (-0.5, 2.0):
        assert_refuses(h.state, t, arg="t", value=repr(t), allowed="[0, t_end] = [0, 1.0]")
    assert_refuses(h.state, "x", exc=(ValueError, TypeError), arg="t")
    assert_refuses(h.states, [0.5, float("nan")], arg="times", value="nan")
    assert_refuses(h.states, [0.5, 3.0], arg="times", value="3.0", allowed="[0, t_end]")
    hm = simulate(PipeRow.random(2, 0.1, seed=0), 1.0, dps=15)
    assert_refuses(hm.states, [0.5, float("nan")], arg="times", value="nan")
    assert_refuses(hm.states, [0.5, 3.0], arg="times", value="3.0", allowed="[0, t_end]")
    assert_refuses(hm.states, [-0.5], arg="times", value="-0.5", allowed="[0, t_end]")
    assert_refuses(hm.states, "0.5", exc=TypeError, arg="times", value="'0.5'")


@pytest.mark.parametrize("t_from", [0.0, 7.5, 19.0, 25.0])
def test_impacts_per_site_counts_the_events_of_those_kinds_from_t_from(t_from):
    # against a plain loop over the event table: impacts and sticks (the default kinds), or
    # impacts alone, at or after t_from, per site 0..n
    row = PipeRow.random(6, 0.5, seed=3, restitution=0.0, Omega=(0.37, 2.1))
    h = simulate(row, 20.0)
    assert np.any(h.kinds == STICK) and np.any(h.kinds == IMPACT)
    for kinds in ((IMPACT, STICK), (IMPACT,)):
        want = [sum(1 for t, s, k in zip(h.times, h.sites, h.kinds, strict=True)
                    if s == site and k in kinds and float(t) >= t_from) for site in range(7)]
        got = h.impacts_per_site(t_from, kinds)
        assert got.tolist() == want and len(got) == row.n + 1
