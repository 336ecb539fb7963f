"""Local Sphinx extension for the symhx book: pages fully offline, figures never silently lost.

Jupyter Book 1.x always loads ``sphinx_thebe``, which puts a CDN address for the thebe bundle
and a Binder repository into every page (used only if a reader presses a launch button, which
this book does not show). This extension disconnects sphinx_thebe's event handlers, so no page
carries those scripts at all. Everything else (MathJax from ``sphinx-mathjax-offline``, the
theme's fonts and icons) is already served from ``_static/``; ``scripts/check_book.py`` verifies
that after the build.

It also warns (an error under ``-W``) when a code cell that declares a figure
(``mystnb: figure:`` metadata) produced no image: that happens when matplotlib does not use the
inline backend (e.g. ``MPLBACKEND=Agg`` in the environment), and myst-nb would otherwise drop the
figure and its caption without a word.
"""

from __future__ import annotations

from docutils import nodes
from sphinx.application import Sphinx
from sphinx.util import logging

logger = logging.getLogger(__name__)


def _drop_thebe(app: Sphinx, config) -> None:
    listeners = app.events.listeners
    for event in list(listeners):
        for listener in list(listeners[event]):
            module = getattr(listener.handler, "__module__", "") or ""
            if module.startswith("sphinx_thebe") and event != "builder-inited":
                app.disconnect(listener.id)


def _check_figure_cells(app: Sphinx, doctree: nodes.document) -> None:
    for cell in doctree.findall(nodes.container):
        if cell.get("nb_element") != "cell_code":
            continue
        meta = cell.get("cell_metadata") or {}
        figure = (meta.get("mystnb") or {}).get("figure")
        if not figure:
            continue
        if not any(True for fig in cell.findall(nodes.figure) for _ in fig.findall(nodes.image)):
            name = figure.get("name", "?") if isinstance(figure, dict) else "?"
            logger.warning(
                "code cell declaring figure %r produced no image (is MPLBACKEND set to a "
                "non-inline backend? did the cell show its figure?)", name,
                location=cell, type="symhx", subtype="figure")


def setup(app: Sphinx) -> dict:
    # config-inited runs after every extension's setup(), so sphinx_thebe's handlers exist
    app.connect("config-inited", _drop_thebe, priority=900)
    app.connect("doctree-read", _check_figure_cells)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
