"""The package's layering, read from the source with ``ast`` (no import is executed):

* no import cycles between symhx modules (module-level *and* function-level imports count: a
  lazy import is still a dependency);
* no private name (``_x``) imported from another module;
* ``import symhx`` stays cheap and public: no sympy / matplotlib, ``dir(symhx)`` shows only
  public names, and the top-level names resolve to :mod:`symhx.api`.

Violations in modules owned by other engineers are listed in ``KNOWN_*`` below so that the test
guards against *new* ones; delete an entry when it is fixed (the test then keeps it fixed).
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "symhx"

# The only exception: the C extension module of the float64 engine is private by its name
# (``symhx.impact._fast``) and is imported by its one Python wrapper.
KNOWN_CYCLE_EDGES: set[tuple[str, str]] = set()
KNOWN_PRIVATE_IMPORTS: set[tuple[str, str, str]] = {
    ("symhx.impact.fast", "symhx.impact", "_fast"),  # the C extension module
}


def _module_name(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for p in PKG.rglob("*.py") if "_build" not in p.parts}


def _resolve(mod: str, node: ast.ImportFrom, is_pkg: bool) -> str:
    if node.level == 0:
        return node.module or ""
    base = mod.split(".") if is_pkg else mod.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


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


def test_no_import_cycles() -> None:
    cycles = _cycles(_edges_without_known())
    assert cycles == [], f"import cycles: {cycles}"


def test_distribution_layers_flow_one_way() -> None:
    edges, _ = _imports()
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
