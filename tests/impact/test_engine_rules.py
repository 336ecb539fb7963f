"""The event rules of ``symhx.impact.engine``: impact (Newton's restitution), graze, stick
(chatter's end, plastic and slow contacts) and release, the cascade backstop, the touch rules of
the run loop -- checked where each outcome is decided and on whole runs with hand-solved or
closed-form references (``tests.reference.impact``).

The physics invariant "a stuck contact is compressive" is checked here on hand-made rows and at
every sampled time of the 1050-row sweep (``test_simulate_sweep.py``).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx.impact import GRAZE, IMPACT, RELEASE, STICK, PipeRow, SimulationError, simulate
from symhx.impact import fast as fast_mod
from symhx.impact.engine import Engine, EventLog, FloatContext, MPContext, cascade_bound
from tests.reference.impact import (
    contact_forces,
    force_scale,
    ode_free_flight,
    single_pipe_closed_form,
    stuck_at,
)

EPS = 2.0**-52
TOL = 64   # the engine's documented rounding bound: 64 eps (scale of the evaluated quantity)
ENGINES = [{"engine": "c"}, {"engine": "python"}, {"dps": 30}] if fast_mod.available() else [
    {"engine": "python"}, {"dps": 30}]


def _row(r=0.5, *, d=1.0, Omega=(2.0,), n=1):
    return PipeRow(n, omega=1.0, d=d, Omega=Omega, restitution=r, alpha=np.zeros((n, len(Omega))),
                   beta=np.zeros((n, len(Omega))), x0=[d * (j + 1) for j in range(n)],
                   v0=[0.0] * n)


def _eng(r=0.5, v_stick=1e-6, **kw):
    return Engine(_row(r, **kw), FloatContext(), v_stick=v_stick)


def _table(h):
    return np.column_stack([h.times, h.sites, h.kinds, h.u_before, h.u_after, h.aux])


# ---------------------------------------------------------------- the impact rule
def _impact(eng, g, t=0.0, i=0):
    """Pipe 1's motion set so that the wall gap (site 0) is ``g``; apply the impact rule."""
    eng.coef[1] = list(g)
    eng.log = EventLog(eng.coef)
    eng._impact(i, t)
    ev = list(zip(*eng.log.event_arrays(), strict=True))
    return [(int(s), int(k)) for _, s, k, _, _, _ in ev], ev


def _gap_with(u, A, J):
    # D = 0, V = u, A, J at t = 0 over F = (1, 2): b0 + 2 b1 = u, -b0 - 8 b1 = J,
    # -a0 - 4 a1 = A with a0 = 1
    b1 = -(u + J) / 6
    b0 = u - 2 * b1
    a1 = -(A + 1) / 4
    return [-(1 + a1), 1.0, b0, a1, b1]


def test_impact_opening_contact_is_a_touch():
    eng = _eng()
    kinds, ev = _impact(eng, [-1.0, 1.0, 0.5, 0.0, 0.0])   # V = +1/2: not approaching
    assert kinds == [(0, GRAZE)] and ev[0][0] == 0.0 and ev[0][3:] == (0.5, 0.5, 0.0)
    assert eng.coef[1] == [-1.0, 1.0, 0.5, 0.0, 0.0] and not any(eng.stuck)


def test_impact_compression_decides_sticking():
    # u = -1, r = 1/2: u' = 1/2 = v_stick exactly (inclusive); it sticks iff compressed:
    # A < -tolA, or |A| <= tolA and J < 0, with tolA = 64 eps (M2 + M3 |t|)
    def sticks(A, J, t=0.0):
        eng = _eng(v_stick=0.5)
        g = _gap_with(-1.0, A, J)
        if t:
            # the same local shape around t instead of 0: rotate each frequency's phase
            out = [g[0]]
            for m, f in enumerate((1.0, 2.0)):
                a, b = g[1 + 2 * m], g[2 + 2 * m]
                c, s = math.cos(f * t), math.sin(f * t)
                out += [a * c - b * s, a * s + b * c]
            g = out
        kinds, ev = _impact(eng, g, t)
        assert kinds[0] == (0, IMPACT) and ev[0][3] == pytest.approx(-1.0, abs=1e-12)
        return [k for _, k in kinds] == [IMPACT, STICK]

    def tolA(A, J, t=0.0):
        _, _, _, M2, M3, _ = _eng().bounds(_gap_with(-1.0, A, J))
        return TOL * EPS * (M2 + M3 * abs(t))

    assert sticks(-1.0, 0.5) and not sticks(1.0, -0.5)
    assert sticks(0.0, -0.5) and not sticks(0.0, 0.5)
    for J in (0.5, -0.5):
        ta = tolA(0.0, J)
        assert sticks(ta / 2, J) == (J < 0)            # within rounding: the jerk decides
        assert sticks(-ta / 2, J) == (J < 0)
        assert sticks(4 * ta, J) is False and sticks(-4 * ta, J) is True
    # at t = 100 the rounding allowance includes M3 |t|
    ta = tolA(0.0, 0.5, 100.0)
    assert not sticks(ta / 2, 0.5, 100.0) and not sticks(-ta / 2, 0.5, 100.0)
    assert sticks(-2 * ta, 0.5, 100.0)


def test_impact_compression_rule_at_its_exact_boundaries():
    # A = -tolA or +tolA exactly, and J = 0 exactly (all with u' = v_stick): the inequalities
    # of the rule as written -- A < -tolA or (|A| <= tolA and J < 0)
    def gap(A_sign, J_sign):
        # F = (1, 2), V = b0 + 2 b1 < 0: a0 = 0 so that A = -4 a1 exactly; J = -b0 - 8 b1 is
        # 0 for b0 = -8 b1, and +2.5 or -0.5 for b1 = -0.25 or +0.25 with V = -1
        if J_sign == 0:
            b1 = 1 / 6
            b0 = -8 * b1
        else:
            b1 = -0.25 * J_sign
            b0 = -1.0 - 2 * b1
        a1 = 0.0
        for _ in range(5):      # tolA depends on a1 (through M2) very weakly: a fixed point
            g = [-a1, 0.0, b0, a1, b1]
            M2 = _eng().bounds(g)[3]
            a1 = -A_sign * TOL * EPS * M2 / 4
        g = [-a1, 0.0, b0, a1, b1]
        D, V, A, J = _eng().derivs(g, 0.0)
        _, _, _, M2, _, _ = _eng().bounds(g)
        assert D == 0 and A == A_sign * TOL * EPS * M2 and (J > 0) - (J < 0) == J_sign
        assert V < 0
        return g, -0.5 * V

    def kinds(g, v_stick):
        return [k for _, k in _impact(_eng(v_stick=v_stick), g)[0]]

    assert kinds(*gap(-1, 1)) == [IMPACT]     # A = -tolA, J > 0: not compressed
    assert kinds(*gap(+1, 1)) == [IMPACT]     # A = +tolA, J > 0
    assert kinds(*gap(0, 0)) == [IMPACT]      # A = 0, J = 0: not compressed
    # A = +tolA with J < 0: compressed (|A| <= tolA counts as zero curvature)
    assert kinds(*gap(+1, -1)) == [IMPACT, STICK]


def test_impact_velocity_threshold_and_accumulation_time():
    # |u| = 1 <= v_stick = 1 (inclusive): no bounce, the bodies merge; the skipped chatter's
    # speed r |u| and accumulation time t + 2 r |u| / (|A| (1 - r)) are recorded
    eng = _eng(r=0.5, v_stick=1.0)
    kinds, ev = _impact(eng, _gap_with(-1.0, -4.0, 0.5))
    assert kinds == [(0, STICK)] and eng.stuck[0]
    assert ev[0][3:] == (-0.5, 0.0, 0.5)          # u0 = -r |u|, aux = 2 (1/2) / (4 (1/2))
    eng = _eng(r=0.5, v_stick=1.0 * (1 - EPS))
    assert [k for _, k in _impact(eng, _gap_with(-1.0, -4.0, 0.5))[0]] == [IMPACT, STICK]
    # no accumulation (aux = t) when the contact is not compressed or r = 1
    for r, A in ((0.5, 1.0), (0.5, 0.0), (1.0, -4.0)):
        eng = _eng(r=r, v_stick=1.0)
        kinds, ev = _impact(eng, _gap_with(-1.0, A, 0.5))
        assert kinds == [(0, STICK)] and ev[0][5] == 0.0


def test_impact_plastic_backstop_only_at_its_instant():
    for at, plastic in ((0.0, True), (1.0, False), (None, False)):
        eng = _eng(r=0.5)
        eng.plastic_at = at
        kinds, _ = _impact(eng, _gap_with(-1.0, 1.0, 0.5))
        assert [k for _, k in kinds] == ([IMPACT, STICK] if plastic else [IMPACT])


# ---------------------------------------------------------------- merges under tension
@pytest.mark.parametrize("kw", ENGINES)
def test_plastic_merge_under_rising_tension_leaves_at_once(kw):
    # issue 28, item 10: one plastic pipe (r = 0) hits the left wall at t0 = 0.158117; at the
    # wall its free acceleration 1 + cos(2t)/2 >= 1/2 pulls it away at every time, so its
    # contact force is tensile (and growing until pi/2): it must leave at t0, not stick until
    # the force starts to fall (t = 1.6146, as it did)
    row = PipeRow(1, restitution=0, Omega=(2.0,), alpha=[[0.5]], beta=[[0.0]], x0=[0.3],
                  v0=[-2.0])
    h = simulate(row, 4.0, **kw)
    assert h.kind_names()[:3] == ["impact", "stick", "release"]
    assert h.times[0] == h.times[1] == h.times[2] and h.sites[:3].tolist() == [0, 0, 0]
    force = dict(alpha=[0.5], beta=[0.0], Omega=[2.0])
    with mpmath.workdps(40):
        t0 = mpmath.mpf(h.times[0])
        # the impact time from the closed form before it (x0, v0 at t = 0)
        assert abs(single_pipe_closed_form(t0, 0, 0.3, -2.0, **force)[0]) < 1e-12
        for t in (0.5, 1.0, 1.5):
            x, _ = h.state(t)
            ref = single_pipe_closed_form(t, t0, 0, 0, **force)[0]   # left at rest from x = 0
            assert abs(float(x[0]) - ref) < 1e-9 and float(x[0]) > 0.05
    # ... and by integrating the equation of motion from the wall (no closed form)
    x_ode, _ = ode_free_flight(1.0, float(h.times[0]), 0, 0, dps=20, **force)
    assert abs(float(h.state(1.0)[0][0]) - x_ode) < 1e-9
    # the pipe does not come back to the wall before t = 4: nothing else happens
    assert len(h) == 3


@pytest.mark.parametrize("kw", ENGINES)
def test_slow_merge_under_tension_leaves_at_once(kw):
    # an impact slower than v_stick merges without asking for compression; here the contact is
    # tensile and the tension still grows (free acceleration 1 + cos(2t)/2 at the wall), so the
    # release follows at the same instant
    row = PipeRow(1, restitution=0.5, Omega=(2.0,), alpha=[[0.5]], beta=[[0.0]], x0=[0.3],
                  v0=[-0.9])
    vs = 1.0 if "dps" not in kw else "1"
    h = simulate(row, 1.5, v_stick=vs, **kw)
    assert h.kind_names()[:2] == ["stick", "release"] and h.times[0] == h.times[1]
    x, _ = h.state(h.times[0] + 0.3)
    assert float(x[0]) > 0.01


@pytest.mark.parametrize("kw", ENGINES)
def test_stuck_contacts_of_random_plastic_rows_are_compressive(kw):
    # Newton's law of every stuck cluster (tests.reference.impact.contact_forces) at many
    # times: no stuck contact is ever under tension beyond rounding
    seeds = (0, 1, 2) if "dps" not in kw else (0,)
    for seed in seeds:
        row = PipeRow.random(6, 0.8, seed=seed, restitution=0.0, Omega=(SQRT2_F, 0.6))
        t_end = 12.0 if "dps" not in kw else 4.0
        h = simulate(row, t_end, **kw)
        ts = np.linspace(0.0, t_end, 801)
        x, _ = h.states(ts)
        stk = stuck_at(h.times, h.kinds, h.sites, row.n, ts)
        assert stk.any() and (h.kinds == STICK).sum() > 3
        lam = contact_forces(row, ts, np.asarray(x, dtype=float), stk)
        assert np.nanmin(lam) > -1e-9 * force_scale(row), (seed, np.nanmin(lam))


SQRT2_F = math.sqrt(2)


# ---------------------------------------------------------------- whole runs
def _chatter_row(r, alpha, d=1.0):
    # one pipe under a constant force alpha (Omega = 0) started at rest at x0 = d/2
    return PipeRow(1, d=d, restitution=r, Omega=(0.0,), alpha=[[alpha]], beta=[[0.0]],
                   x0=[d / 2], v0=[0.0])


def test_chatter_accumulation_time_r_quarter():
    # x'' = -(x - 1) - 3 = -x - 2: x = -2 + 2.5 cos t hits the wall at acos(4/5) with speed 3/2;
    # each later flight lasts 2 atan(v_k / 2), v_k = 1.5 r^k.  At the stick, |x''| (1 - r) = 1.5
    # (not 1: the r = 1/2 reference case cannot tell t + 2u / (|A|(1-r)) from t + 2u |A| (1-r)).
    r = 0.25
    h = simulate(_chatter_row(r, -3.0), 4.0, dps=30)
    imp = [t for t, k in zip(h.times, h.kinds, strict=True) if k == IMPACT]
    with mpmath.workdps(60):
        t1 = mpmath.acos(mpmath.mpf(4) / 5)
        v, rr = mpmath.mpf(3) / 2, mpmath.mpf(r)
        partial = [t1 + mpmath.fsum(2 * mpmath.atan(v * rr**k / 2) for k in range(1, m))
                   for m in range(1, len(imp) + 1)]
        t_acc = t1 + mpmath.nsum(lambda k: 2 * mpmath.atan(v * rr**k / 2), [1, mpmath.inf])
        assert len(imp) > 20
        assert max(abs(a - b) for a, b in zip(imp, partial, strict=True)) < 1e-27
        assert h.kinds[-1] == STICK
        assert abs(h.aux[-1] - t_acc) < 1e-27
    for engine in ("python", "c") if fast_mod.available() else ("python",):
        # float64 chatter times are ill-conditioned (~1e-9 here); the two aux formulas differ
        # by ~2e-6 at the float64 threshold 1e-6
        hf = simulate(_chatter_row(r, -3.0), 4.0, engine=engine)
        assert hf.kinds[-1] == STICK and abs(hf.aux[-1] - float(t_acc)) < 1e-8


@pytest.mark.parametrize("dps", [None, 30])
def test_slow_contacts_stick_and_release(dps):
    # x = 1 - cos t / 2 - 0.9 sin t reaches the wall with speed sqrt(0.06) < v_stick = 1/2: it
    # sticks (no bounce, u0 = -r |u|); the contact is not compressed (x'' = 1 > 0 at x = 0), so
    # no accumulation time and the contact force releases at once
    row = PipeRow(1, restitution=0.5, Omega=(math.sqrt(2),), alpha=[[0.0]], beta=[[0.0]],
                  x0=[0.5], v0=[-0.9])
    h = simulate(row, 3.0, dps=dps, v_stick=0.5)
    assert h.kind_names()[:2] == ["stick", "release"] and h.times[0] == h.times[1]
    with mpmath.workdps(40):
        x0, v0 = mpmath.mpf(0.5), mpmath.mpf(-0.9)      # the row's exact float inputs
        amp = mpmath.sqrt((1 - x0) ** 2 + v0**2)
        # x = 1 - amp cos(t - ph) = 0 first at ph - acos(1/amp), with speed sqrt(amp^2 - 1)
        t_hit = mpmath.atan2(-v0, 1 - x0) - mpmath.acos(1 / amp)
        u = mpmath.sqrt(amp**2 - 1)
        tol = 1e-10 if dps is None else 1e-25
        assert abs(h.times[0] - t_hit) < tol
        assert abs(h.u_before[0] + u / 2) < tol and h.aux[0] == h.times[0]
    # r = 1: the same slow contact under compression (constant force pushing to the wall)
    row1 = _chatter_row(1.0, -3.0)
    h1 = simulate(row1, 1.0, dps=dps, v_stick=2.0)
    assert h1.kind_names() == ["stick"] and h1.aux[0] == h1.times[0]
    with mpmath.workdps(40):
        assert abs(h1.times[0] - mpmath.acos(mpmath.mpf(4) / 5)) < (1e-10 if dps is None else
                                                                    1e-25)
        assert abs(h1.u_before[0] + mpmath.mpf(3) / 2) < (1e-10 if dps is None else 1e-25)


def test_cascade_backstop_at_the_bound():
    # pipe 1 (1 - 2 sin t) reaches the wall and pipe 2 (2 - 4 sin t) reaches pipe 1 at the same
    # instant pi/6; with r = 1/10 the three bodies collapse: ever slower impacts at that one
    # instant.  At dps = 100 (v_stick ~ 1e-51) the chatter threshold comes after
    # cascade_bound(2) = 160 events, so the backstop ends it: events 0..159 are impacts with
    # u' = -r u, event 160 is a plastic impact (impact + stick), then both contacts release.
    row = PipeRow(2, restitution=0.1, alpha=np.zeros((2, 1)), beta=np.zeros((2, 1)),
                  x0=[1.0, 2.0], v0=[-2.0, -4.0])
    h = simulate(row, 0.6, dps=100)
    kinds = h.kind_names()
    assert len(set(h.times)) == 1
    with mpmath.workdps(110):
        assert abs(h.times[0] - mpmath.pi / 6) < mpmath.mpf(10) ** -100
        b = 20 * 3 + 100
        assert kinds[:b + 1] == ["impact"] * (b + 1) and kinds[b + 1] == "stick"
        assert all(abs(u1 + mpmath.mpf(0.1) * u0) < mpmath.mpf(10) ** -100 * abs(u0)
                   for u0, u1, k in zip(h.u_before[:b], h.u_after[:b], kinds[:b], strict=True))
        assert "stick" in kinds[b + 2:] and kinds[-2:] == ["release", "release"]
    # at dps = 60 the threshold (~1e-31) ends the collapse first, before the bound
    h60 = simulate(row, 0.6, dps=60)
    k60 = h60.kind_names()
    assert len(k60) < 160 and k60.index("stick") < 159


def test_instant_that_never_resolves_raises():
    # the loop guard of one instant: with an impact rule that changes nothing (patched), the same
    # contact fires forever at t*; after cascade_bound(n) events the backstop is armed, after
    # twice that the run stops with a clear error (not a hang)
    row = PipeRow(1, restitution=0.5, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    eng = Engine(row, FloatContext(), v_stick=1e-6)
    eng._impact = lambda i, t: (i, i + 1)   # type: ignore[method-assign]
    b = cascade_bound(1)
    with pytest.raises(SimulationError, match=rf"more than {2 * b + 1} events at t=0.523598775598"
                                              r"\d* even with plastic impacts: degenerate contact "
                                              r"configuration"):
        eng.run(1.0, max_events=10 * b)
    assert eng.plastic_at == pytest.approx(math.pi / 6, abs=1e-15)


@pytest.mark.parametrize("dps", [None, 20])
def test_stuck_contact_force_touching_zero_stays_stuck(dps):
    # plastic pipe under F = -1 + cos(0.4 t) + cos(0.8 t): on the left wall its contact force is
    # lambda = -(omega^2 d + F) = -cos(0.4 t) - cos(0.8 t) (eq. 19 at x = 0), which touches zero
    # at 0.4 t = pi (a double root: the pipe stays) and turns tensile at 0.4 t = 5 pi / 3
    row = PipeRow(1, restitution=0.0, Omega=(0.0, 0.4, 0.8), alpha=[[-1.0, 1.0, 1.0]],
                  beta=[[0.0, 0.0, 0.0]], x0=[0.3], v0=[-1.0])
    h = simulate(row, 14.0, dps=dps)
    assert h.kind_names() == ["impact", "stick", "release"]
    assert list(h.sites) == [0, 0, 0] and h.times[1] < 2.5 * math.pi
    with mpmath.workdps(30):
        a = mpmath.mpf(0.4)      # the row's frequencies are the float64 values 0.4 and 2 * 0.4
        assert abs(h.times[2] - 5 * mpmath.pi / (3 * a)) < (1e-9 if dps is None else 1e-18)
    x, _ = h.state(2.5 * math.pi + 0.1)
    assert abs(float(x[0])) < 1e-12


def test_stuck_contact_force_slow_rise_is_not_a_chatter_end():
    # a pipe stuck on the left wall with F = -1/2 - cos(2t)/2 - (p/2) sin 2t: its contact force
    # lambda = -(omega^2 d + F) = sin t (p cos t - sin t) starts at 0 rising with slope p
    # (below v_stick: a *gap* that slow would stick, but a force is not a gap) and turns tensile
    # at tan t = p: the release is there, not at t = 0
    p = 2.0**-22
    row = PipeRow(1, omega=1.0, d=1.0, Omega=(0.0, 2.0), restitution=0.0, alpha=[[-0.5, -0.5]],
                  beta=[[0.0, -p / 2]], x0=[0.5], v0=[0.0])
    eng = Engine(row, FloatContext(), v_stick=1e-6)
    eng.stuck[0] = True
    eng.set_motion(0, 1, 0.0, 0.0, 0.0)
    D, V, A, _ = eng.derivs(eng.contact_force(0), 0.0)
    assert D == 0 and 0 < V <= eng.v_stick and A < -1
    eng.run(2.4e-7)   # just past the release (the free pipe then touches the wall again)
    t, s, k, _, _, _ = eng.log.event_arrays()
    assert (int(s[0]), int(k[0])) == (0, RELEASE)
    assert abs(t[0] - math.atan(p)) < 1e-12


@pytest.mark.parametrize("kw", ENGINES)
def test_plastic_simultaneous_impacts_then_releases_hand_solved(kw):
    # x1 = 1 + 2 sin t, x2 = 2, x3 = 3 - 2 sin t (no force, r = 0): both gaps close at t = pi/6
    # with identical polynomials (an exact tie).  Rules: smaller site first; a plastic impact
    # merges; at one instant the free gaps (impacts) go before the stuck ones (releases).  By
    # hand: gap 1 closes at u = -sqrt 3 -> {1, 2} moves at sqrt(3)/2; gap 2 then closes at
    # u = -sqrt 3 - sqrt(3)/2 -> {1, 2, 3} at rest (momentum 0); its contact forces are tensile
    # (pipes 1 and 3 sit one d off their equilibria): both contacts release at once, all at rest.
    row = PipeRow(3, restitution=0, alpha=np.zeros((3, 1)), beta=np.zeros((3, 1)),
                  x0=[1.0, 2.0, 3.0], v0=[2.0, 0.0, -2.0])
    want = [(1, IMPACT), (1, STICK), (2, IMPACT), (2, STICK), (1, RELEASE), (2, RELEASE)]
    s3 = np.sqrt(3.0)
    h = simulate(row, 1.0, **kw)
    assert list(zip(h.sites.tolist(), h.kinds.tolist(), strict=True)) == want, kw
    assert max(abs(float(t) - np.pi / 6) for t in h.times) < 1e-14
    u = [float(x) for x in h.u_before]
    assert abs(u[0] + s3) < 1e-14 and abs(u[2] + 1.5 * s3) < 1e-14
    _, v = h.state(h.times[-1])
    assert max(abs(float(x)) for x in v) < 1e-14
    # after the releases the outer pipes spring back to their equilibria: no more events
    x, _ = h.state(1.0)
    assert float(x[0]) < 2.0 < float(x[2])


@pytest.mark.skipif(not fast_mod.available(), reason="C extension not built")
@pytest.mark.parametrize("t_end, kinds_at_touch", [
    # a touch (graze) found twice at one instant merges the pair, which then releases
    (494.0, ["graze", "graze", "stick", "release"]),
    # ... and a touch found again after that merge and release steps past it (touch_step)
    (449.5, ["graze", "graze", "stick", "release", "graze"]),
])
def test_repeated_touch_rules_c_equals_python(t_end, kinds_at_touch):
    # a 4-pipe plastic row found by a search at small omega (a release leaves the pair touching
    # within rounding): the touch rules of the run loop, run by the C engine and by the Python
    # port (two implementations of them), bit for bit.  The instant of the touch is found in the
    # run (around t = 449 and 493).
    row = PipeRow.random(4, 2.0634439501276165, seed=5757, restitution=0.0,
                         omega=0.01094089443368739)
    a = simulate(row, t_end, engine="c")
    b = simulate(row, t_end, engine="python")
    assert np.array_equal(_table(a), _table(b))
    names = a.kind_names()
    # instants whose events are exactly the documented touch sequence
    found = [t for t in np.unique(a.times)
             if [names[i] for i in np.flatnonzero(a.times == t)] == kinds_at_touch]
    assert found and t_end - 1.0 < found[-1] < t_end, "the touch sequence did not occur"
    x, _ = a.states(np.linspace(0.0, t_end, 2001))
    assert np.diff(x, axis=1).min() > -1e-9 and x.min() > -1e-9


# ---------------------------------------------------------------- a slow release (no graze stream)
def _slow_release_row(p: float) -> PipeRow:
    return PipeRow(1, omega=1.0, d=1.0, Omega=(0.0, 2.0), restitution=0.0,
                   alpha=[[-0.5, -0.5]], beta=[[0.0, -p / 2]], x0=[0.5], v0=[0.0])


@pytest.mark.parametrize("e", [-22, -16, -10])
def test_slow_release_does_not_stream_grazes(e):
    # one pipe stuck to the left wall, its contact force crossing zero at t = atan(p): after the
    # release the pipe leaves the wall with a curvature just above rounding, and each restart of
    # the search found the touch again ~7e-14 later, never at the same instant (> 10000 grazes
    # in 3e-7).  A touch found again within one touch step is the same touch (the module
    # docstring), so the events stay within 1 + T max(M2 / (2 v_stick), 5 / touch_step).
    p = 2.0**e
    eng = Engine(_slow_release_row(p), FloatContext(), v_stick=1e-6)
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
    mc = MPContext()
    with mc.workdps(30):
        eng = Engine(_slow_release_row(p), mc, v_stick=mc.num("1e-6"))
        eng.stuck[0] = True
        z = mc.num(0)
        eng.set_motion(0, 1, z, z, z)
        eng.run(mc.num("0.01"), max_events=100_000)
    t = eng.log.exported().event_arrays(dtype=object)[0]
    with mpmath.workdps(30):
        assert abs(t[0] - mpmath.atan(mpmath.mpf(p))) < mpmath.mpf(10) ** -25 / p
    assert len(t) < 1000
