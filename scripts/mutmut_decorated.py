"""mutmut, also mutating functions that carry symhx's decorators (run by ``scripts/mutation.py``).

mutmut 3 skips every decorated function but ``@staticmethod``/``@classmethod``: copying a
decorated function for its trampoline would run the decorator again (a registration twice), and
``@property`` does not fit its trampoline.  That left 15 % of symhx's function lines unmutated:
every figure (``@styled``), every derivation (``@register``), the properties, the cached
functions.  Here a function whose decorators are all in :data:`ALLOWED` is mutated too: its
trampoline keeps the decorators (so the decorator runs once, on the trampoline, as it ran on
the function), and the copies it dispatches to (the original and each mutant) are plain
functions.  Decorator arguments are never mutated (mutmut skips decorator nodes).

Usage: the arguments of ``mutmut`` (``python scripts/mutmut_decorated.py run ...``).
"""

from __future__ import annotations

from typing import Any

import libcst as cst
from libcst.metadata import PositionProvider
from mutmut.mutation import file_mutation as fm

#: decorators that wrap a function without copying or re-registering it: a trampoline under
#: them behaves as the function did
ALLOWED = frozenset({
    "styled",            # symhx.plots._style: rcParams while a figure is drawn
    "register",          # symhx.symbolic: a derivation registered by label (once, the trampoline)
    "exported",          # symhx.forcing.arguments: results exported to the global mpmath type
    "with_params_doc",   # symhx.forcing.probability: a docstring
    "property",
    "cached_property",
    "lru_cache",
    "contextmanager",
    "wraps",
})


def _name(decorator: cst.BaseExpression) -> str:
    """The last name of a decorator expression: ``@functools.lru_cache(maxsize=1)`` -> lru_cache."""
    while isinstance(decorator, cst.Call):
        decorator = decorator.func
    if isinstance(decorator, cst.Attribute):
        return decorator.attr.value
    return getattr(decorator, "value", "")


def allowed(function: Any) -> bool:
    """A function with decorators, all of them in :data:`ALLOWED`."""
    return (isinstance(function, cst.FunctionDef) and bool(function.decorators)
            and all(_name(d.decorator) in ALLOWED for d in function.decorators))


_skip = fm.MutationVisitor._skip_node_and_children
_arrange = fm.function_trampoline_arrangement


def _skip_node_and_children(self: Any, node: cst.CSTNode) -> bool:
    skip = _skip(self, node)
    if not (skip and allowed(node)):
        return skip
    # skipped for its decorators: keep mutmut's other reasons (pragmas, names never mutated)
    position = self.get_metadata(PositionProvider, node, None)
    if position and position.start.line in self._ignored_node_lines:
        self.ignored_functions.add(node.name.value)
        return True
    return node in self._enum_creation_hooks or node.name.value in fm.NEVER_MUTATE_FUNCTION_NAMES


def _function_trampoline_arrangement(function: cst.FunctionDef, mutants: Any,
                                     class_name: str | None) -> Any:
    if not allowed(function):
        return _arrange(function, mutants, class_name)
    decl, nodes, assign, names = _arrange(function.with_changes(decorators=[]), mutants,
                                          class_name)
    # the trampoline (first) carries the decorators, outside mutmut's own; the copies are plain
    nodes[0] = nodes[0].with_changes(decorators=[*function.decorators, *nodes[0].decorators])
    return decl, nodes, assign, names


def patch() -> None:
    fm.MutationVisitor._skip_node_and_children = _skip_node_and_children  # type: ignore
    fm.function_trampoline_arrangement = _function_trampoline_arrangement


if __name__ == "__main__":
    patch()
    from mutmut.__main__ import cli

    cli()
