"""The figures of the book's first chapters: they draw, carry labels, and show the right thing."""

from __future__ import annotations

from fractions import Fraction

import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import symhx  # noqa: E402
import symhx.plots as plots  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _gids(fig):
    return [p.get_gid() for p in fig.axes[0].patches]


def test_public_names_reexported():
    for name in ("plot_pipe_row", "plot_impact_graph", "plot_circuit_counts",
                 "impact_labels", "circuit_fractions"):
        assert name in plots.__all__
        assert callable(getattr(plots, name))


@pytest.mark.parametrize("n", [1, 3, 7])
def test_pipe_row(n):
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


def test_impact_labels():
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


def test_plots_draw_into_given_axes():
    fig, (a, b, c) = plt.subplots(1, 3)
    assert plots.plot_pipe_row(2, ax=a) is fig
    assert plots.plot_impact_graph(2, ax=b) is fig
    assert plots.plot_circuit_counts(12, ax=c) is fig


def test_impact_graph_rejects_wrong_labels():
    with pytest.raises(ValueError):
        plots.plot_impact_graph(3, labels=["a", "b"])


@pytest.mark.parametrize("N", [1, 5, 100])
def test_circuit_counts_data_match_phi(N):
    fig = plots.plot_circuit_counts(N)
    ax = fig.axes[0]
    assert "k" in ax.get_xlabel()
    assert r"\phi_N(k)" in ax.get_ylabel()
    assert f"N = {N}" in ax.get_title()
    assert ax.get_yscale() == "log"
    ks, ys = ax.lines[0].get_data()
    total = symhx.total_simple_circuits(N)
    assert list(ks) == list(range(1, N + 1))
    for k, y in zip(ks, ys, strict=True):
        assert y == float(Fraction(symhx.phi(N, int(k)), total))
    fig.canvas.draw()


def test_circuit_counts_linear_axis_and_sum():
    fig = plots.plot_circuit_counts(8, log=False)
    assert fig.axes[0].get_yscale() == "linear"
    _, fracs = plots.circuit_fractions(8)
    assert abs(fracs.sum() - 1) < 1e-15


def test_circuit_fractions_drop_underflow():
    # for N = 200 the shortest circuits are below float64's range: those points are dropped
    _, fracs = plots.circuit_fractions(200)
    assert fracs[0] == 0.0 and fracs[-1] > 0
    fig = plots.plot_circuit_counts(200)
    xs, ys = fig.axes[0].lines[0].get_data()
    assert (ys > 0).all() and len(xs) == int((fracs > 0).sum())


def test_plot_modules_do_not_choose_a_backend():
    # a library module calling matplotlib.use() would switch a notebook kernel away from the
    # inline backend and silently drop every figure of the book
    from pathlib import Path

    import symhx.plots

    for src in Path(symhx.plots.__file__).parent.glob("*.py"):
        assert "matplotlib.use(" not in src.read_text(), src.name
