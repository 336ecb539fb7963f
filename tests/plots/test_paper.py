"""The paper's figures as the book and ``symhx paper`` draw them (symhx.plots.paper): legible at
the book's column width, no overlapping labels, no legend over the data, no empty legend entry,
figure 11 with the paper's panel (b), one choice of sample spaces per figure."""

from __future__ import annotations

import itertools
import re
from pathlib import Path

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.container import ErrorbarContainer  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.text import Text  # noqa: E402

from symhx.plots import paper as P  # noqa: E402

#: the book's text column at a 1280 px window (sphinx-book-theme), px
COLUMN_PX = 688
MIN_FONT_PX = 9.0
BOOK = Path(__file__).resolve().parents[2] / "book"


@pytest.fixture(scope="module")
def ensemble():
    return P.stored_ensemble()


@pytest.fixture(scope="module")
def figures(ensemble):
    figs = {n: P.paper_figure(n, ensemble=ensemble) for n in P.PAPER_FIGURES}
    for fig in figs.values():
        # out of pyplot's hands with an Agg canvas of its own: the per-test plt.close("all")
        # of tests/plots/conftest.py would otherwise leave it a canvas without a renderer
        plt.close(fig)
        FigureCanvasAgg(fig)
        fig.canvas.draw()
    yield figs
    plt.close("all")


def _texts(fig):
    """The texts that are drawn: tick labels of ticks outside the view limits exist but are
    not drawn."""
    hidden = set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                loc = tick.get_loc()
                if loc is None or not lo - 1e-9 * abs(hi - lo) <= loc <= hi + 1e-9 * abs(hi - lo):
                    hidden.update({id(tick.label1), id(tick.label2)})
    return [t for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()
            and t.get_alpha() != 0 and id(t) not in hidden]


def _png_width(fig):
    renderer = fig.canvas.get_renderer()
    return fig.get_tightbbox(renderer).width * fig.dpi  # tight bbox is in inches


@pytest.mark.parametrize("number", sorted(P.PAPER_FIGURES))
def test_fonts_are_at_least_9_px_in_the_column(figures, number):
    fig = figures[number]
    assert fig.dpi == 100
    width = _png_width(fig)
    scale = min(1.0, COLUMN_PX / width)
    assert scale >= 0.8, f"figure {number}: {width:.0f} px is shrunk to {scale:.2f}"
    for t in _texts(fig):
        px = t.get_fontsize() * fig.dpi / 72 * scale
        assert px >= MIN_FONT_PX, (number, t.get_text(), px)


@pytest.mark.parametrize("number", sorted(P.PAPER_FIGURES))
def test_no_two_labels_overlap(figures, number):
    fig = figures[number]
    renderer = fig.canvas.get_renderer()
    boxes = [(t.get_text(), t.get_window_extent(renderer)) for t in _texts(fig)]
    for i, (a, ba) in enumerate(boxes):
        for b, bb in boxes[i + 1:]:
            inter_w = min(ba.x1, bb.x1) - max(ba.x0, bb.x0)
            inter_h = min(ba.y1, bb.y1) - max(ba.y0, bb.y0)
            assert inter_w <= 1 or inter_h <= 1, f"figure {number}: {a!r} overlaps {b!r}"


def _handle_has_data(h):
    if isinstance(h, ErrorbarContainer):
        h = h.lines[0]
    if isinstance(h, Line2D):
        x, y = (np.asarray(v, dtype=float) for v in h.get_data())
        return x.size > 0 and bool(np.isfinite(x).any() and np.isfinite(y).any())
    return True  # patches and collections draw a region


def _display_points(line, step=2.0):
    xy = np.column_stack([np.asarray(v, dtype=float) for v in line.get_data()])
    xy = xy[np.isfinite(xy).all(axis=1)]
    if len(xy) == 0:
        return xy
    pts = line.get_transform().transform(xy)
    if line.get_linestyle() in ("None", "", " ") or len(pts) < 2:
        return pts
    dense = [pts[:1]]
    for a, b in itertools.pairwise(pts):
        n = max(1, int(np.hypot(*(b - a)) / step))
        t = np.linspace(0, 1, n + 1)[1:, None]
        dense.append(a + t * (b - a))
    return np.vstack(dense)


@pytest.mark.parametrize("number", sorted(P.PAPER_FIGURES))
def test_legends_list_visible_data_and_cover_none(figures, number):
    fig = figures[number]
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        handles, labels = ax.get_legend_handles_labels()
        for h, lab in zip(handles, labels, strict=True):
            assert _handle_has_data(h), f"figure {number}: empty legend entry {lab!r}"
        leg = ax.get_legend()
        if leg is None:
            continue
        box = leg.get_window_extent(renderer)
        for line in ax.get_lines():
            pts = _display_points(line)
            inside = ((pts[:, 0] > box.x0) & (pts[:, 0] < box.x1) & (pts[:, 1] > box.y0)
                      & (pts[:, 1] < box.y1)) if len(pts) else np.array([])
            assert not inside.any(), (f"figure {number}: the legend covers "
                                      f"{line.get_label()!r}")


def test_figure_11_has_the_papers_four_panels_with_the_small_k_detail(figures):
    axes = figures[11].axes
    assert [a.get_title()[:3] for a in axes] == ["(a)", "(b)", "(c)", "(d)"]
    from symhx.plots.higher_order import FIG11_PANELS

    (pa, ka), (pb, kb) = FIG11_PANELS[:2]
    assert pa == pb and ka is None and kb is not None
    assert axes[1].get_xlim()[1] < 0.2 * axes[0].get_xlim()[1]


def test_figure_9_is_drawn_on_its_documented_sigma_grid(figures):
    # FIG9_SIGMAS = (lo, hi, n): the p curve has n log-spaced points from lo to hi
    lo, hi, n = P.FIG9_SIGMAS
    xs = figures[9].axes[0].get_lines()[0].get_xdata()
    assert len(xs) == n and np.allclose(xs, np.geomspace(lo, hi, n), rtol=1e-15, atol=0)


def test_figure_6_shows_the_four_stages_with_p_c(figures):
    import symhx

    axes = figures[6].axes
    assert [a.get_title(loc="left")[:3] for a in axes[::2]] == ["(a)", "(b)", "(c)", "(d)"]
    cp = symhx.critical_point(P.PAPER_N, dps=20)
    # (d) is at p_c: the hump of log Phi(k)/Phi(1) reaches 0 at k_after, the mode it jumps to
    k, y = axes[7].get_lines()[0].get_data()
    assert k[np.argmax(y[1:]) + 1] == cp.k_after and abs(max(y[1:])) < 1e-6
    # (c) lies between p_d and p_c: two roots, the hump below Phi(1)
    k, y = axes[5].get_lines()[0].get_data()
    assert -1 < max(y[1:]) < 0


def test_every_figure_is_drawn_by_paper_figure_with_one_choice_of_spaces():
    from symhx.plots.higher_order import FIG13_SPACES

    assert "excess<=4" in P.PAPER_FIGURES[13] and FIG13_SPACES == ("simple", "eq41",
                                                                    "excess<=4")
    # the book never draws figure 13 (or its theory curves) with other spaces
    for page in BOOK.glob("*.md"):
        text = page.read_text()
        for call in re.findall(r"plot_(?:mean_vs_p_spaces|theory_vs_simulation)\([^)]*\)",
                               text):
            assert "spaces=" not in call or "FIG13_SPACES" in call, (page.name, call)
    with pytest.raises(ValueError, match="number: the paper's figures are 1 to 13, got 14"):
        P.paper_figure(14)


def test_save_paper_figure_draws_the_given_ensemble_and_closes_it(tmp_path, ensemble):
    import dataclasses

    from matplotlib.image import imread

    # every other sigma of the stored ensemble: a figure 7 that differs from the default one
    half = dataclasses.replace(ensemble, per_sigma=ensemble.per_sigma[::2])
    assert P.save_paper_figure(7, tmp_path / "half.png", ensemble=half) == tmp_path / "half.png"
    assert plt.get_fignums() == []
    P.paper_figure(7, ensemble=half).savefig(tmp_path / "ref.png", dpi=P.PNG_DPI,
                                             bbox_inches="tight")
    P.save_paper_figure(7, tmp_path / "stored.png")
    got, ref, stored = (imread(tmp_path / f"{n}.png") for n in ("half", "ref", "stored"))
    assert got.shape == ref.shape and (got == ref).all()
    assert got.shape != stored.shape or not (got == stored).all()
