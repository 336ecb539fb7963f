"""Figures 9 and 10's theory curve (:mod:`symhx.plots.forcing`), checked by their data: the
curves of p(sigma) and 1 - p(sigma) against the closed form of eq. (27), the theory curve
against the exact mean of the simple space at the plotted p, titles and legends that name
the parameters."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx.plots as plots
from tests.harness.errors import assert_refuses
from tests.harness.figures import assert_fits_the_column
from tests.reference.distribution import moments_of, pmf_table
from tests.reference.forcing import eq27_p


def test_figure9_plots_p_and_its_complement_from_eq27():
    sigma = np.array([0.05, 0.3, 1.0, 7.0])
    fig = plots.plot_p_sigma(sigma, omega=1.0, d=1.0)
    ax = fig.axes[0]
    (s1, p_line), (s2, q_line) = (line.get_data() for line in ax.lines[:2])
    assert list(s1) == list(s2) == list(sigma)
    with mpmath.workdps(40):
        for s, p, q in zip(sigma, p_line, q_line, strict=True):
            ref = eq27_p(s, None, 1, None, 1)
            # clamped at 1e-300 on the plot (a log axis cannot show 1e-870)
            assert abs(p - max(float(ref), 1e-300)) <= 1e-12 * max(float(ref), 1e-300)
            assert abs(q - max(float(1 - ref), 1e-300)) <= 1e-12 * max(float(1 - ref), 1e-300)
    assert ax.get_xscale() == ax.get_yscale() == "log"
    title = ax.get_title()
    assert title.startswith("Fig. 9") and "ω = 1.0" in title and "Ω = √2" in title
    assert "σ₁ = σ" in title and "d = 1.0" in title
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["p (impact)",
                                                                   "1 − p (no impact)"]


def test_figure9_names_other_parameters_in_its_title():
    fig = plots.plot_p_sigma(np.array([0.5, 1.0]), sigma1=0.25, Omega=1.5, d=2.0)
    title = fig.axes[0].get_title()
    assert "σ₁ = 0.25" in title and "Ω = 1.5" in title and "d = 2.0" in title
    # the defaults: the paper's sigma1 = sigma, Omega = sqrt(2)
    default = plots.plot_p_sigma(np.array([0.5, 1.0])).axes[0].get_title()
    assert default.endswith(": impact probability, σ₁ = σ, ω = 1.0, Ω = √2, d = 1.0")


@pytest.mark.parametrize("N", [11, 101])
def test_figure10_theory_curve_is_the_exact_mean_at_the_plotted_p(N):
    sigma = np.array([0.1, 0.2, 0.4])
    fig = plots.plot_theory_mean_vs_p(sigma, N=N)
    ax = fig.axes[0]
    ps, means = ax.lines[0].get_data()
    with mpmath.workdps(40):
        for s, p in zip(sigma, ps, strict=True):
            assert abs(p - float(eq27_p(s, None, 1, None, 1))) <= 1e-14 * p
    for p, m in zip(ps, means, strict=True):
        mu, _ = moments_of(pmf_table(N, Fraction(float(p))))
        assert abs(m - float(mu)) <= 1e-12 * float(mu)
    assert ax.get_xscale() == "log" and ax.get_xlabel() == "impact probability p"
    assert f"N = {N}" in ax.get_legend().get_texts()[0].get_text()
    assert "space simple" in ax.get_title()


def test_figure10_against_sigma_and_a_simulation_overlay():
    sigma = np.array([0.1, 0.3])
    sim = (np.array([0.1, 0.3]), np.array([1.5, 3.0]))
    fig = plots.plot_theory_mean_vs_p(sigma, N=11, against="sigma", simulation=sim)
    ax = fig.axes[0]
    assert list(ax.lines[0].get_xdata()) == list(sigma)
    xs, ms = ax.lines[1].get_data()
    assert list(xs) == [0.1, 0.3] and list(ms) == [1.5, 3.0]
    assert ax.get_xlabel() == "σ"
    assert [t.get_text() for t in ax.get_legend().get_texts()][-1] == "simulation"


def test_figure10_refuses_an_unknown_axis():
    assert_refuses(plots.plot_theory_mean_vs_p, np.array([0.2]), N=11, against="time",
                   arg="against", value="time", allowed="'p' or 'sigma'")


def test_figures_9_and_10_fit_the_column():
    assert_fits_the_column(plots.plot_p_sigma(np.array([0.05, 0.3, 1.0]), omega=1.0, d=1.0))
    assert_fits_the_column(plots.plot_theory_mean_vs_p(np.array([0.1, 0.3, 1.0]), N=31))
