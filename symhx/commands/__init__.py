"""Sub-commands of the ``symhx`` CLI (one module per topic; see :mod:`symhx.cli`).

This package is the registry of its modules: :func:`command_modules` finds them, for the parser
(:func:`symhx.cli.build_parser`) and for ``symhx paper`` (:func:`symhx.commands.core.cmd_paper`),
so that no command module imports :mod:`symhx.cli` (the dependency points one way: the CLI on top
of its commands).
"""

from __future__ import annotations

import importlib
import pkgutil
from types import ModuleType

__all__ = ["command_modules"]


def command_modules() -> list[ModuleType]:
    """All public modules of :mod:`symhx.commands`, sorted by their ``ORDER`` attribute.

    >>> [m.__name__ for m in command_modules()][0]
    'symhx.commands.core'
    """
    mods = [
        importlib.import_module(f"{__name__}.{info.name}")
        for info in pkgutil.iter_modules(__path__)
        if not info.name.startswith("_")
    ]
    return sorted(mods, key=lambda m: (getattr(m, "ORDER", 100), m.__name__))
