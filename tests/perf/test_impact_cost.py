"""Cost tests of ``symhx.impact`` (deliberate, named as such): the root refinement of the
certified search costs a few evaluations; hopeless random rows are refused up front, not after
redrawing."""

from __future__ import annotations

import time

import numpy as np
import pytest

from symhx.impact import PipeRow
from symhx.impact.engine import Engine, FloatContext

REFINE_CASES = [   # (g over F = (1, 3), bracket): each takes another branch of the iteration
    ([-0.731, 0.695, 0.528, -0.49, -0.009], 1.4500000000000002, 1.5),     # order 3
    ([-0.265, -0.112, 0.124, -0.216, 0.339], 1.0, 1.05),                  # step leaves bracket
    ([-0.677, -0.771, 0.067, -0.731, 0.94], 0.8, 0.8500000000000001),     # g' >= 0 at the start
    ([0.257, 0.633, 0.369, 0.006, 0.201], 1.6801446076207562, 3.2794254642113794),   # Newton
    ([0.498, 0.797, 0.335, 0.077, 0.027], 0.7210453594912931, 3.2576236235843767),   # Halley
]


@pytest.mark.parametrize("g, lo, hi", REFINE_CASES)
def test_refine_costs_at_most_five_evaluations(g, lo, hi):
    # fourth-order iteration (Householder of order 3, with Halley / Newton / bisection as
    # safeguards): at most 5 evaluations of g and its derivatives from these starts
    row = PipeRow(1, omega=1.0, d=1.0, Omega=(3.0,), restitution=0.5, alpha=np.zeros((1, 1)),
                  beta=np.zeros((1, 1)), x0=[1.0], v0=[0.0])
    eng = Engine(row, FloatContext(), v_stick=1e-6)
    calls = []
    derivs = eng.derivs
    eng.derivs = lambda gg, t: calls.append(t) or derivs(gg, t)   # type: ignore[method-assign]
    eng.refine(g, lo, hi)
    assert len(calls) <= 5


def test_hopeless_random_rows_are_refused_within_a_second():
    t0 = time.perf_counter()
    for kw in (dict(sigma=1e6), dict(sigma=1e308), dict(sigma=0.3, d=1e308),
               dict(sigma=0.3, d=5e-324), dict(sigma=0.3, omega=10**1000)):
        with pytest.raises(ValueError):
            PipeRow.random(3, seed=0, **kw)
    assert time.perf_counter() - t0 < 1.0     # refused up front, not after redrawing
