"""The theory chain sigma -> p -> (mean, mode of X) of figure 10 (``symhx.forcing.theory``): the
composition with the graph model at the reference ``p``, the ``p -> 0`` limit below
``THEORY_P_FLOOR`` and the ``N`` cap."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

import symhx
from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from tests.harness.errors import assert_refuses
from tests.reference.forcing import forcing_values
from tests.reference.mp import rel_err


# ----------------------------------------------------------------------------- theory chain
def test_theory_curve_is_the_composition():
    from symhx.api import mean, mode

    tc = F.theory_curve([0.06, 0.12, 0.2], N=101, dps=20)
    for s, p, m, k in zip(tc.sigma, tc.p, tc.mean, tc.mode, strict=True):
        pm = F.impact_probability(float(s), dps=20)
        assert rel_err(p, pm) < 1e-15
        assert rel_err(m, mean(101, pm, dps=20)) < 1e-15
        assert k == mode(101, pm)
    assert np.all(np.diff(tc.mean) > 0)


def test_theory_curve_tiny_p_and_N_cap():
    """Below THEORY_P_FLOOR the p -> 0 shortcut equals the graph model at the exact p."""
    import symhx
    from symhx.forcing.theory import THEORY_MAX_N, theory_curve

    tc = theory_curve([5e-324, 0.01, 0.05, 0.2], N=101, dps=15)
    assert list(tc.p[:2]) == [0.0, 0.0] and list(tc.mode[:2]) == [1, 1]
    for i, s in enumerate((0.01, 0.05, 0.2)):  # p(0.01) ~ 1e-1086: below the floor
        pm = F.impact_probability(s, dps=20)
        assert tc.p[i + 1] == float(pm)
        assert tc.mean[i + 1] == float(symhx.mean(101, pm, space="simple", dps=20))
        assert tc.mode[i + 1] == int(symhx.mode(101, pm, space="simple"))
    assert tc.mean[0] == 1.0
    with pytest.raises(ValueError, match="THEORY_MAX_N"):
        theory_curve(0.3, N=THEORY_MAX_N + 1)
    with pytest.raises(ValueError, match="THEORY_MAX_N"):
        theory_curve(0.3, N=10**1000)


# ------------------------------------------------------------------ theory chain
def test_theory_curve_is_the_composition_with_reference_p():
    sig = np.array([[0.05, 0.12], [0.3, 2.0]])
    tc = F.theory_curve(sig, N=41, d="1.1", Omega="1.6", dps=25)
    assert tc.N == 41 and tc.sigma.shape == tc.p.shape == tc.mean.shape == (2, 2)
    assert tc.mode.dtype == np.int64
    for idx in np.ndindex(sig.shape):
        p = forcing_values(float(sig[idx]), None, 1, "1.6", "1.1", 25)[0]
        assert rel_err(tc.p[idx], p) < 1e-15
        with mpmath.workdps(25), thread_mp().workdps(25):
            p25 = +p
        assert rel_err(tc.mean[idx], symhx.mean(41, p25, dps=25)) < 1e-15
        assert tc.mode[idx] == symhx.mode(41, p25)
    tc = F.theory_curve(0.2, N=11, sigma1=0.25, space="eq41")
    p = forcing_values(0.2, 0.25, dps=30)[0]
    with mpmath.workdps(30), thread_mp().workdps(30):
        p30 = +p
    assert tc.p.shape == (1,) and rel_err(tc.p[0], p) < 1e-15
    assert rel_err(tc.mean[0], symhx.mean(11, p30, space="eq41", dps=30)) < 1e-15
    assert tc.mode[0] == symhx.mode(11, p30, space="eq41") != symhx.mode(11, p30)
    assert F.theory_curve(0.3).N == 101  # the paper's n = 100 pipes


def test_theory_curve_tiny_p_and_limits():
    # log p = -1/(8 sigma**2) + ...: below -2400 for sigma = 0.005 (not evaluated in mpmath,
    # also where mpmath refuses: sigma = 1e-160), and 1e-1000 > p > exp(-2400) for 0.0073
    tc = F.theory_curve([0.005, 0.02, 0.0073, 1e-160, 0.005], N=10**12)
    p002 = float(forcing_values(0.02)[0])
    assert list(tc.p) == [0.0, pytest.approx(p002, rel=1e-15), 0.0, 0.0, 0.0]
    assert tc.p[1] > 0
    assert list(tc.mean[[0, 2, 3, 4]]) == [1.0] * 4 and list(tc.mode[[0, 2, 3, 4]]) == [1] * 4
    # the float pre-filter sees sigma1, Omega and d: none of these p is tiny
    for sigma, kw in [(1e-3, {"sigma1": 0.5}), (1e-3, {"Omega": 1.01}), (2e-4, {"d": 0.01})]:
        tc = F.theory_curve(sigma, N=11, **kw)
        want = forcing_values(sigma, kw.get("sigma1"), 1, kw.get("Omega"), kw.get("d", 1))[0]
        assert 0 < tc.p[0] and rel_err(tc.p[0], want) < 1e-14, (sigma, kw)
    with pytest.raises(ValueError, match=r"sigma must be > 0, got -1"):
        F.theory_curve(-1)
    for kw in [{"sigma1": np.array([0.1, 0.2])}, {"Omega": np.array([1.5, 2.5])}]:
        assert_refuses(F.theory_curve, 0.1, **kw, exc=TypeError,
                       arg=["sigma1", "omega", "Omega", "d"], allowed="must be scalars")
    assert_refuses(F.theory_curve, 0.1, N=10**300 + 1, arg="N", value="an integer of 301 digits",
                   allowed="<= THEORY_MAX_N = 10**300")
    assert F.theory_curve(0.1, N=10**30).N == 10**30
    assert_refuses(F.theory_curve, 0.1, d=[1.0, 2.0], exc=TypeError,
                   arg=["sigma1", "omega", "Omega", "d"], allowed="must be scalars")
