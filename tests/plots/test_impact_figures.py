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
    # marked by open circles, not joined by a line
    assert marked[0].get_marker() == "o" and marked[0].get_linestyle() == "None"
    assert marked[0].get_markerfacecolor() == "none"
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


def test_theory_means_default_to_the_simple_space(res):
    from symhx import mean
    from symhx.plots.impact import theory_means

    got = theory_means([0.01, 0.02], 21)
    assert got.tolist() == [float(mean(21, 0.01, dps=20)), float(mean(21, 0.02, dps=20))]


def test_paper_figures_are_saved_at_200_dpi_from_the_given_ensemble_and_closed(res, tmp_path):
    import matplotlib.pyplot as plt
    from matplotlib.image import imread

    from symhx.plots.paper import paper_figure, save_paper_figure

    before = plt.get_fignums()
    path = save_paper_figure(8, tmp_path / "fig8.png", ensemble=res)
    assert plt.get_fignums() == before  # closed
    height, width = imread(path).shape[:2]
    drawn = paper_figure(8, ensemble=res)
    w_in, h_in = drawn.get_size_inches()
    # 200 dpi, cropped to the content by bbox_inches="tight" (plus its 0.1 in padding)
    assert 0.85 * 200 * w_in < width <= 200 * (w_in + 0.2) + 2
    assert height <= 200 * (h_in + 0.2) + 2
    # the figure of the given ensemble, not of the stored one (its sigmas)
    xs = np.concatenate([ln.get_xdata() for ln in drawn.axes[0].lines])
    assert xs.size and set(xs.tolist()) == set(res.sigmas.tolist())
