"""Figures 4-6 of the paper: distributions of X, the mode path with its jump, and f / Phi."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import mpmath
import numpy as np

from symhx.critical import critical_point, mode_path
from symhx.distribution import distribution_of

__all__ = ["plot_distributions", "plot_f_and_phi", "plot_mode_path"]


def _axes(ax: Any, **kw: Any) -> tuple[Any, Any]:
    if ax is None:
        fig, ax = plt.subplots(**kw)
        return fig, ax
    return ax.figure, ax


def plot_distributions(N: int = 101, ps: Sequence[float] = (0.01, 0.02, 0.05, 0.1), *,
                       ax: Any = None) -> Any:
    """Figure 4: ``P(X = k)`` against k for several p (simple circuits, eq. 7)."""
    fig, ax = _axes(ax, figsize=(6, 4))
    for p in ps:
        d = distribution_of(N, p, dps=20)
        ks = np.arange(1, N + 1)
        ax.plot(ks, [float(d.pmf(int(k))) for k in ks], marker=".", ms=3, label=f"$p={p}$")
    ax.set_xlabel("number of distinct impacts $k$")
    ax.set_ylabel("$P(X=k)$")
    ax.set_title(f"Distribution of $X$, $N={N}$ ({N - 1} pipes)")
    ax.legend()
    return fig


def plot_mode_path(N: int = 101, *, p_max: float = 0.1, ax: Any = None) -> Any:
    """Figure 5: the mode ``k*(p)`` as an exact step function, with ``p_d`` and ``p_c`` marked."""
    fig, ax = _axes(ax, figsize=(6, 4))
    path = mode_path(N, p_max=p_max)
    cp = path.critical
    xs, ys = [0.0], [1]
    for bp, _, right in path.breakpoints:
        xs += [float(bp), float(bp)]
        ys += [ys[-1], right]
    xs.append(p_max)
    ys.append(ys[-1])
    ax.plot(xs, ys, drawstyle="default", color="C0", label="$k^*(p)$ (exact breakpoints)")
    ax.axvline(float(cp.p_d), color="C1", ls=":", label=f"$p_d={mpmath.nstr(cp.p_d, 6)}$")
    ax.axvline(float(cp.p), color="C3", ls="--", label=f"$p_c={mpmath.nstr(cp.p, 6)}$")
    ax.set_xlabel("impact probability $p$")
    ax.set_ylabel("mode $k^*$")
    ax.set_title(f"Mode of $X$, $N={N}$: jump $1 \\to {cp.k_after}$")
    ax.legend(loc="lower right")
    return fig


def plot_f_and_phi(N: int = 101, *, ps: Sequence[float] | None = None, axes: Any = None) -> Any:
    """Figure 6 as real plots: ``f_{N,p}(k)`` (eq. 10) and ``log Phi_{N,p}(k)`` for p at 0, p_d,
    between p_d and p_c, and above p_c."""
    cp = critical_point(N, dps=20)
    pd, pc = float(cp.p_d), float(cp.p)
    if ps is None:
        ps = (0.0, pd, (pd + pc) / 2, pc * 1.05)
    if axes is None:
        fig, axes = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    else:
        fig = axes[0].figure
    k = np.linspace(0.5, N, 400)
    kk = np.arange(1, N + 1)
    from math import lgamma, log

    for p in ps:
        axes[0].plot(k, -p * k**2 + (N * p - 1) * k - 1, label=f"$p={p:.4g}$")
        if p > 0:
            lphi = [ki * log(p) + lgamma(N + 1) - log(ki) - lgamma(N - ki + 1) for ki in kk]
            axes[1].plot(kk, np.array(lphi) - lphi[0], label=f"$p={p:.4g}$")
    axes[0].axhline(0, color="k", lw=0.5)
    axes[0].set_ylabel("$f_{N,p}(k)$")
    axes[0].legend(fontsize="small")
    axes[1].axhline(0, color="k", lw=0.5)
    axes[1].set_ylabel(r"$\log \Phi_{N,p}(k) - \log \Phi_{N,p}(1)$")
    axes[1].set_xlabel("$k$")
    axes[1].set_ylim(-30, 10)
    axes[0].set_title(f"$N={N}$: $p_d={pd:.5g}$, $p_c={pc:.5g}$")
    return fig
