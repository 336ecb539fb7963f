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
    assert len(ax.get_lines()) >= 7
    plt.close(fig)


def test_asymptotic_errors_fit_the_column():
    assert_fits_the_column(plot_asymptotic_errors(error_table((10**3, 10**6), dps=30)))
