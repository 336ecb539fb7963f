"""Figures 4-6 (:mod:`symhx.plots.core`): the distribution, the mode path and f/Phi, checked by
their data against exact references."""

from __future__ import annotations

from fractions import Fraction

import pytest

import symhx
import symhx.plots as plots
from tests.harness.figures import assert_fits_the_column
from tests.reference.distribution import brute_modes, pmf_table


def test_figure4_panels_a_to_d_hold_the_pmf():
    ps = (0.01, 0.02, 0.05, 0.1)
    fig = plots.plot_distributions(31, ps)
    assert len(fig.axes) == 4
    for letter, ax, p in zip("abcd", fig.axes, ps, strict=True):
        assert ax.get_title().startswith(f"({letter})") and f"{p:g}" in ax.get_title()
        assert ax.get_legend() is not None
        ks, ys = ax.lines[0].get_data()
        ref = pmf_table(31, Fraction(p))
        assert list(ks) == list(range(1, 32))
        for y, r in zip(ys, ref, strict=True):
            assert abs(y - float(r)) <= 1e-13 * float(r) + 1e-300


def test_figure5_has_a_blow_up_and_the_mode_of_each_step():
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
                pmf = pmf_table(N, Fraction((x0 + x1) / 2))
                assert y == 1 + max(range(N), key=lambda i: pmf[i]), (x0, x1, y)
        # the path ends flat at the right edge, with the mode of its last step
        assert ys[-1] == ys[-2] and xs[-1] > xs[-2]


def test_figure6_reference_lines_mark_where_f_and_the_log_ratio_vanish():
    # f = 0 (the roots) on the top panel, log Phi(k) - log Phi(1) = 0 (Phi(k) = Phi(1)) below
    fig = plots.plot_f_and_phi(101)
    for ax in fig.axes:
        flat = [ln for ln in ax.lines if len(set(ln.get_ydata())) == 1 and
                list(ln.get_xdata()) == [0, 1]]  # axhline: axes-fraction x from 0 to 1
        assert [ln.get_ydata()[0] for ln in flat] == [0]


def test_figure6_same_colour_for_same_p_and_a_legend_on_each_panel():
    fig = plots.plot_f_and_phi(101)
    top, bottom = fig.axes
    assert top.get_legend() is not None and bottom.get_legend() is not None
    top_colour = {ln.get_label(): ln.get_color() for ln in top.lines if not
                  ln.get_label().startswith("_")}
    legend_labels = [t.get_text() for t in bottom.get_legend().get_texts()]
    assert len(legend_labels) == len(top_colour) == 4
    # the four p: 0, p_d, halfway to p_c, and above p_c
    names = [lab.split("=")[1].strip(" $") for lab in top_colour]
    assert names == ["0", "p_d", "(p_d + p_c)/2", r"1.05\,p_c"], names
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


def test_figure6_marks_the_roots_of_f_and_draws_f_and_phi():
    """Each row's dots on the f panel sit on the real roots of f_{N,p}(k) = -p k**2 + (N p - 1) k
    - 1 (eq. 10) at that row's p (read back from the drawn parabola), and the right panel is
    log Phi(k) - log Phi(1) from exact factorials."""
    import math

    N = 101
    fig = plots.plot_jump_mechanism(N)
    axes = fig.axes
    counts = []
    for row in range(4):
        af, ap = axes[2 * row], axes[2 * row + 1]
        k, fk = af.lines[0].get_data()
        # p from the drawn curve: (f(k) + 1)/k + 1 = p (N - k)
        p = ((fk[-1] + 1) / k[-1] + 1) / (N - k[-1])
        dots = [ln for ln in af.lines[1:] if ln.get_marker() == "o"]
        roots = []
        for ln in dots:
            (r,), (y,) = ln.get_data()
            assert y == 0.0
            assert abs(-p * r * r + (N * p - 1) * r - 1) < 1e-9 * max(1.0, N * p * r)
            roots.append(r)
        if len(roots) == 2:  # both roots (Vieta: their product is 1/p), not one twice
            assert abs(roots[0] * roots[1] * p - 1) < 1e-9
        counts.append(len(dots))
        kk, lphi = ap.lines[0].get_data()
        for ki, v in zip(kk[:20], lphi[:20], strict=True):
            ref = (ki - 1) * math.log(p) + math.lgamma(N + 1) - math.log(ki) \
                - math.lgamma(N - ki + 1) - math.lgamma(N + 1) + math.lgamma(N)
            assert abs(v - ref) < 1e-9 * max(1.0, abs(ref)), (row, ki)
    # (a) no real root, (b) the double root k_d, (c) and (d) two roots
    assert counts[0] == 0 and counts[1] >= 1 and counts[2] == counts[3] == 2


def test_figures_4_to_6_fit_the_column():
    for fig in (plots.plot_distributions(31, (0.01, 0.02, 0.05)), plots.plot_mode_path(21),
                plots.plot_f_and_phi(101), plots.plot_jump_mechanism(101)):
        assert_fits_the_column(fig)


def test_figure4_draws_into_given_axes_and_refuses_too_few():
    import matplotlib.pyplot as plt
    import pytest

    from tests.harness.errors import assert_refuses

    fig, grid = plt.subplots(2, 2)
    assert plots.plot_distributions(31, (0.01, 0.02, 0.05), axes=grid) is fig
    assert [len(ax.lines) > 0 for ax in grid.ravel()] == [True, True, True, False]
    with pytest.raises(ValueError):
        plots.plot_distributions(31, (0.01, 0.02, 0.05), axes=grid[0])
    assert_refuses(plots.plot_distributions, 31, (0.01, 0.02, 0.05), axes=grid[0],
                   arg="axes", value="got 2", allowed="need 3")


def test_figure4_with_one_panel():
    fig = plots.plot_distributions(31, (0.02,))
    assert len(fig.axes) == 1 and fig.axes[0].get_title().startswith("(a)")


def test_figure6_jump_mechanism_defaults_to_the_papers_row():
    fig = plots.plot_jump_mechanism()
    assert "$N = 101$" in fig.axes[1].get_title(loc="right")


@pytest.mark.parametrize("N, p_max, mode", [
    # N = 6: the mode steps 4 -> 5 at p = 5/8, exact in float64; at a breakpoint both lengths
    # maximise Phi and the mode is the smaller one
    (6, 0.625, 4),
    # N = 7: it steps 4 -> 5 at p = 5/12, whose float64 lies above 5/12: the mode there is 5
    (7, 5 / 12, 5),
])
def test_figure5_ends_on_the_mode_at_p_max_when_p_max_is_a_breakpoint(N, p_max, mode):
    end = Fraction(p_max)  # the float exactly
    assert min(brute_modes(N, end)) == mode
    xs, ys = plots.plot_mode_path(N, p_max=p_max).axes[0].lines[0].get_data()
    assert xs[-1] == p_max and ys[-1] == mode
    # and every step drawn is the brute-force mode at its midpoint
    for x0, x1, y in zip(xs[:-1], xs[1:], ys[:-1], strict=True):
        if x1 > x0:
            assert y == min(brute_modes(N, (Fraction(x0) + Fraction(x1)) / 2)), (x0, x1, y)


@pytest.mark.parametrize("N", [5, 7])
def test_figure5_ends_on_the_mode_at_p_max_when_p_max_is_the_rounded_jump(N):
    # p_max = p_c rounded to float64 (exactly 1/2 for N = 5, where 1, 2 and 3 tie; irrational
    # for N = 7, and its float64 lies above it): the last step is the brute-force mode there
    pc = float(symhx.critical_point(N).p)
    xs, ys = plots.plot_mode_path(N, p_max=pc).axes[0].lines[0].get_data()
    assert xs[-1] == pc and ys[-1] == min(brute_modes(N, Fraction(pc))) == {5: 1, 7: 3}[N]
