"""Figure 9 (impact probability p and 1 - p against sigma) and figure 10's theory curve."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from symhx.plots._style import COLUMN_WIDTH, styled

__all__ = ["plot_p_sigma", "plot_theory_mean_vs_p"]


def _ax(ax: Any) -> tuple[Any, Any]:
    if ax is None:
        fig, ax = plt.subplots(figsize=(COLUMN_WIDTH, 4.2), layout="constrained")
        return fig, ax
    return ax.figure, ax


def _params(sigma1: Any, omega: Any, Omega: Any, d: Any) -> str:
    om = "√2" if Omega is None else f"{Omega}"
    s1 = "σ₁ = σ" if sigma1 is None else f"σ₁ = {sigma1}"
    return f"{s1}, ω = {omega}, Ω = {om}, d = {d}"


@styled
def plot_p_sigma(
    sigma: Any = None,
    *,
    sigma1: Any = None,
    omega: float = 1.0,
    Omega: Any = None,
    d: float = 1.0,
    naive: bool = False,
    n_naive: int = 25,
    ymin: float = 1e-40,
    ax: Any = None,
) -> Any:
    """Figure 9: impact probability ``p(σ)`` and ``1 - p(σ)`` (eqs. 22-27) on log-log axes.

    Parameters
    ----------
    sigma : array_like, optional
        Forcing standard deviations (default 400 log-spaced points in ``[0.01, 100]``).
    sigma1, omega, Omega, d
        As in :func:`symhx.forcing.impact_probability` (the paper's values by default).
    naive : bool
        Also plot ``|1 - dblquad(eq. 27)|`` (the paper's literal formula) at ``n_naive``
        points, to show where it loses every digit (negative values are marked).
    n_naive : int
        Number of points for the naive curve (``scipy.integrate.dblquad`` is slow).
    ymin : float
        Lower limit of the probability axis.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure

    >>> fig = plot_p_sigma(np.logspace(-2, 2, 50))
    >>> fig.axes[0].get_xscale(), fig.axes[0].get_yscale()
    ('log', 'log')
    """
    from symhx.forcing import log_impact_probability, log_no_impact_probability

    s = np.logspace(-2, 2, 400) if sigma is None else np.asarray(sigma, dtype=float)
    kw = dict(sigma1=sigma1, omega=omega, Omega=Omega, d=d)
    lp = log_impact_probability(s, **kw) / np.log(10)
    lq = log_no_impact_probability(s, **kw) / np.log(10)
    fig, ax = _ax(ax)
    ax.plot(s, 10.0 ** np.maximum(lp, -300), lw=2, label="p (impact)")
    ax.plot(s, 10.0 ** np.maximum(lq, -300), lw=2, ls="--", label="1 − p (no impact)")
    if naive:
        from symhx.forcing import impact_probability, naive_impact_probability

        sn = np.logspace(np.log10(s.min()), np.log10(s.max()), n_naive)
        vals = np.array([naive_impact_probability(float(v), **kw) for v in sn])
        good = impact_probability(sn, **kw)
        pos = vals > 0
        ax.plot(sn[pos], vals[pos], "x", color="C3", label="1 − dblquad(eq. 27)")
        if (~pos).any():
            ax.plot(sn[~pos], np.abs(vals[~pos]), "v", color="C3", mfc="none",
                    label="|1 − dblquad| (negative)")
        bad = np.abs(vals - good) > 0.5 * good
        if bad.any():
            ax.axvspan(sn[bad].min(), sn[bad].max(), color="C3", alpha=0.08,
                       label="naive formula: no correct digit")
    lo = max(ymin, 10.0 ** np.floor(min(lp.min(), lq.min())))
    ax.set_ylim(lo, 2.0)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("σ (forcing and initial-condition standard deviation)")
    ax.set_ylabel("probability")
    ax.set_title(f"Fig. 9: impact probability, {_params(sigma1, omega, Omega, d)}")
    ax.grid(alpha=0.3, which="both")
    ax.legend(loc="lower right")
    return fig


@styled
def plot_theory_mean_vs_p(
    sigma: Any = None,
    *,
    N: int = 101,
    sigma1: Any = None,
    omega: float = 1.0,
    Omega: Any = None,
    d: float = 1.0,
    space: str = "simple",
    against: str = "p",
    simulation: Any = None,
    dps: int = 20,
    ax: Any = None,
) -> Any:
    """Figure 10's theory curve: expected number of impacts ``E[X]`` through ``σ → p → E[X]``.

    Uses :func:`symhx.forcing.theory_curve` (the graph model's mean at the impact probability of
    eq. 27) for ``N`` possible impacts (``N = n + 1``, the paper's row has ``n = 100``).

    Parameters
    ----------
    sigma : array_like, optional
        Forcing values (default 60 log-spaced points in ``[0.03, 1]``).
    N : int
        Number of possible impacts.
    sigma1, omega, Omega, d
        As in :func:`symhx.forcing.impact_probability`.
    space : str
        Sample space of the graph model.
    against : {"p", "sigma"}
        Horizontal axis: the impact probability (log scale, as the paper) or ``σ``.
    simulation : tuple of arrays, optional
        ``(x, mean)`` points of a simulation to overlay (crosses, as in the paper).
    dps : int
        Digits of the mpmath chain.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure

    >>> fig = plot_theory_mean_vs_p(np.logspace(-1.3, -0.5, 6), N=11)
    >>> fig.axes[0].get_xscale()
    'log'
    """
    from symhx.forcing import theory_curve

    s = np.logspace(np.log10(0.03), 0, 60) if sigma is None else np.asarray(sigma, dtype=float)
    tc = theory_curve(s, N=N, sigma1=sigma1, omega=omega, Omega=Omega, d=d, space=space, dps=dps)
    if against not in ("p", "sigma"):
        raise ValueError(f"against must be 'p' or 'sigma', got {against!r}")
    x = tc.p if against == "p" else tc.sigma
    fig, ax = _ax(ax)
    ax.plot(x, tc.mean, "-", lw=2, label=f"theory (graph model, N = {N})")
    if simulation is not None:
        xs, ms = simulation
        ax.plot(xs, ms, "x", ms=7, label="simulation")
    ax.set_xscale("log")
    ax.set_xlabel("impact probability p" if against == "p" else "σ")
    ax.set_ylabel("expected number of impacts E[X]")
    ax.set_title(f"Fig. 10 (theory): {_params(sigma1, omega, Omega, d)}, space {space}")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    return fig
