"""Figures 7 and 8 (simulation statistics against sigma) and gap time series of a small row."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np

__all__ = ["plot_gaps", "plot_mean_vs_sigma", "plot_mode_vs_sigma"]


def _ax(ax: Any) -> tuple[Any, Any]:
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4))
        return fig, ax
    return ax.figure, ax


def _title(res: Any, what: str) -> str:
    p = res.params
    return (f"{what}: n = {p['n']} pipes, {p['runs']} runs/σ, r = {p['restitution']}, "
            f"window [{p['t_transient']:g}, {p['t_transient'] + p['t_window']:g}]")


def plot_mode_vs_sigma(res: Any, *, what: str = "pipes", ax: Any = None) -> Any:
    """Figure 7: most likely number of impacting pipes (or sites) against σ, bootstrap error bars.

    ``res``: an :class:`symhx.impact.EnsembleResult`.  Returns the Figure.
    """
    fig, ax = _ax(ax)
    s = res.sigmas
    ax.errorbar(s, res.column(what, "mode"), yerr=res.column(what, "mode_se"), fmt="o-", ms=4,
                capsize=2, label=f"mode ({what})")
    ax.set_xlabel("σ (forcing and initial-condition standard deviation)")
    ax.set_ylabel(f"most likely number of impacting {what}")
    ax.set_title(_title(res, "Fig. 7"), fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def plot_mean_vs_sigma(res: Any, *, what: str = "pipes", ax: Any = None) -> Any:
    """Figure 8: expected number of impacting pipes (or sites) against σ, ±1 standard error.

    ``res``: an :class:`symhx.impact.EnsembleResult`.  Returns the Figure.
    """
    fig, ax = _ax(ax)
    s = res.sigmas
    ax.errorbar(s, res.column(what, "mean"), yerr=res.column(what, "se"), fmt="s-", ms=4,
                capsize=2, label=f"mean ({what})")
    ax.set_xlabel("σ (forcing and initial-condition standard deviation)")
    ax.set_ylabel(f"expected number of impacting {what}")
    ax.set_title(_title(res, "Fig. 8"), fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def plot_gaps(history: Any, *, points: int = 2000, ax: Any = None) -> Any:
    """Gaps ``Delta_i(t)`` of a (small) simulated row, events marked by kind. Returns the Figure."""
    fig, ax = _ax(ax)
    t_end = float(history.t_end)
    ts = np.linspace(0.0, t_end, points)
    gaps = np.array([history.gaps(t).astype(float) for t in ts])
    for i in range(gaps.shape[1]):
        ax.plot(ts, gaps[:, i], lw=0.8, label=f"site {i}")
    marks = {0: ("x", "impact"), 1: ("o", "graze"), 2: ("v", "stick"), 3: ("^", "release")}
    times = history.times.astype(float)
    for k, (m, name) in marks.items():
        sel = history.kinds == k
        if np.any(sel):
            ax.plot(times[sel], np.zeros(sel.sum()), m, color="k", ms=5, label=name)
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("t")
    ax.set_ylabel("gap Δ_i(t)")
    ax.set_title(f"n = {history.row.n}, r = {history.row.restitution}", fontsize=9)
    ax.legend(fontsize=6, ncol=2)
    return fig
