"""Figures 11-13 of the paper (section 8): higher-order circuits.

* :func:`plot_class_decomposition` -- figure 11: ``P(X = k)`` over a space and its split by class;
* :func:`plot_simple_vs_higher` -- figure 12: the simple and higher-order distributions together;
* :func:`plot_mean_vs_p_spaces` -- figure 13 (theory curves): ``E[X]`` against ``p`` per space.

Probabilities are computed with mpmath (:mod:`symhx.spaces`) and rounded once to float64.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import mpmath
import numpy as np

from symhx.spaces import class_decomposition, distribution

__all__ = ["plot_class_decomposition", "plot_mean_vs_p_spaces", "plot_simple_vs_higher"]


def _axes(ax, size=(6.0, 3.8)):
    if ax is None:
        fig, ax = plt.subplots(figsize=size)
        return fig, ax
    return ax.figure, ax


def plot_class_decomposition(N: int = 100, p: float = 0.01, *, space: str = "eq41",
                             kmax: int | None = None, logy: bool = True, floor: float = 1e-12,
                             ax=None):
    """Figure 11: ``P(X = k)`` (solid) and ``P(X = k, class)`` per class, with ``P(class)`` in
    the legend.

    On a linear axis the higher-order classes sit flat on 0 for small ``p`` (at ``p = 0.005``
    they are 3-4 orders of magnitude below the simple circuits), so the default is a logarithmic
    probability axis down to ``floor`` times the largest probability shown.

    Parameters
    ----------
    N : int
        Vertices (the paper's figure uses 100 pipes).
    p : float
        Impact probability.
    space : str
        A space of :mod:`symhx.spaces` (default the corrected eq. 41).
    kmax : int, optional
        Largest k shown (default N).
    logy : bool
        Logarithmic probability axis (default) or linear.
    floor : float
        With ``logy``, the bottom of the axis relative to the largest probability.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = _axes(ax)
    cd = class_decomposition(N, p, space=space, dps=20)
    ks = np.arange(1, N + 1)
    top = kmax or N
    total = np.array([float(sum(cd.joint[s][k - 1] for s in cd.shapes)) for k in ks])
    ax.plot(ks[:top], total[:top], color="black", lw=1.6, label=r"$P(X=k)$")
    for s in cd.shapes:
        lab = cd.labels[s].replace("phi", r"\phi")
        ys = np.array([float(v) for v in cd.joint[s][:top]])
        if logy:
            ys[ys <= 0] = np.nan  # impossible k for this class: no line down to log(0)
        ax.plot(ks[:top], ys, lw=0.9, ls="--",
                label=rf"${lab}$: {float(cd.totals[s]):.3g}")
    if logy:
        ax.set_yscale("log")
        peak = float(total[:top].max())
        ax.set_ylim(peak * floor, peak * 3)
    ax.set_xlabel(r"number of distinct impacts $k$")
    ax.set_ylabel(r"probability" + (" (log scale)" if logy else ""))
    ax.set_title(rf"classes of circuits, $N={N}$, $p={p}$, space {space}")
    ax.legend(fontsize=7)
    return fig


def plot_simple_vs_higher(N: int = 100, p: float = 0.015, *, spaces: Sequence[str] = (
        "simple", "eq41"), ax=None):
    """Figure 12: the distributions of X over several spaces on one axes.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = _axes(ax)
    ks = np.arange(1, N + 1)
    for sp in spaces:
        d = distribution(N, p, space=sp, dps=20)
        ax.plot(ks, [float(d.pmf(int(k))) for k in ks], lw=1.2,
                label=f"{sp}: E[X] = {float(d.mean()):.2f}")
    ax.set_xlabel(r"number of distinct impacts $k$")
    ax.set_ylabel(r"$P(X=k)$")
    ax.set_title(rf"simple and higher-order circuits, $N={N}$, $p={p}$")
    ax.legend(fontsize=8)
    return fig


def _space_style(space: str, i: int) -> dict:
    """Line style of a space in figure 13: the paper draws simple circuits dotted and higher-order
    ones solid; the printed eq. (41) is dashed with markers and drawn on top, so that it never
    hides the corrected eq. (41) it almost coincides with."""
    if space == "simple":
        return {"color": "C0", "ls": ":", "lw": 1.8, "zorder": 2}
    if space == "eq41":
        return {"color": "C1", "ls": "-", "lw": 2.6, "zorder": 2, "alpha": 0.8}
    if space == "eq41-printed":
        return {"color": "C3", "ls": "--", "lw": 1.2, "marker": "o", "ms": 3, "mfc": "none",
                "zorder": 3}
    return {"color": f"C{(i + 4) % 10}", "ls": "-.", "lw": 1.2, "zorder": 2}


def plot_mean_vs_p_spaces(N: int = 100, *, spaces: Sequence[str] = ("simple", "eq41",
                                                                    "excess<=6"),
                          p_range: tuple[float, float] = (1e-3, 0.1), points: int = 60,
                          simulation: tuple[Sequence[float], Sequence[float]] | None = None,
                          ax=None):
    """Figure 13 (theory): ``E[X]`` against ``p`` (log axis) for each space; optional
    ``simulation = (p values, mean distinct impacts)`` drawn as crosses.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = _axes(ax)
    ps = np.geomspace(p_range[0], p_range[1], points)
    for i, sp in enumerate(spaces):
        with mpmath.workdps(20):
            mu = [float(distribution(N, float(p), space=sp, dps=15).mean()) for p in ps]
        ax.plot(ps, mu, label=sp, **_space_style(sp, i))
    if simulation is not None:
        ax.plot(simulation[0], simulation[1], "x", color="black", label="simulation")
    ax.set_xscale("log")
    ax.set_xlabel(r"impact probability $p$")
    ax.set_ylabel(r"$E[X]$")
    ax.set_title(rf"expected number of distinct impacts, $N={N}$")
    ax.legend(fontsize=8)
    return fig
