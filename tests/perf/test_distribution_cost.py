"""Cost of the simple distribution: work that must stay cheap whatever the size of ``p``'s
exact value."""

from __future__ import annotations

import time

import mpmath

import symhx


def test_tiny_binary_p_costs_under_two_seconds():
    """A tiny binary p (a 3.3-million-bit denominator) neither hangs nor loses accuracy:
    var X = P(2) + O(p**2) = 5 p (N = 11: Phi(2)/Phi(1) = p (N - 1)/2)."""
    p = mpmath.mpf("1e-1000000")
    t = time.monotonic()
    v = symhx.var(11, p, dps=30)
    assert time.monotonic() - t < 2
    with mpmath.workdps(60):
        assert abs(v / (5 * p) - 1) < mpmath.mpf(10) ** -25
