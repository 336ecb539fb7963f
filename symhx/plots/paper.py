"""The paper's figures 1-13, each drawn one way with the paper's parameters: the book and
``symhx paper`` both call :func:`paper_figure`, so a figure shows the same thing (the same sample
spaces, the same values of ``p``) wherever it appears.

:data:`PAPER_FIGURES` says for each number what is plotted and with which parameters (the
captions of the book quote it); the functions that draw are the ``plot_*`` functions of the
other modules of :mod:`symhx.plots`.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from symhx.plots._style import COLUMN_WIDTH, PNG_DPI, styled
from symhx.validation import InputError

__all__ = ["COLUMN_WIDTH", "PAPER_FIGURES", "PAPER_N", "PNG_DPI", "paper_figure",
           "save_paper_figure", "stored_ensemble"]

#: the paper's row: 100 pipes, so N = 101 possible impacts
PAPER_N = 101

#: what each of the paper's figures shows here, and with which parameters (and the function
#: that draws it)
PAPER_FIGURES: dict[int, str] = {
    1: "a row of n = 3 pipes between two walls; its N = 4 gaps are the possible impacts "
       "(plot_pipe_row)",
    2: "the complete digraph with loops on the N = 4 impacts of 3 pipes: 4 vertices, 16 edges "
       "(plot_impact_graph)",
    3: "fraction of the simple circuits of length k, N = 100 vertices (plot_circuit_counts)",
    4: "P(X = k) over the simple circuits, N = 101, (a) p = 0.01, (b) 0.02, (c) 0.05, (d) 0.1 "
       "(plot_distributions)",
    5: "the mode k*(p), N = 101, (a) 0 < p <= 0.05, (b) a blow-up around the jump "
       "(plot_mode_path)",
    6: "f(k) and log Phi(k)/Phi(1), N = 101, at (a) p = p_d/2, (b) p_d, (c) (p_d + p_c)/2, "
       "(d) p_c (plot_jump_mechanism)",
    7: "most likely number of impacting pipes against sigma, stored ensemble of 100 pipes "
       "(plot_mode_vs_sigma)",
    8: "expected number of impacting pipes against sigma, stored ensemble of 100 pipes "
       "(plot_mean_vs_sigma)",
    9: "p(sigma) and 1 - p(sigma) of eq. (27), sigma_1 = sigma, omega = 1, Omega = sqrt 2, "
       "d = 1, with the paper's 1 - dblquad (plot_p_sigma)",
    10: "E[X] against p, simple circuits, N = 101, against the stored simulation "
        "(plot_theory_vs_simulation)",
    11: "P(X = k) and its classes in the eq. (41) space, N = 101, (a) p = 0.005, (b) its "
        "k <= 15 detail, (c) p = 0.01, (d) p = 0.05 (plot_class_panels)",
    12: "P(X = k) over the simple and the eq. (41) space, N = 101, (a) p = 0.015, (b) p = 0.04 "
        "(plot_simple_vs_higher_panels)",
    13: "E[X] against p for the spaces simple, eq41 and excess<=4, N = 101, against the stored "
        "simulation (plot_theory_vs_simulation)",
}

#: forcing values of figure 9 and the number of points of the paper's naive formula
FIG9_SIGMAS = (0.01, 100.0, 300)
FIG9_NAIVE_POINTS = 15

_SIMULATED = (7, 8, 10, 13)


def stored_ensemble() -> Any:
    """The stored production ensemble behind figures 7, 8, 10 and 13
    (``symhx/data/ensemble_fig7_8.json``) as an :class:`symhx.impact.EnsembleResult`."""
    from importlib import resources

    from symhx.impact import EnsembleResult

    text = resources.files("symhx").joinpath("data/ensemble_fig7_8.json").read_text()
    return EnsembleResult.from_dict(json.loads(text))


@styled
def paper_figure(number: int, *, ensemble: Any = None) -> Any:
    """Figure ``number`` (1-13) of the paper, drawn with the parameters of :data:`PAPER_FIGURES`.

    Parameters
    ----------
    number : int
        The paper's figure number, 1 to 13.
    ensemble : EnsembleResult, optional
        The simulation of figures 7, 8, 10 and 13 (default: :func:`stored_ensemble`).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If ``number`` is not one of 1, ..., 13.

    >>> fig = paper_figure(1)
    >>> fig.axes[0].get_title()
    '$n = 3$ pipes, $N = n + 1 = 4$ possible impacts (sites $i = 0, \\\\ldots, 3$)'
    """
    if isinstance(number, bool) or number not in PAPER_FIGURES:
        raise InputError(f"number: the paper's figures are 1 to 13, got {number!r}")
    if number in _SIMULATED and ensemble is None:
        ensemble = stored_ensemble()
    if number == 1:
        from symhx.plots.graph import plot_pipe_row

        return plot_pipe_row(3)
    if number == 2:
        from symhx.plots.graph import plot_impact_graph

        return plot_impact_graph(3)
    if number == 3:
        from symhx.plots.circuits import plot_circuit_counts

        return plot_circuit_counts(100)
    if number == 4:
        from symhx.plots.core import plot_distributions

        return plot_distributions(PAPER_N, (0.01, 0.02, 0.05, 0.1))
    if number == 5:
        from symhx.plots.core import plot_mode_path

        return plot_mode_path(PAPER_N, p_max=0.05)
    if number == 6:
        from symhx.plots.core import plot_jump_mechanism

        return plot_jump_mechanism(PAPER_N)
    if number == 7:
        from symhx.plots.impact import plot_mode_vs_sigma

        return plot_mode_vs_sigma(ensemble)
    if number == 8:
        from symhx.plots.impact import plot_mean_vs_sigma

        return plot_mean_vs_sigma(ensemble)
    if number == 9:
        from symhx.plots.forcing import plot_p_sigma

        lo, hi, n = FIG9_SIGMAS
        return plot_p_sigma(np.geomspace(lo, hi, n), naive=True, n_naive=FIG9_NAIVE_POINTS)
    if number == 10:
        from symhx.plots.impact import plot_theory_vs_simulation

        return plot_theory_vs_simulation(ensemble, title="Fig. 10")
    if number == 11:
        from symhx.plots.higher_order import plot_class_panels

        return plot_class_panels(PAPER_N)
    if number == 12:
        from symhx.plots.higher_order import plot_simple_vs_higher_panels

        return plot_simple_vs_higher_panels(PAPER_N)
    from symhx.plots.higher_order import FIG13_SPACES
    from symhx.plots.impact import plot_theory_vs_simulation

    return plot_theory_vs_simulation(ensemble, spaces=FIG13_SPACES, title="Fig. 13")


def save_paper_figure(number: int, path: Any, *, ensemble: Any = None) -> Any:
    """Draw figure ``number`` (:func:`paper_figure`), write it as a PNG at
    :data:`symhx.plots._style.PNG_DPI` (1360 px across) to ``path`` and close it; returns
    ``path``."""
    import matplotlib.pyplot as plt

    fig = paper_figure(number, ensemble=ensemble)
    try:
        fig.savefig(path, dpi=PNG_DPI, bbox_inches="tight")
    finally:
        plt.close(fig)
    return path
