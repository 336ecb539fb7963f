"""One style for every figure of symhx: sized for the book's column, legible on screen.

The book's text column is 688 px wide in a 1280 px window (sphinx-book-theme), and figures are
drawn at 100 dpi: a figure :data:`COLUMN_WIDTH` inches wide fills the column at its natural size,
so a 9 pt label is 12.5 px on screen (and never below 9 px unless the figure is shrunk below
0.72 of its width). :func:`styled` applies the font sizes of :data:`RC` while a plot function
draws, without touching the user's global ``matplotlib.rcParams``; ``symhx paper`` saves the
same figures at :data:`PNG_DPI` for sharp stand-alone files.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, TypeVar

import matplotlib as mpl

#: width of the book's text column, in inches at 100 dpi (688 px at a 1280 px window)
COLUMN_WIDTH = 6.8
#: resolution of the figures drawn for the book (the notebook's inline backend)
SCREEN_DPI = 100
#: resolution of the PNG files written by ``symhx paper`` (1360 px across the column width)
PNG_DPI = 200
#: font sizes (points) of every symhx figure: 9 pt or more everywhere
RC: dict[Any, Any] = {
    "figure.dpi": SCREEN_DPI,
    "font.size": 10,
    "axes.titlesize": 10,
    "axes.labelsize": 10,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "legend.fontsize": 9,
    "legend.title_fontsize": 9,
    "figure.titlesize": 11,
    "legend.framealpha": 0.9,
}

F = TypeVar("F", bound=Callable[..., Any])


def styled(fn: F) -> F:
    """Run a plot function under :data:`RC` (fonts and dpi), leaving the caller's rcParams as
    they were."""

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        with mpl.rc_context(RC):
            return fn(*args, **kwargs)

    return wrapper  # type: ignore[return-value]


def space_style(space: str, i: int) -> dict[str, Any]:
    """Line style of the ``i``-th sample space in figure 13: the paper draws simple circuits
    dotted and higher-order ones solid; the printed eq. (41) is dashed with markers and drawn on
    top, so that it never hides the corrected eq. (41) it almost coincides with."""
    if space == "simple":
        return {"color": "C0", "ls": ":", "lw": 1.8, "zorder": 2}
    if space == "eq41":
        return {"color": "C1", "ls": "-", "lw": 2.6, "zorder": 2, "alpha": 0.8}
    if space == "eq41-printed":
        return {"color": "C3", "ls": "--", "lw": 1.2, "marker": "o", "ms": 3, "mfc": "none",
                "zorder": 3}
    # the other spaces cycle through the colours the three above do not use (C7, C8, C9 for
    # the 4th to 6th space of the paper's figure, as before)
    return {"color": _OTHER_COLOURS[(i - 3) % len(_OTHER_COLOURS)], "ls": "-.", "lw": 1.2,
            "zorder": 2}


_OTHER_COLOURS = ("C7", "C8", "C9", "C2", "C4", "C5", "C6")
