"""The ``symhx`` command line.

Sub-commands live in :mod:`symhx.commands`: every module there defines
``register(subparsers)`` and, optionally, ``paper(out: Path, full: bool) -> list[str]``, which
contributes its part of ``symhx paper`` (the
main job: recompute the paper's numbers and figures into a folder). Modules run in the order of
their ``ORDER`` attribute.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
from collections.abc import Sequence
from types import ModuleType

from symhx import __version__


def command_modules() -> list[ModuleType]:
    """All modules of :mod:`symhx.commands`, sorted by their ``ORDER`` attribute."""
    import symhx.commands as pkg

    mods = [
        importlib.import_module(f"symhx.commands.{info.name}")
        for info in pkgutil.iter_modules(pkg.__path__)
        if not info.name.startswith("_")
    ]
    return sorted(mods, key=lambda m: (getattr(m, "ORDER", 100), m.__name__))


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="symhx",
        description="Exact and asymptotic analysis of the graph-theory model of impacts in heat "
        "exchangers. 'symhx paper' recomputes the paper's numbers and figures.",
    )
    parser.add_argument("--version", action="version", version=f"symhx {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for mod in command_modules():
        mod.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        rc = args.func(args)
    except ValueError as exc:  # bad input: one clear line, exit code 2
        print(f"symhx {args.command}: error: {exc}", file=sys.stderr)
        return 2
    return int(rc or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
