"""CLI: ``symhx derive`` (the sympy derivations, verified) and ``symhx asymptotics`` (large-N
approximations of the jump with their errors), plus their part of ``symhx paper``.

sympy is imported only inside the handlers, never when the CLI starts.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from symhx.commands._common import dump_json, int_arg, mpstr
from symhx.commands.core import add_dps, add_json, write_csv

ORDER = 30


def register(sub: Any) -> None:
    d = sub.add_parser("derive", help="sympy derivations of the paper's equations (verified)")
    d.add_argument("labels", nargs="*", metavar="LABEL",
                   help="equation labels, e.g. 16 9 38 crossing (see --list)")
    d.add_argument("--all", action="store_true", help="every derivation")
    d.add_argument("--list", action="store_true", help="list the labels and descriptions")
    d.add_argument("--latex", action="store_true", help="print LaTeX instead of sympy text")
    d.add_argument("--verify", action="store_true", help="run the checks and show the outcome")
    d.add_argument("--steps", action="store_true", help="also print the derivation steps")
    add_json(d)
    d.set_defaults(func=cmd_derive)

    a = sub.add_parser("asymptotics", help="large-N approximations of p_c and k_jump")
    a.add_argument("N", nargs="?", type=int_arg("N", minimum=2), default=None,
                   help="number of vertices (e.g. 1e10, 10**100); omit with --table")
    a.add_argument("--order", default="all",
                   help="leading, next, lambert, corrected, relaxed, best or all")
    add_dps(a)
    a.add_argument("--exact", action="store_true",
                   help="also run the exact solver and show relative errors")
    a.add_argument("--table", action="store_true",
                   help="the error table at N = 1e3, 1e6, 1e10, 1e30, 1e100")
    add_json(a)
    a.set_defaults(func=cmd_asymptotics)


# --------------------------------------------------------------------------- derive
def cmd_derive(args: argparse.Namespace) -> int:
    """``symhx derive``: builds only the derivations asked for (``--list`` builds none)."""
    from symhx.symbolic import catalogue, derivation, latex

    cat = catalogue()
    if args.list:
        for lab, (section, description, _) in cat.items():
            print(f"{lab:>18s}  (sec. {section})  {description}")
        return 0
    if args.all:
        chosen = list(cat)
    elif args.labels:
        unknown = [lab for lab in args.labels if lab not in cat]
        if unknown:
            raise ValueError(f"unknown label(s) {', '.join(unknown)}; try 'symhx derive --list'")
        chosen = list(args.labels)
    else:
        raise ValueError("give equation labels (e.g. 16) or --all; 'symhx derive --list' lists")

    if args.json:
        out = [derivation(lab).as_dict(verify=args.verify) for lab in chosen]
        print(dump_json(out))
        return 0 if not args.verify or all(o["verified"] for o in out) else 1

    failed = []
    for lab in chosen:
        d = derivation(lab)
        print(f"({lab}) {d.markdown if args.latex else d.description}")
        if args.steps:
            for step in d.steps:
                text = step.markdown if args.latex else step.text
                shown = latex(step.expr) if args.latex else str(step.expr)
                print(f"    step: {text} {shown}" if text else f"        = {shown}")
        print("    " + (d.latex() if args.latex else str(d.result)))
        if args.verify:
            rep = d.report()
            ok = bool(rep) and all(r.passed for r in rep)
            failed += [] if ok else [lab]
            for r in rep:
                mark = "ok  " if r.passed else "FAIL"
                what = r.markdown if args.latex else r.description
                print(f"    [{mark}] ({r.kind}) {what}" + (f": {r.error}" if r.error else ""))
    if args.verify:
        print(f"{len(chosen) - len(failed)}/{len(chosen)} derivations verified"
              + (f"; failed: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


# --------------------------------------------------------------------------- asymptotics
def cmd_asymptotics(args: argparse.Namespace) -> int:
    from symhx._mpctx import export, local, mp
    from symhx.asymptotics import ORDERS, asymptotic_critical_point, error_table

    orders = ORDERS if args.order == "all" else (args.order,)
    for o in orders:
        if o not in ORDERS:
            raise ValueError(f"--order must be one of {', '.join(ORDERS)} or all, got {o!r}")
    if args.table:
        rows = error_table(dps=max(args.dps, 120), orders=orders)
        if args.json:
            print(dump_json(rows))
        else:
            from symhx.asymptotics import format_error_table

            print("relative error of N p_c - 1 (and of p_d for the series) vs the exact solver")
            print(format_error_table(rows))
        return 0
    if args.N is None:
        raise ValueError("give N (e.g. 1e10) or --table")
    res = [asymptotic_critical_point(args.N, order=o, dps=args.dps) for o in orders]
    exact = None
    if args.exact:
        from symhx.critical import critical_point

        exact = critical_point(args.N, dps=args.dps)
    ctx = mp()

    def rel_error(q: Any) -> Any:
        assert exact is not None
        with ctx.workdps(args.dps):
            return export(abs(local(q) / local(exact.q) - 1))

    if args.json:
        out = []
        for r in res:
            row = r.as_dict()
            if exact is not None:
                row["q_rel_error"] = rel_error(r.q)
                row["k_exact"] = exact.k_after
            out.append(row)
        print(dump_json(out))
        return 0
    print(f"N = {args.N}: large-N approximations of q = N p_c - 1 and k_jump")
    for r in res:
        line = f"  {r.order:>9s}: q = {mpstr(r.q, 15)}   k = {mpstr(r.k, 15)}"
        if exact is not None:
            line += f"   rel. err. {mpstr(rel_error(r.q), 3)}"
        print(line + f"   [{r.decay}]")
    if exact is not None:
        print(f"  {'exact':>9s}: q = {mpstr(exact.q, 15)}   k = {exact.k_after}")
    return 0


# --------------------------------------------------------------------------- paper
def paper(out: Path, full: bool) -> list[str]:
    """Verified derivation list (labels, LaTeX, verified flags) and the asymptotic error table."""
    from symhx.asymptotics import error_table
    from symhx.symbolic import derivations

    rows = [d.as_dict(verify=True) for d in derivations().values()]
    (out / "derivations.json").write_text(json.dumps(rows, indent=2) + "\n")
    n_ok = sum(r["verified"] for r in rows)
    table = error_table(dps=120)
    (out / "asymptotic_errors.json").write_text(dump_json(table) + "\n")
    write_csv(out / "asymptotic_errors.csv",
              ["N", "formula", "quantity", "rel_error", "k", "k_exact", "decay"],
              [[r["N"], r["formula"], r["quantity"], r["rel_error"], r["k"], r["k_exact"],
                r["decay"]] for r in table])
    if full:
        from symhx.plots.asymptotics import plot_asymptotic_errors

        fig = plot_asymptotic_errors(table)
        fig.savefig(out / "asymptotic_errors.png", dpi=110, bbox_inches="tight")
        import matplotlib.pyplot as plt

        plt.close(fig)
    best = {r["N"]: r["rel_error"] for r in table if r["formula"] == "best"}
    return [
        f"derivations: {n_ok}/{len(rows)} verified "
        f"({sum('symbolic' in r['kinds'] for r in rows)} with a symbolic check)",
        "asymptotics: best-order rel. error of N p_c - 1 at N = 1e10: "
        f"{mpstr(best.get(10**10, 0), 2)}, at 1e100: {mpstr(best.get(10**100, 0), 2)}",
    ]
