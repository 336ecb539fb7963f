"""The package's layering and the test suite's layout, read from the source with ``ast`` (no
import is executed).

The package:

* no import cycles between symhx modules (module-level *and* function-level imports count: a lazy
  import is still a dependency; so do ``importlib.import_module`` / ``__import__`` calls: a
  constant name is one edge, an f-string such as ``f"symhx.commands.{name}"`` is an edge to every
  module under its constant prefix, ``{__name__}`` read as the importing module's name);
* no private name (``_x``) imported from another module;
* ``import symhx`` stays cheap and public: no sympy / matplotlib, ``dir(symhx)`` shows only
  public names, and the top-level names resolve to :mod:`symhx.api`.

The tests (issue 26; see ``book/testing.md``):

* every test file mirrors a source module (``symhx/a/b.py`` -> ``tests/a/test_b.py`` or
  ``tests/a/test_b_<aspect>.py``; a leading underscore dropped, ``__init__`` -> ``test_init``,
  ``__main__`` -> ``test_main``; C sources count as modules) or sits in ``tests/reference/``,
  ``tests/harness/``, ``tests/system/`` or ``tests/perf/``; every test folder is a package;
* no test module imports another test module: shared code is imported from ``tests.reference``
  and ``tests.harness`` only;
* private names of symhx (imports, attributes, ``getattr``/``monkeypatch.setattr`` strings) are
  used only in the mirror file(s) of the module that owns them and in ``tests/perf/``;
* error tests check the argument's name, value and the allowed range (``tests.harness.errors.
  assert_refuses``), never a whole sentence: no ``match=`` anchored with ``^`` or ``$``;
* test names say what they pin, not how it was found (no ``mut``, ``survivor``, ``roundN``,
  ``audit``); no data files in ``tests/`` but the mutation report and reference data;
* independent references are written once, in ``tests/reference/``: no ``_ref*`` /
  ``_reference*`` function elsewhere.

Violations in modules owned by other engineers are listed in ``KNOWN_*`` below so that the test
guards against *new* ones; delete an entry when it is fixed (the test then keeps it fixed).  The
old flat test files that are still being moved into the layout are listed in
:data:`LEGACY_FLAT_FILES`; the layout rules skip exactly those files, and the list must shrink to
empty (an entry whose file is gone fails the test, so the list stays current).
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from collections.abc import Iterator
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PKG = ROOT / "symhx"
TESTS = ROOT / "tests"

KNOWN_CYCLE_EDGES: set[tuple[str, str]] = set()
# The only exception: the C extension module of the float64 engine is private by its name
# (``symhx.impact._fast``) and is imported by its one Python wrapper.
KNOWN_PRIVATE_IMPORTS: set[tuple[str, str, str]] = {
    ("symhx.impact.fast", "symhx.impact", "_fast"),  # the C extension module
}

#: Old flat test files (``tests/test_*.py``) not yet moved into the layout: the layout rules skip
#: exactly these.  Other engineers are moving them; the lead empties this set after merging.
LEGACY_FLAT_FILES: frozenset[str] = frozenset({
})

#: folders of tests/ that are not mirrors of the package
#: private modules whose public names every test may use: the thread-context convention (issue
#: 28) -- a test calling a helper at a working precision needs mp(), export and local
SHARED_PRIVATE_MODULES = frozenset({"symhx._mpctx"})
SHARED_FOLDERS = ("reference", "harness")
FREE_FOLDERS = (*SHARED_FOLDERS, "system", "perf")
#: files in tests/ that are not Python and are kept on purpose
DATA_FILES = {"mutation-report.json"}
#: words that name how a test was found rather than what it pins
FINDING_WORDS = re.compile(r"(?:^|_)(?:mut|survivors?|round\d+|audit\w*)(?=_|\d|$)", re.I)


# =========================================================================== the package
def _module_name(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


@cache
def _modules() -> dict[str, Path]:
    return {_module_name(p): p for p in PKG.rglob("*.py") if "_build" not in p.parts}


def _resolve(mod: str, node: ast.ImportFrom, is_pkg: bool) -> str:
    if node.level == 0:
        return node.module or ""
    base = mod.split(".") if is_pkg else mod.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _dynamic_import_targets(node: ast.Call, mod: str, mods: dict[str, Path]) -> list[str]:
    """Modules named by ``importlib.import_module(x)`` / ``import_module(x)`` /
    ``__import__(x)``: a constant string, or an f-string read up to its first unknown part
    (``{__name__}`` is the importing module's name) as the prefix of every module it may name."""
    f = node.func
    name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else ""
    if name not in ("import_module", "__import__") or not node.args:
        return []
    arg = node.args[0]
    if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
        return [arg.value]
    if not isinstance(arg, ast.JoinedStr):
        return []
    prefix = ""
    for part in arg.values:
        if isinstance(part, ast.Constant):
            prefix += str(part.value)
        elif (isinstance(part, ast.FormattedValue) and isinstance(part.value, ast.Name)
              and part.value.id == "__name__"):
            prefix += mod
        else:
            return [m for m in mods if m.startswith(prefix)] if prefix else []
    return [prefix]


def _imports() -> tuple[dict[str, set[str]], list[tuple[str, str, str]]]:
    mods = _modules()
    edges: dict[str, set[str]] = {m: set() for m in mods}
    private: list[tuple[str, str, str]] = []
    for mod, path in mods.items():
        tree = ast.parse(path.read_text(), filename=str(path))
        is_pkg = path.name == "__init__.py"
        for node in ast.walk(tree):
            targets: list[tuple[str, str | None]] = []
            if isinstance(node, ast.Import):
                targets = [(a.name, None) for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                src = _resolve(mod, node, is_pkg)
                for a in node.names:
                    sub = f"{src}.{a.name}"
                    targets.append((sub, None) if sub in mods else (src, a.name))
            elif isinstance(node, ast.Call):
                targets = [(t, None) for t in _dynamic_import_targets(node, mod, mods)]
            for target, name in targets:
                if not target.startswith("symhx"):
                    continue
                # the module itself, or its package if the target is a name inside it
                t = target
                while t and t not in mods:
                    t = t.rpartition(".")[0]
                if t and t != mod:
                    edges[mod].add(t)
                if name and name.startswith("_") and not name.startswith("__") and t != mod:
                    private.append((mod, t, name))
    return edges, private


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10_000)
    for v in edges:
        if v not in index:
            visit(v)
    return out


def _edges_without_known() -> dict[str, set[str]]:
    edges, _ = _imports()
    for a, b in KNOWN_CYCLE_EDGES:
        edges.get(a, set()).discard(b)
    # a package's __init__ re-exporting its submodules is not a cycle with them
    for mod in list(edges):
        edges[mod] = {t for t in edges[mod] if not (t != mod and mod.startswith(t + ".")
                                                     and _modules()[t].name == "__init__.py")}
    return edges


def test_the_cycle_finder_finds_a_cycle() -> None:
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_importlib_calls_are_read_as_imports() -> None:
    mods = {"symhx.api": Path(), "symhx.commands.core": Path(), "symhx.commands.spaces": Path(),
            "symhx.cli": Path()}

    def targets(code: str, mod: str = "symhx.cli") -> list[str]:
        (call,) = [n for n in ast.walk(ast.parse(code)) if isinstance(n, ast.Call)
                   and getattr(n.func, "attr", getattr(n.func, "id", "")) != "getattr"]
        return sorted(_dynamic_import_targets(call, mod, mods))

    assert targets('importlib.import_module("symhx.api")') == ["symhx.api"]
    assert targets('import_module("symhx.api")') == ["symhx.api"]
    assert targets('__import__("symhx.api")') == ["symhx.api"]
    assert targets('importlib.import_module(f"symhx.commands.{name}")') == [
        "symhx.commands.core", "symhx.commands.spaces"]
    assert targets('importlib.import_module(f"{__name__}.{name}")', "symhx.commands") == [
        "symhx.commands.core", "symhx.commands.spaces"]
    assert targets("importlib.import_module(name)") == []
    # the graph sees the importlib edge of the package
    edges, _ = _imports()
    assert "symhx.commands.core" in edges["symhx.commands"]


def test_no_import_cycles() -> None:
    cycles = _cycles(_edges_without_known())
    assert cycles == [], f"import cycles: {cycles}"


def test_known_cycle_edges_still_exist() -> None:
    """An entry of KNOWN_CYCLE_EDGES whose import is gone must be deleted (so it cannot hide a new
    import later)."""
    edges, _ = _imports()
    stale = sorted((a, b) for a, b in KNOWN_CYCLE_EDGES if b not in edges.get(a, set()))
    assert stale == [], f"delete these from KNOWN_CYCLE_EDGES: {stale}"


def test_command_modules_do_not_import_the_cli() -> None:
    edges, _ = _imports()
    up = sorted(m for m in edges if m.startswith("symhx.commands") and "symhx.cli" in edges[m])
    assert up == [], f"command modules importing symhx.cli: {up}"


def test_distribution_layers_flow_one_way() -> None:
    edges = _edges_without_known()
    lower = ("symhx.distribution", "symhx.circuits", "symhx.graph", "symhx.validation",
             "symhx._numeric")
    for mod in lower:
        assert not any(t.startswith("symhx.spaces") or t == "symhx.api" for t in edges[mod]), (
            mod, edges[mod])
    # only the layers above the API (the package namespace, plots, CLI commands) may import it
    above = ("symhx.plots", "symhx.commands", "symhx.cli")
    importers = {m for m, ts in edges.items() if "symhx.api" in ts}
    below = {m for m in importers if m != "symhx" and not m.startswith(above)}
    assert below == set(), f"modules below the API import symhx.api: {sorted(below)}"


def test_no_private_names_imported_across_modules() -> None:
    _, private = _imports()
    new = sorted(set(private) - KNOWN_PRIVATE_IMPORTS)
    assert new == [], f"private names imported across modules: {new}"


def test_import_symhx_is_cheap_and_public() -> None:
    code = (
        "import sys, symhx\n"
        "bad = {'sympy', 'matplotlib'} & {m.split('.')[0] for m in sys.modules}\n"
        "assert not bad, bad\n"
        "names = dir(symhx)\n"
        "assert not {'Any', 'annotations', 'importlib', '_Any', '_importlib'} & set(names), names\n"
        "assert all(not n.startswith('_') or n == '__version__' for n in names), names\n"
        "import symhx.api as api\n"
        "for n in ('mean', 'mode', 'modes', 'pmf', 'critical_point', 'distribution_of'):\n"
        "    assert getattr(symhx, n) is getattr(api, n), n\n"
        "bad = {'sympy', 'matplotlib'} & {m.split('.')[0] for m in sys.modules}\n"
        "assert not bad, bad\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT,
                   env={"PYTHONPATH": str(ROOT), "PATH": ""})


def test_every_export_resolves() -> None:
    import symhx

    for name in symhx.__all__:
        assert getattr(symhx, name) is not None, name


@pytest.mark.parametrize("word", ["DESIGN.md", "paper.md"])
def test_no_reference_to_files_outside_the_repository(word: str) -> None:
    """Code and docs must not point to files outside the repository (the design notes and the
    paper live outside it): the package, the book, the scripts, the benchmarks, the README."""
    roots = [PKG, ROOT / "book", ROOT / "scripts", ROOT / "benchmarks"]
    files = [f for r in roots for f in r.rglob("*")
             if f.suffix in {".py", ".md", ".yml", ".toml", ".c"} and "_build" not in f.parts]
    files += [ROOT / "README.md", ROOT / "ARCHITECTURE.md", ROOT / "pyproject.toml"]
    hits = [str(f.relative_to(ROOT)) for f in files if word in f.read_text(errors="replace")]
    assert hits == []


def test_mypy_clean_on_the_whole_package() -> None:
    """``mypy`` (configured in pyproject.toml: every file of symhx) reports no error."""
    pytest.importorskip("mypy")
    res = subprocess.run([sys.executable, "-m", "mypy", "--no-incremental"], cwd=ROOT,
                         capture_output=True, text=True, env={"PYTHONPATH": str(ROOT),
                                                               "PATH": ""})
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-2000:]


# =========================================================================== the test layout
def _mirror_stem(path: Path) -> str:
    """The ``x`` of ``test_x``: the source file's name, a leading underscore dropped."""
    stem = path.name.split(".", 1)[0]
    return {"__init__": "init", "__main__": "main"}.get(stem, stem.lstrip("_"))


@cache
def _source_modules() -> dict[tuple[tuple[str, ...], str], frozenset[str]]:
    """(folder below symhx/, mirror stem) -> dotted names of the modules (.py and .c sources)."""
    out: dict[tuple[tuple[str, ...], str], set[str]] = {}
    for p in (*PKG.rglob("*.py"), *PKG.rglob("*.c")):
        if "_build" in p.parts:
            continue
        folder = p.parent.relative_to(PKG).parts
        dotted = ".".join(("symhx", *folder, *([] if p.stem == "__init__" else [p.stem])))
        out.setdefault((folder, _mirror_stem(p)), set()).add(dotted)
    return {k: frozenset(v) for k, v in out.items()}


def mirror_modules(rel: Path) -> frozenset[str]:
    """The modules whose mirror a test file is (``tests/a/test_b[_aspect].py`` -> ``symhx.a.b``
    or ``symhx.a._b``); empty for a file that mirrors nothing."""
    parts = rel.parts[1:]  # below tests/
    if not parts[-1].startswith("test_") or not parts[-1].endswith(".py"):
        return frozenset()
    folder, x = tuple(parts[:-1]), parts[-1][len("test_"):-len(".py")]
    found: set[str] = set()
    for (f, stem), mods in _source_modules().items():
        if f == folder and (x == stem or x.startswith(stem + "_")):
            found |= mods
    return frozenset(found)


def _all_test_files() -> list[Path]:
    """Every Python file below tests/, relative to the repository root."""
    return sorted(p.relative_to(ROOT) for p in TESTS.rglob("*.py") if "__pycache__" not in p.parts)


def _checked(files: list[Path] | None = None) -> list[Path]:
    files = _all_test_files() if files is None else files
    return [f for f in files if not (len(f.parts) == 2 and f.name in LEGACY_FLAT_FILES)]


def _folder(rel: Path) -> str:
    return rel.parts[1] if len(rel.parts) > 2 else ""


def test_legacy_allow_list_is_current() -> None:
    flat = {p.name for p in TESTS.glob("test_*.py")}
    gone = sorted(LEGACY_FLAT_FILES - flat)
    assert gone == [], f"these files are gone: delete them from LEGACY_FLAT_FILES: {gone}"


def test_the_mirror_of_a_module_is_found() -> None:
    assert mirror_modules(Path("tests/forcing/test_rayleigh.py")) == {"symhx.forcing.rayleigh"}
    assert mirror_modules(Path("tests/forcing/test_rayleigh_many_scales.py")) == {
        "symhx.forcing.rayleigh"}
    assert mirror_modules(Path("tests/test_numeric.py")) == {"symhx._numeric"}
    assert mirror_modules(Path("tests/spaces/test_dist_tails.py")) == {"symhx.spaces._dist"}
    assert mirror_modules(Path("tests/impact/test_fast.py")) == {"symhx.impact.fast",
                                                                 "symhx.impact._fast"}
    assert mirror_modules(Path("tests/plots/test_init.py")) == {"symhx.plots"}
    assert mirror_modules(Path("tests/test_main.py")) == {"symhx.__main__"}
    assert mirror_modules(Path("tests/test_rayleigh.py")) == frozenset()
    assert mirror_modules(Path("tests/forcing/test_rayleighs.py")) == frozenset()
    assert mirror_modules(Path("tests/system/test_fuzz.py")) == frozenset()


def layout_problem(rel: Path) -> str | None:
    """Why a file (relative to the root) is not where the layout puts it, or None."""
    folder = _folder(rel)
    if rel.name in ("__init__.py", "conftest.py"):
        return None
    if folder in SHARED_FOLDERS:
        return None
    if folder in ("system", "perf"):
        return None if rel.name.startswith("test_") and len(rel.parts) == 3 else \
            f"tests/{folder}/ holds test_*.py files directly"
    if not rel.name.startswith("test_"):
        return "not a test_*.py file, and not in tests/reference/ or tests/harness/"
    if not mirror_modules(rel):
        return "mirrors no source module (tests/a/test_b[_aspect].py for symhx/a/b.py)"
    return None


def test_every_test_file_mirrors_a_module_or_sits_in_a_shared_folder() -> None:
    bad = {str(f): why for f in _checked() if (why := layout_problem(f))}
    assert bad == {}, f"test files outside the layout: {bad}"


def test_every_test_folder_is_a_package() -> None:
    folders = {p.parent for p in TESTS.rglob("*.py") if "__pycache__" not in p.parts}
    missing = sorted(str(d.relative_to(ROOT)) for d in folders if not (d / "__init__.py").exists())
    assert missing == []


def test_tests_hold_no_data_files_but_the_mutation_report_and_references() -> None:
    extra = sorted(str(p.relative_to(ROOT)) for p in TESTS.rglob("*")
                   if p.is_file() and p.suffix not in (".py", ".pyc") and "__pycache__" not in
                   p.parts and p.name not in DATA_FILES
                   and _folder(p.relative_to(ROOT)) not in SHARED_FOLDERS)
    assert extra == [], f"records or data in tests/ (a failure belongs in a test): {extra}"


#: the names of a private reference helper (``_ref``, ``_ref_pmf``, ``_reference``)
REFERENCE_HELPER = re.compile(r"^_ref(?:erence)?(?:_|$)")


def test_references_live_only_in_the_reference_package() -> None:
    """An independent reference is written once, in ``tests/reference/``: no test file
    defines its own ``_ref*`` / ``_reference*`` function."""
    bad = []
    for f in _checked():
        if _folder(f) == "reference":
            continue
        for node in ast.walk(_parse(f)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and \
                    REFERENCE_HELPER.match(node.name):
                bad.append(f"{f}:{node.lineno} {node.name}")
    assert bad == [], f"references outside tests/reference/: {bad}"


def test_test_names_say_what_they_pin_not_how_they_were_found() -> None:
    bad = [str(f) for f in _checked() if FINDING_WORDS.search(f.stem)]
    for f in _checked():
        for node in ast.walk(_parse(f)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and \
                    node.name.lower().startswith("test") and FINDING_WORDS.search(node.name):
                bad.append(f"{f}:{node.lineno} {node.name}")
    assert bad == [], f"names that record how a test was found: {bad}"


@cache
def _parse(rel: Path) -> ast.Module:
    return ast.parse((ROOT / rel).read_text(), filename=str(rel))


# --------------------------------------------------------------------------- test-to-test imports
def _package_of(rel: Path) -> list[str]:
    parts = list(rel.with_suffix("").parts)
    return parts[:-1]


def imported_test_modules(rel: Path, tree: ast.Module) -> list[tuple[int, str]]:
    """(line, module) of every import of a test module that is not shared code: ``tests.x`` other
    than ``tests.reference`` / ``tests.harness``, a relative import leaving them, ``conftest``,
    or a bare ``test_*`` module."""
    out = []
    test_names = {p.stem for p in TESTS.rglob("test_*.py")}
    for node in ast.walk(tree):
        names: list[str] = []
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = _package_of(rel)
                base = base[: len(base) - (node.level - 1)]
                src = ".".join(base + ([node.module] if node.module else []))
            else:
                src = node.module or ""
            names = [f"{src}.{a.name}" if src else a.name for a in node.names]
        elif isinstance(node, ast.Call):
            names = [t for t in _dynamic_import_targets(node, "", {}) if t.startswith("tests")]
        for name in names:
            parts = name.split(".")
            if parts[0] == "tests":
                if len(parts) > 1 and parts[1] in SHARED_FOLDERS:
                    continue
                out.append((node.lineno, name))
            elif parts[0] == "conftest" or parts[0] in test_names:
                out.append((node.lineno, name))
    return out


def test_the_test_import_finder_finds_test_imports() -> None:
    code = ("from tests.reference.mp import rel_err\nimport tests.harness.errors\n"
            "from tests import reference\nfrom tests.test_fuzz import API\n"
            "from tests.system import test_fuzz\nimport conftest\nfrom ..reference import mp\n"
            "from . import test_core\nimport test_cli\n")
    found = [name for _, name in imported_test_modules(Path("tests/commands/test_x.py"),
                                                       ast.parse(code))]
    assert found == ["tests.test_fuzz.API", "tests.system.test_fuzz", "conftest",
                     "tests.commands.test_core", "test_cli"]


def test_no_test_module_imports_another_test_module() -> None:
    bad = [f"{f}:{line} imports {name}" for f in _checked()
           for line, name in imported_test_modules(f, _parse(f))]
    assert bad == [], "shared test code lives in tests/reference/ or tests/harness/: " + str(bad)


# --------------------------------------------------------------------------- private names
@cache
def _symhx_private_definitions() -> dict[str, frozenset[str]]:
    """Private name -> the modules defining it (functions, classes, assigned names and
    attributes, ``__slots__`` entries) or using it as their own (``self._x``: a subclass's
    inherited internals belong to the subclass's module too)."""
    out: dict[str, set[str]] = {}
    for mod, path in _modules().items():
        for node in ast.walk(ast.parse(path.read_text())):
            names: list[str] = []
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                names = [node.name]
            elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and \
                    node.value.id == "self":
                names = [node.attr]
            elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                for t in targets:
                    for sub in ast.walk(t):
                        if isinstance(sub, ast.Name):
                            names.append(sub.id)
                        elif isinstance(sub, ast.Attribute):
                            names.append(sub.attr)
                if any(isinstance(t, ast.Name) and t.id == "__slots__" for t in targets) and \
                        node.value is not None:
                    names += [c.value for c in ast.walk(node.value)
                              if isinstance(c, ast.Constant) and isinstance(c.value, str)]
            for n in names:
                if _is_private(n):
                    out.setdefault(n, set()).add(mod)
    return {k: frozenset(v) for k, v in out.items()}


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__") and len(name) > 1


def _owner(dotted: str) -> str:
    """The module owning the first private component of a dotted symhx path."""
    parts = dotted.split(".")
    i = next(i for i, p in enumerate(parts) if _is_private(p))
    mods = {**{m: None for m in _modules()}, **{m: None for v in _source_modules().values()
                                                  for m in v}}
    head = ".".join(parts[: i + 1])
    if head in mods:
        return head
    owner = ".".join(parts[:i])
    while owner and owner not in mods:
        owner = owner.rpartition(".")[0]
    return owner


def private_uses(tree: ast.Module) -> list[tuple[int, str, frozenset[str]]]:
    """(line, what, owning modules) of every use of a private symhx name in a test module."""
    aliases: dict[str, str] = {}   # local name -> dotted path of what it is bound to
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                aliases[a.asname or a.name.split(".")[0]] = a.name if a.asname else \
                    a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            for a in node.names:
                aliases[a.asname or a.name] = f"{node.module}.{a.name}"
    own = set()  # private names the test file defines itself
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            own.add(node.name)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store):
            own.add(node.attr)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            own.add(node.id)
    defined = _symhx_private_definitions()
    out: list[tuple[int, str, frozenset[str]]] = []

    def dotted(expr: ast.expr) -> str | None:
        if isinstance(expr, ast.Name):
            return aliases.get(expr.id)
        if isinstance(expr, ast.Attribute):
            base = dotted(expr.value)
            return f"{base}.{expr.attr}" if base else None
        return None

    def use(line: int, base: ast.expr | None, name: str) -> None:
        path = dotted(base) if base is not None else None
        if path is not None:
            if path.split(".")[0] == "symhx":
                out.append((line, f"{path}.{name}", frozenset({_owner(f"{path}.{name}")})))
            return  # another library's private name
        if name in defined and name not in own:
            out.append((line, f"._{name[1:]}", defined[name]))

    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("symhx") and any(_is_private(p) for p in a.name.split(".")):
                    out.append((node.lineno, a.name, frozenset({_owner(a.name)})))
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and \
                (node.module or "").startswith("symhx"):
            for a in node.names:
                full = f"{node.module}.{a.name}"
                if any(_is_private(p) for p in full.split(".")):
                    out.append((node.lineno, full, frozenset({_owner(full)})))
        elif isinstance(node, ast.Attribute) and _is_private(node.attr):
            use(node.lineno, node.value, node.attr)
        elif isinstance(node, ast.Call) and len(node.args) >= 2:
            f = node.func
            fname = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) \
                else ""
            key = node.args[1]
            if fname in ("getattr", "setattr", "hasattr", "delattr") and \
                    isinstance(key, ast.Constant) and isinstance(key.value, str) and \
                    _is_private(key.value):
                use(node.lineno, node.args[0], key.value)
    return out


def test_the_private_name_finder_finds_private_uses() -> None:
    code = ("import symhx\nimport symhx.forcing.rayleigh as R\nimport argparse\n"
            "from symhx._numeric import G\nfrom symhx.spaces import _dist\n"
            "from symhx.critical import _scan\nimport symhx.impact._fast\n"
            "def helper(d, parser, monkeypatch):\n"
            "    symhx.distribution._MOVED, R._private_thing, parser._actions\n"
            "    argparse._SubParsersAction, d._exact_moments\n"
            "    monkeypatch.setattr(R, '_kernel', None)\n"
            "    getattr(d, '_exact_moments')\n")
    found = [(what, sorted(owners)) for _, what, owners in private_uses(ast.parse(code))]
    assert ("symhx._numeric.G", ["symhx._numeric"]) in found
    assert ("symhx.spaces._dist", ["symhx.spaces._dist"]) in found
    assert ("symhx.critical._scan", ["symhx.critical"]) in found
    assert ("symhx.impact._fast", ["symhx.impact._fast"]) in found
    assert ("symhx.distribution._MOVED", ["symhx.distribution"]) in found
    assert ("symhx.forcing.rayleigh._private_thing", ["symhx.forcing.rayleigh"]) in found
    assert ("symhx.forcing.rayleigh._kernel", ["symhx.forcing.rayleigh"]) in found
    assert sum(what == "._exact_moments" for what, _ in found) == 2
    assert not any("_actions" in what or "_SubParsersAction" in what for what, _ in found)


def test_private_symhx_names_only_in_the_owning_mirror_file_or_perf() -> None:
    bad = []
    for f in _checked():
        if _folder(f) == "perf":
            continue
        mine = mirror_modules(f)
        for line, what, owners in private_uses(_parse(f)):
            shared = owners <= SHARED_PRIVATE_MODULES and not _is_private(what.split(".")[-1])
            if not owners & mine and not shared:
                bad.append(f"{f}:{line} {what} (owned by {', '.join(sorted(owners))})")
    assert bad == [], "private names outside their module's mirror file: " + "\n".join(bad)


# --------------------------------------------------------------------------- error messages
def _text_of(node: ast.expr) -> str | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else "{}" for v in node.values)
    return None


def whole_sentence_patterns(tree: ast.Module) -> Iterator[tuple[int, str]]:
    """``match=`` of ``pytest.raises`` / ``pytest.warns`` (or ``excinfo.match(...)``) anchored at
    either end (``^``, ``\\A``, ``$``, ``\\Z``): a pinned sentence (or its opening words in
    their order) instead of its parts.  A refusal is checked by the argument's name, the value
    and what is allowed, each found anywhere in the message."""
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        f = node.func
        fname = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else ""
        patterns = [k.value for k in node.keywords if k.arg == "match"
                    and fname in ("raises", "warns", "deprecated_call")]
        if fname == "match" and isinstance(f, ast.Attribute) and node.args:
            patterns.append(node.args[0])
        for pat in patterns:
            text = _text_of(pat)
            if text is not None and (text.startswith(("^", r"\A"))
                                     or text.endswith(("$", r"\Z"))):
                yield node.lineno, text


def test_the_sentence_finder_finds_anchored_patterns() -> None:
    code = ('with pytest.raises(ValueError, match=r"^N must be >= 2, got 1$"): pass\n'
            'with pytest.raises(ValueError, match=f"^p={p} is not allowed$"): pass\n'
            'with pytest.raises(ValueError, match="N must be"): pass\n'
            'with pytest.raises(ValueError, match=r"^N must be an int, got "): pass\n'
            'info.match(r"^whole$")\n'
            'with pytest.raises(ValueError, match=r"got 0$"): pass\n'
            'with pytest.warns(DeprecationWarning, match="moved to symhx.mean"): pass\n')
    assert sorted(line for line, _ in whole_sentence_patterns(ast.parse(code))) == [1, 2, 4, 5, 6]


def test_error_tests_check_the_parts_of_a_refusal_not_the_whole_sentence() -> None:
    bad = [f"{f}:{line} match={text!r}" for f in _checked()
           for line, text in whole_sentence_patterns(_parse(f))]
    assert bad == [], ("use tests.harness.errors.assert_refuses(fn, ..., arg=, value=, "
                       "allowed=) instead of whole sentences: " + "\n".join(bad))
