"""Render the README's benchmark table from ``benchmarks/results/*.json``.

    python scripts/bench_table.py            # print the Markdown table
    python scripts/bench_table.py --readme   # rewrite the block between the markers in README.md

The numbers are read from the result files, never typed in; ``tests/system/test_readme.py``
checks that the README's block matches what this script renders.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
START, END = "<!-- bench-table:start -->", "<!-- bench-table:end -->"


def _load(name: str) -> dict | None:
    path = RESULTS / f"{name}.json"
    return json.loads(path.read_text()) if path.exists() else None


def rows() -> list[tuple[str, str, str]]:
    out: list[tuple[str, str, str]] = []
    core = _load("core")
    if core:
        def pick(task, method, N, dps):
            for r in core["rows"]:
                if (r["task"], r["method"], r["N"], r["dps"]) == (task, method, N, dps):
                    return r
            return None

        for N in (10**3, 10**5):
            a = pick("critical", "symhx.critical_point", N, 20)
            b = pick("critical", "naive mpmath scan", N, 20)
            if a and b:
                out.append((f"critical point p_c, N = 10^{len(str(N)) - 1}, 20 digits",
                            f"{a['time'] * 1e3:.1f} ms, rel. error {a['error']:.0e}",
                            f"mpmath scan of all k: {b['time'] * 1e3:.0f} ms, "
                            f"error {b['error']:.0e}"))
        speed = core.get("speed")
        if speed:
            t = {r["N"]: r["time"] for r in speed["rows"]
                 if r["call"].startswith("critical_point(")}
            scan = [r["time"] for r in speed["rows"] if r["call"].startswith("exhaustive")]
            out.append(("critical_point(N, dps=50), certified (Arb)",
                        f"N = 10^4: {t['1e4'] * 1e3:.2f} ms; 10^100: {t['1e100'] * 1e3:.2f} ms; "
                        f"10^1000: {t['1e1000'] * 1e3:.0f} ms",
                        f"exhaustive mpmath scan, N = 10^4: {scan[0] * 1e3:.0f} ms "
                        f"({speed['scan_over_symhx_N1e4']:.0f}× slower)"))
        a = pick("mean", "symhx.mean (log space)", 10**4, 50)
        b = pick("mean", "naive mpmath full sum", 10**4, 50)
        if a and b:
            out.append(("E[X], N = 1e4, 50 digits", f"{a['time'] * 1e3:.0f} ms, "
                        f"error {a['error']:.0e}", f"mpmath sum of all terms: "
                        f"{b['time'] * 1e3:.0f} ms"))
    forcing = _load("forcing")
    if forcing:
        f64 = forcing["float64_1e6_array"]
        mp50 = forcing["mpmath_50_digits"]
        out.append(("p(σ) float64, 1e6 array, one core",
                    f"{f64['impact_probability']['values_per_second']:.2e} values/s "
                    f"(1 − p: {f64['no_impact_probability']['values_per_second']:.2e})",
                    "target 1e7 values/s"))
        out.append(("p(σ) mpmath, 50 digits",
                    f"{mp50['impact_probability']['microseconds_per_value']:.0f} µs/value "
                    f"(1 − p: {mp50['no_impact_probability']['microseconds_per_value']:.0f})",
                    "target 200 µs/value"))
        naive = forcing.get("naive_at_0.05")
        if isinstance(naive, dict):
            out.append((f"p(σ = {naive['sigma']}), where the paper's eq. (27) fails",
                        f"{float(naive['true_p']):.6e} (checked against quadrature of eq. 26)",
                        f"1 − scipy dblquad(eq. 27): {naive['naive_1_minus_dblquad']:.3e}"))
    thr = _load("impact_throughput")
    if thr:
        out.append((f"impact engine (C), {thr['n']} pipes, σ = {thr['sigma']}",
                    f"{thr['impacts_per_s_one_core']:.2e} impacts/s (one core)",
                    f"two processes: {thr['impacts_per_s_two_processes_wall']:.2e}/s wall"))
    wp = _load("impact_work_precision")
    if wp:
        best = min(wp["solve_ivp"], key=lambda r: r["error"])
        missed = max(r["missed"] for r in wp["solve_ivp"])
        out.append((f"impact times, {wp['n']} pipes, t ≤ {wp['t_end']:g}",
                    f"{wp['symhx']['seconds'] * 1e3:.2f} ms, error {wp['symhx']['error']:.0e},"
                    f" {wp['symhx']['missed']} missed",
                    f"solve_ivp DOP853 best: {best['seconds'] * 1e3:.0f} ms, error "
                    f"{best['error']:.0e} (rtol {best['rtol']:g}); up to {missed} missed"))
    hey = _load("impact_vs_heyoka")
    if hey:
        for n in sorted({r["n"] for r in hey["per_run"]}):
            rs = [r for r in hey["per_run"] if r["n"] == n]
            out.append((f"impact run vs heyoka, {n} pipes, t ≤ {rs[0]['t_end']:g}, "
                        f"{len(rs)} seeds",
                        f"{min(r['symhx_s'] for r in rs) * 1e6:.0f}–"
                        f"{max(r['symhx_s'] for r in rs) * 1e6:.0f} µs, error ≤ "
                        f"{max(r['symhx_error'] for r in rs):.0e}",
                        f"heyoka (tol 1e-15, same sites): "
                        f"{min(r['heyoka_s'] for r in rs) * 1e6:.0f}–"
                        f"{max(r['heyoka_s'] for r in rs) * 1e6:.0f} µs; symhx "
                        f"{min(r['speedup'] for r in rs):.1f}–{max(r['speedup'] for r in rs):.1f}× "
                        f"faster"))
        ens = hey.get("ensemble")
        if isinstance(ens, dict) and "symhx_runs_per_s_2_processes" in ens:
            out.append((f"figures 7–8 runs ({ens['n']} pipes, t ≤ {ens['t_end']:g}), 2 workers",
                        f"{ens['symhx_runs_per_s_2_processes']:.0f} runs/s",
                        f"heyoka ensemble propagation: "
                        f"{ens['heyoka_runs_per_s_ensemble_2_threads']:.1f} runs/s"))
    large = _load("large_n")
    if large:
        out.extend(_large_n_rows(large["rows"]))
    spaces = _load("spaces")
    if spaces:
        for r in spaces["rows"]:
            if r.get("space") == "eq41" and "naive_mpf_N100_s" in r:
                out.append(("pmf of X, eq. (41) space, N = 100, dps 30",
                            f"{r['pmf_N100_dps30_s'] * 1e3:.1f} ms",
                            f"naive mpf sum over patterns: {r['naive_mpf_N100_s'] * 1e3:.0f} ms"))
    return out


def _span(values: list[float]) -> str:
    """``lo–hi`` of rounded values, or the one value when they round alike."""
    lo, hi = f"{min(values):.0f}", f"{max(values):.0f}"
    return lo if lo == hi else f"{lo}–{hi}"


def _large_n_rows(rs: list[dict]) -> list[tuple[str, str, str]]:
    """Rows of ``bench_large_n``: the cold mean at N = 10^100 and 10^1000 (both cases), and
    the float64 pmf beyond the table against the gammaln formula."""
    out: list[tuple[str, str, str]] = []
    for N, label, walk in (("1e100", "10^100", "10^50"), ("1e1000", "10^1000", "10^500")):
        m = [r for r in rs if r["N"] == N and r["stat"] == "mean"]
        c = [r for r in rs if r["N"] == N and r["stat"] == "cdf after mean"]
        if m:
            ms = _span([r["time_s"] * 1e3 for r in m])
            calls = _span([r["ratio_to_critical_point"] for r in m])
            out.append((f"E[X] at N = {label}, 50 digits (2 p_c and N p − 1 = 2 (N p_c − 1))",
                        f"{ms} ms ({calls} critical_point calls), error ≤ "
                        f"{max(r['rel_err'] for r in m):.0e}"
                        + (f"; cdf after it {max(r['time_s'] for r in c) * 1e3:.0f} ms"
                           if c else ""),
                        f"direct sum: ~{walk} terms (√N); target ~30 critical_point calls"))
    for N in ("1e10", "1e100"):
        f = [r for r in rs if r["N"] == N and r["stat"] == "cdf x1001 (float64)"]
        g = [r for r in rs if r["N"] == N and r["stat"] == "cdf per k (17 digits)"]
        if f and g:
            per = max(r["time_s"] / r["points"] for r in g)
            out.append((f"float64 cdf at 1001 k, N = {N} (dps=None), first call",
                        f"{max(r['time_s'] for r in f) * 1e3:.0f} ms, rel. error "
                        f"{max(r['rel_err'] for r in f):.0e}",
                        f"one 17-digit partial sum per k: {per * 1e3:.1f} ms per k "
                        f"({per * 1001:.1f} s for 1001)"))
    for N in ("1e10", "1e100"):
        f = [r for r in rs if r["N"] == N and r["stat"] == "pmf x1001 (float64)"]
        g = [r for r in rs if r["N"] == N and r["stat"] == "pmf x1001 (gammaln)"]
        if f and g:
            bad = max(r["rel_err"] for r in g)
            out.append((f"float64 pmf at 1001 k, N = {N} (dps=None)",
                        f"{max(r['time_s'] for r in f) * 1e3:.0f} ms, rel. error "
                        f"{max(r['rel_err'] for r in f):.0e}",
                        f"gammaln formula: {max(r['time_s'] for r in g) * 1e3:.2f} ms, "
                        + ("no digit right" if bad >= 1 else f"rel. error {bad:.0e}")))
    return out


def render() -> str:
    lines = ["| task | symhx | naive way / target |", "|---|---|---|"]
    lines += [f"| {a} | {b} | {c} |" for a, b, c in rows()]
    return "\n".join(lines)


def main(argv: list[str]) -> int:
    table = render()
    if "--readme" in argv:
        readme = ROOT / "README.md"
        text = readme.read_text()
        i, j = text.index(START) + len(START), text.index(END)
        readme.write_text(text[:i] + "\n" + table + "\n" + text[j:])
    print(table)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
