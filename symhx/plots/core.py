"""Figures 4-6 of the paper: distributions of X, the mode path with its jump, and the mechanism
of the jump (f and Phi at the paper's four stages, :func:`plot_jump_mechanism`).

Conventions of every figure here: the same colour for the same ``p`` in every panel of a
figure, panel letters as in the paper, sized for the book's column (:mod:`symhx.plots._style`).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from math import lgamma, log
from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from symhx._mpctx import mp
from symhx.api import distribution_of
from symhx.critical import compare_with_critical, critical_point, mode_path
from symhx.plots._style import COLUMN_WIDTH, styled
from symhx.validation import InputError

__all__ = ["plot_distributions", "plot_f_and_phi", "plot_jump_mechanism", "plot_mode_path"]

PANEL_LETTERS = "abcdefghijklmnopqrstuvwxyz"


def _panel_axes(n: int, axes: Any, ncols: int, size: tuple[float, float]) -> tuple[Any, list]:
    if axes is None:
        nrows = -(-n // ncols)
        fig, grid = plt.subplots(nrows, ncols, figsize=size, squeeze=False, layout="constrained")
        flat = list(grid.ravel())
        for extra in flat[n:]:
            extra.remove()
        return fig, flat[:n]
    flat = list(np.ravel(axes))
    if len(flat) < n:
        raise InputError(f"axes: need {n} axes, got {len(flat)}")
    return flat[0].figure, flat[:n]


@styled
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
                                  (COLUMN_WIDTH, 2.6 * -(-len(ps) // ncols) + 0.4))
    for i, (p, a) in enumerate(zip(ps, panels, strict=True)):
        d = distribution_of(N, p, dps=20)
        pmf = np.array([float(d.pmf(int(k))) for k in ks])
        mean = f"$E[X] = {float(d.mean()):.3g}$"
        a.plot(ks, pmf, marker=".", ms=3, lw=0.8, color=f"C{i}",
               label=mean if ax is None else f"$p = {p:g}$, {mean}")
        if ax is None:
            a.set_title(f"({PANEL_LETTERS[i]}) $p = {p:g}$")
            a.set_xlabel("distinct impacts $k$")
            a.set_ylabel("$P(X=k)$")
            if logy:
                a.set_yscale("log")
            a.legend(loc="best", handlelength=1.2)
    if ax is not None:
        ax.set_xlabel("number of distinct impacts $k$")
        ax.set_ylabel("$P(X=k)$")
        ax.set_title(f"Distribution of $X$, $N={N}$ ({N - 1} pipes)")
        if logy:
            ax.set_yscale("log")
        ax.legend()
    else:
        fig.suptitle(f"Distribution of $X$ (eq. 7), $N = {N}$ ({N - 1} pipes)")
    return fig


def _mode_steps(path: Any, p_max: float) -> tuple[list[float], list[int]]:
    """The step function ``k*(p)`` on ``[0, p_max]`` as line data, ending on the mode at
    ``p_max`` itself: a breakpoint that rounds to ``p_max`` is passed only if ``p_max`` lies
    above it exactly (at a breakpoint the mode is still the smaller maximiser, ``k_left``)."""
    xs, ys = [0.0], [1]
    for i, (bp, _, right) in enumerate(path.breakpoints):
        x = float(bp)
        if x > p_max or (x == p_max and not _above_breakpoint(path, i, p_max)):
            break
        xs += [float(bp), float(bp)]
        ys += [ys[-1], right]
    xs.append(p_max)
    ys.append(ys[-1])
    return xs, ys


def _above_breakpoint(path: Any, i: int, p: float) -> bool:
    """``p > p_i`` exactly, for breakpoint ``i`` of ``path`` (the jump ``p_c`` by Arb balls)."""
    fr = Fraction(p)
    if i == 0:
        return compare_with_critical(path.critical, fr) > 0
    return bool(fr > path.breakpoints[i][0])


@styled
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
        fig, pair = _panel_axes(2, axes, 2, (COLUMN_WIDTH, 3.1))
        panels = [(pair[0], p_max), (pair[1], zoom or min(1.6 * pc, p_max))]
    nstr = mp().nstr
    for i, (a, right) in enumerate(panels):
        xs, ys = _mode_steps(path, right)
        a.plot(xs, ys, color="C0", label="$k^*(p)$, exact")
        a.axvline(pd, color="C1", ls=":", label=f"$p_d = {nstr(cp.p_d, 5)}$")
        a.axvline(pc, color="C3", ls="--", label=f"$p_c = {nstr(cp.p, 5)}$")
        a.set_xlim(0, right)
        a.set_xlabel("impact probability $p$")
        a.set_ylabel("mode $k^*$")
        what = "" if i == 0 else ", blow-up"
        a.set_title(f"({PANEL_LETTERS[i]}) $N={N}${what}: jump $1 \\to {cp.k_after}$")
        a.legend(loc="lower right" if i == 0 else "upper left")
        a.tick_params(axis="x", labelrotation=30)
    return fig


@styled
def plot_f_and_phi(N: int = 101, *, ps: Sequence[float] | None = None, axes: Any = None) -> Any:
    """Figure 6 as real plots: ``f_{N,p}(k)`` (eq. 10, top) and
    ``log Phi_{N,p}(k) - log Phi_{N,p}(1)`` (bottom) for ``p`` at 0, ``p_d``, between ``p_d``
    and ``p_c``, and above ``p_c``. Each ``p`` has the same colour in both panels and both panels
    have a legend; at ``p = 0``, ``Phi(k) = 0`` for ``k >= 2`` (the curve is at minus infinity
    and only listed in the legend). The book and ``symhx paper`` draw figure 6 with
    :func:`plot_jump_mechanism`, the paper's sequence (a)-(d) zoomed where the roots are.

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
        fig, axes = plt.subplots(2, 1, figsize=(COLUMN_WIDTH, 6.4), sharex=True,
                                 layout="constrained")
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
    axes[0].legend()
    axes[1].axhline(0, color="k", lw=0.5)
    axes[1].set_ylabel(r"$\log \Phi_{N,p}(k) - \log \Phi_{N,p}(1)$")
    axes[1].set_xlabel("$k$")
    axes[1].set_ylim(-30, 10)
    axes[1].legend(loc="lower left")
    axes[0].set_title(f"$N={N}$: $p_d={pd:.5g}$, $p_c={pc:.5g}$")
    return fig


def _f_roots(N: int, p: float) -> list[float]:
    """Real roots of ``f_{N,p}(k) = -p k**2 + (N p - 1) k - 1`` (eq. 10), ascending."""
    b = N * p - 1
    disc = b * b - 4 * p
    if disc < 0:
        return []
    r = disc**0.5
    return sorted(((b - r) / (2 * p), (b + r) / (2 * p)))


@styled
def plot_jump_mechanism(N: int = 101, *, kmax: int | None = None, axes: Any = None) -> Any:
    r"""Figure 6: the mechanism of the jump as the paper's sequence (a)-(d), one row per stage,
    ``f_{N,p}(k)`` (eq. 10) on the left and ``log Phi_{N,p}(k) - log Phi_{N,p}(1)`` (eq. 8) on
    the right, both zoomed on ``0 < k <= kmax`` where the roots are:

    * (a) ``p = p_d/2``: ``f < 0`` for every ``k``, so ``Phi`` decreases and the mode is 1 (as at
      ``p = 0``, where ``Phi(k) = 0`` for ``k >= 2`` and nothing could be drawn);
    * (b) ``p = p_d`` (eq. 16): ``f`` has a double root at ``k_d = sqrt(N+1) - 1``, ``Phi`` an
      inflexion; the mode is still 1;
    * (c) ``p = (p_d + p_c)/2``: two roots ``k_- < k_+``, a local minimum and a local maximum of
      ``Phi``, the maximum still below ``Phi(1)``;
    * (d) ``p = p_c``: the local maximum reaches ``Phi(1)`` and the mode jumps from 1 to
      ``k_after``.

    Roots of ``f`` are marked by dots and dotted vertical lines in both panels of their row (they
    are the turning points of ``Phi``); the modes are marked by stars.

    Parameters
    ----------
    N : int
        Vertices (the paper's 100 pipes: ``N = 101``), ``N >= 4`` (below, ``p_c = p_d`` or there
        is no jump).
    kmax : int, optional
        Right end of the zoom (default ``1.6 k_after``, at most ``N``).
    axes : 4 x 2 array of Axes, optional
        Where to draw (rows (a)-(d); left ``f``, right ``Phi``).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If ``N < 4``.

    >>> fig = plot_jump_mechanism(101)
    >>> [a.get_title(loc="left")[:3] for a in fig.axes[::2]]
    ['(a)', '(b)', '(c)', '(d)']
    """
    if not isinstance(N, int) or isinstance(N, bool) or N < 4:
        raise InputError(f"N must be an integer >= 4 (a jump with p_c > p_d), got {N!r}")
    cp = critical_point(N, dps=30)
    pd, pc = float(cp.p_d), float(cp.p)
    k_top = kmax or min(N, int(np.ceil(1.6 * cp.k_after)) + 1)
    nstr = mp().nstr
    stages = (
        (pd / 2, rf"$p = p_d/2 = {pd / 2:.4g}$", "f < 0: Phi decreasing"),
        (pd, rf"$p = p_d = {nstr(cp.p_d, 4)}$", "double root"),
        ((pd + pc) / 2, r"$p = (p_d + p_c)/2$", "two roots"),
        (pc, rf"$p = p_c = {nstr(cp.p, 4)}$", "jump"),
    )
    if axes is None:
        fig, grid = plt.subplots(4, 2, figsize=(COLUMN_WIDTH, 8.6), sharex=True,
                                 layout="constrained")
    else:
        grid = np.asarray(axes).reshape(4, 2)
        fig = grid[0, 0].figure
    k = np.linspace(0.0, k_top, 600)
    kk = np.arange(1, k_top + 1)
    for row, (p, name, _) in enumerate(stages):
        colour = f"C{row}"
        af, ap = grid[row]
        fk = -p * k**2 + (N * p - 1) * k - 1
        af.plot(k, fk, color=colour, lw=1.6)
        af.axhline(0, color="k", lw=0.6)
        roots = [(N + 1) ** 0.5 - 1] if row == 1 else _f_roots(N, p)  # k_d of eq. 16
        roots = [r for r in roots if 0 < r <= k_top]
        lphi = np.array([ki * log(p) + lgamma(N + 1) - log(ki) - lgamma(N - ki + 1)
                         for ki in kk])
        lphi -= lphi[0]
        ap.plot(kk, lphi, color=colour, lw=1.4, marker=".", ms=3)
        ap.axhline(0, color="k", lw=0.6, ls="--")
        for r in roots:
            af.plot([r], [0.0], "o", color=colour, ms=5)
            for a in (af, ap):
                a.axvline(r, color=colour, lw=0.8, ls=":")
        mode_k = [1] if row < 3 else sorted({1, int(cp.k_after)})
        ap.plot(mode_k, lphi[np.array(mode_k) - 1], "*", color="k", ms=9)
        letter = PANEL_LETTERS[row]
        af.set_title(f"({letter}) {name}", loc="left")
        n_roots = "no root" if not roots else ("double root" if row == 1 else "two roots")
        af.text(0.98, 0.94, n_roots, transform=af.transAxes, ha="right", va="top")
        mode_text = ("mode 1" if row < 3
                     else f"modes 1 and {cp.k_after}: the jump")
        ap.text(0.98, 0.94, mode_text, transform=ap.transAxes, ha="right", va="top")
        af.set_ylim(-2.2, 1.1)
        ap.set_ylim(-1.7, 0.45)
        af.set_ylabel(r"$f_{N,p}(k)$")
        ap.set_ylabel(r"$\log \Phi(k)/\Phi(1)$")
    grid[0, 1].set_title(rf"$N = {N}$: $\star$ = mode", loc="right")
    grid[3, 0].set_xlabel("$k$")
    grid[3, 1].set_xlabel("$k$")
    grid[3, 0].set_xlim(0, k_top)
    return fig
