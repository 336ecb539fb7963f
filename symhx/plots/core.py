"""Figures 4-6 of the paper: distributions of X, the mode path with its jump, and f / Phi.

Conventions of every figure here: one legend per panel, the same colour for the same ``p`` in
every panel of a figure, panel letters as in the paper.
"""

from __future__ import annotations

from collections.abc import Sequence
from math import lgamma, log
from typing import Any

import matplotlib.pyplot as plt
import mpmath
import numpy as np

from symhx.api import distribution_of
from symhx.critical import critical_point, mode_path

__all__ = ["plot_distributions", "plot_f_and_phi", "plot_mode_path"]

PANEL_LETTERS = "abcdefghijklmnopqrstuvwxyz"


def _panel_axes(n: int, axes: Any, ncols: int, size: tuple[float, float]) -> tuple[Any, list]:
    if axes is None:
        nrows = -(-n // ncols)
        fig, grid = plt.subplots(nrows, ncols, figsize=size, squeeze=False)
        flat = list(grid.ravel())
        for extra in flat[n:]:
            extra.remove()
        return fig, flat[:n]
    flat = list(np.ravel(axes))
    if len(flat) < n:
        raise ValueError(f"axes: need {n} axes, got {len(flat)}")
    return flat[0].figure, flat[:n]


def plot_distributions(N: int = 101, ps: Sequence[float] = (0.01, 0.02, 0.05, 0.1), *,
                       axes: Any = None, ax: Any = None, logy: bool = False) -> Any:
    """Figure 4: ``P(X = k)`` (eq. 7, simple circuits) against ``k``, one panel per ``p``
    (the paper's (a)-(d): ``p = 0.01, 0.02, 0.05, 0.1`` for 100 pipes).

    Parameters
    ----------
    N : int
        Vertices (``N = 101`` for 100 pipes).
    ps : sequence of float
        One panel per value; ``p`` is taken at its exact binary value.
    axes : sequence of Axes, optional
        Draw the panels into these (at least ``len(ps)``).
    ax : Axes, optional
        Draw every ``p`` into this one axes instead (one legend).
    logy : bool
        Logarithmic probability axis (shows both tails).

    Returns
    -------
    matplotlib.figure.Figure

    >>> fig = plot_distributions(11, (0.1, 0.3))
    >>> [a.get_title() for a in fig.axes]
    ['(a) $p = 0.1$', '(b) $p = 0.3$']
    """
    ks = np.arange(1, N + 1)
    if ax is not None:
        fig, panels = ax.figure, [ax] * len(ps)
    else:
        ncols = 2 if len(ps) > 1 else 1
        fig, panels = _panel_axes(len(ps), axes, ncols,
                                  (5.2 * ncols, 3.2 * -(-len(ps) // ncols)))
    for i, (p, a) in enumerate(zip(ps, panels, strict=True)):
        d = distribution_of(N, p, dps=20)
        pmf = np.array([float(d.pmf(int(k))) for k in ks])
        a.plot(ks, pmf, marker=".", ms=3, lw=0.8, color=f"C{i}",
               label=f"$p = {p:g}$, $E[X] = {float(d.mean()):.3g}$")
        if ax is None:
            a.set_title(f"({PANEL_LETTERS[i]}) $p = {p:g}$")
            a.set_xlabel("number of distinct impacts $k$")
            a.set_ylabel("$P(X=k)$")
            if logy:
                a.set_yscale("log")
            a.legend(fontsize="small")
    if ax is not None:
        ax.set_xlabel("number of distinct impacts $k$")
        ax.set_ylabel("$P(X=k)$")
        ax.set_title(f"Distribution of $X$, $N={N}$ ({N - 1} pipes)")
        if logy:
            ax.set_yscale("log")
        ax.legend(fontsize="small")
    else:
        fig.suptitle(f"Distribution of $X$ (eq. 7), $N = {N}$ ({N - 1} pipes)")
        fig.tight_layout()
    return fig


def _mode_steps(path: Any, p_max: float) -> tuple[list[float], list[int]]:
    xs, ys = [0.0], [1]
    for bp, _, right in path.breakpoints:
        if float(bp) > p_max:
            break
        xs += [float(bp), float(bp)]
        ys += [ys[-1], right]
    xs.append(p_max)
    ys.append(ys[-1])
    return xs, ys


def plot_mode_path(N: int = 101, *, p_max: float = 0.1, zoom: float | None = None,
                   axes: Any = None, ax: Any = None) -> Any:
    """Figure 5: the mode ``k*(p)`` as an exact step function, with ``p_d`` and ``p_c`` marked:
    (a) on ``(0, p_max]``, (b) a blow-up of the small-``p`` region around the jump.

    Parameters
    ----------
    N : int
        Vertices.
    p_max : float
        Right end of panel (a).
    zoom : float, optional
        Right end of the blow-up (b); default ``1.6 p_c``.
    axes : pair of Axes, optional
        Where to draw (a) and (b).
    ax : Axes, optional
        Draw panel (a) only, into this axes.

    Returns
    -------
    matplotlib.figure.Figure

    >>> fig = plot_mode_path(11, p_max=1.0)
    >>> [a.get_title()[:3] for a in fig.axes]
    ['(a)', '(b)']
    """
    path = mode_path(N, p_max=p_max)
    cp = path.critical
    pd, pc = float(cp.p_d), float(cp.p)
    if ax is not None:
        fig, panels = ax.figure, [(ax, p_max)]
    else:
        fig, pair = _panel_axes(2, axes, 2, (11, 3.8))
        panels = [(pair[0], p_max), (pair[1], zoom or min(1.6 * pc, p_max))]
    for i, (a, right) in enumerate(panels):
        xs, ys = _mode_steps(path, right)
        a.plot(xs, ys, color="C0", label="$k^*(p)$ (exact breakpoints)")
        a.axvline(pd, color="C1", ls=":", label=f"$p_d = {mpmath.nstr(cp.p_d, 6)}$ (eq. 16)")
        a.axvline(pc, color="C3", ls="--", label=f"$p_c = {mpmath.nstr(cp.p, 6)}$")
        a.set_xlim(0, right)
        a.set_xlabel("impact probability $p$")
        a.set_ylabel("mode $k^*$")
        what = "" if i == 0 else ", blow-up of small $p$"
        a.set_title(f"({PANEL_LETTERS[i]}) $N={N}${what}: jump $1 \\to {cp.k_after}$")
        a.legend(loc="center right" if i == 0 else "upper left", fontsize="small")
    if ax is None:
        fig.tight_layout()
    return fig


def plot_f_and_phi(N: int = 101, *, ps: Sequence[float] | None = None, axes: Any = None) -> Any:
    """Figure 6 as real plots: ``f_{N,p}(k)`` (eq. 10, top) and
    ``log Phi_{N,p}(k) - log Phi_{N,p}(1)`` (bottom) for ``p`` at 0, ``p_d``, between ``p_d``
    and ``p_c``, and above ``p_c``. Each ``p`` has the same colour in both panels and both panels
    have a legend; at ``p = 0``, ``Phi(k) = 0`` for ``k >= 2`` (the curve is at minus infinity
    and only listed in the legend).

    Returns
    -------
    matplotlib.figure.Figure

    >>> fig = plot_f_and_phi(11)
    >>> len(fig.axes), [len(a.get_legend().get_texts()) for a in fig.axes]
    (2, [4, 4])
    """
    cp = critical_point(N, dps=20)
    pd, pc = float(cp.p_d), float(cp.p)
    if ps is None:
        ps = (0.0, pd, (pd + pc) / 2, pc * 1.05)
    if axes is None:
        fig, axes = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True)
    else:
        fig = axes[0].figure
    k = np.linspace(0.5, N, 400)
    kk = np.arange(1, N + 1)
    names = {pd: "p_d", (pd + pc) / 2: r"(p_d + p_c)/2", pc * 1.05: r"1.05\,p_c"}
    for i, p in enumerate(ps):
        colour = f"C{i}"
        label = f"$p = {names[p]} = {p:.4g}$" if p in names else f"$p = {p:.4g}$"
        axes[0].plot(k, -p * k**2 + (N * p - 1) * k - 1, color=colour, label=label)
        if p > 0:
            lphi = np.array([ki * log(p) + lgamma(N + 1) - log(ki) - lgamma(N - ki + 1)
                             for ki in kk])
            axes[1].plot(kk, lphi - lphi[0], color=colour, label=label)
        else:
            axes[1].plot([], [], color=colour, label=label + r" ($\Phi(k) = 0$, $k \geq 2$)")
    axes[0].axhline(0, color="k", lw=0.5)
    axes[0].set_ylabel("$f_{N,p}(k)$")
    axes[0].legend(fontsize="small")
    axes[1].axhline(0, color="k", lw=0.5)
    axes[1].set_ylabel(r"$\log \Phi_{N,p}(k) - \log \Phi_{N,p}(1)$")
    axes[1].set_xlabel("$k$")
    axes[1].set_ylim(-30, 10)
    axes[1].legend(fontsize="small", loc="lower left")
    axes[0].set_title(f"$N={N}$: $p_d={pd:.5g}$, $p_c={pc:.5g}$")
    return fig
