"""scripts/mutation.py without running a campaign: the tests of a module come from the mirror
layout, the C operators change exactly one token of code (never a comment, a string or an
include), and the committed report reads fine, including which modules have no run yet."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("mutation_script", ROOT / "scripts" / "mutation.py")
mutation = importlib.util.module_from_spec(spec)
sys.modules.setdefault("mutation_script", mutation)
spec.loader.exec_module(mutation)


def _tree(tmp_path: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    return tmp_path


def test_mirror_stem_drops_the_leading_underscore():
    assert mutation.mirror_stem("rayleigh.py") == "rayleigh"
    assert mutation.mirror_stem("_dist.py") == "dist"
    assert mutation.mirror_stem("_fast.c") == "fast"
    assert mutation.mirror_stem("__init__.py") == "init"
    assert mutation.mirror_stem("__main__.py") == "main"


def test_tests_of_a_module_are_its_mirror_files_and_their_named_extras(tmp_path):
    root = _tree(tmp_path, {
        "symhx/a/b.py": "", "symhx/a/b_c.py": "", "symhx/a/_d.py": "", "symhx/a/_b.c": "",
        "tests/a/test_b.py": 'MUTATION_ALSO = ("tests/system/test_job.py", "tests/gone.py")\n',
        "tests/a/test_b_tails.py": "", "tests/a/test_b_c.py": "", "tests/a/test_b_c_x.py": "",
        "tests/a/test_d.py": "", "tests/a/test_bx.py": "", "tests/system/test_job.py": "",
    })
    assert mutation.mirror_tests("symhx/a/b.py", root) == [
        "tests/a/test_b.py", "tests/a/test_b_tails.py", "tests/system/test_job.py"]
    assert mutation.mirror_tests("symhx/a/b_c.py", root) == [
        "tests/a/test_b_c.py", "tests/a/test_b_c_x.py"]
    assert mutation.mirror_tests("symhx/a/_d.py", root) == ["tests/a/test_d.py"]
    # the C source symhx/a/_b.c has the mirror of b: its tests are b's
    assert mutation.mirror_tests("symhx/a/_b.c", root)[:2] == [
        "tests/a/test_b.py", "tests/a/test_b_tails.py"]
    assert mutation.all_modules(root) == ["symhx/a/_b.c", "symhx/a/_d.py", "symhx/a/b.py",
                                          "symhx/a/b_c.py"]


def test_every_module_of_the_package_is_a_mutation_target():
    modules = mutation.all_modules()
    assert "symhx/impact/_fast.c" in modules and "symhx/graph.py" in modules
    assert mutation.mirror_tests("symhx/cli.py") == ["tests/test_cli.py",
                                                      "tests/test_cli_errors.py"]
    assert "tests/commands/test_common.py" in mutation.mirror_tests("symhx/commands/_common.py")


C_SNIPPET = """#include <math.h>
#define TOLF 64.0
/* a < b in a comment, 3 + 4 */
static double f(double a, double b, int n) {
    const char *s = "x < 1 && y";   // if (a < b) return 1;
    if (!(a < b) && n >= 2) return -a + b / 2.0;
    n += 1;
    return p->x - 0.0;
}
"""


def test_c_operators_change_one_token_of_code_only():
    muts = mutation.c_mutants(C_SNIPPET, "m.c")
    changes = {(m.line, m.old, m.new) for m in muts}
    assert changes == {
        (2, "64.0", "128.0"),
        (6, "!", ""), (6, "<", "<="), (6, "&&", "||"), (6, ">=", ">"), (6, "2", "3"),
        (6, "+", "-"), (6, "/", "*"), (6, "2.0", "4.0"),
        (7, "+=", "-="), (7, "1", "2"),
        (8, "-", "+"), (8, "0.0", "1.0"),
    }
    # the unary minus of "-a", "->", the include, the comments and the string are left alone
    for m in muts:
        mutated = m.apply(C_SNIPPET)
        assert mutated != C_SNIPPET
        assert len([ln for ln in zip(C_SNIPPET.splitlines(), mutated.splitlines(), strict=True)
                    if ln[0] != ln[1]]) == 1
        assert m.diff(C_SNIPPET).startswith("- ") and "\n+ " in m.diff(C_SNIPPET)
    (sub,) = [m for m in muts if m.old == "/"]
    assert sub.name == "m.c:6:43:/->*"  # line and column from 1


def test_c_mutants_of_the_engine_cover_its_lines_and_a_spread_sample_is_even():
    text = (ROOT / "symhx" / "impact" / "_fast.c").read_text()
    muts = mutation.c_mutants(text, "symhx/impact/_fast.c")
    assert len(muts) > 500 and len({m.name for m in muts}) == len(muts)
    assert all(m.apply(text) != text for m in muts)
    sample = mutation.spread(muts, 10)
    lines = [m.line for m in sample]
    assert len(sample) == 10 and lines == sorted(lines)
    assert lines[0] < len(text.splitlines()) / 10 and lines[-1] > len(text.splitlines()) * 0.8
    assert mutation.spread(muts, None) == muts


def test_the_committed_report_reads_and_lists_the_modules_without_a_run():
    report = json.loads((ROOT / "tests" / "mutation-report.json").read_text())
    lines = mutation.summary_lines(report)
    run = set(report["modules"])
    assert len(lines) == len(set(mutation.all_modules()) | run) + 1
    for m in mutation.all_modules():
        line = next(ln for ln in lines if ln.startswith(m + ":"))
        assert ("no run yet" in line) == (m not in run), line
    assert lines[-1].startswith("all modules: kill rate")


@pytest.mark.parametrize("old_entry", [
    {"total": 10, "killed": 8, "survived": 0, "no_tests": 0, "equivalent": 2, "not_checked": 0,
     "kill_rate": 1.0, "survivors": {}},  # written before the timeouts were counted
    {"total": 5, "killed": 5, "timeouts": 1, "survived": 0, "no_tests": 0, "equivalent": 0,
     "not_checked": 0, "kill_rate": 1.0, "kill_rate_without_timeouts": 0.8, "survivors": {}},
])
def test_old_reports_merge_with_new_c_entries(old_entry):
    c_entry = {"total": 20, "killed": 3, "timeouts": 1, "survived": 1, "no_tests": 0,
               "equivalent": 1, "not_checked": 15, "kill_rate": 0.75, "survivors": {"x": "d"},
               "tool": mutation.C_TOOL}
    merged = mutation.merge_reports([{"modules": {"symhx/graph.py": old_entry}},
                                     {"modules": {"symhx/impact/_fast.c": c_entry}}])
    t = merged["totals"]
    assert t["total"] == old_entry["total"] + 20
    assert t["killed"] == old_entry["killed"] + 3
    assert t["kill_rate"] == round(t["killed"] / (t["killed"] + 1), 4)
    assert mutation.C_TOOL in merged["tool"]
    assert "symhx/impact/_fast.c" not in merged["modules_without_run"]
    assert "symhx/critical.py" in merged["modules_without_run"]


def test_wilson_interval_brackets_the_rate_and_narrows_with_the_sample():
    from statistics import NormalDist

    assert mutation.wilson(0, 0) == (0.0, 1.0)
    lo, hi = mutation.wilson(10, 10)
    assert hi == 1.0 and 0.70 < lo < 0.75  # (n/(n + z**2)) = 0.7225 for k = n = 10
    for k, n in ((3, 10), (50, 60), (990, 1000)):
        lo, hi = mutation.wilson(k, n)
        assert lo < k / n < hi
        lo2, hi2 = mutation.wilson(4 * k, 4 * n)
        assert hi2 - lo2 < hi - lo
    # the interval's centre and half-width solve |p - k/n| = z sqrt(p (1 - p)/n) (its definition)
    k, n = 7, 20
    z = NormalDist().inv_cdf(0.975)
    for p in mutation.wilson(k, n, z):
        assert abs(abs(p - k / n) - z * (p * (1 - p) / n) ** 0.5) < 1e-12


def test_a_sample_draws_only_mutants_without_a_verdict_reproducibly(tmp_path):
    codes = {f"symhx.a.x_f__mutmut_{i}": (1 if i % 3 == 0 else None) for i in range(30)}
    meta = tmp_path / "mutants" / "symhx" / "a.py.meta"
    meta.parent.mkdir(parents=True)
    meta.write_text(json.dumps({"exit_code_by_key": codes}))
    one = mutation.sample_mutants(tmp_path, ["symhx/a.py", "symhx/gone.py"], 5, seed=3)
    assert one == mutation.sample_mutants(tmp_path, ["symhx/a.py"], 5, seed=3)
    assert len(one) == len(set(one)) == 5
    assert all(codes[n] is None for n in one)
    assert one != mutation.sample_mutants(tmp_path, ["symhx/a.py"], 5, seed=4)
    pending = sorted(n for n, c in codes.items() if c is None)
    assert sorted(mutation.sample_mutants(tmp_path, ["symhx/a.py"], 99, seed=0)) == pending


def test_report_weights_each_module_rate_by_its_mutants():
    rep = mutation._assemble({
        "symhx/a.py": {"total": 900, "killed": 900, "survived": 0, "no_tests": 0,
                       "equivalent": 0, "kill_rate": 1.0},
        "symhx/b.py": {"total": 100, "killed": 5, "survived": 5, "no_tests": 0,
                       "equivalent": 0, "kill_rate": 0.5, "sample": {"size_per_run": 10}},
    }, {}, {})
    assert rep["totals"]["kill_rate_weighted_by_module_size"] == 0.95
    assert rep["totals"]["kill_rate"] == round(905 / 910, 4)


def test_every_module_level_cache_is_emptied_for_each_mutant():
    """A module-level dict or list that is empty after a fresh import is a cache filled on
    demand (a thread-local store too): each is listed in tests/harness/caches.py, so a mutant's
    test run (forked by mutmut after its clean run) starts without them."""
    import subprocess

    code = (
        "import importlib, pkgutil, threading, json, symhx\n"
        "out = []\n"
        "for m in pkgutil.walk_packages(symhx.__path__, 'symhx.'):\n"
        "    mod = importlib.import_module(m.name)\n"
        "    for k, v in vars(mod).items():\n"
        "        if (isinstance(v, (dict, list)) and not v) or isinstance(v, threading.local):\n"
        "            out.append([m.name, k])\n"
        "print(json.dumps(out))\n")
    found = json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True,
                                      text=True, check=True, cwd=ROOT).stdout)
    from tests.harness.caches import CACHES, clear_caches

    # the per-thread mpmath contexts hold no values: not a cache
    missing = [(m, k) for m, k in found if k not in CACHES.get(m, ()) and
               (m, k) != ("symhx._mpctx", "_tls")]
    assert not missing, missing
    # and clearing empties them (and the functools caches)
    import symhx

    symhx.mean(101, "0.02", dps=20)
    assert clear_caches() >= len(CACHES)
    for module, names in CACHES.items():
        for name in names:
            store = getattr(importlib.import_module(module), name)
            assert not (store if isinstance(store, (dict, list)) else vars(store)), (module, name)


def test_functions_with_symhx_decorators_are_mutated_and_keep_their_decorators():
    """scripts/mutmut_decorated.py: a function under allowed decorators gets mutants; its
    trampoline carries the decorators (outside mutmut's own), the copies it calls are plain;
    a function under another decorator is still skipped, and decorator arguments are never
    mutated."""
    spec2 = importlib.util.spec_from_file_location("mutmut_decorated",
                                                   ROOT / "scripts" / "mutmut_decorated.py")
    md = importlib.util.module_from_spec(spec2)
    spec2.loader.exec_module(md)
    md.patch()
    from mutmut.mutation.file_mutation import mutate_file_contents

    src = (
        "import functools\n"
        "def styled(f):\n    return f\n"
        "def other(f):\n    return f\n"
        "@styled\n"
        "def draw(x):\n    return x + 1\n"
        "@functools.lru_cache(maxsize=8)\n"
        "def cached(x):\n    return x * 2\n"
        "@other\n"
        "def skipped(x):\n    return x - 1\n"
        "class A:\n"
        "    @property\n"
        "    def value(self):\n        return 3 + 4\n"
    )
    res = mutate_file_contents("m.py", src)
    names = res.mutant_names
    assert any(n.startswith("x_draw__mutmut_") for n in names)
    assert any(n.startswith("x_cached__mutmut_") for n in names)
    assert any("value__mutmut_" in n for n in names)
    assert not any("skipped" in n for n in names)
    code = res.code
    assert "@styled\n@_mutmut_mutated(mutants_x_draw__mutmut)\ndef draw(" in code
    assert "@functools.lru_cache(maxsize=8)\n@_mutmut_mutated" in code  # maxsize kept
    assert "\ndef x_draw__mutmut_orig(" in code and "@styled\ndef x_draw__mutmut_orig" not in code
    assert "@property\n    @_mutmut_mutated" in code
    # and the mutated module runs: the decorators wrap the trampoline, which calls the copies
    namespace: dict = {}
    exec(compile(code, "m.py", "exec"), namespace)
    assert namespace["draw"](1) == 2 and namespace["cached"](2) == 4
    assert namespace["A"]().value == 7


def test_a_function_is_tested_by_every_test_of_the_files_that_run_it(tmp_path):
    # mutmut credits a module-scoped fixture's calls to the first test that uses it only: the
    # later tests of that file (the figure-data checks of a figure drawn once) are added, the
    # files that never run the function are not, and the other fields are kept
    stats = {"tests_by_mangled_function_name": {"f": ["t/a.py::one"], "g": ["t/b.py::x[1]"]},
             "duration_by_test": {"t/a.py::one": 0.1, "t/a.py::two": 0.2, "t/b.py::x[1]": 0.1,
                                  "t/b.py::x[2]": 0.1, "t/c.py::other": 0.3},
             "function_hashes": {"f": "h"}}
    path = tmp_path / "mutmut-stats.json"
    path.write_text(json.dumps(stats))
    assert mutation.widen_to_test_files(path) == 2
    got = json.loads(path.read_text())
    assert got["tests_by_mangled_function_name"] == {
        "f": ["t/a.py::one", "t/a.py::two"], "g": ["t/b.py::x[1]", "t/b.py::x[2]"]}
    assert got["function_hashes"] == {"f": "h"} and got["duration_by_test"] == stats[
        "duration_by_test"]
    assert mutation.widen_to_test_files(tmp_path / "none.json") == 0
