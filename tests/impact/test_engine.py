"""``symhx.impact.engine``: its documented formulas, the row's closed-form arrays, the event
record, the shared cos/sin kernel, the arithmetics (float64 and the thread's own mpmath context)
and the bodies (contact forces, merged motion).

The certified search has ``test_engine_search.py``; the impact / stick / release rules of a run
``test_engine_rules.py``.
"""

from __future__ import annotations

import math
import threading

import mpmath
import numpy as np
import pytest

from symhx.impact import GRAZE, IMPACT, RELEASE, STICK, PipeRow
from symhx.impact.engine import (
    EVENT_DTYPE,
    Engine,
    EventLog,
    FloatContext,
    MPContext,
    _cos_sin,
    cascade_bound,
    default_v_stick,
    row_arrays,
    work_dps,
)
from symhx.impact.history import History
from tests.reference.impact import contact_forces

EPS = 2.0**-52


def _row(r=0.5, *, d=1.0, Omega=(2.0,), n=1):
    # unforced pipes, forcing frequency 2 present (amplitude 0): gap polynomials of length 5
    return PipeRow(n, omega=1.0, d=d, Omega=Omega, restitution=r, alpha=np.zeros((n, len(Omega))),
                   beta=np.zeros((n, len(Omega))), x0=[d * (j + 1) for j in range(n)],
                   v0=[0.0] * n)


# ---------------------------------------------------------------- small documented formulas
def test_work_dps_cascade_bound_and_v_stick_formulas():
    for dps in (1, 15, 30, 1000):
        assert work_dps(dps) == 2 * dps + 10
    for n in (1, 2, 7, 500):
        assert cascade_bound(n) == 20 * (n + 1) + 100
    with pytest.raises(TypeError, match="row must be a PipeRow, got int"):
        default_v_stick(3, 10)


def test_kinds_are_recorded_with_their_names():
    assert [int(k) for k in (IMPACT, GRAZE, STICK, RELEASE)] == [0, 1, 2, 3]


def test_cos_sin_reduction_range():
    # Cody-Waite reduction for |x| < 823549.6 (~2**19 pi/2), libm beyond (both engines)
    for x in (823549.6, -823549.6, 823549.60037, 823549.60333, 823550.5, -823549.60037, 1e7):
        assert _cos_sin(x) == (math.cos(x), math.sin(x))
    with mpmath.workdps(40):
        for x in (823549.5, 1e5 + 0.3, -2.5, 0.7853981633974483):
            c, s = _cos_sin(x)
            assert abs(c - mpmath.cos(x)) <= EPS and abs(s - mpmath.sin(x)) <= EPS


def test_float_cos_sin_kernel_against_mpmath():
    # the kernel both float64 engines share (Cody-Waite + fdlibm polynomials, Estrin tails):
    # absolute error below 2**-52 against 40-digit mpmath, on random arguments over the range
    # it serves and on arguments next to multiples of pi/2 (where the reduction cancels most)
    rng = np.random.default_rng(13)
    xs = list(rng.uniform(-1, 1, 3000) * 10.0 ** rng.uniform(-3, 5.9, 3000))
    with mpmath.workdps(40):
        half_pi = mpmath.pi / 2
        for k in rng.integers(1, 500_000, 300):
            x = float(k * half_pi)
            xs += [x, math.nextafter(x, 0.0), math.nextafter(x, math.inf)]
        worst = mpmath.mpf(0)
        for x in xs:
            c, s = _cos_sin(x)
            worst = max(worst, abs(c - mpmath.cos(x)), abs(s - mpmath.sin(x)))
        assert worst < mpmath.mpf(2) ** -52
        assert worst > mpmath.mpf(2) ** -60   # the check sees rounding at all (not vacuous)
    # outside the reduction's exact range the kernel is libm
    assert _cos_sin(1e7) == (math.cos(1e7), math.sin(1e7))


def test_bounds_are_the_documented_sums():
    # M_k = sum_m c_m F_m**k with c_m = |(a_m, b_m)|; zero frequencies fold into c0
    eng = Engine(_row(Omega=(2.0, 0.0, 3.0)), FloatContext(), v_stick=1e-6)
    g = [0.5, 0.6, 0.8, 0.3, 0.4, 0.25, 0.0, 0.0, -2.0]
    c0, S, M1, M2, M3, M4 = eng.bounds(g)
    cs = [(1.0, 1.0), (2.0, 0.5), (3.0, 2.0)]
    assert c0 == 0.5 + 0.25
    for k, Mk in enumerate((S, M1, M2, M3, M4)):
        assert Mk == pytest.approx(sum(c * f**k for f, c in cs), rel=1e-15)


# ---------------------------------------------------------------- the arithmetics
def test_mp_context_uses_the_threads_own_precision():
    # the engine's mpmath arithmetic never reads or sets mpmath's global precision: it works at
    # the precision of its own workdps, whatever the global one is, and leaves it alone
    mc = MPContext()
    before = mpmath.mp.prec
    with mpmath.workdps(5):          # a user's global precision, much lower
        with mc.workdps(40):
            x = mc.num(1) / 3
            eps = mc.eps
            assert mc.mp.prec == 136 and mpmath.mp.prec == 20
        assert mc.mp.prec != 136
    assert mpmath.mp.prec == before
    with mpmath.workdps(60):
        assert abs(x - mpmath.mpf(1) / 3) < mpmath.mpf(10) ** -40
        assert eps == mpmath.mpf(2) ** -136
    # each thread has a context of its own
    other = []
    t = threading.Thread(target=lambda: other.append(MPContext().mp))
    t.start()
    t.join()
    assert other[0] is not mc.mp and MPContext().mp is mc.mp


def test_event_log_export_keeps_every_bit():
    # the mpmath engine's record leaves its thread as mpmath's global type, bit for bit
    row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    mc = MPContext()
    with mc.workdps(40):
        eng = Engine(row, mc, v_stick=1e-6)
        eng.run(mc.num(1))
    out = eng.log.exported()
    t0, s0, k0, u0, v0, a0 = eng.log.event_arrays(object)
    t1, s1, k1, u1, v1, a1 = out.event_arrays(object)
    assert len(out) == len(eng.log) == 1 and (s0 == s1).all() and (k0 == k1).all()
    for a, b in zip((*t0, *u0, *v0, *a0), (*t1, *u1, *v1, *a1), strict=True):
        assert isinstance(b, mpmath.mpf) and b._mpf_ == a._mpf_
    (st0, c0), (st1, c1) = eng.log.updates(), out.updates()
    for j in range(3):
        assert [x._mpf_ for x in st0[j]] == [x._mpf_ for x in st1[j]]
        for p, q in zip(c0[j], c1[j], strict=True):
            assert [x._mpf_ for x in p] == [x._mpf_ for x in q]
            assert all(isinstance(x, mpmath.mpf) for x in q)
    # float logs need nothing
    fl = Engine(row, FloatContext(), v_stick=1e-6)
    fl.run(1.0)
    assert fl.log.exported() is fl.log


# ---------------------------------------------------------------- row set-up and records
@pytest.mark.parametrize("mp", [False, True])
def test_row_arrays_layout_with_three_forcing_frequencies(mp):
    rng = np.random.default_rng(5)
    n, K = 4, 3
    alpha, beta = rng.normal(size=(n, K)), rng.normal(size=(n, K))
    row = PipeRow(n, omega=1.7, d=0.6, Omega=(0.0, 2.3, 0.37), restitution=0.5, alpha=alpha,
                  beta=beta, x0=[0.6, 1.2, 1.8, 2.4], v0=[0.1, -0.2, 0.3, 0.0])
    ctx = MPContext() if mp else FloatContext()
    with MPContext().workdps(30):
        ra = row_arrays(row, ctx)
        for arr in (ra.coef, ra.forced, ra.raw):
            assert arr.shape == (n + 2, 3 + 2 * K)
            assert arr.dtype == (object if mp else np.float64)
        assert float(ra.chunk) == pytest.approx(2 / 1.7, rel=1e-15)   # search horizon 2/omega
        for m in range(K):
            np.testing.assert_allclose(ra.raw[1:n + 1, 3 + 2 * m].astype(float), alpha[:, m],
                                       rtol=1e-15)
            np.testing.assert_allclose(ra.raw[1:n + 1, 4 + 2 * m].astype(float), beta[:, m],
                                       rtol=1e-15)
        assert not ra.raw[:, :3].any() and not ra.raw[[0, n + 1]].any()


def test_event_log_types():
    for dtype in (float, object):
        cols = EventLog([[0.0] * 5] * 3).event_arrays(dtype)
        assert [c.dtype for c in cols] == [np.dtype(dtype), np.int64, np.int8, np.dtype(dtype),
                                          np.dtype(dtype), np.dtype(dtype)]
    log = EventLog([[0.0] * 5] * 3)
    log.add_event(0.5, 1, GRAZE, 0.25, 0.25, 0.0)
    t, s, k, u0, u1, aux = log.event_arrays()
    assert (t.dtype, s.dtype, k.dtype) == (np.float64, np.int64, np.int8)
    assert (t[0], s[0], k[0], u0[0], u1[0], aux[0]) == (0.5, 1, 1, 0.25, 0.25, 0.0)
    assert len(log) == 1


def test_event_log_of_c_buffers_and_chunk_option():
    # the C engine's buffers (48-byte records of EVENT_DTYPE, float64 update rows j, t, coef...)
    # are read as they are: their length, their fields, the updates per pipe
    rec = np.zeros(3, dtype=EVENT_DTYPE)
    rec["t"], rec["site"], rec["kind"] = [0.5, 0.5, 1.25], [0, 1, 1], [IMPACT, STICK, RELEASE]
    rec["u0"], rec["u1"], rec["aux"] = [-1.0, -0.0, 0.0], [0.5, 0.0, 0.0], [0.0, 0.5, 1.25]
    width = 5
    coef0 = np.arange(3 * width, dtype=np.float64)
    upd = np.array([[1, 0.5, *range(10, 15)], [1, 1.25, *range(20, 25)]], dtype=np.float64)
    log = EventLog.from_buffers(coef0.tobytes(), rec.tobytes(), upd.tobytes(), width)
    assert len(log) == 3
    t, s, k, u0, u1, aux = log.event_arrays()
    assert t.tolist() == [0.5, 0.5, 1.25] and s.tolist() == [0, 1, 1]
    assert u0.tolist() == [-1.0, -0.0, 0.0] and u1.tolist() == [0.5, 0.0, 0.0]
    assert k.tolist() == [0, 2, 3] and aux.tolist() == [0.0, 0.5, 1.25]
    starts, coefs = log.updates()
    assert starts[1] == [0.0, 0.5, 1.25] and starts[0] == [0.0] and starts[2] == [0.0]
    assert np.asarray(coefs[1]).tolist() == [[5, 6, 7, 8, 9], list(range(10, 15)),
                                             list(range(20, 25))]
    row = PipeRow.random(5, 2.0, seed=1, restitution=0.8)
    assert Engine(row, FloatContext(), v_stick=1e-6, chunk=0.5).chunk == 0.5
    eng = Engine(row, FloatContext(), v_stick=1e-6)
    assert eng.chunk == 2 / row.omega and eng.row is row


# ---------------------------------------------------------------- bodies and forces
@pytest.mark.parametrize("stuck, k", [
    ((0, 1, 2), 1),      # pipes 1..3 on the left wall
    ((2, 3, 4), 3),      # pipes 2..4 on the right wall (n = 4)
    ((2, 4, 4), 2),      # only pipe 4 on the right wall
    ((1, 2), 2),         # free cluster of pipes 1..3
])
def test_contact_force_is_newtons_law_of_the_cluster(stuck, k):
    # the engine's contact force (a trigonometric polynomial) against Newton's law of the
    # cluster evaluated from positions and forces (tests.reference.impact.contact_forces): a
    # wall cluster sits on its wall, a free one anywhere (its position cancels)
    n, om, d = 4, 1.3, 0.7
    rng = np.random.default_rng(9)
    row = PipeRow(n, omega=om, d=d, Omega=(0.0, 2.1, 0.45), restitution=0.0,
                  alpha=rng.normal(size=(n, 3)), beta=rng.normal(size=(n, 3)),
                  x0=[0.7, 1.4, 2.1, 2.8], v0=[0.0] * n)
    eng = Engine(row, FloatContext(), v_stick=1e-6)
    st = np.zeros(n + 1, dtype=bool)
    for s in set(stuck):
        eng.stuck[s] = True
        st[s] = True
    lo, hi = eng.body(k)
    lam = eng.contact_force(k)
    for t in (0.0, 0.8, 3.1):
        val = eng.derivs(lam, t)[0]
        X = 0.0 if lo == 0 else (n + 1) * d if hi == n + 1 else 0.123   # 0.123: any
        x = np.arange(1, n + 1) * d
        x[max(lo, 1) - 1:min(hi, n)] = X
        want = contact_forces(row, [t], [x], st[None, :])[0, k]
        assert val == pytest.approx(want, abs=1e-12)


@pytest.mark.parametrize("mp", [False, True])
def test_stick_positions_with_d_not_one(mp):
    # a merged free pair oscillates about the mean of its pipes' equilibria ((1 + 2) d / 2); a
    # body stuck on the right wall sits at (n + 1) d
    d = 0.6
    ctx = MPContext() if mp else FloatContext()
    with MPContext().workdps(30):
        row = PipeRow(2, d=d, restitution=0.0, alpha=np.zeros((2, 1)), beta=np.zeros((2, 1)),
                      x0=[0.5, 1.1], v0=[0.3, -0.3])
        eng = Engine(row, ctx, v_stick=1e-6)
        t = ctx.num(0.25)
        eng._stick(1, 1, 2, t, eng.zero, ctx.num(-1), 1, 1)
        X, V = eng._pos_vel(1, t)
        X2, V2 = eng._pos_vel(2, t)
        x1, v1 = 0.6 + (0.5 - 0.6) * math.cos(0.25) + 0.3 * math.sin(0.25), \
            -(0.5 - 0.6) * math.sin(0.25) + 0.3 * math.cos(0.25)
        x2, v2 = 1.2 + (1.1 - 1.2) * math.cos(0.25) - 0.3 * math.sin(0.25), \
            -(1.1 - 1.2) * math.sin(0.25) - 0.3 * math.cos(0.25)
        Xm, Vm = (x1 + x2) / 2, (v1 + v2) / 2
        assert float(X) == pytest.approx(Xm, abs=1e-15) and float(V) == pytest.approx(Vm, abs=1e-15)
        assert (X2, V2) == (X, V)
        s = 1.7   # later: free oscillation about 0.9 = 1.5 d
        Xs = eng._pos_vel(1, ctx.num(0.25 + s))[0]
        assert float(Xs) == pytest.approx(0.9 + (Xm - 0.9) * math.cos(s) + Vm * math.sin(s),
                                          abs=1e-14)
        eng._stick(2, 1, 3, t, eng.zero, ctx.num(-1), 2, None)
        assert eng.coef[1][0] == eng.coef[2][0] == 3 * eng.d
        assert float(eng._pos_vel(2, ctx.num(5))[0]) == pytest.approx(3 * d, abs=1e-15)
    # the reference engine takes d exactly: "0.6" is 3/5, not the float64 0.6
    mc = MPContext()
    with mc.workdps(40):
        row = PipeRow(2, d="0.6", restitution=0, alpha=[["0"], ["0"]], beta=[["0"], ["0"]],
                      x0=["0.5", "1.1"], v0=["0.3", "-0.3"])
        eng = Engine(row, mc, v_stick=1e-6)
        eng._stick(1, 1, 2, mc.num(1) / 4, eng.zero, mc.num(-1), 1, 1)
        with mpmath.workdps(40):
            assert abs(eng.coef[1][0] - mpmath.mpf(9) / 10) < mpmath.mpf(10) ** -38
        eng._stick(2, 1, 3, mc.num(1) / 4, eng.zero, mc.num(-1), 2, None)
        with mpmath.workdps(40):
            assert abs(eng.coef[1][0] - mpmath.mpf(9) / 5) < mpmath.mpf(10) ** -38


@pytest.mark.parametrize("mp", [False, True])
def test_engine_state_closed_form(mp):
    # one elastic pipe x = 1 + 2 sin t hits the wall x = 2 at t* = pi/6 with speed sqrt 3; after
    # it x = 1 + cos(t - t*) - sqrt(3) sin(t - t*) (closed form), before it 1 + 2 sin t
    row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    ctx = MPContext() if mp else FloatContext()
    with MPContext().workdps(40):
        eng = Engine(row, ctx, v_stick=1e-6)
        eng.run(ctx.num(1))
    assert len(eng.log) == 1  # the one impact
    log = eng.log.exported()
    F = [float(f) for f in eng.F] if not mp else [mpmath.mp.make_mpf(f._mpf_) for f in eng.F]
    h = History.from_log(row, 1.0, 30 if mp else None, log, F, wdps=40 if mp else None)
    with mpmath.workdps(40):
        ts = mpmath.pi / 6
        s3 = mpmath.sqrt(3)
        tol = 1e-35 if mp else 1e-14
        t1, t2 = mpmath.mpf(0.3), mpmath.mpf(0.8)
        for t, x_ref, v_ref in ((t1, 1 + 2 * mpmath.sin(t1), 2 * mpmath.cos(t1)),
                                (t2, 1 + mpmath.cos(t2 - ts) - s3 * mpmath.sin(t2 - ts),
                                 -mpmath.sin(t2 - ts) - s3 * mpmath.cos(t2 - ts))):
            xs, vs = h.state(t if mp else float(t))
            assert len(xs) == len(vs) == 1
            assert abs(xs[0] - x_ref) < tol and abs(vs[0] - v_ref) < tol
