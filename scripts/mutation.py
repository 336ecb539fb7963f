#!/usr/bin/env python
"""Mutation testing of symhx on demand (not in CI): mutate modules, run their tests, write a report.

Usage (from the repository root)::

    python scripts/mutation.py                      # the default module list (pyproject)
    python scripts/mutation.py symhx/circuits.py symhx/graph.py
    python scripts/mutation.py --all                # every module of the package, C included
    python scripts/mutation.py --summary            # which modules have a run, their kill rates
    python scripts/mutation.py symhx/impact/_fast.c --c-mutants 10   # 10 C mutants (a sample)
    python scripts/mutation.py --report-only        # rebuild the report from the last run
    python scripts/mutation.py --merge A.json B.json  # one report from parallel runs
    python scripts/mutation.py symhx/circuits.py --rerun symhx.circuits.x_phi__mutmut_3  # after
                                                    # adding a test for a survivor
    python scripts/mutation.py symhx/critical.py --workdir W --resume  # finish a stopped run
    python scripts/mutation.py symhx/plots/core.py --sample 12        # 12 random mutants

**Which tests cover a module** is read from the layout of ``tests/`` (issue 26), never from a
hand-kept map: the tests of ``symhx/a/b.py`` (or ``symhx/a/_b.py``, or the C source
``symhx/a/_b.c``) are its mirror files ``tests/a/test_b.py`` and ``tests/a/test_b_*.py`` (a
leading underscore dropped; ``__init__`` -> ``test_init``; files that mirror a longer module
name such as ``symhx/a/b_c.py`` are not taken for ``b``).  A mirror file may name further test
files that exercise the module, as a module-level tuple of paths from the repository root::

    MUTATION_ALSO = ("tests/system/test_paper_job.py",)

(read with ``ast``, never imported).  ``--tests FILE...`` overrides the derivation for one run.
A module without mirror files has no tests to run: it is listed as such and not mutated.

**Python modules** are mutated by mutmut 3 in a scratch copy of the repository (``--workdir``,
default a directory under the system temp dir), so the work tree never gets a ``mutants/``
directory. The copy gets a ``[tool.mutmut]`` table restricted to the chosen modules and their
tests; mutmut is run under ``nice -n 19`` with ``--max-children`` workers (default 1) and its
per-mutant CPU timeout (``timeout_multiplier`` x the clean run time of the tests covering the
mutated function). mutmut also stops a mutant after half that limit of wall time, so on a busy
machine some passing mutants end as timeouts: raise ``--timeout-multiplier`` there, and read the
report's ``kill_rate_without_timeouts`` next to ``kill_rate``.

**The C engine** (``symhx/impact/_fast.c``) is mutated by this script's own operators, one change
per mutant, applied to a copy of the source in a scratch repository (``<workdir>-c``): comparisons
(``<`` / ``<=``, ``>`` / ``>=``, ``==`` / ``!=``), ``&&`` / ``||``, a dropped ``!``, binary ``+`` /
``-`` (and ``+=`` / ``-=``), ``/`` -> ``*``, and numeric constants (an integer ``n`` -> ``n + 1``,
a float ``x`` -> ``2 x``, ``0.0`` -> ``1.0``); comments, strings and ``#include`` lines are never
touched. For each mutant the extension is rebuilt from scratch (old build deleted, ``build_ext
--inplace --force``); a build is used only if the new ``.so`` is newer than the mutated source and
the test interpreter imports exactly that file (path and SHA-256 checked), so a stale build cannot
be tested. A mutant that does not compile is ``not_checked``; one whose build is byte-identical to
the unmutated build is ``equivalent`` (the compiler folded the change). The mirror tests of the C
source (``tests/impact/test_fast*.py``) run against each mutant (``pytest -x``, time limit
``--timeout-multiplier`` x the clean run). ``--c-mutants K`` runs K mutants spread evenly over the
file (default: all; a full campaign takes hours); with ``--resume`` mutants that already have a
verdict in the report are skipped.

The report (``tests/mutation-report.json``) lists, per module, the counts ``killed`` (tests failed,
including timeouts), ``survived``, ``equivalent`` and ``no_tests`` (no test executes the mutated
function), the ``kill_rate = killed / (killed + survived + no_tests)`` over non-equivalent mutants,
the test files used and the diff of every surviving mutant, plus ``modules_without_run``: every
module of the package that has no entry yet. Equivalent mutants are declared by hand in the
``equivalent`` section of the report: ``{mutant name: {"diff": ..., "why": one line}}``. A
declaration only counts while its diff still matches the mutant (mutant names are renumbered
when the code changes); stale declarations are listed under ``stale_equivalent`` and the mutant
counts as survived. Reports written by earlier versions of this script are read as they are
(missing fields count as absent).

``--resume`` continues a stopped run in its ``--workdir`` with the current sources and tests:
mutmut keeps the verdict of every mutant whose function is unchanged (it compares a hash of each
function's source) and runs the rest; with ``--rerun NAMES`` it brings the work folder to the
current sources and tests first and then runs only those mutants (a survivor's function may have
changed since its verdict).

``--sample K`` runs, for each Python module, ``K`` mutants drawn at random (``--seed``) from those
without a verdict (all of them in a fresh run; with ``--resume``, the ones a stopped run did not
reach): an unbiased estimate of the module's kill rate where a full campaign would take hours
(mutmut itself runs mutants in order of their tests' cost, so the first ones of a stopped run
are not a random sample).  The report marks such an entry with ``"sample"`` and
``--summary`` prints a 95% Wilson interval for it.
"""

from __future__ import annotations

import argparse
import ast
import difflib
import hashlib
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import tomllib

ROOT = Path(__file__).resolve().parent.parent
REPORT = ROOT / "tests" / "mutation-report.json"

KILLED = {1, 3, 36, 24, -24, 152, 255, -11, -9}  # test failure, pytest error, timeouts, crashes
TIMEOUT = {36, 24, -24, 152, 255}  # counted as killed, and also on their own: mutmut's wall-clock
# limit (half its CPU limit) also fires on a loaded machine, so a timeout is a weaker verdict
SURVIVED = {0}
NO_TESTS = {5, 33}


def _config() -> dict:
    data = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))
    return data.get("tool", {}).get("symhx-mutation", {})


def mirror_stem(filename: str) -> str:
    """The ``x`` of a source file's mirror ``test_x.py``: ``b.py``, ``_b.py`` and ``_b.c`` give
    ``b``; ``__init__.py`` gives ``init``, ``__main__.py`` gives ``main``."""
    stem = filename.split(".", 1)[0]
    return {"__init__": "init", "__main__": "main"}.get(stem, stem.lstrip("_"))


def all_modules(root: Path = ROOT) -> list[str]:
    """Every module of the package that can be mutated: its Python files and its C sources."""
    pkg = root / "symhx"
    files = [*pkg.rglob("*.py"), *pkg.rglob("*.c")]
    return sorted(str(p.relative_to(root)) for p in files
                  if "_build" not in p.parts and "__pycache__" not in p.parts)


def mirror_tests(module: str, root: Path = ROOT) -> list[str]:
    """The test files of ``module`` (a path such as ``symhx/forcing/rayleigh.py``): its mirror
    files ``tests/<folder>/test_<stem>.py`` and ``test_<stem>_*.py``, without the mirrors of a
    longer module name in the same folder, plus the files they name in ``MUTATION_ALSO``."""
    src = Path(module)
    folder = root / "tests" / Path(*src.parts[1:-1])
    stem = mirror_stem(src.name)
    siblings = {mirror_stem(p.name) for p in (root / src.parent).iterdir()
                if p.suffix in (".py", ".c")}
    longer = sorted(s for s in siblings if s.startswith(stem + "_"))

    def others(name: str) -> bool:
        return any(name == f"test_{s}.py" or name.startswith(f"test_{s}_") for s in longer)

    found = [p for p in [folder / f"test_{stem}.py", *sorted(folder.glob(f"test_{stem}_*.py"))]
             if p.is_file() and not others(p.name)]
    extra: list[str] = []
    for p in found:
        extra += _mutation_also(p)
    out = [str(p.relative_to(root)) for p in found]
    return out + sorted({e for e in extra if e not in out and (root / e).is_file()})


def _mutation_also(path: Path) -> list[str]:
    """The paths in a test file's module-level ``MUTATION_ALSO = (...)`` (literal strings)."""
    for node in ast.parse(path.read_text("utf-8")).body:
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and
                                                t.id == "MUTATION_ALSO" for t in node.targets):
            value = ast.literal_eval(node.value)
            return [value] if isinstance(value, str) else [str(v) for v in value]
    return []


def _copy_repo(workdir: Path, *, keep_mutants: bool = False) -> None:
    """Copy the tracked files plus the in-place C extension (and nothing else) to ``workdir``.

    With ``keep_mutants`` the files are copied over an earlier run's work directory and its
    ``mutants/`` (mutmut's results) is kept."""
    if workdir.exists() and not keep_mutants:
        shutil.rmtree(workdir)
    files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=ROOT,
                           check=True, capture_output=True, text=True).stdout.split()
    files += [str(p.relative_to(ROOT)) for p in (ROOT / "symhx").rglob("*.so")]
    for f in files:
        src = ROOT / f
        if not src.is_file() or f.startswith(("book/", "mutants/")):
            continue
        dst = workdir / f
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, dst)


def _write_mutmut_config(workdir: Path, modules: list[str], tests: list[str],
                         timeout_multiplier: float) -> None:
    py = workdir / "pyproject.toml"
    text = py.read_text("utf-8")
    # drop every [tool.mutmut] table (the repository's own; an earlier run's): one restricted
    # table is appended
    while (start := text.find("\n[tool.mutmut]")) >= 0:
        end = text.find("\n[", start + 1)
        text = text[:start + 1] + (text[end + 1:] if end >= 0 else "")
    table = [
        "[tool.mutmut]",
        'source_paths = ["symhx"]',
        f"only_mutate = {json.dumps(modules)}",
        f"pytest_add_cli_args_test_selection = {json.dumps(tests)}",
        "pytest_add_cli_args = []",
        f"timeout_multiplier = {timeout_multiplier}",
        "timeout_constant = 2.0",
        "use_git_change_detection = false",
        "",
    ]
    py.write_text(text.rstrip() + "\n\n" + "\n".join(table), "utf-8")


def _function_sources(path: Path) -> dict[str, list[str]]:
    """Source lines (without the ``def`` line) of every function in a mutated file."""
    text = path.read_text("utf-8")
    lines = [ln.encode("utf-8") for ln in text.split("\n")]   # ast offsets count utf-8 bytes
    out: dict[str, list[str]] = {}
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            # the node's source segment by line slices (ast.get_source_segment rescans the whole
            # text for every function: quadratic, minutes on a large mutated module)
            first, last = node.lineno - 1, (node.end_lineno or node.lineno) - 1
            end = node.end_col_offset
            if first == last:
                seg_b = [lines[first][node.col_offset:end]]
            else:
                seg_b = [lines[first][node.col_offset:], *lines[first + 1:last], lines[last][:end]]
            body = [b.decode("utf-8") for b in seg_b]
            start = next((i for i, ln in enumerate(body) if ln.rstrip().endswith(":")), 0)
            out[node.name] = [ln.strip() for ln in body[start + 1:]] + [
                " ".join(body[: start + 1]).split("(", 1)[-1].strip()]
    return out


def _mutant_diff(sources: dict[str, list[str]], name: str) -> str:
    """``-`` / ``+`` lines between a mutant and the original function (from mutmut's file)."""
    func = name.rsplit(".", 1)[-1]
    orig = sources.get(func.rsplit("__mutmut_", 1)[0] + "__mutmut_orig")
    mutant = sources.get(func)
    if orig is None or mutant is None:
        return "(source not found)"
    lines = [ln for ln in difflib.ndiff(orig, mutant) if ln.startswith(("- ", "+ "))]
    return "\n".join(ln[0] + " " + ln[2:] for ln in lines)


def _module_of(meta: Path, workdir: Path) -> str:
    rel = meta.relative_to(workdir / "mutants")
    return str(rel)[: -len(".meta")]


def build_report(workdir: Path, modules: list[str], old: dict,
                 tests: dict[str, list[str]] | None = None,
                 sample: dict[str, dict] | None = None) -> dict:
    """Read mutmut's ``.meta`` files in ``workdir`` and merge with the equivalent declarations
    (and the modules of ``old`` that this run did not touch)."""
    equivalent_decl: dict = old.get("equivalent", {})
    per_module: dict = dict(old.get("modules", {}))
    stale: dict = {}
    for meta in sorted((workdir / "mutants").rglob("*.py.meta")):
        module = _module_of(meta, workdir)
        if module not in modules:
            continue
        codes = json.loads(meta.read_text())["exit_code_by_key"]
        sources = _function_sources(meta.with_suffix(""))
        killed = survived = equivalent = no_tests = other = timeouts = 0
        survivors: dict[str, str] = {}
        unresolved: dict[str, str] = {}
        for name, code in sorted(codes.items()):
            if code in KILLED:
                killed += 1
                timeouts += code in TIMEOUT
                continue
            diff = _mutant_diff(sources, name)
            decl = equivalent_decl.get(name)
            if code in SURVIVED | NO_TESTS and decl is not None:
                if decl.get("diff") == diff:
                    equivalent += 1
                    continue
                stale[name] = decl
            if code in SURVIVED:
                survived += 1
                survivors[name] = diff
            elif code in NO_TESTS:
                no_tests += 1
                survivors[name] = diff
            else:
                other += 1
                unresolved[name] = f"exit code {code}: {diff}"
        live = killed + survived + no_tests
        per_module[module] = {
            "total": len(codes),
            "killed": killed,
            "timeouts": timeouts,
            "survived": survived,
            "no_tests": no_tests,
            "equivalent": equivalent,
            "not_checked": other,
            "kill_rate": round(killed / live, 4) if live else None,
            "kill_rate_without_timeouts": round((killed - timeouts) / live, 4) if live else None,
            "survivors": survivors,
            **({"unresolved": unresolved} if unresolved else {}),
            **({"tests": tests[module]} if tests and module in tests else {}),
            **({"sample": sample[module]} if sample and module in sample else {}),
        }
    return _assemble(per_module, equivalent_decl, stale)


def _assemble(per_module: dict, equivalent_decl: dict, stale: dict) -> dict:
    """The report: per-module results, their totals and the equivalent declarations.

    ``kill_rate`` is over the mutants that ran; ``kill_rate_all_mutants`` counts the ones a
    stopped run never reached (``not_checked``) as not killed."""
    for m in per_module.values():
        rest = m.get("total", 0) - m.get("equivalent", 0)
        m["kill_rate_all_mutants"] = round(m.get("killed", 0) / rest, 4) if rest else None
    tot = {k: sum(m.get(k, 0) for m in per_module.values())
           for k in ("total", "killed", "timeouts", "survived", "no_tests", "equivalent",
                     "not_checked")}
    live = tot["killed"] + tot["survived"] + tot["no_tests"]
    tot["kill_rate"] = round(tot["killed"] / live, 4) if live else None
    tot["kill_rate_without_timeouts"] = (round((tot["killed"] - tot["timeouts"]) / live, 4)
                                         if live else None)
    rest = tot["total"] - tot["equivalent"]
    tot["kill_rate_all_mutants"] = round(tot["killed"] / rest, 4) if rest else None
    # each module's rate (of a full run, a stopped one or a random sample) weighted by its
    # number of mutants: an estimate for the package, where a plain total would let the
    # modules with full runs outweigh the sampled ones
    rated = [(m["total"], m["kill_rate"]) for m in per_module.values()
             if m.get("kill_rate") is not None and m.get("total")]
    weight = sum(t for t, _ in rated)
    tot["kill_rate_weighted_by_module_size"] = (round(sum(t * r for t, r in rated) / weight, 4)
                                                if weight else None)
    tools = ["mutmut " + _mutmut_version()]
    if any(m.endswith(".c") for m in per_module):
        tools.append(C_TOOL)
    return {
        "tool": " + ".join(tools),
        "command": "python scripts/mutation.py " + " ".join(sorted(per_module)),
        "modules_without_run": [m for m in all_modules() if m not in per_module],
        "kill_rate_definition": "killed / (killed + survived + no_tests); equivalent excluded; "
                                "killed includes timeouts (also counted on their own)",
        "totals": tot,
        "modules": dict(sorted(per_module.items())),
        "equivalent": dict(sorted(equivalent_decl.items())),
        **({"stale_equivalent": dict(sorted(stale.items()))} if stale else {}),
    }


def merge_reports(reports: list[dict]) -> dict:
    """One report from several (for instance runs on different modules in parallel): a module's
    entry and the declarations for its mutants come from the last report that ran it."""
    per_module: dict = {}
    owner: dict = {}
    for i, rep in enumerate(reports):
        for module, entry in rep.get("modules", {}).items():
            per_module[module] = entry
            owner[module] = i

    def keep(name: str, i: int) -> bool:   # a declaration belongs to the module of its mutant
        if ".c:" in name:  # a C mutant: "symhx/impact/_fast.c:LINE:COL:old->new"
            module = name.split(":", 1)[0]
        else:
            module = re.split(r"\.x[_\u01c1]", name, maxsplit=1)[0].replace(".", "/") + ".py"
        return owner.get(module, i) == i

    equivalent: dict = {}
    stale: dict = {}
    for i, rep in enumerate(reports):
        equivalent.update({k: v for k, v in rep.get("equivalent", {}).items() if keep(k, i)})
        stale.update({k: v for k, v in rep.get("stale_equivalent", {}).items() if keep(k, i)})
    return _assemble(per_module, equivalent, stale)


# --------------------------------------------------------------------------- the C engine
C_TOOL = "scripts/mutation.py C operators"
C_KEYWORDS = {"return", "case", "else", "do", "sizeof", "goto"}
_C_TOKEN = re.compile(r"""
    (?P<comment>/\*.*?\*/|//[^\n]*)
  | (?P<string>"(?:\\.|[^"\\\n])*"|'(?:\\.|[^'\\\n])*')
  | (?P<pre>^[ \t]*\#[^\n]*(?:\\\n[^\n]*)*)
  | (?P<ident>[A-Za-z_]\w*)
  | (?P<number>(?:0[xX][0-9a-fA-F]+|(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?)[uUlLfF]*)
  | (?P<op><<=|>>=|->|\+\+|--|<<|>>|<=|>=|==|!=|&&|\|\||\+=|-=|\*=|/=|[-+*/%<>!=&|^~?:;,.(){}\[\]])
  | (?P<space>\s+)
""", re.S | re.M | re.X)
_DEFINE_NUMBER = re.compile(r"#\s*define\s+\w+\s+\(?\s*(-?)(\d[\w.+-]*)")
_SWAP = {"<": "<=", "<=": "<", ">": ">=", ">=": ">", "==": "!=", "!=": "==", "&&": "||",
         "||": "&&", "+=": "-=", "-=": "+=", "/": "*", "!": ""}


@dataclass(frozen=True)
class CMutant:
    """One change of a C source: ``old`` at ``offset`` (line, column from 1) becomes ``new``."""

    module: str
    line: int
    col: int
    offset: int
    old: str
    new: str

    @property
    def name(self) -> str:
        return f"{self.module}:{self.line}:{self.col}:{self.old}->{self.new}"

    def apply(self, text: str) -> str:
        assert text[self.offset:self.offset + len(self.old)] == self.old, self
        return text[:self.offset] + self.new + text[self.offset + len(self.old):]

    def diff(self, text: str) -> str:
        start = text.rfind("\n", 0, self.offset) + 1
        end = text.find("\n", self.offset)
        end = len(text) if end < 0 else end
        line = text[start:end]
        col = self.offset - start
        return f"- {line.strip()}\n+ {(line[:col] + self.new + line[col + len(self.old):]).strip()}"


def _mutated_number(tok: str) -> str | None:
    """An integer ``n`` -> ``n + 1``, a float ``x`` -> ``2 x`` and ``0.0`` -> ``1.0`` (suffixes
    kept; hex untouched)."""
    m = re.fullmatch(r"([0-9.]+(?:[eE][+-]?\d+)?)([uUlLfF]*)", tok)
    if m is None:
        return None
    core, suffix = m.groups()
    if re.fullmatch(r"\d+", core):
        return str(int(core) + 1) + suffix
    return repr(2 * float(core) if float(core) else 1.0) + suffix


def c_mutants(text: str, module: str) -> list[CMutant]:
    """Every single-token mutant of a C source, in source order (see the module docstring)."""
    out: list[CMutant] = []
    line_starts = [0] + [i + 1 for i, ch in enumerate(text) if ch == "\n"]

    def add(offset: int, old: str, new: str) -> None:
        import bisect

        line = bisect.bisect_right(line_starts, offset)
        out.append(CMutant(module, line, offset - line_starts[line - 1] + 1, offset, old, new))

    prev_kind, prev = "", ""
    pos = 0
    while pos < len(text):
        m = _C_TOKEN.match(text, pos)
        if m is None:
            pos += 1
            continue
        kind, tok, start = m.lastgroup or "", m.group(), m.start()
        pos = m.end()
        if kind in ("space", "comment"):
            continue
        if kind == "pre":
            d = _DEFINE_NUMBER.match(tok.strip())
            if d and (new := _mutated_number(d.group(2))) is not None:
                add(start + tok.index(d.group(2), tok.index("define")), d.group(2), new)
            prev_kind, prev = "", ""
            continue
        if kind == "number" and (new := _mutated_number(tok)) is not None:
            add(start, tok, new)
        elif kind == "op":
            binary = prev_kind == "number" or (prev_kind == "ident" and prev not in C_KEYWORDS) \
                or prev in (")", "]")
            if tok in ("+", "-") and binary:
                add(start, tok, "-" if tok == "+" else "+")
            elif tok in _SWAP and (tok != "/" or binary):
                add(start, tok, _SWAP[tok])
        prev_kind, prev = kind, tok
    return out


def spread(items: list, k: int | None) -> list:
    """``k`` items evenly spaced over the list (all of them for ``k`` None or too large)."""
    if k is None or k >= len(items):
        return list(items)
    return [items[(2 * i + 1) * len(items) // (2 * k)] for i in range(k)]


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


class CWorkspace:
    """A scratch copy of the repository in which one C source is mutated and rebuilt."""

    def __init__(self, workdir: Path, module: str, nice: bool) -> None:
        self.root, self.module, self.nice = workdir, module, nice
        self.src = workdir / module
        self.original = self.src.read_text("utf-8")
        self.env = {**os.environ, "PYTHONPATH": str(workdir)}  # this copy before any install
        self.import_name = module[: -len(".c")].replace("/", ".")

    def _cmd(self, cmd: list[str]) -> list[str]:
        return ["nice", "-n", "19", *cmd] if self.nice else cmd

    def build(self, text: str) -> Path | None:
        """Write ``text`` as the source and build the extension from scratch; the new ``.so``, or
        None if it does not compile.  Raises if the build could be stale."""
        for old in self.src.parent.glob(self.src.stem + "*.so"):
            old.unlink()
        shutil.rmtree(self.root / "build", ignore_errors=True)
        self.src.write_text(text, "utf-8")
        written = self.src.stat().st_mtime_ns
        subprocess.run(self._cmd([sys.executable, "setup.py", "-q", "build_ext", "--inplace",
                                  "--force"]), cwd=self.root, env=self.env,
                       capture_output=True, text=True, check=False)
        built = list(self.src.parent.glob(self.src.stem + "*.so"))
        if len(built) != 1:  # the extension is optional: a compile error leaves no .so
            return None
        so = built[0]
        # setuptools copies the built file in place with its time cut to whole seconds, so a
        # build within the second of the write looks older: compare whole seconds
        if so.stat().st_mtime_ns < written - written % 10**9:
            raise RuntimeError(f"stale build of {self.module}: {so} is older than the source")
        return so

    def check_loaded(self, so: Path) -> None:
        """The test interpreter imports exactly this build (path and content)."""
        code = f"import {self.import_name} as m; print(m.__file__)"
        out = subprocess.run([sys.executable, "-c", code], cwd=self.root, env=self.env,
                             capture_output=True, text=True, check=False).stdout.strip()
        if not out or Path(out).resolve() != so.resolve() or _sha256(Path(out)) != _sha256(so):
            raise RuntimeError(f"the tests would import {out or 'nothing'}, not {so}")

    def run_tests(self, tests: list[str], limit: float | None) -> tuple[str, float]:
        """``killed`` / ``timeout`` / ``survived`` / ``no_tests`` and the wall time."""
        cmd = self._cmd([sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider",
                         *tests])
        t0 = time.perf_counter()
        try:
            rc = subprocess.run(cmd, cwd=self.root, env=self.env, capture_output=True,
                                timeout=limit, check=False).returncode
        except subprocess.TimeoutExpired:
            return "timeout", time.perf_counter() - t0
        dt = time.perf_counter() - t0
        return {0: "survived", 5: "no_tests"}.get(rc, "killed"), dt


def run_c_module(module: str, tests: list[str], workdir: Path, k: int | None,
                 timeout_multiplier: float, nice: bool, old: dict, equivalent_decl: dict,
                 resume: bool) -> dict:
    """Mutate one C source (``k`` mutants spread over the file), rebuild and test each; the
    report entry of the module."""
    _copy_repo(workdir)
    ws = CWorkspace(workdir, module, nice)
    mutants = c_mutants(ws.original, module)
    verdicts: dict[str, str] = dict(old.get("verdicts", {})) if resume else {}
    verdicts = {m.name: verdicts[m.name] for m in mutants if m.name in verdicts}
    todo = [m for m in spread(mutants, k) if m.name not in verdicts]
    clean = ws.build(ws.original)
    if clean is None:
        raise RuntimeError(f"{module} does not build unmutated")
    ws.check_loaded(clean)
    clean_hash = _sha256(clean)
    verdict, t_clean = ws.run_tests(tests, None)
    if verdict != "survived":
        raise RuntimeError(f"the tests of {module} fail on the unmutated build ({verdict})")
    limit = max(10.0, timeout_multiplier * t_clean)
    print(f"{module}: {len(mutants)} mutants, running {len(todo)}; clean tests {t_clean:.1f} s, "
          f"limit {limit:.0f} s", flush=True)
    try:
        for i, mut in enumerate(todo, 1):
            so = ws.build(mut.apply(ws.original))
            if so is None:
                verdicts[mut.name] = "not_compiled"
            elif _sha256(so) == clean_hash:
                verdicts[mut.name] = "same_binary"
            else:
                ws.check_loaded(so)
                verdicts[mut.name], _ = ws.run_tests(tests, limit)
            print(f"  [{i}/{len(todo)}] {mut.name}: {verdicts[mut.name]}", flush=True)
    finally:
        ws.build(ws.original)  # leave the scratch copy unmutated
    by_name = {m.name: m for m in mutants}
    counts = dict.fromkeys(("killed", "timeouts", "survived", "no_tests", "equivalent"), 0)
    survivors: dict[str, str] = {}
    for name, v in verdicts.items():
        diff = by_name[name].diff(ws.original)
        decl = equivalent_decl.get(name)
        if v in ("killed", "timeout"):
            counts["killed"] += 1
            counts["timeouts"] += v == "timeout"
        elif v == "same_binary" or (decl is not None and decl.get("diff") == diff):
            counts["equivalent"] += 1
        elif v in ("survived", "no_tests"):
            counts[v] += 1
            survivors[name] = diff
    live = counts["killed"] + counts["survived"] + counts["no_tests"]
    return {
        "total": len(mutants),
        **counts,
        "not_checked": len(mutants) - live - counts["equivalent"],
        "kill_rate": round(counts["killed"] / live, 4) if live else None,
        "kill_rate_without_timeouts": (round((counts["killed"] - counts["timeouts"]) / live, 4)
                                       if live else None),
        "survivors": survivors,
        "tests": tests,
        "tool": C_TOOL,
        "verdicts": dict(sorted(verdicts.items())),
    }


def wilson(k: int, n: int, z: float = 1.96) -> tuple[float, float]:
    """The Wilson score interval of a proportion ``k/n`` (95% for ``z = 1.96``)."""
    if n == 0:
        return 0.0, 1.0
    ph = k / n
    den = 1 + z * z / n
    mid = (ph + z * z / (2 * n)) / den
    half = z * math.sqrt(ph * (1 - ph) / n + z * z / (4 * n * n)) / den
    return max(0.0, mid - half), min(1.0, mid + half)


def summary_lines(report: dict) -> list[str]:
    """One line per module of the package: its kill rate, or that it has no run yet."""
    lines = []
    modules = report.get("modules", {})
    for m in sorted(set(all_modules()) | set(modules)):
        r = modules.get(m)
        if r is None:
            tests = mirror_tests(m) if (ROOT / m).exists() else []
            lines.append(f"{m}: no run yet" + ("" if tests else " (no mirror tests)"))
        else:
            line = (f"{m}: killed {r.get('killed', 0)}, survived {r.get('survived', 0)}, "
                    f"no tests {r.get('no_tests', 0)}, equivalent {r.get('equivalent', 0)},"
                    f" not checked {r.get('not_checked', 0)} of {r.get('total', 0)}, "
                    f"kill rate {r.get('kill_rate')}")
            if "sample" in r:
                live = r.get("killed", 0) + r.get("survived", 0) + r.get("no_tests", 0)
                lo, hi = wilson(r.get("killed", 0), live)
                line += f" (random sample of {live}: 95% interval {lo:.3f}-{hi:.3f})"
            lines.append(line)
    t = report.get("totals", {})
    lines.append(f"all modules: kill rate {t.get('kill_rate')} over the {len(modules)} modules "
                 f"run ({t.get('kill_rate_all_mutants')} counting mutants never run; "
                 f"{t.get('kill_rate_weighted_by_module_size')} as the modules' rates weighted "
                 f"by their mutants); {len(set(all_modules()) - set(modules))} modules without "
                 f"a run")
    return lines


def _mutmut_version() -> str:
    from importlib.metadata import version

    return version("mutmut")


def main(argv: list[str] | None = None) -> int:
    cfg = _config()
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("modules", nargs="*",
                        help="files to mutate, .py or .c (default: [tool.symhx-mutation] default)")
    parser.add_argument("--all", action="store_true",
                        help="every module of the package, the C engine included")
    parser.add_argument("--summary", action="store_true",
                        help="only print every module's kill rate, or that it has no run yet")
    parser.add_argument("--tests", nargs="+", metavar="FILE", default=None,
                        help="run these test files instead of the modules' mirror files")
    parser.add_argument("--c-mutants", type=int, default=None, metavar="K",
                        help="mutate a C source K times, spread over the file (default: all)")
    parser.add_argument("--max-children", type=int, default=1)
    parser.add_argument("--timeout-multiplier", type=float, default=4.0)
    parser.add_argument("--workdir", type=Path,
                        default=Path(tempfile.gettempdir()) / "symhx-mutation")
    parser.add_argument("--report", type=Path, default=REPORT)
    parser.add_argument("--report-only", action="store_true",
                        help="only rebuild the report from the last run in --workdir")
    parser.add_argument("--no-nice", action="store_true")
    parser.add_argument("--merge", nargs="+", type=Path, metavar="REPORT", default=None,
                        help="only merge these reports (e.g. from parallel runs on different "
                             "modules) into --report")
    parser.add_argument("--rerun", nargs="+", metavar="MUTANT", default=None,
                        help="rerun only these mutants in the existing --workdir with the current "
                             "test files (after adding tests for survivors), then rebuild the "
                             "report")
    parser.add_argument("--sample", type=int, default=None, metavar="K",
                        help="run K mutants per Python module, drawn at random from those "
                             "without a verdict (an estimate of the kill rate)")
    parser.add_argument("--seed", type=int, default=0, help="the seed of --sample")
    parser.add_argument("--resume", action="store_true",
                        help="continue a stopped run in --workdir: refresh its sources and tests, "
                             "keep the verdicts of unchanged functions (C: of mutants in the "
                             "report), run the other mutants")
    args = parser.parse_args(argv)

    old = json.loads(args.report.read_text()) if args.report.exists() else {}
    if args.summary:
        print("\n".join(summary_lines(old)))
        return 0
    if args.merge:
        merged = merge_reports([json.loads(p.read_text()) for p in args.merge])
        args.report.write_text(json.dumps(merged, indent=1) + "\n")
        print(json.dumps(merged["totals"]))
        return 0
    modules = args.modules or (all_modules() if args.all else cfg.get("default", []))
    missing = [m for m in modules if not (ROOT / m).is_file()]
    if missing:
        parser.error(f"no such source files: {missing}")
    tests_of = {m: list(args.tests) if args.tests else mirror_tests(m) for m in modules}
    untested = [m for m in modules if not tests_of[m]]
    for m in untested:
        print(f"{m}: no mirror tests (tests/.../test_{mirror_stem(Path(m).name)}*.py): not run")
    py_modules = [m for m in modules if m.endswith(".py") and tests_of[m]]
    c_modules = [m for m in modules if m.endswith(".c") and tests_of[m]]
    workdir: Path = args.workdir.resolve()
    report = old
    if py_modules:
        report = run_python_modules(args, py_modules, tests_of, workdir, old)
    for m in c_modules:
        entry = run_c_module(m, tests_of[m], workdir.with_name(workdir.name + "-c"),
                             args.c_mutants, args.timeout_multiplier, not args.no_nice,
                             report.get("modules", {}).get(m, {}), report.get("equivalent", {}),
                             args.resume)
        report = _assemble({**report.get("modules", {}), m: entry},
                           report.get("equivalent", {}), report.get("stale_equivalent", {}))
    if not (py_modules or c_modules) and not args.report_only:
        print("nothing to run")
        return 1
    args.report.write_text(json.dumps(report, indent=1) + "\n")
    print(json.dumps(report["totals"]))
    for m in modules:
        r = report["modules"].get(m)
        if r is not None:
            print(f"{m}: killed {r['killed']}, survived {r['survived']}, no tests "
                  f"{r['no_tests']}, equivalent {r['equivalent']}, not checked "
                  f"{r.get('not_checked', 0)}, kill rate {r['kill_rate']}")
    print(f"modules without a run: {len(report['modules_without_run'])} "
          f"(python scripts/mutation.py --summary)")
    return 0


def run_python_modules(args: argparse.Namespace, modules: list[str],
                       tests_of: dict[str, list[str]], workdir: Path, old: dict) -> dict:
    """mutmut over the Python modules in ``workdir``; the report with their entries."""
    tests = sorted({t for m in modules for t in tests_of[m]})
    if args.resume:
        if not (workdir / "mutants").is_dir():
            raise SystemExit("--resume needs the --workdir of an earlier run")
        _copy_repo(workdir, keep_mutants=True)
        for m in modules:  # mutmut regenerates a module's mutants only when its source is newer
            # (copy2 kept the old time, and an earlier run on other modules left a plain copy)
            os.utime(workdir / m)
    if args.rerun or args.resume:
        for dest in (workdir / "tests", workdir / "mutants" / "tests"):
            shutil.copytree(ROOT / "tests", dest, dirs_exist_ok=True)
        # mutmut copies the files it does not mutate (the C engine's source and build) into
        # mutants/ only once: refresh them, or a rebuilt extension is tested against its old copy;
        # the same for the modules that are not mutated in this run: without this a rerun tests
        # the current tests against the other modules as they were at the first run (a module
        # that an earlier run in this folder mutated keeps its trampolined copy: it has a .meta)
        mutated = {ROOT / m for m in modules}
        for src in (*(ROOT / "symhx").rglob("*.so"), *(ROOT / "symhx").rglob("*.c"),
                    *(p for p in (ROOT / "symhx").rglob("*.py") if p not in mutated)):
            dst = workdir / "mutants" / src.relative_to(ROOT)
            if dst.parent.is_dir() and not dst.with_name(dst.name + ".meta").exists():
                shutil.copy2(src, dst)
                # and the work directory's own copy, which mutmut copies into mutants/ again
                # when it starts (a rerun would otherwise test against the modules as they
                # were at the first run)
                own = workdir / src.relative_to(ROOT)
                if own.parent.is_dir():
                    shutil.copy2(src, own)
        # new tests are only run for a mutant once mutmut has re-collected which tests
        # execute which function
        (workdir / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)
    if not args.report_only:
        if not (args.rerun or args.resume):
            _copy_repo(workdir)
        # a rerun takes the current mirror files too (test files added since the first run)
        _write_mutmut_config(workdir, modules, tests, args.timeout_multiplier)
        # mutmut, also mutating functions with symhx's decorators (scripts/mutmut_decorated.py)
        cmd = [sys.executable, str(ROOT / "scripts" / "mutmut_decorated.py"), "run",
               "--max-children", str(args.max_children)]
        if not args.no_nice:
            cmd = ["nice", "-n", "19", *cmd]
        # mutmut puts mutants/ first on sys.path itself; an inherited PYTHONPATH (for instance the
        # work tree) would make the tests import the unmutated code, or confuse its statistics.
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        print("running:", " ".join(cmd), "in", workdir, "\n  tests:", " ".join(tests), flush=True)
        # a filter that matches no mutant: mutmut generates the mutants and collects which tests
        # run which function, then stops; each function then gets every test of the files
        # that run it (widen_to_test_files), and the mutants run
        subprocess.run([*cmd, "symhx.no_such_mutant"], cwd=workdir, env=env, check=False,
                       capture_output=True)
        added = widen_to_test_files(workdir / "mutants" / "mutmut-stats.json")
        print(f"  {added} (function, test) pairs added from the same test files", flush=True)
        if args.sample is None:
            subprocess.run([*cmd, *(args.rerun or [])], cwd=workdir, env=env, check=False)
        else:
            chosen = sample_mutants(workdir, modules, args.sample, args.seed)
            print(f"  a random sample of {len(chosen)} mutants (seed {args.seed})", flush=True)
            if chosen or args.rerun:
                subprocess.run([*cmd, *(args.rerun or []), *chosen], cwd=workdir, env=env,
                               check=False)
    sample = None if args.sample is None else {
        m: {"size_per_run": args.sample, "seed": args.seed} for m in modules}
    return build_report(workdir, modules, old, tests_of, sample)


def widen_to_test_files(stats_path: Path) -> int:
    """Give each function every recorded test of the test files that run it; returns the number
    of (function, test) pairs added.

    mutmut records which tests run a function by watching the calls, so a module- or
    session-scoped fixture counts only for the first test that uses it: a later test of the
    same file that checks the fixture's result (a figure drawn once for the whole file) is never
    run on that function's mutants, which then survive although a normal run kills them. A
    test file is one behaviour's tests, so its tests go together."""
    if not stats_path.exists():
        return 0
    stats = json.loads(stats_path.read_text())
    by_file: dict[str, set[str]] = {}
    for test in stats.get("duration_by_test", {}):
        by_file.setdefault(test.split("::", 1)[0], set()).add(test)
    added = 0
    table = stats.get("tests_by_mangled_function_name", {})
    for name, tests in table.items():
        wide = set(tests).union(*(by_file.get(t.split("::", 1)[0], set()) for t in tests))
        added += len(wide) - len(set(tests))
        table[name] = sorted(wide)
    stats_path.write_text(json.dumps(stats))
    return added


def sample_mutants(workdir: Path, modules: list[str], k: int, seed: int) -> list[str]:
    """``k`` mutants per module, drawn at random from those without a verdict in ``workdir``."""
    rng = random.Random(seed)
    chosen: list[str] = []
    for m in modules:
        meta = workdir / "mutants" / (m + ".meta")
        if not meta.exists():
            continue
        codes = json.loads(meta.read_text())["exit_code_by_key"]
        pending = sorted(n for n, c in codes.items() if c is None)
        chosen += sorted(rng.sample(pending, min(k, len(pending))))
    return chosen


if __name__ == "__main__":
    raise SystemExit(main())
