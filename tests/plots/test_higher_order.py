"""Figures 11-13 of section 8 (:mod:`symhx.plots.higher_order`): the class decomposition, simple
against higher-order circuits, and E[X] against p per sample space, checked by their data."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import symhx
from symhx.plots.higher_order import (
    plot_class_decomposition,
    plot_mean_vs_p_spaces,
    plot_simple_vs_higher,
)
from tests.harness.figures import assert_fits_the_column
from tests.reference.distribution import pmf_table


def test_figures_draw_one_line_per_class_space_or_simulation():
    assert len(plot_class_decomposition(30, 0.03, kmax=20).axes[0].lines) == 6
    assert len(plot_simple_vs_higher(30, 0.04).axes[0].lines) == 2
    f3 = plot_mean_vs_p_spaces(30, points=5, simulation=([0.01], [3.0]))
    assert len(f3.axes[0].lines) == 4


def test_figure11_log_axis_and_no_line_to_zero():
    fig = plot_class_decomposition(30, 0.005, kmax=15)
    ax = fig.axes[0]
    assert ax.get_yscale() == "log"
    lo, _hi = ax.get_ylim()
    for ln in ax.lines:
        y = np.asarray(ln.get_data()[1], dtype=float)
        finite = y[np.isfinite(y)]
        assert (finite > 0).all()
        # every class is visible somewhere above the bottom of the axis
        assert finite.max() > lo, ln.get_label()


def test_figure13_eq41_not_hidden_under_eq41_printed():
    fig = plot_mean_vs_p_spaces(30, spaces=("simple", "eq41", "eq41-printed"), points=4)
    lines = {ln.get_label(): ln for ln in fig.axes[0].lines}
    a, b = lines["eq41"], lines["eq41-printed"]
    assert a.get_linestyle() != b.get_linestyle() and a.get_color() != b.get_color()
    assert a.get_linewidth() > b.get_linewidth()  # the wide line below stays visible
    assert lines["simple"].get_linestyle() == ":"  # as in the paper: simple circuits dotted


@pytest.mark.parametrize("N", [12, 30])
def test_figure13_theory_lines_are_the_mean_of_each_space_on_the_plotted_grid(N):
    spaces = ("simple", "eq41", "excess<=2")
    fig = plot_mean_vs_p_spaces(N, spaces=spaces, p_range=(1e-3, 0.5), points=7)
    ax = fig.axes[0]
    assert f"N={N}" in ax.get_title().replace(" ", "")
    lines = {ln.get_label(): ln for ln in ax.lines}
    assert set(spaces) <= set(lines)
    for sp in spaces:
        xs, ys = (np.asarray(v, dtype=float) for v in lines[sp].get_data())
        assert len(xs) == 7 and xs[0] == pytest.approx(1e-3) and xs[-1] == pytest.approx(0.5)
        for x, y in zip(xs, ys, strict=True):
            if sp == "simple":  # E[X] = sum k P(X = k) in exact Fractions at the plotted p
                ref = float(sum(k * w for k, w in enumerate(pmf_table(N, Fraction(x)), 1)))
            else:
                ref = float(symhx.mean(N, float(x), space=sp, dps=30))
            assert y == pytest.approx(ref, rel=1e-13), (sp, x)


def test_figures_11_to_13_fit_the_column():
    from symhx.plots.higher_order import plot_class_panels, plot_simple_vs_higher_panels

    for fig in (plot_class_decomposition(30, 0.03, kmax=20), plot_simple_vs_higher(30, 0.04),
                plot_mean_vs_p_spaces(30, points=5),
                plot_class_panels(30, ((0.01, None), (0.03, 12))),
                plot_simple_vs_higher_panels(30, (0.02, 0.04))):
        assert_fits_the_column(fig)


def test_figure11_total_is_drawn_over_k():
    fig = plot_class_decomposition(30, 0.03, kmax=20)
    total = next(ln for ln in fig.axes[0].lines if ln.get_label() == "$P(X=k)$")
    ks, ys = total.get_data()
    assert list(ks) == list(range(1, len(ks) + 1))
    # the class decomposition adds up to the pmf of its space (eq. 41 by default)
    ref = [float(symhx.pmf(30, 0.03, int(k), space="eq41", dps=20)) for k in ks]
    assert len(ks) >= 10 and all(abs(y - r) <= 1e-12 * r for y, r in zip(ys, ref, strict=True))
    assert "(log scale)" in fig.axes[0].get_ylabel()
