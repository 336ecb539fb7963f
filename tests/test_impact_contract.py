"""Impact engines: chatter threshold, float64 vs mpmath event sequences, bad inputs (#12, #16)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx.impact import IMPACT, STICK, PipeRow, SimulationError, simulate
from symhx.impact.fast import available, count_impacts


def _chatter_row():
    # constant force (Omega = 0) pressing one pipe into the right wall: equilibrium at
    # d + alpha / omega^2 = 1 + 1.5 > 2 d; released at rest from x = 1.5, r = 1/2
    return PipeRow(1, restitution=0.5, Omega=(0,), alpha=[[1.5]], beta=[[0.0]], x0=[1.5],
                   v0=[0.0])


@pytest.mark.parametrize("dps", [None, 12])
def test_default_chatter_threshold(dps):
    # documented default: v_stick = omega d 10**(-dps/2 - 1), float64 as dps = 10 -> 1e-6
    vs = 1e-6 if dps is None else 10.0 ** (-dps / 2 - 1)
    h = simulate(_chatter_row(), 10.0, dps=dps)
    imp = [k for k in range(len(h)) if h.kinds[k] == IMPACT]
    stick = [k for k in range(len(h)) if h.kinds[k] == STICK]
    assert len(stick) == 1 and stick[0] == imp[-1] + 1 and h.sites[stick[0]] == 1
    # the chatter ends at the first bounce slower than v_stick, not before
    assert abs(float(h.u_after[imp[-1]])) <= vs
    assert abs(float(h.u_after[imp[-2]])) > vs
    # independent count: the speeds are u0 r^k with u0 from energy (no forcing work lost)
    u0 = abs(float(h.u_before[imp[0]]))
    assert math.isclose(u0, math.sqrt(2 * 1.5 * 0.5 - (1.0**2 - 0.5**2)), rel_tol=1e-9)
    assert len(imp) == math.ceil(math.log(u0 / vs) / math.log(2))


def _rows50():
    rng = np.random.default_rng(5)
    for k in range(50):
        yield PipeRow.random(int(rng.integers(2, 12)), float(rng.uniform(0.1, 0.6)), seed=k,
                             restitution=float(rng.choice([0.0, 0.5, 0.8, 1.0])))


def _clusters(h, tol=1e-9):
    """Events grouped into clusters closer than ``tol`` in time: near-simultaneous events (a
    plastic cascade 1e-16 apart in mpmath is one instant in float64) may be resolved in a
    different order, but each cluster must involve the same contact sites at the same time."""
    out = []
    for t, site, kind in zip(h.times, h.sites, h.kinds, strict=True):
        t = float(t)
        if out and t - out[-1][1] <= tol:
            out[-1][1] = t
            out[-1][2].add((int(site), kind == 1))
        else:
            out.append([t, t, {(int(site), kind == 1)}])
    return out


@pytest.mark.parametrize("chunk", range(5))
def test_float_vs_mpmath_event_sequences_50_rows(chunk):
    # equal v_stick in both engines: the same event clusters (sites; graze or contact), times
    # within 1e-9; rows without near-simultaneous events must match event by event
    for idx, row in enumerate(_rows50()):
        if idx % 5 != chunk:
            continue
        ref = simulate(row, 8.0, dps=20, v_stick=1e-6)
        fl = simulate(row, 8.0, v_stick=1e-6)
        a, b = _clusters(ref), _clusters(fl)
        assert [c[2] for c in a] == [c[2] for c in b], idx
        err = max((abs(x[0] - y[0]) for x, y in zip(a, b, strict=True)), default=0.0)
        assert err < 1e-9, (idx, err)
        if len(a) == len(ref):
            assert fl.kinds.tolist() == ref.kinds.tolist()


@pytest.mark.parametrize("t_end", [float("nan"), -1.0, 0.0, float("inf"), "abc"])
def test_bad_horizon(t_end):
    row = PipeRow.random(2, 0.1, seed=0)
    with pytest.raises((ValueError, TypeError), match="t_end"):
        simulate(row, t_end)


@pytest.mark.parametrize("dps", [0, -1, 2.5, True, 10**6])
def test_bad_dps_refused_up_front(dps):
    row = PipeRow.random(2, 0.1, seed=0)
    with pytest.raises((ValueError, TypeError), match="dps"):
        simulate(row, 1.0, dps=dps)


def test_bad_state_time():
    h = simulate(PipeRow.random(2, 0.1, seed=0), 1.0)
    for t in (float("nan"), -0.5, 2.0):
        with pytest.raises(ValueError, match="t"):
            h.state(t)
    with pytest.raises(ValueError, match="times"):
        h.states([0.5, float("nan")])


@pytest.mark.parametrize("kwargs, name", [
    (dict(n=True, sigma=0.3), "n"), (dict(n=2, sigma=True), "sigma"),
    (dict(n=2, sigma=0.3, d=0), "d"), (dict(n=2, sigma=-0.3), "sigma"),
    (dict(n=2, sigma=0.3, omega=math.sqrt(2)), "resonance"),
    (dict(n=2, sigma=float("nan")), "sigma"),
])
def test_bad_random_rows(kwargs, name):
    with pytest.raises((ValueError, TypeError), match=name):
        PipeRow.random(**kwargs)


def test_undrawable_row_clear_error():
    with pytest.raises(ValueError, match="too large for the spacing d"):
        PipeRow.random(30, 3.0, seed=1, d=0.01, omega=1.4)


def test_bad_row_values_named():
    with pytest.raises(ValueError, match=r"alpha\[0\]\[0\]"):
        PipeRow(1, restitution=1, alpha=[["nan"]], beta=[[0]], x0=[1], v0=[0])
    with pytest.raises(ValueError, match=r"beta\[1\]\[0\] must be finite"):
        PipeRow(2, restitution=1, alpha=[[0], [0]], beta=[[0], [math.inf]], x0=[1, 2], v0=[0, 0])
    with pytest.raises(TypeError, match="restitution"):
        PipeRow(1, restitution=True, alpha=[[0]], beta=[[0]], x0=[1], v0=[0])
    with pytest.raises(ValueError, match="restitution"):
        PipeRow(1, restitution="1.5", alpha=[[0]], beta=[[0]], x0=[1], v0=[0])
    with pytest.raises(ValueError, match="resonance"):
        PipeRow(1, restitution=1, Omega=("1",), alpha=[[0]], beta=[[0]], x0=[1], v0=[0])


@pytest.mark.skipif(not available(), reason="C extension not built")
def test_simulation_error_is_runtime_error():
    row = PipeRow.random(20, 0.4, seed=1, restitution=1.0)
    with pytest.raises(SimulationError, match="max_events"):
        count_impacts(row, 100.0, 0.0, max_events=10)
    assert issubclass(SimulationError, RuntimeError)


def test_mpmath_global_precision_untouched():
    before = mpmath.mp.dps
    simulate(PipeRow.random(3, 0.3, seed=2), 3.0, dps=25).state(1.0)
    assert mpmath.mp.dps == before


# ----------------------------------------------------------------- fuzz round (issue 12)
def test_scale_invariance_and_scale_cap():
    # the model is linear in lengths: a row scaled by k has the same event times; rows beyond
    # MAX_SCALE are refused (a row scaled by 1e160 used to lose every impact silently)
    from symhx.impact.model import MAX_SCALE

    ref = simulate(PipeRow.random(3, 1.0, seed=3), 50.0)
    assert len(ref) > 20
    for k in (1e-90, 1e90):
        h = simulate(PipeRow.random(3, 1.0 * k, d=k, seed=3), 50.0, v_stick=1e-6 * k)
        assert h.sites.tolist() == ref.sites.tolist()
        assert np.allclose(np.asarray(h.times, float), np.asarray(ref.times, float), rtol=1e-9)
    for k in (MAX_SCALE * 10, 1 / MAX_SCALE / 10):
        with pytest.raises(ValueError, match="MAX_SCALE"):
            PipeRow.random(3, 1.0 * k, d=k, seed=3)


def test_v_stick_zero_and_huge():
    row = _chatter_row()
    with pytest.raises(ValueError, match="v_stick must be > 0"):
        simulate(row, 10.0, v_stick=0)
    with pytest.raises(ValueError, match="v_stick"):
        simulate(row, 10.0, v_stick=10**1000)          # beyond float64: no OverflowError
    h = simulate(row, 10.0, v_stick=10**1000, dps=15)  # exact in mpmath: the first contact sticks
    assert [int(k) for k in h.kinds] == [STICK]


def test_horizon_and_event_caps():
    from symhx.impact.model import MAX_EVENTS, MAX_HORIZON

    row = PipeRow.random(2, 0.1, seed=0, omega=2)
    assert len(simulate(row, MAX_HORIZON / 2)) >= 0             # omega * t_end == cap: allowed
    for t_end in (MAX_HORIZON / 2 * (1 + 1e-9), 1e308, 10**1000):
        with pytest.raises(ValueError, match="MAX_HORIZON"):
            simulate(row, t_end)
    with pytest.raises(ValueError, match="MAX_EVENTS"):
        simulate(row, 1.0, max_events=MAX_EVENTS + 1)
    with pytest.raises(ValueError, match="max_events"):
        simulate(row, 1.0, max_events=10**1000)


def test_default_v_stick_and_work_dps_validate():
    from symhx.impact import default_v_stick, work_dps

    row = PipeRow.random(2, 0.1, seed=0, d=2)
    with pytest.raises(TypeError, match="row must be a PipeRow"):
        default_v_stick(3.0, None)
    for bad in (0, -1, 2.5, True, float("nan"), 10**6):
        with pytest.raises((ValueError, TypeError), match="dps"):
            default_v_stick(row, bad)
        with pytest.raises((ValueError, TypeError), match="dps"):
            work_dps(bad)
    # far below the float64 range at MAX_DPS, and still the documented omega d 10**(-dps/2 - 1)
    with mpmath.workdps(30):
        ref = 2 * mpmath.mpf(10) ** -2501
        assert abs(default_v_stick(row, 5000) / ref - 1) < mpmath.mpf(10) ** -18
    assert default_v_stick(row, None) == 2e-6


def test_random_row_seed_and_hopeless_draws():
    import time

    from symhx.impact.model import MAX_PIPES

    a = PipeRow.random(4, 0.3, seed=5)
    b = PipeRow.random(4, 0.3, seed=np.random.SeedSequence(5))   # numpy: the same stream
    assert np.array_equal(a.x0, b.x0) and np.array_equal(a.alpha, b.alpha)
    for seed in (True, [], -1, 2.5):
        with pytest.raises((ValueError, TypeError), match="seed"):
            PipeRow.random(3, 0.3, seed=seed)
    t0 = time.perf_counter()
    for kw in (dict(sigma=1e6), dict(sigma=1e308), dict(sigma=0.3, d=1e308),
               dict(sigma=0.3, d=5e-324), dict(sigma=0.3, omega=10**1000)):
        with pytest.raises(ValueError):
            PipeRow.random(3, seed=0, **kw)
    assert time.perf_counter() - t0 < 1.0     # refused up front, not after redrawing
    with pytest.raises(ValueError, match="MAX_PIPES"):
        PipeRow.random(MAX_PIPES + 1, 0.3)
