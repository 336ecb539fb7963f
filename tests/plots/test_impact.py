"""Figures 7, 8, 10 and 13 of the simulation chapter (:mod:`symhx.plots.impact`), checked by
their data: the theory line of figures 10 and 13 is ``E[X]`` of the graph model at ``N = n + 1``
for a row of ``n`` pipes, on the plotted grid of ``p``, and the title says so."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import symhx
from symhx.plots.impact import plot_theory_vs_simulation
from tests.reference.distribution import pmf_table


@pytest.fixture(scope="module", params=[3, 6])
def small_ensemble(request):
    """A quick ensemble of a row of n pipes (its statistics do not matter here, only n)."""
    return symhx.ensemble([0.3, 0.6], 3, n=request.param, t_transient=20.0, t_window=20.0,
                          seed=0, progress=False)


def _theory_lines(fig):
    return {ln.get_label().rsplit(" ", 1)[-1]: ln for ln in fig.axes[0].lines
            if ln.get_label().startswith("theory")}


def _exact_mean(N, p):
    """E[X] of eq. (7) in exact Fractions at the float p (the plotted grid point)."""
    return sum(k * w for k, w in enumerate(pmf_table(N, Fraction(p)), 1))


def test_figure10_theory_line_is_the_mean_at_n_plus_one_on_the_plotted_grid(small_ensemble):
    n = small_ensemble.params["n"]
    fig = plot_theory_vs_simulation(small_ensemble)
    ax = fig.axes[0]
    assert ax.get_title().startswith("Fig. 10: ")
    assert f"N = {n + 1};" in ax.get_title() and f"n = {n} pipes" in ax.get_title()
    (line,) = _theory_lines(fig).values()
    xs, ys = (np.asarray(v, dtype=float) for v in line.get_data())
    assert len(xs) > 10 and (np.diff(xs) > 0).all() and xs[-1] == pytest.approx(0.9)
    for x, y in zip(xs, ys, strict=True):
        assert y == pytest.approx(float(_exact_mean(n + 1, x)), rel=1e-14), x


def test_figure10_theory_line_follows_a_given_grid(small_ensemble):
    n = small_ensemble.params["n"]
    grid = [0.01, 0.05, 0.2, 0.7]
    fig = plot_theory_vs_simulation(small_ensemble, p_grid=grid, measured=False)
    (line,) = _theory_lines(fig).values()
    xs, ys = line.get_data()
    assert list(xs) == grid
    assert list(ys) == pytest.approx([float(_exact_mean(n + 1, x)) for x in grid], rel=1e-14)


def test_figure13_theory_line_of_each_space_is_its_mean_at_n_plus_one(small_ensemble):
    n = small_ensemble.params["n"]
    spaces = ("simple", "eq41", "excess<=2")
    fig = plot_theory_vs_simulation(small_ensemble, spaces=spaces, title="Fig. 13",
                                    p_grid=np.geomspace(1e-3, 0.9, 9))
    title_text = fig.axes[0].get_title()
    assert title_text.startswith("Fig. 13:") and f"N = {n + 1};" in title_text
    lines = _theory_lines(fig)
    assert set(lines) == set(spaces)
    for sp, line in lines.items():
        xs, ys = line.get_data()
        for x, y in zip(xs, ys, strict=True):
            ref = _exact_mean(n + 1, x) if sp == "simple" else symhx.mean(n + 1, float(x),
                                                                           space=sp, dps=30)
            assert y == pytest.approx(float(ref), rel=1e-14), (sp, x)


def test_figure10_of_the_stored_ensemble_is_the_paper_row_N_101():
    from symhx.plots import stored_ensemble

    res = stored_ensemble()
    fig = plot_theory_vs_simulation(res, p_grid=[0.005, 0.0128, 0.05])
    assert "N = 101;" in fig.axes[0].get_title() and res.params["n"] == 100
    (line,) = _theory_lines(fig).values()
    xs, ys = line.get_data()
    assert list(ys) == pytest.approx([float(_exact_mean(101, x)) for x in xs], rel=1e-14)


def test_figures_7_and_8_count_from_zero(small_ensemble):
    # a number of impacting pipes is >= 0: both axes start at 0, whatever the data's range
    from symhx.plots.impact import plot_mean_vs_sigma, plot_mode_vs_sigma

    for plot in (plot_mode_vs_sigma, plot_mean_vs_sigma):
        fig = plot(small_ensemble, min_count=1)
        assert fig.axes[0].get_ylim()[0] == 0, plot.__name__
