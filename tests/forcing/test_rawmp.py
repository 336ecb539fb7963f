"""The raw-libmp fast path of the one-component mpmath evaluation (``symhx.forcing.rawmp``).

Two checks per point: (1) the value is correct to ``dps`` digits against an independent
reference (the closed form of eq. (27) written out, at a precision raised by every digit that
cancels, from the exact binary inputs: :func:`tests.reference.forcing.eq27_value`); (2) the
documented promise of the module, "the same operations, roundings and precisions as the
mpf-object code": the fast value agrees with the object code of :mod:`symhx.forcing.kernels_mp`
at the same working precision to within a few units of its last digits (so a cut precision
shows even where ``dps`` digits survive), and bit for bit where both use mpmath's erf series.
Low ``dps``, far tails and deep cancellation through the public functions complete it.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx
from symhx._mpctx import mp as thread_mp
from symhx.forcing.kernels_mp import (
    estimate_float,
    mp_p_from_xy,
    mp_q_from_xy,
    mp_xy_forcing,
    precision_plan,
)
from symhx.forcing.rawmp import single_mp_fast
from tests.harness.twins import check_twins
from tests.reference.forcing import eq27_p_or_q, eq27_value, eq27_xy

WANTS = ("p", "q", "logp", "logq")


def _object_code(args, want, dps):
    """The mpf-object evaluation of kernels_mp at the fast path's working precision."""
    guard, direct_q = precision_plan(estimate_float(*args), want)
    with mpmath.workdps(dps + guard), thread_mp().workdps(dps + guard):
        x, y = mp_xy_forcing(*args)
        if want == "p":
            return mp_p_from_xy(x, y), mpmath.mp.prec
        if want == "logp":
            return mpmath.log(mp_p_from_xy(x, y)), mpmath.mp.prec
        q = 1 - mp_p_from_xy(x, y) if direct_q else mp_q_from_xy(x, y)
        return (q if want == "q" else mpmath.log(q)), mpmath.mp.prec


def _scale(want, ref, pt, dps):
    """What a rounding of p at the working precision moves the value by (relative units):
    ``|v|`` for p and log p; 1 - p and its log move by the rounding of p, not of themselves."""
    if want == "q":
        return max(abs(ref), mpmath.mpf(1) - abs(ref))
    if want == "logq":
        return 1 / abs(eq27_value(*pt, "q", dps)) - 1 + abs(ref)
    return abs(ref)


def _fr(v):
    return None if v is None else Fraction(v)


POINTS = [  # (sigma, sigma1, omega, Omega, d): both tails, u == v, erf arguments 0.01 .. 60
    (0.12, None, 1.0, None, 1.0), (0.05, None, 1.0, None, 1.0), (0.3, None, 1.0, None, 1.0),
    (0.9, None, 1.0, None, 1.0), (3.0, None, 1.0, None, 1.0), (40.0, None, 1.0, None, 1.0),
    (0.02, None, 1.0, None, 1.0), (0.011, None, 1.0, None, 1.0), (0.2, 0.7, 0.8, 1.7, 0.6),
    (0.4, 0.003, 1.3, 0.9, 2.0), (5.0, 0.08, 1.0, None, 3.0), (0.07, 9.0, 1.0, None, 1.0),
    (1e-3, 2.0, 1.0, 0.5, 1.0), (2.0, 1e-3, 1.0, None, 1.0), (0.25, 0.25, 2.0, 1.0, 1.0),
    (0.015, 0.5, 1.0, None, 0.75), (7.0, 0.6, 1.2, None, 1.0), (300.0, 100.0, 1.0, None, 1.0),
    (0.6, 1.5, 1.0, 3.0, 4.0), (0.035, 0.035, 1.0, None, 0.5),
]


@pytest.mark.parametrize("dps", [15, 40])
@pytest.mark.parametrize("pt", POINTS)
def test_fast_path_against_reference_and_object_code(pt, dps):
    args = tuple(_fr(v) for v in pt)
    done = 0
    for want in WANTS:
        val = single_mp_fast(*args, dps, want)
        if want == "p":  # the fast path always serves p for float inputs
            assert val is not None
        if val is None:
            continue
        done += 1
        ref = eq27_value(*pt, want, dps)
        with mpmath.workdps(dps + 40), thread_mp().workdps(dps + 40):
            err = abs(val - ref) / abs(ref)
            assert err < mpmath.mpf(10) ** -dps, (want, pt, val, ref)
            obj, prec = _object_code(args, want, dps)
            # same roundings at the same precision: a few units of the last of prec bits,
            # amplified by the exponent uv (exp(-uv)) and by the digits cancelled in 1 - p
            diff = abs(val - obj) / _scale(want, ref, pt, dps)
            assert diff < mpmath.mpf(2) ** (-prec + 12) * (1 + abs(eq27_value(*pt, "logp", dps))), (
                want, pt, float(diff), prec)
    assert done >= 2


def test_inputs_it_does_not_take_give_none():
    one = Fraction(1)
    fr = Fraction(1, 10)  # not dyadic
    for args in [(fr, None, one, None, one), (Fraction(1, 8), None, one, fr, one),
                 (Fraction(1, 8), fr, one, None, one), (Fraction(1, 8), None, fr, None, one),
                 (Fraction(1, 8), None, one, None, fr),
                 (Fraction((1 << 70) + 1, 1 << 80), None, one, None, one),  # 71-bit mantissa
                 (Fraction(-1, 8), None, one, None, one), ("0.1", None, one, None, one),
                 (1 << 60, None, one, None, one), (math.inf, None, one, None, one),
                 (0.0, None, one, None, one), (Fraction(1, 4), None, 1.5, 1.5, one)]:
        assert single_mp_fast(*args, 20, "p") is None, args
    # resonance with Omega None: omega**2 = 2 cannot happen for a dyadic omega; huge inputs
    # (x beyond 1e150) are left to the general path
    assert single_mp_fast(Fraction(1, 1 << 300), None, one, None, one, 20, "p") is None
    # ints, floats and dyadic Fractions are taken (and give the same value)
    a = single_mp_fast(Fraction(3, 8), None, 1, None, 2, 30, "p")
    b = single_mp_fast(0.375, None, 1.0, None, 2.0, 30, "p")
    c = single_mp_fast(Fraction(3, 8), None, Fraction(1), None, Fraction(2), 30, "p")
    assert a is not None and a == b == c
    with mpmath.workdps(50), thread_mp().workdps(50):
        assert abs(a / eq27_value(0.375, None, 1.0, None, 2.0, "p", 30) - 1) < mpmath.mpf(10) ** -30


def test_large_erf_arguments_keep_full_precision():
    """u, v from 2 to ~60 (erf by 1 - erfc, or exactly 1): p at 60 digits is still right; the
    erf term carries most of B there, so a wrong erf shows at once."""
    for s in (0.2, 0.1, 0.05, 0.03, 0.02, 0.012):
        for s1 in (None, 0.5 * s, 3 * s):
            pt = (s, s1, 1.0, None, 1.0)
            args = tuple(_fr(v) for v in pt)
            for want in ("p", "logp"):
                val = single_mp_fast(*args, 60, want)
                if val is None:  # log p with p > 1/2: log1p(-(1 - p)) in the general path
                    assert want == "logp" and eq27_value(*pt, "p", 30) > 0.5
                    continue
                ref = eq27_value(*pt, want, 60)
                obj, prec = _object_code(args, want, 60)
                with mpmath.workdps(120), thread_mp().workdps(120):
                    assert abs(val / ref - 1) < mpmath.mpf(10) ** -60, (pt, want)
                    assert abs(val / obj - 1) < mpmath.mpf(2) ** (-prec + 12) * (
                        1 + abs(mpmath.log(abs(ref)))), (pt, want)


def test_sqrt_pi_at_fresh_precisions(monkeypatch):
    """The cached sqrt(pi) is computed right at a precision not seen before (empty cache)."""
    from symhx.forcing import rawmp

    monkeypatch.setattr(rawmp, "_SQRT_PI_CACHE", {})
    pt = (0.3, 0.2, 1.0, None, 1.0)
    args = tuple(_fr(v) for v in pt)
    for dps in (23, 23, 61):
        val = single_mp_fast(*args, dps, "p")
        obj, prec = _object_code(args, "p", dps)
        with mpmath.workdps(120), thread_mp().workdps(120):
            assert abs(val / obj - 1) < mpmath.mpf(2) ** (-prec + 8), dps
            assert abs(val / eq27_value(*pt, "p", dps) - 1) < mpmath.mpf(10) ** -dps
    assert len(rawmp._SQRT_PI_CACHE) == 2


def test_erf_raw_is_within_one_ulp_of_prec():
    """The documented accuracy of the erf helper: erf(u) to ``prec`` bits (within one unit of
    the last bit) for u from 0.01 to 60 and several precisions, against mpmath at 3x the
    precision."""
    from symhx.forcing.rawmp import _erf_raw

    lm = mpmath.libmp
    for prec in (60, 120, 200, 400):
        # and u just below the point where erf(u) rounds to 1 at prec bits (u^2 log2(e) ~ prec)
        edge = [math.sqrt((prec + k) / 1.4426950408889634) for k in (-2.5, -1, 0.5, 2)]
        for uf in (0.013, 0.7, 1.9, 2.1, 3.3, 5.0, 7.5, 9.9, 12.5, 17.0, 23.0, 31.0, 60.0, *edge):
            u = lm.from_float(uf)
            got = mpmath.mp.make_mpf(_erf_raw(u, prec))  # exact, no rounding
            with mpmath.workprec(3 * prec), thread_mp().workprec(3 * prec):
                ref = mpmath.erf(mpmath.mpf(uf))
                assert abs(got - ref) <= mpmath.mpf(2) ** (-prec) * abs(ref), (prec, uf)


# ---- "the same operations, roundings and precisions as the mpf-object code", bit for bit
# (where both use mpmath's erf series: u, v < 2, so that _erf_raw is mpmath.erf)
BIT_POINTS = [(0.3, None, 1.0, None, 1.0), (0.2, 0.7, 0.8, 1.7, 0.6), (0.9, 0.35, 1.3, 0.9, 2.0),
              (0.45, 0.45, 2.0, 1.0, 1.0), (0.6, 1.5, 1.0, 3.0, 4.0), (1.7, 0.25, 1.1, None, 0.9)]


def _raw(v):
    return None if v is None else mpmath.libmp.from_float(v)


@pytest.mark.parametrize("prec", [53, 113, 200])
@pytest.mark.parametrize("pt", BIT_POINTS)
def test_raw_xy_and_closed_form_are_the_object_code_bit_for_bit(pt, prec):
    from symhx.forcing.rawmp import _raw_p_parts, from_xy_raw, raw_xy

    s0, s1, om, Om, d = pt
    x, y = raw_xy(_raw(s0), _raw(s0 if s1 is None else s1), _raw(om), _raw(Om), _raw(d), prec)
    with mpmath.workprec(prec), thread_mp().workprec(prec):
        xm, ym = mp_xy_forcing(s0, s1, om, Om, d)
        assert (x, y) == (xm._mpf_, ym._mpf_)
        nuv, b, r = _raw_p_parts(x, y, prec)
        # the mpf-object code of kernels_mp written out, operation for operation
        r_ = mpmath.sqrt(xm + ym)
        u, v = xm / r_, ym / r_
        b_ = v * mpmath.exp(-u * u) + u * mpmath.exp(-v * v)
        b_ += mpmath.sqrt(mpmath.pi) * u * v * (mpmath.erf(u) + mpmath.erf(v))
        uv, b_r = u * v, b_ / r_
        assert nuv == (-uv)._mpf_
        assert mpmath.libmp.mpf_div(b, r, prec, mpmath.libmp.round_nearest) == b_r._mpf_
        p = mp_p_from_xy(xm, ym)
        assert from_xy_raw(x, y, prec, "p", 12, False) == p
        assert from_xy_raw(x, y, prec, "logp", 12, False) == -uv + mpmath.log(b_r)
        # 1 - p formed directly (p near 1/2 here: nothing cancels)
        assert from_xy_raw(x, y, prec, "q", 12, True) == 1 - p
        assert from_xy_raw(x, y, prec, "logq", 12, True) == mpmath.log(1 - p)
        if p > 0.5:  # not planned as direct: the caller's adaptive 1 - p
            assert from_xy_raw(x, y, prec, "q", 12, False) is None
            assert from_xy_raw(x, y, prec, "logq", 12, False) is None
        else:
            assert from_xy_raw(x, y, prec, "q", 12, False) == 1 - p
            assert from_xy_raw(x, y, prec, "logq", 12, False) == mpmath.log(1 - p)


def test_raw_xy_resonance_and_default_omega():
    from symhx.forcing.rawmp import raw_xy

    one = mpmath.libmp.from_int(1)
    assert raw_xy(one, one, one, one, one, 60) is None  # omega == Omega
    x, y = raw_xy(one, one, one, None, one, 60)  # Omega**2 = 2: delta = -1
    assert (mpmath.mpf(x), mpmath.mpf(y)) == (0.25, 0.25)


def test_from_xy_raw_leaves_small_p_logs_and_deep_cancellation_to_the_caller():
    from symhx.forcing.rawmp import from_xy_raw

    prec = 120
    with mpmath.workprec(prec), thread_mp().workprec(prec):
        big, tiny = mpmath.mpf(40)._mpf_, mpmath.mpf("1e-10")._mpf_
        # p ~ 2e-9 < 2**-16: log(1 - p) is log1p(-p) of the caller
        assert from_xy_raw(big, big, prec, "logq", 12, False) is None
        assert from_xy_raw(big, big, prec, "q", 12, False) is not None
        # x = y = 1e-10: 1 - p ~ 1e-20 cancels ~66 bits; 12 guard digits allow 3.3 * 8 bits
        assert from_xy_raw(tiny, tiny, prec, "q", 12, True) is None
        assert from_xy_raw(tiny, tiny, prec, "logq", 12, True) is None
        # 30 guard digits allow 3.3 * 26 = 85.8 bits: taken, and right to its working bits
        q = from_xy_raw(tiny, tiny, prec, "q", 30, True)
        lq = from_xy_raw(tiny, tiny, prec, "logq", 30, True)
    with mpmath.workdps(80), thread_mp().workdps(80):
        ref_q = 1 - mp_p_from_xy(mpmath.mpf("1e-10"), mpmath.mpf("1e-10"))
        assert abs(q / ref_q - 1) < mpmath.mpf(2) ** (-prec + 70)
        assert abs(lq - mpmath.log(ref_q)) < mpmath.mpf(2) ** (-prec + 70)


def _units(value, ref, dps):
    """Relative error in units of ``10**-dps``."""
    with mpmath.workdps(dps + 60), thread_mp().workdps(dps + 60):
        return abs(value / ref - 1) * mpmath.mpf(10) ** dps


LOW_DPS_POINTS = [  # 53-bit sigma/sigma1 (4 sigma**2 rounds below 53 bits), omega < 1
    (0.1, None, 0.3, None, 1.0), (0.2, 0.7, 0.8, 1.7, 0.6), (0.3, 0.1, 0.7, None, 0.9),
    (0.1, 0.3, 1.3, 0.9, 2.0),
]


@pytest.mark.parametrize("dps", [1, 2, 3])
@pytest.mark.parametrize("pt", LOW_DPS_POINTS)
def test_low_dps_float_inputs_give_correct_digits(pt, dps):
    """dps 1-3 work below 53 bits: the roundings of 4 sigma**2 and of omega**2 - Omega**2 must
    still use a rounding mode (a dropped mode raised KeyError inside mpmath.libmp)."""
    sigma, sigma1, omega, Omega, d = pt
    p = symhx.impact_probability(sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=d, dps=dps)
    assert _units(p, eq27_p_or_q(*pt, "p", 60), dps) < 1


# sigma1 far from sigma, omega near Omega: the estimate with sigma1 = sigma sees E ~ 0.04,
# the true exponent is E = 5e13 (13 more guard digits needed)
TAIL_SIGMA1 = (5e-8, 1e-15, 1.0, 1.00000001, 1.0)


# omega**2 ~ 2 but Omega = 0.1: the estimate with Omega**2 = 2 sees E ~ 1e-17, the true E ~ 8e13
TAIL_OMEGA = (5e-8, None, 1.4142135623730951, 0.1, 1.0)


@pytest.mark.parametrize("dps", [15, 30])
@pytest.mark.parametrize("pt", [TAIL_SIGMA1, TAIL_OMEGA])
def test_far_tail_guard_uses_sigma1_and_Omega(pt, dps):
    """The precision plan must be made from the actual sigma1 and Omega: p = exp(-E) with
    E ~ 1e14 needs log10(E) guard digits, an estimate that drops sigma1 or Omega gives ~12
    and p then carries ~100 units of error at dps digits."""
    sigma, sigma1, omega, Omega, d = pt
    p = symhx.impact_probability(sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=d, dps=dps)
    assert _units(p, eq27_p_or_q(*pt, "p", dps + 60), dps) < 1


def _sigma_for_q_bits(bits):
    """sigma (omega = 1, Omega**2 = 2, d = 1: x = y = 1/(4 sigma**2)) with 1 - p ~ x y / 6
    = 2**-bits."""
    with mpmath.workdps(30), thread_mp().workdps(30):
        return float((mpmath.mpf(2) ** bits / 96) ** mpmath.mpf(0.25))


@pytest.mark.parametrize("dps", [10, 15, 20, 30])
@pytest.mark.parametrize("bits", [1072.2, 1072.9, 1100.0])
def test_one_minus_p_for_tiny_x_y_keeps_its_digits(bits, dps):
    """sigma ~ 1e80: x, y below the float range, the estimate floors x y at 1e-300 and plans
    ~301 cancelled digits while 1 - p ~ 2**-1072 .. 2**-1100 cancels up to 331: the a
    posteriori check (at most guard - 4 digits cancelled) must send these to the adaptive loop;
    a looser check returns 1 - p with fewer than dps correct digits."""
    sigma = _sigma_for_q_bits(bits)
    q = symhx.no_impact_probability(sigma, dps=dps)
    ref = eq27_p_or_q(sigma, None, 1.0, None, 1.0, "q", dps + 1100)
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert abs(-mpmath.log(ref, 2) - bits) < 0.01  # the point is where it was aimed
    assert _units(q, ref, dps) < 1


def _twin_cases(n, seed):
    """Seeded random one-component forcings (log-uniform sigma, sigma1/sigma, omega, Omega, d;
    Omega None in a quarter of them), each with a dps and a wanted quantity."""
    rng = np.random.default_rng(seed)
    cases = []
    for _ in range(n):
        s0 = float(10 ** rng.uniform(-2.3, 2.5))
        s1 = None if rng.random() < 0.3 else float(s0 * 10 ** rng.uniform(-3, 3))
        om = float(10 ** rng.uniform(-0.5, 0.5))
        Om = None if rng.random() < 0.25 else float(om * 10 ** rng.uniform(-0.6, 0.6))
        d = float(10 ** rng.uniform(-1, 1))
        cases.append(((s0, s1, om, Om, d), int(rng.choice([5, 15, 30, 60])),
                      WANTS[int(rng.integers(4))]))
    return cases


def _raw_route(pt, dps, want):
    """The raw-libmp twin, with the working precision of its plan (None: it declines)."""
    args = tuple(_fr(v) for v in pt)
    val = single_mp_fast(*args, dps, want)
    return None if val is None else (val, _object_code(args, want, dps)[1])


def _mpf_route(pt, dps, want):
    """The mpf-object twin (kernels_mp with the same plan) at the same working precision."""
    return _object_code(tuple(_fr(v) for v in pt), want, dps)


def _same_roundings(raw, obj, case):
    """Bit for bit where both use mpmath's erf series (erf arguments below 2), else within a
    few units of the last of the working bits (the raw erf takes 1 - erfc above 2)."""
    if raw is None:   # the raw route declines: the public path uses the object code itself
        return
    (val, prec), (ref, prec2) = raw, obj
    assert prec == prec2
    pt, dps, want = case
    with mpmath.workprec(80), thread_mp().workprec(80):
        x, y = eq27_xy(*pt)
        r = mpmath.sqrt(x + y)
        small_erf = x / r < 2 and y / r < 2
    if small_erf:
        assert val == ref, (val, ref)
        return
    with mpmath.workprec(prec + 60), thread_mp().workprec(prec + 60):
        scale = _scale(want, eq27_value(*pt, want, dps), pt, dps)
        diff = abs(val - ref) / scale
        assert diff < mpmath.mpf(2) ** (-prec + 12) * (1 + abs(eq27_value(*pt, "logp", dps))), (
            float(diff))


def test_raw_libmp_and_mpf_object_twins_on_seeded_cases():
    """Twins (tests/harness/twins.py): the raw-libmp route and the mpf-object route of the same
    precision plan, on 300 seeded random forcings, dps 5 to 60, every wanted quantity."""
    cases = _twin_cases(300, 20260628)
    assert check_twins(_raw_route, _mpf_route, cases, _same_roundings) == 300
    assert sum(_raw_route(*c) is not None for c in cases) > 200   # the raw route is exercised
