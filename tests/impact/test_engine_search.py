"""The certified first-root search of ``symhx.impact.engine`` (``Engine.search``), its graze
helper, touch step and root refinement, one rule at a time and in both arithmetics.

Many cases build a gap (or contact force) whose value and derivatives at the start are exact
binary numbers, so that a rounding bound of the search is met *with equality* (the rule "a
quantity within its rounding bound carries no information" is inclusive), or so that a
denominator of the refinement vanishes exactly.  The expected outcomes come from the rules of the
module docstring and from mpmath (roots of the trigonometric polynomial at 50 digits,
``tests.reference.impact``), never from the engine's own output.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx.impact import PipeRow, SimulationError
from symhx.impact.engine import Engine, FloatContext, MPContext, Outcome
from tests.reference.impact import first_root_on_grid, trig_root, trig_value

EPS = 2.0**-52
TOL = 64   # the engine's documented rounding bound: 64 eps (scale of the evaluated quantity)


def _row(r=0.5, *, d=1.0, Omega=(2.0,), n=1):
    # unforced pipes, forcing frequency 2 present (amplitude 0): gap polynomials of length 5
    return PipeRow(n, omega=1.0, d=d, Omega=Omega, restitution=r, alpha=np.zeros((n, len(Omega))),
                   beta=np.zeros((n, len(Omega))), x0=[d * (j + 1) for j in range(n)],
                   v0=[0.0] * n)


def _eng(r=0.5, v_stick=1e-6, **kw):
    return Engine(_row(r, **kw), FloatContext(), v_stick=v_stick)


# ---------------------------------------------------------------- separated and constant gaps
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


def test_search_margin_exactly_at_the_amplitude_bound_is_a_touch():
    # g = c0 - S cos t with c0 - S = 2**-45 = 64 eps (c0 + S) exactly: the amplitude bound
    # c0 - S is within rounding, so the gap is searched (a touch at 2 pi), not "never closes"
    c0, S = 1 + 2.0**-46, 1 - 2.0**-46
    eng = _eng()
    g = [c0, -S, 0.0, 0.0, 0.0]
    assert c0 - S == TOL * EPS * (c0 + S)
    t, code = eng.search(g, 0.5, 10.0)
    assert code == Outcome.GRAZE and abs(t - 2 * math.pi) < 1e-6


# ---------------------------------------------------------------- at a contact: one-sided start
def test_search_contact_start_by_the_third_derivative():
    # at t = 0: D = V = A = 0 exactly (dyadic coefficients, F = (1, 2)); J = -b0 - 8 b1 decides
    eng = _eng()
    with pytest.raises(SimulationError) as info:
        eng.search([-0.75, 1.0, 0.0, -0.25, 0.0], 0.0, 5.0)
    assert str(info.value) == "degenerate contact at t=0.0: value and three derivatives vanish"
    # J = -0.75 < 0: closing at once
    assert eng.search([-0.75, 1.0, -0.25, -0.25, 0.125], 0.0, 5.0) == (0.0, Outcome.NOW)
    # J = +0.75: opens like J t^3 / 6, closes again at the next root of g
    g = [-0.75, 1.0, 0.25, -0.25, -0.125]
    t, code = eng.search(g, 0.0, 10.0)
    root = trig_root(g, t - 1e-3, t + 1e-3, (1.0, 2.0))
    assert code == Outcome.ROOT and root > 0.5
    # no earlier root: g > 0 on a fine grid of (0, root)
    with mpmath.workdps(30):
        assert all(trig_value(root * k / 400, g, (1.0, 2.0)) > 0 for k in range(1, 400))
    assert abs(t - root) < 1e-14


@pytest.mark.parametrize("mp", [False, True])
def test_search_contact_start_rules(mp):
    ctx = MPContext() if mp else FloatContext()
    with MPContext().workdps(40):
        eng = Engine(_row(), ctx, v_stick=1e-6)
        num = ctx.num
        # g = -1 + cos t + sin t / 2: at contact, opening (V = 1/2), compressed (A = -1); its
        # next root 2 atan(1/2)
        g = [num(x) for x in (-1.0, 1.0, 0.5, 0.0, 0.0)]
        with mpmath.workdps(40):
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


@pytest.mark.parametrize("mp", [False, True])
def test_search_tensile_contact_force_is_a_release_now_even_while_rising(mp):
    # a contact force clearly below zero is tensile: contact "now" (the stuck contact releases
    # at once), whatever its slope -- a rising force used to start the one-sided search of a gap
    # that opens, and the release came only when the force started to fall (issue 28, item 10).
    # lambda = -(1 + cos(2t) / 2) (a pipe on the left wall under 1 + cos(2t)/2 >= 1/2)
    ctx = MPContext() if mp else FloatContext()
    with MPContext().workdps(40):
        eng = Engine(_row(), ctx, v_stick=1e-6)
        num = ctx.num
        lam = [num(x) for x in (-1.0, 0.0, 0.0, -0.5, 0.0)]
        for t0 in (0.158, 0.5, 1.0, 2.0):      # rising (t < pi/2) and falling (after)
            assert eng.search(lam, num(t0), num(t0 + 5), is_gap=False) == (num(t0), Outcome.NOW)
        # a gap overlapping by as much and opening is a contact that opens (one-sided start)
        t, code = eng.search(lam, num(0.5), num(5.5))
        assert code != Outcome.NOW and t > 0.5
        # a contact force rising from within rounding of zero stays stuck (compressive next)
        rising = [num(x) for x in (0.0, 0.0, 0.0, 0.0, 0.5)]      # sin(2t) / 2 at t = 0
        t, code = eng.search(rising, num(0), num(1), is_gap=False)
        assert code != Outcome.NOW and t > 0


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


# ---------------------------------------------------------------- exactly at a rounding bound
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
        assert abs(t - trig_root(g, t - 1e-3, t + 1e-3, (1.0, 2.0))) < 1e-14
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


def test_search_gap_exactly_at_plus_rounding_and_closing_is_contact_now():
    # g = (-1 + T) + cos t - (1/2 + T) sin 2t at t = 0: D = T = 64 eps (|c0| + S) exactly
    # (|c0| + S = 2.5), V = -1 - 2T: within rounding of zero and closing -> in contact now
    T = 5 * 2.0**-47
    eng = _eng()
    g = [-1 + T, 1.0, 0.0, 0.0, -(0.5 + T)]
    D, V, _, _ = eng.derivs(g, 0.0)
    c0, S = eng.bounds(g)[:2]
    assert D == TOL * EPS * (abs(c0) + S) == T and V < -1
    assert eng.search(g, 0.0, 5.0) == (0.0, Outcome.NOW)


def test_search_overlap_exactly_at_minus_rounding_with_zero_slope_opens():
    # g = (5/4 - T/2) - cos t - (1/4 + T/2) cos 2t: D(0) = -T = -64 eps (|c0| + S) exactly,
    # V = 0, A = 2 + 2T > 0: an overlap within rounding at a minimum is a contact that opens
    # (one-sided start), not "overlapping and not opening"; the next touch is at 2 pi
    T = 5 * 2.0**-47
    eng = _eng()
    g = [1.25 - T / 2, -1.0, 0.0, -(0.25 + T / 2), 0.0]
    D, V, A, _ = eng.derivs(g, 0.0)
    c0, S = eng.bounds(g)[:2]
    assert D == -TOL * EPS * (abs(c0) + S) and V == 0 and A > 1
    t, code = eng.search(g, 0.0, 10.0)
    assert code != Outcome.NOW and abs(t - 2 * math.pi) < 1e-6


def test_search_overlap_with_slope_exactly_at_its_rounding_bound_is_contact_now():
    # g = -1/2 + b0 sin t + b1 sin 2t: D = -1/2 (a real overlap), V = b0 + 2 b1 = 2**-44 =
    # 64 eps M1 exactly (M1 = 4): a slope at its rounding bound is not opening -> contact now
    h = 2.0**-46
    eng = _eng()
    g = [-0.5, 0.0, 2 * (1 + h), 0.0, -(1 - h)]
    V = eng.derivs(g, 0.0)[1]
    assert V == TOL * EPS * eng.bounds(g)[2] == 2.0**-44
    assert eng.search(g, 0.0, 5.0) == (0.0, Outcome.NOW)


def test_search_slow_opening_with_curvature_exactly_at_its_bound_is_not_a_chatter_end():
    # F = (1, 2, 4): g = c0 + cos t + a1 cos 2t + b sin 4t with D(0) = 0, V = 4 b = 1/8 (below
    # v_stick = 1) and A = -delta = -64 eps M2 exactly (M2 = 5/2): a curvature at its rounding
    # bound is no compression, so the gap opens and closes again at its first root
    delta = 5 * 2.0**-47
    a1 = -(1 - delta) / 4
    b = 2.0**-5 + 5 * 2.0**-51
    g = [-(0.75 + delta / 4), 1.0, 0.0, a1, 0.0, 0.0, b]
    eng = _eng(Omega=(2.0, 4.0), v_stick=1.0)
    D, V, A, _ = eng.derivs(g, 0.0)
    M2, M3 = eng.bounds(g)[3:5]
    assert D == 0 and 0 < V <= eng.v_stick and A == -TOL * EPS * (M2 + M3 * 0.0)
    t, code = eng.search(g, 0.0, 5.0)
    root = first_root_on_grid(g, (1.0, 2.0, 4.0), 1e-3, 2.0)
    assert code == Outcome.ROOT and abs(t - root) < 1e-13


# F = (1, 2, 3, 4): D = V = A = 0 at t = 0 exactly, J = 21 b3 = +-64 eps M3 exactly
_A0 = 1.0 + 2 * 2.0**-50
_B3 = float.fromhex("0x1.24924924925a0p-49")


@pytest.mark.parametrize("sign", [-1, 1])
def test_search_third_derivative_exactly_at_its_bound_is_degenerate(sign):
    # value, slope and curvature vanish and the third derivative equals its rounding bound:
    # nothing is known about the contact -> the documented SimulationError (not "closing now",
    # not a zero-length opening step)
    eng = _eng(Omega=(2.0, 3.0, 4.0))
    b3 = sign * _B3
    g = [-(_A0 - _A0 / 4), _A0, 0.0, -_A0 / 4, 0.0, 0.0, b3, 0.0, -0.75 * b3]
    D, V, A, J = eng.derivs(g, 0.0)
    M3, M4 = eng.bounds(g)[4:6]
    assert (D, V, A) == (0, 0, 0) and J == sign * TOL * EPS * (M3 + M4 * 0.0)
    with pytest.raises(SimulationError) as info:
        eng.search(g, 0.0, 5.0)
    assert str(info.value) == "degenerate contact at t=0.0: value and three derivatives vanish"


@pytest.mark.parametrize("mp", [False, True])
def test_near_contact_slow_closing_root_not_late(mp):
    # found by the 1050-row sweep (row 1041, omega ~ 0.0164): a gap within rounding of zero
    # (D <= tolD, big amplitudes of the slow mode) closing with |V| ~ 1e-8 under a curvature of
    # -2.9.  Its first root is ~4e-6 ahead; the linear guess D / -V put it 1.9e-3 late, with the
    # pipes overlapping by 5e-6 meanwhile.  Reference: the root of the same trig polynomial by
    # mpmath at 50 digits (bisection-safe findroot from the bracket).
    om = 0.016386317992556732
    g = [1.5, 34.87395522044951, -109.45862710357925, 1.967176842464283, 0.15543004880653571]
    t0 = 403.8348033097121
    row = PipeRow(1, omega=om, restitution=0.3, alpha=[[0.0]], beta=[[0.0]], x0=[30.0],
                  v0=[0.0], d=30.0)
    with mpmath.workdps(50):
        F = [mpmath.mpf(om), mpmath.sqrt(2)]
        t0m = mpmath.mpf(t0)
        assert trig_value(t0m, g, F) > 0 and trig_value(t0m + mpmath.mpf("1e-5"), g, F) < 0
        root = trig_root(g, t0m, t0m + mpmath.mpf("1e-5"), F)
        assert root - t0m > mpmath.mpf("1e-6")
    ctx = MPContext() if mp else FloatContext()
    with MPContext().workdps(50):
        eng = Engine(row, ctx, v_stick=1e-8)
        gg = [ctx.num(x) for x in g]
        te, code = eng.search(gg, ctx.num(t0), ctx.num(403.837))
    assert code == Outcome.ROOT
    # float64: the gap's rounding (~3e-11 here) leaves ~sqrt(2 tolD / |A|) ~ 4e-6 of time
    # uncertainty near this touch; the late answer was 1.9e-3 off
    with mpmath.workdps(50):
        assert abs(mpmath.mpf(te._mpf_ if mp else te) - root) < (1e-7 if not mp else 1e-30)


# ---------------------------------------------------------------- graze helper and touch step
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
    root = trig_root(gd, math.pi - 2e-5, math.pi, (1.0, 2.0))
    assert code == Outcome.ROOT and abs(t - root) < 1e-9 and t < math.pi
    # the same dip within the rounding allowance: a graze at the minimum
    t, code = eng._graze(gd, t0, 0.0, 1e-11)
    assert code == Outcome.GRAZE and abs(t - math.pi) < 1e-12


def test_graze_at_zero_curvature_is_the_touch_itself():
    # g = -3/4 + cos t - cos(2t)/4 = -t**4/8 + ...: D = V = A = 0 at t = 0 (no minimum to
    # look for by Newton on g'): the touch is at the start, and no division by A = 0
    eng = _eng()
    g = [-0.75, 1.0, 0.0, -0.25, 0.0]
    assert eng.derivs(g, 0.0)[:3] == (0, 0, 0)
    assert eng._graze(g, 0.0, 0.0, 1e-14) == (0.0, Outcome.GRAZE)


def test_graze_dip_exactly_at_the_allowance_is_a_graze():
    # g = (1 - 2**-30) - cos t: minimum -2**-30 at 2 pi; with the allowance tolD = 2**-30 the
    # dip is within rounding (inclusive): a graze at the minimum, not a refined crossing
    eng = _eng()
    g = [1 - 2.0**-30, -1.0, 0.0, 0.0, 0.0]
    t, code = eng._graze(g, 2 * math.pi - 1e-3, 0.0, 2.0**-30)
    assert code == Outcome.GRAZE and abs(t - 2 * math.pi) < 1e-12
    assert eng.derivs(g, t)[0] == -(2.0**-30)


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
    # (its cost, a few evaluations, is pinned in tests/perf/test_impact_cost.py)
    eng = Engine(_row(Omega=(3.0,)), FloatContext(), v_stick=1e-6)
    x = eng.refine(g, lo, hi)
    root = trig_root(g, lo, hi, (1.0, 3.0))
    assert abs(x - root) <= 4 * EPS * abs(root)


REFINE_CORNERS = [
    # g(0) = 2**-50 (within rounding) with g'(0) = 0 exactly: no Newton step from a flat start
    ([-1 + 2.0**-50, 1.0, 0.0, 0.0, 0.0], 0.0, 0.1),
    # D, V, A, J = 3/4, -3, 24, -288 at 0: Householder denominator 6V^3 - 6DVA + D^2 J = 0
    ([30.75, -32.0, -100.0, 2.0, 48.5], 0.0, 0.253),
    # D, V, A, J = 1, -1, 2, -5: Householder denominator 13 > 0, Halley's 2V^2 - DA = 0
    ([2.25, -1.0, -3.0, -0.25, 1.0], 0.0, 1.163),
    # D, V, A, J = 1, -1, 2, -8: the Householder step is exactly zero (6V^2 = 3DA), xn = lo
    ([3.0, -2.0, -4.0, 0.0, 1.5], 0.0, 0.952),
]


@pytest.mark.parametrize("g, lo, hi", REFINE_CORNERS)
def test_refine_exact_corners(g, lo, hi):
    F = (1.0, 2.0)
    eng = _eng()
    assert eng.derivs(g, lo)[0] > 0 > eng.derivs(g, hi)[0]
    # g is decreasing on [lo, hi] (a fine grid): one root there
    assert all(eng.derivs(g, lo + (hi - lo) * k / 500)[1] <= 0 for k in range(501))
    x = eng.refine(g, lo, hi)
    root = first_root_on_grid(g, F, lo, hi)
    c0, S = eng.bounds(g)[:2]
    with mpmath.workdps(50):
        slope = abs(mpmath.diff(lambda t: trig_value(t, g, F), root))
    # within the rounding of g (64 eps times its scale) divided by the slope, and a few ulps
    assert abs(x - root) <= TOL * EPS * (abs(c0) + S) / slope + 4 * EPS * abs(root)
    assert lo < x < hi


def test_refine_zero_householder_step_does_not_return_the_bracket_end():
    # the last corner: a zero step at lo must not be taken for convergence (g(lo) = 1)
    g, lo, hi = REFINE_CORNERS[3]
    x = _eng().refine(g, lo, hi)
    assert x > 0.5 and abs(x - first_root_on_grid(g, (1.0, 2.0), lo, hi)) < 1e-14
