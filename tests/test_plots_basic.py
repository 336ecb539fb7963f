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


# --------------------------------------------------------------------------- figures 4-6, 11, 13
def _pmf_brute(N, p):
    """P(X = k) from phi_N(k) = N!/((N-k)! k) (eq. 7) with exact rationals (independent of the
    package's distribution code)."""
    p = Fraction(p)
    w = [Fraction(math.perm(N, k), k) * p**k for k in range(1, N + 1)]
    z = sum(w)
    return [x / z for x in w]


import math  # noqa: E402


def test_figure4_panels_a_to_d_hold_the_pmf():
    ps = (0.01, 0.02, 0.05, 0.1)
    fig = plots.plot_distributions(31, ps)
    assert len(fig.axes) == 4
    for letter, ax, p in zip("abcd", fig.axes, ps, strict=True):
        assert ax.get_title().startswith(f"({letter})") and f"{p:g}" in ax.get_title()
        assert ax.get_legend() is not None
        ks, ys = ax.lines[0].get_data()
        ref = _pmf_brute(31, p)
        assert list(ks) == list(range(1, 32))
        for y, r in zip(ys, ref, strict=True):
            assert abs(y - float(r)) <= 1e-13 * float(r) + 1e-300


def test_figure5_has_a_blow_up_and_the_right_steps():
    N = 21
    fig = plots.plot_mode_path(N, p_max=0.5)
    a, b = fig.axes
    assert a.get_title().startswith("(a)") and b.get_title().startswith("(b)")
    assert b.get_xlim()[1] < a.get_xlim()[1] / 2  # a real blow-up
    for ax in (a, b):
        assert ax.get_legend() is not None
        xs, ys = ax.lines[0].get_data()
        # between consecutive breakpoints the mode is the brute-force argmax of the pmf
        for x0, x1, y in zip(xs[:-1], xs[1:], ys[:-1], strict=True):
            if x1 - x0 > 1e-9:
                mid = Fraction((x0 + x1) / 2)
                pmf = _pmf_brute(N, mid)
                assert y == 1 + max(range(N), key=lambda i: pmf[i]), (x0, x1, y)


def test_figure6_same_colour_for_same_p_and_a_legend_on_each_panel():
    fig = plots.plot_f_and_phi(101)
    top, bottom = fig.axes
    assert top.get_legend() is not None and bottom.get_legend() is not None
    top_colour = {ln.get_label(): ln.get_color() for ln in top.lines if not
                  ln.get_label().startswith("_")}
    legend_labels = [t.get_text() for t in bottom.get_legend().get_texts()]
    assert len(legend_labels) == len(top_colour) == 4
    for ln in bottom.lines:
        lab = ln.get_label()
        if lab.startswith("_"):
            continue
        key = next(k for k in top_colour if lab.startswith(k))
        assert ln.get_color() == top_colour[key], lab
    # the message of the figure: below p_c, Phi(k) < Phi(1) for every k >= 2; above, not
    cp = symhx.critical_point(101, dps=30)
    for ln in bottom.lines:
        x, y = ln.get_data()
        if len(x) == 0 or ln.get_label().startswith("_"):
            continue
        p = float(ln.get_label().rsplit("=", 1)[1].strip(" $"))
        assert (max(y[1:]) > 0) == (p > float(cp.p)), ln.get_label()


def test_figure11_log_axis_and_no_line_to_zero():
    from symhx.plots.higher_order import plot_class_decomposition

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
    from symhx.plots.higher_order import plot_mean_vs_p_spaces

    fig = plot_mean_vs_p_spaces(30, spaces=("simple", "eq41", "eq41-printed"), points=4)
    lines = {ln.get_label(): ln for ln in fig.axes[0].lines}
    a, b = lines["eq41"], lines["eq41-printed"]
    assert a.get_linestyle() != b.get_linestyle() and a.get_color() != b.get_color()
    assert a.get_linewidth() > b.get_linewidth()  # the wide line below stays visible
    assert lines["simple"].get_linestyle() == ":"  # as in the paper: simple circuits dotted


import numpy as np  # noqa: E402
