"""Figure 3 (:mod:`symhx.plots.circuits`): the fraction of simple circuits of each length, checked
by the plotted data against eq. (5)."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest

import symhx.plots as plots


@pytest.mark.parametrize("N", [1, 5, 100])
def test_circuit_counts_plot_phi_over_the_total_for_every_length(N):
    fig = plots.plot_circuit_counts(N)
    ax = fig.axes[0]
    assert "k" in ax.get_xlabel()
    assert r"\phi_N(k)" in ax.get_ylabel()
    assert f"N = {N}" in ax.get_title()
    assert ax.get_yscale() == "log"
    ks, ys = ax.lines[0].get_data()
    # eq. (5) written out: N!/((N-k)! k), and its sum over k
    counts = [math.perm(N, k) // k for k in range(1, N + 1)]
    assert list(ks) == list(range(1, N + 1))
    for y, c in zip(ys, counts, strict=True):
        assert y == float(Fraction(c, sum(counts)))
    assert ax.get_xlim() == (0, N + 1)  # every length k = 1..N inside, with a margin of one
    lo, hi = ax.get_ylim()  # every plotted fraction inside, a decade of margin below
    assert hi == 3.0 and 0 < lo <= min(ys) / 10
    fig.canvas.draw()


def test_circuit_counts_linear_axis_and_fractions_sum_to_one():
    fig = plots.plot_circuit_counts(8, log=False)
    assert fig.axes[0].get_yscale() == "linear"
    ks, fracs = plots.circuit_fractions(8)
    assert abs(fracs.sum() - 1) < 1e-15
    assert ks.tolist() == list(range(1, 9))  # k = 1..N, one fraction each
    assert len(fracs) == 8


def test_circuit_fractions_below_float64_range_are_dropped_from_the_log_plot():
    # for N = 200 the shortest circuits are below float64's range: those points are dropped
    _, fracs = plots.circuit_fractions(200)
    assert fracs[0] == 0.0 and fracs[-1] > 0
    fig = plots.plot_circuit_counts(200)
    xs, ys = fig.axes[0].lines[0].get_data()
    assert (ys > 0).all() and len(xs) == int((fracs > 0).sum())


def test_tick_steps_are_1_2_5_times_a_power_of_ten():
    from symhx.plots.circuits import _nice_step

    assert [_nice_step(t) for t in (0.5, 1, 1.5, 2, 3, 5, 7, 10, 11, 40, 99, 101, 4000)] == \
        [1, 1, 2, 2, 5, 5, 10, 10, 20, 50, 100, 200, 5000]
