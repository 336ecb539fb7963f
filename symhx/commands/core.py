"""CLI: ``symhx critical``, ``symhx distribution``, ``symhx circuits``, ``symhx mode-path`` and the
core part of ``symhx paper``."""

from __future__ import annotations

import argparse
import csv
import json
import time
from fractions import Fraction
from pathlib import Path
from typing import Any

import mpmath

from symhx.commands._common import dump_json, jsonable, mpstr

ORDER = 10

#: the paper's row: 100 pipes -> N = 101 possible impacts
PAPER_N = 101
TABLE_NS = (2, 3, 4, 5, 6, 7, 8, 10, 20, 50, 100, 101, 1000, 10**4, 10**6, 10**10, 10**30,
            10**100)


def parse_int(text: str) -> int:
    """Integers like ``101``, ``10**100``, ``1e100`` (exactly, no float rounding)."""
    t = text.replace("_", "").strip()
    if "**" in t:
        b, e = t.split("**")
        return int(b) ** int(e)
    if "e" in t.lower():
        m, e = t.lower().split("e")
        if "." not in m:
            return int(m) * 10 ** int(e)
    return int(t)


def parse_p(text: str) -> Any:
    """``1/50`` -> Fraction (exact); ``0.02`` -> Fraction of the decimal (exact); keep it exact."""
    t = text.strip()
    return Fraction(t)


def register(sub: Any) -> None:
    c = sub.add_parser("critical", help="critical point p_c, jump and p_d (eq. 16) for N")
    c.add_argument("N", type=parse_int, help="number of vertices N = pipes + 1 (e.g. 101, 1e100)")
    c.add_argument("--dps", type=int, default=30, help="significant digits (default 30)")
    c.add_argument("--json", action="store_true", help="JSON output")
    c.set_defaults(func=cmd_critical)

    d = sub.add_parser("distribution", help="distribution of X: mean, variance, modes, pmf")
    d.add_argument("N", type=parse_int)
    d.add_argument("p", type=parse_p, help="impact probability, e.g. 0.02 or 1/50 (exact)")
    d.add_argument("--dps", type=int, default=30)
    d.add_argument("--space", default="simple", help="sample space (default simple)")
    d.add_argument("--float", action="store_true",
                   help="evaluate with mpmath at --dps instead of exactly")
    d.add_argument("--table", action="store_true", help="include P(X=k) for every k")
    d.add_argument("--json", action="store_true")
    d.set_defaults(func=cmd_distribution)

    k = sub.add_parser("circuits", help="circuit counts: simple phi_N(k) or any visit pattern")
    k.add_argument("N", type=parse_int)
    k.add_argument("--visits", help="visit pattern, e.g. 2,1,1 (one vertex twice, two once)")
    k.add_argument("--length", type=int, help="all visit patterns of this length")
    k.add_argument("--json", action="store_true")
    k.set_defaults(func=cmd_circuits)

    m = sub.add_parser("mode-path", help="exact breakpoints of the mode k*(p)")
    m.add_argument("N", type=parse_int)
    m.add_argument("--p-max", type=parse_p, default=Fraction(1))
    m.add_argument("--dps", type=int, default=30)
    m.add_argument("--json", action="store_true")
    m.set_defaults(func=cmd_mode_path)

    paper = sub.add_parser("paper", help="recompute the paper's numbers and figures (main job)")
    paper.add_argument("--out", type=Path, default=Path("symhx-paper"),
                       help="output folder (default ./symhx-paper)")
    paper.add_argument("--full", action="store_true",
                       help="also run the long simulation ensembles (figures 7, 8)")
    paper.set_defaults(func=cmd_paper)


def critical_summary(N: int, dps: int) -> dict[str, Any]:
    from symhx.critical import critical_point

    cp = critical_point(N, dps=dps)
    return cp.as_dict()


def cmd_critical(args: argparse.Namespace) -> int:
    from symhx.critical import critical_point

    cp = critical_point(args.N, dps=args.dps)
    if args.json:
        print(dump_json(cp.as_dict()))
        return 0
    print(f"N = {cp.N}  ({cp.N - 1} pipes)")
    print(f"p_d (eq. 16)     = {mpstr(cp.p_d, args.dps)}")
    print(f"p_c              = {mpstr(cp.p_exact or cp.p, args.dps)}")
    print(f"N p_c - 1        = {mpstr(cp.q, args.dps)}")
    print(f"jump of the mode : {cp.k_before} -> {cp.k_after}   (argmins of c_k: {cp.argmins})")
    return 0


def cmd_distribution(args: argparse.Namespace) -> int:
    from symhx.distribution import distribution_of

    p = args.p
    if args.float:
        with mpmath.workdps(args.dps + 10):
            p = mpmath.mpf(p.numerator) / p.denominator
    d = distribution_of(args.N, p, space=args.space, dps=args.dps)
    out: dict[str, Any] = {"N": args.N, "p": args.p, "space": args.space, "exact": d.exact,
                           "mean": d.mean, "variance": d.variance, "modes": list(d.modes),
                           "mode": d.mode, "log_normaliser": d.log_normaliser}
    if args.table:
        out["pmf"] = {k: d.pmf(k) for k in d.support}
    if args.json:
        print(dump_json(out))
        return 0
    for key in ("N", "p", "space", "mean", "variance", "mode", "modes", "log_normaliser"):
        val = out[key]
        shown = mpstr(val, args.dps) if not isinstance(val, (list, str)) else val
        print(f"{key:15s} = {shown}")
    if args.table:
        for k, v in out["pmf"].items():
            print(f"  P(X={k}) = {mpstr(v, min(args.dps, 20))}")
    return 0


def cmd_circuits(args: argparse.Namespace) -> int:
    from symhx import circuits as C

    if args.visits:
        visits = tuple(int(v) for v in args.visits.split(","))
        out: Any = {"N": args.N, "visits": list(visits), "length": sum(visits),
                    "distinct": len(visits), "count": C.circuit_count(args.N, visits)}
    elif args.length:
        out = {"N": args.N, "length": args.length,
               "by_pattern": {",".join(map(str, v)): c
                              for v, c in C.circuits_of_length(args.N, args.length).items()},
               "total": C.necklace_count(args.N, args.length)}
    else:
        if args.N > 2000:
            raise ValueError("the table of phi_N(k) is for N <= 2000; use --visits 1,1,... ")
        out = {"N": args.N, "phi": {k: C.phi(args.N, k) for k in range(1, args.N + 1)},
               "total": C.total_simple_circuits(args.N)}
    if args.json:
        print(dump_json(out))
    else:
        print(json.dumps(jsonable(out), indent=1))
    return 0


def cmd_mode_path(args: argparse.Namespace) -> int:
    from symhx.critical import mode_path

    path = mode_path(args.N, p_max=args.p_max, dps=args.dps)
    rows = path.as_rows()
    if args.json:
        print(dump_json({"N": args.N, "breakpoints": rows}))
        return 0
    print(f"mode of X for N = {args.N}: 1 on (0, p_c]")
    for r in rows:
        print(f"  p = {mpstr(r['p'], args.dps):>40s}   {r['k_left']} -> {r['k_right']}")
    return 0


# --------------------------------------------------------------------------- paper
def paper(out: Path, full: bool) -> list[str]:
    """Core numbers: p_d, p_c, the jump and the mode path for N = 101; a table over N;
    figures 3-6."""
    from symhx.critical import critical_point, mode_path

    t0 = time.perf_counter()
    dps = 50
    cp = critical_point(PAPER_N, dps=dps)
    path = mode_path(PAPER_N)
    (out / "critical_N101.json").write_text(dump_json(cp.as_dict()) + "\n")
    with open(out / "mode_path_N101.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["p", "k_left", "k_right"])
        for r in path.as_rows():
            w.writerow([jsonable(r["p"]), r["k_left"], r["k_right"]])
    rows = [critical_point(N, dps=dps).as_dict() for N in TABLE_NS]
    (out / "critical_table.json").write_text(dump_json(rows) + "\n")
    with open(out / "critical_table.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["N", "p_d", "p_c", "N_p_c_minus_1", "k_after"])
        for r in rows:
            w.writerow([jsonable(r["N"]), jsonable(r["p_d"]), jsonable(r["p_c"]),
                        jsonable(r["N_p_c_minus_1"]), r["k_after"]])
    from symhx import plots

    for name, fig in (("fig4_distributions.png", plots.plot_distributions(PAPER_N)),
                      ("fig5_mode_path.png", plots.plot_mode_path(PAPER_N)),
                      ("fig6_f_and_phi.png", plots.plot_f_and_phi(PAPER_N))):
        fig.savefig(out / name, dpi=110, bbox_inches="tight")
    if hasattr(plots, "plot_circuit_counts"):
        plots.plot_circuit_counts(100).savefig(out / "fig3_circuit_counts.png", dpi=110,
                                                bbox_inches="tight")
    import matplotlib.pyplot as plt

    plt.close("all")
    big = critical_point(10**100, dps=30)
    return [
        f"N = {PAPER_N} ({PAPER_N - 1} pipes): p_d = {mpstr(cp.p_d, 20)}, "
        f"p_c = {mpstr(cp.p, 20)}, mode jumps 1 -> {cp.k_after}",
        f"mode path: {len(path.breakpoints)} exact breakpoints in (0, 1]",
        f"N = 10^100: N p_c - 1 = {mpstr(big.q, 20)}, jump to k = {big.k_after:.6e}",
        f"core section: {time.perf_counter() - t0:.1f} s",
    ]


def cmd_paper(args: argparse.Namespace) -> int:
    from symhx.cli import command_modules

    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    summary: dict[str, list[str]] = {}
    failed = []
    for mod in command_modules():
        fn = getattr(mod, "paper", None)
        if fn is None:
            continue
        name = mod.__name__.rsplit(".", 1)[-1]
        t0 = time.perf_counter()
        print(f"[symhx paper] {name} ...", flush=True)
        try:
            lines = fn(out, args.full)
        except Exception as exc:  # report and keep going; exit non-zero at the end
            failed.append(name)
            lines = [f"FAILED: {type(exc).__name__}: {exc}"]
        summary[name] = lines
        for line in lines:
            print(f"    {line}")
        print(f"    ({time.perf_counter() - t0:.1f} s)", flush=True)
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(f"[symhx paper] results in {out.resolve()}")
    return 1 if failed else 0
