"""CLI: ``symhx critical``, ``symhx distribution``, ``symhx circuits``, ``symhx mode-path`` and the
core part of ``symhx paper`` (which also drives every other section, see :func:`cmd_paper`)."""

from __future__ import annotations

import argparse
import json
import sys
import time
from fractions import Fraction
from pathlib import Path
from typing import Any

from symhx._mpctx import export, mp
from symhx.commands._common import (
    N_HELP,
    P_HELP,
    SITES_HELP,
    add_dps,
    add_json,
    dump_json,
    int_arg,
    int_show,
    mpstr,
    rational_arg,
    sites_arg,
    sites_for,
    sites_json,
    sites_show,
    write_csv,
)
from symhx.validation import DEFAULT_DPS, DEFAULT_SPACE, InputError

ORDER = 10

#: the paper's row: 100 pipes -> N = 101 possible impacts
PAPER_N = 101
TABLE_NS = (2, 3, 4, 5, 6, 7, 8, 10, 20, 50, 100, 101, 1000, 10**4, 10**6, 10**10, 10**30,
            10**100)
#: ``circuits --length L`` lists one row per partition of L: refused above this (a work limit;
#: p(40) = 37338 rows)
MAX_CIRCUIT_LENGTH = 40
#: ``circuits N`` (the table of phi_N(k), k = 1..N) is refused above this N
MAX_PHI_TABLE_N = 2000

def register(sub: Any) -> None:
    c = sub.add_parser("critical", help="critical point p_c, the jump of the mode and p_d "
                       "(eq. 16) for N vertices",
                       description="The critical probability p_c where the mode of X jumps "
                       "from 1, and the discriminant root p_d (eq. 16). Both are also shown "
                       "as N p - 1, which separates them when N is huge.")
    c.add_argument("N", type=int_arg("N", minimum=2), help=N_HELP)
    c.add_argument("--sites", type=sites_arg, default=None,
                   help="the critical point t_c along the direction p_v = t w_v of per-class "
                   "weights: size:weight pairs, e.g. wall=2:1/2,pipe=99:1 (sizes add up to N; "
                   "one size may be 'rest': wall=2:1/2,pipe=rest:1)")
    add_dps(c)
    add_json(c)
    c.set_defaults(func=cmd_critical)

    d = sub.add_parser("distribution", help="distribution of X: mean, variance, modes, pmf",
                       description="The distribution of X, the number of distinct impacts "
                       "(eq. 7), exactly (rational p) or with mpmath (--float).")
    d.add_argument("N", type=int_arg("N", minimum=1),
                   help=N_HELP + "; N >= 1 as in the API (N = 1: X = 1 with certainty)")
    d.add_argument("p", type=rational_arg("p"), nargs="?", default=None,
                   help=P_HELP + "; or --sites")
    d.add_argument("--sites", type=sites_arg, default=None, help=SITES_HELP)
    add_dps(d, help_text="significant digits shown (and of the mpmath values with --float)")
    d.add_argument("--space", default=DEFAULT_SPACE,
                   help="sample space: simple, eq41, eq41-printed or excess<=m")
    d.add_argument("--float", action="store_true",
                   help="evaluate with mpmath at --dps instead of exactly")
    d.add_argument("--table", action="store_true",
                   help="include P(X=k) for every k (N <= 10000; exact p: N <= 2000; "
                        "symhx.distribution.MAX_TABLE_N, MAX_EXACT_TABLE_N)")
    add_json(d)
    d.set_defaults(func=cmd_distribution)

    k = sub.add_parser("circuits", help="circuit counts: simple phi_N(k) or any visit pattern",
                       description="Without options: the table of phi_N(k), the number of "
                       f"simple circuits through k of N vertices (N <= {MAX_PHI_TABLE_N}).")
    k.add_argument("N", type=int_arg("N", minimum=1), help=N_HELP)
    k.add_argument("--visits", help="visit pattern, e.g. 2,1,1 (one vertex twice, two once)")
    k.add_argument("--length", type=int_arg("--length", minimum=1, maximum=MAX_CIRCUIT_LENGTH,
                                            limit="symhx.commands.core.MAX_CIRCUIT_LENGTH"),
                   help=f"all visit patterns of this length (at most {MAX_CIRCUIT_LENGTH})")
    add_json(k)
    k.set_defaults(func=cmd_circuits)

    m = sub.add_parser("mode-path", help="exact breakpoints of the mode k*(p)",
                       description="The mode k*(p) of X as an exact step function of p on "
                       "(0, p_max]: every breakpoint where it changes.")
    m.add_argument("N", type=int_arg("N", minimum=2), help=N_HELP)
    m.add_argument("--p-max", type=rational_arg("--p-max"), default=Fraction(1),
                   help="largest p of the path (exact rational)")
    add_dps(m, help_text="significant digits of breakpoints that are not rational")
    add_json(m)
    m.set_defaults(func=cmd_mode_path)

    paper = sub.add_parser("paper", help="recompute the paper's numbers and figures (main job)",
                           description="Recompute the paper's numbers, tables and figures into "
                           "a folder: JSON at full precision, CSV with 17-digit floats, PNG "
                           "figures, and summary.json.")
    paper.add_argument("--out", type=Path, default=Path("symhx-paper"), help="output folder")
    paper.add_argument("--full", action="store_true",
                       help="also run the long simulation ensembles and the slower figures")
    paper.set_defaults(func=cmd_paper)


def pipes_show(N: int) -> str:
    """``N - 1`` (the number of pipes) for text output; ``N - 1`` literally when N is huge."""
    return int_show(N - 1) if N < 10**17 else "N - 1"


def cmd_critical(args: argparse.Namespace) -> int:
    from symhx.critical import critical_point, discriminant_root_q

    if args.sites is not None:
        return _critical_sites(args)
    cp = critical_point(args.N, dps=args.dps)
    q_d = discriminant_root_q(args.N, dps=args.dps)
    if args.json:
        print(dump_json({**cp.as_dict(), "N_p_d_minus_1": q_d}, args.dps))
        return 0
    dps = args.dps
    pc = mpstr(cp.p_exact, dps) if cp.p_exact is not None else mpstr(cp.p, dps)
    print(f"N = {int_show(cp.N)} vertices ({pipes_show(cp.N)} pipes), {dps} significant digits")
    print(f"p_d  (eq. 16)       = {mpstr(cp.p_d, dps)}")
    print(f"N p_d - 1           = {mpstr(q_d, dps)}")
    print(f"p_c  (mode jumps)   = {pc}")
    print(f"N p_c - 1           = {mpstr(cp.q, dps)}")
    argmins = ", ".join(int_show(a) for a in cp.argmins)
    print(f"jump of the mode    : {cp.k_before} -> {int_show(cp.k_after)}   "
          f"(argmin of c_k: {argmins})")
    return 0


def _critical_sites(args: argparse.Namespace) -> int:
    """``symhx critical N --sites ...``: the critical point along the direction of the classes."""
    from symhx.api import critical_point

    sites = sites_for(args.sites, args.N)
    cp = critical_point(args.N, weights=sites, dps=args.dps)
    if args.json:
        print(dump_json(cp.as_dict(), args.dps))
        return 0
    print(f"N = {int_show(cp.N)} vertices ({pipes_show(cp.N)} pipes), direction --sites "
          f"{sites_show(sites)}: p_v = t w_v")
    print(str(cp))
    return 0


def p_or_sites(args: argparse.Namespace) -> tuple[Any, Any]:
    """``(p, sites)`` of a command taking ``p`` or ``--sites`` (exactly one of them); with
    ``--float`` as mpf of ``--dps`` + 10 digits."""
    if args.sites is not None and args.p is not None:
        raise InputError(f"give either p or --sites, not both (got p = {args.p} and --sites "
                         f"{args.sites})")
    if args.sites is not None:
        sites = sites_for(args.sites, args.N)
        return (sites_for(sites, args.N, args.dps) if args.float else sites), sites
    if args.p is None:
        raise InputError("p is missing: give an impact probability p (e.g. 0.02) or --sites "
                         "size:probability pairs (e.g. 2:0.01,99:0.02)")
    p: Any = args.p
    if args.float:
        ctx = mp()
        with ctx.workdps(args.dps + 10):
            p = export(ctx.mpf(p.numerator) / p.denominator)
    return p, None


def cmd_distribution(args: argparse.Namespace) -> int:
    from symhx.api import distribution_of

    p, sites = p_or_sites(args)
    d = distribution_of(args.N, p, space=args.space, dps=args.dps)
    rows = None
    if args.table:  # first: a refused table costs nothing
        try:
            rows = d.table()
        except InputError as e:
            raise InputError(f"--table: {e}", cli=f"--table: {e.cli or e}") from None
    out: dict[str, Any] = {"N": args.N, "p": args.p, "space": args.space, "exact": d.exact,
                           "mean": d.mean(), "variance": d.var(), "modes": list(d.modes()),
                           "mode": d.mode(), "log_normaliser": d.log_normaliser}
    if sites is not None:
        out["sites"] = sites_json(sites)
    if rows is not None:
        out["pmf"] = dict(rows)
    if args.json:
        print(dump_json(out, args.dps))
        return 0
    how = "exact rational arithmetic" if d.exact else f"mpmath, {args.dps} significant digits"
    given = f"sites {sites_show(sites)}" if sites is not None \
        else f"p = {mpstr(args.p, args.dps)}"
    print(f"distribution of X for N = {int_show(args.N)}, {given} ({args.space} circuits; {how})")
    for key in ("mean", "variance", "mode", "modes", "log_normaliser"):
        val = out[key]
        shown = ", ".join(int_show(v) for v in val) if isinstance(val, list) \
            else mpstr(val, args.dps)
        print(f"  {key:15s} = {shown}")
    if args.table:
        digits = min(args.dps, 20)
        print(f"  {'k':>8s}  P(X=k)")
        for k, v in out["pmf"].items():
            print(f"  {k:8d}  {mpstr(v, digits)}")
    return 0


def cmd_circuits(args: argparse.Namespace) -> int:
    from symhx import circuits as C

    if args.visits is not None:
        try:
            visits = tuple(int(v) for v in args.visits.split(","))
        except ValueError:
            raise InputError(f"--visits must be comma-separated positive integers such as "
                             f"2,1,1, got {args.visits!r}") from None
        count = C.circuit_count(args.N, visits)
        if args.json:
            print(dump_json({"N": args.N, "visits": list(visits), "length": sum(visits),
                             "distinct": len(visits), "count": count}))
        else:
            print(f"circuits on N = {int_show(args.N)} vertices with visit pattern "
                  f"{','.join(map(str, visits))} (length {sum(visits)}, {len(visits)} "
                  f"distinct vertices): {int_show(count)}")
        return 0
    if args.length:
        rows = C.circuits_of_length(args.N, args.length)
        total = C.necklace_count(args.N, args.length)
        if args.json:
            print(dump_json({"N": args.N, "length": args.length,
                             "by_pattern": {",".join(map(str, v)): c for v, c in rows.items()},
                             "total": total}))
            return 0
        print(f"circuits of length {args.length} on N = {int_show(args.N)} vertices")
        print(f"  {'visit pattern':<30s} count")
        for v, c in rows.items():
            print(f"  {','.join(map(str, v)):<30s} {int_show(c)}")
        print(f"  {'total':<30s} {int_show(total)}")
        return 0
    if args.N > MAX_PHI_TABLE_N:
        raise InputError(f"the table of phi_N(k) is for N <= {MAX_PHI_TABLE_N} (the work limit "
                         f"symhx.commands.core.MAX_PHI_TABLE_N; got N = {int_show(args.N)}); use "
                         f"--visits 1,1,... for one k")
    phi = {k: C.phi(args.N, k) for k in range(1, args.N + 1)}
    total = C.total_simple_circuits(args.N)
    if args.json:
        print(dump_json({"N": args.N, "phi": phi, "total": total}))
        return 0
    print(f"simple circuits through k of N = {args.N} vertices")
    print(f"  {'k':>6s}  phi_N(k)")
    for kk, count in phi.items():
        print(f"  {kk:6d}  {int_show(count)}")
    print(f"  {'total':>6s}  {int_show(total)}")
    return 0


def cmd_mode_path(args: argparse.Namespace) -> int:
    from symhx.critical import mode_path

    path = mode_path(args.N, p_max=args.p_max, dps=args.dps)
    rows = path.as_rows()
    if args.json:
        print(dump_json({"N": args.N, "p_max": args.p_max, "breakpoints": rows}, args.dps))
        return 0
    print(f"mode k*(p) of X for N = {int_show(args.N)} on (0, {mpstr(args.p_max, 17)}]: "
          f"{len(rows)} breakpoints (k* = 1 up to the first)")
    print(f"  {'k* left':>9s} {'k* right':>9s}  breakpoint p")
    for r in rows:
        print(f"  {int_show(r['k_left']):>9s} {int_show(r['k_right']):>9s}  "
              f"{mpstr(r['p'], args.dps)}")
    return 0


# --------------------------------------------------------------------------- paper
def paper(out: Path, full: bool) -> list[str]:
    """Core numbers: p_d, p_c, the jump and the mode path for N = 101; a table over N;
    figures 1-6. JSON files at full precision, CSV files with 17-digit floats."""
    from symhx.critical import critical_point, discriminant_root_q, mode_path

    dps = DEFAULT_DPS
    cp = critical_point(PAPER_N, dps=dps)
    path = mode_path(PAPER_N, dps=dps)
    (out / "critical_N101.json").write_text(dump_json(cp.as_dict()) + "\n")
    rows_path = path.as_rows()
    (out / "mode_path_N101.json").write_text(dump_json(rows_path) + "\n")
    write_csv(out / "mode_path_N101.csv", ["p", "k_left", "k_right"],
              [[r["p"], r["k_left"], r["k_right"]] for r in rows_path])
    rows = []
    for N in TABLE_NS:
        row = critical_point(N, dps=dps).as_dict()
        row["N_p_d_minus_1"] = discriminant_root_q(N, dps=dps)
        rows.append(row)
    (out / "critical_table.json").write_text(dump_json(rows) + "\n")
    write_csv(out / "critical_table.csv",
              ["N", "p_d", "N_p_d_minus_1", "p_c", "N_p_c_minus_1", "k_after"],
              [[r["N"], r["p_d"], r["N_p_d_minus_1"], r["p_c"], r["N_p_c_minus_1"],
                r["k_after"]] for r in rows])
    import matplotlib

    matplotlib.use("Agg")
    from symhx.plots.paper import save_paper_figure

    for number, name in ((1, "fig1_pipe_row.png"), (2, "fig2_impact_graph.png"),
                         (3, "fig3_circuit_counts.png"), (4, "fig4_distributions.png"),
                         (5, "fig5_mode_path.png"), (6, "fig6_f_and_phi.png")):
        save_paper_figure(number, out / name)
    big = critical_point(10**100, dps=dps)
    big_qd = discriminant_root_q(10**100, dps=dps)
    return [
        f"N = {PAPER_N} ({PAPER_N - 1} pipes): p_d = {mpstr(cp.p_d, 20)}, "
        f"p_c = {mpstr(cp.p, 20)}, mode jumps 1 -> {cp.k_after}",
        f"mode path: {len(path.breakpoints)} exact breakpoints in (0, 1]",
        f"N = 10**100: N p_d - 1 = {mpstr(big_qd, 20)}, N p_c - 1 = {mpstr(big.q, 20)}, "
        f"jump to k = {int_show(big.k_after)}",
    ]


#: sections started first when ``symhx paper`` runs them side by side (the longest ones)
PAPER_LONG_SECTIONS = ("derive", "spaces")


def _paper_section(module: str, out: Path, full: bool) -> tuple[list[str], float, bool]:
    """Run one module's ``paper`` section: (summary lines, seconds, failed). Runs in a worker
    process of :func:`cmd_paper`; an exception is reported in the lines, never raised."""
    import importlib

    t0 = time.perf_counter()
    try:
        lines = list(importlib.import_module(module).paper(out, full))
        failed = False
    except Exception as exc:  # report and keep going; exit non-zero at the end
        failed = True
        lines = [f"FAILED: {type(exc).__name__}: {' '.join(str(exc).split())}"]
    return lines, time.perf_counter() - t0, failed


def cmd_paper(args: argparse.Namespace) -> int:
    """Run every command module's ``paper`` section, two at a time in worker processes (the
    longest first); a failing section is reported and the others still run (exit code 1 at the
    end). Progress: a tqdm bar on stderr when it is a terminal (silent otherwise); each section's
    summary and its time (once) on stdout, in the modules' order."""
    import os
    from concurrent.futures import ProcessPoolExecutor

    from tqdm import tqdm

    from symhx.commands import command_modules

    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    probe = out / ".symhx-write-test"
    probe.write_text("")  # an unwritable folder fails here, before minutes of work
    probe.unlink()
    sections = [(m.__name__.rsplit(".", 1)[-1], m.__name__) for m in command_modules()
                if hasattr(m, "paper")]
    summary: dict[str, list[str]] = {}
    failed = []
    t_all = time.perf_counter()
    bar = tqdm(total=len(sections), desc="symhx paper", unit="section", file=sys.stderr,
               disable=None, leave=False)
    start_order = sorted(sections, key=lambda s: s[0] not in PAPER_LONG_SECTIONS)
    with ProcessPoolExecutor(max_workers=max(1, min(2, os.cpu_count() or 1))) as pool:
        futures = {name: pool.submit(_paper_section, module, out, args.full)
                   for name, module in start_order}
        for fut in futures.values():
            fut.add_done_callback(lambda _f: bar.update())
        for name, _ in sections:  # report in the modules' order
            lines, dt, bad = futures[name].result()
            if bad:
                failed.append(name)
            summary[name] = [*lines, f"time: {dt:.1f} s"]
            tqdm.write(f"[symhx paper] {name} ({dt:.1f} s)", file=sys.stdout)
            for line in lines:
                tqdm.write(f"    {line}", file=sys.stdout)
            sys.stdout.flush()
    bar.close()
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(f"[symhx paper] {len(sections) - len(failed)}/{len(sections)} sections in "
          f"{time.perf_counter() - t_all:.1f} s; results in {out.resolve()}")
    if failed:
        print(f"symhx paper: error: section(s) failed: {', '.join(failed)}", file=sys.stderr)
    return 1 if failed else 0
