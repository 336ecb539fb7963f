"""CLI: ``symhx p-sigma`` (impact probability against forcing, eqs. 22-27) and the forcing part
of ``symhx paper`` (figure 9)."""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
from pathlib import Path
from typing import Any

import mpmath
import numpy as np

from symhx.commands._common import jsonable, mpstr

ORDER = 40


def _omega_arg(text: str) -> Any:
    """``1.5`` -> one component; ``1.5,2.5`` -> several components (eq. 22)."""
    parts = [t for t in text.split(",") if t.strip()]
    return [p.strip() for p in parts] if len(parts) > 1 else parts[0].strip()


def register(sub: Any) -> None:
    ps = sub.add_parser(
        "p-sigma",
        help="impact probability p and 1 - p for forcing sigma (eqs. 22-27)",
        description="Impact probability p = P(Y0 + sum Y_i/|omega^2 - Omega_i^2| > d) and "
        "1 - p for forcing standard deviation sigma (sigma1 = sigma unless given).",
    )
    ps.add_argument("sigma", nargs="*", help="sigma values (decimal strings are exact)")
    ps.add_argument("--grid", nargs=3, metavar=("START", "STOP", "NUM"),
                    help="NUM log-spaced sigma values from START to STOP")
    ps.add_argument("--dps", type=int, default=None,
                    help="significant digits (mpmath); default: float64")
    ps.add_argument("--sigma1", default=None,
                    help="forcing standard deviation(s), comma separated per component "
                    "(default: = sigma)")
    ps.add_argument("--omega", default="1", help="natural frequency (default 1)")
    ps.add_argument("--Omega", default=None,
                    help="forcing frequency, or comma separated list of components "
                    "(default: sqrt(2), exact)")
    ps.add_argument("--d", default="1", help="pipe spacing (default 1)")
    ps.add_argument("--inverse", action="store_true",
                    help="treat the values as target probabilities p and print sigma(p)")
    ps.add_argument("--json", action="store_true", help="JSON output")
    ps.add_argument("--csv", type=Path, default=None, metavar="FILE", help="write a CSV file")
    ps.set_defaults(func=cmd_p_sigma)


def _values(args: argparse.Namespace) -> list[Any]:
    vals: list[Any] = list(args.sigma)
    if args.grid:
        a, b, n = float(args.grid[0]), float(args.grid[1]), int(args.grid[2])
        if not (a > 0 and b > 0 and n >= 1):
            raise ValueError("--grid: need START > 0, STOP > 0, NUM >= 1")
        vals += [float(v) for v in np.logspace(math.log10(a), math.log10(b), n)]
    if not vals:
        raise ValueError("give sigma values or --grid START STOP NUM")
    return vals


def _kwargs(args: argparse.Namespace) -> dict[str, Any]:
    Omega = None if args.Omega is None else _omega_arg(args.Omega)
    sigma1 = None if args.sigma1 is None else _omega_arg(args.sigma1)
    if args.dps is None:
        def conv(v: Any) -> Any:
            return [float(x) for x in v] if isinstance(v, list) else float(v)

        Omega = None if Omega is None else conv(Omega)
        sigma1 = None if sigma1 is None else conv(sigma1)
        return dict(sigma1=sigma1, omega=float(args.omega), Omega=Omega, d=float(args.d))
    return dict(sigma1=sigma1, omega=args.omega, Omega=Omega, d=args.d)


def _rows(vals: list[Any], args: argparse.Namespace) -> list[dict[str, Any]]:
    from symhx import forcing as F

    kw = _kwargs(args)
    dps = args.dps
    rows = []
    for v in vals:
        if args.inverse:
            s = F.sigma_for_impact_probability(v if dps else float(v), **kw, dps=dps)
        else:
            s = v if dps else float(v)
        p = F.impact_probability(s, **kw, dps=dps)
        q = F.no_impact_probability(s, **kw, dps=dps)
        lp = F.log_impact_probability(s, **kw, dps=dps)
        lq = F.log_no_impact_probability(s, **kw, dps=dps)
        rows.append({"sigma": s, "p": p, "one_minus_p": q, "log_p": lp, "log_one_minus_p": lq})
    return rows


def _fmt(x: Any, dps: int | None) -> str:
    if dps is None:
        return repr(float(x))
    with mpmath.workdps(dps + 5):
        return mpstr(x, dps)


def cmd_p_sigma(args: argparse.Namespace) -> int:
    rows = _rows(_values(args), args)
    dps = args.dps
    if args.csv is not None:
        with open(args.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(list(rows[0]))
            for r in rows:
                w.writerow([_fmt(v, dps) for v in r.values()])
    if args.json:
        out = [{k: (_fmt(v, dps) if dps else float(v)) for k, v in r.items()} for r in rows]
        print(json.dumps(jsonable(out), indent=2))
    elif args.csv is None or len(rows) <= 20:
        for r in rows:
            print(f"sigma = {_fmt(r['sigma'], dps)}")
            print(f"  p     = {_fmt(r['p'], dps)}")
            print(f"  1 - p = {_fmt(r['one_minus_p'], dps)}")
            if float(r["p"]) == 0.0 or float(r["one_minus_p"]) == 0.0:
                print(f"  ln p = {_fmt(r['log_p'], dps)}, ln(1 - p) = "
                      f"{_fmt(r['log_one_minus_p'], dps)}")
    if args.csv is not None:
        print(f"wrote {len(rows)} rows to {args.csv}", file=sys.stderr)
    return 0


def paper(out: Path, full: bool) -> list[str]:
    """Figure 9 data (p and 1 - p over sigma in [0.01, 100], CSV + JSON) and the figure."""
    from symhx import forcing as F

    n = 401 if full else 161
    s = np.logspace(-2, 2, n)
    lp = F.log_impact_probability(s)
    lq = F.log_no_impact_probability(s)
    p = F.impact_probability(s)
    q = F.no_impact_probability(s)
    with open(out / "fig9_p_sigma.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["sigma", "p", "one_minus_p", "log_p", "log_one_minus_p"])
        for row in zip(s, p, q, lp, lq, strict=True):
            w.writerow([repr(float(v)) for v in row])
    checks = {}
    for sv in ("0.05", "0.12"):
        checks[sv] = {"p": F.impact_probability(sv, dps=30),
                      "naive_1_minus_dblquad": F.naive_impact_probability(float(sv))}
    s_half = F.sigma_for_impact_probability("0.5", dps=30)
    s_1e10 = F.sigma_for_impact_probability("1e-10", dps=30)
    s_q1e10 = F.sigma_for_impact_probability(mpmath.mpf(1) - mpmath.mpf("1e-10"), dps=30)
    meta = {
        "parameters": {"sigma1": "sigma", "omega": 1, "Omega": "sqrt(2)", "d": 1},
        "sigma": s.tolist(), "p": p.tolist(), "one_minus_p": q.tolist(),
        "log_p": lp.tolist(), "log_one_minus_p": lq.tolist(),
        "sigma_at_p_1e-10": s_1e10, "sigma_at_p_one_half": s_half,
        "sigma_at_one_minus_p_1e-10": s_q1e10, "checks": checks,
    }
    (out / "fig9_p_sigma.json").write_text(json.dumps(jsonable(meta), indent=1) + "\n")
    from symhx.plots.forcing import plot_p_sigma

    fig = plot_p_sigma(s, naive=True, n_naive=17 if not full else 33)
    fig.savefig(out / "fig9_p_sigma.png", dpi=110, bbox_inches="tight")
    import matplotlib.pyplot as plt

    plt.close("all")
    with mpmath.workdps(30):
        naive = checks["0.05"]["naive_1_minus_dblquad"]
        return [
            f"p(sigma = 0.12) = {mpstr(checks['0.12']['p'], 15)} (paper's parameters)",
            f"p(sigma = 0.05) = {mpstr(checks['0.05']['p'], 15)}; paper's 1 - dblquad(eq. 27) "
            f"gives {naive:.3e}",
            f"p = 1e-10 at sigma = {mpstr(s_1e10, 15)}; p = 1/2 at sigma = {mpstr(s_half, 15)}; "
            f"1 - p = 1e-10 at sigma = {mpstr(s_q1e10, 15)}",
        ]
