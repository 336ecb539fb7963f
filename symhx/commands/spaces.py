"""CLI: ``symhx spaces`` (a higher-order sample space: jump, moments, classes) and
``symhx convergence`` (E[X] and p_c as the truncation m grows); the section-8 part of
``symhx paper`` (figures 11-13 data and plots, the convergence table)."""

from __future__ import annotations

import argparse
from fractions import Fraction
from pathlib import Path
from typing import Any

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
    rational_show,
    sites_arg,
    sites_json,
    sites_show,
    write_csv,
)
from symhx.commands.core import p_or_sites
from symhx.spaces import _classes, study  # their work limits, read when the parser is built
from symhx.validation import InputError

ORDER = 60

#: the paper's row for figures 11-13: 100 pipes -> N = 101
PAPER_N = 101


def register(sub: Any) -> None:
    # the work limits as they are now (each ``main`` call builds its parser): the help shows
    # them and --max-m / convergence's N are checked against them, naming their owner
    space_work, max_excess = _classes.MAX_SPACE_WORK, _classes.MAX_EXCESS
    study_n = study.STUDY_N_LIMIT
    s = sub.add_parser("spaces", help="higher-order sample spaces (section 8): jump, E[X], "
                       "modes, class probabilities",
                       description="The distribution of X over a sample space with "
                       "higher-order circuits (section 8): the jump of the mode and, given p, "
                       "E[X], Var[X], the modes and the class probabilities.")
    s.add_argument("N", type=int_arg("N", minimum=2),
                   help=N_HELP + f"; N * (m + 1) <= {space_work:.0e} (work limit "
                   f"symhx.spaces._classes.MAX_SPACE_WORK: N <= {space_work // 4:.0e} for eq41)")
    s.add_argument("p", type=rational_arg("p"), nargs="?", default=None,
                   help=P_HELP + "; omit for the jump only")
    s.add_argument("--sites", type=sites_arg, default=None,
                   help=SITES_HELP + "; E[X], Var[X] and the modes with per-class "
                   "probabilities (the jump along a direction is 'symhx critical --sites')")
    s.add_argument("--space", default="eq41",
                   help="simple | eq41 | eq41-printed | excess<=m, optionally with ;distinct")
    add_dps(s)
    s.add_argument("--float", action="store_true", help="mpmath at --dps instead of exact")
    s.add_argument("--classes", action="store_true", help="probability of each class")
    add_json(s)
    s.set_defaults(func=cmd_spaces)

    c = sub.add_parser("convergence", help="E[X] and the jump p_c for excess<=m, m = 0..M, "
                       "against eq. (41)")
    c.add_argument("N", type=int_arg("N", minimum=2, maximum=study_n,
                                     limit="symhx.spaces.study.STUDY_N_LIMIT"), nargs="?",
                   default=100, help=N_HELP + f"; at most {study_n:.0e} (work limit)")
    c.add_argument("--max-m", type=int_arg("--max-m", minimum=0, maximum=max_excess,
                                           limit="symhx.spaces._classes.MAX_EXCESS"), default=6,
                   help=f"largest excess m of the truncated spaces (at most {max_excess}, "
                   "a work limit)")
    c.add_argument("--p", action="append", default=None, type=rational_arg("--p"),
                   help=P_HELP + " (repeatable; default: the paper's figure values "
                   "0.005, 0.01, 0.015, 0.04, 0.05)")
    add_dps(c)
    add_json(c)
    c.set_defaults(func=cmd_convergence)


def _spaces_sites(args: argparse.Namespace) -> int:
    """``symhx spaces N --sites ...``: E[X], Var[X] and the modes with per-class probabilities."""
    from symhx.api import distribution_of

    if args.classes:
        raise InputError("--classes (the probability of each class of the space) is not "
                         "available with --sites; drop one of them")
    p, sites = p_or_sites(args)
    d = distribution_of(args.N, p, space=args.space, dps=args.dps)
    out: dict[str, Any] = {"N": args.N, "space": args.space, "sites": sites_json(sites),
                           "mean": d.mean(), "variance": d.var(), "modes": list(d.modes())}
    if args.json:
        print(dump_json(out))
        return 0
    print(f"space {args.space}, N = {int_show(args.N)}, sites {sites_show(sites)}:")
    print(f"  E[X]   = {mpstr(out['mean'], args.dps)}")
    print(f"  Var[X] = {mpstr(out['variance'], args.dps)}")
    print(f"  modes  = {', '.join(int_show(m) for m in out['modes'])}")
    return 0


def cmd_spaces(args: argparse.Namespace) -> int:
    from symhx._mpctx import export, mp
    from symhx.spaces import (
        check_space_work,
        class_probabilities,
        critical_point,
        distribution,
        parse_space,
    )

    check_space_work(parse_space(args.space), args.N, "symhx spaces")  # before any work
    if args.sites is not None:
        return _spaces_sites(args)
    cp = critical_point(args.N, space=args.space, dps=args.dps)
    out: dict[str, Any] = {"N": args.N, "space": args.space, "critical": cp.as_dict()}
    if args.p is not None:
        p = args.p
        if args.float:
            ctx = mp()
            with ctx.workdps(args.dps + 10):
                p = export(ctx.mpf(args.p.numerator) / args.p.denominator)
        d = distribution(args.N, p, space=args.space, dps=args.dps)
        out.update(p=args.p, mean=d.mean(), variance=d.var(), modes=list(d.modes()))
        if args.classes:
            out["classes"] = class_probabilities(args.N, p, space=args.space, dps=args.dps)
    if args.json:
        print(dump_json(out, args.dps))
        return 0
    print(f"space {args.space}, N = {int_show(args.N)}: mode jumps 1 -> "
          f"{int_show(cp.k_after)} at p_c = {mpstr(cp.p, args.dps)}")
    if args.p is not None:
        print(f"p = {mpstr(args.p, args.dps)}:")
        print(f"  E[X]   = {mpstr(out['mean'], args.dps)}")
        print(f"  Var[X] = {mpstr(out['variance'], args.dps)}")
        print(f"  modes  = {', '.join(int_show(m) for m in out['modes'])}")
        if out.get("classes"):
            print(f"  {'class':<24s} probability")
            for lab, v in out["classes"].items():
                print(f"  {lab:<24s} {mpstr(v, args.dps)}")
    return 0


def _convergence_rows(N: int, max_m: int, ps: list[Fraction] | None, dps: int) -> list[dict]:
    """The study's rows as dicts; ``means`` keyed by each p as typed (``"0.005"``, ``"1/3"``)."""
    from symhx.spaces import DEFAULT_PS, convergence_study

    texts = [rational_show(p) for p in ps] if ps else DEFAULT_PS  # exact strings, exact values
    rows = convergence_study(N, ms=range(0, max_m + 1), ps=texts, dps=dps)
    return [r.as_dict() for r in rows]


def cmd_convergence(args: argparse.Namespace) -> int:
    rows = _convergence_rows(args.N, args.max_m, args.p, args.dps)
    if args.json:
        print(dump_json({"N": args.N, "rows": rows}, args.dps))
        return 0
    ps = list(rows[0]["means"])
    print(f"N = {args.N}: E[X] at p = {', '.join(ps)}")
    print(f"{'space':>14s} {'p_c':>14s} {'k':>4s} " + " ".join(f"{p:>9s}" for p in ps))
    pc_digits, mean_digits = min(8, args.dps), min(5, args.dps)  # never beyond --dps
    for r in rows:
        print(f"{r['space']:>14s} {mpstr(r['p_c'], pc_digits):>14s} {r['k_after']:4d} "
              + " ".join(f"{mpstr(v, mean_digits):>9s}" for v in r["means"].values()))
    return 0


def paper(out: Path, full: bool) -> list[str]:
    """Figures 11-13 (data and plots), the boundary corrections and the convergence table."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from symhx.plots.higher_order import plot_mean_vs_p_spaces
    from symhx.plots.paper import PNG_DPI, save_paper_figure
    from symhx.spaces import boundary_table, class_decomposition, critical_point

    N = PAPER_N
    from fractions import Fraction

    for p in ("0.005", "0.01", "0.05"):
        for space in ("eq41", "eq41-printed"):
            cd = class_decomposition(N, float(Fraction(p)), space=space, dps=20)
            header = ["k", *[cd.labels[s] for s in cd.shapes]]
            table = [[k, *[cd.joint[s][k - 1] for s in cd.shapes]] for k in range(1, N + 1)]
            write_csv(out / f"fig11_classes_{space}_p{p}.csv", header, table)
            (out / f"fig11_classes_{space}_p{p}.json").write_text(
                dump_json({"columns": header, "rows": table}) + "\n")
    save_paper_figure(11, out / "fig11_classes.png")
    save_paper_figure(12, out / "fig12_simple_vs_higher.png")
    # figure 13's theory curves alone (the spaces of figure 13), over the paper's range of p
    fig = plot_mean_vs_p_spaces(N, points=40 if full else 20)
    fig.savefig(out / "fig13_theory.png", dpi=PNG_DPI, bbox_inches="tight")
    plt.close(fig)
    (out / "section8_boundary.json").write_text(dump_json(
        [{**r, "class": list(r["class"])} for r in boundary_table(N)]) + "\n")
    lines = []
    for n in (100, 101):
        rows = _convergence_rows(n, 8 if full else 6, None, 20)
        (out / f"convergence_N{n}.json").write_text(dump_json(rows) + "\n")
        r0 = {r["space"]: r for r in rows}
        lines.append(
            f"N = {n}: p_c simple {mpstr(r0['excess<=0']['p_c'], 8)}, eq41 "
            f"{mpstr(r0['eq41']['p_c'], 8)} (jump to {r0['eq41']['k_after']}), excess<=6 "
            f"{mpstr(r0['excess<=6']['p_c'], 8)} (jump to {r0['excess<=6']['k_after']})")
    cp = critical_point(10**6, space="eq41", dps=20)
    lines.append(f"eq41, N = 10^6: p_c = {mpstr(cp.p, 15)}, jump 1 -> {cp.k_after}")
    return lines
