"""symhx.critical against independent references (issue 16, mutation testing): exact integer
comparisons of ``c_k`` (no logs, no balls), Fraction brute force of the pmf, mpmath's loggamma
at 3x the digits, and direct counts for the small helpers. Every test is fast."""

from __future__ import annotations

import dataclasses
import math
from fractions import Fraction

import mpmath
import pytest
from flint import arb

from symhx import critical as C
from symhx.certify import UndecidedError
from symhx.critical import (
    MAX_BREAKPOINTS,
    argmin_certificate,
    certified_argmin,
    critical_point,
    discriminant_root,
    discriminant_root_q,
    log_c,
    mode_path,
)
from tests.reference.critical import log_c_direct
from tests.reference.distribution import brute_modes


# ---------------------------------------------------------------- exact references for c_k
def _ck_power(N: int, k: int) -> Fraction:
    """c_k**(k-1) = k (N-k)! / (N-1)! exactly."""
    return Fraction(k * math.factorial(N - k), math.factorial(N - 1))


def _cmp_c(N: int, j: int, k: int) -> int:
    """Exact sign of c_j - c_k (powers to the common exponent (j-1)(k-1), integers only)."""
    a, b = _ck_power(N, j), _ck_power(N, k)
    lhs = a.numerator ** (k - 1) * b.denominator ** (j - 1)
    rhs = b.numerator ** (j - 1) * a.denominator ** (k - 1)
    return (lhs > rhs) - (lhs < rhs)


def _exact_argmins(N: int) -> list[int]:
    best = [2]
    for k in range(3, N + 1):
        s = _cmp_c(N, k, best[0])
        if s < 0:
            best = [k]
        elif s == 0:
            best.append(k)
    return best


SMALL = [*range(2, 41), 57, 64, 90, 101]


@pytest.mark.parametrize("N", SMALL)
def test_argmin_every_seed_against_exact_integers(N):
    argmins = _exact_argmins(N)
    assert critical_point(N, dps=10).argmins == tuple(argmins)
    # the verification lands on the answer from every seed (secant, gallop and bisection)
    for seed in range(2, N + 3):
        assert certified_argmin(N, seed=seed) == tuple(argmins), (N, seed)
    # the certificate accepts exactly the first argmin
    for k in range(2, N + 1):
        assert argmin_certificate(N, k) == (k == argmins[0]), (N, k)


@pytest.mark.parametrize("N", [5, 12, 30, 101])
def test_sign_oracle_and_its_exact_fallback(N):
    oracle = C._SignOracle(N)
    for k in range(2, N):
        want = _cmp_c(N, k + 1, k)
        assert oracle.sign(k) == want, (N, k)
        assert oracle._exact(k) == want, (N, k)
    assert oracle.sign(N) == 1 and oracle.sign(N + 5) == 1
    assert oracle.evaluations == N - 2  # cached: each k evaluated once
    oracle.sign(3)
    assert oracle.evaluations == N - 2


def test_sign_oracle_exact_fallback_refuses_huge_work():
    oracle = C._SignOracle(10**12)
    k = C.EXACT_BITS_LIMIT // 41 + 10  # k * (bits of N + 1) just above the limit
    with pytest.raises(UndecidedError, match="exact comparison needs"):
        oracle._exact(k)


def test_seed_is_close_to_the_argmin():
    # the Lambert-W seed (with its fitted shift) lands within 3 of the certified argmin
    for N in [*range(25, 400, 7), *(10**e for e in range(3, 40)), 10**100, 10**300, 2**200 + 1]:
        k = certified_argmin(N)[0]
        assert abs(C._seed(N) - k) <= 3, (N, C._seed(N), k)
    assert all(C._seed(N) == 2 for N in range(2, 25))
    assert critical_point(10**300, dps=10).sign_evaluations <= 4


def test_exact_tie_N5():
    assert C._argmin_c(5) == (2, True, C._argmin_c(5)[2])
    assert C._argmin_c(2) == (2, False, 0)
    cp = critical_point(5, dps=30)
    assert cp.argmins == (2, 3) and cp.k_after == 3 and cp.jump == 2 and cp.k_before == 1


# ------------------------------------------------------------------------ small helpers
def test_perm_and_legendre():
    for n in range(0, 60):
        for r in range(0, n + 1):
            assert C._perm(n, r) == math.factorial(n) // math.factorial(n - r)
        for p in (2, 3, 5, 7, 11):
            f, v = math.factorial(n), 0
            while f % p == 0:
                f //= p
                v += 1
            assert C._vp_factorial(n, p) == v, (n, p)


def test_exact_root():
    assert C._exact_root(Fraction(9, 4), 2) == Fraction(3, 2)
    assert C._exact_root(Fraction(8, 27), 3) == Fraction(2, 3)
    assert C._exact_root(Fraction(5, 7), 1) == Fraction(5, 7)
    assert C._exact_root(Fraction(9, 2), 2) is None
    assert C._exact_root(Fraction(2, 9), 2) is None
    assert C._exact_root(Fraction(16, 81), 4) == Fraction(2, 3)
    assert C._exact_root(Fraction(16, 81), 2) == Fraction(4, 9)


def test_rational_critical_points_beyond_k2():
    # c_k rational for k >= 3: the prefilter must let it through and p_exact must be found
    found = []
    for N in range(3, 200):
        for k in range(3, min(N, 12) + 1):
            r = C._exact_root(Fraction(k, math.perm(N - 1, k - 1)), k - 1)
            if r is not None:
                assert C._root_possible(N, k)
                assert r ** (k - 1) == _ck_power(N, k)
                found.append((N, k))
    assert found  # e.g. (N, k) = (5, 3): c_3 = 1/2
    # and the prefilter rejects where an exponent of 2, 3, 5 or 7 is not a multiple of k-1
    assert not C._root_possible(10, 3)
    assert C._root_possible(5, 3)


def test_fmt_int():
    assert C._fmt_int(12345) == "12345"
    assert C._fmt_int(2**160 - 1) == str(2**160 - 1)
    assert C._fmt_int(2**160) == "~1.4615016373309e+48"
    assert C._fmt_int(10**5000) == "~1.0e+5000"


# -------------------------------------------------------------------- discriminant, log c
@pytest.mark.parametrize("N", [2, 3, 4, 10, 101, 10**6, 10**50, 10**400])
@pytest.mark.parametrize("dps", [1, 15, 60, 300])
def test_discriminant_root_correctly_rounded(N, dps):
    d = len(str(N))
    with mpmath.workdps(3 * dps + 2 * d + 30):
        s = mpmath.sqrt(N + 1)
        pd = ((1 + s) / N) ** 2
        qd = 2 * (1 + s) / N
    pd_got, qd_got = discriminant_root(N, dps=dps), discriminant_root_q(N, dps=dps)
    with mpmath.workdps(dps):  # the reference rounded to nearest at dps digits
        pd_ref, qd_ref = +pd, +qd
    with mpmath.workdps(3 * dps + 2 * d + 30):
        # equal to the correctly rounded value, or one ulp off only at a near-halfway case
        for got, ref, exact in ((pd_got, pd_ref, pd), (qd_got, qd_ref, qd)):
            if got != ref:
                assert abs(got - exact) <= abs(ref - exact) * (1 + mpmath.mpf(10) ** -20)
            assert abs(got - exact) <= mpmath.mpf(2) ** -(mpmath.mpf(dps) * 3.32) * exact


@pytest.mark.parametrize("N, k", [(5, 2), (101, 20), (101, 101), (10**6, 3802), (10**6, 7),
                                  (10**40, 10**20), (10**200, 10**99 + 7)])
@pytest.mark.parametrize("dps", [5, 40, 250])
def test_log_c_against_loggamma(N, k, dps):
    got = log_c(N, k, dps=dps)
    ref = log_c_direct(N, k, 3 * dps)
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        assert abs(got - ref) <= mpmath.mpf(10) ** (1 - dps) * abs(ref), (N, k, dps)


# ----------------------------------------------------------------------- the enclosures
def _ref_pc(N: int, k: int, dps: int) -> mpmath.mpf:
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        return mpmath.exp(log_c_direct(N, k, 3 * dps)) / N


@pytest.mark.parametrize("N", [4, 7, 101, 1000, 10**6, 10**25, 10**120])
@pytest.mark.parametrize("dps", [3, 30, 300])
def test_critical_point_width_and_value(N, dps):
    cp = critical_point(N, dps=dps)
    k = cp.argmins[0]
    ref = _ref_pc(N, k, dps)
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        one = mpmath.mpf(10) ** -dps
        lo, hi = cp.p_bounds
        qlo, qhi = cp.q_bounds
        assert lo <= ref <= hi and lo <= cp.p <= hi
        assert hi - lo <= one * ref
        assert abs(cp.p - ref) <= one * ref
        qref = N * ref - 1
        assert qlo <= qref <= qhi and qlo <= cp.q <= qhi
        assert qhi - qlo <= one * qref
        assert abs(cp.q - qref) <= one * qref
    assert cp.dps == dps and cp.N == N


@pytest.mark.parametrize("N", [2, 3, 4, 5])
@pytest.mark.parametrize("dps", [4, 40])
def test_rational_critical_point(N, dps):
    cp = critical_point(N, dps=dps)
    assert cp.argmins[0] == 2  # c_2 = 2/(N-1); N = 5 ties c_2 = c_3
    exact = Fraction(2, N - 1)
    assert cp.p_exact == exact
    with mpmath.workdps(4 * dps):
        e = mpmath.mpf(exact.numerator) / exact.denominator
        lo, hi = cp.p_bounds
        qlo, qhi = cp.q_bounds
        assert lo <= e <= hi and hi - lo <= mpmath.mpf(10) ** -dps * e
        assert abs(cp.p - e) <= mpmath.mpf(10) ** -dps * e
        q = N * e - 1
        assert qlo <= q <= qhi and abs(cp.q - q) <= mpmath.mpf(10) ** -dps * q
        if N == 5:  # 1/2: exactly representable, a zero-width enclosure
            assert lo == hi == e


def test_exact_enclosure_is_outward():
    for N, a in ((9, Fraction(1, 4)), (17, Fraction(1, 8)), (7, Fraction(1, 3)),
                 (12, Fraction(2, 11))):
        for dps in (3, 30):
            p, q, (lo, hi), (qlo, qhi) = C.exact_enclosure(N, a, dps)
            flo, fhi = C._frac(lo), C._frac(hi)
            assert flo <= a <= fhi and fhi - flo <= a / 10**dps
            assert C._frac(qlo) <= N * a - 1 <= C._frac(qhi)
            assert lo <= p <= hi and qlo <= q <= qhi


def test_repr_str_and_dict():
    cp = critical_point(101, dps=12)
    assert repr(cp).startswith("CriticalPoint(N=101, p_c=0.0128891153265, ")
    assert "argmins=(20,)" in repr(cp) and "k_after=20" in repr(cp)
    assert "dps=12)" in repr(cp)
    s = str(cp)
    assert s.splitlines()[0] == "critical point, N = 101 (12 digits)"
    assert "mode jumps  1 -> 20  (argmins 20)" in s
    assert "(= " not in s  # irrational
    five = critical_point(5, dps=6)
    assert "p_c         = 0.5  (= 1/2)" in str(five)
    assert "argmins=(2, 3)," in repr(five)
    d = five.as_dict()
    assert d["argmins"] == [2, 3] and d["p_c_exact"] == Fraction(1, 2)
    assert d["p_c_lo"] == d["p_c_hi"] == mpmath.mpf("0.5") and d["dps"] == 6
    assert d["N"] == 5 and d["k_before"] == 1 and d["k_after"] == 3
    assert d["N_p_c_minus_1"] == five.q and d["N_p_d_minus_1"] == five.q_d
    assert d["p_d"] == five.p_d and d["p_c"] == five.p
    big = critical_point(10**60, dps=8)
    assert "CriticalPoint(N=~1.0e+60, " in repr(big) and f"k_after={big.k_after}," in repr(big)
    assert str(big).startswith("critical point, N = ~1.0e+60 (8 digits)")


# ------------------------------------------------------------------ compare_with_critical
def test_compare_with_critical_all_paths():
    cp = critical_point(101, dps=20)
    lo, hi = (C._frac(b) for b in cp.p_bounds)
    assert C.compare_with_critical(cp, lo - Fraction(1, 10**40)) == -1
    assert C.compare_with_critical(cp, hi + Fraction(1, 10**40)) == 1
    ref = _ref_pc(101, 20, 40)
    with mpmath.workdps(150):
        for sgn in (-1, 1):
            fr = C._frac(ref * (1 + sgn * mpmath.mpf(10) ** -30))
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


# ------------------------------------------------------------------------- the mode path
def _breakpoints_brute(N: int, k0: int, pm: Fraction) -> int:
    last = k0 - 1
    for k in range(k0, N):
        if Fraction(k + 1, k * (N - k)) <= pm:
            last = k
    return last


def test_breakpoints_below_against_brute_force():
    for N in (3, 4, 7, 20, 61):
        for k0 in range(2, N):
            for pm in (Fraction(1, 10), Fraction(1, 3), Fraction(1, 2), Fraction(9, 10),
                       Fraction(1), Fraction(N, N - 1), Fraction(7), Fraction(k0 + 1,
                                                                          k0 * (N - k0))):
                assert C._breakpoints_below(N, k0, pm) == _breakpoints_brute(N, k0, pm), (
                    N, k0, pm)


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


def test_mode_path_cap_boundary():
    N = 10**6
    cp = critical_point(N, dps=10)
    last = cp.k_after + MAX_BREAKPOINTS - 2  # exactly MAX_BREAKPOINTS breakpoints
    pm = Fraction(last + 1, last * (N - last))
    path = mode_path(N, p_max=pm, dps=10)
    assert len(path.breakpoints) == MAX_BREAKPOINTS
    assert path.breakpoints[-1] == (pm, last, last + 1)
    nxt = Fraction(last + 2, (last + 1) * (N - last - 1))
    with pytest.raises(ValueError, match=f"would list {MAX_BREAKPOINTS + 1} breakpoints"):
        mode_path(N, p_max=nxt, dps=10)


def test_mode_at_rejects():
    path = mode_path(20, p_max=Fraction(1, 2))
    for bad in (0, -1, Fraction(-1, 3)):
        with pytest.raises(ValueError, match="positive"):
            path.mode_at(bad)
    with pytest.raises(ValueError, match="p_max = 1/2"):
        path.mode_at(Fraction(1, 2) + Fraction(1, 10**20))
    assert path.mode_at(Fraction(1, 2)) == brute_modes(20, Fraction(1, 2))[0]
    assert path.mode_at(0.25) == brute_modes(20, Fraction(0.25))[0]


def test_validation_of_k_and_seed():
    for call, name in ((lambda v: log_c(10, v), "k"), (lambda v: argmin_certificate(10, v), "k"),
                       (lambda v: certified_argmin(10, seed=v), "seed")):
        with pytest.raises(ValueError, match=f"^{name} must be >= 2, got 1$"):
            call(1)
        with pytest.raises(TypeError, match=f"^{name} must be an int"):
            call(2.5)
    for call in (lambda: log_c(10, 11), lambda: argmin_certificate(10, 11)):
        with pytest.raises(ValueError, match=r"^k must be <= 10, got 11$"):
            call()
    assert certified_argmin(10, seed=10**9) == certified_argmin(10)  # a seed above N is fine
    assert log_c(10, 10) > 0 and argmin_certificate(10, 10) is False


def test_sign_oracle_exact_work_limit_boundary():
    N = 2**38 + 12345  # 39 bits: k * (39 + 1) hits the limit exactly at k = LIMIT / 40
    k = C.EXACT_BITS_LIMIT // 40
    assert k * (N.bit_length() + 1) == C.EXACT_BITS_LIMIT
    assert C._SignOracle(N)._exact(k) == -1  # at the limit: still computed (c_{k+1} < c_k)
    with pytest.raises(UndecidedError, match=rf"^c_{k + 2} vs c_{k + 1} for N={N}: balls"):
        C._SignOracle(N)._exact(k + 1)


def test_repr_and_str_show_every_field():
    cp = critical_point(101, dps=12)

    def s(x):
        return mpmath.nstr(x, 12)

    lo, hi = cp.p_bounds
    assert repr(cp) == (
        f"CriticalPoint(N=101, p_c={s(cp.p)}, q=N*p_c-1={s(cp.q)}, k_before=1, k_after=20, "
        f"argmins=(20,), p_d={s(cp.p_d)}, q_d=N*p_d-1={s(cp.q_d)}, p_exact=None, "
        f"p_bounds=({s(lo)}, {s(hi)}), dps=12)")
    assert str(cp).splitlines() == [
        "critical point, N = 101 (12 digits)", f"  p_c         = {s(cp.p)}",
        f"  N p_c - 1   = {s(cp.q)}", f"  p_c in        [{s(lo)}, {s(hi)}]  (Arb ball)",
        f"  p_d         = {s(cp.p_d)}", f"  N p_d - 1   = {s(cp.q_d)}",
        "  mode jumps  1 -> 20  (argmins 20)"]
    assert lo < hi
    five = critical_point(5, dps=6)
    assert str(five).splitlines()[-1] == "  mode jumps  1 -> 3  (argmins 2, 3)"
    d = cp.as_dict()
    assert (d["p_c_lo"], d["p_c_hi"]) == (lo, hi)


def test_log_c_precision_loop_from_a_low_start(monkeypatch):
    # the default start precision already gives dps + 2 digits (log k - G(k-1) >= log 2), so
    # the doubling loop of log_c is exercised here from a 16-bit start: it must still deliver
    # dps digits, and stop (cap 40 x start = 640 bits)
    def low_start(N, extra):
        return 16 + 0 * N.bit_length() + 0 * int(extra)

    monkeypatch.setattr(C, "bits_for", low_start)
    for N, k in ((101, 20), (10**6, 3802), (10**40, 10**20)):
        for dps in range(5, 121, 23):
            got = log_c(N, k, dps=dps)
            ref = log_c_direct(N, k, 3 * dps)
            with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
                assert abs(got - ref) <= mpmath.mpf(10) ** -dps * abs(ref), (N, k, dps)
    # beyond the cap (640 bits < 200 digits): the loop stops and returns what it has
    got = log_c(101, 20, dps=400)
    with mpmath.workdps(500):
        assert abs(got - log_c_direct(101, 20, 400)) < mpmath.mpf(10) ** -150


# ------------------------------------------------- the documented cost of the certification
# Each certified sign is one Arb ball of E(k) at the start precision (the ball separates at
# once unless E(k) = 0 exactly), a correct seed is proved by exactly the two signs
# E(k*-1) < 0 <= E(k*), a seed a few steps off costs a few more, and a far seed costs a
# gallop plus a bisection: at most 2 log2(distance) + 2 signs. The spies count calls of the
# ball functions; the first argmin itself comes from an independent reference.
@pytest.fixture
def e_calls(monkeypatch):
    calls: list[int] = []
    orig = C._E_arb

    def spy(N, k):
        calls.append(k)
        return orig(N, k)

    monkeypatch.setattr(C, "_E_arb", spy)
    return calls


def _first_argmin_ref(N: int) -> int:
    """The first argmin: exact integers for small N, else the Lambert-W neighbourhood checked
    with mpmath loggamma (c_{k-1} > c_k <= c_{k+1} and unimodality)."""
    if N <= 200:
        return _exact_argmins(N)[0]
    k = certified_argmin(N)[0]
    s0, s1, s2 = (log_c_direct(N, j, 30) for j in (k - 1, k, k + 1))
    assert s0 > s1 <= s2
    return k


COST_N = [10**4, 10**6, 10**9 + 7, 10**12, 10**18, 10**30]


@pytest.mark.parametrize("N", [3, 4, 6, 7, 8, 12, 30, 101, *COST_N])
def test_a_correct_seed_costs_exactly_the_two_proving_signs(N, e_calls):
    k = _first_argmin_ref(N)
    e_calls.clear()
    got = C._argmin_c(N, k)
    assert got == (k, False, 1 if k == 2 else 2)
    assert sorted(e_calls) == ([2] if k == 2 else [k - 1, k])  # one ball per sign
    # certified_argmin passes its seed on: the same two balls
    e_calls.clear()
    assert certified_argmin(N, seed=k) == (k,)
    assert sorted(e_calls) == ([2] if k == 2 else [k - 1, k])
    # and critical_point reports the signs its own (Lambert-W) seed needed
    e_calls.clear()
    cp = critical_point(N, dps=5)
    assert cp.argmins[0] == k
    assert cp.sign_evaluations == len(set(e_calls)) == len(e_calls) >= (1 if k == 2 else 2)


def test_the_exact_tie_costs_the_full_doubling_then_integers(e_calls):
    # N = 5: E(2) = 0 exactly, so the ball of E(2) contains 0 at every precision: it is tried at
    # start, 2, 4, 8 and 16 x start bits (max_bits = 16 x start), then the integers decide
    assert C._argmin_c(5, 2) == (2, True, 1)
    assert e_calls == [2] * 5


@pytest.mark.parametrize("N", COST_N)
def test_a_seed_a_few_steps_off_costs_a_few_more_signs(N, e_calls):
    k = _first_argmin_ref(N)
    for d in range(-6, 7):
        e_calls.clear()
        got = C._argmin_c(N, k + d)
        assert got[:2] == (k, False)
        # off by one: the failed check shows the direction, one more sign proves k*;
        # further off: one secant step on the two balls lands on k* (E is nearly linear there)
        assert got[2] == (2 if d == 0 else 3 if abs(d) == 1 else 4), (N, d, got)
        assert len(e_calls) == got[2]


@pytest.mark.parametrize("N", [30, 101, 1000, *COST_N, 10**60])
def test_a_far_seed_costs_a_gallop_and_a_bisection(N, e_calls):
    k = _first_argmin_ref(N)
    for seed in (2, 3, N - 1, N):  # from k >= N - 1 the search gallops down at once
        e_calls.clear()
        got = C._argmin_c(N, seed)
        assert got[:2] == (k, False)
        dist = abs(seed - k)
        assert got[2] <= 2 * dist.bit_length() + 2, (N, seed, got)
        assert len(e_calls) == got[2]


def test_small_N_argmin_costs():
    # N = 2: nothing to compare; N = 3, 4: c_3 > c_2 is the one sign that proves k* = 2
    assert C._argmin_c(2) == (2, False, 0)
    assert C._argmin_c(3) == (2, False, 1)
    assert C._argmin_c(4) == (2, False, 1)
    assert critical_point(3).sign_evaluations == 1


@pytest.mark.parametrize("N", [6, 12, 101, 10**6, 10**30])
@pytest.mark.parametrize("dps", [1, 15, 60, 200])
def test_critical_point_encloses_with_one_ball(N, dps, monkeypatch):
    # the start precision of the p_c enclosure already meets the width: a single ball of s(k*)
    calls = []
    orig = C._s_arb

    def spy(n, k):
        calls.append(k)
        return orig(n, k)

    monkeypatch.setattr(C, "_s_arb", spy)
    cp = critical_point(N, dps=dps)
    assert cp.p_exact is None and calls == [cp.argmins[0]]
    # p_d (eq. 16), where f first gets real roots: the larger root of (N p - 1)**2 = 4 p
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        pd = (1 + mpmath.sqrt(N + 1)) ** 2 / N**2
        assert abs(cp.p_d - pd) <= mpmath.mpf(10) ** (1 - dps) * pd


# ------------------------------------------- compare_with_critical: balls, integers, limits
def _spy(monkeypatch, name):
    calls = []
    orig = getattr(C, name)

    def spy(*args):
        calls.append(args)
        return orig(*args)

    monkeypatch.setattr(C, name, spy)
    return calls


@pytest.mark.parametrize("N, dps", [(12, 5), (101, 20), (101, 60), (10**6, 30), (10**30, 15)])
def test_compare_near_p_c_one_ball_then_two(N, dps, monkeypatch):
    cp = critical_point(N, dps=dps)
    k = cp.argmins[0]
    ref = _ref_pc(N, k, 2 * dps + 40)  # independent p_c, far beyond the distances used
    lo, hi = (C._frac(b) for b in cp.p_bounds)
    g_calls = _spy(monkeypatch, "G_arb")
    perm_calls = _spy(monkeypatch, "_perm")
    start = C.bits_for(N, int(dps * 3.33) + 2 * k.bit_length() + 40)
    tested = set()
    for sgn in (-1, 1):
        for extra, balls in ((int(dps * 3.33) + 2 * k.bit_length() + 20, 1), (start + 24, 2)):
            with mpmath.workdps(2 * dps + 40 + 2 * len(str(N))):
                fr = C._frac(ref * (1 + sgn * mpmath.mpf(2) ** -extra))
            if not lo < fr < hi:  # p_c sits near one end of the (hulled) bounds
                continue
            g_calls.clear()
            assert C.compare_with_critical(cp, fr) == sgn
            # the start precision separates at 2**-(dps*3.33 + 2 log2 k + 20); closer
            # (2**-(start + 24)) the doubled precision does: never the exact integers
            assert len(g_calls) == balls and not perm_calls, (sgn, extra)
            tested.add(balls)
    assert tested == {1, 2}


def test_compare_exact_fallback_against_factorials(monkeypatch):
    # force the exact integer path (as if no ball separated) and check it against
    # fr**(k-1) vs c_k**(k-1) = k (N-k)! / (N-1)! in Fractions
    cps = [critical_point(N, dps=10) for N in (6, 12, 30, 101)]
    monkeypatch.setattr(C, "certified_sign", lambda ball, *, start_bits, max_bits, exact_fn:
                        exact_fn())
    for cp in cps:
        N, k = cp.N, cp.argmins[0]
        wide = dataclasses.replace(cp, p_bounds=(mpmath.mpf(0), mpmath.mpf(10)))
        pc = C._frac(cp.p)
        for fr in (Fraction(1, 2 * N), pc * Fraction(999, 1000), pc, pc * Fraction(1001, 1000),
                   Fraction(2, 3), Fraction(7, 5)):
            a, b = fr ** (k - 1), _ck_power(N, k)
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
    with pytest.raises(UndecidedError,
                       match=r"^p=3/250 vs p_c for N=101: exact comparison too big$"):
        C.compare_with_critical(cp, fr)


def test_compare_on_an_exact_tie_doubles_to_16x_then_integers(monkeypatch):
    # N = 5 with p_exact withheld: the ball of the exact zero is tried at start, 2, 4, 8 and
    # 16 x start bits, then the integers say 0
    blind = dataclasses.replace(critical_point(5), p_exact=None,
                                p_bounds=(mpmath.mpf("0.4"), mpmath.mpf("0.6")))
    g_calls = _spy(monkeypatch, "G_arb")
    assert C.compare_with_critical(blind, Fraction(1, 2)) == 0
    assert len(g_calls) == 5


# ------------------------------------------------------------------- _root_possible, direct
def _vp(n: int, p: int) -> int:
    v = 0
    while n % p == 0:
        n //= p
        v += 1
    return v


def test_root_possible_against_direct_valuations():
    passed = []
    for N in range(3, 400):
        for k in range(2, (N if N < 70 else 12) + 1):
            perm = math.perm(N - 1, k - 1)
            want = all((_vp(k, p) - _vp(perm, p)) % (k - 1) == 0 for p in (2, 3, 5, 7))
            assert C._root_possible(N, k) == want, (N, k)
            if want and k >= 3:
                passed.append((N, k))
    # e.g. N = 110, k = 4: 4 / (109 * 108 * 107) has exponents 2 - 2 = 0 of 2 and 0 - 3 of 3
    assert (110, 4) in passed and (5, 3) in passed


# ------------------------------------------------------------------------ mode_path, more
def test_mode_path_names_p_max_and_keeps_dps_and_the_critical_point():
    with pytest.raises(ValueError, match=r"^p_max must be a number such as"):
        mode_path(10, p_max="x")
    with pytest.raises(ValueError, match=r"^p_max must be finite, got nan$"):
        mode_path(10, p_max=float("nan"))
    path = mode_path(101, p_max=Fraction(1, 20), dps=7)
    assert path.critical.dps == 7
    ref = _ref_pc(101, 20, 7)
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


def test_log_c_from_a_low_start_is_correct_to_the_last_bit(monkeypatch):
    # the loop stops only once the ball is 100x narrower than a unit of the dps-th digit, so
    # the returned mpf is within one unit in the last place (dps digits = mpmath's prec bits)
    # of the true value, for every dps (a stop at the dps-th digit itself misses this)
    monkeypatch.setattr(C, "bits_for", lambda N, extra: 16 + 0 * N + 0 * int(extra))
    for N, k in ((101, 20), (10**6, 3802), (10**40, 10**20)):
        for dps in range(1, 121):
            got = log_c(N, k, dps=dps)
            ref = log_c_direct(N, k, 3 * dps)
            with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
                ulp = mpmath.mpf(2) ** (1 - mpmath.libmp.dps_to_prec(dps))
                assert abs(got - ref) <= ulp * abs(ref), (N, k, dps)


@pytest.mark.parametrize("N", [5, 101, 10**30])
@pytest.mark.parametrize("dps", [3, 20, 70])
def test_every_returned_mpf_is_rounded_to_dps_digits(N, dps):
    cp = critical_point(N, dps=dps)
    with mpmath.workdps(dps):
        for x in (cp.p, cp.q, cp.p_d, cp.q_d, log_c(N, 3, dps=dps)):
            assert +x == x  # already a dps-digit number: rounding it changes nothing


@pytest.mark.parametrize("t", [3, 4, 7, 12, 21, 30])
def test_search_on_a_synthetic_exact_tie_from_every_seed(t, monkeypatch):
    # the search logic alone, on E(k) = k - t (an exact zero at k = t: c_{t+1} = c_t, a tie
    # like N = 5 has at t = 2): from every seed it must return the first k with E(k) >= 0,
    # t, and report the tie; the brute-force reference is that first index itself
    monkeypatch.setattr(C, "_E_arb", lambda N, k: arb(k - t))
    monkeypatch.setattr(C._SignOracle, "_exact", lambda self, k: (k > t) - (k < t))
    for N in (t + 1, t + 2, t + 3, 2 * t + 5, 40):
        for seed in range(2, N + 1):
            kstar, tie, _ = C._argmin_c(N, seed)
            assert (kstar, tie) == (t, True), (N, seed)


def test_fmt_int_is_correctly_rounded_to_15_digits():
    """Huge N in messages: exact up to 160 bits, else N rounded once to 15 significant digits
    (reference: mpmath at 60 digits, then Decimal rounding half to even)."""
    import random
    from decimal import ROUND_HALF_EVEN, Decimal, localcontext

    from symhx.critical import _fmt_int

    assert _fmt_int(2**160 - 1) == str(2**160 - 1)
    rng = random.Random(7)
    cases = [95676649905087550000000000000004549377870619113110, 10**200, 10**200 - 1,
             10**49 * 999999999999999 + 5 * 10**48, 10**49 * 999999999999998 + 5 * 10**48]
    cases += [rng.randrange(2**160, 10 ** rng.randint(49, 300)) for _ in range(300)]
    for N in cases:
        if N.bit_length() <= 160:
            continue
        with localcontext() as ctx:
            ctx.prec = 15
            ctx.rounding = ROUND_HALF_EVEN
            ref = +Decimal(N)  # N's digits fit Decimal: exact, then one rounding
        got = _fmt_int(N)
        assert got.startswith("~") and Decimal(got[1:]) == ref, (N, got, ref)
