"""The mechanics of whole runs against closed forms: single pipes in free flight, grazing,
exactly and nearly simultaneous impacts, chatter to sticking and release when the force
reverses, energy conservation over a thousand elastic impacts, and a brute-force scan for missed
contacts (mostly the mpmath reference engine, the float64 engine beside it)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx.impact import GRAZE, IMPACT, RELEASE, STICK, PipeRow, simulate

SQ2 = (math.sqrt(2),)


def one_pipe(x0, v0, *, r=1.0, d=1.0, Omega=SQ2, alpha=0.0):
    return PipeRow(1, d=d, restitution=r, Omega=Omega, alpha=[[alpha]], beta=[[0.0]],
                   x0=[x0], v0=[v0])


def free_row(x0, v0, r=1.0):
    n = len(x0)
    return PipeRow(n, restitution=r, alpha=np.zeros((n, 1)), beta=np.zeros((n, 1)), x0=x0, v0=v0)


# ------------------------------------------------------------------ closed forms
@pytest.mark.parametrize("dps", [20, 40])
def test_single_elastic_pipe_closed_form(dps):
    # x = 1 + 2 sin t hits the right wall x = 2 at pi/6 with speed sqrt(3); after an elastic
    # bounce x - 1 = 2 cos(s + pi/3) reaches the left wall after pi/3, and so on by symmetry:
    # impacts at pi/6 + k pi/3, against pi computed independently at higher precision
    h = simulate(one_pipe(1.0, 2.0), 10.0, dps=dps)
    with mpmath.workdps(dps + 20):
        pi = mpmath.pi
        expected = [pi / 6 + k * pi / 3 for k in range(12) if pi / 6 + k * pi / 3 <= 10]
        assert len(h.times) == len(expected)
        err = max(abs(a - b) for a, b in zip(h.times, expected, strict=False))
    assert err < mpmath.mpf(10) ** (-dps + 2)
    assert all(h.kinds == IMPACT)
    # elastic: relative speed is sqrt(3) at every impact, reversed
    with mpmath.workdps(dps):
        assert all(abs(abs(u) - mpmath.sqrt(3)) < mpmath.mpf(10) ** (-dps + 2) for u in h.u_before)


# ------------------------------------------------------------------ grazing
@pytest.mark.parametrize("dps", [None, 30])
def test_exact_graze_reported_once(dps):
    # x = 1 + sin t touches x = 2 at pi/2 and x = 0 at 3 pi/2 with zero velocity.
    h = simulate(one_pipe(1.0, 1.0), 20.0, dps=dps)
    assert list(h.kinds) == [GRAZE] * 6
    assert list(h.sites) == [1, 0, 1, 0, 1, 0]
    for k, t in enumerate(h.times):
        assert abs(float(t) - (2 * k + 1) * math.pi / 2) < 1e-6   # graze times are ill-conditioned
    # nothing changed: the motion is still 1 + sin t
    x, _v = h.state(19.0)
    assert abs(float(x[0]) - (1 + math.sin(19.0))) < 1e-9


@pytest.mark.parametrize("dps", [None, 30])
def test_near_graze_impact_and_near_miss(dps):
    # walls at 0 and 2d, x = d + sin t: dips 2**-40 past the wall when d = 1 - 2**-40
    d = 1 - 2.0**-40
    h = simulate(one_pipe(d, 1.0, d=d), 3.0, dps=dps)
    assert list(h.kinds) == [IMPACT] and list(h.sites) == [1]
    with mpmath.workdps(60):
        dd = mpmath.mpf(d)
        t_star = mpmath.asin(dd)            # d + sin t = 2d
        u_star = -mpmath.cos(t_star)         # gap 2d - x has derivative -cos t
    tol = 1e-9 if dps is None else 1e-25
    assert abs(h.times[0] - t_star) < tol
    assert abs(h.u_before[0] - u_star) < (1e-7 if dps is None else 1e-25)
    # the mirror case passes 2**-40 short of the wall: no event at all
    d2 = 1 + 2.0**-40
    h2 = simulate(one_pipe(d2, 1.0, d=d2), 3.0, dps=dps)
    assert len(h2) == 0


# ------------------------------------------------------------------ simultaneous impacts
def test_exactly_simultaneous_adjacent_impacts_rule():
    # pipes 1 and 3 hit pipe 2 at the same instant t = pi/6 (identical gap polynomials):
    # rule: increasing site order, pairwise, re-fire while a contact approaches.
    row = free_row([1.0, 2.0, 3.0], [2.0, 0.0, -2.0])
    h = simulate(row, 1.0, dps=30)
    assert list(h.sites) == [1, 2, 1]
    assert all(h.kinds == IMPACT)
    with mpmath.workdps(40):
        assert all(abs(t - mpmath.pi / 6) < mpmath.mpf(10) ** -30 for t in h.times)
        _x, v = h.state(mpmath.pi / 6)
        s3 = mpmath.sqrt(3)
        assert abs(v[0] + s3) < 1e-28 and abs(v[1]) < 1e-28 and abs(v[2] - s3) < 1e-28
    assert abs(h.energy(0.9) - h.energy(0)) < 1e-28


@pytest.mark.parametrize("b", [np.nextafter(4.0, 5.0), 4.0, np.nextafter(4.0, 3.0)])
def test_near_simultaneous_adjacent_impacts_ordered(b):
    # pipe 1 (x1 = 1 - 2 sin t) hits the left wall at pi/6; pipe 2 (x2 = 2 - b sin t) reaches
    # pipe 1 at asin(1/(b-2)): one ulp of b from 4 puts it ~3e-16 before or after (or, for b = 4,
    # exactly at) pi/6.  Independent check: both roots in closed form at 80 digits.
    b = float(b)
    with mpmath.workdps(80):
        root0 = mpmath.pi / 6
        root1 = mpmath.asin(1 / (mpmath.mpf(b) - 2))
    assert abs(root1 - root0) < 1e-15
    row = free_row([1.0, 2.0], [-2.0, -b])
    h = simulate(row, 0.6, dps=30)
    first = 0 if root0 <= root1 else 1        # exact tie: smaller site first (stated rule)
    assert h.sites[0] == first
    assert abs(h.times[0] - min(root0, root1)) < 1e-28
    assert len(h) >= 2 and h.times[1] - h.times[0] < 1e-12
    # energy is conserved through the close pair of impacts
    assert abs(h.energy(0.59) - h.energy(0)) < 1e-28
    # no contact is lost: all gaps positive just after the pair
    assert min(h.gaps(h.times[1] + mpmath.mpf(10) ** -6)) > 0


# ------------------------------------------------------------------ chatter and sticking
def _chatter_row():
    # constant force (Omega = 0) pushing pipe 1 into the left wall: x = -2 + 2.5 cos t until the
    # first impact at acos(4/5) with speed 3/2; after that each flight lasts 2 atan(v_k / 2) with
    # v_k = 1.5 r^k: accumulation time t_acc = acos(4/5) + sum_k 2 atan(1.5 r^k / 2).
    return one_pipe(0.5, 0.0, r=0.5, Omega=(0.0,), alpha=-3.0)


def test_chatter_accumulation_time_closed_form():
    dps = 30
    h = simulate(_chatter_row(), 6.0, dps=dps)
    imp = [t for t, k in zip(h.times, h.kinds, strict=False) if k == IMPACT]
    with mpmath.workdps(80):
        t1 = mpmath.acos(mpmath.mpf(4) / 5)
        v = mpmath.mpf(3) / 2
        r = mpmath.mpf(1) / 2
        partial = [t1 + mpmath.fsum(2 * mpmath.atan(v * r**k / 2) for k in range(1, m))
                   for m in range(1, len(imp) + 1)]
        t_acc = t1 + mpmath.nsum(lambda k: 2 * mpmath.atan(v * r**k / 2), [1, mpmath.inf])
    assert len(imp) > 40           # the chatter is followed down to speeds ~1e-16
    assert max(abs(a - b) for a, b in zip(imp, partial, strict=False)) < 1e-25
    assert h.kinds[-1] == STICK
    assert abs(h.aux[-1] - t_acc) < 1e-25       # estimated accumulation time
    assert h.times[-1] <= t_acc
    x, v = h.state(5.0)
    assert abs(x[0]) < 1e-25 and abs(v[0]) < 1e-25   # stays on the wall: force never reverses


@pytest.mark.parametrize("dps", [None, 25])
def test_sticking_releases_when_force_reverses(dps):
    # F = -10 cos(t/2) pushes into the left wall; the contact force 1 - 10 cos(t/2) (eq. 19 at
    # x = 0) changes sign at t = 2 acos(1/10): the release must happen exactly there.
    row = one_pipe(0.5, 0.0, r=0.5, Omega=(0.5,), alpha=-10.0)
    h = simulate(row, 4.0, dps=dps)
    kinds = list(h.kinds)
    assert STICK in kinds and RELEASE in kinds
    i_rel = kinds.index(RELEASE)
    with mpmath.workdps(50):
        t_rel = 2 * mpmath.acos(mpmath.mpf(1) / 10)
    assert abs(h.times[i_rel] - t_rel) < (1e-9 if dps is None else 1e-20)
    assert h.sites[i_rel] == 0
    x, _ = h.state(h.times[i_rel] + 0.05)
    assert float(x[0]) > 0


@pytest.mark.parametrize("r", [0.0, 0.3, 0.9])
def test_chatter_never_hangs_on_random_rows(r):
    row = PipeRow.random(6, 0.6, seed=3, restitution=r)
    h = simulate(row, 30.0)
    assert len(h) > 0
    assert np.all(np.diff(h.times) >= 0)
    for t in np.linspace(0, 30, 301):
        assert np.all(h.gaps(t) > -1e-9)


# ------------------------------------------------------------------ energy and no misses
def test_elastic_unforced_energy_conserved_1000_impacts():
    rng = np.random.default_rng(7)
    n = 5
    x0 = np.arange(1, n + 1) + rng.uniform(-0.3, 0.3, n)
    v0 = rng.normal(0, 3.0, n)
    row = free_row(x0, v0)
    h = simulate(row, 250.0, dps=20, max_events=5000)
    n_imp = int(np.sum(h.kinds == IMPACT))
    t_last = h.times[n_imp - 1] if n_imp >= 1000 else h.t_end
    assert n_imp >= 1000, n_imp
    e0 = h.energy(0)
    assert abs(h.energy(t_last) - e0) / e0 < 1e-20
    hf = simulate(row, float(t_last))
    assert abs(hf.energy(float(t_last)) - float(e0)) / float(e0) < 1e-10


@pytest.mark.parametrize("dps", [None, 20])
def test_no_missed_contact_brute_force_scan(dps):
    # between consecutive events every gap stays positive (fine grid of the closed-form state),
    # and at each impact the gap is zero: an independent check that no root was stepped over.
    row = PipeRow.random(6, 0.35, seed=5, restitution=0.7)
    h = simulate(row, 15.0, dps=dps)
    assert len(h) > 5
    grid = np.linspace(0, 15.0, 3001)
    for t in grid:
        assert np.min(h.gaps(t).astype(float)) > -1e-9
    for t, s in zip(h.times, h.sites, strict=False):
        assert abs(float(h.gaps(t)[s])) < 1e-9
