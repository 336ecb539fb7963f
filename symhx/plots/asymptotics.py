"""Figure: relative error of each large-N formula for ``N p_c - 1`` (and the ``p_d`` series)
against the exact solver, on log-log axes."""

from __future__ import annotations

from typing import Any

from symhx.plots._style import COLUMN_WIDTH, styled

__all__ = ["plot_asymptotic_errors"]


@styled
def plot_asymptotic_errors(rows: list[dict[str, Any]] | None = None, *, ax: Any = None,
                           dps: int = 120) -> Any:
    """Relative error vs N of every formula of :mod:`symhx.asymptotics`.

    Parameters
    ----------
    rows : list of dict, optional
        Output of :func:`symhx.asymptotics.error_table`; computed (at ``dps``) if omitted.
    ax : matplotlib Axes, optional
    dps : int
        Digits for the table when it is computed here; errors below ``10**-dps`` sit on that floor
        (drawn as a dotted line).

    Returns
    -------
    matplotlib.figure.Figure

    >>> from symhx.asymptotics import error_table
    >>> fig = plot_asymptotic_errors(error_table((10**3, 10**6), dps=30))
    >>> fig.axes[0].get_xscale()
    'log'
    """
    import matplotlib.pyplot as plt
    if rows is None:
        from symhx.asymptotics import error_table

        rows = error_table(dps=dps)
    if ax is None:
        fig, ax = plt.subplots(figsize=(COLUMN_WIDTH, 5.0), layout="constrained")
    else:
        fig = ax.figure
    formulas = list(dict.fromkeys(r["formula"] for r in rows))
    floor_log = None
    for f in formulas:
        pts = [(r["N"], r["rel_error"]) for r in rows if r["formula"] == f]
        xs = [float(n) for n, _ in pts]
        ys = [float(e) if e > 0 else float("nan") for _, e in pts]  # floats reach 1e-308
        style = "--" if f.startswith("pd") else "-"
        ax.plot(xs, ys, style, marker="o", ms=4, label=f)
        if f == "best":
            floor_log = min(ys)
    if floor_log is not None:
        ax.axhline(floor_log, color="0.6", ls=":", lw=1, label="precision floor")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"$N$")
    ax.set_ylabel("relative error")
    ax.set_title(r"Large-$N$ formulas for $N p_c - 1$ and $p_d$ vs the exact solver")
    # below the axes: the curves fill the plot from corner to corner
    ax.legend(ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    ax.grid(True, alpha=0.3)
    return fig
