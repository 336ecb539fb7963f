"""Figures 7, 8 (simulation statistics against sigma), 10 and 13 (theory against simulation through
p) and gap time series of a small row."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from symhx.plots._style import COLUMN_WIDTH, space_style, styled

__all__ = ["plot_gaps", "plot_mean_vs_sigma", "plot_mode_vs_sigma", "plot_theory_vs_simulation",
           "theory_means"]


def _ax(ax: Any) -> tuple[Any, Any]:
    if ax is None:
        fig, ax = plt.subplots(figsize=(COLUMN_WIDTH, 4.0), layout="constrained")
        return fig, ax
    return ax.figure, ax


def _short_title(res: Any, what: str) -> str:
    p = res.params
    return f"{what}: n = {p['n']} pipes, {p['runs']} runs per σ, r = {p['restitution']}"


def _yerr(res: Any, what: str, stat: str) -> tuple[np.ndarray, np.ndarray]:
    """Asymmetric error bars from the stored 95 % bootstrap percentile interval."""
    centre = res.column(what, stat)
    ci = res.column(what, f"{stat}_ci")
    return centre, np.vstack([centre - ci[:, 0], ci[:, 1] - centre])


def _few(res: Any, what: str, min_count: int) -> np.ndarray:
    """The values of σ resting on fewer than ``min_count`` runs with an impact."""
    return res.column(what, "count") < min_count


def _mark_few(ax: Any, s: np.ndarray, y: np.ndarray, few: np.ndarray, min_count: int) -> None:
    if np.any(few & np.isfinite(y)):
        ax.plot(s[few], y[few], "o", mfc="none", color="0.5", ms=5,
                label=f"fewer than {min_count} runs with an impact\n(not reliable)")


@styled
def plot_mode_vs_sigma(res: Any, *, what: str = "pipes", min_count: int = 100,
                       ax: Any = None) -> Any:
    """Figure 7: most likely number of impacting pipes (or sites) against σ.

    Error bars: 95 % bootstrap percentile interval of the mode (resampling the runs; they stay
    inside the observed values, never below 0).  Values of σ with fewer than ``min_count`` runs
    with an impact are only marked (open grey circles), not joined.  ``res``: an
    :class:`symhx.impact.EnsembleResult`.  Returns the Figure.
    """
    fig, ax = _ax(ax)
    s = res.sigmas
    mode, err = _yerr(res, what, "mode")
    few = _few(res, what, min_count)
    ax.errorbar(s[~few], mode[~few], yerr=err[:, ~few], fmt="o-", ms=4, capsize=2,
                label=f"mode of impacting {what}\n(95 % bootstrap interval)")
    _mark_few(ax, s, mode, few, min_count)
    ax.set_xlabel("σ (forcing and initial-condition standard deviation)")
    ax.set_ylabel(f"most likely number of\nimpacting {what}")
    ax.set_title(_short_title(res, "Fig. 7"))
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right")
    return fig


@styled
def plot_mean_vs_sigma(res: Any, *, what: str = "pipes", min_count: int = 100,
                       ax: Any = None) -> Any:
    """Figure 8: expected number of impacting pipes (or sites) against σ, runs without impact
    excluded; error bars: 95 % bootstrap percentile interval of the mean.  Values of σ with
    fewer than ``min_count`` runs with an impact are only marked (open grey circles).

    ``res``: an :class:`symhx.impact.EnsembleResult`.  Returns the Figure.
    """
    fig, ax = _ax(ax)
    s = res.sigmas
    mean, err = _yerr(res, what, "mean")
    few = _few(res, what, min_count)
    ax.errorbar(s[~few], mean[~few], yerr=err[:, ~few], fmt="s-", ms=4, capsize=2,
                label=f"mean impacting {what}\n(95 % bootstrap interval)")
    _mark_few(ax, s, mean, few, min_count)
    ax.set_xlabel("σ (forcing and initial-condition standard deviation)")
    ax.set_ylabel(f"expected number of\nimpacting {what}")
    ax.set_title(_short_title(res, "Fig. 8"))
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right")
    return fig


def theory_means(p: Any, N: int, space: str = "simple", dps: int = 20) -> np.ndarray:
    """``E[X]`` of the graph model (``symhx.mean``) at each impact probability ``p`` (float64)."""
    import symhx

    return np.array([float(symhx.mean(N, float(q), space=space, dps=dps)) for q in p])


@styled
def plot_theory_vs_simulation(res: Any, *, spaces: Any = ("simple",), measured: bool = True,
                              title: str = "Fig. 10", p_grid: Any = None, ax: Any = None) -> Any:
    """Figures 10 and 13: ``E[X]`` against the impact probability ``p``, graph theory against the
    simulation.

    Theory: ``symhx.mean(N, p, space)`` for each sample space, ``N = n + 1``.  Simulation: the
    mean number of distinct impact sites of the runs with an impact (95 % bootstrap interval),
    placed at ``p(σ)`` of eq. (27) (crosses, as in the paper) and, with ``measured``, at the
    per-gap impact rate measured in the window (circles; horizontal bars: ±2 standard errors).

    ``res``: an :class:`symhx.impact.EnsembleResult`.  Returns the Figure.
    """
    import symhx

    fig, ax = _ax(ax)
    N = int(res.params["n"]) + 1
    sig = res.sigmas
    p_eq27 = np.asarray(symhx.impact_probability(sig), dtype=float)
    rate, rate_se = res.gap_rates()
    mean, err = _yerr(res, "sites", "mean")
    xs = [q for q in list(p_eq27) + (list(rate) if measured else []) if q > 0]
    lo = max(min(xs) / 2, 1e-6) if xs else 1e-4
    grid = np.logspace(np.log10(lo), np.log10(0.9), 60) if p_grid is None else np.asarray(p_grid)
    for i, space in enumerate(spaces):
        # one space (figure 10): a solid line, as in the paper; several (figure 13): dotted
        # simple circuits, solid higher-order ones
        style = space_style(space, i) if len(spaces) > 1 else {"color": "C0", "lw": 1.8}
        ax.plot(grid, theory_means(grid, N, space), label=f"theory E[X], space {space}",
                **style)
    ok = p_eq27 > 0
    ax.errorbar(p_eq27[ok], mean[ok], yerr=err[:, ok], fmt="kx", ms=6, capsize=2,
                label="simulation at p(σ) of eq. 27")
    if measured:
        okm = rate > 0
        ax.errorbar(rate[okm], mean[okm], xerr=2 * rate_se[okm], yerr=err[:, okm], fmt="o",
                    mfc="none", color="tab:red", ms=5, capsize=2,
                    label="simulation at the measured per-gap rate")
    ax.set_xscale("log")
    ax.set_xlabel("impact probability p")
    ax.set_ylabel("expected number of\ndistinct impacts E[X]")
    ax.set_ylim(bottom=0)
    ax.set_title(f"{title}: theory N = {N}; " + _short_title(res, "simulation")[12:])
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left")
    return fig


@styled
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
    ax.set_title(f"n = {history.row.n}, r = {history.row.restitution}")
    ax.legend(ncol=2)
    return fig
