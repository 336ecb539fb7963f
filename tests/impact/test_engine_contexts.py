"""``symhx.impact.engine``: the documented stick speed for any ``omega`` and ``d``, the thread
context's functions offered by :class:`MPContext`, and the export of an mpmath record that has
no event yet (its pieces are the initial coefficients)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from symhx.impact import PipeRow
from symhx.impact.engine import Engine, FloatContext, MPContext, default_v_stick, row_arrays


def _row(omega, d):
    return PipeRow(1, omega=omega, d=d, restitution=1, alpha=[[0.0]], beta=[[0.0]],
                   x0=[d], v0=[0.0])


@pytest.mark.parametrize("omega, d", [(1.0, 1.0), (2.5, 0.4), (0.3, 7.0)])
def test_default_v_stick_is_omega_d_times_ten_to_minus_half_dps_minus_one(omega, d):
    """``omega d 10**(-dps/2 - 1)``: ``1e-6 omega d`` in float64 (``dps=None``), an mpf to 20
    digits for an int ``dps`` (odd ``dps`` too: a half power of ten)."""
    row = _row(omega, d)
    v = default_v_stick(row, None)
    assert isinstance(v, float) and v == pytest.approx(omega * d * 1e-6, rel=1e-15)
    for dps in (10, 20, 31, 2000):
        v = default_v_stick(row, dps)
        assert isinstance(v, mpmath.mpf)
        with mpmath.workdps(40):
            want = mpmath.mpf(omega) * mpmath.mpf(d) * mpmath.mpf(10) ** (-mpmath.mpf(dps) / 2 - 1)
            assert abs(v / want - 1) < mpmath.mpf(10) ** -19, (dps, v, want)


def test_mp_context_functions_are_the_threads_at_its_working_precision():
    """``cos``, ``sin``, ``sqrt``, ``cos_sin`` and ``workprec`` of an :class:`MPContext` compute
    in the thread's own context at the working precision set through it."""
    mc = MPContext()
    with mc.workprec(200):
        assert mc.mp.prec == 200
        x = mc.num(1) / 7
        got = (mc.cos(x), mc.sin(x), mc.sqrt(x), *mc.cos_sin(x))
    with mpmath.workprec(260):
        xr = mpmath.mpf(1) / 7
        want = (mpmath.cos(xr), mpmath.sin(xr), mpmath.sqrt(xr), mpmath.cos(xr), mpmath.sin(xr))
        for g, w in zip(got, want, strict=True):
            assert abs(g - w) <= mpmath.mpf(2) ** -198 * abs(w)


def test_exported_record_without_events_gives_the_initial_pieces():
    """An mpmath run that ends before any event: its exported record has, per pipe, one piece
    from t = 0 with the initial coefficients, as mpmath's global type, bit for bit."""
    row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[0.1])
    mc = MPContext()
    with mc.workdps(30):
        eng = Engine(row, mc, v_stick=1e-6)
        eng.run(mc.num(1) / 100)
        coef0 = [[c for c in r] for r in eng.log._coef0_rows()]
    assert len(eng.log) == 0
    out = eng.log.exported()
    times, coefs = out.updates()
    assert len(times) == len(coefs) == len(coef0) == 3
    for j in range(3):
        assert len(times[j]) == 1 and times[j][0] == 0
        assert isinstance(times[j][0], mpmath.mpf)
        assert len(coefs[j]) == 1
        assert all(isinstance(c, mpmath.mpf) for c in coefs[j][0])
        assert [c._mpf_ for c in coefs[j][0]] == [c._mpf_ for c in coef0[j]]
    assert np.asarray(coefs[1][0], dtype=float)[0] == 1.0   # pipe 1 rests at x = d = 1


def test_mpmath_engine_uses_the_exact_restitution():
    """Restitution "0.3" (a decimal string: exactly 3/10) is applied as 3/10 at the working
    precision, not as the float64 0.29999999999999998890."""
    row = PipeRow(1, restitution="0.3", alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    mc = MPContext()
    with mc.workdps(40):
        eng = Engine(row, mc, v_stick=1e-6)
        eng.run(mc.num(1))
        _, _, _, u0, u1, _ = eng.log.event_arrays(object)
        assert len(u0) == 1
        ratio = u1[0] / u0[0]
        assert abs(ratio + mc.num(3) / 10) < mc.mp.mpf(10) ** -35


@pytest.mark.parametrize("mp", [False, True])
def test_row_arrays_start_every_pipe_at_its_initial_position_and_velocity(mp):
    """With forcing at three frequencies (one of them 0) and both forcing coefficients nonzero,
    each pipe's closed form ``c0 + sum a_m cos(F_m t) + b_m sin(F_m t)`` and its derivative
    give ``x0`` and ``v0`` at ``t = 0`` (the free part absorbs the forced one); the walls rest
    at 0 and ``(n + 1) d``."""
    rng = np.random.default_rng(11)
    n, K = 3, 3
    alpha, beta = rng.normal(size=(n, K)), rng.normal(size=(n, K))
    x0, v0 = [0.55, 1.3, 1.75], [0.4, -0.7, 0.2]
    row = PipeRow(n, omega=1.7, d=0.6, Omega=(0.0, 2.3, 0.37), restitution=0.5, alpha=alpha,
                  beta=beta, x0=x0, v0=v0)
    ctx = MPContext() if mp else FloatContext()
    with MPContext().workdps(30):
        ra = row_arrays(row, ctx)
        # the walls rest at 0 and (n + 1) d
        assert [float(v) for v in ra.coef[0]] == [0.0] * ra.coef.shape[1]
        assert float(ra.coef[n + 1][0]) == pytest.approx((n + 1) * 0.6, rel=1e-15)
        assert not any(float(v) for v in ra.coef[n + 1][1:])
        for j in range(1, n + 1):
            c = [float(v) for v in ra.coef[j]]
            F = [float(f) for f in ra.F]
            pos = c[0] + sum(c[1 + 2 * m] for m in range(len(F)))
            vel = sum(c[2 + 2 * m] * F[m] for m in range(len(F)))
            assert pos == pytest.approx(x0[j - 1], rel=1e-13, abs=1e-13), j
            assert vel == pytest.approx(v0[j - 1], rel=1e-13, abs=1e-13), j
