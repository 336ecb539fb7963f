"""Local Sphinx extension for the symhx book: cross-references to symhx objects by any of their
import paths, and the list of figures.

**References.** symhx documents every public object once (``symhx.impact_probability`` on the
page of :mod:`symhx`, although it is defined in ``symhx.forcing.probability`` and also exported
by ``symhx.forcing``). A docstring may name it by any of those paths (``:func:`symhx.forcing.
impact_probability```, or ``:func:`impact_probability``` inside its own module). When Sphinx
does not find the target, this extension imports it and links to the documented entry of the
same object; a reference to a private module links to the page of its public package. What
is still unresolved (a misspelt name) stays a warning, an error under ``-W -n``.

**List of figures.** The directive ``{list-of-figures}`` becomes a list of every numbered
figure of the book, with its number, caption and a link, in reading order.
"""

from __future__ import annotations

import importlib
import inspect
from typing import Any

from docutils import nodes
from sphinx import addnodes
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import make_refnode

_OBJ_TYPES = ("function", "class", "exception", "method", "property", "attribute", "data")


def _import(path: str) -> Any:
    """The object at a dotted path (a module, then attributes), or None."""
    parts = path.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj: Any = importlib.import_module(".".join(parts[:i]))
        except Exception:
            continue
        try:
            for name in parts[i:]:
                obj = inspect.getattr_static(obj, name) if inspect.isclass(obj) else getattr(
                    obj, name)
        except AttributeError:
            return None
        return obj
    return None


def _identity(obj: Any) -> Any:
    """What identifies an object across its import paths (functions and classes themselves;
    data only by name, since equal numbers are often the same object)."""
    if isinstance(obj, (staticmethod, classmethod)):
        obj = obj.__func__
    if inspect.isfunction(obj) or inspect.isclass(obj) or isinstance(obj, property):
        return ("obj", id(obj))
    return None


def _documented(env: Any) -> dict[Any, str]:
    cache = getattr(env, "_symhx_documented", None)
    if cache is None or cache[0] != len(env.domains["py"].objects):
        table: dict[Any, str] = {}
        for name, entry in env.domains["py"].objects.items():
            if entry.objtype not in _OBJ_TYPES or not name.startswith("symhx"):
                continue
            key = _identity(_import(name))
            if key is not None:
                table.setdefault(key, name)
        cache = (len(env.domains["py"].objects), table)
        env._symhx_documented = cache
    return cache[1]


def _resolve(app: Sphinx, env: Any, node: Any, contnode: Any) -> Any:
    if node.get("refdomain") != "py":
        return None
    target = node.get("reftarget", "")
    objects = env.domains["py"].objects
    modules = env.domains["py"].modules
    context = [node.get("py:module") or "", node.get("py:class") or ""]
    candidates = [target]
    if context[0]:
        candidates.append(f"{context[0]}.{target}")
        if context[1]:
            candidates.append(f"{context[0]}.{context[1]}.{target}")
    for cand in candidates:
        if not cand.startswith("symhx"):
            continue
        if node.get("reftype") == "mod":
            parts = cand.split(".")
            for i in range(len(parts), 0, -1):  # the nearest documented package
                mod = ".".join(parts[:i])
                if mod in modules:
                    entry = modules[mod]
                    return make_refnode(app.builder, node["refdoc"], entry.docname,
                                        entry.node_id, contnode, mod)
            continue
        obj = _import(cand)
        if obj is None:  # e.g. a dataclass field: link to its documented class
            parent = _import(cand.rpartition(".")[0]) if "." in cand else None
            if not inspect.isclass(parent):
                continue
            obj = parent
        key = _identity(obj)
        documented = _documented(env).get(key) if key is not None else None
        if documented is None and "." in cand:  # an undocumented method: its class
            parent = _import(cand.rpartition(".")[0])
            if inspect.isclass(parent):
                documented = _documented(env).get(_identity(parent))
        if documented is None:  # data: the same name in a documented parent package
            head, _, name = cand.rpartition(".")
            for full, entry in objects.items():
                if (full.endswith("." + name) and head.startswith(full.rpartition(".")[0])
                        and entry.objtype in _OBJ_TYPES):
                    documented = full
                    break
        if documented is not None:
            entry = objects[documented]
            return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id,
                                contnode, documented)
    # a bare name documented exactly once anywhere under symhx (e.g. SigmaStats, named from a
    # docstring that is shown on the page of another module)
    tail = "." + target.split(".", 1)[-1] if "." in target else "." + target
    hits = [full for full, entry in objects.items() if full.startswith("symhx")
            and full.endswith(tail) and entry.objtype in _OBJ_TYPES]
    if len(hits) == 1 and node.get("reftype") != "mod":
        entry = objects[hits[0]]
        return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id,
                            contnode, hits[0])
    return None


def _data_doc(app: Sphinx, what: str, name: str, obj: Any, options: Any,
               lines: list[str]) -> None:
    """The doc of a constant is the ``#:`` comment of the module that assigns it, as written. A
    constant re-exported by a package (``symhx.plots.PAPER_FIGURES``) has no comment where
    autodoc looks, which then shows the docstring of its *type* (``dict``, ``sympy.Symbol``);
    and napoleon would read a comment such as "the paper's row: 100 pipes" as "type:
    description"."""
    if what != "data":
        return
    import sys

    from sphinx.pycode import ModuleAnalyzer

    short = name.rpartition(".")[2]
    for modname, mod in list(sys.modules.items()):
        if not modname.startswith("symhx") or getattr(mod, short, None) is not obj:
            continue
        try:
            docs = ModuleAnalyzer.for_module(modname).find_attr_docs()
        except Exception:
            continue
        if ("", short) in docs:
            lines[:] = [line for line in docs[("", short)] if line is not None]
            return
    type_doc = (type(obj).__doc__ or "").strip().splitlines()
    if lines and type_doc and lines[0].strip() == type_doc[0].strip():
        lines[:] = []


def _examples_section(app: Sphinx, what: str, name: str, obj: Any, options: Any,
                      lines: list[str]) -> None:
    """A doctest right after a numpydoc section (``Returns``, ``Raises``, ...) is the example of
    the docstring: give it its ``Examples`` heading, so that napoleon does not read ``>>>``
    lines as more returned values or exceptions."""
    headings = {i for i in range(1, len(lines)) if lines[i].strip() and set(lines[i].strip())
                == {"-"} and lines[i - 1].strip()}
    if not headings or any(lines[i - 1].strip() == "Examples" for i in headings):
        return
    last = max(headings)
    for j in range(last + 1, len(lines)):
        if lines[j].lstrip().startswith(">>>"):
            indent = lines[j][: len(lines[j]) - len(lines[j].lstrip())]
            lines[j:j] = [f"{indent}Examples", f"{indent}--------"]
            if lines[j - 1].strip():
                lines.insert(j, "")
            return


# --------------------------------------------------------------------------- list of figures
class list_of_figures(nodes.General, nodes.Element):
    pass


class ListOfFigures(SphinxDirective):
    """``{list-of-figures}``: every numbered figure of the book, in reading order."""

    def run(self) -> list[nodes.Node]:
        return [list_of_figures("")]


def _collect_figures(app: Sphinx, doctree: nodes.document) -> None:
    env = app.env
    figs = []
    for fig in doctree.findall(nodes.figure):
        caption = next(iter(fig.findall(nodes.caption)), None)
        if caption is None or not fig["ids"]:
            continue
        # the caption's nodes (its maths stays maths); references become their text, since
        # they are resolved in their own page, not in the list
        copy = caption.deepcopy()
        for xref in list(copy.findall(addnodes.pending_xref)):
            xref.replace_self(xref.children or [nodes.Text(xref.astext())])
        figs.append((fig["ids"][0], copy.children))
    if not hasattr(env, "symhx_figures"):
        env.symhx_figures = {}
    env.symhx_figures[env.docname] = figs


def _purge(app: Sphinx, env: Any, docname: str) -> None:
    getattr(env, "symhx_figures", {}).pop(docname, None)


def _merge(app: Sphinx, env: Any, docnames: Any, other: Any) -> None:
    if not hasattr(env, "symhx_figures"):
        env.symhx_figures = {}
    env.symhx_figures.update(getattr(other, "symhx_figures", {}))


def _fill_lists(app: Sphinx, doctree: nodes.document, docname: str) -> None:
    env = app.env
    order = [docname_ for docname_ in _reading_order(env)]
    for node in list(doctree.findall(list_of_figures)):
        items = nodes.bullet_list()
        for doc in order:
            numbers = env.toc_fignumbers.get(doc, {}).get("figure", {})
            for fig_id, caption in getattr(env, "symhx_figures", {}).get(doc, []):
                number = numbers.get(fig_id)
                if number is None:
                    continue
                label = "Fig. " + ".".join(map(str, number))
                para = nodes.paragraph()
                ref = nodes.reference("", "", internal=True,
                                      refuri=app.builder.get_relative_uri(docname, doc)
                                      + "#" + fig_id)
                ref += nodes.strong(label, label)
                para += ref
                para += nodes.Text(" ")
                para.extend(child.deepcopy() for child in caption)
                items += nodes.list_item("", para)
        node.replace_self(items)


def _reading_order(env: Any) -> list[str]:
    """Documents in the order of the table of contents."""
    seen: list[str] = []

    def walk(doc: str) -> None:
        if doc in seen:
            return
        seen.append(doc)
        for child in env.toctree_includes.get(doc, []):
            walk(child)

    walk(env.config.root_doc)
    return seen


def setup(app: Sphinx) -> dict:
    app.setup_extension("sphinx.ext.autodoc")
    app.connect("missing-reference", _resolve)
    app.connect("autodoc-process-docstring", _examples_section, priority=400)  # before napoleon
    # after napoleon, which would read "the paper's row: 100 pipes" as "type: description"
    app.connect("autodoc-process-docstring", _data_doc, priority=600)
    # "(eq. 16)" and "(eqs. 22-27)" do not end the first sentence of a summary table entry
    from sphinx.ext import autosummary

    extra = ("eq.", "eqs.", "Fig.", "vs.", "cf.")
    autosummary.WELL_KNOWN_ABBREVIATIONS = tuple(  # type: ignore[attr-defined]
        dict.fromkeys((*autosummary.WELL_KNOWN_ABBREVIATIONS, *extra)))
    app.add_node(list_of_figures)
    app.add_directive("list-of-figures", ListOfFigures)
    app.connect("doctree-read", _collect_figures)
    app.connect("env-purge-doc", _purge)
    app.connect("env-merge-info", _merge)
    app.connect("doctree-resolved", _fill_lists)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
