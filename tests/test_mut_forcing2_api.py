"""dp/dsigma, the inverse sigma(p) and the theory chain against independent references.

References: the completed-square closed form of ``test_mut_forcing2_paths`` (checked there
against ``mpmath.quad``); derivatives by ``mpmath.diff`` of it (numerical differentiation of an
independent formula at high precision) or by the elementary one-Rayleigh limit; the inverse by
an independent bracketing root (bisection in ``ln sigma``)
of the reference forward map, and by the round trip through the reference. Relative errors are
computed inside ``workdps`` above the claimed precision.
"""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx
from symhx import forcing as F
from tests.test_mut_forcing2_paths import DPS, _mp, _p_sq, ref, ref_dp, ref_three_gl, rel, squares


def tol(dps=DPS):
    return mpmath.mpf(10) ** -dps


# ------------------------------------------------------------------ derivative
@pytest.mark.parametrize("sigma1", [None, "0.25", "4"])
def test_dp_mpmath_on_a_log_grid(sigma1):
    for s in np.logspace(-2, 2, 9):
        sd = repr(float(s))
        want = ref_dp(sd, sigma1)
        got = F.dp_dsigma(sd, sigma1=sigma1, dps=DPS)
        assert isinstance(got, mpmath.mpf)
        assert rel(got, want) <= tol(), (sd, sigma1, mpmath.nstr(rel(got, want), 3))
        # rounded once to dps digits
        assert got._mpf_[1].bit_length() <= mpmath.workdps(DPS)(lambda: mpmath.mp.prec)()


def test_dp_mpmath_other_parameters_and_extremes():
    for sigma, kw in [("0.07", {"omega": "1.3", "Omega": "1.7", "d": "1.9"}),
                      ("0.7", {"sigma1": "0.2", "omega": "0.6", "Omega": "2.5", "d": "0.45"}),
                      ("1e-7", {}), ("3e-6", {"sigma1": "0.5"}), ("1e6", {}),
                      (Fraction(1, 3), {"sigma1": Fraction(1, 7)}), (0.3, {}),
                      (0.3, {"sigma1": 0.5})]:
        want = ref_dp(sigma, kw.get("sigma1"), kw.get("omega", 1), kw.get("Omega"),
                      kw.get("d", 1))
        got = F.dp_dsigma(sigma, **kw, dps=DPS)
        assert rel(got, want) <= tol(), (sigma, kw, mpmath.nstr(rel(got, want), 3))


def test_dp_float64_vectorised_against_reference():
    s = np.array([0.03, 0.05, 0.3, 1.0, 7.0, 80.0])
    d = np.array([[1.0], [1.7]])
    got = F.dp_dsigma(s, d=d)
    assert got.shape == (2, 6) and got.dtype == float
    got1 = F.dp_dsigma(s, sigma1=0.4, Omega=2.0, d=d)
    for i, dv in enumerate(d[:, 0]):
        for j, sv in enumerate(s):
            assert rel(got[i, j], ref_dp(float(sv), None, 1, None, float(dv))) < 1e-12
            assert rel(got1[i, j], ref_dp(float(sv), 0.4, 1, 2.0, float(dv))) < 1e-12
    sc = F.dp_dsigma(0.3)
    assert isinstance(sc, float) and rel(sc, ref_dp(0.3)) < 1e-13
    assert F.dp_dsigma(np.array([])).shape == (0,)


def _one_rayleigh_dp(sigma, d=1):
    """``d/dsigma exp(-d**2/(4 sigma**2)) = d**2/(2 sigma**3) exp(-d**2/(4 sigma**2))``."""
    with mpmath.workdps(40):
        s, dd = _mp(sigma), _mp(d)
        return dd * dd / (2 * s**3) * mpmath.exp(-dd * dd / (4 * s * s))


def test_dp_float64_fallback_where_the_kernel_overflows():
    """Inputs whose float kernel over/underflows: the elementary one-Rayleigh limit."""
    # sigma1 -> 0 (y overflows): p = P(R0 > d), partial derivative at fixed sigma1
    got = F.dp_dsigma(np.array([0.5, 0.3]), sigma1=np.array([1e-170, 0.5]))
    assert rel(got[0], _one_rayleigh_dp(0.5)) < 1e-14
    assert rel(got[1], ref_dp(0.3, 0.5)) < 1e-12
    # huge |omega**2 - Omega**2| (tied scales): s1 -> 0 again, total derivative
    got = F.dp_dsigma(0.4, omega=1e200)
    assert isinstance(got, float) and rel(got, _one_rayleigh_dp(0.4)) < 1e-14
    got = F.dp_dsigma(np.array([0.4, 0.6]), omega=1e200, Omega=3.0, d=np.array([1.0, 1.2]))
    assert rel(got[0], _one_rayleigh_dp(0.4)) < 1e-14
    assert rel(got[1], _one_rayleigh_dp(0.6, 1.2)) < 1e-14
    got = F.dp_dsigma(0.5, sigma1=2.0, Omega=1e200, d=1.5)
    assert rel(got, _one_rayleigh_dp(0.5, 1.5)) < 1e-14
    # the float kernel's over/underflow stays silent even where numpy is told to raise
    with np.errstate(all="raise"):
        assert F.dp_dsigma(1e160) == 0.0  # x, y underflow; dp ~ 1e-801
        assert F.dp_dsigma(9.43e-115, sigma1=2.01e-147) == 0.0  # y overflows, E ~ 3e227
        assert rel(F.dp_dsigma(0.5, sigma1=1e-170), _one_rayleigh_dp(0.5)) < 1e-14
    # exponent far beyond float64: exactly 0.0, no NaN
    assert F.dp_dsigma(1e-160) == 0.0
    out = F.dp_dsigma(np.array([1e-160, 0.3]))
    assert out[0] == 0.0 and rel(out[1], ref_dp(0.3)) < 1e-12


def _ref_three_p(sigma, Oms, d, work):
    """P(R0 + R1 + R2 > d) with all scales proportional to sigma (Gauss-Legendre over R2)."""
    return ref_three_gl(sigma, Oms, d, work, 12, 24)


def test_dp_several_components():
    """Central difference (h = 1e-12, 60 digits) of an independent two-component quadrature."""
    Oms, d = ["1.7", "2.2"], "1.2"
    with mpmath.workdps(60):
        s = mpmath.mpf("0.35")
        h = mpmath.mpf("1e-12")
        want = (_ref_three_p(s + h, Oms, d, 60) - _ref_three_p(s - h, Oms, d, 60)) / (2 * h)
    got = F.dp_dsigma("0.35", Omega=Oms, d=d, dps=DPS)
    assert rel(got, want) <= tol(DPS - 1), mpmath.nstr(rel(got, want), 3)
    gf = F.dp_dsigma(0.35, Omega=[1.7, 2.2], d=1.2)
    assert isinstance(gf, float) and rel(gf, want) < 1e-11
    ga = F.dp_dsigma(np.array([0.35, 0.35]), Omega=[1.7, 2.2], d=1.2)
    assert ga.shape == (2,) and ga.dtype == float and rel(ga[0], want) < 1e-11
    gm = F.dp_dsigma(np.array(["0.35"], dtype=object), Omega=Oms, d=d, dps=DPS)
    assert gm.shape == (1,) and gm.dtype == object and rel(gm[0], want) <= tol(DPS - 1)
    with pytest.raises(ValueError, match=r"^sigma1: dp_dsigma with several components supports "
                                         r"only sigma1=None \(all sigma_i = sigma\)$"):
        F.dp_dsigma(0.35, sigma1=0.2, Omega=[1.7, 2.2])


# ------------------------------------------------------------------ inverse
def _root_ref(p_target, sigma1=None, omega=1, Omega=None, d=1, work=60):
    """sigma with p(sigma) = p_target: bracketing root of the reference in ln sigma."""
    with mpmath.workdps(work):
        pt = _mp(p_target) if not isinstance(p_target, mpmath.mpf) else p_target
        upper = pt > 0.5
        lt = mpmath.log(1 - pt) if upper else mpmath.log(pt)

        def f(ls):
            S0, S1 = squares(mpmath.exp(ls), sigma1 if sigma1 is not None else mpmath.exp(ls),
                             omega, Omega)
            p = _p_sq(S0, S1, _mp(d))
            return (lt - mpmath.log(1 - p)) if upper else (mpmath.log(p) - lt)

        lo, hi = mpmath.mpf(-8), mpmath.mpf(6)
        for _ in range(200):
            if f(lo) < 0:
                break
            lo -= 4
        else:
            raise AssertionError("reference bracket: target not reachable")
        while f(hi) < 0:
            hi += 4
        while hi - lo > mpmath.mpf(10) ** (8 - work):  # bisection (f increases)
            mid = (lo + hi) / 2
            if f(mid) > 0:
                hi = mid
            else:
                lo = mid
        return mpmath.exp((lo + hi) / 2)


@pytest.mark.parametrize("p", ["1e-250", "1e-30", "1e-5", "0.3", "0.5", "0.7", "0.999999"])
def test_inverse_float_and_mp_against_bracketing_root(p):
    want = _root_ref(p)
    got = F.sigma_for_impact_probability(float(p))
    want_f = _root_ref(Fraction(float(p)))  # the float's exact binary value
    assert isinstance(got, float) and rel(got, want_f) < 1e-13, (p, got)
    gm = F.sigma_for_impact_probability(p, dps=DPS)
    assert rel(gm, want) <= tol(), (p, mpmath.nstr(rel(gm, want), 3))
    # round trip through the reference
    r = ref(gm)
    with mpmath.workdps(3 * DPS):
        pt = mpmath.mpf(p)
        kappa = gm * ref_dp(gm) / (r[0] if pt <= 0.5 else r[1])
        err = rel(r[0], pt) if pt <= 0.5 else rel(r[1], 1 - pt)
        assert err <= 3 * abs(kappa) * tol()


@pytest.mark.parametrize("p", ["1e-400", "1e-2000", "1 - 1e-20", "1 - 1e-60"])
def test_inverse_far_outside_float64(p):
    """The bisection start of the mpmath path (no float64 start exists)."""
    with mpmath.workdps(100):
        pt = 1 - mpmath.mpf(p[4:]) if p.startswith("1 - ") else mpmath.mpf(p)
    target = pt if not p.startswith("1 - ") else Fraction(1) - Fraction(p[4:])
    want = _root_ref(pt, work=120)
    gm = F.sigma_for_impact_probability(target if isinstance(target, Fraction) else p, dps=DPS)
    assert rel(gm, want) <= tol(), (p, mpmath.nstr(rel(gm, want), 3))


def test_inverse_other_parameters():
    # fixed sigma1 = 0.3: p(sigma) > P(R1 > 1) = exp(-1/0.36) = 0.062
    for p, kw in [("0.1", {"sigma1": "0.3"}), ("0.8", {"sigma1": "0.3"}),
                  ("0.2", {"omega": "1.3", "Omega": "2.5", "d": "1.7"}),
                  ("1e-8", {"Omega": "0.5", "d": "0.6"}),
                  # roots far from the paper's (tied, Omega**2 = 2) root: the float start of the
                  # mpmath path must use the same sigma1 and Omega
                  ("0.0623", {"sigma1": "0.3"}), ("0.9", {"Omega": "1.0001"})]:
        want = _root_ref(p, kw.get("sigma1"), kw.get("omega", 1), kw.get("Omega"),
                         kw.get("d", 1))
        assert rel(F.sigma_for_impact_probability(p, **kw, dps=DPS), want) <= tol(), (p, kw)
        if p in ("0.0623", "0.9"):  # ill-conditioned in float64 (p nearly flat in sigma)
            continue
        kf = {k: float(v) for k, v in kw.items()}
        assert rel(F.sigma_for_impact_probability(float(p), **kf), want) < 1e-13, (p, kw)


def test_inverse_arrays():
    ps = np.array([[1e-10, 0.2], [0.6, 0.99]])
    out = F.sigma_for_impact_probability(ps)
    assert out.shape == (2, 2) and out.dtype == float
    for idx in np.ndindex(ps.shape):
        assert rel(out[idx], _root_ref(repr(float(ps[idx])))) < 1e-13
    om = F.sigma_for_impact_probability(["1e-10", Fraction(3, 5)], dps=DPS)
    assert om.shape == (2,) and om.dtype == object
    assert rel(om[1], _root_ref(Fraction(3, 5))) <= tol()
    with pytest.raises(ValueError, match=r"p must be in \(0, 1\), got 1.0 at index 1$"):
        F.sigma_for_impact_probability([0.5, 1.0])
    with pytest.raises(ValueError, match=r"got 1.5 at index \(1, 0\)"):
        F.sigma_for_impact_probability([[0.5, 0.2], [1.5, 0.1]])
    with pytest.raises(ValueError, match=r"must be in \(0, 1\), got '2' at index 1$"):
        F.sigma_for_impact_probability(["0.5", "2"], dps=DPS)
    with pytest.raises(ValueError, match=r"at index \(0, 1\)$"):
        F.sigma_for_impact_probability([["0.5", "0"]], dps=DPS)


def test_inverse_bad_and_unreachable_targets():
    with pytest.raises(ValueError, match=r"^p must be in \(0, 1\), got 0$"):
        F.sigma_for_impact_probability(0)
    with pytest.raises(ValueError, match=r"^p must be in \(0, 1\), got '1'$"):
        F.sigma_for_impact_probability("1", dps=DPS)
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
    assert rel(s, _root_ref("1e-10", 0.1)) < 1e-13
    for name in ("sigma1", "omega", "Omega", "d"):
        with pytest.raises(TypeError, match=f"^{name} must be a scalar for the inverse, got "
                                            "ndarray$"):
            F.sigma_for_impact_probability(0.5, **{name: np.array([1.5, 2.5])})
    with pytest.raises(TypeError, match="omega must be a scalar"):
        F.sigma_for_impact_probability(0.5, omega=[1.0, 2.0])
    import sympy

    s = F.sigma_for_impact_probability(sympy.sqrt(2) / 4, dps=DPS)
    with mpmath.workdps(60):
        assert rel(s, _root_ref(mpmath.sqrt(2) / 4)) <= tol()


def test_inverse_several_components_round_trip():
    """Round trip through the independent two-component quadrature (kappa < 3 here)."""
    sm = F.sigma_for_impact_probability("0.2", Omega=["1.7", "2.2"], d="1.2", dps=10)
    sf = F.sigma_for_impact_probability(0.2, Omega=[1.7, 2.2], d=1.2)
    with mpmath.workdps(40):
        assert rel(_ref_three_p(sm, ["1.7", "2.2"], "1.2", 40), "0.2") <= 3 * tol(10)
        assert rel(_ref_three_p(sf, ["1.7", "2.2"], "1.2", 40), "0.2") <= 1e-14
    sf = F.sigma_for_impact_probability(0.2, sigma1=[0.3, 0.4], Omega=[1.7, 2.2])
    assert rel(F.impact_probability(sf, sigma1=[0.3, 0.4], Omega=[1.7, 2.2]), 0.2) < 1e-13


# ------------------------------------------------------------------ theory chain
def test_theory_curve_is_the_composition_with_reference_p():
    sig = np.array([[0.05, 0.12], [0.3, 2.0]])
    tc = F.theory_curve(sig, N=41, d="1.1", Omega="1.6", dps=25)
    assert tc.N == 41 and tc.sigma.shape == tc.p.shape == tc.mean.shape == (2, 2)
    assert tc.mode.dtype == np.int64
    for idx in np.ndindex(sig.shape):
        p = ref(float(sig[idx]), None, 1, "1.6", "1.1", 25)[0]
        assert rel(tc.p[idx], p) < 1e-15
        with mpmath.workdps(25):
            p25 = +p
        assert rel(tc.mean[idx], symhx.mean(41, p25, dps=25)) < 1e-15
        assert tc.mode[idx] == symhx.mode(41, p25)
    tc = F.theory_curve(0.2, N=11, sigma1=0.25, space="eq41")
    p = ref(0.2, 0.25, dps=30)[0]
    with mpmath.workdps(30):
        p30 = +p
    assert tc.p.shape == (1,) and rel(tc.p[0], p) < 1e-15
    assert rel(tc.mean[0], symhx.mean(11, p30, space="eq41", dps=30)) < 1e-15
    assert tc.mode[0] == symhx.mode(11, p30, space="eq41") != symhx.mode(11, p30)
    assert F.theory_curve(0.3).N == 101  # the paper's n = 100 pipes


def test_theory_curve_tiny_p_and_limits():
    # log p = -1/(8 sigma**2) + ...: below -2400 for sigma = 0.005 (not evaluated in mpmath,
    # also where mpmath refuses: sigma = 1e-160), and 1e-1000 > p > exp(-2400) for 0.0073
    tc = F.theory_curve([0.005, 0.02, 0.0073, 1e-160, 0.005], N=10**12)
    assert list(tc.p) == [0.0, pytest.approx(float(ref(0.02)[0]), rel=1e-15), 0.0, 0.0, 0.0]
    assert tc.p[1] > 0
    assert list(tc.mean[[0, 2, 3, 4]]) == [1.0] * 4 and list(tc.mode[[0, 2, 3, 4]]) == [1] * 4
    # the float pre-filter sees sigma1, Omega and d: none of these p is tiny
    for sigma, kw in [(1e-3, {"sigma1": 0.5}), (1e-3, {"Omega": 1.01}), (2e-4, {"d": 0.01})]:
        tc = F.theory_curve(sigma, N=11, **kw)
        want = ref(sigma, kw.get("sigma1"), 1, kw.get("Omega"), kw.get("d", 1))[0]
        assert 0 < tc.p[0] and rel(tc.p[0], want) < 1e-14, (sigma, kw)
    with pytest.raises(ValueError, match=r"^sigma must be > 0, got -1"):
        F.theory_curve(-1)
    for kw in [{"sigma1": np.array([0.1, 0.2])}, {"Omega": np.array([1.5, 2.5])}]:
        with pytest.raises(TypeError, match=r"^theory_curve: sigma1, omega, Omega and d must be "
                                            r"scalars$"):
            F.theory_curve(0.1, **kw)
    with pytest.raises(ValueError, match=r"^N must be <= THEORY_MAX_N = 10\*\*300, got "):
        F.theory_curve(0.1, N=10**300 + 1)
    with pytest.raises(ValueError, match="an integer of 301 digits"):
        F.theory_curve(0.1, N=10**300 + 1)
    assert F.theory_curve(0.1, N=10**30).N == 10**30
    with pytest.raises(TypeError, match=r"^theory_curve: sigma1, omega, Omega and d must be "
                                        r"scalars$"):
        F.theory_curve(0.1, d=[1.0, 2.0])


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
            with pytest.raises(ValueError, match=r"^p = 1e-(300|50) is not reachable for these "
                                                 r"parameters \(sigma1 fixed\?\)$"):
                F.sigma_for_impact_probability(p, **kw)
            continue
        got = F.sigma_for_impact_probability(p, **kw)
        want = _root_ref(Fraction(p), *args, work=32)
        assert isinstance(got, float) and rel(got, want) < 1e-14, (p, kw, rel(got, want))


def test_inverse_float_roots_far_from_d():
    """Roots at sigma ~ 1e-200 d (omega**2 - Omega**2 ~ 1e-200): the bracket steps double."""
    for p, om in ((0.5, 1e-100), (1e-10, 1e-100), (0.5, 1e-150)):  # 1e-150: ln sigma = -690
        got = F.sigma_for_impact_probability(p, omega=om, Omega=2 * om)
        want = _root_ref(Fraction(p), None, Fraction(om), Fraction(2 * om), work=32)
        assert rel(got, want) < 1e-13, (p, om, rel(got, want))
    for p in ("0.5", "1e-10"):
        gm = F.sigma_for_impact_probability(p, omega="1e-100", Omega="2e-100", dps=30)
        assert rel(gm, _root_ref(p, None, "1e-100", "2e-100", work=70)) <= tol(30)
    # root at ln sigma = 705 (d = 1e303): the search is clipped at the float64 range (a step
    # to 712 would overflow)
    got = F.sigma_for_impact_probability(1 - 1e-15, d=1e303)
    assert rel(got, _root_ref(Fraction(1 - 1e-15), d=Fraction(1e303), work=32)) < 1e-13


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
    with mpmath.workdps(dps + 60):
        pt = 1 - mpmath.mpf(p[4:]) if p.startswith("1 - ") else mpmath.mpf(p)
    target = Fraction(1) - Fraction(p[4:]) if p.startswith("1 - ") else p
    want = _root_ref(pt, kw.get("sigma1"), kw.get("omega", 1), kw.get("Omega"), kw.get("d", 1),
                     work=dps + 40)
    got = F.sigma_for_impact_probability(target, **kw, dps=dps)
    assert isinstance(got, mpmath.mpf)
    assert rel(got, want) <= tol(dps), (p, kw, dps, mpmath.nstr(rel(got, want), 3))


def test_inverse_mp_polishes_the_float_root(monkeypatch):
    """Where float64 has a root, the mpmath path starts from it: a few secant steps at the
    working precision (not a bracket and 60 bisections)."""
    import symhx.forcing.inverse as inv

    calls = []
    real = inv.evaluate

    def counting(fp, dps, want):
        calls.append(dps)
        return real(fp, dps, want)

    monkeypatch.setattr(inv, "evaluate", counting)
    for p in ("1e-250", "0.3", "0.9", Fraction(1) - Fraction(1, 10**15)):
        calls.clear()
        got = F.sigma_for_impact_probability(p, dps=30)
        assert rel(got, _root_ref(p, work=70)) <= tol(30)
        assert 0 < sum(d is not None for d in calls) <= 10, (p, calls)
    for p, kw in [("0.3", {"d": "1e8"}), ("0.1", {"sigma1": "0.3"}),
                  ("0.01", {"sigma1": "4", "d": "20"}),
                  ("0.2", {"omega": "1.3", "Omega": "1.000001"}),
                  ("0.2", {"sigma1": ["0.3", "0.4"], "Omega": ["1.7", "2.2"]})]:
        calls.clear()
        F.sigma_for_impact_probability(p, **kw, dps=12)
        assert 0 < sum(d is not None for d in calls) <= 10, (p, kw, calls)


def test_inverse_mp_unreachable_messages(monkeypatch):
    with pytest.raises(ValueError, match=r"^p = 1\.23456789e-400 is not reachable for these "
                                         r"parameters \(no root with \|ln\(sigma/d\)\| < "
                                         r"32767\)$"):
        F.sigma_for_impact_probability("1.2345678901234e-400", sigma1="0.1", dps=10)
    import symhx.forcing.inverse as inv

    monkeypatch.setattr(inv, "_bracket", lambda *args: None)  # as if no root within the range
    with pytest.raises(ValueError, match=r"^1 - p = 1\.0e-400 is not reachable for these "
                                         r"parameters \(no root with \|ln\(sigma/d\)\| < "
                                         r"32767\)$"):
        F.sigma_for_impact_probability(Fraction(1) - Fraction(1, 10**400), dps=10)


def test_inverse_mp_several_components_with_sigma1():
    """sigma1 given per component (a list): mpmath against float64 and the round trip."""
    kw = {"sigma1": ["0.3", "0.4"], "Omega": ["1.7", "2.2"]}
    sm = F.sigma_for_impact_probability("0.2", **kw, dps=12)
    sf = F.sigma_for_impact_probability(0.2, sigma1=[0.3, 0.4], Omega=[1.7, 2.2])
    assert isinstance(sm, mpmath.mpf) and rel(sm, sf) < 1e-11
    assert rel(F.impact_probability(sm, **kw, dps=12), "0.2") <= 3 * tol(12)
    s1 = F.sigma_for_impact_probability("0.2", sigma1=["0.3"], Omega=["1.7"], dps=20)
    assert rel(s1, _root_ref("0.2", "0.3", 1, "1.7", work=60)) <= tol(20)


def test_inverse_symbolic_targets_keep_their_digits():
    """A sympy irrational is evaluated to the digits the precision needs (of 1 - p near 1)."""
    import sympy

    s = F.sigma_for_impact_probability(sympy.sqrt(2) / 4, dps=60)
    with mpmath.workdps(120):
        want = _root_ref(mpmath.sqrt(2) / 4, work=100)
    assert rel(s, want) <= tol(60)
    s = F.sigma_for_impact_probability(1 - sympy.exp(-100), dps=20)  # 1 - p = 3.7e-44
    with mpmath.workdps(120):
        want = _root_ref(1 - mpmath.exp(-100), work=120)
    assert rel(s, want) <= tol(20)
    s = F.sigma_for_impact_probability(1 - sympy.exp(-20))
    with mpmath.workdps(120):
        pt = 1 - mpmath.exp(-20)
        want = _root_ref(Fraction(float(pt)), work=40)  # the float nearest to p
    assert isinstance(s, float) and rel(s, want) < 1e-14
    with mpmath.workdps(40):
        nearest = float(mpmath.pi / 10)
    assert F.sigma_for_impact_probability(sympy.pi / 10) == F.sigma_for_impact_probability(nearest)


@pytest.mark.parametrize("dps", [None, 20])
def test_inverse_bad_targets_name_p(dps):
    import sympy

    for bad, exc, msg in [("abc", ValueError, "p must be a number such as"),
                          (float("nan"), ValueError, "p must be finite, got nan"),
                          (True, TypeError, "p must be a real number, got bool"),
                          (sympy.Symbol("x"), TypeError, "p must be a finite real number"),
                          (2, ValueError, r"p must be in \(0, 1\), got 2$")]:
        with pytest.raises(exc, match="^" + msg):
            F.sigma_for_impact_probability(bad, dps=dps)
    if dps is None:  # the float64 array path converts p once (float_arg)
        with pytest.raises(TypeError, match=r"^p must hold real numbers, got an array of dtype"):
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
