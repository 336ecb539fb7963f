"""Arb-certified decisions and enclosures (issue 11): every enclosure contains a value recomputed
independently (mpmath loggamma route at 3x the digits, or exact brute force), widths meet the
contract and shrink with dps, a perturbed argmin fails its certificate, any N works."""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import flint
import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import symhx
import symhx.asymptotics
import symhx.spaces
import symhx.validation
from symhx.certify import UndecidedError, certified_sign, mpf_bounds, to_arb
from symhx.critical import (
    MAX_BREAKPOINTS,
    argmin_certificate,
    certified_argmin,
    critical_point,
    discriminant_root,
    mode_path,
)
from tests.reference.critical import critical_by_scan, log_c_direct
from tests.reference.distribution import brute_modes


def _pc_reference(N: int, k: int, dps: int) -> mpmath.mpf:
    """c_k from the definition (loggamma) at 3x the digits, plus 2 log10(N) guard digits."""
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        return mpmath.exp(log_c_direct(N, k, 3 * dps)) / N


def _check_enclosure(cp, ref):
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


@pytest.mark.parametrize("N", [*range(2, 41), 64, 101, 257, 400])
@pytest.mark.parametrize("dps", [5, 50])
def test_enclosure_small_N_against_scan(N, dps):
    cp = critical_point(N, dps=dps)
    argmins, _ = critical_by_scan(N, 3 * dps)
    assert list(cp.argmins) == argmins
    _check_enclosure(cp, _pc_reference(N, argmins[0], dps))


@pytest.mark.parametrize("N", [10**3, 10**4, 10**6, 10**12, 10**30, 10**100, 10**306])
@pytest.mark.parametrize("dps", [15, 50, 120])
def test_enclosure_large_N(N, dps):
    cp = critical_point(N, dps=dps)
    _check_enclosure(cp, _pc_reference(N, cp.k_after, dps))


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


def _local_min_independent(N: int, k: int) -> None:
    """c_{k-1} > c_k < c_{k+1} from the loggamma definition at a precision that resolves
    the gaps (~ 1/k**2 relative); with the proved unimodality this makes k the argmin."""
    dps = 30 + 2 * (k.bit_length() * 30103 // 100000 + 1)
    v = [log_c_direct(N, j, dps) for j in (k - 1, k, k + 1)]
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        assert v[1] < v[0] and v[1] < v[2]


@pytest.mark.parametrize("e", [306, 1000])
def test_huge_N(e):
    N = 10**e
    cp = critical_point(N, dps=30)
    assert cp.sign_evaluations <= 4  # seeded, then verified: never a scan
    _local_min_independent(N, cp.k_after)
    _check_enclosure(cp, _pc_reference(N, cp.k_after, 30))
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


@pytest.mark.parametrize("N", [3, 4, 5, 6, 7, 20, 50, 101, 1000, 12345, 10**6, 10**20, 10**100])
def test_perturbed_argmin_fails_certificate(N):
    cp = critical_point(N, dps=20)
    k = cp.argmins[0]
    assert argmin_certificate(N, k)
    for wrong in (k - 1, k + 1, k + 2):
        if 2 <= wrong <= N and wrong not in cp.argmins[:1]:
            assert not argmin_certificate(N, wrong), (N, wrong)


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


def test_mode_at_near_irrational_jump():
    N = 101
    path = mode_path(N, dps=30)
    pc_lo, pc_hi = path.bounds[0]
    with mpmath.workdps(60):
        below = symhx.validation.as_fraction(pc_lo * (1 - mpmath.mpf(10) ** -40))
        above = symhx.validation.as_fraction(pc_hi * (1 + mpmath.mpf(10) ** -40))
    assert path.mode_at(below) == 1 == brute_modes(N, below)[0]
    assert path.mode_at(above) == 20 == brute_modes(N, above)[0]
    # inside the 30-digit enclosure but 1e-33 away from p_c: decided by Arb, checked exactly
    ref = _pc_reference(N, 20, 30)
    with mpmath.workdps(120):
        near_lo = symhx.validation.as_fraction(ref * (1 - mpmath.mpf(10) ** -33))
        near_hi = symhx.validation.as_fraction(ref * (1 + mpmath.mpf(10) ** -33))
    assert path.mode_at(near_lo) == 1 == brute_modes(N, near_lo)[0]
    assert path.mode_at(near_hi) == 20 == brute_modes(N, near_hi)[0]


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
    with pytest.raises(ValueError, match="MAX_BREAKPOINTS"):
        mode_path(N)
    assert MAX_BREAKPOINTS >= 10**5


@pytest.mark.parametrize("bad", [0, -1, 2.5, True, 10**6, "50", None])
def test_bad_dps(bad):
    calls = [lambda: critical_point(101, dps=bad), lambda: mode_path(20, dps=bad),
             lambda: discriminant_root(101, dps=bad),
             lambda: symhx.asymptotics.asymptotic_critical_point(1000, dps=bad),
             lambda: symhx.spaces.critical_point(20, space="eq41", dps=bad),
             lambda: symhx.asymptotics.pd_series(100, dps=bad)]
    for call in calls:
        with pytest.raises((ValueError, TypeError), match="dps"):
            call()


def test_bad_inputs():
    from symhx.asymptotics import asymptotic_critical_point, pd_series, pd_series_coefficients

    for N in (1, 0, -5):
        with pytest.raises(ValueError, match="N"):
            pd_series(N)
        with pytest.raises(ValueError, match="N"):
            critical_point(N)
    for N in (True, 10.0, 101.5, [3]):
        with pytest.raises(TypeError, match="N"):
            critical_point(N)
        with pytest.raises(TypeError, match="N"):
            pd_series(N)
    for n_terms in (0, -1, 10**9):
        with pytest.raises(ValueError, match="n_terms"):
            pd_series(100, n_terms)
        with pytest.raises(ValueError, match="n_terms"):
            pd_series_coefficients(n_terms)
    with pytest.raises(TypeError, match="n_terms"):
        pd_series(100, 2.0)
    with pytest.raises(ValueError, match="order"):
        asymptotic_critical_point(1000, order="best ")
    with pytest.raises(TypeError, match="order"):
        asymptotic_critical_point(1000, order=True)
    for pm in (0, -1, "-0.5", float("nan"), float("inf")):
        with pytest.raises(ValueError, match="p_max"):
            mode_path(20, p_max=pm)
    with pytest.raises(TypeError, match="p_max"):
        mode_path(20, p_max=[1])
    with pytest.raises(ValueError, match="k"):
        argmin_certificate(10, 11)
    with pytest.raises(ValueError, match="p"):
        mode_path(20).mode_at(0)
    with pytest.raises(ValueError, match="p_max"):
        mode_path(20, p_max=Fraction(1, 2)).mode_at(Fraction(3, 4))


def test_no_global_precision_leak():
    flint_prec, mp_dps = flint.ctx.prec, mpmath.mp.dps
    critical_point(10**50, dps=200)
    symhx.spaces.critical_point(50, space="eq41", dps=80)
    symhx.asymptotics.asymptotic_critical_point(10**20, dps=90)
    mode_path(300, dps=70).mode_at(Fraction(1, 10))
    symhx.modes(10**4, Fraction(3, 10**4))
    assert flint.ctx.prec == flint_prec and mpmath.mp.dps == mp_dps


def test_certify_primitives():
    # a true tie is undecidable by balls: the exact fallback decides, or a clear error
    assert certified_sign(lambda: to_arb(3).sqrt() ** 2 - 3, start_bits=64, max_bits=256,
                          exact_fn=lambda: 0) == 0
    with pytest.raises(UndecidedError):
        certified_sign(lambda: to_arb(3).sqrt() ** 2 - 3, start_bits=64, max_bits=128)
    assert certified_sign(lambda: to_arb(Fraction(1, 3)) - to_arb(mpmath.mpf(1) / 3),
                          start_bits=64, max_bits=64) == 1  # 1/3 > its binary rounding
    with flint.ctx.workprec(300):
        lo, hi = mpf_bounds(flint.arb(2).sqrt(), 40)
    with mpmath.workdps(100):
        assert lo < mpmath.sqrt(2) < hi and (hi - lo) < mpmath.mpf(10) ** -44


def test_repr_shows_dps_digits():
    cp = critical_point(101, dps=30)
    text = repr(cp)
    assert mpmath.nstr(cp.p, 30) in text and "p_bounds" in text
    d = cp.as_dict()
    assert d["p_c_lo"] <= d["p_c"] <= d["p_c_hi"]
    assert set(d) >= {"N", "p_c", "N_p_c_minus_1", "k_after", "argmins", "p_d", "p_c_exact"}
    assert math.isclose(float(d["p_c"]), 0.012889115326530578, rel_tol=1e-15)


def test_rational_root_prefilter_is_only_necessary():
    # p_exact: the cheap p-adic prefilter never rejects a c_k that is rational (exhaustive)
    from symhx.critical import _exact_root, _root_possible

    found = 0
    for N in range(3, 300):
        for k in range(2, min(N, 30) + 1):
            if _exact_root(Fraction(k, math.perm(N - 1, k - 1)), k - 1) is not None:
                found += 1
                assert _root_possible(N, k), (N, k)
    assert found >= 297  # every k = 2 at least (c_2 = 2/(N-1))


@pytest.mark.parametrize("N,k", [(101, 20), (10**6, 3802), (10**40, None)])
def test_enclosure_loop_from_low_start_precision(N, k):
    # the width loop itself (not the generous default start) must deliver 10**-dps
    from symhx.critical import _s_arb, enclose_from_s

    k = k or critical_point(N, dps=10).k_after
    for dps in (20, 60):
        ref = _pc_reference(N, k, dps)
        # every start precision, so that some land just above/below the needed one
        for start in range(64, 64 + 8 * (dps + 3 * len(str(N))), 3):
            _, _, (lo, hi), (qlo, qhi) = enclose_from_s(N, lambda: _s_arb(N, k), dps, start)
            with mpmath.workdps(3 * dps + 2 * len(str(N)) + 40):
                assert lo <= ref <= hi and (hi - lo) <= mpmath.mpf(10) ** -dps * ref
                assert qlo <= N * ref - 1 <= qhi
                assert (qhi - qlo) <= mpmath.mpf(10) ** -dps * (N * ref - 1)


@pytest.mark.parametrize("N", [7, 101, 1000, 10**30])
def test_mode_at_inside_the_enclosure(N):
    # rationals inside p_bounds, 1e-45 from p_c on either side: only the Arb comparison
    # (not the enclosure) can decide them; checked against exact brute force for small N
    cp = critical_point(N, dps=30)
    k = cp.k_after  # p_max: the first breakpoint after the jump
    path = mode_path(N, p_max=Fraction(k + 1, k * (N - k)), dps=30)
    if cp.p_exact is not None:
        pytest.skip("rational p_c")
    ref = _pc_reference(N, cp.argmins[0], 30)
    with mpmath.workdps(200):
        for sgn in (-1, 1):
            fr = symhx.validation.as_fraction(ref * (1 + sgn * mpmath.mpf(10) ** -45))
            assert symhx.validation.as_fraction(cp.p_bounds[0]) < fr
            assert fr < symhx.validation.as_fraction(cp.p_bounds[1])
            got = path.mode_at(fr)
            assert got == (cp.k_after if sgn > 0 else 1)
            if N <= 101:
                assert brute_modes(N, fr)[0] == got


def test_rel_width_ok_threshold():
    from symhx.certify import rel_width_ok

    with flint.ctx.workprec(200):
        for dps in (5, 30):
            mid = flint.arb(3)
            ok = flint.arb(mid, mid * flint.arb(10) ** -dps / 5)   # width 2 r / mid = 0.4e-dps
            bad = flint.arb(mid, mid * flint.arb(10) ** -dps / 3)  # 2 r / mid = 0.67e-dps > 1/4
            assert rel_width_ok(ok, dps) and not rel_width_ok(bad, dps)
            assert rel_width_ok(flint.arb(7), dps) and not rel_width_ok(flint.arb(0, 1), dps)


def test_mode_path_cap_is_counted_before_building():
    import time

    N = 10**6
    t = time.monotonic()
    with pytest.raises(ValueError, match="MAX_BREAKPOINTS") as exc:
        mode_path(N)
    assert time.monotonic() - t < 1
    # independent count: after the jump the mode climbs one step per k with
    # (k+1)/(k(N-k)) <= 1, i.e. every k from k_after to N-1 (checked by brute force here)
    k0 = symhx.critical_point(N).k_after
    count = sum(1 for k in range(k0, N) if k + 1 <= k * (N - k)) + 1
    assert f"would list {count} breakpoints" in str(exc.value)
