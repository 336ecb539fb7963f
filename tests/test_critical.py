"""symhx.critical: the critical point p_c, its certified argmin and enclosure, the
discriminant root p_d and log c_k, against independent references (tests.reference.critical):
exact integer comparisons of ``c_k`` (no logs, no balls), mpmath's loggamma at 3x the digits,
exhaustive scans, Fraction brute force of the pmf, and direct counts for the small helpers.
The mode path and comparisons with p_c are in ``test_critical_mode_path.py``, the stored
constants in ``test_critical_constants.py``, the cost of the certification in
``tests/perf/test_critical_cost.py``."""

from __future__ import annotations

import itertools
import math
import random
from decimal import ROUND_HALF_EVEN, Decimal, localcontext
from fractions import Fraction

import flint
import mpmath
import pytest
from flint import arb
from hypothesis import given, settings
from hypothesis import strategies as st

import symhx
import symhx.asymptotics
import symhx.spaces
from symhx import critical as C
from symhx.certify import UndecidedError
from symhx.critical import (
    argmin_certificate,
    certified_argmin,
    critical_point,
    discriminant_root,
    discriminant_root_q,
    log_c,
    mode_path,
)
from symhx.validation import as_fraction
from tests.harness.errors import assert_refuses
from tests.reference.combinatorics import valuation
from tests.reference.critical import (
    ck_power,
    compare_c,
    critical_by_scan,
    exact_argmins,
    is_first_argmin,
    log_c_direct,
    p_c_direct,
    p_d_closed,
)
from tests.reference.distribution import brute_modes
from tests.reference.mp import rel_err


def _check_enclosure(cp, ref):
    """``cp.p_bounds`` and ``cp.q_bounds`` contain the reference and are at most ``10**-dps``
    wide (zero-width around an exact rational p_c)."""
    lo, hi = cp.p_bounds
    if cp.p_exact is not None:  # exact rational p_c: a zero-width enclosure
        with mpmath.workdps(3 * cp.dps + 40):
            exact = mpmath.mpf(cp.p_exact.numerator) / cp.p_exact.denominator
            assert abs(ref - exact) <= mpmath.mpf(10) ** (2 - 3 * cp.dps) * exact
            assert lo <= exact <= hi and (hi - lo) <= mpmath.mpf(10) ** -cp.dps * exact
        return
    with mpmath.workdps(3 * cp.dps + 40 + 2 * len(str(cp.N))):
        assert lo <= ref <= hi, (cp.N, lo, ref, hi)
        assert lo <= cp.p <= hi
        assert (hi - lo) / ref <= mpmath.mpf(10) ** -cp.dps
        qref = cp.N * ref - 1
        qlo, qhi = cp.q_bounds
        assert qlo <= qref <= qhi
        assert (qhi - qlo) / qref <= mpmath.mpf(10) ** -cp.dps


# --------------------------------------------------------------------------- the argmin
@pytest.mark.parametrize("N", [*range(2, 121), 200, 257, 400])
def test_critical_against_exhaustive_scan(N):
    cp = symhx.critical_point(N, dps=50)
    argmins, p_scan = critical_by_scan(N, 50)
    assert list(cp.argmins) == argmins
    assert cp.k_after == max(argmins) and cp.k_before == 1
    assert rel_err(cp.p, p_scan, dps=400) < mpmath.mpf(10) ** -48
    assert cp.p >= cp.p_d


SMALL = [*range(2, 41), 57, 64, 90, 101]


@pytest.mark.parametrize("N", SMALL)
def test_argmin_every_seed_against_exact_integers(N):
    argmins = exact_argmins(N)
    assert critical_point(N, dps=10).argmins == tuple(argmins)
    # the verification lands on the answer from every seed (secant, gallop and bisection)
    for seed in range(2, N + 3):
        assert certified_argmin(N, seed=seed) == tuple(argmins), (N, seed)
    # the certificate accepts exactly the first argmin
    for k in range(2, N + 1):
        assert argmin_certificate(N, k) == (k == argmins[0]), (N, k)


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 3000))
def test_certified_argmin_any_seed(N):
    # the verification from any (bad) seed lands on the exhaustive scan's answer
    argmins, _ = critical_by_scan(N, 20) if N <= 400 else (None, None)
    ref = certified_argmin(N)
    if argmins is not None:
        assert list(ref) == argmins
    for seed in (2, N, max(2, N // 3)):
        assert certified_argmin(N, seed=seed) == ref


@pytest.mark.parametrize("N", [3, 4, 5, 6, 7, 20, 50, 101, 1000, 12345, 10**6, 10**20, 10**100])
def test_perturbed_argmin_fails_certificate(N):
    cp = critical_point(N, dps=20)
    k = cp.argmins[0]
    assert argmin_certificate(N, k)
    for wrong in (k - 1, k + 1, k + 2):
        if 2 <= wrong <= N and wrong not in cp.argmins[:1]:
            assert not argmin_certificate(N, wrong), (N, wrong)


@pytest.mark.parametrize("N", [10**6, 10**12, 10**100])
def test_argmin_is_certified_locally(N):
    # the integer argmin beats its neighbours, checked with the definition at high precision
    cp = symhx.critical_point(N, dps=30)
    k = cp.k_after
    dps = 60 + 3 * len(str(N))
    v = [log_c_direct(N, j, dps) for j in (k - 1, k, k + 1)]
    with mpmath.workdps(dps):
        assert v[1] < v[0] and v[1] < v[2]
        assert rel_err(mpmath.exp(v[1]) / N, cp.p, dps=400) < mpmath.mpf(10) ** -28


@pytest.mark.parametrize("N", [20, 101, 1000, 5000])
def test_c_is_unimodal_exhaustive(N):
    # log c_k is unimodal in k (proof in symhx.critical); check every k
    vals = [log_c_direct(N, k, 30) for k in range(2, N + 1)]
    d = [b - a for a, b in itertools.pairwise(vals)]
    changes = sum(1 for x, y in itertools.pairwise(d) if (x < 0) != (y < 0))
    assert changes <= 1


@pytest.mark.parametrize("N", [5, 12, 30, 101])
def test_sign_oracle_and_its_exact_fallback(N):
    oracle = C._SignOracle(N)
    for k in range(2, N):
        want = compare_c(N, k + 1, k)
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


def test_sign_oracle_exact_work_limit_boundary():
    N = 2**38 + 12345  # 39 bits: k * (39 + 1) hits the limit exactly at k = LIMIT / 40
    k = C.EXACT_BITS_LIMIT // 40
    assert k * (N.bit_length() + 1) == C.EXACT_BITS_LIMIT
    assert C._SignOracle(N)._exact(k) == -1  # at the limit: still computed (c_{k+1} < c_k)
    with pytest.raises(UndecidedError) as info:
        C._SignOracle(N)._exact(k + 1)
    msg = str(info.value)  # which comparison, for which N, and that the balls did not decide
    assert f"c_{k + 2} vs c_{k + 1}" in msg and f"N={N}" in msg and "balls" in msg


def test_seed_is_close_to_the_argmin():
    # the Lambert-W seed (with its fitted shift) lands within 3 of the certified argmin
    for N in [*range(25, 400, 7), *(10**e for e in range(3, 40)), 10**100, 10**300, 2**200 + 1]:
        k = certified_argmin(N)[0]
        assert abs(C._seed(N) - k) <= 3, (N, C._seed(N), k)
    assert all(C._seed(N) == 2 for N in range(2, 25))
    assert critical_point(10**300, dps=10).sign_evaluations <= 4


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


# --------------------------------------------------------------------------- small N and ties
def test_degenerate_small_N():
    # degenerate small N (see the symhx.critical docstring)
    cp2 = symhx.critical_point(2)
    assert cp2.p_exact == 2 and cp2.p > 1  # no jump in (0, 1]
    cp3 = symhx.critical_point(3)
    assert cp3.p_exact == 1 and symhx.discriminant_root(3) == 1
    cp5 = symhx.critical_point(5)
    assert cp5.argmins == (2, 3) and cp5.k_after == 3 and cp5.p_exact == Fraction(1, 2)
    assert symhx.modes(5, Fraction(1, 2)) == (1, 2, 3)
    for N in range(4, 8):
        cp = symhx.critical_point(N)
        assert cp.k_after in (2, 3)
        assert cp.p > cp.p_d  # strictly larger for N >= 4


def test_exact_tie_N5():
    assert C._argmin_c(5) == (2, True, C._argmin_c(5)[2])
    assert C._argmin_c(2) == (2, False, 0)
    cp = critical_point(5, dps=30)
    assert cp.argmins == (2, 3) and cp.k_after == 3 and cp.jump == 2 and cp.k_before == 1


def test_exact_ties():
    cp = critical_point(5)
    assert cp.argmins == (2, 3) and cp.p_exact == Fraction(1, 2)
    assert cp.p_bounds == (mpmath.mpf("0.5"), mpmath.mpf("0.5"))
    assert symhx.modes(5, Fraction(1, 2)) == (1, 2, 3) == brute_modes(5, Fraction(1, 2))
    # N = 101 at p = 1/50: f(50) = 0, Phi(50) = Phi(51) (a mode-path breakpoint)
    assert symhx.modes(101, Fraction(1, 50)) == (50, 51) == brute_modes(101, Fraction(1, 50))
    path = mode_path(101)
    assert (Fraction(1, 50), 50, 51) in path.breakpoints
    assert path.mode_at(Fraction(1, 50)) == 50
    assert path.mode_at(Fraction(1, 50) + Fraction(1, 10**30)) == 51


@pytest.mark.parametrize("N", [4, 7, 30, 101, 500])
def test_mode_around_critical_point(N):
    cp = symhx.critical_point(N, dps=60)
    with mpmath.workdps(80):
        eps = mpmath.mpf(10) ** -50
        below, above = cp.p * (1 - eps), cp.p * (1 + eps)
    assert symhx.mode(N, below) == 1
    assert symhx.mode(N, above) == cp.k_after
    # brute force with exact Fractions of those binary values
    assert brute_modes(N, as_fraction(above))[0] == cp.k_after


# --------------------------------------------------------------------------- rational p_c
def test_perm_and_legendre():
    for n in range(0, 60):
        for r in range(0, n + 1):
            assert C._perm(n, r) == math.factorial(n) // math.factorial(n - r)
        for p in (2, 3, 5, 7, 11):
            assert C._vp_factorial(n, p) == valuation(math.factorial(n), p), (n, p)


def test_exact_root():
    assert C._exact_root(Fraction(9, 4), 2) == Fraction(3, 2)
    assert C._exact_root(Fraction(8, 27), 3) == Fraction(2, 3)
    assert C._exact_root(Fraction(5, 7), 1) == Fraction(5, 7)
    assert C._exact_root(Fraction(9, 2), 2) is None
    assert C._exact_root(Fraction(2, 9), 2) is None
    assert C._exact_root(Fraction(16, 81), 4) == Fraction(2, 3)
    assert C._exact_root(Fraction(16, 81), 2) == Fraction(4, 9)


def test_rational_root_prefilter_is_only_necessary():
    # p_exact: the cheap p-adic prefilter never rejects a c_k that is rational (exhaustive)
    found = 0
    for N in range(3, 300):
        for k in range(2, min(N, 30) + 1):
            if C._exact_root(Fraction(k, math.perm(N - 1, k - 1)), k - 1) is not None:
                found += 1
                assert C._root_possible(N, k), (N, k)
    assert found >= 297  # every k = 2 at least (c_2 = 2/(N-1))


def test_rational_critical_points_beyond_k2():
    # c_k rational for k >= 3: the prefilter must let it through and p_exact must be found
    found = []
    for N in range(3, 200):
        for k in range(3, min(N, 12) + 1):
            r = C._exact_root(Fraction(k, math.perm(N - 1, k - 1)), k - 1)
            if r is not None:
                assert C._root_possible(N, k)
                assert r ** (k - 1) == ck_power(N, k)
                found.append((N, k))
    assert found  # e.g. (N, k) = (5, 3): c_3 = 1/2
    # and the prefilter rejects where an exponent of 2, 3, 5 or 7 is not a multiple of k-1
    assert not C._root_possible(10, 3)
    assert C._root_possible(5, 3)


def test_root_possible_against_direct_valuations():
    passed = []
    for N in range(3, 400):
        for k in range(2, (N if N < 70 else 12) + 1):
            perm = math.perm(N - 1, k - 1)
            want = all((valuation(k, p) - valuation(perm, p)) % (k - 1) == 0
                       for p in (2, 3, 5, 7))
            assert C._root_possible(N, k) == want, (N, k)
            if want and k >= 3:
                passed.append((N, k))
    # e.g. N = 110, k = 4: 4 / (109 * 108 * 107) has exponents 2 - 2 = 0 of 2 and 0 - 3 of 3
    assert (110, 4) in passed and (5, 3) in passed


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
            flo, fhi = as_fraction(lo), as_fraction(hi)
            assert flo <= a <= fhi and fhi - flo <= a / 10**dps
            assert as_fraction(qlo) <= N * a - 1 <= as_fraction(qhi)
            assert lo <= p <= hi and qlo <= q <= qhi


# --------------------------------------------------------------------------- the enclosures
@pytest.mark.parametrize("N", [*range(2, 41), 64, 101, 257, 400])
@pytest.mark.parametrize("dps", [5, 50])
def test_enclosure_small_N_against_scan(N, dps):
    cp = critical_point(N, dps=dps)
    argmins, _ = critical_by_scan(N, 3 * dps)
    assert list(cp.argmins) == argmins
    _check_enclosure(cp, p_c_direct(N, argmins[0], dps))


@pytest.mark.parametrize("N", [10**3, 10**4, 10**6, 10**12, 10**30, 10**100, 10**306])
@pytest.mark.parametrize("dps", [15, 50, 120])
def test_enclosure_large_N(N, dps):
    cp = critical_point(N, dps=dps)
    _check_enclosure(cp, p_c_direct(N, cp.k_after, dps))


@pytest.mark.parametrize("N", [4, 7, 101, 1000, 10**6, 10**25, 10**120])
@pytest.mark.parametrize("dps", [3, 30, 300])
def test_critical_point_width_and_value(N, dps):
    cp = critical_point(N, dps=dps)
    k = cp.argmins[0]
    ref = p_c_direct(N, k, dps)
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


@pytest.mark.parametrize("N", [101, 10**4, 10**40])
def test_widths_shrink_as_dps_grows(N):
    widths = []
    for dps in (10, 20, 40, 80, 160):
        lo, hi = critical_point(N, dps=dps).p_bounds
        with mpmath.workdps(400):
            w = (hi - lo) / lo
        assert w <= mpmath.mpf(10) ** -dps
        widths.append(w)
    assert all(b < a / 10**9 for a, b in itertools.pairwise(widths)), widths


@pytest.mark.parametrize("N,k", [(101, 20), (10**6, 3802), (10**40, None)])
def test_enclosure_loop_from_low_start_precision(N, k):
    # the width loop itself (not the generous default start) must deliver 10**-dps
    k = k or critical_point(N, dps=10).k_after
    for dps in (20, 60):
        ref = p_c_direct(N, k, dps)
        # every start precision, so that some land just above/below the needed one
        for start in range(64, 64 + 8 * (dps + 3 * len(str(N))), 3):
            _, _, (lo, hi), (qlo, qhi) = C.enclose_from_s(N, lambda: C._s_arb(N, k), dps, start)
            with mpmath.workdps(3 * dps + 2 * len(str(N)) + 40):
                assert lo <= ref <= hi and (hi - lo) <= mpmath.mpf(10) ** -dps * ref
                assert qlo <= N * ref - 1 <= qhi
                assert (qhi - qlo) <= mpmath.mpf(10) ** -dps * (N * ref - 1)


@pytest.mark.parametrize("e", [3, 6, 10, 30, 100, 150])
@pytest.mark.parametrize("dps", [15, 50, 100, 200])
def test_huge_N_precision_doubling(e, dps):
    N = 10**e
    cp = symhx.critical_point(N, dps=dps)
    hi = symhx.critical_point(N, dps=2 * dps)
    assert cp.k_after == hi.k_after
    tol = mpmath.mpf(10) ** (1 - dps)
    assert rel_err(cp.p, hi.p, dps=400) < tol and rel_err(cp.q, hi.q, dps=400) < tol
    # q = N p - 1 is consistent with p
    with mpmath.workdps(2 * dps + e + 10):
        assert rel_err(N * hi.p - 1, hi.q, dps=400) < mpmath.mpf(10) ** (e - 2 * dps + 2)


@pytest.mark.parametrize("e", [306, 1000])
def test_huge_N(e):
    N = 10**e
    cp = critical_point(N, dps=30)
    assert cp.sign_evaluations <= 4  # seeded, then verified: never a scan
    assert is_first_argmin(N, cp.k_after)
    _check_enclosure(cp, p_c_direct(N, cp.k_after, 30))
    # p_c and p_d round to the same 30 digits but q = N p - 1 tells them apart
    assert cp.q > 0 and cp.q_d > 0 and cp.q > cp.q_d
    assert "p_c" in repr(cp) and "N*p_c-1" in repr(cp)


def test_N_ten_thousand_digits():
    N = 10**10000
    cp = critical_point(N, dps=20)
    assert cp.sign_evaluations <= 4
    # k ~ sqrt(N v), v = -W_{-1}(-e^2/N) ~ ln N - 2 + ln(ln N - 2): k has 5002 digits
    assert 5001 <= cp.k_after.bit_length() * 0.30103 <= 5003
    with mpmath.workdps(30):
        L = 10000 * mpmath.log(10)
        assert abs(cp.q / mpmath.sqrt(L / mpmath.mpf(N)) - 1) < mpmath.mpf("0.01")
    assert str(cp).startswith("critical point, N = ~1.0e+10000")


@pytest.mark.parametrize("N", [5, 101, 10**30])
@pytest.mark.parametrize("dps", [3, 20, 70])
def test_every_returned_mpf_is_rounded_to_dps_digits(N, dps):
    cp = critical_point(N, dps=dps)
    with mpmath.workdps(dps):
        for x in (cp.p, cp.q, cp.p_d, cp.q_d, log_c(N, 3, dps=dps)):
            assert +x == x  # already a dps-digit number: rounding it changes nothing


def test_no_global_precision_leak():
    flint_prec, mp_dps = flint.ctx.prec, mpmath.mp.dps
    critical_point(10**50, dps=200)
    symhx.spaces.critical_point(50, space="eq41", dps=80)
    symhx.asymptotics.asymptotic_critical_point(10**20, dps=90)
    mode_path(300, dps=70).mode_at(Fraction(1, 10))
    symhx.modes(10**4, Fraction(3, 10**4))
    assert flint.ctx.prec == flint_prec and mpmath.mp.dps == mp_dps


# --------------------------------------------------------------------------- p_d and log c_k
@pytest.mark.parametrize("N", [2, 3, 10, 101, 10**6, 10**100])
def test_discriminant_root(N):
    pd = symhx.discriminant_root(N, dps=80)
    qd = discriminant_root_q(N, dps=80)
    with mpmath.workdps(120 + 2 * len(str(N))):
        # f has a double root at p_d: discriminant (N p - 1)^2 - 4 p = 0, with q = N p - 1
        assert abs(N * pd - 1 - qd) < mpmath.mpf(10) ** -78 * N * pd
        assert abs(qd**2 - 4 * pd) < mpmath.mpf(10) ** -77 * pd
        # the spurious root ((1 - sqrt(N+1))/N)^2 has its double root at k < 0
        ps = ((1 - mpmath.sqrt(N + 1)) / N) ** 2
        assert (N * ps - 1) / (2 * ps) < 0


@pytest.mark.parametrize("N", [2, 3, 4, 10, 101, 10**6, 10**50, 10**400])
@pytest.mark.parametrize("dps", [1, 15, 60, 300])
def test_discriminant_root_correctly_rounded(N, dps):
    pd, qd = p_d_closed(N, 3 * dps)
    pd_got, qd_got = discriminant_root(N, dps=dps), discriminant_root_q(N, dps=dps)
    with mpmath.workdps(dps):  # the reference rounded to nearest at dps digits
        pd_ref, qd_ref = +pd, +qd
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 30):
        # equal to the correctly rounded value, or one ulp off only at a near-halfway case
        for got, ref, exact in ((pd_got, pd_ref, pd), (qd_got, qd_ref, qd)):
            if got != ref:
                assert abs(got - exact) <= abs(ref - exact) * (1 + mpmath.mpf(10) ** -20)
            assert abs(got - exact) <= mpmath.mpf(2) ** -(mpmath.mpf(dps) * 3.32) * exact


@given(st.integers(3, 10**30), st.integers(2, 10**4))
def test_log_c_matches_definition(N, k):
    k = min(k, N)
    assert rel_err(log_c(N, k, dps=40), log_c_direct(N, k, 40), dps=400) < mpmath.mpf(10) ** -38


@pytest.mark.parametrize("N, k", [(5, 2), (101, 20), (101, 101), (10**6, 3802), (10**6, 7),
                                  (10**40, 10**20), (10**200, 10**99 + 7)])
@pytest.mark.parametrize("dps", [5, 40, 250])
def test_log_c_against_loggamma(N, k, dps):
    got = log_c(N, k, dps=dps)
    ref = log_c_direct(N, k, 3 * dps)
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        assert abs(got - ref) <= mpmath.mpf(10) ** (1 - dps) * abs(ref), (N, k, dps)


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


def test_log_c_precision_loop_stops_at_its_cap(monkeypatch):
    # from a 16-bit start the doubling loop of log_c is capped at 40 x start = 640 bits: asked
    # for 400 digits (more than 640 bits) it stops and returns what it has
    monkeypatch.setattr(C, "bits_for", lambda N, extra: 16 + 0 * N + 0 * int(extra))
    got = log_c(101, 20, dps=400)
    with mpmath.workdps(500):
        assert abs(got - log_c_direct(101, 20, 400)) < mpmath.mpf(10) ** -150


# --------------------------------------------------------------------------- display
def test_fmt_int():
    assert C._fmt_int(12345) == "12345"
    assert C._fmt_int(2**160 - 1) == str(2**160 - 1)
    assert C._fmt_int(2**160) == "~1.4615016373309e+48"
    assert C._fmt_int(10**5000) == "~1.0e+5000"


def test_fmt_int_is_correctly_rounded_to_15_digits():
    """Huge N in messages: exact up to 160 bits, else N rounded once to 15 significant digits
    (reference: Decimal's own rounding, half to even)."""
    assert C._fmt_int(2**160 - 1) == str(2**160 - 1)
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
        got = C._fmt_int(N)
        assert got.startswith("~") and Decimal(got[1:]) == ref, (N, got, ref)


def test_repr_shows_dps_digits():
    cp = critical_point(101, dps=30)
    text = repr(cp)
    assert mpmath.nstr(cp.p, 30) in text and "p_bounds" in text
    d = cp.as_dict()
    assert d["p_c_lo"] <= d["p_c"] <= d["p_c_hi"]
    assert set(d) >= {"N", "p_c", "N_p_c_minus_1", "k_after", "argmins", "p_d", "p_c_exact"}
    assert math.isclose(float(d["p_c"]), 0.012889115326530578, rel_tol=1e-15)


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


# --------------------------------------------------------------------------- bad input
DPS_ALLOWED = "an int between 1 and 5000"
BAD_DPS = [0, -1, 2.5, True, 10**6, "50", None]


def _dps_error(bad):
    return ValueError if type(bad) is int else TypeError


@pytest.mark.parametrize("bad", BAD_DPS)
def test_bad_dps(bad):
    for fn, args in ((critical_point, (101,)), (discriminant_root, (101,)),
                     (discriminant_root_q, (101,)), (log_c, (101, 20))):
        assert_refuses(fn, *args, dps=bad, exc=_dps_error(bad), arg="dps", allowed=DPS_ALLOWED)


def test_bad_inputs():
    for N in (1, 0, -5):
        assert_refuses(critical_point, N, arg="N", value=str(N), allowed=">= 2")
    for N in (True, 10.0, 101.5, [3]):
        assert_refuses(critical_point, N, exc=TypeError, arg="N")
    assert_refuses(argmin_certificate, 10, 11, arg="k", value="11", allowed="<= 10")


def test_validation_of_k_and_seed():
    for call, name in ((lambda v: log_c(10, v), "k"), (lambda v: argmin_certificate(10, v), "k"),
                       (lambda v: certified_argmin(10, seed=v), "seed")):
        assert_refuses(call, 1, arg=name, value="1", allowed=">= 2")
        assert_refuses(call, 2.5, exc=TypeError, arg=name, value="float 2.5", allowed="an int")
    for call in (lambda: log_c(10, 11), lambda: argmin_certificate(10, 11)):
        assert_refuses(call, arg="k", value="11", allowed="<= 10")
    assert certified_argmin(10, seed=10**9) == certified_argmin(10)  # a seed above N is fine
    assert log_c(10, 10) > 0 and argmin_certificate(10, 10) is False
