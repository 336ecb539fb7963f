"""Figures 1 and 2 of the paper: the pipe row and the complete digraph of its impacts.

* :func:`plot_pipe_row` -- a schematic of ``n`` pipes between two walls (figure 1), with the
  equilibrium positions ``x = j d``, the walls at ``x = 0`` and ``x = (n + 1) d`` and every gap
  labelled both by its site index (``0`` = left wall, ``n`` = right wall) and by its impact name
  (``L-1``, ``1-2``, ..., ``n-R``).
* :func:`plot_impact_graph` -- the complete directed graph with self-loops whose ``N = n + 1``
  vertices are those impacts (figure 2 for ``n = 3``): ``N`` vertices, ``N**2`` directed edges
  (``N (N - 1)`` between distinct vertices and ``N`` loops).

Every artist that stands for a vertex has ``gid == "vertex"``, every edge ``gid == "edge"``, so a
test (or a curious reader) can count them.
"""

from __future__ import annotations

import math
from typing import Any

import matplotlib.pyplot as plt
from matplotlib.patches import Circle, FancyArrowPatch, Rectangle
from matplotlib.path import Path

from symhx.graph import vertices_row
from symhx.plots._style import COLUMN_WIDTH, styled
from symhx.validation import InputError

__all__ = ["impact_labels", "plot_impact_graph", "plot_pipe_row"]


def impact_labels(n: int) -> list[str]:
    """Names of the ``N = n + 1`` possible impacts of a row of ``n`` pipes, left to right.

    Site ``i`` is the gap between pipe ``i`` and pipe ``i + 1`` (pipe ``0`` is the left wall and
    pipe ``n + 1`` the right wall).

    >>> impact_labels(3)
    ['L-1', '1-2', '2-3', '3-R']
    >>> impact_labels(1)
    ['L-1', '1-R']
    """
    N = vertices_row(n)
    names = []
    for i in range(N):
        left = "L" if i == 0 else str(i)
        right = "R" if i == n else str(i + 1)
        names.append(f"{left}-{right}")
    return names


def _new_axes(ax, figsize):
    if ax is None:
        fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    else:
        fig = ax.figure
    return fig, ax


@styled
def plot_pipe_row(n: int = 3, *, ax=None):
    """Figure 1: ``n`` pipes (cross-sections) in a row between two fixed walls.

    Pipe ``j`` vibrates about its equilibrium ``x = j d`` along the row; the walls are at ``x = 0``
    and ``x = (n + 1) d``. Each gap is a possible impact: it is labelled by its site index
    ``i = 0 .. n`` (above) and its impact name (below). Returns the Figure.

    Parameters
    ----------
    n : int
        Number of pipes, ``n >= 1``.
    ax : matplotlib Axes, optional
        Axes to draw in; a new figure is made if omitted.
    """
    N = vertices_row(n)
    fig, ax = _new_axes(ax, (min(COLUMN_WIDTH, 1.3 * (n + 2) + 1.0), 2.4))
    radius = 0.3
    wall_w = 0.25
    # walls
    for x0, side in ((0.0, -1), (n + 1.0, 1)):
        ax.add_patch(Rectangle((x0 if side > 0 else x0 - wall_w, -0.9), wall_w, 1.8,
                               facecolor="0.75", edgecolor="0.2", hatch="///", gid="wall"))
    # pipes at equilibrium, with a double arrow showing the direction of vibration
    for j in range(1, n + 1):
        ax.add_patch(Circle((j, 0.0), radius, facecolor="#9ecae1", edgecolor="#08519c", lw=1.5,
                            gid="pipe"))
        ax.text(j, 0.0, str(j), ha="center", va="center", fontsize=10)
        ax.add_patch(FancyArrowPatch((j - 0.28, -0.52), (j + 0.28, -0.52), arrowstyle="<->",
                                     mutation_scale=8, color="0.3"))
    # gaps = possible impacts
    labels = impact_labels(n)
    for i in range(N):
        xl = i + (radius if i > 0 else 0.0)
        xr = i + 1 - (radius if i < n else 0.0)
        xm = 0.5 * (xl + xr)
        ax.add_patch(FancyArrowPatch((xl, 0.0), (xr, 0.0), arrowstyle="|-|", mutation_scale=3,
                                     color="#cb181d", lw=0.8, gid="gap"))
        ax.text(xm, 0.28, f"$i={i}$", ha="center", va="bottom", fontsize=9, color="#cb181d")
        ax.text(xm, -0.78, labels[i], ha="center", va="top", fontsize=9, color="#cb181d")
    ax.set_xlim(-0.6, n + 1.6)
    ax.set_ylim(-1.15, 1.0)
    ax.set_aspect("equal")
    ticks = list(range(n + 2))
    ax.set_xticks(ticks)
    ax.set_xticklabels(["$0$", "$d$"] + [f"${j}d$" for j in range(2, n + 2)])
    ax.set_yticks([])
    for spine in ("left", "right", "top"):
        ax.spines[spine].set_visible(False)
    ax.set_xlabel(r"$x$  (pipe $j$ at rest at $x = j\,d$)")
    ax.set_title(f"$n = {n}$ pipes, $N = n + 1 = {N}$ possible impacts "
                 f"(sites $i = 0, \\ldots, {n}$)")
    return fig


@styled
def plot_impact_graph(n: int = 3, *, ax=None, labels: list[str] | None = None):
    """Figure 2: the complete digraph with self-loops on the ``N = n + 1`` impacts of ``n`` pipes.

    Vertices sit on a circle, labelled ``L-1, 1-2, ..., n-R``; each ordered pair of distinct
    vertices is joined by a directed edge (drawn as two arcs, one each way) and each vertex has a
    loop: ``N**2`` edges in all, the all-ones adjacency matrix. Returns the Figure.

    Parameters
    ----------
    n : int
        Number of pipes; a drawing stays readable up to ``n`` of about 8.
    ax : matplotlib Axes, optional
        Axes to draw in; a new figure is made if omitted.
    labels : list of str, optional
        Vertex labels, default :func:`impact_labels`.
    """
    N = vertices_row(n)
    labels = impact_labels(n) if labels is None else list(labels)
    if len(labels) != N:
        raise InputError(f"need {N} labels, got {len(labels)}")
    fig, ax = _new_axes(ax, (4.8, 4.8))
    r_vertex = 0.17 if N <= 6 else 0.12
    pos = []
    for i in range(N):
        # first vertex at the top-left, then clockwise, so a 4-vertex graph is a square
        angle = math.pi / 2 + math.pi / N - 2 * math.pi * i / N
        pos.append((math.cos(angle), math.sin(angle)))
    for i, (x, y) in enumerate(pos):
        ax.add_patch(Circle((x, y), r_vertex, facecolor="white", edgecolor="#08519c", lw=1.5,
                            zorder=3, gid="vertex"))
        ax.text(x, y, labels[i], ha="center", va="center", fontsize=9 if N <= 6 else 8,
                zorder=4)
    arrow: dict[str, Any] = {"arrowstyle": "-|>", "mutation_scale": 10, "color": "0.25",
                             "lw": 0.9, "shrinkA": 0, "shrinkB": 0}
    for i, (xi, yi) in enumerate(pos):
        for j, (xj, yj) in enumerate(pos):
            if i == j:
                continue
            # arc from the rim of i to the rim of j; the reverse edge bends the other way
            dx, dy = xj - xi, yj - yi
            dist = math.hypot(dx, dy)
            ux, uy = dx / dist, dy / dist
            start = (xi + r_vertex * ux, yi + r_vertex * uy)
            end = (xj - r_vertex * ux, yj - r_vertex * uy)
            ax.add_patch(FancyArrowPatch(start, end, connectionstyle="arc3,rad=0.12", **arrow,
                                         gid="edge"))
    # self-loops: a circular arc outside the vertex, leaving and re-entering its rim
    rl = 0.55 * r_vertex
    for x, y in pos:
        norm = math.hypot(x, y)
        ux, uy = x / norm, y / norm
        cx, cy = x + ux * (r_vertex + 0.6 * rl), y + uy * (r_vertex + 0.6 * rl)
        # angle (seen from the loop's centre) of the two crossings with the vertex rim
        dist = r_vertex + 0.6 * rl
        half = math.acos((dist**2 + rl**2 - r_vertex**2) / (2 * dist * rl))
        back = math.atan2(-uy, -ux)
        angles = [back + half + (2 * math.pi - 2 * half) * t / 40 for t in range(41)]
        pts = [(cx + rl * math.cos(a), cy + rl * math.sin(a)) for a in angles]
        ax.add_patch(FancyArrowPatch(path=Path(pts), **arrow, gid="edge"))
    lim = 1.0 + 2.6 * r_vertex
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(f"$n = {n}$ pipes: $N = {N}$ vertices, $N^2 = {N * N}$ edges")
    return fig
