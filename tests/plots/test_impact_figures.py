"""Figures 7, 8, 10 and 13 of ``symhx.plots.impact`` from an ensemble: legends, error bars that
never go below 0, and the data drawn (values of sigma resting on fewer than ``min_count`` runs
with an impact are marked apart, not joined to the curve)."""

from __future__ import annotations

import numpy as np
import pytest

from symhx.impact.ensemble import ensemble
from tests.harness.figures import assert_fits_the_column

mpl = pytest.importorskip("matplotlib")
mpl.use("Agg")


@pytest.fixture(scope="module")
def res():
    return ensemble([0.12, 0.2, 0.35], 12, chunk=5, n=20, t_transient=30.0, t_window=20.0,
                    seed=123, progress=False)


def test_figures_have_legends_and_nonnegative_error_bars(res):
    import matplotlib.pyplot as plt

    from symhx import plots

    for f in (plots.plot_mode_vs_sigma, plots.plot_mean_vs_sigma,
              plots.plot_theory_vs_simulation):
        fig = f(res)
        for ax in fig.axes:
            assert ax.get_legend() is not None
            assert ax.get_ylim()[0] >= 0
        plt.close(fig)
    mode, err = plots.impact._yerr(res, "pipes", "mode")
    ok = np.isfinite(mode)
    assert np.all(mode[ok] - err[0][ok] >= 0) and np.all(err[:, ok] >= 0)
    # the bars span exactly the stored 95 % interval
    ci = res.column("pipes", "mode_ci")
    assert np.allclose((mode - err[0])[ok], ci[ok, 0], rtol=0, atol=1e-12)
    assert np.allclose((mode + err[1])[ok], ci[ok, 1], rtol=0, atol=1e-12)


@pytest.mark.parametrize("stat", ["mode", "mean"])
def test_figures_7_and_8_mark_sigmas_with_few_runs_apart(res, stat):
    import matplotlib.pyplot as plt

    from symhx import plots

    f = plots.plot_mode_vs_sigma if stat == "mode" else plots.plot_mean_vs_sigma
    counts = res.column("pipes", "count")
    values = res.column("pipes", stat)
    cut = sorted(counts)[1] + 0.5          # one or two sigmas fall below it
    few = counts < cut
    assert few.any() and (~few).any()
    fig = f(res, min_count=cut)
    ax = fig.axes[0]
    curve = ax.lines[0]                     # the joined curve: only the well-sampled sigmas
    assert np.array_equal(curve.get_xdata(), res.sigmas[~few])
    assert np.array_equal(curve.get_ydata(), values[~few], equal_nan=True)
    marked = [ln for ln in ax.lines if ln.get_label().startswith("fewer than")]
    assert len(marked) == 1
    assert np.array_equal(marked[0].get_xdata(), res.sigmas[few])
    assert np.array_equal(marked[0].get_ydata(), values[few], equal_nan=True)
    plt.close(fig)
    fig = f(res, min_count=0)               # nothing marked: one curve through every sigma
    assert not [ln for ln in fig.axes[0].lines if ln.get_label().startswith("fewer than")]
    assert np.array_equal(fig.axes[0].lines[0].get_xdata(), res.sigmas)
    plt.close(fig)


def test_ensemble_figures_fit_the_column(res):
    from symhx import plots

    for f in (plots.plot_mode_vs_sigma, plots.plot_mean_vs_sigma, plots.plot_theory_vs_simulation):
        assert_fits_the_column(f(res))
    from symhx.impact import PipeRow, simulate

    assert_fits_the_column(plots.plot_gaps(simulate(PipeRow.random(4, 0.5, seed=1), 10.0)))
