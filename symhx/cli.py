"""The ``symhx`` command line (also ``python -m symhx``).

Sub-commands live in :mod:`symhx.commands`: every module there defines
``register(subparsers)`` and, optionally, ``paper(out: Path, full: bool) -> list[str]``, which
contributes its part of ``symhx paper`` (the main job: recompute the paper's numbers and figures
into a folder). Modules run in the order of their ``ORDER`` attribute.

Errors: :func:`main` is the one top-level handler. Every error is one line on stderr,
``symhx CMD: error: ...``, never a traceback unless asked for:

* exit code **2** for bad input: argparse errors, :class:`symhx.validation.InputError` (what
  symhx raises for every refused input: a value out of range, a documented work limit), and
  ``OSError`` (e.g. an unwritable ``--out`` or a missing file);
* exit code **1** for an internal error (any other exception, a plain ``ValueError`` or
  ``TypeError`` included): one line saying it is a bug, with a request to report it; the
  traceback too with ``--debug`` or the environment variable :data:`DEBUG_ENV` set (to
  anything but ``""`` or ``0``);
* exit code 130 on Ctrl-C.

Help: every option shows its default (``symhx CMD --help``).
"""

from __future__ import annotations

import argparse
import os
import sys
import traceback
from collections.abc import Sequence
from typing import Any, NoReturn

from symhx import __version__
from symhx.commands import command_modules
from symhx.validation import InputError

#: where internal errors should be reported
REPORT_HINT = "this is a bug in symhx; please report it with the command line you ran"
#: environment variable that, set (to anything but "" or "0"), prints an internal error's traceback
DEBUG_ENV = "SYMHX_DEBUG"
DEBUG_HELP = f"print the traceback of an internal error (or set {DEBUG_ENV}=1)"


def _no_default(action: argparse.Action) -> bool:
    """True for flags and options whose default is None (nothing worth showing); by identity,
    so that a default of 0 is still shown."""
    return any(action.default is x for x in (None, False, argparse.SUPPRESS))


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """argparse's defaults formatter that also shows the default of options without help text,
    and never ``(default: None)`` or ``(default: False)`` (flags and optional values)."""

    def _get_help_string(self, action: argparse.Action) -> str:
        help_text = action.help or ""
        if ("%(default)" in help_text or "default" in help_text.lower()
                or _no_default(action)):
            return help_text  # no default, or the text already states it
        if action.option_strings or action.nargs in (argparse.OPTIONAL, argparse.ZERO_OR_MORE):
            return (help_text + " " if help_text else "") + "(default: %(default)s)"
        return help_text


class Parser(argparse.ArgumentParser):
    """ArgumentParser with :class:`HelpFormatter` and one-line errors (exit code 2)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)

    def add_argument(self, *args: Any, **kwargs: Any) -> argparse.Action:
        """As argparse's; an option without help text still shows its default."""
        action = super().add_argument(*args, **kwargs)
        if not action.help and action.option_strings and not _no_default(action):
            action.help = "(default: %(default)s)"
        return action

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message} (see '{self.prog} --help')\n")


def build_parser() -> argparse.ArgumentParser:
    """The full ``symhx`` parser (sub-parsers inherit :class:`Parser`)."""
    parser = Parser(
        prog="symhx",
        description="Exact and asymptotic analysis of the graph-theory model of impacts in heat "
        "exchangers. 'symhx paper' recomputes the paper's numbers and figures. "
        "Conventions: the positional N is the number of vertices (possible impacts, "
        "N = pipes + 1); numbers such as 0.02, 2e-2 or 1/50 are exact rationals.",
    )
    parser.add_argument("--version", action="version", version=f"symhx {__version__}")
    parser.add_argument("--debug", action="store_true", help=DEBUG_HELP)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for mod in command_modules():
        mod.register(sub)
    for command in sub.choices.values():  # also after the command: symhx CMD ... --debug
        command.add_argument("--debug", action="store_true", dest="debug_after",
                             help=DEBUG_HELP)
    parser.set_defaults(_subparsers=sub.choices)
    return parser


def _one_line(exc: BaseException | str) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    return text if len(text) <= 2000 else text[:1997] + "..."


def _debug_env() -> bool:
    return os.environ.get(DEBUG_ENV, "") not in ("", "0")


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit code (see the module docstring)."""
    old_limit = sys.get_int_max_str_digits() if hasattr(sys, "get_int_max_str_digits") else None
    if old_limit is not None:  # exact huge integers parse and print in full, never raise midway
        sys.set_int_max_str_digits(0)
    try:
        return _run(argv)
    finally:
        if old_limit is not None:
            sys.set_int_max_str_digits(old_limit)


def _run(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    try:
        args, extra = parser.parse_known_args(argv)
        if extra:  # reported by the command's own parser: "symhx paper: error: ..."
            args._subparsers[args.command].error(f"unrecognized arguments: {' '.join(extra)}")
    except SystemExit as exc:  # --help, --version, or a usage error already printed (one line)
        return exc.code if isinstance(exc.code, int) else 2
    prog = f"symhx {args.command}"
    try:
        rc = args.func(args)
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # e.g. `symhx ... | head`: the reader left, nothing to report
        try:
            sys.stdout = open("/dev/null", "w")
        except OSError:  # pragma: no cover
            pass
        return 0
    except InputError as exc:  # bad input, refused by symhx (worded for the command line)
        print(f"{prog}: error: {_one_line(exc.cli or exc)}", file=sys.stderr)
        return 2
    except OSError as exc:  # unwritable --out / --csv, missing file, ...
        msg = (f"{exc.strerror}: {exc.filename}" if exc.filename and exc.strerror
               else _one_line(exc))
        print(f"{prog}: error: {msg}", file=sys.stderr)
        return 2
    except Exception as exc:  # internal error: one line and a request to report it
        if args.debug or getattr(args, "debug_after", False) or _debug_env():
            traceback.print_exc(file=sys.stderr)
        print(f"{prog}: internal error: {type(exc).__name__}: {_one_line(exc)} ({REPORT_HINT})",
              file=sys.stderr)
        return 1
    return int(rc or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
