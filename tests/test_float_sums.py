"""symhx.float_sums: float64 lower/upper partial sums of Phi, vectorised over k, against
independent sums (a float cumsum of every term below the table limit, mpmath walks of the
exact term ratio in the tails, exact integer turning points)."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx
from symhx.float_sums import FloatSums, _turns
from symhx.float_terms import log_phi_diff
from tests.reference.distribution import phi_exact
from tests.reference.distribution_large_n import (
    critical_p,
    log_lower_sum_geometric,
    log_phi,
    log_upper_sum_walk,
)


def _sums(N: int, p: Fraction) -> tuple[FloatSums, int, float]:
    """The module's sums relative to the mode (exact) with ``log(p (N + 1 - c))`` at 30
    digits (not the distribution's engine)."""
    c = symhx.mode(N, p)
    with mpmath.workdps(30):
        lpx = float(mpmath.log(mpmath.mpf(p.numerator) * (N + 1 - c) / p.denominator))
    return FloatSums(N, p, c, lpx), c, lpx


def _close(got: np.ndarray, want: np.ndarray, tol: float) -> None:
    both_inf = np.isneginf(got) & np.isneginf(want)
    err = np.where(both_inf, 0.0, np.abs(got - want) / (1 + np.abs(want)))
    assert err.max() <= tol, (err.max(), int(np.argmax(err)))


@pytest.mark.parametrize("N", [2, 3, 7, 50, 1001])
@pytest.mark.parametrize("p", [Fraction(1, 10**6), Fraction(1, 100), Fraction(3, 100),
                               Fraction(1, 2), Fraction(1), Fraction(5)])
def test_turning_points_bracket_the_monotone_runs(N: int, p: Fraction) -> None:
    m, t = _turns(N, p)
    phi = [phi_exact(N, p, k) for k in range(1, N + 1)]
    assert 1 <= m <= t <= N
    assert all(phi[k] >= phi[k + 1] for k in range(0, m - 1))  # decreasing on [1, m]
    assert all(phi[k] <= phi[k + 1] for k in range(m - 1, t - 1))  # increasing on [m, t]
    assert all(phi[k] >= phi[k + 1] for k in range(t - 1, N - 1))  # decreasing on [t, N]


@pytest.mark.parametrize("ratio", ["1e-3", "0.5", "0.999", "1.001", "2", "10", "1e3"])
def test_tails_match_every_term_summed_below_the_table_limit(ratio: str) -> None:
    """N = 300001: the module (panels, EM, windows) against the float cumsum of all terms."""
    N = 300_001
    p = critical_p(N) * Fraction(ratio)
    fs, c, lpx = _sums(N, p)
    lv = log_phi_diff(N, c, lpx, np.arange(1, N + 1))
    lower = np.logaddexp.accumulate(lv)
    upper = np.append(np.logaddexp.accumulate(lv[::-1])[::-1][1:], -np.inf)
    rng = np.random.default_rng(5)
    ks = np.unique(np.concatenate([np.geomspace(1, N - 1, 80).astype(np.int64),
                                   rng.integers(1, N, 80), [1, 2, N - 2, N - 1]]))
    lo, up = fs.log_tails(ks)
    _close(lo + fs.shift, lower[ks - 1], 1e-13)
    _close(up + fs.shift, upper[ks - 1], 1e-13)


@pytest.mark.parametrize("p", [Fraction(1, 2), Fraction(1), Fraction(3), Fraction(1, 1000)])
def test_tails_near_n_match_every_term(p: Fraction) -> None:
    """p of order 1 (mass at k near N, Poisson-like in N - k), N = 300001."""
    N = 300_001
    fs, c, lpx = _sums(N, p)
    lv = log_phi_diff(N, c, lpx, np.arange(1, N + 1))
    lower = np.logaddexp.accumulate(lv)
    upper = np.append(np.logaddexp.accumulate(lv[::-1])[::-1][1:], -np.inf)
    ks = np.unique(np.concatenate([N - np.geomspace(1, N - 1, 60).astype(np.int64),
                                   np.geomspace(1, N - 1, 30).astype(np.int64)]))
    ks = ks[(ks >= 1) & (ks <= N - 1)]
    lo, up = fs.log_tails(ks)
    _close(lo + fs.shift, lower[ks - 1], 1e-13)
    _close(up + fs.shift, upper[ks - 1], 1e-13)


@pytest.mark.parametrize("N", [10**7 + 1, 10**9], ids=["1e7+1", "1e9"])
@pytest.mark.parametrize("ratio", ["2", "10"])
def test_far_tails_match_mpmath_walks(N: int, ratio: str) -> None:
    """Above the jump: the right tail beyond the hump and the left tail far below it, each
    walked term by term in mpmath from k (loggamma for the first term), far below 1e-300."""
    p = critical_p(N) * Fraction(ratio)
    fs, c, _ = _sums(N, p)
    ref_c = log_phi(N, p, c, 30)
    right = [N - 2, N - N // 50, N - N // 20]
    left = [3, 100, N // 100]
    _, up = fs.log_tails(np.array(right))
    lo, _ = fs.log_tails(np.array(left))
    want_up = [float(log_upper_sum_walk(N, p, k, 25) - ref_c) for k in right]
    want_lo = [float(log_lower_sum_geometric(N, p, k, 25) - ref_c) for k in left]
    _close(up + fs.shift, np.array(want_up), 1e-14)
    _close(lo + fs.shift, np.array(want_lo), 1e-14)
    assert max(want_up) < -700 and max(want_lo) < -700  # far below float64's range


def test_upper_tail_is_summed_not_taken_from_the_lower() -> None:
    """sf far right keeps its digits (1 - cdf would be 0): N = 1e12, p = 2 p_c."""
    N = 10**12
    p = critical_p(N) * 2
    fs, c, _ = _sums(N, p)
    k = c + 12 * 10**6  # ~17 sigma above the top: sf ~ 1e-60
    lo, up = fs.log_tails(np.array([k, k + 1]))
    sf = np.exp(up - np.logaddexp(lo, up))
    assert 1e-80 < sf[0] < 1e-40
    want = np.exp(float(log_phi(N, p, k + 1, 30) - log_phi(N, p, c, 30)) - fs.shift
                  - np.logaddexp(lo[0], up[0]))
    assert abs(sf[0] - sf[1] - want) <= 1e-13 * sf[0]  # the difference is one exact term


def test_huge_n_keeps_integer_differences_exact() -> None:
    """N = 10**300 + 7, p = 3: k = N - j needs N + 1 - k = j + 1 exactly."""
    N = 10**300 + 7
    fs, _, _ = _sums(N, Fraction(3))
    ks = np.array([N - 1, N - 2, N - 5, N - 30], dtype=object)
    lo, up = fs.log_tails(ks)
    lam = mpmath.mpf(1) / 3  # Phi(N - j)/Phi(N) = lam**j / j! to 1e-299
    for k, u in zip(ks, up, strict=True):
        J = N - k
        want = mpmath.log(mpmath.fsum(lam**j / mpmath.factorial(j) for j in range(J)))
        assert abs(u + fs.shift - float(want)) < 1e-14 * (1 + abs(float(want)))
    assert np.all(np.isfinite(lo))


def test_far_windows_beyond_and_inside_the_float64_range_in_one_call() -> None:
    """N = 10**308, p = 1: k = N/2 has every term below exp(-1.8e308) of the mode (its lower
    tail is -inf) and k = N - 10**4 a lower tail of a few terms (each ~1/(N - k) of the next);
    asked together, each is what it is alone, the second against an mpmath sum of its terms
    (``log Phi(i)/Phi(c) = log(c/i) + loggamma(N - c + 1) - loggamma(N - i + 1)``)."""
    N = 10**308
    fs, c, _ = _sums(N, Fraction(1))
    k = N - 10**4
    lo, _ = fs.log_tails(np.array([N // 2, k], dtype=object))
    alone, _ = fs.log_tails(np.array([k], dtype=object))
    with mpmath.workdps(40):
        def d(i: int):
            return (mpmath.log(mpmath.mpf(c) / i) + mpmath.loggamma(N - c + 1)
                    - mpmath.loggamma(N - i + 1))

        want = float(d(k) + mpmath.log(mpmath.fsum(mpmath.exp(d(k - j) - d(k))
                                                   for j in range(12))))
    assert lo[0] == -np.inf and lo[1] == alone[0]
    assert abs(lo[1] + fs.shift - want) <= 1e-14 * abs(want)


def test_one_structure_serves_any_number_of_k() -> None:
    """The per-distribution work is done once: 2000 more k add no panels or items."""
    N = 10**15
    fs, _, _ = _sums(N, critical_p(N) * 2)
    items = list(fs._items)
    ks = np.array(sorted({int(v) for v in np.geomspace(1, N - 1, 2000)}))
    lo, up = fs.log_tails(ks)
    assert fs._items == items
    assert np.all(np.isfinite(lo) & np.isfinite(up))
    assert np.all(np.diff(lo) >= -1e-12) and np.all(np.diff(up) <= 1e-12)  # monotone in k
