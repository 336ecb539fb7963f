#!/usr/bin/env python
"""Mutation testing of symhx on demand (not in CI): run mutmut over chosen modules, write a report.

Usage (from the repository root)::

    python scripts/mutation.py                      # the default module list (pyproject)
    python scripts/mutation.py symhx/circuits.py symhx/graph.py
    python scripts/mutation.py --all                # every core module in pyproject
    python scripts/mutation.py --report-only        # rebuild the report from the last run
    python scripts/mutation.py --merge A.json B.json  # one report from parallel runs
    python scripts/mutation.py symhx/circuits.py --rerun symhx.circuits.x_phi__mutmut_3  # after
                                                    # adding a test for a survivor
    python scripts/mutation.py symhx/critical.py --workdir W --resume  # finish a stopped run

Each run works in a scratch copy of the repository (``--workdir``, default a directory under the
system temp dir), so the work tree never gets a ``mutants/`` directory. The copy gets a
``[tool.mutmut]`` table restricted to the chosen modules and to the test files mapped to them in
``[tool.symhx-mutation.tests]`` of ``pyproject.toml``; mutmut is run under ``nice -n 19`` with
``--max-children`` workers (default 1) and its per-mutant CPU timeout
(``timeout_multiplier`` x the clean run time of the tests covering the mutated function).
mutmut also stops a mutant after half that limit of wall time, so on a busy machine some passing
mutants end as timeouts: raise ``--timeout-multiplier`` there, and read the report's
``kill_rate_without_timeouts`` next to ``kill_rate``.

The report (``tests/mutation-report.json``) lists, per module, the counts ``killed`` (tests failed,
including timeouts), ``survived``, ``equivalent`` and ``no_tests`` (no test executes the mutated
function), the ``kill_rate = killed / (killed + survived + no_tests)`` over non-equivalent mutants,
and the diff of every surviving mutant. Equivalent mutants are declared by hand in the
``equivalent`` section of the report: ``{mutant name: {"diff": ..., "why": one line}}``. A
declaration only counts while its diff still matches the mutant (mutant names are renumbered
when the code changes); stale declarations are listed under ``stale_equivalent`` and the mutant
counts as survived.

``--resume`` continues a stopped run in its ``--workdir`` with the current sources and tests:
mutmut keeps the verdict of every mutant whose function is unchanged (it compares a hash of each
function's source) and runs the rest.
"""

from __future__ import annotations

import argparse
import ast
import difflib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
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


def build_report(workdir: Path, modules: list[str], old: dict) -> dict:
    """Read mutmut's ``.meta`` files in ``workdir`` and merge with the equivalent declarations."""
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
        }
    return _assemble(per_module, equivalent_decl, stale)


def _assemble(per_module: dict, equivalent_decl: dict, stale: dict) -> dict:
    """The report: per-module results, their totals and the equivalent declarations.

    ``kill_rate`` is over the mutants that ran; ``kill_rate_all_mutants`` counts the ones a
    stopped run never reached (``not_checked``) as not killed."""
    for m in per_module.values():
        rest = m["total"] - m["equivalent"]
        m["kill_rate_all_mutants"] = round(m["killed"] / rest, 4) if rest else None
    tot = {k: sum(m.get(k, 0) for m in per_module.values())
           for k in ("total", "killed", "timeouts", "survived", "no_tests", "equivalent",
                     "not_checked")}
    live = tot["killed"] + tot["survived"] + tot["no_tests"]
    tot["kill_rate"] = round(tot["killed"] / live, 4) if live else None
    tot["kill_rate_without_timeouts"] = (round((tot["killed"] - tot["timeouts"]) / live, 4)
                                         if live else None)
    rest = tot["total"] - tot["equivalent"]
    tot["kill_rate_all_mutants"] = round(tot["killed"] / rest, 4) if rest else None
    return {
        "tool": "mutmut " + _mutmut_version(),
        "command": "python scripts/mutation.py " + " ".join(sorted(per_module)),
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
        module = re.split(r"\.x[_\u01c1]", name, maxsplit=1)[0].replace(".", "/") + ".py"
        return owner.get(module, i) == i

    equivalent: dict = {}
    stale: dict = {}
    for i, rep in enumerate(reports):
        equivalent.update({k: v for k, v in rep.get("equivalent", {}).items() if keep(k, i)})
        stale.update({k: v for k, v in rep.get("stale_equivalent", {}).items() if keep(k, i)})
    return _assemble(per_module, equivalent, stale)


def _mutmut_version() -> str:
    from importlib.metadata import version

    return version("mutmut")


def main(argv: list[str] | None = None) -> int:
    cfg = _config()
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("modules", nargs="*",
                        help="files to mutate (default: [tool.symhx-mutation] default)")
    parser.add_argument("--all", action="store_true", help="every module in [tool.symhx-mutation]")
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
    parser.add_argument("--resume", action="store_true",
                        help="continue a stopped run in --workdir: refresh its sources and tests, "
                             "keep the verdicts of unchanged functions, run the other mutants")
    args = parser.parse_args(argv)

    if args.merge:
        merged = merge_reports([json.loads(p.read_text()) for p in args.merge])
        args.report.write_text(json.dumps(merged, indent=1) + "\n")
        print(json.dumps(merged["totals"]))
        return 0
    test_map: dict[str, list[str]] = cfg.get("tests", {})
    modules = args.modules or (sorted(test_map) if args.all else cfg.get("default", []))
    unknown = [m for m in modules if m not in test_map]
    if unknown:
        parser.error(f"no test files mapped for {unknown} in [tool.symhx-mutation.tests] of "
                     f"pyproject.toml; add them there")
    tests = sorted({t for m in modules for t in test_map[m] if (ROOT / t).exists()})
    workdir: Path = args.workdir.resolve()

    if args.resume:
        if args.rerun or not (workdir / "mutants").is_dir():
            parser.error("--resume needs the --workdir of an earlier run and no --rerun")
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
        # new tests are only run for a mutant once mutmut has re-collected which tests
        # execute which function
        (workdir / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)
    if not args.report_only:
        if not (args.rerun or args.resume):
            _copy_repo(workdir)
        # a rerun takes the current test map too (test files added since the first run)
        _write_mutmut_config(workdir, modules, tests, args.timeout_multiplier)
        cmd = [sys.executable, "-m", "mutmut", "run", "--max-children", str(args.max_children),
               *(args.rerun or [])]
        if not args.no_nice:
            cmd = ["nice", "-n", "19", *cmd]
        # mutmut puts mutants/ first on sys.path itself; an inherited PYTHONPATH (for instance the
        # work tree) would make the tests import the unmutated code, or confuse its statistics.
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        print("running:", " ".join(cmd), "in", workdir, "\n  tests:", " ".join(tests), flush=True)
        subprocess.run(cmd, cwd=workdir, env=env, check=False)

    old = json.loads(args.report.read_text()) if args.report.exists() else {}
    report = build_report(workdir, modules, old)
    args.report.write_text(json.dumps(report, indent=1) + "\n")
    print(json.dumps(report["totals"]))
    for m, r in report["modules"].items():
        print(f"{m}: killed {r['killed']}, survived {r['survived']}, no tests {r['no_tests']}, "
              f"equivalent {r['equivalent']}, kill rate {r['kill_rate']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
