"""The asymptotic-error figure (:mod:`symhx.plots.asymptotics`)."""

from __future__ import annotations

import matplotlib.pyplot as plt

from symhx.asymptotics import error_table
from symhx.plots.asymptotics import plot_asymptotic_errors
from tests.harness.figures import assert_fits_the_column


def test_asymptotic_errors_on_log_log_axes_one_line_per_order():
    fig = plot_asymptotic_errors(error_table((10**3, 10**6, 10**10), dps=40))
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert ax.get_ylabel() == "relative error" and "N" in ax.get_xlabel()
    assert len(ax.get_lines()) >= 7
    plt.close(fig)


def test_asymptotic_errors_fit_the_column():
    assert_fits_the_column(plot_asymptotic_errors(error_table((10**3, 10**6), dps=30)))


def _floor_lines(fig):
    return [ln for ln in fig.axes[0].get_lines() if ln.get_label() == "precision floor"]


def test_precision_floor_is_the_smallest_best_order_error_and_needs_that_row():
    rows = error_table((10**3, 10**6), dps=30)
    (floor,) = _floor_lines(plot_asymptotic_errors(rows))
    best = [float(r["rel_error"]) for r in rows if r["formula"] == "best"]
    assert best and list(floor.get_ydata()) == [min(best)] * 2
    # a table without the best-order row has no floor to draw
    assert _floor_lines(plot_asymptotic_errors([r for r in rows if r["formula"] != "best"])) \
        == []
