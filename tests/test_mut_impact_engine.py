"""The rules of the event engine (``symhx.impact.engine``) one at a time, in both arithmetics.

Each rule of the module docstring is checked where its outcome is decided: the certified search
at a contact (value, slope, curvature, third derivative), the restitution / sticking rule of an
impact, the accumulation time of a chatter, the contact force of a stuck cluster (Newton's law
for the cluster, written out here from the row's forces), the cascade backstop, the root
refinement (against mpmath at 50 digits) and the record types.  The float64 engines are also run
on rows chosen to exercise rare paths (K = 3 forcing frequencies with a constant one, d != 1,
plastic rows, a 1e-300 chatter threshold) and compared bit for bit with the C port.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx.impact import GRAZE, IMPACT, RELEASE, STICK, PipeRow, SimulationError, simulate
from symhx.impact import fast as fast_mod
from symhx.impact.engine import (
    Engine,
    EventLog,
    FloatContext,
    MPContext,
    Outcome,
    cascade_bound,
    default_v_stick,
    row_arrays,
    work_dps,
)

EPS = 2.0**-52
TOL = 64   # the engine's documented rounding bound: 64 eps (scale of the evaluated quantity)


def _row(r=0.5, *, d=1.0, Omega=(2.0,), n=1):
    # unforced pipes, forcing frequency 2 present (amplitude 0): gap polynomials of length 5
    return PipeRow(n, omega=1.0, d=d, Omega=Omega, restitution=r, alpha=np.zeros((n, len(Omega))),
                   beta=np.zeros((n, len(Omega))), x0=[d * (j + 1) for j in range(n)],
                   v0=[0.0] * n)


def _eng(r=0.5, v_stick=1e-6, **kw):
    return Engine(_row(r, **kw), FloatContext(), v_stick=v_stick)


def _g(t, g, F=(1.0, 2.0)):
    return g[0] + sum(g[1 + 2 * m] * mpmath.cos(f * t) + g[2 + 2 * m] * mpmath.sin(f * t)
                      for m, f in enumerate(F))


def _root(g, a, b, F=(1.0, 2.0)):
    with mpmath.workdps(50):
        return mpmath.findroot(lambda t: _g(t, g, F), (mpmath.mpf(a), mpmath.mpf(b)),
                               solver="anderson")


# ---------------------------------------------------------------- small documented formulas
def test_work_dps_cascade_bound_and_v_stick_formulas():
    for dps in (1, 15, 30, 1000):
        assert work_dps(dps) == 2 * dps + 10
    for n in (1, 2, 7, 500):
        assert cascade_bound(n) == 20 * (n + 1) + 100
    with pytest.raises(TypeError, match="row must be a PipeRow, got int"):
        default_v_stick(3, 10)


def test_cos_sin_reduction_range():
    # Cody-Waite reduction for |x| < 823549.6 (~2**19 pi/2), libm beyond (both engines)
    from symhx.impact.engine import _cos_sin

    for x in (823549.6, -823549.6, 823549.60037, 823549.60333, 823550.5, -823549.60037, 1e7):
        assert _cos_sin(x) == (math.cos(x), math.sin(x))
    with mpmath.workdps(40):
        for x in (823549.5, 1e5 + 0.3, -2.5, 0.7853981633974483):
            c, s = _cos_sin(x)
            assert abs(c - mpmath.cos(x)) <= EPS and abs(s - mpmath.sin(x)) <= EPS


def test_bounds_are_the_documented_sums():
    # M_k = sum_m c_m F_m**k with c_m = |(a_m, b_m)|; zero frequencies fold into c0
    eng = Engine(_row(Omega=(2.0, 0.0, 3.0)), FloatContext(), v_stick=1e-6)
    g = [0.5, 0.6, 0.8, 0.3, 0.4, 0.25, 0.0, 0.0, -2.0]
    c0, S, M1, M2, M3, M4 = eng.bounds(g)
    cs = [(1.0, 1.0), (2.0, 0.5), (3.0, 2.0)]
    assert c0 == 0.5 + 0.25
    for k, Mk in enumerate((S, M1, M2, M3, M4)):
        assert Mk == pytest.approx(sum(c * f**k for f, c in cs), rel=1e-15)


# ---------------------------------------------------------------- row set-up and records
@pytest.mark.parametrize("mp", [False, True])
def test_row_arrays_layout_with_three_forcing_frequencies(mp):
    rng = np.random.default_rng(5)
    n, K = 4, 3
    alpha, beta = rng.normal(size=(n, K)), rng.normal(size=(n, K))
    row = PipeRow(n, omega=1.7, d=0.6, Omega=(0.0, 2.3, 0.37), restitution=0.5, alpha=alpha,
                  beta=beta, x0=[0.6, 1.2, 1.8, 2.4], v0=[0.1, -0.2, 0.3, 0.0])
    with mpmath.workdps(30):
        ra = row_arrays(row, MPContext() if mp else FloatContext())
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


@pytest.mark.skipif(not fast_mod.available(), reason="C extension not built")
def test_c_log_length_and_chunk_option():
    row = PipeRow.random(5, 2.0, seed=1, restitution=0.8)
    h = simulate(row, 20.0, engine="c")
    assert len(h._log) == len(h.times) > 10
    assert Engine(row, FloatContext(), v_stick=1e-6, chunk=0.5).chunk == 0.5
    eng = Engine(row, FloatContext(), v_stick=1e-6)
    assert eng.chunk == 2 / row.omega and eng.row is row


# ---------------------------------------------------------------- the certified search
def test_search_constant_and_separated_gaps():
    eng = _eng()
    z = [0.0] * 5
    assert eng.search(z, 0.5, 1.0) == (0.5, Outcome.NOW)            # constant zero: in contact
    assert eng.search([-1e-10, *z[1:]], 0.5, 1.0) == (0.5, Outcome.NOW)
    assert eng.search([1e-10, *z[1:]], 0.5, 1.0) == (math.inf, Outcome.NONE)
    # amplitude bound c0 - sum c_m = 3 - 1.25 - 0.5 > 0: never closes, not searched
    assert eng.search([3.0, 0.75, 1.0, 0.3, 0.4], 0.0, 1.0) == (math.inf, Outcome.NONE)
    # a zero frequency is a constant: folded into c0 (F = (1, 0))
    e0 = Engine(_row(Omega=(0.0,)), FloatContext(), v_stick=1e-6)
    assert e0.search([1.0, 0.0, 0.0, -1.0, 0.0], 0.25, 1.0) == (0.25, Outcome.NOW)


def test_search_margin_below_rounding_is_a_touch():
    # g = 1e6 - (1e6 - 1e-9) cos t: its minimum 1e-9 (at 0, 2 pi, ...) is below the rounding of a
    # gap of size 2e6 (64 eps 2e6 ~ 2.8e-8): not "never closes" -- a touch at 2 pi
    eng = _eng()
    g = [1e6, -(1e6 - 1e-9), 0.0, 0.0, 0.0]
    t, code = eng.search(g, 0.0, 10.0)
    assert code == Outcome.GRAZE
    assert abs(t - 2 * math.pi) < 1e-6


def test_search_contact_start_by_the_third_derivative():
    # at t = 0: D = V = A = 0 exactly (dyadic coefficients, F = (1, 2)); J = -b0 - 8 b1 decides
    eng = _eng()
    with pytest.raises(SimulationError, match=r"degenerate contact at t=0.0: value and three "
                                              r"derivatives vanish"):
        eng.search([-0.75, 1.0, 0.0, -0.25, 0.0], 0.0, 5.0)
    # J = -0.75 < 0: closing at once
    assert eng.search([-0.75, 1.0, -0.25, -0.25, 0.125], 0.0, 5.0) == (0.0, Outcome.NOW)
    # J = +0.75: opens like J t^3 / 6, closes again at the next root of g
    g = [-0.75, 1.0, 0.25, -0.25, -0.125]
    t, code = eng.search(g, 0.0, 10.0)
    root = _root(g, t - 1e-3, t + 1e-3)
    assert code == Outcome.ROOT and root > 0.5
    # no earlier root: g > 0 on a fine grid of (0, root)
    with mpmath.workdps(30):
        assert all(_g(root * k / 400, g) > 0 for k in range(1, 400))
    assert abs(t - root) < 1e-14


@pytest.mark.parametrize("mp", [False, True])
def test_search_contact_start_rules(mp):
    with mpmath.workdps(40):
        ctx = MPContext() if mp else FloatContext()
        eng = Engine(_row(), ctx, v_stick=1e-6)
        num = ctx.num
        # g = -1 + cos t + sin t / 2: at contact, opening (V = 1/2), compressed (A = -1); its
        # next root 2 atan(1/2)
        g = [num(x) for x in (-1.0, 1.0, 0.5, 0.0, 0.0)]
        t_next = 2 * mpmath.atan(mpmath.mpf(1) / 2)
        tol = 1e-30 if mp else 1e-14
        for restart in (False, True):
            t, code = eng.search(g, num(0), num(5), graze_restart=restart)
            assert code == Outcome.ROOT and abs(t - t_next) < tol
        # ... but slower than v_stick under compression: in contact now (a chatter's end);
        # the threshold is inclusive, and only for gaps (not for contact forces)
        eng.v_stick = num(0.5)
        assert eng.search(g, num(0), num(5)) == (0, Outcome.NOW)
        assert eng.search(g, num(0), num(5), is_gap=False)[1] == Outcome.ROOT
        eng.v_stick = num(0.5) * (1 - ctx.eps)
        assert eng.search(g, num(0), num(5))[1] == Outcome.ROOT
        # closing at contact (V = -1/2): now -- except right after a graze, where the slope is
        # taken as zero and the curvature (A = +1) decides
        eng.v_stick = num(1e-6)
        gs = [num(x) for x in (1.0, -1.0, -0.5, 0.0, 0.0)]
        assert eng.search(gs, num(0), num(5)) == (0, Outcome.NOW)
        assert eng.search(gs, num(0), num(5), graze_restart=True)[1] != Outcome.NOW


def test_search_small_print():
    eng = _eng()
    g = [-0.75, 1.0, 0.25, -0.25, -0.125]          # at contact, opening by its third derivative
    # an empty interval is certified at once (nothing is evaluated)
    assert eng.search([-1.0, 0.5, 0.0, 0.0, 0.0], 1.0, 1.0) == (1.0, Outcome.CONT)
    # a third derivative below its rounding bound is no information: degenerate
    tiny = 1e-20
    with pytest.raises(SimulationError, match="degenerate contact"):
        eng.search([-0.75, 1.0, tiny / 3, -0.25, -tiny / 6], 0.0, 5.0)
    # slower than v_stick but not compressed (A = 0 exactly): not a contact, searched on
    eng.v_stick = 0.5
    t, code = eng.search([-0.75, 1.0, 0.5, -0.25, 0.0], 0.0, 5.0)
    assert code != Outcome.NOW and t > 0
    assert eng.search(g, 0.0, 10.0)[1] == Outcome.ROOT


def test_search_slope_exactly_at_its_rounding_bound():
    # at t = 0 over F = (1, 2) with only sine parts: D = c0 = 0, A = 0, V = b0 + 2 b1 and
    # M1 = |b0| + 2 |b1| = 4, so V = +-2**-44 is exactly the slope's rounding bound
    # tolV = 64 eps M1: not a slope at all -- the third derivative J = -b0 - 8 b1 ~ 6 decides:
    # the gap opens (its dip below zero, ~1e-20, is below rounding) and closes at its next root
    eng = _eng()
    h = 2.0**-46
    for sign, b0, b1 in ((1, 2 * (1 + h), -(1 - h)), (-1, 2 * (1 - h), -(1 + h))):
        g = [0.0, 0.0, b0, 0.0, b1]
        D, V, A, J = eng.derivs(g, 0.0)
        assert (D, A) == (0, 0) and V == sign * TOL * EPS * eng.bounds(g)[2] == sign * 2.0**-44
        assert J > 5
        t, code = eng.search(g, 0.0, 10.0)
        assert code == Outcome.ROOT and t > 1
        assert abs(t - _root(g, t - 1e-3, t + 1e-3)) < 1e-14
    # a slope one ulp beyond the bound is a slope: closing at once
    g = [0.0, 0.0, 2 * (1 - h), 0.0, np.nextafter(-(1 + h), -2.0)]
    assert eng.derivs(g, 0.0)[1] < -TOL * EPS * eng.bounds(g)[2]
    assert eng.search(g, 0.0, 10.0) == (0.0, Outcome.NOW)


def test_search_curvature_exactly_at_its_rounding_bound():
    # F = (1, 2, 3, 4): A = -4 a1 (a cosine at frequency 2 only), V = 3 b3 + 4 b4 = 0 with
    # b4 = -3 b3 / 4, J = -(27 b3 + 64 b4) = 21 b3; a1 is set so that A = +-tolA exactly
    # (tolA = 64 eps M2 depends on a1 only through 4 |a1|: a fixed point).  A curvature at its
    # rounding bound is no curvature: J decides
    eng = Engine(_row(Omega=(2.0, 3.0, 4.0)), FloatContext(), v_stick=1e-6)
    for sign, b3 in ((-1, 0.25), (1, -0.25)):
        a1 = 0.0
        for _ in range(5):
            g = [-a1, 0.0, 0.0, a1, 0.0, 0.0, b3, 0.0, -0.75 * b3]
            a1 = -sign * TOL * EPS * eng.bounds(g)[3] / 4
        g = [-a1, 0.0, 0.0, a1, 0.0, 0.0, b3, 0.0, -0.75 * b3]
        D, V, A, J = eng.derivs(g, 0.0)
        assert (D, V) == (0, 0) and A == sign * TOL * EPS * eng.bounds(g)[3]
        t, code = eng.search(g, 0.0, 10.0)
        if sign < 0:    # A = -tolA, J = 21/4 > 0: opening
            assert J > 0 and code != Outcome.NOW and t > 0.1
        else:           # A = +tolA, J < 0: closing now
            assert J < 0 and (t, code) == (0.0, Outcome.NOW)


# ---------------------------------------------------------------- graze and touch step
def test_graze_helper():
    eng = _eng()
    # g = -1 + cos t at t = 0: D = V = 0, A = -1 < 0: no minimum to look for -- the touch is there
    g = [-1.0, 1.0, 0.0, 0.0, 0.0]
    assert eng._graze(g, 0.0, 0.0, 1e-14) == (0.0, Outcome.GRAZE)
    # ... also when the gap there is below its rounding allowance (nothing to refine between
    # the start and itself)
    assert eng._graze([-1.0 - 2e-14, 1.0, 0.0, 0.0, 0.0], 0.0, 0.0, 1e-14) == (0.0, Outcome.GRAZE)
    # g = 1e-12 (1 + ...) dipping 3e-12 below zero near t = pi: a real (slow) crossing, refined
    # between the start and the minimum
    gd = [-2e-12 + 1.0, 1.0, 0.0, 0.0, 0.0]          # min at pi: -2e-12 + 1 - 1 = -2e-12
    t0 = math.pi - 1e-3
    t, code = eng._graze(gd, t0, 0.0, 1e-12)
    root = _root(gd, math.pi - 2e-5, math.pi)
    assert code == Outcome.ROOT and abs(t - root) < 1e-9 and t < math.pi
    # the same dip within the rounding allowance: a graze at the minimum
    t, code = eng._graze(gd, t0, 0.0, 1e-11)
    assert code == Outcome.GRAZE and abs(t - math.pi) < 1e-12


def test_touch_step_formula():
    eng = _eng()
    g = [0.5, 0.3, 0.4, 0.0, 0.0]           # c0 = 0.5, S = 0.5, M1 = 0.5, M3 = 0.5
    for t in (0.0, 10.0):
        tolD = TOL * EPS * (0.5 + 0.5 + 0.5 * t)
        assert eng.touch_step(g, t) == pytest.approx((6 * tolD / 0.5) ** (1 / 3), rel=1e-14)
    assert eng.touch_step([0.5, 0.0, 0.0, 0.0, 0.0], 1.0) == eng.chunk   # M3 = 0


# ---------------------------------------------------------------- refinement
REFINE_CASES = [   # (g over F = (1, 3), bracket): each takes another branch of the iteration
    ([-0.731, 0.695, 0.528, -0.49, -0.009], 1.4500000000000002, 1.5),     # order 3
    ([-0.265, -0.112, 0.124, -0.216, 0.339], 1.0, 1.05),                  # step leaves bracket
    ([-0.677, -0.771, 0.067, -0.731, 0.94], 0.8, 0.8500000000000001),     # g' >= 0 at the start
    ([0.257, 0.633, 0.369, 0.006, 0.201], 1.6801446076207562, 3.2794254642113794),   # Newton
    ([0.498, 0.797, 0.335, 0.077, 0.027], 0.7210453594912931, 3.2576236235843767),   # Halley
]


@pytest.mark.parametrize("g, lo, hi", REFINE_CASES)
def test_refine_against_mpmath(g, lo, hi):
    eng = Engine(_row(Omega=(3.0,)), FloatContext(), v_stick=1e-6)
    calls = []
    derivs = eng.derivs
    eng.derivs = lambda gg, t: calls.append(t) or derivs(gg, t)   # type: ignore[method-assign]
    x = eng.refine(g, lo, hi)
    root = _root(g, lo, hi, F=(1.0, 3.0))
    assert abs(x - root) <= 4 * EPS * abs(root)
    assert len(calls) <= 5      # fourth-order iteration from these starts: at most 5 steps


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


# ---------------------------------------------------------------- bodies and forces
def _force(row, j, t):
    # F_j(t) = sum_m alpha_jm cos(Omega_m t) + beta_jm sin(Omega_m t) (eq. 20)
    return sum(row.alpha[j - 1, m] * math.cos(w * t) + row.beta[j - 1, m] * math.sin(w * t)
               for m, w in enumerate(row.Omega))


@pytest.mark.parametrize("stuck, k", [
    ((0, 1, 2), 1),      # pipes 1..3 on the left wall
    ((2, 3, 4), 3),      # pipes 2..4 on the right wall (n = 4)
    ((2, 4, 4), 2),      # only pipe 4 on the right wall
    ((1, 2), 2),         # free cluster of pipes 1..3
])
def test_contact_force_is_newtons_law_of_the_cluster(stuck, k):
    # cluster at common position X: pipe j feels f_j = -omega^2 (X - j d) + F_j (eq. 19); a wall
    # cluster does not move (X = 0 or (n + 1) d), a free one accelerates as the mean of f_j.  The
    # contact force at gap k is what the part left of it must receive: sum_{j<=k} (a - f_j)
    # (a = 0 on a wall; X drops out for a free cluster)
    n, om, d = 4, 1.3, 0.7
    rng = np.random.default_rng(9)
    row = PipeRow(n, omega=om, d=d, Omega=(0.0, 2.1, 0.45), restitution=0.0,
                  alpha=rng.normal(size=(n, 3)), beta=rng.normal(size=(n, 3)),
                  x0=[0.7, 1.4, 2.1, 2.8], v0=[0.0] * n)
    eng = Engine(row, FloatContext(), v_stick=1e-6)
    for s in set(stuck):
        eng.stuck[s] = True
    lo, hi = eng.body(k)
    lam = eng.contact_force(k)
    for t in (0.0, 0.8, 3.1):
        val = eng.derivs(lam, t)[0]
        if lo == 0:
            X = 0.0
        elif hi == n + 1:
            X = (n + 1) * d
        else:
            X = 0.123   # any: it cancels
        f = {j: -om**2 * (X - j * d) + _force(row, j, t) for j in range(1, n + 1)}
        if lo == 0:
            want = -sum(f[j] for j in range(k + 1, hi + 1))
        elif hi == n + 1:
            want = sum(f[j] for j in range(lo, k + 1))
        else:
            a = sum(f[j] for j in range(lo, hi + 1)) / (hi - lo + 1)
            want = sum(f[j] - a for j in range(lo, k + 1))
        assert val == pytest.approx(want, abs=1e-12)


@pytest.mark.parametrize("mp", [False, True])
def test_stick_positions_with_d_not_one(mp):
    # a merged free pair oscillates about the mean of its pipes' equilibria ((1 + 2) d / 2); a
    # body stuck on the right wall sits at (n + 1) d
    d = 0.6
    with mpmath.workdps(30):
        ctx = MPContext() if mp else FloatContext()
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
    with mpmath.workdps(40):
        row = PipeRow(2, d="0.6", restitution=0, alpha=[["0"], ["0"]], beta=[["0"], ["0"]],
                      x0=["0.5", "1.1"], v0=["0.3", "-0.3"])
        eng = Engine(row, MPContext(), v_stick=1e-6)
        eng._stick(1, 1, 2, mpmath.mpf(1) / 4, eng.zero, mpmath.mpf(-1), 1, 1)
        assert abs(eng.coef[1][0] - mpmath.mpf(9) / 10) < mpmath.mpf(10) ** -38
        eng._stick(2, 1, 3, mpmath.mpf(1) / 4, eng.zero, mpmath.mpf(-1), 2, None)
        assert abs(eng.coef[1][0] - mpmath.mpf(9) / 5) < mpmath.mpf(10) ** -38


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


@pytest.mark.parametrize("dps", [None, 20])
def test_max_events_and_horizon_are_inclusive(dps):
    row = PipeRow.random(4, 2.0, seed=3, restitution=0.8)
    kw = {"dps": dps} if dps else {"engine": "python"}
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


# ---------------------------------------------------------------- C port vs Python, rare paths
def _rare_rows():
    yield PipeRow.random(6, 2.0, seed=0, restitution=0.0, Omega=(0.0, 2.3, 0.37), omega=1.7,
                         d=0.6), 25.0, {}
    yield PipeRow.random(6, 0.5, seed=2, restitution=0.5, Omega=(0.0, 2.3, 0.37), omega=1.7,
                         d=0.6), 25.0, {}
    yield PipeRow.random(6, 2.0, seed=1, restitution=0.0, Omega=(0.0, 2.3, 0.37), omega=1.7,
                         d=0.6), 25.0, {}
    yield PipeRow.random(5, 10.0, seed=0, restitution=0.3), 30.0, {}
    yield PipeRow.random(7, 1.0, seed=1, restitution=0.0, omega=0.5, d=6.0,
                         Omega=(1.3, 0.9)), 100.0, {}
    yield _chatter_row(0.4, 3.0, d=0.6), 6.0, {}
    yield PipeRow(2, restitution=0.1, alpha=np.zeros((2, 1)), beta=np.zeros((2, 1)),
                  x0=[1.0, 2.0], v0=[-2.0, -4.0]), 0.6, {"v_stick": 1e-300}


@pytest.mark.skipif(not fast_mod.available(), reason="C extension not built")
@pytest.mark.parametrize("k", range(7))
def test_rare_paths_c_equals_python(k):
    row, t_end, kw = list(_rare_rows())[k]
    a = simulate(row, t_end, engine="c", **kw)
    b = simulate(row, t_end, engine="python", **kw)
    assert len(a) > 3

    def table(h):
        return np.column_stack([h.times, h.sites, h.kinds, h.u_before, h.u_after, h.aux])

    assert np.array_equal(table(a), table(b))
    ua_t, ua_c = a._log.updates()
    ub_t, ub_c = b._log.updates()
    for j in range(row.n + 2):
        assert ua_t[j] == ub_t[j]
        assert np.array_equal(np.asarray(ua_c[j], dtype=float), np.asarray(ub_c[j], dtype=float))


def test_kinds_are_recorded_with_their_names():
    assert [int(k) for k in (IMPACT, GRAZE, STICK, RELEASE)] == [0, 1, 2, 3]
