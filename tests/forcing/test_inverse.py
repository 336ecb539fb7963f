"""The inverse sigma(p) (``symhx.forcing.inverse``) against an independent bracketing root
(bisection in ``ln sigma``) of the completed-square closed form
(:func:`tests.reference.forcing.sigma_root`), round trips through the references, both tails,
scales far from ``d``, far outside float64, arrays, symbolic targets and every refusal."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from tests.harness.errors import assert_refuses
from tests.reference.forcing import (
    forcing_dp,
    forcing_values,
    quadrature_values,
    sigma_root,
    three_gl_p,
)
from tests.reference.mp import rel_err

DPS = 20


def tol(dps=DPS):
    return mpmath.mpf(10) ** -dps


EPS = np.finfo(float).eps


# ----------------------------------------------------------------------------- inverse
@pytest.mark.parametrize("p", [1e-300, 1e-30, 1e-10, 0.01, 0.5, 0.9, 1 - 1e-9, 1 - 1e-15])
def test_inverse_round_trip_float(p):
    s = F.sigma_for_impact_probability(p)
    if p <= 0.5:
        assert rel_err(F.impact_probability(s), p) < 1e-12 + 8 * EPS * abs(math.log(p))
    else:
        assert rel_err(F.no_impact_probability(s), 1 - p) < 1e-12


def test_inverse_mpmath_and_arrays():
    with mpmath.workdps(60), thread_mp().workdps(60):
        for p in ("1e-400", "1e-20", "0.3", "0.999999"):
            s = F.sigma_for_impact_probability(p, dps=40, Omega=1.9, d=0.5)
            back = F.impact_probability(s, Omega=1.9, d=0.5, dps=45)
            if mpmath.mpf(p) < 0.5:
                assert rel_err(back, mpmath.mpf(p)) < mpmath.mpf(10) ** -37
            else:
                assert rel_err(1 - back, 1 - mpmath.mpf(p)) < mpmath.mpf(10) ** -33
    arr = F.sigma_for_impact_probability(np.array([1e-5, 0.2, 0.7]))
    assert arr.shape == (3,) and np.all(np.diff(arr) > 0)


def test_inverse_fixed_sigma1_and_components():
    s = F.sigma_for_impact_probability(0.3, sigma1=0.2)
    assert rel_err(F.impact_probability(s, sigma1=0.2), 0.3) < 1e-13
    with pytest.raises(ValueError, match="not reachable"):
        # with sigma1 fixed, p(sigma0 -> 0) = P(R1 > 1) = exp(-1/(4 * 0.4**2)) ~ 0.21
        F.sigma_for_impact_probability(0.1, sigma1=0.4)
    s2 = F.sigma_for_impact_probability(1e-6, Omega=[1.5, 2.5])
    assert rel_err(F.impact_probability(s2, Omega=[1.5, 2.5]), 1e-6) < 1e-12
    with pytest.raises(ValueError, match="p must be in"):
        F.sigma_for_impact_probability(np.array([0.5, 1.0]))


def test_inverse_bad_targets():
    for p in (0, 1, -0.5, 1.5, float("nan")):
        with pytest.raises(ValueError, match="p"):
            F.sigma_for_impact_probability(p)
    with pytest.raises(ValueError, match=r"p must be in \(0, 1\).*index 1"):
        F.sigma_for_impact_probability([0.5, 1.0])
    with pytest.raises(TypeError, match="p"):
        F.sigma_for_impact_probability(True)
    with pytest.raises(ValueError, match="rounds to"):
        F.sigma_for_impact_probability("1e-400")


@pytest.mark.parametrize("target", ["1e-300", "1e-40", "0.001", "0.5", "0.999", "1 - 1e-30"])
def test_inverse_against_independent_quadrature(target):
    with mpmath.workdps(60), thread_mp().workdps(60):
        pt = (1 - mpmath.mpf("1e-30")) if target == "1 - 1e-30" else mpmath.mpf(target)
    s = F.sigma_for_impact_probability(pt, dps=DPS)
    p, q, dp = quadrature_values(s, None, 1, None, 1, 2 * DPS + 10)
    with mpmath.workdps(2 * DPS + 10), thread_mp().workdps(2 * DPS + 10):
        # sigma is correct to dps digits, so p(sigma) is within kappa * 10**-dps of the target
        # (kappa = |d ln p/d ln sigma|, or of 1 - p in the upper half)
        if pt <= 0.5:
            kappa = s * dp / p
            assert rel_err(p, pt) < 2 * kappa * mpmath.mpf(10) ** -DPS
        else:
            kappa = s * dp / q
            assert rel_err(q, 1 - pt) < 2 * kappa * mpmath.mpf(10) ** -DPS


@pytest.mark.parametrize("p", ["1e-250", "1e-30", "1e-5", "0.3", "0.5", "0.7", "0.999999"])
def test_inverse_float_and_mp_against_bracketing_root(p):
    want = sigma_root(p)
    got = F.sigma_for_impact_probability(float(p))
    want_f = sigma_root(Fraction(float(p)))  # the float's exact binary value
    assert isinstance(got, float) and rel_err(got, want_f) < 1e-13, (p, got)
    gm = F.sigma_for_impact_probability(p, dps=DPS)
    assert rel_err(gm, want) <= tol(), (p, mpmath.nstr(rel_err(gm, want), 3))
    # round trip through the reference
    r = forcing_values(gm)
    with mpmath.workdps(3 * DPS), thread_mp().workdps(3 * DPS):
        pt = mpmath.mpf(p)
        kappa = gm * forcing_dp(gm) / (r[0] if pt <= 0.5 else r[1])
        err = rel_err(r[0], pt) if pt <= 0.5 else rel_err(r[1], 1 - pt)
        assert err <= 3 * abs(kappa) * tol()


@pytest.mark.parametrize("p", ["1e-400", "1e-2000", "1 - 1e-20", "1 - 1e-60"])
def test_inverse_far_outside_float64(p):
    """The bisection start of the mpmath path (no float64 start exists)."""
    with mpmath.workdps(100), thread_mp().workdps(100):
        pt = 1 - mpmath.mpf(p[4:]) if p.startswith("1 - ") else mpmath.mpf(p)
    target = pt if not p.startswith("1 - ") else Fraction(1) - Fraction(p[4:])
    want = sigma_root(pt, work=120)
    gm = F.sigma_for_impact_probability(target if isinstance(target, Fraction) else p, dps=DPS)
    assert rel_err(gm, want) <= tol(), (p, mpmath.nstr(rel_err(gm, want), 3))


def test_inverse_other_parameters():
    # fixed sigma1 = 0.3: p(sigma) > P(R1 > 1) = exp(-1/0.36) = 0.062
    for p, kw in [("0.1", {"sigma1": "0.3"}), ("0.8", {"sigma1": "0.3"}),
                  ("0.2", {"omega": "1.3", "Omega": "2.5", "d": "1.7"}),
                  ("1e-8", {"Omega": "0.5", "d": "0.6"}),
                  # roots far from the paper's (tied, Omega**2 = 2) root: the float start of the
                  # mpmath path must use the same sigma1 and Omega
                  ("0.0623", {"sigma1": "0.3"}), ("0.9", {"Omega": "1.0001"})]:
        want = sigma_root(p, kw.get("sigma1"), kw.get("omega", 1), kw.get("Omega"),
                         kw.get("d", 1))
        assert rel_err(F.sigma_for_impact_probability(p, **kw, dps=DPS), want) <= tol(), (p, kw)
        if p in ("0.0623", "0.9"):  # ill-conditioned in float64 (p nearly flat in sigma)
            continue
        kf = {k: float(v) for k, v in kw.items()}
        assert rel_err(F.sigma_for_impact_probability(float(p), **kf), want) < 1e-13, (p, kw)


def test_inverse_arrays():
    ps = np.array([[1e-10, 0.2], [0.6, 0.99]])
    out = F.sigma_for_impact_probability(ps)
    assert out.shape == (2, 2) and out.dtype == float
    for idx in np.ndindex(ps.shape):
        assert rel_err(out[idx], sigma_root(repr(float(ps[idx])))) < 1e-13
    om = F.sigma_for_impact_probability(["1e-10", Fraction(3, 5)], dps=DPS)
    assert om.shape == (2,) and om.dtype == object
    assert rel_err(om[1], sigma_root(Fraction(3, 5))) <= tol()
    with pytest.raises(ValueError, match=r"p must be in \(0, 1\), got 1.0 at index 1"):
        F.sigma_for_impact_probability([0.5, 1.0])
    with pytest.raises(ValueError, match=r"got 1.5 at index \(1, 0\)"):
        F.sigma_for_impact_probability([[0.5, 0.2], [1.5, 0.1]])
    with pytest.raises(ValueError, match=r"must be in \(0, 1\), got '2' at index 1"):
        F.sigma_for_impact_probability(["0.5", "2"], dps=DPS)
    with pytest.raises(ValueError, match=r"at index \(0, 1\)"):
        F.sigma_for_impact_probability([["0.5", "0"]], dps=DPS)


def test_inverse_bad_and_unreachable_targets():
    assert_refuses(F.sigma_for_impact_probability, 0, arg="p", value="got 0",
                   allowed="in (0, 1)")
    assert_refuses(F.sigma_for_impact_probability, "1", dps=DPS, arg="p", value="'1'",
                   allowed="in (0, 1)")
    with pytest.raises(ValueError, match=r"rounds to 0\.0 in float64; use dps="):
        F.sigma_for_impact_probability("1e-400")
    with pytest.raises(ValueError, match=r"rounds to 1\.0 in float64"):
        F.sigma_for_impact_probability("0.99999999999999999999")
    # fixed sigma1: p(sigma) >= P(R1 > d) = exp(-1/(4 sigma1**2)) = exp(-25) for sigma1 = 0.1
    with pytest.raises(ValueError, match=r"p = 1e-12 is not reachable"):
        F.sigma_for_impact_probability(1e-12, sigma1=0.1)
    with pytest.raises(ValueError, match="is not reachable for these parameters"):
        F.sigma_for_impact_probability("1e-400", sigma1="0.1", dps=DPS)
    s = F.sigma_for_impact_probability(1e-10, sigma1=0.1)  # reachable: above exp(-25)
    assert rel_err(s, sigma_root("1e-10", 0.1)) < 1e-13
    for name in ("sigma1", "omega", "Omega", "d"):
        assert_refuses(F.sigma_for_impact_probability, 0.5, **{name: np.array([1.5, 2.5])},
                       exc=TypeError, arg=name, value="ndarray",
                       allowed="a scalar for the inverse")
    with pytest.raises(TypeError, match="omega must be a scalar"):
        F.sigma_for_impact_probability(0.5, omega=[1.0, 2.0])
    import sympy

    s = F.sigma_for_impact_probability(sympy.sqrt(2) / 4, dps=DPS)
    with mpmath.workdps(60), thread_mp().workdps(60):
        assert rel_err(s, sigma_root(mpmath.sqrt(2) / 4)) <= tol()


def test_inverse_several_components_round_trip():
    """Round trip through the independent two-component quadrature (kappa < 3 here)."""
    sm = F.sigma_for_impact_probability("0.2", Omega=["1.7", "2.2"], d="1.2", dps=10)
    sf = F.sigma_for_impact_probability(0.2, Omega=[1.7, 2.2], d=1.2)
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert rel_err(three_gl_p(sm, ["1.7", "2.2"], "1.2", 40), "0.2") <= 3 * tol(10)
        assert rel_err(three_gl_p(sf, ["1.7", "2.2"], "1.2", 40), "0.2") <= 1e-14
    sf = F.sigma_for_impact_probability(0.2, sigma1=[0.3, 0.4], Omega=[1.7, 2.2])
    assert rel_err(F.impact_probability(sf, sigma1=[0.3, 0.4], Omega=[1.7, 2.2]), 0.2) < 1e-13


# The float64 accuracy of the inverse (documented: relative 1e-14 where p(sigma) is well
# conditioned), both tails, scales away from 1, fixed sigma1, other frequencies. The reference is
# the bisection root of the independent closed form for the float inputs' exact binary values.
_FLOAT_PS = [1e-300, 1e-50, 1e-8, 0.05, 0.5, 0.65, 0.999999, 1 - 1e-12]


@pytest.mark.parametrize("kw", [{}, {"d": 1e8}, {"d": 1e-8}, {"sigma1": 0.05},
                                {"omega": 0.5, "Omega": 3.0}])
def test_inverse_float_accuracy_grid(kw):
    args = [Fraction(kw[k]) if k in kw else v
            for k, v in (("sigma1", None), ("omega", 1), ("Omega", None), ("d", 1))]
    for p in _FLOAT_PS:
        if "sigma1" in kw and p < 1e-43:  # below P(R1 > 1) = exp(-100): not reachable
            assert_refuses(F.sigma_for_impact_probability, p, **kw, arg="p", value=repr(p),
                           allowed="not reachable for these parameters (sigma1 fixed?)")
            continue
        got = F.sigma_for_impact_probability(p, **kw)
        want = sigma_root(Fraction(p), *args, work=32)
        assert isinstance(got, float) and rel_err(got, want) < 1e-14, (p, kw, rel_err(got, want))


def test_inverse_float_roots_far_from_d():
    """Roots at sigma ~ 1e-200 d (omega**2 - Omega**2 ~ 1e-200): the bracket steps double."""
    for p, om in ((0.5, 1e-100), (1e-10, 1e-100), (0.5, 1e-150)):  # 1e-150: ln sigma = -690
        got = F.sigma_for_impact_probability(p, omega=om, Omega=2 * om)
        want = sigma_root(Fraction(p), None, Fraction(om), Fraction(2 * om), work=32)
        assert rel_err(got, want) < 1e-13, (p, om, rel_err(got, want))
    for p in ("0.5", "1e-10"):
        gm = F.sigma_for_impact_probability(p, omega="1e-100", Omega="2e-100", dps=30)
        assert rel_err(gm, sigma_root(p, None, "1e-100", "2e-100", work=70)) <= tol(30)
    # root at ln sigma = 705 (d = 1e303): the search is clipped at the float64 range (a step
    # to 712 would overflow)
    got = F.sigma_for_impact_probability(1 - 1e-15, d=1e303)
    assert rel_err(got, sigma_root(Fraction(1 - 1e-15), d=Fraction(1e303), work=32)) < 1e-13


# mpmath path: both tails (the bisection start below 1e-300 and for 1 - p below 1e-16), scales
# 1e+-8 and 1e100, frequencies near resonance, fixed sigma1, dps 5 / 15 / 45.
_MP_CASES = [
    ("1e-400", {"d": "1e8"}, 15), ("1e-400", {"d": "1e-8"}, 45), ("1e-400", {"d": "1e100"}, 5),
    ("1e-12", {"d": "1e8"}, 45), ("0.3", {"d": "1e-8"}, 15), ("0.9", {"d": "1e8"}, 5),
    ("1 - 1e-25", {"d": "1e-8"}, 15), ("1 - 1e-25", {"d": "1e100"}, 45),
    ("0.5", {"Omega": "1.000001"}, 45), ("1e-20", {"Omega": "1.000001"}, 15),
    ("0.98", {"sigma1": "3"}, 15), ("1e-6", {"sigma1": "1e-3"}, 45),
    ("1e-350", {"sigma1": "0.01"}, 15),
]


@pytest.mark.parametrize("p, kw, dps", _MP_CASES)
def test_inverse_mp_scales_tails_and_precisions(p, kw, dps):
    with mpmath.workdps(dps + 60), thread_mp().workdps(dps + 60):
        pt = 1 - mpmath.mpf(p[4:]) if p.startswith("1 - ") else mpmath.mpf(p)
    target = Fraction(1) - Fraction(p[4:]) if p.startswith("1 - ") else p
    want = sigma_root(pt, kw.get("sigma1"), kw.get("omega", 1), kw.get("Omega"), kw.get("d", 1),
                     work=dps + 40)
    got = F.sigma_for_impact_probability(target, **kw, dps=dps)
    assert isinstance(got, mpmath.mpf)
    assert rel_err(got, want) <= tol(dps), (p, kw, dps, mpmath.nstr(rel_err(got, want), 3))


def test_inverse_mp_unreachable_messages(monkeypatch):
    assert_refuses(F.sigma_for_impact_probability, "1.2345678901234e-400", sigma1="0.1", dps=10,
                   arg="p", value="1.23456789e-400",
                   allowed="not reachable for these parameters (no root with |ln(sigma/d)| "
                           "< 32767)")
    import symhx.forcing.inverse as inv

    monkeypatch.setattr(inv, "_bracket", lambda *args: None)  # as if no root within the range
    assert_refuses(F.sigma_for_impact_probability, Fraction(1) - Fraction(1, 10**400), dps=10,
                   arg="p", value="1 - p = 1.0e-400",
                   allowed="not reachable for these parameters (no root with |ln(sigma/d)| "
                           "< 32767)")


def test_inverse_mp_several_components_with_sigma1():
    """sigma1 given per component (a list): mpmath against float64 and the round trip."""
    kw = {"sigma1": ["0.3", "0.4"], "Omega": ["1.7", "2.2"]}
    sm = F.sigma_for_impact_probability("0.2", **kw, dps=12)
    sf = F.sigma_for_impact_probability(0.2, sigma1=[0.3, 0.4], Omega=[1.7, 2.2])
    assert isinstance(sm, mpmath.mpf) and rel_err(sm, sf) < 1e-11
    assert rel_err(F.impact_probability(sm, **kw, dps=12), "0.2") <= 3 * tol(12)
    s1 = F.sigma_for_impact_probability("0.2", sigma1=["0.3"], Omega=["1.7"], dps=20)
    assert rel_err(s1, sigma_root("0.2", "0.3", 1, "1.7", work=60)) <= tol(20)


def test_inverse_symbolic_targets_keep_their_digits():
    """A sympy irrational is evaluated to the digits the precision needs (of 1 - p near 1)."""
    import sympy

    s = F.sigma_for_impact_probability(sympy.sqrt(2) / 4, dps=60)
    with mpmath.workdps(120), thread_mp().workdps(120):
        want = sigma_root(mpmath.sqrt(2) / 4, work=100)
    assert rel_err(s, want) <= tol(60)
    s = F.sigma_for_impact_probability(1 - sympy.exp(-100), dps=20)  # 1 - p = 3.7e-44
    with mpmath.workdps(120), thread_mp().workdps(120):
        want = sigma_root(1 - mpmath.exp(-100), work=120)
    assert rel_err(s, want) <= tol(20)
    s = F.sigma_for_impact_probability(1 - sympy.exp(-20))
    with mpmath.workdps(120), thread_mp().workdps(120):
        pt = 1 - mpmath.exp(-20)
        want = sigma_root(Fraction(float(pt)), work=40)  # the float nearest to p
    assert isinstance(s, float) and rel_err(s, want) < 1e-14
    with mpmath.workdps(40), thread_mp().workdps(40):
        nearest = float(mpmath.pi / 10)
    assert F.sigma_for_impact_probability(sympy.pi / 10) == F.sigma_for_impact_probability(nearest)


@pytest.mark.parametrize("dps", [None, 20])
def test_inverse_bad_targets_name_p(dps):
    import sympy

    for bad, exc, value, allowed in [("abc", ValueError, None, "a number such as"),
                                     (float("nan"), ValueError, "nan", "finite"),
                                     (True, TypeError, "bool", "a real number"),
                                     (sympy.Symbol("x"), TypeError, None, "a finite real number"),
                                     (2, ValueError, "got 2", "in (0, 1)")]:
        assert_refuses(F.sigma_for_impact_probability, bad, dps=dps, exc=exc, arg="p",
                       value=value, allowed=allowed)
    if dps is None:  # the float64 array path converts p once (float_arg)
        with pytest.raises(TypeError, match=r"p must hold real numbers, got an array of dtype"):
            F.sigma_for_impact_probability([0.5, "x"])


def test_inverse_bracket_contract():
    """The doubling search returns lo < hi with f(lo) <= 0 <= f(hi) in both directions, stays
    inside the clip, and gives None when f keeps its sign (or is NaN)."""
    from symhx.forcing.inverse import _bracket

    for x, r in [(0.0, 5.5), (0.0, -5.5), (2.0, 2.5), (3.0, -700.25), (-20.0, 600.5)]:
        br = _bracket(lambda t, r=r: t - r, x, 12)
        assert br is not None and br[0] < br[1] and br[0] - r <= 0 <= br[1] - r, (x, r, br)
        assert br[1] - br[0] <= max(1.0, abs(r - x)), (x, r, br)  # the last (doubled) step
    assert _bracket(lambda t: t - 706.0, 690.0, 12, (-744.0, 709.0)) == (705.0, 709.0)
    assert _bracket(lambda t: t - 720.0, 690.0, 12, (-744.0, 709.0)) is None
    assert _bracket(lambda t: 1.0, 0.0, 12) is None
    assert _bracket(lambda t: float("nan"), 0.0, 12) is None


@pytest.mark.parametrize("dps", [5, 15, 33, 60])
def test_inverse_mp_value_is_rounded_to_dps(dps):
    """ARCHITECTURE.md: an mpmath result is rounded once, at the end, to ``dps`` digits (the
    guard digits of the secant polish are not handed out): ``s == +s`` at ``dps``."""
    for p, kw in [("1e-30", {}), ("0.3", {}), ("0.9", {"d": "2"}), (1e-5, {"Omega": "1.7"}),
                  ("0.2", {"Omega": ["1.7", "2.2"]}), ("1e-400", {})]:
        s = F.sigma_for_impact_probability(p, **kw, dps=dps)
        assert isinstance(s, mpmath.mpf)
        with mpmath.workdps(dps), thread_mp().workdps(dps):
            assert s == +s, (p, kw, dps)
