"""``symhx simulate`` and ``symhx ensemble`` (``symhx.commands.impact``): tables, JSON, files,
help texts, refusals, and the ensemble on a two-process dask cluster (API and CLI) against the
serial numbers."""

from __future__ import annotations

import io
import json

import pytest

from symhx.cli import build_parser, main
from symhx.impact.ensemble import EnsembleResult, ensemble

KW = dict(n=20, t_transient=30.0, t_window=20.0, seed=123, progress=False)
SIGMAS = [0.12, 0.2, 0.35]


def _cli(argv, capsys):
    rc = main(argv)
    out = capsys.readouterr()
    return rc, out.out, out.err


def _key(res):
    return [(s.sigma, s.runs, s.excluded, s.failed, s.pipes.tolist(), s.sites.tolist(),
             s.site_hits.tolist(), s.events, s.impacts, json.dumps(s.stats, sort_keys=True))
            for s in res.per_sigma]


def test_cli_simulate_table_and_json(capsys):
    rc, out, _ = _cli(["simulate", "--pipes", "4", "--sigma", "0.4", "--t-end", "5"], capsys)
    assert rc == 0 and "time t" in out and "kind" in out and "events" in out
    assert not out.lstrip().startswith("{")
    rc, out2, _ = _cli(["simulate", "--n", "4", "--sigma", "0.4", "--t-end", "5", "--json"],
                       capsys)
    data = json.loads(out2)
    last = out.strip().splitlines()[-1]
    assert data["pipes"] == 4 and last.startswith(f"{len(data['events'])} events")
    # the JSON states every setting of the run (the defaults included)
    assert {k: data[k] for k in ("sigma", "seed", "restitution", "t_end", "dps")} == {
        "sigma": 0.4, "seed": 0, "restitution": 0.8, "t_end": 5.0, "dps": None}


def test_cli_ensemble(capsys, tmp_path):
    path = tmp_path / "e.json"
    rc, out, err = _cli(["ensemble", "--sigmas", "0.2", "0.3", "--runs", "3", "--pipes", "8",
                         "--t-transient", "10", "--t-window", "10", "--workers", "1",
                         "--out", str(path)], capsys)
    assert rc == 0 and "mean pipes" in out and "\r" not in err
    # every mode comes with its bootstrap probability of being the mode
    assert "P(mode)" in out
    back = EnsembleResult.load(path)
    assert back.per_sigma[1].runs == 3
    rows = [line.split() for line in out.splitlines() if line[:6].strip() in ("0.200", "0.300")]
    for row, st in zip(rows, back.per_sigma, strict=True):
        if st.stats["pipes"]["mode"] is not None:
            assert float(row[-3]) == pytest.approx(st.stats["pipes"]["mode_prob"], abs=0.005)
    rc, out, err = _cli(["ensemble", "--sigmas", "0.2", "--runs", "2", "--pipes", "8",
                         "--workers", "1", "--json", "--t-transient", "5"], capsys)
    assert json.loads(out)["params"]["n"] == 8
    assert _cli(["ensemble", "--sigmas", "nan", "--runs", "2", "--workers", "1"], capsys)[0] == 2


def test_cli_ensemble_without_impacts_says_so(capsys):
    rc, out, _ = _cli(["ensemble", "--sigmas", "0", "--runs", "1", "--pipes", "3",
                       "--t-transient", "1", "--t-window", "1", "--workers", "1"], capsys)
    assert rc == 0 and "nan" not in out.lower() and "no runs with an impact" in out


def test_cli_help_has_defaults():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    for name in ("simulate", "ensemble"):
        buf = io.StringIO()
        sub.choices[name].print_help(buf)
        text = buf.getvalue()
        assert "--pipes" in text and "--n " not in text
        for action in sub.choices[name]._actions:
            if action.help and action.help != "==SUPPRESS==" and action.dest != "help":
                assert action.option_strings[0] in text
                assert "default" in (action.help % {"default": "x", "prog": "p"}) or \
                    isinstance(action.default, bool) or action.default is None or \
                    "(default:" in text


@pytest.mark.slow
def test_ensemble_on_a_dask_cluster_equals_serial_numbers(capsys):
    # a two-process dask.distributed LocalCluster through its executor (the API) and through
    # its scheduler address (the CLI): the same numbers as the serial run, bit for bit
    distributed = pytest.importorskip("distributed")
    serial = ensemble(SIGMAS, 12, chunk=5, **KW)
    argv = ["ensemble", "--sigmas", "0.2", "0.3", "--runs", "6", "--pipes", "10",
            "--t-transient", "10", "--t-window", "10", "--seed", "3", "--chunk", "2", "--json"]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        res = ensemble(SIGMAS, 12, chunk=4, executor=client.get_executor(), **KW)
        capsys.readouterr()
        # the CLI pointed at the scheduler address
        assert main([*argv, "--scheduler", cluster.scheduler_address]) == 0
        via_cli = json.loads(capsys.readouterr().out)
    assert _key(res) == _key(serial)
    assert main([*argv, "--workers", "1"]) == 0
    here = json.loads(capsys.readouterr().out)
    assert via_cli["per_sigma"] == here["per_sigma"]


def test_impact_paper_section_writes_the_quick_ensemble_and_its_table(tmp_path):
    """``symhx paper``'s impact part (quick): the ensemble saved as JSON reloads, the CSV holds
    one row per sigma with that ensemble's statistics (empty cells where no run impacts), and
    the summary names the steepest rise of the stored ensemble's mean."""
    import csv

    import numpy as np

    from symhx.commands.impact import QUICK_RUNS, QUICK_SIGMAS, paper
    from symhx.plots import stored_ensemble

    lines = paper(tmp_path, False)
    res = EnsembleResult.load(tmp_path / "ensemble_quick.json")
    assert list(res.sigmas) == list(QUICK_SIGMAS)
    assert all(s.runs == QUICK_RUNS for s in res.per_sigma)
    with open(tmp_path / "ensemble_quick.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(QUICK_SIGMAS)
    for row, s in zip(rows, res.per_sigma, strict=True):
        p = s.stats["pipes"]
        assert float(row["sigma"]) == s.sigma and int(row["runs"]) == s.runs
        if p["mean"] is None:
            assert row["mean_pipes"] == row["se_pipes"] == ""
        else:
            assert float(row["mean_pipes"]) == p["mean"] and float(row["se_pipes"]) == p["se"]
            assert float(row["mode_pipes_ci_hi"]) == p["mode_ci"][1]
    stored = stored_ensemble()
    means = stored.column("pipes", "mean")
    k = int(np.nanargmax(np.diff(means) / np.diff(stored.sigmas)))
    assert f"between sigma = {stored.sigmas[k]:g} and {stored.sigmas[k + 1]:g}" in lines[0]
    for name in ("fig7_mode_vs_sigma.png", "fig13_spaces_vs_simulation.png"):
        assert (tmp_path / name).stat().st_size > 0
