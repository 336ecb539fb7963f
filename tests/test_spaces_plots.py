"""Smoke tests of the section-8 figures."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

from symhx.plots.higher_order import (
    plot_class_decomposition,
    plot_mean_vs_p_spaces,
    plot_simple_vs_higher,
)


def test_figures_draw():
    import matplotlib.pyplot as plt

    f1 = plot_class_decomposition(30, 0.03, kmax=20)
    assert len(f1.axes[0].lines) == 6
    f2 = plot_simple_vs_higher(30, 0.04)
    assert len(f2.axes[0].lines) == 2
    f3 = plot_mean_vs_p_spaces(30, points=5, simulation=([0.01], [3.0]))
    assert len(f3.axes[0].lines) == 4
    for f in (f1, f2, f3):
        plt.close(f)
