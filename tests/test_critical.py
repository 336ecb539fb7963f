"""Critical point p_c, discriminant root p_d and the mode path (section 6)."""

from fractions import Fraction
from itertools import pairwise

import mpmath
import pytest
from hypothesis import given
from hypothesis import strategies as st

import symhx
from symhx._numeric import G_direct, G_mp
from symhx.critical import discriminant_root_q, log_c
from tests.reference.critical import critical_by_scan, log_c_direct
from tests.reference.distribution import brute_modes


def rel(a, b):
    with mpmath.workdps(400):
        return abs(a - b) / abs(b)


@pytest.mark.parametrize("N", [*range(2, 121), 200, 257, 400])
def test_critical_against_exhaustive_scan(N):
    cp = symhx.critical_point(N, dps=50)
    argmins, p_scan = critical_by_scan(N, 50)
    assert list(cp.argmins) == argmins
    assert cp.k_after == max(argmins) and cp.k_before == 1
    assert rel(cp.p, p_scan) < mpmath.mpf(10) ** -48
    assert cp.p >= cp.p_d


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


@pytest.mark.parametrize("N", [4, 7, 30, 101, 500])
def test_mode_around_critical_point(N):
    cp = symhx.critical_point(N, dps=60)
    with mpmath.workdps(80):
        eps = mpmath.mpf(10) ** -50
        below, above = cp.p * (1 - eps), cp.p * (1 + eps)
    assert symhx.mode(N, below) == 1
    assert symhx.mode(N, above) == cp.k_after
    # brute force with exact Fractions of those binary values
    from symhx._numeric import as_fraction

    assert brute_modes(N, as_fraction(above))[0] == cp.k_after


@pytest.mark.parametrize("e", [3, 6, 10, 30, 100, 150])
@pytest.mark.parametrize("dps", [15, 50, 100, 200])
def test_huge_N_precision_doubling(e, dps):
    N = 10**e
    cp = symhx.critical_point(N, dps=dps)
    hi = symhx.critical_point(N, dps=2 * dps)
    assert cp.k_after == hi.k_after
    tol = mpmath.mpf(10) ** (1 - dps)
    assert rel(cp.p, hi.p) < tol and rel(cp.q, hi.q) < tol
    # q = N p - 1 is consistent with p
    with mpmath.workdps(2 * dps + e + 10):
        assert rel(N * hi.p - 1, hi.q) < mpmath.mpf(10) ** (e - 2 * dps + 2)


@pytest.mark.parametrize("N", [10**6, 10**12, 10**100])
def test_argmin_is_certified_locally(N):
    # the integer argmin beats its neighbours, checked with the definition at high precision
    cp = symhx.critical_point(N, dps=30)
    k = cp.k_after
    dps = 60 + 3 * len(str(N))
    v = [log_c_direct(N, j, dps) for j in (k - 1, k, k + 1)]
    with mpmath.workdps(dps):
        assert v[1] < v[0] and v[1] < v[2]
        assert rel(mpmath.exp(v[1]) / N, cp.p) < mpmath.mpf(10) ** -28


@pytest.mark.parametrize("N", [20, 101, 1000, 5000])
def test_c_is_unimodal_exhaustive(N):
    # log c_k is unimodal in k (proof in symhx.critical); check every k
    vals = [log_c_direct(N, k, 30) for k in range(2, N + 1)]
    d = [b - a for a, b in pairwise(vals)]
    changes = sum(1 for x, y in pairwise(d) if (x < 0) != (y < 0))
    assert changes <= 1


@given(st.integers(10**5, 10**40), st.integers(0, 10**6))
def test_G_rewrite_matches_definition(N, K):
    K = min(K, N - 1)
    with mpmath.workdps(60):
        a = G_mp(N, K)
        b = G_direct(N, K)
    if K == 0:
        assert a == 0
        return
    with mpmath.workdps(60):
        assert abs(a - b) <= mpmath.mpf(10) ** -55 * abs(b)


@given(st.integers(3, 10**30), st.integers(2, 10**4))
def test_log_c_matches_definition(N, k):
    k = min(k, N)
    assert rel(log_c(N, k, dps=40), log_c_direct(N, k, 40)) < mpmath.mpf(10) ** -38


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


def test_mode_path_large_N_runs():
    path = symhx.mode_path(10**4)
    assert len(path.breakpoints) > 9000
    assert path.breakpoints[0][2] == symhx.critical_point(10**4).k_after
