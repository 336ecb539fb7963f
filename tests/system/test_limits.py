"""Documented work limits take effect where they are changed (issue 26).

symhx caps long work with documented module constants (``MAX_*``, ``*_LIMIT``) that a user with
the memory or the time raises *in the module that owns it*.  Two checks:

* the conformance table: every limit constant of the package, lowered in its owner module,
  makes each function that checks it -- in every module that reads it, the CLI too -- refuse an
  input just above the lowered value (an input far below the default, so only the lowered value
  can refuse it), naming the constant by its owner (``symhx.site_weights.BALL_TABLE_N_LIMIT``);
* a static check over ``symhx/`` (``ast``, nothing imported): no module binds another module's
  limit constant by ``from ... import`` and reads it in a function (that reads the copy taken at
  import, so a changed limit never reaches it), and no value is computed from a limit when a
  module is imported (a default argument, a module or class constant): such copies are caught
  when they are written.

Every constant is either in the table or listed in :data:`NOT_REFUSALS` with the reason it
refuses nothing (a precision cap that ends in :class:`symhx.certify.UndecidedError`, a switch
between two exact methods, a display width); the table and that list must cover the package.
"""

from __future__ import annotations

import ast
import importlib
import re
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from pathlib import Path
from typing import Any

import mpmath
import pytest

import symhx
from symhx.certify import UndecidedError
from symhx.cli import main
from symhx.validation import InputError

ROOT = Path(__file__).resolve().parents[2]
PKG = ROOT / "symhx"

#: a limit constant: an UPPER_CASE module-level name with the word MAX or LIMIT in it
LIMIT_NAME = re.compile(r"^[A-Z][A-Z0-9]*(?:_[A-Z0-9]+)*$")
LIMIT_WORD = re.compile(r"(?:^|_)(?:MAX|LIMIT)(?:_|$)")


def is_limit_name(name: str) -> bool:
    return bool(LIMIT_NAME.match(name) and LIMIT_WORD.search(name))


# =========================================================================== the package's limits
def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


@cache
def _sources() -> dict[str, tuple[Path, ast.Module]]:
    return {_module_name(p): (p, ast.parse(p.read_text(), filename=str(p)))
            for p in sorted(PKG.rglob("*.py")) if "_build" not in p.parts}


def _assigned_names(tree: ast.Module) -> set[str]:
    out: set[str] = set()
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else \
            [node.target] if isinstance(node, ast.AnnAssign) and node.value is not None else []
        out |= {t.id for t in targets if isinstance(t, ast.Name)}
    return out


@cache
def package_limits() -> frozenset[tuple[str, str]]:
    """(owner module, name) of every limit constant the package assigns at module level."""
    return frozenset((mod, name) for mod, (_, tree) in _sources().items()
                     for name in _assigned_names(tree) if is_limit_name(name))


# =========================================================================== the conformance table
@dataclass(frozen=True)
class Case:
    """Lowering ``owner.name`` to ``lowered`` makes ``call`` (in ``consumer``) refuse."""

    owner: str
    name: str
    consumer: str
    lowered: Any
    call: Callable[[], Any]
    exc: type[BaseException] = InputError
    #: more (module, name, value) to set first: reaches a fallback that is otherwise rare
    also: tuple[tuple[str, str, Any], ...] = ()

    @property
    def id(self) -> str:
        return f"{self.owner}.{self.name}@{self.consumer}"


@dataclass(frozen=True)
class CliCase:
    """Lowering ``owner.name`` to ``lowered`` makes ``symhx *argv`` exit 2 naming it."""

    owner: str
    name: str
    consumer: str
    lowered: Any
    argv: tuple[str, ...]
    #: the option the refusal names (the command's own check, not the API's behind it)
    option: str | None = None

    @property
    def id(self) -> str:
        return f"{self.owner}.{self.name}@cli:{' '.join(self.argv)}"


def _api(name: str) -> Callable[..., Any]:
    """A function of the package by its dotted public address, looked up at the call."""
    mod, _, attr = name.rpartition(".")
    return getattr(importlib.import_module(mod), attr)


def _row() -> Any:
    return symhx.PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[0.0])


def _sites(*values: Any) -> Any:
    return symhx.SiteClasses((2,) * len(values), values)


def _small_site_hits() -> Any:
    return _api("symhx.impact.sites.site_hit_tables")([0.3], 3, n=6, t_transient=10,
                                                      t_window=10, seed=1)


V, C, D = "symhx.validation", "symhx.circuits", "symhx.distribution"
SW, SP, F, IM = "symhx.site_weights", "symhx.spaces", "symhx.forcing", "symhx.impact"

CASES: tuple[Case, ...] = (
    # --- the conversion layer (every module converts through it)
    Case(V, "MAX_DPS", V, 10, lambda: symhx.mean(101, "1/50", dps=11)),
    Case(V, "MAX_DECIMAL_EXPONENT", V, 10, lambda: symhx.mean(101, "1e-11")),
    Case(V, "MAX_DECIMAL_EXPONENT", V, 10, lambda: symhx.mean("10**11", "1/50")),
    Case(V, "MAX_BINARY_EXPONENT", V, 100, lambda: symhx.mean(101, mpmath.mpf(2) ** -200)),
    Case(V, "MAX_SAMPLE_SIZE", D, 5, lambda: symhx.rvs(101, 0.02, size=6, random_state=1)),
    Case(V, "MAX_SAMPLE_SIZE", f"{F}.rayleigh", 5,
         lambda: symhx.RayleighSum([1, 2]).rvs(6, random_state=1)),
    # --- circuit counts
    Case(C, "MAX_TOTAL_N", C, 10, lambda: _api(f"{C}.total_simple_circuits")(11)),
    Case(C, "MAX_CIRCUIT_LENGTH", C, 3, lambda: symhx.circuit_count(5, (2, 2))),
    Case(C, "MAX_COUNT_BITS", C, 10, lambda: symhx.phi(1000, 2)),
    Case(C, "MAX_COUNT_BITS", f"{SP}._classes", 10, lambda: symhx.class_count(1000, (2, 2), 4)),
    Case(C, "MAX_PATTERN_LENGTH", C, 3, lambda: _api(f"{C}.circuits_of_length")(5, 4)),
    Case(C, "MAX_ENUMERATION_LENGTH", C, 3, lambda: list(_api(f"{C}.enumerate_circuits")(2, 4))),
    Case(C, "MAX_ENUMERATION", C, 10, lambda: list(_api(f"{C}.enumerate_circuits")(2, 4))),
    # --- the simple distribution and the base class every distribution shares
    Case(D, "EXACT_N_LIMIT", f"{SP}._dist", 10,
         lambda: symhx.distribution_of(11, "1/50", space="eq41")),
    Case(D, "EXACT_WORK_LIMIT", f"{SP}._dist", 10, lambda: symhx.mean(11, "1/50", space="eq41")),
    Case(D, "EXACT_QUANTILE_WORK_LIMIT", D, 10,
         lambda: symhx.median(11, "1/50", space="eq41")),
    Case(D, "FLOAT_N_LIMIT", D, 10, lambda: symhx.rvs(11, 0.02, size=1, random_state=1)),
    Case(D, "MAX_TABLE_N", D, 10, lambda: symhx.distribution_of(11, 0.02, dps=15).table()),
    Case(D, "MAX_EXACT_TABLE_N", D, 10, lambda: symhx.distribution_of(11, "1/50").table()),
    Case(D, "MP_SUM_N_LIMIT", D, 10, lambda: symhx.mean(11, 0.02, dps=15)),
    Case(D, "MP_QUANTILE_N_LIMIT", D, 10, lambda: symhx.median(11, 0.02, dps=15)),
    # --- critical point, asymptotics
    Case("symhx.critical", "MAX_BREAKPOINTS", "symhx.critical", 2,
         lambda: symhx.mode_path(101)),
    Case("symhx.asymptotics", "MAX_FORMULA_DIGITS", "symhx.asymptotics", 5,
         lambda: symhx.asymptotic_critical_point(10**5, order="next")),
    Case("symhx.asymptotics", "MAX_RELAXED_DIGITS", "symhx.asymptotics", 5,
         lambda: symhx.asymptotic_critical_point(10**5, order="best")),
    Case("symhx.asymptotics", "MAX_PD_TERMS", "symhx.asymptotics", 3,
         lambda: symhx.pd_series(10**6, n_terms=4)),
    # --- site classes
    Case("symhx.sites", "MAX_SITE_SEQUENCE", "symhx.sites", 5,
         lambda: symhx.distribution_of(6, [0.1, 0.1, 0.1, 0.2, 0.2, 0.2])),
    Case(SW, "SITE_PATTERN_LIMIT", SW, 1,
         lambda: symhx.distribution_of(4, _sites("1/2", "1/3"), space="eq41")),
    Case(SW, "EXACT_TABLE_BITS_LIMIT", SW, 10,
         lambda: _api(f"{SW}.exact_weights")(_sites("1/2", "1/3"))),
    Case(SW, "EXACT_TABLE_BITS_LIMIT", "symhx.site_distribution", 10,
         lambda: symhx.distribution_of(4, _sites("1/2", "1/3"))),
    # a tie of c_k that the balls leave open goes to the exact table: beyond the lowered limit
    # it is undecided (TABLE_MAX_BITS below the first ball's 64 bits skips the balls)
    Case(SW, "EXACT_TABLE_BITS_LIMIT", "symhx.critical_sites", 10,
         lambda: symhx.critical_point(4, weights=[1, 1, 2, 2]), exc=UndecidedError,
         also=(("symhx.critical_sites", "TABLE_MAX_BITS", 32),)),
    Case(SW, "BALL_TABLE_N_LIMIT", SW, 3,
         lambda: _api(f"{SW}.ball_weights")(_sites(0.5, 0.25))),
    Case(SW, "BALL_TABLE_N_LIMIT", "symhx.site_distribution", 3,
         lambda: symhx.distribution_of(4, _sites(0.5, 0.25), dps=15)),
    Case(SW, "BALL_TABLE_N_LIMIT", "symhx.critical_sites", 3,
         lambda: symhx.critical_point(4, weights=[1, 1, 2, 2])),
    # --- higher-order spaces
    Case(f"{SP}._classes", "MAX_EXCESS", f"{SP}._classes", 3,
         lambda: symhx.parse_space("excess<=4")),
    Case(f"{SP}._classes", "MAX_EXCESS", f"{SP}.study", 3,
         lambda: symhx.convergence_study(20, ms=[4], ps=["0.05"], extra=())),
    Case(f"{SP}._classes", "MAX_EXCESS", f"{SP}.study", 3,
         lambda: symhx.convergence_study(20, ms=range(0, 5), ps=["0.05"], extra=())),
    Case(f"{SP}._classes", "MAX_SPACE_WORK", f"{SP}._classes", 100,
         lambda: symhx.critical_point(30, space="eq41")),
    Case(f"{SP}.study", "STUDY_N_LIMIT", f"{SP}.study", 10,
         lambda: symhx.convergence_study(11, ms=[0], ps=["0.05"], extra=())),
    Case(f"{SP}._dist", "DIRECT_LIMIT", f"{SP}._dist", 10,
         lambda: symhx.class_decomposition(11, 0.02, space="eq41")),
    # --- forcing
    Case(f"{F}.arguments", "MAX_SCALES", f"{F}.arguments", 3,
         lambda: symhx.impact_probability(0.3, Omega=[1.1, 1.2, 1.3])),
    Case(f"{F}.arguments", "MAX_SCALES", f"{F}.rayleigh", 3,
         lambda: symhx.RayleighSum([1, 2, 3, 4])),
    Case(f"{F}.kernels_mp", "MAX_EXPONENT", f"{F}.kernels_mp", 10,
         lambda: symhx.impact_probability(0.05, dps=20)),
    Case(f"{F}.kernels_mp", "MAX_EXPONENT", f"{F}.rayleigh", 10,
         lambda: symhx.RayleighSum([1, 2, 3]).sf(20, dps=15)),
    Case(f"{F}.rayleigh", "MAX_MP_SUM_WORK", f"{F}.rayleigh", 20,
         lambda: symhx.RayleighSum([1, 2, 3]).sf(1, dps=10)),
    Case(f"{F}.theory", "THEORY_MAX_N", f"{F}.theory", 100,
         lambda: symhx.theory_curve(0.3, N=101)),
    # --- the impact engines
    Case(f"{IM}.model", "MAX_PIPES", f"{IM}.model", 3,
         lambda: symhx.ensemble([0.3], 1, n=4, t_transient=1, t_window=1, seed=1)),
    Case(f"{IM}.model", "MAX_HORIZON", f"{IM}.model", 100,
         lambda: symhx.simulate(_row(), Fraction(101), dps=15)),
    # the float64 fast path decides "inside the cap" from the rounded product omega * t_end
    Case(f"{IM}.model", "MAX_HORIZON", f"{IM}.simulate", 100,
         lambda: symhx.simulate(_row(), 101.0)),
    Case(f"{IM}.model", "MAX_EVENTS", f"{IM}.simulate", 10,
         lambda: symhx.simulate(_row(), 1.0, max_events=11)),
    Case(f"{IM}.model", "MAX_SCALE", f"{IM}.model", 10,
         lambda: symhx.PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0],
                               v0=[0.0], d=11)),
    Case(f"{IM}.ensemble", "MAX_RUNS", f"{IM}.ensemble", 3,
         lambda: symhx.ensemble([0.3], 4, n=2, t_transient=1, t_window=1, seed=1)),
    Case(f"{IM}.ensemble", "MAX_RUNS", f"{IM}.sites", 3,
         lambda: _api(f"{IM}.sites.site_hit_tables")([0.3], 4, n=2, t_transient=1,
                                                     t_window=1, seed=1)),
    Case(f"{IM}.ensemble", "MAX_TOTAL_RUNS", f"{IM}.ensemble", 3,
         lambda: symhx.ensemble([0.3, 0.4], 2, n=2, t_transient=1, t_window=1, seed=1)),
    Case(f"{IM}.ensemble", "MAX_TOTAL_RUNS", f"{IM}.sites", 3,
         lambda: _api(f"{IM}.sites.site_hit_tables")([0.3, 0.4], 2, n=2, t_transient=1,
                                                     t_window=1, seed=1)),
    Case(f"{IM}.ensemble", "MAX_GAPS", f"{IM}.ensemble", 3,
         lambda: symhx.free_flight_closure_fraction(0.3, 4, seed=1)),
    Case(f"{IM}.site_theory", "MAX_REPLICATES", f"{IM}.site_theory", 3,
         lambda: _api(f"{IM}.site_theory.compare_site_models")(_small_site_hits(),
                                                               replicates=4)),
)

CS, CC = "symhx.commands.spaces", "symhx.commands.core"
CLI_CASES: tuple[CliCase, ...] = (
    CliCase(f"{SP}._classes", "MAX_EXCESS", CS, 3, ("convergence", "20", "--max-m", "4"),
            option="--max-m"),
    CliCase(f"{SP}._classes", "MAX_SPACE_WORK", CS, 100, ("spaces", "30")),
    CliCase(f"{SP}.study", "STUDY_N_LIMIT", CS, 10, ("convergence", "11")),
    CliCase(CC, "MAX_CIRCUIT_LENGTH", CC, 3, ("circuits", "5", "--length", "4"),
            option="--length"),
    CliCase(CC, "MAX_PHI_TABLE_N", CC, 3, ("circuits", "4")),
    CliCase(V, "MAX_DPS", V, 10, ("critical", "101", "--dps", "11")),
)

#: limit constants that refuse no input, and why
NOT_REFUSALS: dict[tuple[str, str], str] = {
    ("symhx.certify", "MAX_IRRATIONAL_BITS"):
        "precision cap of decisions on irrational input: UndecidedError at the limit, read at "
        "the call (tests/test_certify_irrational.py, tests/test_distribution_irrational_p.py)",
    ("symhx.critical", "EXACT_BITS_LIMIT"):
        "exact comparison after the balls failed to separate: UndecidedError (a true tie)",
    ("symhx.spaces._dist", "EXACT_BITS_LIMIT"):
        "exact comparison after the balls failed to separate: UndecidedError (a true tie)",
    ("symhx.critical_sites", "TABLE_MAX_BITS"):
        "precision of the ball table before the exact table decides (no refusal)",
    ("symhx.site_distribution", "MODES_MAX_BITS"):
        "precision of the ball table before the exact table decides (no refusal)",
    ("symhx.site_weights", "MAX_SMALL_SITES"):
        "chooses the short-sum method of e_k; larger sets of small classes take the table",
    ("symhx.float_sums", "SLOPE_MAX"): "a switch between two float64 summation methods",
    ("symhx.commands._common", "MAX_INT_DIGITS_SHOWN"): "display width of an int in the CLI",
}


def test_every_limit_constant_is_in_the_table_or_refuses_nothing() -> None:
    tabled = {(c.owner, c.name) for c in CASES} | {(c.owner, c.name) for c in CLI_CASES}
    found = set(package_limits())
    assert tabled & set(NOT_REFUSALS) == set()
    assert sorted(found - tabled - set(NOT_REFUSALS)) == [], "limit constants without a case"
    assert sorted((tabled | set(NOT_REFUSALS)) - found) == [], "cases of no constant"


def test_every_consumer_of_a_limit_has_a_case() -> None:
    """Every module that reads a limit of another module (through the owner, at the call) is
    a consumer that the table exercises."""
    readers: set[tuple[str, str, str]] = set()
    limits = package_limits()
    owners = {name: {o for o, n in limits if n == name} for _, name in limits}
    for mod, (_, tree) in _sources().items():
        aliases = _module_aliases(mod, tree)
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and \
                    node.value.id in aliases and (aliases[node.value.id], node.attr) in limits:
                readers.add((aliases[node.value.id], node.attr, mod))
        for fn in ast.walk(tree):   # call-time imports inside a function
            if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for node in ast.walk(fn):
                if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                    readers |= {(node.module, a.name, mod) for a in node.names
                                if node.module in owners.get(a.name, ()) and node.module != mod}
    covered = {(c.owner, c.name, c.consumer) for c in (*CASES, *CLI_CASES)}
    # read for a message only (the refusal is the owner's own check)
    message_only = {("symhx.site_weights", "MAX_SMALL_SITES", "symhx.critical_sites")}
    assert sorted(readers - covered - message_only) == []


def _lower(monkeypatch: pytest.MonkeyPatch, owner: str, name: str, value: Any) -> None:
    mod = importlib.import_module(owner)
    assert isinstance(getattr(mod, name), type(value)) or isinstance(value, int), (owner, name)
    assert value < getattr(mod, name), "lower the limit, never raise it"
    monkeypatch.setattr(mod, name, value)


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_a_lowered_limit_refuses_just_above_it_naming_its_owner(
        case: Case, monkeypatch: pytest.MonkeyPatch) -> None:
    for owner, name, value in case.also:
        _lower(monkeypatch, owner, name, value)
    _lower(monkeypatch, case.owner, case.name, case.lowered)
    with pytest.raises(case.exc) as info:
        case.call()
    assert f"{case.owner}.{case.name}" in str(info.value)


@pytest.mark.parametrize("case", CLI_CASES, ids=[c.id for c in CLI_CASES])
def test_a_lowered_limit_refuses_on_the_command_line(
        case: CliCase, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture) -> None:
    _lower(monkeypatch, case.owner, case.name, case.lowered)
    assert main(list(case.argv)) == 2
    err = capsys.readouterr().err
    assert f"{case.owner}.{case.name}" in err and "Traceback" not in err
    if case.option is not None:
        assert case.option in err


# =========================================================================== the static check
def _resolve(mod: str, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    path, _ = _sources()[mod]
    base = mod.split(".") if path.name == "__init__.py" else mod.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _module_aliases(mod: str, tree: ast.Module) -> dict[str, str]:
    """Local name -> symhx module, for ``import symhx.x as y`` / ``from symhx import x``."""
    mods = _sources()
    out: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.asname and a.name in mods:
                    out[a.asname] = a.name
        elif isinstance(node, ast.ImportFrom):
            src = _resolve(mod, node)
            for a in node.names:
                if f"{src}.{a.name}" in mods:
                    out[a.asname or a.name] = f"{src}.{a.name}"
    return out


def _owner_of(src: str, name: str, seen: frozenset[str] = frozenset()) -> str | None:
    """The module assigning ``name`` that ``from src import name`` reaches (re-exports followed)."""
    sources = _sources()
    if src not in sources or src in seen:
        return None
    _, tree = sources[src]
    if name in _assigned_names(tree):
        return src
    for node in tree.body:
        if isinstance(node, ast.ImportFrom) and any(a.name == name and a.asname is None
                                                    for a in node.names):
            return _owner_of(_resolve(src, node), name, seen | {src})
    return None


def _local_names(fn: ast.AST) -> set[str]:
    """Names a function binds itself (a call-time import, an assignment)."""
    out: set[str] = set()
    for sub in ast.walk(fn):
        if isinstance(sub, (ast.Import, ast.ImportFrom)):
            out |= {a.asname or a.name.split(".")[0] for a in sub.names}
        elif isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Store):
            out.add(sub.id)
    return out


def _function_reads(tree: ast.AST, names: set[str]) -> list[tuple[int, str]]:
    """(line, name) of every load of the module-level ``names`` inside a function or lambda
    body (a name the function binds itself is its own)."""
    out = []
    for fn in ast.walk(tree):
        if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            body = fn.body if isinstance(fn.body, list) else [fn.body]
            outer = names - _local_names(fn)
            for stmt in body:
                for sub in ast.walk(stmt):
                    if isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Load) and \
                            sub.id in outer:
                        out.append((sub.lineno, sub.id))
    return sorted(set(out))


def _import_time_reads(tree: ast.Module, names: set[str],
                       attributes: dict[str, str]) -> list[tuple[int, str]]:
    """(line, name) of loads of ``names`` (or of ``module.NAME`` for ``attributes``: local module
    alias -> module) evaluated when the module is imported: module and class-level statements,
    default arguments, decorators."""
    out: list[tuple[int, str]] = []
    limits = package_limits()

    def loads(node: ast.AST | None) -> None:
        if node is None:
            return
        for sub in ast.walk(node):
            if isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Load) and sub.id in names:
                out.append((sub.lineno, sub.id))
            elif isinstance(sub, ast.Attribute) and isinstance(sub.value, ast.Name) and \
                    sub.value.id in attributes and \
                    (attributes[sub.value.id], sub.attr) in limits:
                out.append((sub.lineno, f"{attributes[sub.value.id]}.{sub.attr}"))

    def visit(body: list[ast.stmt]) -> None:
        for stmt in body:
            if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef)):
                for d in (*stmt.args.defaults, *stmt.args.kw_defaults, *stmt.decorator_list):
                    loads(d)
            elif isinstance(stmt, ast.ClassDef):
                for d in stmt.decorator_list:
                    loads(d)
                visit(stmt.body)
            elif isinstance(stmt, (ast.If, ast.Try)):
                loads(getattr(stmt, "test", None))
                visit(stmt.body)
                visit(stmt.orelse)
            elif not isinstance(stmt, (ast.Import, ast.ImportFrom, ast.Expr)):
                loads(stmt)
    visit(tree.body)
    return sorted(set(out))


def limit_copies(mod: str, tree: ast.Module) -> list[str]:
    """Where module ``mod`` reads a copy of a limit constant instead of its owner's value."""
    limits = package_limits()
    own = {name for owner, name in limits if owner == mod}
    imported: dict[str, str] = {}   # local name -> owner.name, bound at import
    for node in tree.body:
        if isinstance(node, ast.ImportFrom):
            src = _resolve(mod, node)
            for a in node.names:
                owner = _owner_of(src, a.name)
                if owner is not None and owner != mod and (owner, a.name) in limits:
                    imported[a.asname or a.name] = f"{owner}.{a.name}"
    bad = [f"{mod}:{line} reads {imported[n]} as imported (read it from its owner when "
           f"called)" for line, n in _function_reads(tree, set(imported))]
    bad += [f"{mod}:{line} computes a value from {n} at import (compute it when called)"
            for line, n in _import_time_reads(tree, own | set(imported),
                                              _module_aliases(mod, tree))]
    return bad


def test_the_copy_finder_finds_copies() -> None:
    sources = _sources()
    code = ("from symhx.site_weights import BALL_TABLE_N_LIMIT, SIMPLE\n"
            "from symhx import site_weights as _sw\n"
            "CAP = BALL_TABLE_N_LIMIT // 2\n"
            "def f(N):\n    return N > BALL_TABLE_N_LIMIT\n"
            "def g(N):\n    return N > _sw.BALL_TABLE_N_LIMIT\n"
            "def h(N, cap=_sw.BALL_TABLE_N_LIMIT):\n    return N > cap\n"
            "def k(N):\n    from symhx.site_weights import BALL_TABLE_N_LIMIT\n"
            "    return N > BALL_TABLE_N_LIMIT\n")
    assert "symhx.site_distribution" in sources
    found = limit_copies("symhx.site_distribution", ast.parse(code))
    assert [line.split(" ")[0] for line in found] == ["symhx.site_distribution:5",
                                                       "symhx.site_distribution:3",
                                                       "symhx.site_distribution:8"]
    # the owner's own default argument and derived constant are copies too
    own = ("MAX_RUNS = 10\nHALF = MAX_RUNS // 2\n"
           "def run(n, cap=MAX_RUNS):\n    return n <= cap\n")
    found = limit_copies("symhx.impact.ensemble", ast.parse(own))
    assert [line.split(" ")[0] for line in found] == ["symhx.impact.ensemble:2",
                                                       "symhx.impact.ensemble:3"]
    # a re-export is followed to the owner
    assert _owner_of("symhx.spaces", "MAX_EXCESS") == "symhx.spaces._classes"


def test_no_module_reads_a_copy_of_a_limit() -> None:
    bad = [b for mod, (_, tree) in _sources().items() for b in limit_copies(mod, tree)]
    assert bad == [], "\n".join(bad)
