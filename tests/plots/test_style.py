"""The one figure style (:mod:`symhx.plots._style`): fonts of 9 pt or more while a plot function
draws, the caller's rcParams untouched, figures that fit the book's column, and the line style
of each sample space in figure 13."""

from __future__ import annotations

import matplotlib as mpl

from symhx.plots._style import COLUMN_WIDTH, RC, SCREEN_DPI, space_style, styled


def test_styled_applies_the_style_inside_and_restores_the_callers():
    before = {k: mpl.rcParams[k] for k in RC}
    mpl.rcParams["font.size"] = 17.0
    try:
        seen = {}

        @styled
        def draw(x, *, y):
            seen.update({k: mpl.rcParams[k] for k in RC})
            return x + y

        assert draw(1, y=2) == 3 and draw.__name__ == "draw"
        assert seen == RC
        assert mpl.rcParams["font.size"] == 17.0
    finally:
        mpl.rcParams.update(before)


def test_every_font_is_at_least_nine_points_and_a_figure_fits_the_column():
    sizes = [v for k, v in RC.items() if k.endswith("size")]
    assert sizes and min(sizes) >= 9
    assert COLUMN_WIDTH * SCREEN_DPI <= 688  # the book's text column at a 1280 px window


def test_sample_spaces_have_distinct_styles_and_the_printed_eq41_is_on_top():
    """Up to seven further spaces get colours of their own (the eighth space of a figure took
    simple's colour before)."""
    simple, eq41 = space_style("simple", 0), space_style("eq41", 1)
    printed = space_style("eq41-printed", 2)
    assert simple["ls"] == ":" and eq41["ls"] == "-" and printed["ls"] == "--"
    assert printed["zorder"] > eq41["zorder"] and printed["marker"] == "o"
    others = [space_style("excess<=1", i) for i in range(3, 10)]  # seven other spaces
    assert len({o["color"] for o in others}) == len(others)
    assert {o["color"] for o in others}.isdisjoint({simple["color"], eq41["color"],
                                                   printed["color"]})
    # the 4th to 6th space of the paper's figure keep the colours they always had
    assert [o["color"] for o in others[:3]] == ["C7", "C8", "C9"]
