"""Edge cases of the event engine (``symhx.impact.engine``) that ordinary runs never reach.

Each test builds a gap (or contact force) whose value and derivatives at the start are exact
binary numbers, so that a rounding bound of the certified search is met *with equality* (the
rule "a quantity within its rounding bound carries no information" is inclusive), or so that a
denominator of the root refinement vanishes exactly.  The expected outcomes come from the rules
of the module docstring and from mpmath (roots of the trigonometric polynomial at 50 digits),
never from the engine's own output.
"""

from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import pytest

from symhx.impact import RELEASE, PipeRow, SimulationError
from symhx.impact.engine import Engine, FloatContext, Outcome

EPS = 2.0**-52
TOL = 64   # the engine's documented rounding bound: 64 eps (scale of the evaluated quantity)


def _eng(Omega=(2.0,), v_stick=1e-6):
    # one unforced pipe; the frequencies (1, *Omega) define the gap polynomials' layout
    row = PipeRow(1, omega=1.0, d=1.0, Omega=Omega, restitution=0.5,
                  alpha=np.zeros((1, len(Omega))), beta=np.zeros((1, len(Omega))), x0=[1.0],
                  v0=[0.0])
    return Engine(row, FloatContext(), v_stick=v_stick)


def _g(t, g, F):
    return g[0] + sum(g[1 + 2 * m] * mpmath.cos(f * t) + g[2 + 2 * m] * mpmath.sin(f * t)
                      for m, f in enumerate(F))


def _first_root(g, F, a, b, n=400):
    """First sign change of ``g`` on a fine grid of ``[a, b]``, refined at 50 digits."""
    with mpmath.workdps(50):
        ts = [mpmath.mpf(a) + (mpmath.mpf(b) - a) * k / n for k in range(n + 1)]
        for lo, hi in itertools.pairwise(ts):
            if _g(lo, g, F) > 0 >= _g(hi, g, F):
                return mpmath.findroot(lambda t: _g(t, g, F), (lo, hi), solver="anderson")
    raise AssertionError("no root on the grid")


# ---------------------------------------------------------------- search at an exact bound
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
    root = _first_root(g, (1.0, 2.0, 4.0), 1e-3, 2.0)
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
    with pytest.raises(SimulationError, match=r"^degenerate contact at t=0\.0: value and three "
                                              r"derivatives vanish$"):
        eng.search(g, 0.0, 5.0)


def test_search_margin_exactly_at_the_amplitude_bound_is_a_touch():
    # g = c0 - S cos t with c0 - S = 2**-45 = 64 eps (c0 + S) exactly: the amplitude bound
    # c0 - S is within rounding, so the gap is searched (a touch at 2 pi), not "never closes"
    c0, S = 1 + 2.0**-46, 1 - 2.0**-46
    eng = _eng()
    g = [c0, -S, 0.0, 0.0, 0.0]
    assert c0 - S == TOL * EPS * (c0 + S)
    t, code = eng.search(g, 0.5, 10.0)
    assert code == Outcome.GRAZE and abs(t - 2 * math.pi) < 1e-6


# ---------------------------------------------------------------- graze helper
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


# ---------------------------------------------------------------- refinement, exact corners
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
    root = _first_root(g, F, lo, hi)
    c0, S = eng.bounds(g)[:2]
    with mpmath.workdps(50):
        slope = abs(mpmath.diff(lambda t: _g(t, g, F), root))
    # within the rounding of g (64 eps times its scale) divided by the slope, and a few ulps
    assert abs(x - root) <= TOL * EPS * (abs(c0) + S) / slope + 4 * EPS * abs(root)
    assert lo < x < hi


def test_refine_zero_householder_step_does_not_return_the_bracket_end():
    # the last corner: a zero step at lo must not be taken for convergence (g(lo) = 1)
    g, lo, hi = REFINE_CORNERS[3]
    x = _eng().refine(g, lo, hi)
    assert x > 0.5 and abs(x - _first_root(g, (1.0, 2.0), lo, hi)) < 1e-14


# ---------------------------------------------------------------- contact force search in run
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
