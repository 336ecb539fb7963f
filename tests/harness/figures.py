"""The conformance check of every symhx figure (:mod:`symhx.plots._style`): sized for the book's
column, laid out by matplotlib's constrained engine, and nothing drawn outside the figure (tick
labels, axis labels, titles, legends and figure texts, once drawn)."""

from __future__ import annotations

from typing import Any

from matplotlib.layout_engine import ConstrainedLayoutEngine

from symhx.plots import COLUMN_WIDTH


def _inside(inner: Any, outer: Any) -> bool:
    return (outer.x0 - 1 <= inner.x0 and inner.x1 <= outer.x1 + 1 and outer.y0 - 1 <= inner.y0
            and inner.y1 <= outer.y1 + 1)


def assert_fits_the_column(fig: Any, *, full_width: bool = True, constrained: bool = True
                           ) -> None:
    """``fig`` is ``COLUMN_WIDTH`` inches wide (at most that with ``full_width=False``), uses the
    constrained layout (unless ``constrained=False``: drawings placed by hand), and every axes
    with its decorations, and every figure-level text, lies within the figure (1 px slack)."""
    width, height = fig.get_size_inches()
    if full_width:
        assert abs(width - COLUMN_WIDTH) < 1e-9, f"width {width} in, not {COLUMN_WIDTH}"
    else:
        assert width <= COLUMN_WIDTH + 1e-9, f"width {width} in > {COLUMN_WIDTH}"
    assert 1.0 < height < 12.0, f"height {height} in"
    if constrained:
        assert isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine), "not constrained"
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    for ax in fig.axes:
        if ax.get_visible():
            tight = ax.get_tightbbox(renderer)
            assert _inside(tight, box), f"axes {ax.get_title()!r} sticks out: {tight} in {box}"
    for artist in (*fig.texts, *fig.legends, *([fig._suptitle] if fig._suptitle else [])):
        if artist.get_visible():
            e = artist.get_window_extent(renderer)
            assert _inside(e, box), f"{artist!r} is clipped: {e} in {box}"
