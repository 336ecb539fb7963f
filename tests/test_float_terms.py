"""float64 differences of log Phi without cancellation (symhx.float_terms), against mpmath's
loggamma at digits(N) + 40 digits, over log grids of N (10 ... 10**300), of p relative to the
jump and of k around the reference (bulk, far tails, both ends of the support)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx.float_terms import bd0, log_phi_diff, stirling_remainder
from tests.reference.distribution_large_n import log_phi_ratio
from tests.reference.mp import int_log_grid, log_grid


def _cases() -> list[tuple[int, float, int]]:
    """(N, p, c): below the jump (c = 1, N p < 1), just above it and far above (c = the hump's
    top, N + 1 - 1/p rounded), over N = 10 ... 10**300 (p relative to p_d)."""
    out = []
    for N in int_log_grid(10, 10**300, 9):
        pc = ((1 + math.sqrt(N + 1)) / N) ** 2  # p_d: the scale of the jump
        out.append((N, 0.5 * pc, 1))
        for r in (1.5, 10.0, 1e3):
            p = min(r * pc, 0.9)
            out.append((N, p, max(1, N + 1 - round(1 / p))))
    return out


@pytest.mark.parametrize(("N", "p", "c"), _cases())
def test_log_phi_diff_matches_loggamma(N: int, p: float, c: int) -> None:
    """Absolute error <= 1e-13 (1 + |result|) wherever the pmf can be seen (|result| < 800) and
    relative 1e-12 far out; the caller's log(p x) is rounded once to float."""
    with mpmath.workdps(len(str(N)) + 40):
        lpx = float(mpmath.log(mpmath.mpf(p) * (N + 1 - c)))
    width = math.sqrt(1 / p) if c > 1 else 1 / max(abs(math.log(p * N)), 1e-3)
    offs = [0, 1, -1] + [s * int(f * width) for f in (1, 5, 40) for s in (1, -1)]
    ks = sorted({min(max(c + o, 1), N) for o in offs} | {1, 2, N - 1, N})
    arr = np.array(ks, dtype=object if N > 2**62 else np.int64)
    got = log_phi_diff(N, c, lpx, arr)
    for k, g in zip(ks, got, strict=True):
        want = log_phi_ratio(N, p, k, c, len(str(N)) + 40)
        tol = 1e-13 * (1 + abs(want)) if abs(want) < 800 else 1e-12 * abs(want)
        assert abs(g - want) <= tol, (N, p, c, k, g, want)


def test_log_phi_diff_is_zero_at_the_reference() -> None:
    assert log_phi_diff(10**9, 123, 0.37, np.array([123]))[0] == 0.0


@pytest.mark.parametrize("z", list(log_grid(1.0, 1e300, 25)))
def test_stirling_remainder_matches_loggamma(z: float) -> None:
    with mpmath.workdps(340):
        zm = mpmath.mpf(z)
        want = mpmath.loggamma(zm) - (zm - 0.5) * mpmath.log(zm) + zm \
            - mpmath.log(2 * mpmath.pi) / 2
    got = stirling_remainder(np.array([z]))[0]
    assert abs(got - want) <= 1e-15 * abs(want) + 1e-16, (z, got, want)


@pytest.mark.parametrize("x", [1.0, 10.0, 1e5, 1e12, 1e200])
@pytest.mark.parametrize("ratio", [1e-9, 0.3, 0.9, 0.999, 1.0, 1.001, 1.1, 3.0])
def test_bd0_keeps_relative_accuracy_near_and_far_from_y_equals_x(x: float, ratio: float) -> None:
    """bd0(y, x) = y log(y/x) + x - y, relative 1e-14, also where it is ~(x - y)**2/(2x) and
    the direct form cancels."""
    y = x * ratio
    with mpmath.workdps(60):
        xm, ym = mpmath.mpf(x), mpmath.mpf(y)
        want = ym * mpmath.log(ym / xm) + xm - ym
        d = float(xm - ym)
    got = bd0(np.array([y]), np.array([x]), np.array([d]))[0]
    if want == 0:
        assert got == 0
    else:
        assert abs(got - want) <= 1e-14 * abs(want), (x, y, got, want)
