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

import numpy as np

from symhx._mpctx import export, local, mp
from symhx.commands._common import jsonable, mpstr

ORDER = 40


def _omega_arg(text: str) -> Any:
    """``1.5`` -> one component; ``1.5,2.5`` -> several components (eq. 22)."""
    parts = [t.strip() for t in text.split(",") if t.strip()]
    if not parts:
        raise ValueError(f"expected a number or a comma separated list, got {text!r}")
    return parts if len(parts) > 1 else parts[0]


def register(sub: Any) -> None:
    ps = sub.add_parser(
        "p-sigma",
        help="impact probability p and 1 - p for forcing sigma (eqs. 22-27)",
        description="Impact probability p = P(Y0 + sum Y_i/abs(omega^2 - Omega_i^2) > d), 1 - p "
        "and their natural logs for forcing standard deviation sigma (sigma1 = sigma unless "
        "given). Numbers are exact decimals (0.05 is 1/20). JSON output is strict: with --dps "
        "every value is a decimal string; in float64 a value outside the float range "
        "(log p = -inf for sigma -> 0) is the string \"-inf\" (or \"inf\"), never a bare "
        "-Infinity.",
    )
    ps.add_argument("sigma", nargs="*",
                    help="sigma values (decimal strings are exact); or target p with --inverse")
    ps.add_argument("--grid", nargs=3, metavar=("START", "STOP", "NUM"),
                    help="add NUM log-spaced sigma values from START to STOP (default: none)")
    ps.add_argument("--dps", type=int, default=None,
                    help="significant digits (mpmath); default: float64")
    ps.add_argument("--sigma1", default=None,
                    help="forcing standard deviation(s), comma separated per component "
                    "(default: = sigma)")
    ps.add_argument("--omega", default="1", help="natural frequency (default: 1)")
    ps.add_argument("--Omega", default=None,
                    help="forcing frequency, or comma separated list of components "
                    "(default: sqrt(2), exact)")
    ps.add_argument("--d", default="1", help="pipe spacing (default: 1)")
    ps.add_argument("--inverse", action="store_true",
                    help="treat the values as target probabilities p and print sigma(p) "
                    "(default: off)")
    ps.add_argument("--json", action="store_true",
                    help="strict JSON output (default: text)")
    ps.add_argument("--csv", type=Path, default=None, metavar="FILE",
                    help="also write a CSV file (default: none)")
    ps.set_defaults(func=cmd_p_sigma)


def _values(args: argparse.Namespace) -> list[Any]:
    vals: list[Any] = list(args.sigma)
    if args.grid:
        try:
            a, b, n = float(args.grid[0]), float(args.grid[1]), int(args.grid[2])
        except ValueError:
            raise ValueError(f"--grid: need START STOP NUM numbers, got {args.grid}") from None
        if not (0 < a < math.inf and 0 < b < math.inf and 1 <= n <= 100_000):
            raise ValueError("--grid: need 0 < START, STOP < inf and 1 <= NUM <= 100000, got "
                             f"{args.grid}")
        vals += [float(v) for v in np.logspace(math.log10(a), math.log10(b), n)]
    if not vals:
        raise ValueError("give sigma values or --grid START STOP NUM")
    return vals


def _kwargs(args: argparse.Namespace) -> dict[str, Any]:
    """The forcing options as API arguments (decimal strings: exact)."""
    Omega = None if args.Omega is None else _omega_arg(args.Omega)
    sigma1 = None if args.sigma1 is None else _omega_arg(args.sigma1)
    return dict(sigma1=sigma1, omega=_omega_scalar("--omega", args.omega), Omega=Omega,
                d=_omega_scalar("--d", args.d))


def _omega_scalar(name: str, text: str) -> str:
    if "," in text:
        raise ValueError(f"{name} takes one number, got {text!r}")
    return text.strip()


def _rows(vals: list[Any], args: argparse.Namespace) -> list[dict[str, Any]]:
    """sigma, p, 1 - p, log p, log(1 - p) for every value; the forcing is validated once.

    float64: one vectorised evaluation per quantity over all sigma values. mpmath: per sigma,
    ``p`` and ``1 - p`` are evaluated once each (each by its stable form, see
    :mod:`symhx.forcing`) and the logs are derived from them at the working precision
    (``log p = log1p(-(1 - p))`` when ``p > 1/2``, so they keep their relative accuracy).
    """
    from symhx import forcing as F
    from symhx.validation import check_dps

    kw = _kwargs(args)
    dps = check_dps(args.dps, allow_none=True)
    F.ForcingParams.validated(1, dps=dps, **kw)  # bad options fail before any work
    if args.inverse:
        sig: list[Any] = [F.sigma_for_impact_probability(v, **kw, dps=dps) for v in vals]
    else:
        sig = list(vals)
    if dps is None:
        s = np.array([float(F.ForcingParams.validated(v).sigma) if isinstance(v, str) else v
                      for v in sig], dtype=float)
        cols = [F.impact_probability(s, **kw), F.no_impact_probability(s, **kw),
                F.log_impact_probability(s, **kw), F.log_no_impact_probability(s, **kw)]
        return [{"sigma": float(s[i]), "p": float(cols[0][i]), "one_minus_p": float(cols[1][i]),
                 "log_p": float(cols[2][i]), "log_one_minus_p": float(cols[3][i])}
                for i in range(len(s))]
    rows = []
    for v in sig:
        p = F.impact_probability(v, **kw, dps=dps + 3)
        q = F.no_impact_probability(v, **kw, dps=dps + 3)
        ctx = mp()
        with ctx.workdps(dps + 3):
            lp = export(ctx.log(p) if p <= 0.5 else ctx.log1p(-local(q)))
            lq = export(ctx.log(q) if q <= 0.5 else ctx.log1p(-local(p)))
        rows.append({"sigma": v, "p": p, "one_minus_p": q, "log_p": lp, "log_one_minus_p": lq})
    return rows


def _fmt(x: Any, dps: int | None) -> str:
    if dps is None:
        return repr(float(x))
    if isinstance(x, str):
        return x
    return mpstr(x, dps)  # printed from the value's own bits: no working precision involved


def strict_json_value(x: Any, dps: int | None) -> Any:
    """A JSON-safe value: decimal strings with ``dps``; floats, or ``"inf"``/``"-inf"``/
    ``"nan"`` strings for non-finite floats (JSON has no infinities)."""
    if dps is not None:
        return _fmt(x, dps)
    f = float(x)
    return f if math.isfinite(f) else repr(f)


def cmd_p_sigma(args: argparse.Namespace) -> int:
    rows = _rows(_values(args), args)
    dps = args.dps
    if args.csv is not None:
        try:
            fh = open(args.csv, "w", newline="")
        except OSError as exc:
            raise ValueError(f"--csv: cannot write {str(args.csv)!r}: {exc.strerror}") from None
        with fh:
            w = csv.writer(fh)
            w.writerow(list(rows[0]))
            for r in rows:
                w.writerow([_fmt(v, dps) for v in r.values()])
    if args.json:
        out = [{k: strict_json_value(v, dps) for k, v in r.items()} for r in rows]
        print(json.dumps(jsonable(out), indent=2, allow_nan=False))
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
    ctx = mp()
    with ctx.workprec(53):  # 1 - 1e-10 rounded to 53 bits, as before
        q1e10 = export(ctx.mpf(1) - ctx.mpf("1e-10"))
    s_q1e10 = F.sigma_for_impact_probability(q1e10, dps=30)
    meta = {
        "parameters": {"sigma1": "sigma", "omega": 1, "Omega": "sqrt(2)", "d": 1},
        "sigma": s.tolist(), "p": p.tolist(), "one_minus_p": q.tolist(),
        "log_p": lp.tolist(), "log_one_minus_p": lq.tolist(),
        "sigma_at_p_1e-10": s_1e10, "sigma_at_p_one_half": s_half,
        "sigma_at_one_minus_p_1e-10": s_q1e10, "checks": checks,
    }
    (out / "fig9_p_sigma.json").write_text(json.dumps(jsonable(meta), indent=1) + "\n")
    from symhx.plots.paper import save_paper_figure

    save_paper_figure(9, out / "fig9_p_sigma.png")
    naive = checks["0.05"]["naive_1_minus_dblquad"]
    return [
        f"p(sigma = 0.12) = {mpstr(checks['0.12']['p'], 15)} (paper's parameters)",
        f"p(sigma = 0.05) = {mpstr(checks['0.05']['p'], 15)}; paper's 1 - dblquad(eq. 27) "
        f"gives {naive:.3e}",
        f"p = 1e-10 at sigma = {mpstr(s_1e10, 15)}; p = 1/2 at sigma = {mpstr(s_half, 15)}; "
        f"1 - p = 1e-10 at sigma = {mpstr(s_q1e10, 15)}",
    ]
