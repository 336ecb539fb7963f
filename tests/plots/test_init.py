"""The plots package (:mod:`symhx.plots`): every submodule's public ``plot_*`` is re-exported, each
draws into a given Axes, and no module chooses a matplotlib backend."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt

import symhx.plots as plots


def test_public_names_of_the_submodules_are_reexported():
    for name in ("plot_pipe_row", "plot_impact_graph", "plot_circuit_counts",
                 "impact_labels", "circuit_fractions"):
        assert name in plots.__all__
        assert callable(getattr(plots, name))


def test_plots_draw_into_given_axes():
    fig, (a, b, c) = plt.subplots(1, 3)
    assert plots.plot_pipe_row(2, ax=a) is fig
    assert plots.plot_impact_graph(2, ax=b) is fig
    assert plots.plot_circuit_counts(12, ax=c) is fig


def test_plot_modules_do_not_choose_a_backend():
    # a library module calling matplotlib.use() would switch a notebook kernel away from the
    # inline backend and silently drop every figure of the book
    for src in Path(plots.__file__).parent.glob("*.py"):
        assert "matplotlib.use(" not in src.read_text(), src.name
