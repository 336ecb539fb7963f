"""Ensembles: counting checked against independent paths (the Python engine's event history, a
hand-counted row), reproducibility across executors/chunking/dask, failures, validation,
histogram statistics against numpy, checkpoints, the CLI and the figures."""

from __future__ import annotations

import importlib
import io
import json
import math
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

from symhx.forcing import impact_probability
from symhx.impact import IMPACT, STICK, PipeRow, simulate
from symhx.impact.ensemble import (
    EnsembleResult,
    describe_histogram,
    ensemble,
    free_flight_closure_fraction,
    pipes_and_sites,
    transition_dependence,
    window_counts,
)
from tests.reference.seeds import run_seed_ref

# the package re-exports a function named ensemble: get the module itself
E = importlib.import_module("symhx.impact.ensemble")
KW = dict(n=20, t_transient=30.0, t_window=20.0, seed=123, progress=False)
SIGMAS = [0.12, 0.2, 0.35]


def _key(res):
    return [(s.sigma, s.runs, s.excluded, s.failed, s.pipes.tolist(), s.sites.tolist(),
             s.site_hits.tolist(), s.events, s.impacts, json.dumps(s.stats, sort_keys=True))
            for s in res.per_sigma]


@pytest.fixture(scope="module")
def serial():
    return ensemble(SIGMAS, 12, chunk=5, **KW)



# ----------------------------------------------------------------- counting (issue 16)
def _hand_count(sigma, k, *, n, t_transient, t_window, seed, restitution=0.8):
    """Independent count of one run: the Python float64 engine's full event history, impacts
    (and sticking) at t >= t_transient, pipes touching an impacted gap counted by hand."""
    row = PipeRow.random(n, sigma, seed=run_seed_ref(seed, sigma, k), restitution=restitution)
    h = simulate(row, t_transient + t_window, engine="python")
    sites_hit = {int(s) for s, kind, t in zip(h.sites, h.kinds, h.times, strict=True)
                 if kind in (IMPACT, STICK) and float(t) >= t_transient}
    pipes = set()
    for s in sites_hit:          # gap s lies between pipe s (0: left wall) and pipe s + 1
        pipes.update(j for j in (s, s + 1) if 1 <= j <= n)
    ever = {int(s) for s, kind in zip(h.sites, h.kinds, strict=True) if kind in (IMPACT, STICK)}
    return len(pipes), len(sites_hit), len(ever), sites_hit


def test_counts_match_hand_count_from_the_python_engine():
    sigmas, runs = [0.13, 0.16, 0.3], 8
    kw = dict(n=12, t_transient=25.0, t_window=15.0, seed=8)   # a seed whose runs can tell
    res = ensemble(sigmas, runs, chunk=3, progress=False, **kw)
    saw_window_differs = saw_pipes_ne_sites = False
    for s, st in zip(sigmas, res.per_sigma, strict=True):
        hand = [_hand_count(s, k, **kw) for k in range(runs)]
        kept = [(p, q) for p, q, _, _ in hand if q > 0]
        assert st.pipes.tolist() == [p for p, _ in kept]
        assert st.sites.tolist() == [q for _, q in kept]
        assert st.excluded == sum(q == 0 for _, q, _, _ in hand)
        # runs with an impact at each site, and the measured rate of the pipe-pipe sites
        hits = np.zeros(kw["n"] + 1, dtype=int)
        for *_, where in hand:
            hits[sorted(where)] += 1
        assert st.site_hits.tolist() == hits.tolist()
        interior = sum(len([x for x in where if 1 <= x <= kw["n"] - 1]) for *_, where in hand)
        assert st.gap_rate(interior=True)[0] == pytest.approx(
            interior / (runs * (kw["n"] - 1)), rel=1e-12)
        saw_window_differs |= any(q != ever for _, q, ever, _ in hand)
        saw_pipes_ne_sites |= any(p != q for p, q in kept)
    # the data can tell a window starting at 0 from one at t_transient, and pipes from sites
    assert saw_window_differs and saw_pipes_ne_sites


def test_hand_counted_rows():
    # one elastic pipe, x = 1 + 2 sin t until it hits the right wall (x = 2) at pi/6; by the
    # mirror symmetry of elastic reflection it then hits the walls alternately every pi/3:
    # site 1 at pi/6 + 2k pi/3, site 0 at pi/2 + 2k pi/3
    row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    assert window_counts(row, 5.0, 5.0).tolist() == [3, 2]      # 5.76 .. 9.95
    assert pipes_and_sites(window_counts(row, 5.0, 5.0)) == (1, 2)
    assert window_counts(row, 1.0, 1.0).tolist() == [1, 0]      # only pi/2
    assert window_counts(row, 0.0, 2.0).tolist() == [1, 1]      # pi/6 and pi/2
    assert pipes_and_sites(window_counts(row, 1.0, 1.0)) == (1, 1)
    # three pipes: pipes 1-2 touch (site 1) and pipe 3 hits the right wall (site 3)
    assert pipes_and_sites([0, 4, 0, 1]) == (3, 2)
    assert pipes_and_sites([2, 0, 0, 0]) == (1, 1)
    assert pipes_and_sites([0, 1, 1, 0]) == (3, 2)


def test_site_hits_and_gap_rate_are_consistent(serial):
    for s in serial.per_sigma:
        # every kept run contributes its number of distinct sites to the per-site hit counts
        assert int(s.site_hits.sum()) == int(s.sites.sum())
        q, se = s.gap_rate(interior=False)
        assert q == pytest.approx(s.sites.sum() / (s.finished * (KW["n"] + 1)))
        assert se >= 0


# ----------------------------------------------------------------- reproducibility
def test_reproducible_across_executors_and_chunking(serial):
    with ProcessPoolExecutor(2) as ex:
        par = ensemble(SIGMAS, 12, chunk=3, executor=ex, **KW)
    with ThreadPoolExecutor(3) as ex:
        thr = ensemble(SIGMAS, 12, chunk=7, executor=ex, **KW)
    assert _key(par) == _key(serial) == _key(thr)
    other = ensemble(SIGMAS, 12, chunk=5, **{**KW, "seed": 124})
    assert _key(other) != _key(serial)


def test_dask_local_cluster_two_processes_gives_serial_numbers(serial, capsys):
    distributed = pytest.importorskip("distributed")
    from symhx.cli import main

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


# ----------------------------------------------------------------- robustness
def test_failed_runs_are_counted_not_fatal(monkeypatch):
    real = E.count_impacts
    calls = {"n": 0}

    class SimulationError(RuntimeError):
        pass

    def flaky(row, t_end, t_from, **kw):
        calls["n"] += 1
        if calls["n"] % 3 == 0:
            raise SimulationError("chatter did not end")
        return real(row, t_end, t_from, **kw)

    monkeypatch.setattr(E, "count_impacts", flaky)
    res = ensemble([0.2, 0.3], 9, chunk=4, **KW)
    assert [s.failed for s in res.per_sigma] == [3, 3]
    st = res.per_sigma[0]
    assert st.failures[0][1] == "SimulationError: chatter did not end"
    assert st.excluded + len(st.sites) + st.failed == 9
    assert st.stats["sites"]["count"] == len(st.sites) == 9 - 3 - st.excluded
    back = EnsembleResult.from_dict(json.loads(json.dumps(res.as_dict())))
    assert back.per_sigma[1].failed == 3


def test_failed_draws_are_counted():
    # sigma0 = 0: the pipes start at j d + forced(0); with strong forcing some rows overlap and
    # cannot be drawn: failed runs with the reason "draw", the others counted as usual
    res = ensemble([0.5], 12, **{**KW, "sigma0": 0.0})   # 2 of these 12 rows cannot be drawn
    st = res.per_sigma[0]
    assert 0 < st.failed < 12 and st.failures[0][1].startswith("draw: could not draw")
    assert st.failed + st.excluded + len(st.sites) == 12
    with pytest.raises(ValueError, match="resonance"):   # bad parameters: one clear error
        ensemble([0.1], 2, **{**KW, "Omega": (1.0,)})


@pytest.mark.parametrize("kw, err, match", [
    ({"t_window": math.inf}, ValueError, "t_window"),
    ({"t_transient": math.inf}, ValueError, "t_transient"),
    ({"t_transient": math.nan}, ValueError, "t_transient"),
    ({"t_window": 0.0}, ValueError, "t_window"),
    ({"t_transient": -1.0}, ValueError, "t_transient"),
    ({"seed": 2.5}, TypeError, "seed"),
    ({"seed": -1}, ValueError, "seed"),
    ({"seed": True}, TypeError, "seed"),
    ({"executor": "x"}, TypeError, "executor"),
    ({"progress": "yes"}, TypeError, "progress"),
    ({"n": True}, TypeError, "n"),
    ({"restitution": 1.5}, ValueError, "restitution"),
    ({"chunk": 0}, ValueError, "chunk"),
    ({"sigma0": [0.1, 0.2]}, ValueError, "sigma0"),
    ({"sigma0": -0.1}, ValueError, "sigma0"),
])
def test_bad_input(kw, err, match):
    with pytest.raises(err, match=match):
        ensemble([0.1], 2, **{**KW, **kw})


def test_bad_sigmas_and_runs():
    with pytest.raises(ValueError, match="sigmas"):
        ensemble([], 3, **KW)
    with pytest.raises(ValueError, match=r"sigmas\[1\]"):
        ensemble([0.1, math.nan], 3, **KW)
    with pytest.raises(ValueError, match=r"sigmas\[0\]"):
        ensemble([-0.1], 3, **KW)
    with pytest.raises(TypeError, match="sigmas"):
        ensemble(0.1, 3, **KW)
    with pytest.raises(ValueError, match="runs"):
        ensemble([0.1], 0, **KW)
    with pytest.raises(TypeError, match="runs"):
        ensemble([0.1], True, **KW)
    with pytest.raises(TypeError, match="runs"):
        ensemble([0.1], 2.0, **KW)
    with pytest.raises(ValueError, match="MAX_RUNS"):
        ensemble([0.1, 0.2], E.MAX_RUNS + 1, **KW)
    with pytest.raises(ValueError, match="MAX_TOTAL_RUNS"):
        ensemble([0.1] * (E.MAX_TOTAL_RUNS // E.MAX_RUNS + 1), E.MAX_RUNS, **KW)


# ----------------------------------------------------------------- statistics
def test_describe_histogram_against_numpy():
    rng = np.random.default_rng(5)
    values = rng.binomial(30, 0.3, size=4000)
    hist = np.bincount(values, minlength=31)
    st = describe_histogram(hist, np.random.default_rng(1))
    assert st["mean"] == pytest.approx(values.mean(), rel=1e-12)
    assert st["se"] == pytest.approx(values.std(ddof=1) / math.sqrt(len(values)), rel=1e-12)
    counts = np.bincount(values)
    assert st["mode"] == int(np.flatnonzero(counts == counts.max())[0])
    lo, hi = st["mean_ci"]     # percentile interval ~ mean +- 1.96 se for a large sample
    assert lo < st["mean"] < hi
    assert abs((hi - lo) / (2 * 1.96 * st["se"]) - 1) < 0.15
    assert st["mode_ci"][0] <= st["mode"] <= st["mode_ci"][1]
    # intervals never leave the observed values (no error bar below 0 pipes)
    st0 = describe_histogram([5, 1, 0, 0], np.random.default_rng(2))
    assert st0["mean_ci"][0] >= 0 and st0["mode_ci"] == [0, 0]
    # ties: the smallest most frequent value, as in the paper's k* = min argmax
    assert describe_histogram([0, 3, 1, 3], np.random.default_rng(0))["mode"] == 1
    empty = describe_histogram([0, 0, 0])
    assert empty["mode"] is None and empty["mean"] is None and empty["mean_ci"] == [None, None]
    one = describe_histogram([0, 1])   # a single run: no spread, so no standard errors
    assert one["mean"] == 1 and one["se"] is None and one["mode_se"] is None


def test_statistics_match_per_run_arrays(serial):
    for s in serial.per_sigma:
        kept = s.runs - s.excluded - s.failed
        assert len(s.sites) == kept and len(s.pipes) == kept
        if kept:
            st = s.stats["sites"]
            assert sum(st["hist"]) == kept
            assert st["mean"] == pytest.approx(np.mean(s.sites), rel=1e-12)
            assert st["mode"] == int(np.argmax(np.bincount(s.sites)))
            assert np.all(s.sites >= 1) and np.all(s.sites <= 21)
            assert np.all(s.pipes <= 2 * s.sites) and np.all(s.pipes >= s.sites - 1)
    back = EnsembleResult.from_dict(serial.as_dict())
    assert np.allclose(back.column("pipes", "mean"), serial.column("pipes", "mean"),
                       equal_nan=True)
    assert back.column("pipes", "mode_ci").shape == (3, 2)


def test_checkpoints_are_honest_prefixes(tmp_path, monkeypatch):
    snaps = []
    real_save = EnsembleResult.save

    def spy(self, path):
        snaps.append(json.loads(json.dumps(self.as_dict())))
        real_save(self, path)

    monkeypatch.setattr(EnsembleResult, "save", spy)
    path = tmp_path / "ens.json"
    final = ensemble(SIGMAS, 9, chunk=3, checkpoint=path, checkpoint_every=0.0, **KW)
    assert json.loads(path.read_text()) == json.loads(json.dumps(final.as_dict()))
    partial = [s for s in snaps if s["params"].get("partial")]
    assert partial
    mid = partial[len(partial) // 2]
    for i, s in enumerate(mid["per_sigma"]):
        k = s["runs"]
        assert k % 3 == 0 and k < 9
        if k:   # the prefix equals a fresh ensemble of k runs (run j is deterministic)
            fresh = ensemble(SIGMAS, k, **KW).per_sigma[i]
            assert s["sites"]["hist"] == fresh.stats["sites"]["hist"]
            assert s["excluded"] == fresh.excluded


# ----------------------------------------------------------------- assumptions
def test_transition_dependence_detects_order_and_accepts_iid():
    rng = np.random.default_rng(3)
    iid = [rng.integers(0, 10, size=300) for _ in range(5)]
    res = transition_dependence(iid, 10, shuffles=40, seed=1)
    assert abs(res["z"]) < 4
    assert abs(res["same"] - 0.1) < 0.05
    walk = [np.cumsum(rng.choice([-1, 1], size=400)) % 10 for _ in range(3)]
    dep = transition_dependence(walk, 10, shuffles=40, seed=1)
    # |step| = 1 except across the wrap 9 <-> 0 (probability 1/5)
    assert dep["z"] > 10 and dep["adjacent"] > 0.7 > 0.3 > dep["adjacent_null"]


@pytest.mark.parametrize("sigma", [0.2, 0.3])
def test_free_flight_closure_fraction_approaches_impact_probability(sigma):
    gaps = 3000
    f = free_flight_closure_fraction(sigma, gaps, horizon=600.0, seed=7)
    p = float(impact_probability(sigma))
    se = math.sqrt(p * (1 - p) / gaps)
    assert abs(f - p) < 4 * se


# ----------------------------------------------------------------- CLI and figures
def _cli(argv, capsys):
    from symhx.cli import main

    rc = main(argv)
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_cli_simulate_table_and_json(capsys):
    rc, out, _ = _cli(["simulate", "--pipes", "4", "--sigma", "0.4", "--t-end", "5"], capsys)
    assert rc == 0 and "time t" in out and "kind" in out and "events" in out
    assert not out.lstrip().startswith("{")
    rc, out2, _ = _cli(["simulate", "--n", "4", "--sigma", "0.4", "--t-end", "5", "--json"],
                       capsys)
    data = json.loads(out2)
    last = out.strip().splitlines()[-1]
    assert data["pipes"] == 4 and last.startswith(f"{len(data['events'])} events")


def test_cli_ensemble(capsys, tmp_path):
    path = tmp_path / "e.json"
    rc, out, err = _cli(["ensemble", "--sigmas", "0.2", "0.3", "--runs", "3", "--pipes", "8",
                         "--t-transient", "10", "--t-window", "10", "--workers", "1",
                         "--out", str(path)], capsys)
    assert rc == 0 and "mean pipes" in out and "\r" not in err
    assert EnsembleResult.load(path).per_sigma[1].runs == 3
    rc, out, err = _cli(["ensemble", "--sigmas", "0.2", "--runs", "2", "--pipes", "8",
                         "--workers", "1", "--json", "--t-transient", "5"], capsys)
    assert json.loads(out)["params"]["n"] == 8
    assert _cli(["ensemble", "--sigmas", "nan", "--runs", "2", "--workers", "1"], capsys)[0] == 2


def test_cli_help_has_defaults():
    from symhx.cli import build_parser

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


def test_figures_have_legends_and_nonnegative_error_bars(serial):
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    import matplotlib.pyplot as plt

    from symhx import plots

    for f in (plots.plot_mode_vs_sigma, plots.plot_mean_vs_sigma,
              plots.plot_theory_vs_simulation):
        fig = f(serial)
        for ax in fig.axes:
            assert ax.get_legend() is not None
            assert ax.get_ylim()[0] >= 0
        plt.close(fig)
    mode, err = plots.impact._yerr(serial, "pipes", "mode")
    ok = np.isfinite(mode)
    assert np.all(mode[ok] - err[0][ok] >= 0) and np.all(err[:, ok] >= 0)


# ----------------------------------------------------------------- fuzz round (issue 12)
def test_caps_and_horizons_refused_up_front():
    from symhx.impact.model import MAX_HORIZON, MAX_PIPES

    for kw, match in ((dict(n=MAX_PIPES + 1), "MAX_PIPES"),
                      (dict(t_transient=MAX_HORIZON), "MAX_HORIZON"),
                      (dict(t_window=1e308), "MAX_HORIZON"),
                      (dict(t_window=10**1000), "MAX_HORIZON"),
                      (dict(t_transient=10**1000), "MAX_HORIZON"),
                      (dict(t_window=5e-324), "too short"),
                      (dict(t_window="1e-400"), "t_window")):
        with pytest.raises(ValueError, match=match):
            ensemble([0.3], 2, **{**KW, **kw})


def test_no_impact_statistics_are_none_not_nan(capsys):
    # sigma = 0 and sigma0 = 0: every pipe rests at j d, no run has an impact in the window
    res = ensemble([0.0], 3, **{**KW, "sigma0": 0.0, "progress": None})
    st = res.per_sigma[0]
    assert st.excluded == 3 and st.failed == 0
    for what in ("pipes", "sites"):
        assert st.stats[what]["mean"] is None and st.stats[what]["mode"] is None
    assert np.isnan(res.column("pipes", "mean")).all()   # documented: NaN in the plotting column
    rc, out, _ = _cli(["ensemble", "--sigmas", "0", "--runs", "1", "--pipes", "3",
                       "--t-transient", "1", "--t-window", "1", "--workers", "1"], capsys)
    assert rc == 0 and "nan" not in out.lower() and "no runs with an impact" in out


def test_free_flight_closure_fraction_validates():
    ff = free_flight_closure_fraction
    for kw, exc in ((dict(sigma=math.nan), ValueError), (dict(sigma=0), ValueError),
                    (dict(sigma=True), TypeError), (dict(sigma=1e300), ValueError),
                    (dict(gaps=0), ValueError), (dict(gaps=True), TypeError),
                    (dict(gaps=E.MAX_GAPS + 1), ValueError), (dict(horizon=0), ValueError),
                    (dict(horizon=math.inf), ValueError), (dict(horizon=10**1000), ValueError),
                    (dict(seed=True), TypeError), (dict(seed=[]), TypeError),
                    (dict(Omega=1.0), ValueError)):
        args = {"sigma": 0.3, "gaps": 3, "horizon": 10.0, **kw}
        with pytest.raises(exc, match=next(iter(kw))):
            ff(**args)
