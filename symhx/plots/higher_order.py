"""Figures 11-13 of the paper (section 8): higher-order circuits.

* :func:`plot_class_decomposition` -- figure 11: ``P(X = k)`` over a space and its split by class;
* :func:`plot_simple_vs_higher` -- figure 12: the simple and higher-order distributions together;
* :func:`plot_mean_vs_p_spaces` -- figure 13 (theory curves): ``E[X]`` against ``p`` per space.

Probabilities are computed with mpmath (:mod:`symhx.spaces`) and rounded once to float64.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from symhx.plots._style import COLUMN_WIDTH, space_style, styled
from symhx.spaces import class_decomposition, distribution

__all__ = ["FIG11_PANELS", "FIG12_PS", "FIG12_SPACES", "FIG13_SPACES", "plot_class_decomposition",
           "plot_class_panels", "plot_mean_vs_p_spaces", "plot_simple_vs_higher",
           "plot_simple_vs_higher_panels"]

#: figure 11's panels as in the paper: (p, largest k shown), (b) the small-k detail of (a)
FIG11_PANELS: tuple[tuple[float, int | None], ...] = ((0.005, None), (0.005, 15), (0.01, 40),
                                                      (0.05, None))
#: figure 12's two values of p and the spaces it compares (simple circuits and eq. 41)
FIG12_PS: tuple[float, ...] = (0.015, 0.04)
FIG12_SPACES: tuple[str, ...] = ("simple", "eq41")
#: the sample spaces of figure 13, in the book and in ``symhx paper`` alike: the paper's simple
#: circuits (dotted) and eq. (41) (solid), and the consistent truncation ``excess<=4``
FIG13_SPACES: tuple[str, ...] = ("simple", "eq41", "excess<=4")


def _axes(ax, size=(COLUMN_WIDTH, 3.8)):
    if ax is None:
        fig, ax = plt.subplots(figsize=size, layout="constrained")
        return fig, ax
    return ax.figure, ax


@styled
def plot_class_decomposition(N: int = 100, p: float = 0.01, *, space: str = "eq41",
                             kmax: int | None = None, logy: bool = True, floor: float = 1e-12,
                             ax=None, legend: bool = True):
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
    legend : bool
        Draw the legend (class names with ``P(class)``) in the axes.

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
        ax.plot(ks[:top], ys, lw=1.1, ls="--",
                label=rf"${lab}$: {float(cd.totals[s]):.3g}")
    if logy:
        ax.set_yscale("log")
        peak = float(total[:top].max())
        ax.set_ylim(peak * floor, peak * 3)
    ax.set_xlabel(r"number of distinct impacts $k$")
    ax.set_ylabel(r"probability" + (" (log scale)" if logy else ""))
    ax.set_title(rf"classes of circuits, $N={N}$, $p={p}$, space {space}")
    if legend:
        ax.legend(title="class: P(class)")
    return fig


@styled
def plot_class_panels(N: int = 101, panels: Sequence[tuple[float, int | None]] = FIG11_PANELS,
                      *, space: str = "eq41") -> Any:
    """Figure 11 as in the paper: one panel of :func:`plot_class_decomposition` per
    ``(p, kmax)`` of ``panels`` (default :data:`FIG11_PANELS`: (a) ``p = 0.005``, (b) its
    small-``k`` detail, (c) ``p = 0.01``, (d) ``p = 0.05``), one legend of the classes below.

    Returns
    -------
    matplotlib.figure.Figure

    >>> fig = plot_class_panels(30, ((0.01, None), (0.01, 8)))
    >>> [a.get_title()[:3] for a in fig.axes]
    ['(a)', '(b)']
    """
    n = len(panels)
    rows = -(-n // 2)
    fig, grid = plt.subplots(rows, 2, figsize=(COLUMN_WIDTH, 2.7 * rows + 0.9), squeeze=False,
                             layout="constrained")
    axes = list(grid.ravel())
    for extra in axes[n:]:
        extra.remove()
    for i, (ax, (p, kmax)) in enumerate(zip(axes, panels, strict=False)):
        plot_class_decomposition(N, p, space=space, kmax=kmax, ax=ax, legend=False)
        detail = f", $k \\leq {kmax}$" if kmax else ""
        ax.set_title(f"({'abcdefgh'[i]}) $p = {p:g}${detail}")
        ax.set_ylabel("probability")
        ax.set_xlabel("distinct impacts $k$")
    handles, labels = axes[0].get_legend_handles_labels()
    names = [lab.split(":")[0] for lab in labels]
    fig.legend(handles, names, loc="outside lower center", ncol=len(names))
    fig.suptitle(f"Classes of circuits, space {space}, $N = {N}$")
    return fig


@styled
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
                label=f"{sp}, E[X] = {float(d.mean()):.1f}")
    ax.set_xlabel(r"number of distinct impacts $k$")
    ax.set_ylabel(r"$P(X=k)$")
    ax.set_title(rf"simple and higher-order circuits, $N={N}$, $p={p}$")
    ax.legend()
    return fig


@styled
def plot_simple_vs_higher_panels(N: int = 101, ps: Sequence[float] = FIG12_PS, *,
                                 spaces: Sequence[str] = FIG12_SPACES) -> Any:
    """Figure 12 as in the paper: :func:`plot_simple_vs_higher` at each ``p`` of ``ps`` (default
    :data:`FIG12_PS`, the paper's (a) ``p = 0.015`` and (b) ``p = 0.04``), side by side, with one
    legend of the spaces below; each panel's title gives ``E[X]`` per space.

    Returns
    -------
    matplotlib.figure.Figure

    >>> fig = plot_simple_vs_higher_panels(30, (0.05, 0.1))
    >>> [a.get_title()[:3] for a in fig.axes]
    ['(a)', '(b)']
    """
    fig, axes = plt.subplots(1, len(ps), figsize=(COLUMN_WIDTH, 3.5), squeeze=False,
                             layout="constrained")
    for i, (ax, p) in enumerate(zip(axes[0], ps, strict=True)):
        plot_simple_vs_higher(N, p, spaces=spaces, ax=ax)
        means = ", ".join(lab.rsplit("= ", 1)[1] for lab in ax.get_legend_handles_labels()[1])
        ax.get_legend().remove()
        ax.set_title(f"({'abcdefgh'[i]}) $p = {p:g}$: $E[X]$ = {means}")
        ax.set_xlabel("distinct impacts $k$")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, [lab.split(",")[0] for lab in labels], loc="outside lower center",
               ncol=len(labels))
    fig.suptitle(f"Simple and higher-order circuits, $N = {N}$")
    return fig


@styled
def plot_mean_vs_p_spaces(N: int = 100, *, spaces: Sequence[str] = FIG13_SPACES,
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
        mu = [float(distribution(N, float(p), space=sp, dps=15).mean()) for p in ps]
        ax.plot(ps, mu, label=sp, **space_style(sp, i))
    if simulation is not None:
        ax.plot(simulation[0], simulation[1], "x", color="black", label="simulation")
    ax.set_xscale("log")
    ax.set_xlabel(r"impact probability $p$")
    ax.set_ylabel(r"$E[X]$")
    ax.set_title(rf"expected number of distinct impacts, $N={N}$")
    ax.legend()
    return fig
