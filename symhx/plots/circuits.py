"""Figure 3 of the paper: how the simple circuits are spread over their lengths.

:func:`plot_circuit_counts` draws ``phi_N(k) / phi_N^tot`` against ``k`` where ``phi_N(k)`` is
eq. (5) and ``phi_N^tot = sum_j phi_N(j)``. The ratios are computed from the exact integers and
rounded once to float64 (:func:`circuit_fractions`), so every plotted point is correctly rounded;
ratios below the float64 range (about ``1e-308``, only for ``N`` in the hundreds) are dropped.
"""

from __future__ import annotations

from fractions import Fraction

import matplotlib.pyplot as plt
import numpy as np

from symhx.circuits import phi, total_simple_circuits
from symhx.plots._style import COLUMN_WIDTH, styled

__all__ = ["circuit_fractions", "plot_circuit_counts"]


def circuit_fractions(N: int) -> tuple[np.ndarray, np.ndarray]:
    """``(k, phi_N(k) / phi_N^tot)`` for ``k`` from 1 to ``N``, each ratio exact, then rounded
    to float64.

    >>> k, frac = circuit_fractions(4)
    >>> k.tolist(), frac.tolist() == [4 / 24, 6 / 24, 8 / 24, 6 / 24]
    ([1, 2, 3, 4], True)
    """
    total = total_simple_circuits(N)
    ks = np.arange(1, N + 1)
    fracs = np.array([float(Fraction(phi(N, int(k)), total)) for k in ks])
    return ks, fracs


def _nice_step(target: float) -> int:
    """Smallest of 1, 2, 5, 10, 20, 50, ... decades that is >= ``target``."""
    scale = 1
    while True:
        for m in (1, 2, 5):
            if m * scale >= target:
                return m * scale
        scale *= 10


@styled
def plot_circuit_counts(N: int = 100, *, ax=None, log: bool = True):
    """Figure 3: fraction of the simple circuits that have length ``k``, for ``N`` vertices.

    Parameters
    ----------
    N : int
        Number of vertices (``N = n + 1`` for ``n`` pipes); the paper uses ``N = 100``.
    ax : matplotlib Axes, optional
        Axes to draw in; a new figure is made if omitted.
    log : bool
        Logarithmic ordinate (default): the fractions span hundreds of decades.

    Returns
    -------
    matplotlib.figure.Figure
        The first line of the axes holds the plotted data (zero ratios removed).
    """
    if ax is None:
        fig, ax = plt.subplots(figsize=(COLUMN_WIDTH, 3.6), layout="constrained")
    else:
        fig = ax.figure
    ks, fracs = circuit_fractions(N)
    keep = fracs > 0
    ax.plot(ks[keep], fracs[keep], marker="o", ms=2.5, lw=0.8, color="#08519c",
            label=r"$\phi_N(k)/\phi_N^{\mathrm{tot}}$")
    if log:
        ax.set_yscale("log")
        smallest = fracs[keep].min()
        lowest = int(np.floor(np.log10(smallest)))
        step = _nice_step(-lowest / 8)
        ticks = [10.0**e for e in range(0, lowest - 1, -step)]
        ax.set_yticks([t for t in ticks if t >= smallest])
        bottom = 10.0 ** (lowest - 1)
        ax.set_ylim(bottom if bottom > 0 else smallest, 3.0)
    ax.set_xlabel(r"circuit length $k$")
    ax.set_ylabel(r"$\phi_N(k)\,/\,\phi_N^{\mathrm{tot}}$")
    ax.set_title(rf"simple circuits of the complete digraph, $N = {N}$")
    ax.set_xlim(0, N + 1)
    ax.grid(True, which="major", alpha=0.3)
    return fig
