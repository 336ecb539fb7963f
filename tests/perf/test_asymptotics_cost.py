"""The cost of symhx.asymptotics' relaxed order, counted by wrapping its private relaxation (a
cost test, not a behaviour test)."""

from __future__ import annotations

import mpmath
import pytest

import symhx.asymptotics as asym
from symhx.asymptotics import asymptotic_critical_point
from tests.reference.critical import asymptotic_k


@pytest.mark.parametrize("N", [10**3, 10**40, 10**1000], ids=["1e3", "1e40", "1e1000"])
def test_relaxed_bracket_costs_a_few_evaluations(N, monkeypatch):
    """The root of F is bracketed from the Lambert point in O(1) evaluations: widening ``hi``
    only while ``F(hi) < 0`` (a loop that ran on to N - 2 took ~1660 doublings, 25x the time,
    at N = 10**1000 and gave the same root). Counted by wrapping ``_Relaxation.F``."""
    calls = []
    real = asym._Relaxation.F

    def counted(self, x):
        calls.append(x)
        return real(self, x)

    monkeypatch.setattr(asym._Relaxation, "F", counted)
    a = asymptotic_critical_point(N, order="relaxed", dps=20)
    assert len(calls) <= 60, len(calls)
    with mpmath.workdps(80):
        assert abs(a.k / asymptotic_k(N, "relaxed", 20) - 1) < mpmath.mpf(10) ** -19
