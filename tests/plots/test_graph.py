"""Figures 1-2 (:mod:`symhx.plots.graph`): the row of pipes and the impact graph, checked by what
they draw (patches tagged by gid, texts, title)."""

from __future__ import annotations

import pytest
from matplotlib.figure import Figure

import symhx
import symhx.plots as plots
from tests.harness.errors import assert_refuses
from tests.harness.figures import assert_fits_the_column


def _gids(fig):
    return [p.get_gid() for p in fig.axes[0].patches]


@pytest.mark.parametrize("n", [1, 3, 7])
def test_pipe_row_draws_n_pipes_two_walls_and_every_gap_labelled(n):
    fig = plots.plot_pipe_row(n)
    assert isinstance(fig, Figure)
    ax = fig.axes[0]
    assert "$x$" in ax.get_xlabel()
    assert f"$n = {n}$" in ax.get_title()
    gids = _gids(fig)
    assert gids.count("pipe") == n
    assert gids.count("wall") == 2
    assert gids.count("gap") == symhx.vertices_row(n)
    texts = {t.get_text() for t in ax.texts}
    assert set(plots.impact_labels(n)) <= texts
    fig.canvas.draw()


def test_impact_labels_name_each_gap_by_its_neighbours():
    assert plots.impact_labels(3) == ["L-1", "1-2", "2-3", "3-R"]
    assert len(plots.impact_labels(10)) == symhx.vertices_row(10)


@pytest.mark.parametrize("n", [1, 3, 6])
def test_impact_graph_has_N_vertices_and_N2_edges(n):
    N = symhx.vertices_row(n)
    fig = plots.plot_impact_graph(n)
    assert isinstance(fig, Figure)
    gids = _gids(fig)
    assert gids.count("vertex") == N
    assert gids.count("edge") == N * N
    ax = fig.axes[0]
    assert f"$N = {N}$" in ax.get_title() and f"= {N * N}$" in ax.get_title()
    assert {t.get_text() for t in ax.texts} == set(plots.impact_labels(n))
    fig.canvas.draw()


def test_impact_graph_refuses_a_wrong_number_of_labels():
    assert_refuses(plots.plot_impact_graph, 3, labels=["a", "b"], arg="labels", value="2",
                   allowed="4")


@pytest.mark.parametrize("n", [1, 7])
def test_graph_figures_fit_the_column(n):
    # narrower than the column for a short row
    assert_fits_the_column(plots.plot_pipe_row(n), full_width=False)
    assert_fits_the_column(plots.plot_impact_graph(n), full_width=False)
