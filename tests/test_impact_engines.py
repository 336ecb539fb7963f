"""The two float64 engines (C and pure Python) bit for bit, the C row set-up against
``row_arrays``, and the lean float64 path of ``simulate`` against the fully validated one."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from symhx.impact import SQRT2, PipeRow, simulate
from symhx.impact import fast as fast_mod
from symhx.impact.engine import FloatContext, row_arrays
from symhx.impact.model import MAX_HORIZON

pytestmark = pytest.mark.skipif(not fast_mod.available(), reason="C extension not built")


def _rows():
    # forced elastic, inelastic, plastic (r = 0: sticking, releases), chatter-prone r = 0.5,
    # two forcing frequencies (one of them 0: a constant force), omega and d not 1
    yield PipeRow.random(10, 0.3, seed=1, restitution=0.8), 30.0
    yield PipeRow.random(12, 0.5, seed=4, restitution=0.0), 40.0
    yield PipeRow.random(8, 0.6, seed=5, restitution=0.5), 60.0
    yield PipeRow.random(6, 0.4, seed=7, restitution=1.0, Omega=(0.0, 2.3), omega=1.7,
                         d=0.6), 25.0
    yield PipeRow.random(30, 1.0, seed=3, restitution=0.3, Omega=(SQRT2, 0.37), d=3.0), 15.0


def _event_table(h):
    return np.column_stack([h.times, h.sites, h.kinds, h.u_before, h.u_after, h.aux])


@pytest.mark.parametrize("k", range(5))
def test_c_and_python_float_engines_bit_identical(k):
    row, t_end = list(_rows())[k]
    a = simulate(row, t_end, engine="python")
    b = simulate(row, t_end, engine="c")
    assert len(a) >= 20
    # same IEEE operations in the same order: every number of every event equal, not close
    assert np.array_equal(_event_table(a), _event_table(b))
    ua_t, ua_c = a._log.updates()
    ub_t, ub_c = b._log.updates()
    for j in range(row.n + 2):
        assert ua_t[j] == ub_t[j]
        assert np.array_equal(np.asarray(ua_c[j], dtype=float), ub_c[j])
    ts = np.linspace(0.0, t_end, 37)
    xa, va = a.states(ts)
    xb, vb = b.states(ts)
    assert np.array_equal(xa, xb) and np.array_equal(va, vb)


@pytest.mark.parametrize("k", range(5))
def test_c_row_setup_bit_identical_to_row_arrays(k):
    row, _ = list(_rows())[k]
    F, out = fast_mod._call(row, 1e-9, 0.0, 1e-6, True, None)
    coef0 = np.frombuffer(out[4], dtype=np.float64).reshape(row.n + 2, -1)
    ra = row_arrays(row, FloatContext())
    assert F == ra.F.tolist()
    assert np.array_equal(coef0, ra.coef)


def test_row_setup_independent_closed_form():
    # x_j(0) and x_j'(0) of every pipe from the coefficients equal the row's x0, v0 (eq. 21)
    row = PipeRow.random(7, 0.8, seed=11, restitution=0.8, Omega=(SQRT2, 0.5), omega=1.3)
    _, out = fast_mod._call(row, 1e-9, 0.0, 1e-6, True, None)
    c = np.frombuffer(out[4], dtype=np.float64).reshape(row.n + 2, -1)
    F = np.array([row.omega, *row.omega_float()])
    x = c[:, 0] + c[:, 1::2].sum(axis=1)
    v = (c[:, 2::2] * F).sum(axis=1)
    np.testing.assert_allclose(x[1:-1], row.x0, rtol=0, atol=1e-13)
    np.testing.assert_allclose(v[1:-1], row.v0, rtol=0, atol=1e-13)
    assert x[0] == 0.0 and x[-1] == (row.n + 1) * row.d
    # the forced part: amplitudes alpha / (omega^2 - Omega^2) straight from the row
    den = row.omega**2 - F[1:] ** 2
    np.testing.assert_allclose(c[1:-1, 3::2], row.alpha / den, rtol=1e-15)
    np.testing.assert_allclose(c[1:-1, 4::2], row.beta / den, rtol=1e-15)


def test_fortran_ordered_inputs():
    row = PipeRow.random(9, 0.4, seed=2, restitution=0.8, Omega=(SQRT2, 0.3, 2.2))
    rowF = PipeRow(9, restitution=0.8, Omega=(SQRT2, 0.3, 2.2), alpha=np.asfortranarray(row.alpha),
                   beta=np.asfortranarray(row.beta), x0=row.x0, v0=row.v0)
    assert not rowF.alpha.flags.c_contiguous
    a, b = simulate(row, 20.0), simulate(rowF, 20.0)
    assert len(a) > 10 and np.array_equal(_event_table(a), _event_table(b))


def test_lean_float_path_equals_validated_path():
    row = PipeRow.random(10, 0.3, seed=2, restitution=0.8)
    a = simulate(row, 30.0)                                  # lean path
    b = simulate(row, Fraction(30), v_stick=1e-6, max_events=10**8, engine="c")   # full checks
    assert np.array_equal(_event_table(a), _event_table(b))
    assert a.t_end == b.t_end == 30.0 and type(a.t_end) is float


def test_lean_path_horizon_cap_exact():
    row = PipeRow(1, restitution=1, omega=3.0, alpha=[[0.0]], beta=[[0.0]], x0=[1.0],
                  v0=[0.0])
    t_max = MAX_HORIZON / 3.0          # omega * t_max rounds to 1e5 but is exactly above it
    assert Fraction(t_max) * 3 > MAX_HORIZON
    with pytest.raises(ValueError, match="too long"):
        simulate(row, t_max)
    t_ok = np.nextafter(t_max, 0.0).item()
    assert Fraction(t_ok) * 3 <= MAX_HORIZON
    h = simulate(row, t_ok, max_events=10)   # accepted (no event: the pipe rests)
    assert len(h) == 0
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError):
            simulate(row, bad)
    with pytest.raises(ValueError, match="engine"):
        simulate(row, 1.0, engine="fortran")


def test_float_cos_sin_kernel_against_mpmath():
    # the kernel both float64 engines share (Cody-Waite + fdlibm polynomials, Estrin tails):
    # absolute error below 2**-52 against 40-digit mpmath, on random arguments over the range
    # it serves and on arguments next to multiples of pi/2 (where the reduction cancels most)
    import math

    import mpmath

    from symhx.impact.engine import _cos_sin

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


def test_plastic_simultaneous_impacts_then_releases_hand_solved():
    # x1 = 1 + 2 sin t, x2 = 2, x3 = 3 - 2 sin t (no force, r = 0): both gaps close at t = pi/6
    # with identical polynomials (an exact tie).  Rules: smaller site first; a plastic impact
    # merges; at one instant the free gaps (impacts) go before the stuck ones (releases).  By
    # hand: gap 1 closes at u = -sqrt 3 -> {1, 2} moves at sqrt(3)/2; gap 2 then closes at
    # u = -sqrt 3 - sqrt(3)/2 -> {1, 2, 3} at rest (momentum 0); its contact forces are tensile
    # (pipes 1 and 3 sit one d off their equilibria): both contacts release at once, all at rest.
    from symhx.impact import IMPACT, RELEASE, STICK

    row = PipeRow(3, restitution=0, alpha=np.zeros((3, 1)), beta=np.zeros((3, 1)),
                  x0=[1.0, 2.0, 3.0], v0=[2.0, 0.0, -2.0])
    want = [(1, IMPACT), (1, STICK), (2, IMPACT), (2, STICK), (1, RELEASE), (2, RELEASE)]
    s3 = np.sqrt(3.0)
    for kw in ({"engine": "c"}, {"engine": "python"}, {"dps": 30}):
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


@pytest.mark.parametrize("k, sigma, omega, t_touch, kinds_at_touch", [
    # a touch (graze) found twice at one instant merges the pair, which then releases
    (3945, 0.48176162723346405, 0.03030774030312454, 393.21425751496616,
     ["graze", "graze", "stick", "release"]),
    # ... and a touch found again after that merge and release steps past it (touch_step)
    (2818, 2.2707357379416577, 0.012903439759520111, 1120.5846466477813,
     ["graze", "graze", "stick", "release", "graze"]),
])
def test_repeated_touch_rules_c_equals_python(k, sigma, omega, t_touch, kinds_at_touch):
    # 4-pipe plastic rows found by a search at small omega (a release leaves the pair touching
    # within rounding): the touch rules of the run loop, run by the C engine and by the Python
    # port (two implementations of them), bit for bit
    row = PipeRow.random(4, sigma, seed=k, restitution=0.0, omega=omega)
    a = simulate(row, t_touch + 0.5, engine="c")
    b = simulate(row, t_touch + 0.5, engine="python")
    at = np.nonzero(a.times == t_touch)[0]
    assert [a.kind_names()[i] for i in at] == kinds_at_touch
    assert np.array_equal(_event_table(a), _event_table(b))
    x, _ = a.states(np.linspace(0.0, t_touch + 0.5, 2001))
    assert np.diff(x, axis=1).min() > -1e-9 and x.min() > -1e-9


@pytest.mark.parametrize("mp", [False, True])
def test_engine_state_closed_form(mp):
    # one elastic pipe x = 1 + 2 sin t hits the wall x = 2 at t* = pi/6 with speed sqrt 3; after
    # it x = 1 + cos(t - t*) - sqrt(3) sin(t - t*) (closed form), before it 1 + 2 sin t
    import mpmath

    from symhx.impact.engine import Engine, MPContext
    from symhx.impact.history import History

    row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    with mpmath.workdps(40):
        eng = Engine(row, MPContext() if mp else FloatContext(), v_stick=1e-6)
        eng.run(1.0)
        assert len(eng.log) == 1  # the one impact
        h = History.from_log(row, 1.0, 30 if mp else None, eng.log, eng.F,
                             wdps=40 if mp else None)
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


@pytest.mark.parametrize("mp", [False, True])
def test_near_contact_slow_closing_root_not_late(mp):
    # found by the 1050-row sweep (row 1041, omega ~ 0.0164): a gap within rounding of zero
    # (D <= tolD, big amplitudes of the slow mode) closing with |V| ~ 1e-8 under a curvature of
    # -2.9.  Its first root is ~4e-6 ahead; the linear guess D / -V put it 1.9e-3 late, with the
    # pipes overlapping by 5e-6 meanwhile.  Reference: the root of the same trig polynomial by
    # mpmath at 50 digits (bisection-safe findroot from the bracket).
    import mpmath

    from symhx.impact.engine import Engine, MPContext, Outcome

    om = 0.016386317992556732
    g = [1.5, 34.87395522044951, -109.45862710357925, 1.967176842464283, 0.15543004880653571]
    t0 = 403.8348033097121
    row = PipeRow(1, omega=om, restitution=0.3, alpha=[[0.0]], beta=[[0.0]], x0=[30.0],
                  v0=[0.0], d=30.0)
    with mpmath.workdps(50):
        F = [mpmath.mpf(om), mpmath.sqrt(2)]

        def gm(t):
            return g[0] + sum(g[1 + 2 * m] * mpmath.cos(f * t) + g[2 + 2 * m] * mpmath.sin(f * t)
                              for m, f in enumerate(F))

        t0m = mpmath.mpf(t0)
        assert gm(t0m) > 0 and gm(t0m + mpmath.mpf("1e-5")) < 0
        root = mpmath.findroot(gm, (t0m, t0m + mpmath.mpf("1e-5")), solver="anderson")
        assert root - t0m > mpmath.mpf("1e-6")
        ctx = MPContext() if mp else FloatContext()
        eng = Engine(row, ctx, v_stick=1e-8)
        gg = [ctx.num(x) for x in g]
        te, code = eng.search(gg, ctx.num(t0), ctx.num(403.837))
        assert code == Outcome.ROOT
        # float64: the gap's rounding (~3e-11 here) leaves ~sqrt(2 tolD / |A|) ~ 4e-6 of time
        # uncertainty near this touch; the late answer was 1.9e-3 off
        assert abs(te - root) < (1e-7 if not mp else 1e-30)
