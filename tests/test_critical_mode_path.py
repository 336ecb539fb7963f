"""symhx.critical: the mode path k*(p) and the certified comparison of a rational p with p_c,
against exact Fraction brute force of the pmf's modes (tests.reference.distribution) and p_c
from loggamma at 3x the digits (tests.reference.critical)."""

from __future__ import annotations

import dataclasses
import time
from fractions import Fraction

import mpmath
import pytest

import symhx
from symhx import critical as C
from symhx.certify import UndecidedError
from symhx.critical import MAX_BREAKPOINTS, critical_point, mode_path
from symhx.validation import as_fraction
from tests.harness.errors import assert_refuses
from tests.reference.critical import ck_power, last_breakpoint_k, p_c_direct
from tests.reference.distribution import brute_modes


# --------------------------------------------------------------------------- the breakpoints
@pytest.mark.parametrize("N", [2, 3, 4, 5, 6, 9, 31, 101, 150])
def test_mode_path_against_brute_force(N):
    path = symhx.mode_path(N)
    # exact breakpoints: at each, both sides maximise; just after, the right one
    for bp, left, right in path.breakpoints[1:]:
        assert isinstance(bp, Fraction)
        assert set(brute_modes(N, bp)) >= {left, right}
        assert brute_modes(N, bp + Fraction(1, 10**12))[0] == right
        assert brute_modes(N, bp - Fraction(1, 10**12))[0] == left
    # a grid of p values
    for i in range(1, 200):
        p = Fraction(i, 200)
        assert path.mode_at(p) == brute_modes(N, p)[0], (N, p)


@pytest.mark.parametrize("N", [2, 3, 4, 5, 6, 9, 20, 31])
@pytest.mark.parametrize("p_max", [Fraction(1, 3), Fraction(1), Fraction(3, 2), Fraction(10)])
def test_mode_path_against_brute_force_modes(N, p_max):
    path = mode_path(N, p_max=p_max, dps=20)
    assert path.N == N and path.p_max == p_max
    # every exact breakpoint: both sides maximise there, the right one just above
    for bp, left, right in path.breakpoints[1:]:
        assert bp <= p_max and right == left + 1
        assert set(brute_modes(N, bp)) >= {left, right}
        assert brute_modes(N, bp + Fraction(1, 10**15))[0] == right
    # the last breakpoint is the last mode change below p_max (brute force beyond it)
    modes = [brute_modes(N, p_max * Fraction(i, 240))[0] for i in range(1, 241)]
    if path.breakpoints:  # at a breakpoint itself the smaller (left) mode holds
        bp, left, right = path.breakpoints[-1]
        assert (left if bp == p_max else right) == brute_modes(N, p_max)[0]
        assert right == brute_modes(N, p_max + Fraction(1, 10**12))[0] or bp < p_max
    else:
        assert brute_modes(N, p_max)[0] == 1
    assert path.mode_at(p_max) == brute_modes(N, p_max)[0]
    for i in range(1, 241):
        p = p_max * Fraction(i, 240)
        assert path.mode_at(p) == modes[i - 1], (N, p)
    rows = path.as_rows()
    assert len(rows) == len(path.breakpoints)
    for row, (bp, kl, kr), (lo, hi) in zip(rows, path.breakpoints, path.bounds, strict=True):
        assert (row["p"], row["k_left"], row["k_right"], row["p_lo"], row["p_hi"]) == (
            bp, kl, kr, lo, hi)
        assert lo <= bp <= hi


def test_breakpoints_below_against_brute_force():
    for N in (3, 4, 7, 20, 61):
        for k0 in range(2, N):
            for pm in (Fraction(1, 10), Fraction(1, 3), Fraction(1, 2), Fraction(9, 10),
                       Fraction(1), Fraction(N, N - 1), Fraction(7), Fraction(k0 + 1,
                                                                          k0 * (N - k0))):
                assert C._breakpoints_below(N, k0, pm) == last_breakpoint_k(N, k0, pm), (
                    N, k0, pm)


def test_mode_path_keeps_last_breakpoint_above_one():
    for N in (3, 4, 6, 9, 31):
        path = mode_path(N, p_max=10)
        last = path.breakpoints[-1]
        assert last == (Fraction(N, N - 1), N - 1, N), (N, last)
        for i in range(1, 200):
            p = Fraction(i, 20)
            assert path.mode_at(p) == brute_modes(N, p)[0], (N, p)
    # p_max between two breakpoints keeps exactly those below it
    assert [b[1:] for b in mode_path(6, p_max=Fraction(5, 8)).breakpoints] == [
        (1, 3), (3, 4), (4, 5)]
    assert [b[1:] for b in mode_path(6, p_max=Fraction(5, 8) - Fraction(1, 10**9))
            .breakpoints] == [(1, 3), (3, 4)]


def test_mode_path_bounds_and_empty_paths():
    path = mode_path(101, dps=25)
    assert path.bounds[0] == path.critical.p_bounds
    assert all(lo == hi == bp for (bp, _, _), (lo, hi) in zip(path.breakpoints[1:],
                                                                path.bounds[1:], strict=True))
    # rational jump point: a zero-width bound at the Fraction itself
    five = mode_path(5)
    assert five.breakpoints[0][0] == Fraction(1, 2)
    assert five.bounds[0] == (Fraction(1, 2), Fraction(1, 2))
    # p_max below p_c: no breakpoint, the mode is 1 everywhere on the path
    low = mode_path(101, p_max=Fraction(1, 100))
    assert low.breakpoints == () and low.mode_at(Fraction(1, 100)) == 1
    # p_max exactly at a rational p_c keeps the jump
    at = mode_path(5, p_max=Fraction(1, 2))
    assert [b[1:] for b in at.breakpoints] == [(1, 3)]
    assert mode_path(5, p_max=Fraction(1, 2) - Fraction(1, 10**9)).breakpoints == ()
    # N = 2: the jump at p_c = 2 goes straight to k = N
    two = mode_path(2, p_max=3)
    assert two.breakpoints == ((Fraction(2), 1, 2),)
    assert two.mode_at(2) == 1 and two.mode_at(Fraction(201, 100)) == 2
    assert mode_path(2).breakpoints == ()


def test_mode_path_keeps_dps_and_the_critical_point():
    path = mode_path(101, p_max=Fraction(1, 20), dps=7)
    assert path.critical.dps == 7
    ref = p_c_direct(101, 20, 7)
    with mpmath.workdps(40):
        assert abs(path.breakpoints[0][0] - ref) <= mpmath.mpf(10) ** -7 * ref
    # an empty path still carries the critical point it was compared with
    low = mode_path(101, p_max=Fraction(1, 100), dps=9)
    assert low.breakpoints == () and low.critical.dps == 9 and low.critical.argmins == (20,)
    with mpmath.workdps(40):
        assert abs(low.critical.p - ref) <= mpmath.mpf(10) ** -7 * ref
    # a rational jump point is the exact Fraction (not its mpf)
    for N, pc in ((5, Fraction(1, 2)), (3, Fraction(1)), (4, Fraction(2, 3))):
        bp = mode_path(N, p_max=2).breakpoints[0][0]
        assert type(bp) is Fraction and bp == pc


def test_mode_path_large_N_runs():
    path = symhx.mode_path(10**4)
    assert len(path.breakpoints) > 9000
    assert path.breakpoints[0][2] == symhx.critical_point(10**4).k_after


def test_mode_path_huge_N():
    N = 10**306
    cp = critical_point(N, dps=30)
    K = cp.k_after + 40  # p_max: the 41st breakpoint after the jump
    pmax = Fraction(K + 1, K * (N - K))
    path = mode_path(N, p_max=pmax, dps=30)
    ks = [b[2] for b in path.breakpoints]
    assert ks[0] == cp.k_after and ks == list(range(ks[0], ks[0] + len(ks)))
    assert len(ks) == 42 and path.breakpoints[-1][0] == pmax
    for bp, left, _ in path.breakpoints[1:]:  # f_{N,p}(left) = 0 exactly
        assert -bp * left**2 + (N * bp - 1) * left - 1 == 0
    assert_refuses(mode_path, N, arg="p_max", allowed="MAX_BREAKPOINTS")
    assert MAX_BREAKPOINTS >= 10**5


# --------------------------------------------------------------------------- the cap
def test_mode_path_cap_boundary():
    N = 10**6
    cp = critical_point(N, dps=10)
    last = cp.k_after + MAX_BREAKPOINTS - 2  # exactly MAX_BREAKPOINTS breakpoints
    pm = Fraction(last + 1, last * (N - last))
    path = mode_path(N, p_max=pm, dps=10)
    assert len(path.breakpoints) == MAX_BREAKPOINTS
    assert path.breakpoints[-1] == (pm, last, last + 1)
    nxt = Fraction(last + 2, (last + 1) * (N - last - 1))
    assert_refuses(mode_path, N, p_max=nxt, dps=10, arg="p_max",
                   value=f" {MAX_BREAKPOINTS + 1} ",
                   allowed=["MAX_BREAKPOINTS", str(MAX_BREAKPOINTS)])


def test_mode_path_cap_is_counted_before_building():
    N = 10**6
    t = time.monotonic()
    msg = assert_refuses(mode_path, N, arg="p_max", allowed="MAX_BREAKPOINTS")
    assert time.monotonic() - t < 1
    # independent count: after the jump the mode climbs one step per k with
    # (k+1)/(k(N-k)) <= 1, i.e. every k from k_after to N-1 (checked by brute force here)
    k0 = symhx.critical_point(N).k_after
    count = sum(1 for k in range(k0, N) if k + 1 <= k * (N - k)) + 1
    assert f" {count} breakpoints" in msg


# --------------------------------------------------------------------------- mode_at near p_c
def test_mode_at_near_irrational_jump():
    N = 101
    path = mode_path(N, dps=30)
    pc_lo, pc_hi = path.bounds[0]
    with mpmath.workdps(60):
        below = as_fraction(pc_lo * (1 - mpmath.mpf(10) ** -40))
        above = as_fraction(pc_hi * (1 + mpmath.mpf(10) ** -40))
    assert path.mode_at(below) == 1 == brute_modes(N, below)[0]
    assert path.mode_at(above) == 20 == brute_modes(N, above)[0]
    # inside the 30-digit enclosure but 1e-33 away from p_c: decided by Arb, checked exactly
    ref = p_c_direct(N, 20, 30)
    with mpmath.workdps(120):
        near_lo = as_fraction(ref * (1 - mpmath.mpf(10) ** -33))
        near_hi = as_fraction(ref * (1 + mpmath.mpf(10) ** -33))
    assert path.mode_at(near_lo) == 1 == brute_modes(N, near_lo)[0]
    assert path.mode_at(near_hi) == 20 == brute_modes(N, near_hi)[0]


@pytest.mark.parametrize("N", [7, 101, 1000, 10**30])
def test_mode_at_inside_the_enclosure(N):
    # rationals inside p_bounds, 1e-45 from p_c on either side: only the Arb comparison
    # (not the enclosure) can decide them; checked against exact brute force for small N
    cp = critical_point(N, dps=30)
    k = cp.k_after  # p_max: the first breakpoint after the jump
    path = mode_path(N, p_max=Fraction(k + 1, k * (N - k)), dps=30)
    if cp.p_exact is not None:
        pytest.skip("rational p_c")
    ref = p_c_direct(N, cp.argmins[0], 30)
    with mpmath.workdps(200):
        for sgn in (-1, 1):
            fr = as_fraction(ref * (1 + sgn * mpmath.mpf(10) ** -45))
            assert as_fraction(cp.p_bounds[0]) < fr
            assert fr < as_fraction(cp.p_bounds[1])
            got = path.mode_at(fr)
            assert got == (cp.k_after if sgn > 0 else 1)
            if N <= 101:
                assert brute_modes(N, fr)[0] == got


def test_mode_at_rejects():
    path = mode_path(20, p_max=Fraction(1, 2))
    for bad in (0, -1, Fraction(-1, 3)):
        assert_refuses(path.mode_at, bad, arg="p", value=repr(bad), allowed="positive")
    assert_refuses(path.mode_at, Fraction(1, 2) + Fraction(1, 10**20), arg="p",
                   allowed="<= p_max = 1/2")
    assert path.mode_at(Fraction(1, 2)) == brute_modes(20, Fraction(1, 2))[0]
    assert path.mode_at(0.25) == brute_modes(20, Fraction(0.25))[0]


# --------------------------------------------------------------------------- p against p_c
def test_compare_with_critical_all_paths():
    cp = critical_point(101, dps=20)
    lo, hi = (as_fraction(b) for b in cp.p_bounds)
    assert C.compare_with_critical(cp, lo - Fraction(1, 10**40)) == -1
    assert C.compare_with_critical(cp, hi + Fraction(1, 10**40)) == 1
    ref = p_c_direct(101, 20, 40)
    with mpmath.workdps(150):
        for sgn in (-1, 1):
            fr = as_fraction(ref * (1 + sgn * mpmath.mpf(10) ** -30))
            assert lo < fr < hi
            assert C.compare_with_critical(cp, fr) == sgn
    # rational p_c: exact comparison
    five = critical_point(5)
    for fr, want in ((Fraction(1, 2), 0), (Fraction(1, 2) + Fraction(1, 10**50), 1),
                     (Fraction(1, 2) - Fraction(1, 10**50), -1)):
        assert C.compare_with_critical(five, fr) == want
    # the ball path on an exact tie (p_exact withheld, wide bounds): the exact fall-back decides
    blind = dataclasses.replace(five, p_exact=None,
                                p_bounds=(mpmath.mpf("0.4"), mpmath.mpf("0.6")))
    assert C.compare_with_critical(blind, Fraction(1, 2)) == 0
    assert C.compare_with_critical(blind, Fraction(1, 2) + Fraction(1, 10**60)) == 1
    assert C.compare_with_critical(blind, Fraction(1, 2) - Fraction(1, 10**60)) == -1
    # and with k = 3 (c_3 = 1/2 for N = 5 as well): the tie across the other argmin
    blind3 = dataclasses.replace(blind, argmins=(3,))
    assert C.compare_with_critical(blind3, Fraction(1, 2)) == 0
    assert C.compare_with_critical(blind3, Fraction(1, 3)) == -1


def test_compare_exact_fallback_against_factorials(monkeypatch):
    # force the exact integer path (as if no ball separated) and check it against
    # fr**(k-1) vs c_k**(k-1) = k (N-k)! / (N-1)! in Fractions
    cps = [critical_point(N, dps=10) for N in (6, 12, 30, 101)]
    monkeypatch.setattr(C, "certified_sign", lambda ball, *, start_bits, max_bits, exact_fn:
                        exact_fn())
    for cp in cps:
        N, k = cp.N, cp.argmins[0]
        wide = dataclasses.replace(cp, p_bounds=(mpmath.mpf(0), mpmath.mpf(10)))
        pc = as_fraction(cp.p)
        for fr in (Fraction(1, 2 * N), pc * Fraction(999, 1000), pc, pc * Fraction(1001, 1000),
                   Fraction(2, 3), Fraction(7, 5)):
            a, b = fr ** (k - 1), ck_power(N, k)
            assert C.compare_with_critical(wide, fr) == (a > b) - (a < b), (N, fr)


def test_compare_exact_fallback_size_limit(monkeypatch):
    N = 101
    cp = dataclasses.replace(critical_point(N, dps=10), p_bounds=(mpmath.mpf(0), mpmath.mpf(1)))
    monkeypatch.setattr(C, "certified_sign", lambda ball, *, start_bits, max_bits, exact_fn:
                        exact_fn())
    k = cp.argmins[0]
    fr = Fraction(3, 250)  # below p_c = 0.01289...
    size = k * (N.bit_length() + fr.numerator.bit_length() + fr.denominator.bit_length())
    monkeypatch.setattr(C, "EXACT_BITS_LIMIT", size)
    assert C.compare_with_critical(cp, fr) == -1  # at the limit: still exact
    monkeypatch.setattr(C, "EXACT_BITS_LIMIT", size - 1)
    with pytest.raises(UndecidedError) as info:
        C.compare_with_critical(cp, fr)
    msg = str(info.value)  # which p, which N, and that the exact comparison is too big
    assert "p=3/250" in msg and "p_c" in msg and "N=101" in msg and "too big" in msg


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("bad", [0, -1, 2.5, True, 10**6, "50", None])
def test_bad_dps(bad):
    exc = ValueError if type(bad) is int else TypeError
    assert_refuses(mode_path, 20, dps=bad, exc=exc, arg="dps",
                   allowed="an int between 1 and 5000")


def test_bad_inputs():
    for pm in (0, -1, "-0.5", float("nan"), float("inf")):
        assert_refuses(mode_path, 20, p_max=pm, arg="p_max")
    assert_refuses(mode_path, 20, p_max=[1], exc=TypeError, arg="p_max")
    assert_refuses(mode_path(20).mode_at, 0, arg="p")
    assert_refuses(mode_path(20, p_max=Fraction(1, 2)).mode_at, Fraction(3, 4), arg="p_max")


def test_mode_path_names_p_max():
    assert_refuses(mode_path, 10, p_max="x", arg="p_max", value="'x'",
                   allowed="a number such as")
    assert_refuses(mode_path, 10, p_max=float("nan"), arg="p_max", value="nan",
                   allowed="finite")
