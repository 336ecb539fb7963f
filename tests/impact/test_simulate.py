"""``symhx.impact.simulate``: the entry point of both engines -- its arguments, defaults, caps
and refusals, the lean float64 path against the fully validated one, and the model's scale
invariance.  The mechanics of the runs are in ``test_simulate_mechanics.py``, the exact inputs
and precision in ``test_simulate_exact.py``, the 1050-row sweep in ``test_simulate_sweep.py``."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx.impact import IMPACT, STICK, PipeRow, SimulationError, simulate
from symhx.impact import fast as fast_mod
from symhx.impact.model import MAX_EVENTS, MAX_HORIZON, MAX_SCALE
from tests.harness.errors import assert_refuses


def _table(h):
    return np.column_stack([h.times, h.sites, h.kinds, h.u_before, h.u_after, h.aux])


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


def test_default_v_stick_and_work_dps_validate():
    from symhx.impact import default_v_stick, work_dps

    row = PipeRow.random(2, 0.1, seed=0, d=2)
    assert_refuses(default_v_stick, 3.0, None, exc=TypeError, arg="row", value="float 3.0",
                   allowed="a PipeRow")
    for bad in (0, -1, 2.5, True, float("nan"), 10**6):
        assert_refuses(default_v_stick, row, bad, exc=(ValueError, TypeError), arg="dps")
        assert_refuses(work_dps, bad, exc=(ValueError, TypeError), arg="dps")
    # far below the float64 range at MAX_DPS, and still the documented omega d 10**(-dps/2 - 1)
    with mpmath.workdps(30):
        ref = 2 * mpmath.mpf(10) ** -2501
        assert abs(default_v_stick(row, 5000) / ref - 1) < mpmath.mpf(10) ** -18
    assert default_v_stick(row, None) == 2e-6


def test_v_stick_zero_and_huge():
    row = _chatter_row()
    assert_refuses(simulate, row, 10.0, v_stick=0, arg="v_stick", value="0", allowed="> 0")
    assert_refuses(simulate, row, 10.0, v_stick=10**1000, arg="v_stick",
                   allowed=["float64 range", "positive float64 number"])  # no OverflowError
    h = simulate(row, 10.0, v_stick=10**1000, dps=15)  # exact in mpmath: the first contact sticks
    assert [int(k) for k in h.kinds] == [STICK]


@pytest.mark.parametrize("t_end", [float("nan"), -1.0, 0.0, float("inf"), "abc"])
def test_bad_horizon(t_end):
    row = PipeRow.random(2, 0.1, seed=0)
    assert_refuses(simulate, row, t_end, exc=(ValueError, TypeError), arg="t_end")


@pytest.mark.parametrize("dps", [0, -1, 2.5, True, 10**6])
def test_bad_dps_refused_up_front(dps):
    row = PipeRow.random(2, 0.1, seed=0)
    assert_refuses(simulate, row, 1.0, dps=dps, exc=(ValueError, TypeError), arg="dps")


def test_bad_row_and_engine():
    assert_refuses(simulate, 3.0, 1.0, exc=TypeError, arg="row", allowed="a PipeRow")
    row = PipeRow.random(2, 0.1, seed=0)
    assert_refuses(simulate, row, 1.0, engine="fortran", arg="engine", value="'fortran'",
                   allowed="'auto'")


def test_horizon_and_event_caps():
    row = PipeRow.random(2, 0.1, seed=0, omega=2)
    assert len(simulate(row, MAX_HORIZON / 2)) >= 0             # omega * t_end == cap: allowed
    for t_end in (MAX_HORIZON / 2 * (1 + 1e-9), 1e308, 10**1000):
        assert_refuses(simulate, row, t_end, arg="t_end", allowed=["MAX_HORIZON", "omega = 2.0"])
    assert_refuses(simulate, row, 1.0, max_events=MAX_EVENTS + 1, arg="max_events",
                   value=str(MAX_EVENTS + 1), allowed="MAX_EVENTS")
    assert_refuses(simulate, row, 1.0, max_events=10**1000, arg="max_events")
    for few in (0, -5):  # a run records at least one event
        assert_refuses(simulate, row, 1.0, max_events=few, arg="max_events", value=str(few),
                       allowed=">= 1")


@pytest.mark.parametrize("kw", [{}, {"max_events": 10_000}])
def test_engine_c_without_the_extension_says_it_is_not_built(kw, monkeypatch):
    row = PipeRow.random(4, 2.0, seed=3, restitution=0.8)
    monkeypatch.setattr(fast_mod, "available", lambda: False)
    with pytest.raises(SimulationError, match=r"C extension symhx\.impact\._fast is not built"):
        simulate(row, 10.0, engine="c", **kw)
    assert len(simulate(row, 10.0, **kw)) > 5          # "auto" falls back to Python


@pytest.mark.parametrize("engine", ["python", "c"])
def test_the_event_cap_applies_by_default(engine, monkeypatch):
    # without max_events the documented default cap MAX_EVENTS holds on the common float64
    # call too (a cap of 5 here, set where it is documented: the run has more events)
    import symhx.impact.model as model_mod

    if engine == "c" and not fast_mod.available():
        pytest.skip("C extension not built")
    row = PipeRow.random(4, 2.0, seed=3, restitution=0.8)
    assert len(simulate(row, 10.0, engine=engine)) > 5
    monkeypatch.setattr(model_mod, "MAX_EVENTS", 5)
    with pytest.raises(SimulationError, match="max_events=5"):
        simulate(row, 10.0, engine=engine)


@pytest.mark.parametrize("dps, engine", [(None, "python"), (None, "c"), (20, None)])
def test_max_events_and_horizon_are_inclusive(dps, engine):
    if engine == "c" and not fast_mod.available():
        pytest.skip("C extension not built")
    row = PipeRow.random(4, 2.0, seed=3, restitution=0.8)
    kw = {"dps": dps} if dps else {"engine": engine}
    h = simulate(row, 10.0, **kw)
    n = len(h)
    assert n > 5
    assert len(simulate(row, 10.0, max_events=n, **kw)) == n
    with pytest.raises(SimulationError, match=rf"more than max_events={n - 1} events before "
                                              r"t_end"):
        simulate(row, 10.0, max_events=n - 1, **kw)
    # an event exactly at t_end belongs to the run
    te = h.times[3]
    h2 = simulate(row, te if dps else float(te), **kw)
    assert len(h2) == 4 and h2.times[-1] == te


@pytest.mark.skipif(not fast_mod.available(), reason="C extension not built")
def test_lean_float_path_equals_validated_path():
    row = PipeRow.random(10, 0.3, seed=2, restitution=0.8)
    a = simulate(row, 30.0)                                  # lean path
    b = simulate(row, Fraction(30), v_stick=1e-6, max_events=10**8, engine="c")   # full checks
    assert np.array_equal(_table(a), _table(b))
    assert a.t_end == b.t_end == 30.0 and type(a.t_end) is float


def test_lean_path_horizon_cap_exact():
    row = PipeRow(1, restitution=1, omega=3.0, alpha=[[0.0]], beta=[[0.0]], x0=[1.0],
                  v0=[0.0])
    t_max = MAX_HORIZON / 3.0          # omega * t_max rounds to 1e5 but is exactly above it
    assert Fraction(t_max) * 3 > MAX_HORIZON
    assert_refuses(simulate, row, t_max, arg="t_end", value=repr(t_max), allowed="too long")
    t_ok = np.nextafter(t_max, 0.0).item()
    assert Fraction(t_ok) * 3 <= MAX_HORIZON
    h = simulate(row, t_ok, max_events=10)   # accepted (no event: the pipe rests)
    assert len(h) == 0
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        assert_refuses(simulate, row, bad, arg="t_end")
    assert_refuses(simulate, row, 1.0, engine="fortran", arg="engine")


def test_mpmath_global_precision_untouched():
    before = mpmath.mp.dps
    simulate(PipeRow.random(3, 0.3, seed=2), 3.0, dps=25).state(1.0)
    assert mpmath.mp.dps == before


def test_mpmath_engine_ignores_the_global_precision():
    # the reference engine works in its thread's own context: a user's mpmath.mp.dps changes
    # nothing in its results (bit for bit), at low and at high global precision
    row = PipeRow.random(3, 0.3, seed=2)
    ref = simulate(row, 3.0, dps=25)
    for dps in (5, 200):
        with mpmath.workdps(dps):
            h = simulate(row, 3.0, dps=25)
            x = h.state(1.0)[0]
        assert [t._mpf_ for t in h.times] == [t._mpf_ for t in ref.times]
        assert [a._mpf_ for a in x] == [a._mpf_ for a in ref.state(1.0)[0]]


def test_scale_invariance_and_scale_cap():
    # the model is linear in lengths: a row scaled by k has the same event times; rows beyond
    # MAX_SCALE are refused (a row scaled by 1e160 used to lose every impact silently)
    ref = simulate(PipeRow.random(3, 1.0, seed=3), 50.0)
    assert len(ref) > 20
    for k in (1e-90, 1e90):
        h = simulate(PipeRow.random(3, 1.0 * k, d=k, seed=3), 50.0, v_stick=1e-6 * k)
        assert h.sites.tolist() == ref.sites.tolist()
        assert np.allclose(np.asarray(h.times, float), np.asarray(ref.times, float), rtol=1e-9)
    for k in (MAX_SCALE * 10, 1 / MAX_SCALE / 10):
        assert_refuses(PipeRow.random, 3, 1.0 * k, d=k, seed=3, arg="d", allowed="MAX_SCALE")


def test_engine_python_never_runs_the_c_kernel(monkeypatch):
    # engine="python" is honoured when the C extension is there: the C entry point is not called
    def no_c(*args, **kwargs):
        raise AssertionError("the C engine ran")

    monkeypatch.setattr(fast_mod, "simulate_c", no_c)
    row = PipeRow.random(3, 0.3, seed=2)
    assert len(simulate(row, 5.0, engine="python")) >= 0
    if fast_mod.available():
        with pytest.raises(AssertionError, match="the C engine ran"):
            simulate(row, 5.0)


@pytest.mark.parametrize("engine", ["python", "c"])
def test_the_quick_float64_path_sticks_at_the_default_threshold(engine):
    # simulate(row, float t_end) takes a shortcut past the argument checks; it must use the
    # same sticking threshold as every other call, default_v_stick(row, None) = omega d V,
    # also when the spacing d and the frequency omega are not 1
    from symhx.impact import default_v_stick

    if engine == "c" and not fast_mod.available():
        pytest.skip("the C extension is not built")
    row = PipeRow.random(5, 10.0, seed=4, restitution=0.5, d=2.5, omega=1.7)
    quick = simulate(row, 40.0, engine=engine)
    checked = simulate(row, 40.0, engine=engine, v_stick=default_v_stick(row, None),
                       max_events=MAX_EVENTS)
    assert len(quick) == len(checked) > 10
    assert np.array_equal(quick.times, checked.times)
    assert np.array_equal(quick.sites, checked.sites) and np.array_equal(quick.kinds, checked.kinds)
    assert set(quick.kinds.tolist()) > {IMPACT}  # sticking happens: the threshold matters
