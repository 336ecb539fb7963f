"""``symhx.impact.ensemble``: counting runs (against every run's full event history from the
pure-Python engine, counted by hand in ``tests.reference.impact``), reproducibility on any
executor and chunking, seeds keyed by sigma, failed runs, checkpoints, progress, parameters and
refusals.  The statistics have ``test_ensemble_statistics.py``; the assumption checks (site
sequences, free flight) ``test_ensemble_assumptions.py``."""

from __future__ import annotations

import importlib
import inspect
import json
import math
from concurrent.futures import Executor, Future, ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

from symhx.impact import PipeRow, simulate
from symhx.impact.ensemble import (
    EnsembleResult,
    ensemble,
    free_flight_closure_fraction,
    pipes_and_sites,
    run_chunk,
    run_seed,
    sigma_key,
    site_transitions,
    thresholds,
    transition_dependence,
    window_counts,
)
from symhx.impact.model import MAX_HORIZON, MAX_PIPES, SQRT2, SimulationError
from tests.harness.errors import assert_refuses
from tests.reference.impact import count_by_hand
from tests.reference.seeds import run_seed_ref

# the package re-exports a function named ensemble: get the module itself
E = importlib.import_module("symhx.impact.ensemble")

# a small ensemble with every model parameter away from its default
MODEL = dict(restitution=0.5, omega=1.3, d=1.2, Omega=(0.7,))
KW = dict(n=6, t_transient=6.0, t_window=5.0, seed=7, progress=False, **MODEL)
SIGMAS = [0.22, 0.4]
SIGMA0 = [0.3, 0.25]
RUNS = 5
# a larger one at the defaults of the model
KW20 = dict(n=20, t_transient=30.0, t_window=20.0, seed=123, progress=False)
SIGMAS20 = [0.12, 0.2, 0.35]


def _hand(sigma, k, *, n, t_transient, t_window, seed, sigma0=None, restitution=0.8, omega=1.0,
          d=1.0, Omega=(SQRT2,)):
    """One run counted by hand from the Python engine's full history."""
    row = PipeRow.random(n, sigma, seed=run_seed_ref(seed, sigma, k), restitution=restitution,
                         omega=omega, d=d, Omega=Omega, sigma0=sigma0)
    h = simulate(row, t_transient + t_window, engine="python")
    return count_by_hand(h.times, h.sites, h.kinds, n, t_transient)


def _key(res):
    return [(s.sigma, s.runs, s.excluded, s.failed, s.pipes.tolist(), s.sites.tolist(),
             s.site_hits.tolist(), s.events, s.impacts, json.dumps(s.stats, sort_keys=True))
            for s in res.per_sigma]


# function scope on purpose: mutation testing credits a function to the tests that run it, and a
# module-scoped fixture runs inside the first test only
@pytest.fixture
def hand():
    kw = {k: v for k, v in KW.items() if k != "progress"}
    return [[_hand(s, k, sigma0=SIGMA0[i], **kw) for k in range(RUNS)]
            for i, s in enumerate(SIGMAS)]


@pytest.fixture
def res():
    return ensemble(SIGMAS, RUNS, chunk=2, sigma0=SIGMA0, **KW)


@pytest.fixture(scope="module")
def serial():
    return ensemble(SIGMAS20, 12, chunk=5, **KW20)


# ----------------------------------------------------------------- counting
def test_ensemble_counts_equal_hand_counts(res, hand):
    saw_window = saw_pipes = False
    for i, st in enumerate(res.per_sigma):
        runs = hand[i]
        kept = [r for r in runs if r["sites"] > 0]
        assert st.sigma == SIGMAS[i] and st.runs == RUNS and st.failed == 0
        assert st.failures == []
        assert st.pipes.tolist() == [r["pipes"] for r in kept]
        assert st.sites.tolist() == [r["sites"] for r in kept]
        assert st.excluded == RUNS - len(kept)
        assert st.impacts == sum(r["impacts"] for r in runs)
        assert st.events == sum(r["events"] for r in runs)
        hits = np.zeros(KW["n"] + 1, dtype=int)
        for r in runs:
            hits[sorted(r["where"])] += 1
        assert st.site_hits.tolist() == hits.tolist()
        for what in ("pipes", "sites"):
            vals = np.array([r[what] for r in kept])
            s = st.stats[what]
            assert s["count"] == len(kept)
            assert len(s["hist"]) == KW["n"] + (1 if what == "pipes" else 2)
            assert s["hist"] == np.bincount(vals, minlength=len(s["hist"])).tolist()
            if len(kept):
                assert s["mean"] == pytest.approx(vals.mean(), rel=1e-12)
        saw_window |= any(r["ever"] != r["where"] for r in runs)
        saw_pipes |= any(r["pipes"] != r["sites"] for r in kept)
    assert saw_window and saw_pipes     # the data tells the window and pipes/sites apart
    assert sum(st.excluded for st in res.per_sigma) > 0
    assert res.params == {
        "runs": RUNS, "n": 6, "t_transient": 6.0, "t_window": 5.0, "seed": 7,
        "restitution": 0.5, "omega": 1.3, "d": 1.2, "Omega": ["0.7"], "sigma0": SIGMA0,
        "chunk": 2, "engine": "float64 C" if E._c_available() else "float64 python"}
    assert res.seconds >= 0


def test_counts_match_hand_count_at_the_default_model():
    sigmas, runs = [0.13, 0.16, 0.3], 8
    kw = dict(n=12, t_transient=25.0, t_window=15.0, seed=8)   # a seed whose runs can tell
    res = ensemble(sigmas, runs, chunk=3, progress=False, **kw)
    saw_window_differs = saw_pipes_ne_sites = False
    for s, st in zip(sigmas, res.per_sigma, strict=True):
        hand = [_hand(s, k, **kw) for k in range(runs)]
        kept = [r for r in hand if r["sites"] > 0]
        assert st.pipes.tolist() == [r["pipes"] for r in kept]
        assert st.sites.tolist() == [r["sites"] for r in kept]
        assert st.excluded == sum(r["sites"] == 0 for r in hand)
        # runs with an impact at each site, and the measured rate of the pipe-pipe sites
        hits = np.zeros(kw["n"] + 1, dtype=int)
        for r in hand:
            hits[sorted(r["where"])] += 1
        assert st.site_hits.tolist() == hits.tolist()
        interior = sum(len([x for x in r["where"] if 1 <= x <= kw["n"] - 1]) for r in hand)
        assert st.gap_rate(interior=True)[0] == pytest.approx(
            interior / (runs * (kw["n"] - 1)), rel=1e-12)
        saw_window_differs |= any(r["sites"] != len(r["ever"]) for r in hand)
        saw_pipes_ne_sites |= any(r["pipes"] != r["sites"] for r in kept)
    # the data can tell a window starting at 0 from one at t_transient, and pipes from sites
    assert saw_window_differs and saw_pipes_ne_sites


def test_run_chunk_equals_hand_counts(hand):
    kw = {k: v for k, v in KW.items() if k not in ("progress", "n", "t_transient", "t_window",
                                                      "seed")}
    out = run_chunk(SIGMAS[1], [3, 1, 4], 6, 6.0, 5.0, KW["seed"], sigma0=SIGMA0[1], **kw)
    runs = [hand[1][k] for k in (3, 1, 4)]
    assert out["pipes"].tolist() == [r["pipes"] for r in runs]
    assert out["sites"].tolist() == [r["sites"] for r in runs]
    assert out["impacts"].tolist() == [r["impacts"] for r in runs]
    assert out["events"] == sum(r["events"] for r in runs) and out["failures"] == []
    hits = np.zeros(7, dtype=int)
    for r in runs:
        hits[sorted(r["where"])] += 1
    assert out["site_hits"].tolist() == hits.tolist()
    assert {k: v.dtype for k, v in out.items() if isinstance(v, np.ndarray)} == {
        "pipes": np.int64, "sites": np.int64, "impacts": np.int64, "site_hits": np.int64}


def test_window_counts_hand_counted_row():
    # one elastic pipe, x = 1 + 2 sin t: walls at pi/6 + 2k pi/3 (site 1), pi/2 + 2k pi/3 (0)
    row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    t1 = [math.pi / 6 + 2 * k * math.pi / 3 for k in range(20)]
    t0 = [math.pi / 2 + 2 * k * math.pi / 3 for k in range(20)]
    for a, w in ((5.0, 5.0), (1.0, 1.0), (0.0, 2.0), (2.0, 0.5), (0.6, 3.0)):
        ref = [sum(a <= t <= a + w for t in t0), sum(a <= t <= a + w for t in t1)]
        got = window_counts(row, a, w)
        assert got.tolist() == ref and got.dtype == np.int64


def test_window_counts_chatter_with_the_default_threshold():
    # a constant force (Omega = 0) presses one pipe into the right wall: with y = 2.5 - x the
    # motion is y'' = -y, the wall at y = 1/2; released at rest from y = 1 it reaches the wall
    # at t = pi/3 with speed u0 = sqrt(3)/2, and after an impact leaving at speed u it returns
    # after 2 atan(u / (1/2)).  Bounces continue while the speed after the bounce exceeds the
    # default float64 threshold v_stick = 1e-6 omega d; then the pipe sticks (one STICK event,
    # counted as an impact at that site).
    row = PipeRow(1, restitution=0.5, Omega=(0,), alpha=[[1.5]], beta=[[0.0]], x0=[1.5],
                  v0=[0.0])
    u0, r, vs = math.sqrt(3) / 2, 0.5, 1e-6
    times, t, u = [], math.pi / 3, u0
    while True:
        times.append(t)
        u *= r
        if u <= vs:
            break
        t += 2 * math.atan(u / 0.5)
    assert len(times) == 20
    assert window_counts(row, 0.0, 10.0).tolist() == [0, len(times) + 1]
    for a in (1.0, 2.5, 3.2):
        ref = sum(t >= a for t in times) + 1          # the stick happens at the last bounce
        assert window_counts(row, a, 10.0 - a).tolist() == [0, ref]
    assert window_counts(row, 0.0, 1.1).tolist() == [0, 1]     # only the first bounce


def test_pipes_and_sites_by_hand():
    rng = np.random.default_rng(4)
    for _ in range(200):
        n = int(rng.integers(1, 8))
        counts = rng.integers(0, 3, size=n + 1) * (rng.random(n + 1) < 0.4)
        sites = {i for i in range(n + 1) if counts[i]}
        pipes = {j for i in sites for j in (i, i + 1) if 1 <= j <= n}
        assert pipes_and_sites(counts) == (len(pipes), len(sites))
        assert pipes_and_sites(list(counts)) == (len(pipes), len(sites))
    assert pipes_and_sites([3, 0]) == (1, 1) and pipes_and_sites([0, 0, 1]) == (1, 1)
    # one pipe hitting both walls; pipes 1-2 touching and pipe 3 on the right wall; ...
    assert pipes_and_sites([3, 2]) == (1, 2) and pipes_and_sites([1, 0]) == (1, 1)
    assert pipes_and_sites([0, 4, 0, 1]) == (3, 2)
    assert pipes_and_sites([2, 0, 0, 0]) == (1, 1)
    assert pipes_and_sites([0, 1, 1, 0]) == (3, 2)


def test_site_hits_and_gap_rate_are_consistent(serial):
    for s in serial.per_sigma:
        # every kept run contributes its number of distinct sites to the per-site hit counts
        assert int(s.site_hits.sum()) == int(s.sites.sum())
        q, se = s.gap_rate(interior=False)
        assert q == pytest.approx(s.sites.sum() / (s.finished * (KW20["n"] + 1)))
        assert se >= 0


# ----------------------------------------------------------------- reproducibility
def test_reproducible_across_executors_and_chunking(serial):
    with ProcessPoolExecutor(2) as ex:
        par = ensemble(SIGMAS20, 12, chunk=3, executor=ex, **KW20)
    with ThreadPoolExecutor(3) as ex:
        thr = ensemble(SIGMAS20, 12, chunk=7, executor=ex, **KW20)
    assert _key(par) == _key(serial) == _key(thr)
    other = ensemble(SIGMAS20, 12, chunk=5, **{**KW20, "seed": 124})
    assert _key(other) != _key(serial)


def test_keep_runs_false_and_executors(res):
    light = ensemble(SIGMAS, RUNS, chunk=3, sigma0=SIGMA0, keep_runs=False, **KW)
    with ThreadPoolExecutor(2) as ex:
        thr = ensemble(SIGMAS, RUNS, chunk=1, sigma0=SIGMA0, executor=ex, **KW)
    for a, b, c in zip(res.per_sigma, light.per_sigma, thr.per_sigma, strict=True):
        assert a.stats == b.stats == c.stats and a.site_hits.tolist() == b.site_hits.tolist()
        assert len(b.pipes) == len(b.sites) == 0 and b.pipes.dtype == np.int64
        assert b.sites.dtype == np.int64
        assert c.pipes.tolist() == a.pipes.tolist() and c.events == a.events
        assert (a.impacts, a.excluded) == (b.impacts, b.excluded) == (c.impacts, c.excluded)


class _Reversed(Executor):
    """Runs each task at once but hands the futures back in reverse order."""

    def submit(self, fn, *args, **kwargs):
        f = Future()
        f.set_result(fn(*args, **kwargs))
        return f


def test_any_executor_and_completion_order(res, monkeypatch):
    monkeypatch.setattr(E, "as_completed", lambda futs: list(futs)[::-1])
    out = ensemble(SIGMAS, RUNS, chunk=2, sigma0=SIGMA0, executor=_Reversed(), **KW)
    assert [s.stats for s in out.per_sigma] == [s.stats for s in res.per_sigma]
    assert [s.pipes.tolist() for s in out.per_sigma] == [s.pipes.tolist() for s in res.per_sigma]


def test_sigma_key_and_run_seed_are_the_documented_formula():
    assert sigma_key(0.0) == sigma_key(-0.0) == 0
    assert sigma_key(1.0) == 0x3FF0000000000000 and sigma_key(2.0) == 0x4000000000000000
    assert sigma_key(np.nextafter(0.3, 1.0)) == sigma_key(0.3) + 1
    assert sigma_key(np.float32(0.5)) == sigma_key(0.5) and sigma_key(1) == sigma_key(1.0)
    for seed, sigma, k in ((0, 0.16, 0), (9, 0.3, 11), (2**70, 5e-324, 3)):
        ref = run_seed_ref(seed, sigma, k)
        got = run_seed(seed, sigma, k)
        assert got.entropy == ref.entropy
        assert np.array_equal(got.generate_state(4), ref.generate_state(4))


def test_rows_of_a_sigma_do_not_depend_on_the_grid():
    # the point of keying the seed by sigma: one column of a stored grid can be recomputed alone
    kw = dict(n=5, t_transient=2.0, t_window=4.0, seed=9, progress=False)
    both = ensemble([0.3, 0.5], 12, chunk=5, **kw)
    alone = ensemble([0.5], 12, chunk=7, **kw)
    other = ensemble([0.5, 0.2, 0.3], 12, chunk=4, **kw)
    pairs = ((alone.per_sigma[0], both.per_sigma[1]), (other.per_sigma[0], both.per_sigma[1]),
             (other.per_sigma[2], both.per_sigma[0]))
    for st, ref in pairs:
        assert st.sigma == ref.sigma and st.stats == ref.stats
        assert (st.pipes.tolist(), st.sites.tolist(), st.site_hits.tolist()) == (
            ref.pipes.tolist(), ref.sites.tolist(), ref.site_hits.tolist())
        assert (st.events, st.impacts, st.excluded) == (ref.events, ref.impacts, ref.excluded)
    assert both.per_sigma[0].pipes.tolist() != both.per_sigma[1].pipes.tolist()
    # neighbouring floats are different forcings with different rows
    a = PipeRow.random(5, 0.3, seed=run_seed(9, 0.3, 0))
    b = PipeRow.random(5, 0.3, seed=run_seed(9, np.nextafter(0.3, 1.0), 0))
    assert not np.array_equal(a.x0, b.x0)
    # site_transitions draws the same rows as the ensemble at any sigma of its grid
    seqs = site_transitions(0.5, 3, n=5, t_transient=2.0, t_window=4.0, seed=9)
    kept = [len(set(q.tolist())) for q in seqs if len(q)]
    assert kept == both.per_sigma[1].sites.tolist()[: len(kept)]


# ----------------------------------------------------------------- failures and options
def test_failed_runs_are_counted_not_fatal(monkeypatch):
    real = E.count_impacts
    calls = {"n": 0}

    def flaky(row, t_end, t_from, **kw):
        calls["n"] += 1
        if calls["n"] % 3 == 0:
            raise SimulationError("chatter did not end")
        return real(row, t_end, t_from, **kw)

    monkeypatch.setattr(E, "count_impacts", flaky)
    res = ensemble([0.2, 0.3], 9, chunk=4, **KW20)
    assert [s.failed for s in res.per_sigma] == [3, 3]
    st = res.per_sigma[0]
    assert st.failures[0][1] == "SimulationError: chatter did not end"
    assert st.excluded + len(st.sites) + st.failed == 9
    assert st.stats["sites"]["count"] == len(st.sites) == 9 - 3 - st.excluded
    back = EnsembleResult.from_dict(json.loads(json.dumps(res.as_dict())))
    assert back.per_sigma[1].failed == 3


def test_failures_recorded_with_reasons_and_capped(monkeypatch):
    calls = {"n": 0}
    real = E.count_impacts

    def flaky(row, t_end, t_from, **kw):
        calls["n"] += 1
        if calls["n"] % 2 == 0:
            raise SimulationError(f"stuck {calls['n']}" + "x" * 400)
        return real(row, t_end, t_from, **kw)

    monkeypatch.setattr(E, "count_impacts", flaky)
    res = ensemble([0.3], 50, chunk=7, **{**KW, "n": 3})
    st = res.per_sigma[0]
    assert st.failed == 25 and len(st.failures) == 20 and st.finished == 25
    run, reason = st.failures[0]
    assert run == 1 and reason.startswith("SimulationError: stuck 2xx") and len(reason) == 300
    assert [f[0] for f in st.failures] == list(range(1, 40, 2))
    assert st.excluded + len(st.sites) == 25 == st.stats["sites"]["count"] + st.excluded
    assert st.impacts >= 0 and np.all(st.site_hits <= 25)
    out = run_chunk(0.3, [0, 1], 3, 1.0, 1.0, 0, 0.8, 1.0, 1.0, (SQRT2,))
    assert out["pipes"].tolist()[1] == out["sites"].tolist()[1] == -1
    assert out["impacts"].tolist()[1] == -1


def test_failed_draws_are_counted():
    # sigma0 = 0: the pipes start at j d + forced(0); with strong forcing some rows overlap and
    # cannot be drawn: failed runs with the reason "draw", the others counted as usual
    res = ensemble([0.5], 12, **{**KW20, "sigma0": 0.0})   # 2 of these 12 rows cannot be drawn
    st = res.per_sigma[0]
    assert 0 < st.failed < 12 and st.failures[0][1].startswith("draw: could not draw")
    assert st.failed + st.excluded + len(st.sites) == 12
    # bad parameters: one clear error
    assert_refuses(ensemble, [0.1], 2, **{**KW20, "Omega": (1.0,)}, arg="Omega[0]",
                   allowed="resonance")


def test_failed_draws_are_named_draw():
    # sigma0 = 0: the pipes start at j d + forced(0); some rows overlap and cannot be drawn
    out = run_chunk(2.0, list(range(6)), 6, 1.0, 1.0, 0, 0.8, 1.0, 1.0, (1.05,), 0.0)
    assert out["failures"]
    for run, reason in out["failures"]:
        assert reason.startswith("draw: could not draw non-overlapping")
        k = list(range(6)).index(run)
        assert out["pipes"][k] == out["sites"][k] == out["impacts"][k] == -1


def test_defaults_recorded_in_params():
    # sigma = sigma0 = 0: every pipe rests at j d, no impact (cheap even at the default n = 100)
    res = ensemble([0.0], 1, sigma0=0.0, progress=False)
    assert res.params == {
        "runs": 1, "n": 100, "t_transient": 200.0, "t_window": 100.0, "seed": 0,
        "restitution": 0.8, "omega": 1.0, "d": 1.0, "Omega": ["sqrt(2)"], "sigma0": [0.0],
        "chunk": 50, "engine": res.params["engine"]}
    st = res.per_sigma[0]
    assert (st.excluded, st.failed, st.events, st.impacts, len(st.site_hits)) == (1, 0, 0, 0, 101)
    assert ensemble([0.0], 1, sigma0=0.0, progress=False, n=2).params["sigma0"] == [0.0]
    assert ensemble([0.1], 1, progress=False, n=2, t_transient=1,
                    t_window=1).params["sigma0"] == "sigma"


def test_documented_defaults():
    def defaults(f):
        return {k: p.default for k, p in inspect.signature(f).parameters.items()
                if p.default is not inspect.Parameter.empty}

    assert defaults(ensemble) == {
        "n": 100, "t_transient": 200.0, "t_window": 100.0, "seed": 0, "executor": None,
        "progress": None, "restitution": 0.8, "omega": 1.0, "d": 1.0, "Omega": (SQRT2,),
        "sigma0": None, "chunk": 50, "checkpoint": None, "checkpoint_every": 60.0,
        "keep_runs": True}
    assert defaults(site_transitions) == {
        "n": 100, "t_transient": 200.0, "t_window": 100.0, "seed": 0, "restitution": 0.8,
        "sigma0": None}
    assert defaults(thresholds) == {"level": 10, "min_kept": 20, "boot": 400, "seed": 0}
    assert defaults(free_flight_closure_fraction) == {
        "horizon": 400.0, "seed": 0, "omega": 1.0, "d": 1.0, "Omega": math.sqrt(2)}
    assert defaults(transition_dependence) == {"shuffles": 50, "seed": 0, "stat": None}
    assert defaults(E.describe_histogram) == {"rng": None, "boot": 2000}


def test_no_impact_statistics_are_none_not_nan():
    # sigma = 0 and sigma0 = 0: every pipe rests at j d, no run has an impact in the window
    res = ensemble([0.0], 3, **{**KW20, "sigma0": 0.0, "progress": None})
    st = res.per_sigma[0]
    assert st.excluded == 3 and st.failed == 0
    for what in ("pipes", "sites"):
        assert st.stats[what]["mean"] is None and st.stats[what]["mode"] is None
        assert st.stats[what]["mode_prob"] is None
    assert np.isnan(res.column("pipes", "mean")).all()   # documented: NaN in the plotting column


def test_sigma0_forms(hand):
    one = ensemble(SIGMAS, 3, sigma0=0.3, **KW)
    assert one.params["sigma0"] == [0.3, 0.3]
    assert one.per_sigma[0].pipes.tolist() == [r["pipes"] for r in hand[0][:3] if r["sites"]]
    arr = ensemble(SIGMAS, 2, sigma0=np.array(SIGMA0), **KW)
    assert arr.params["sigma0"] == SIGMA0
    scalar_omega = ensemble([0.3], 2, **{**KW, "Omega": 0.7})
    assert scalar_omega.params["Omega"] == ["0.7"]
    assert ensemble([0.3], 1, **{**KW, "Omega": (SQRT2,)}).params["Omega"] == ["sqrt(2)"]


def test_model_parameters_checked_up_front_with_their_values():
    # the up-front check uses the given omega and d (resonance at omega = 2, walls at 3 d)
    assert_refuses(ensemble, [0.1], 2, **{**KW, "omega": 2.0, "Omega": (2.0,)},
                   arg=["Omega[0]", "omega"], value="Omega[0] = 2.0",
                   allowed=["omega = 2.0", "resonance"])
    res = ensemble([0.0], 1, **{**KW, "d": 3.0, "sigma0": 0.0})
    assert res.params["d"] == 3.0 and res.per_sigma[0].failed == 0


def test_engine_name_and_seconds(monkeypatch):
    monkeypatch.setattr(E, "_c_available", lambda: False)
    res = ensemble([0.0], 1, **{**KW, "sigma0": 0.0})
    assert res.params["engine"] == "float64 python"
    monkeypatch.undo()

    class Clock:
        now = 1e9

        def time(self):
            self.now += 60.0
            return self.now

    monkeypatch.setattr(E, "time", Clock())
    res = ensemble([0.0], 2, chunk=1, **{**KW, "sigma0": 0.0})
    assert 0 < res.seconds <= 600 and res.seconds % 60 == 0


# ----------------------------------------------------------------- checkpoints and progress
def test_checkpoints_are_honest_prefixes(tmp_path, monkeypatch):
    snaps = []
    real_save = EnsembleResult.save

    def spy(self, path):
        snaps.append(json.loads(json.dumps(self.as_dict())))
        real_save(self, path)

    monkeypatch.setattr(EnsembleResult, "save", spy)
    path = tmp_path / "ens.json"
    final = ensemble(SIGMAS20, 9, chunk=3, checkpoint=path, checkpoint_every=0.0, **KW20)
    assert json.loads(path.read_text()) == json.loads(json.dumps(final.as_dict()))
    partial = [s for s in snaps if s["params"].get("partial")]
    assert partial
    mid = partial[len(partial) // 2]
    for i, s in enumerate(mid["per_sigma"]):
        k = s["runs"]
        assert k % 3 == 0 and k < 9
        if k:   # the prefix equals a fresh ensemble of k runs (run j is deterministic)
            fresh = ensemble(SIGMAS20, k, **KW20).per_sigma[i]
            assert s["sites"]["hist"] == fresh.stats["sites"]["hist"]
            assert s["excluded"] == fresh.excluded


def test_checkpoints_follow_the_clock(tmp_path, monkeypatch):
    saves = []
    real_save = EnsembleResult.save

    def spy(self, path):
        saves.append(self.as_dict())
        real_save(self, path)

    class Clock:
        now = 1000.0

        def time(self):
            self.now += 30.0
            return self.now

    monkeypatch.setattr(EnsembleResult, "save", spy)
    monkeypatch.setattr(E, "time", Clock())
    path = tmp_path / "c.json"
    final = ensemble([0.3, 0.4], 4, chunk=1, checkpoint=path, checkpoint_every=60, **KW)
    # the clock advances 30 s per reading: a partial save at every second store (>= 60 s)
    partial = [s for s in saves if s["params"].get("partial")]
    assert len(partial) == 4 and not saves[-1]["params"].get("partial")
    assert [s["params"]["runs"] for s in partial] == [1, 2, 3, 4]
    assert json.loads(path.read_text()) == json.loads(json.dumps(final.as_dict()))
    assert final.params.get("partial") is None and final.params["runs"] == 4
    saves.clear()
    Clock.now = 0.0
    ensemble([0.3], 3, chunk=1, checkpoint=path, **KW)     # default: every 60 s
    assert len(saves) == 2
    saves.clear()
    ensemble([0.3], 3, chunk=1, checkpoint=None, **KW)
    assert saves == []


def test_default_checkpoint_interval_is_60_seconds(tmp_path, monkeypatch):
    saves = []
    real_save = EnsembleResult.save

    def spy(self, path):
        saves.append(self.as_dict()["params"].get("partial", False))
        real_save(self, path)

    class Clock:
        now = 0.0

        def time(self):       # 60 s between readings: every store is due with the default
            self.now += 60.0
            return self.now

    monkeypatch.setattr(EnsembleResult, "save", spy)
    monkeypatch.setattr(E, "time", Clock())
    ensemble([0.3], 3, chunk=1, checkpoint=tmp_path / "c.json", **KW)
    assert saves == [True, True, True, False]


def test_partial_snapshots_with_chunks_out_of_order(tmp_path, monkeypatch):
    saves = []
    real_save = EnsembleResult.save

    def spy(self, path):
        saves.append(self.as_dict())
        real_save(self, path)

    monkeypatch.setattr(EnsembleResult, "save", spy)
    monkeypatch.setattr(E, "as_completed", lambda futs: list(futs)[::-1])
    final = ensemble([0.3, 0.4], 4, chunk=1, executor=_Reversed(), checkpoint=tmp_path / "p.json",
                     checkpoint_every=0.0, **KW)
    partial = [s for s in saves if s["params"].get("partial")]
    # chunks come back last first: no prefix is complete until chunk 0 of that sigma is in
    assert [s["params"]["runs"] for s in partial][:6] == [0] * 6
    assert [p["runs"] for p in partial[6]["per_sigma"]] == [0, 4]      # sigma 1 complete
    assert final.params["runs"] == 4 and [s.runs for s in final.per_sigma] == [4, 4]


def test_progress_bar(monkeypatch):
    bar = E._make_progress(12, True)
    assert (bar.total, bar.unit, bar.desc, bar.disable) == (12, "run", "ensemble", False)
    bar.close()
    assert E._make_progress(3, False).disable is True

    class Tty:
        def __init__(self, tty):
            self.tty = tty

        def isatty(self):
            return self.tty

        def write(self, s):
            return len(s)

        def flush(self):
            pass

    monkeypatch.setattr(E.sys, "stderr", Tty(False))
    assert E._make_progress(3, None).disable is True
    monkeypatch.setattr(E.sys, "stderr", Tty(True))
    b = E._make_progress(3, None)
    assert b.disable is False and b.fp is not None
    b.close()
    updates = []

    class Bar:
        def update(self, k):
            updates.append(k)

        def close(self):
            updates.append("closed")

    monkeypatch.setattr(E, "_make_progress", lambda total, progress: updates.append(
        (total, progress)) or Bar())
    ensemble([0.3, 0.2], 5, chunk=2, **{**KW, "progress": True})
    assert updates[0] == (10, True) and updates[-1] == "closed"
    assert sorted(updates[1:-1]) == [1, 1, 2, 2, 2, 2]


def test_progress_bar_resizes_and_gap_cap(monkeypatch):
    bar = E._make_progress(3, True)
    assert callable(bar.dynamic_ncols)       # dynamic_ncols=True: the width follows the terminal
    bar.close()
    monkeypatch.setattr(E, "MAX_GAPS", 3)
    assert free_flight_closure_fraction(0.3, 3, horizon=5.0) in (0, 1 / 3, 2 / 3, 1)
    assert_refuses(free_flight_closure_fraction, 0.3, 4, horizon=5.0, arg="gaps", value="4",
                   allowed="<= 3")


# ----------------------------------------------------------------- caps and refusals
def test_caps_are_inclusive(monkeypatch):
    monkeypatch.setattr(E, "MAX_RUNS", 2)
    monkeypatch.setattr(E, "MAX_TOTAL_RUNS", 4)
    res = ensemble([0.0, 0.0], 2, n=2, t_transient=1, t_window=1, sigma0=0.0, progress=False)
    assert [s.runs for s in res.per_sigma] == [2, 2]
    assert_refuses(ensemble, [0.0], 3, n=2, t_transient=1, t_window=1, sigma0=0.0,
                   progress=False, arg="runs", value="3", allowed="<= 2 per sigma")
    assert_refuses(ensemble, [0.0] * 3, 2, n=2, t_transient=1, t_window=1, sigma0=0.0,
                   progress=False, arg="runs", value="len(sigmas) * runs = 6",
                   allowed="MAX_TOTAL_RUNS = 4")


def test_caps_and_horizons_refused_up_front():
    for kw, arg, allowed in ((dict(n=MAX_PIPES + 1), "n", "MAX_PIPES"),
                             (dict(t_transient=MAX_HORIZON), "(t_transient + t_window)",
                              "MAX_HORIZON"),
                             (dict(t_window=1e308), "t_window", "MAX_HORIZON"),
                             (dict(t_window=10**1000), "t_window", "MAX_HORIZON"),
                             (dict(t_transient=10**1000), "t_transient", "MAX_HORIZON"),
                             (dict(t_window=5e-324), "t_window", "too short"),
                             (dict(t_window="1e-400"), "t_window", None)):
        assert_refuses(ensemble, [0.3], 2, **{**KW20, **kw}, arg=arg, allowed=allowed)


BAD_ARGUMENTS = [   # (changes, exception, argument, value shown, what is allowed)
    (dict(restitution=-0.1), ValueError, "restitution", "-0.1", ">= 0"),
    (dict(restitution=1.5), ValueError, "restitution", "1.5", "<= 1"),
    (dict(omega=0), ValueError, "omega", "0", "> 0"),
    (dict(omega="1e400"), ValueError, "omega", "1.0e+400", "float64 range"),
    (dict(d=-1), ValueError, "d", "-1", "> 0"),
    (dict(d="1e400"), ValueError, "d", "1.0e+400", "float64 range"),
    (dict(sigma0=-1), ValueError, "sigma0", "-1", ">= 0"),
    (dict(sigma0=-0.1), ValueError, "sigma0", "-0.1", ">= 0"),
    (dict(sigma0="1e400"), ValueError, "sigma0", "1.0e+400", "float64 range"),
    (dict(sigma0=[0.1, -2]), ValueError, "sigma0[1]", "-2", ">= 0"),
    (dict(sigma0=[0.1, "1e400"]), ValueError, "sigma0[1]", "1.0e+400", "float64 range"),
    (dict(sigma0=[0.1]), ValueError, "sigma0", "1 values", "one number per sigma (2)"),
    (dict(sigma0=[0.1, 0.2, 0.3]), ValueError, "sigma0", "3 values", "one number per sigma"),
    (dict(checkpoint_every=-1), ValueError, "checkpoint_every", "-1", ">= 0"),
    (dict(checkpoint_every="1e400"), ValueError, "checkpoint_every", "1.0e+400",
     "float64 range"),
    (dict(t_transient=-1), ValueError, "t_transient", "-1", ">= 0"),
    (dict(t_transient=math.inf), ValueError, "t_transient", None, None),
    (dict(t_transient=math.nan), ValueError, "t_transient", None, None),
    (dict(t_window=0), ValueError, "t_window", "0", "> 0"),
    (dict(t_window=math.inf), ValueError, "t_window", None, None),
    (dict(t_transient=60000, t_window=60000), ValueError, "(t_transient + t_window)",
     "120000.0", "must be <= 100000"),
    (dict(omega=2.0, t_window=50001), ValueError, "t_window", "50001", "omega = 2.0"),
    (dict(omega=2.0, t_transient=50001), ValueError, "t_transient", "50001", "too long"),
    (dict(t_transient=1e17, t_window=1.0, omega=1e-12), ValueError, "t_window", "1.0",
     "must exceed t_transient = 1e+17 in float64"),
    (dict(seed=None), TypeError, "seed", "None", "an int >= 0"),
    (dict(seed=-1), ValueError, "seed", "-1", None),
    (dict(seed=2.5), TypeError, "seed", "2.5", None),
    (dict(seed=True), TypeError, "seed", "True", None),
    (dict(n=0), ValueError, "n", "0", ">= 1"),
    (dict(n=True), TypeError, "n", "True", None),
    (dict(chunk=0), ValueError, "chunk", "0", ">= 1"),
    (dict(chunk=1.5), TypeError, "chunk", "1.5", None),
    (dict(executor=3), TypeError, "executor", "int 3", "a concurrent.futures.Executor or None"),
    (dict(executor="x"), TypeError, "executor", "'x'", "a concurrent.futures.Executor"),
    (dict(progress=1), TypeError, "progress", "1", "True, False or None"),
    (dict(progress="yes"), TypeError, "progress", "'yes'", "True, False or None"),
    (dict(keep_runs="no"), TypeError, "keep_runs", "'no'", "True, False or None"),
    (dict(Omega=(-1.0,)), ValueError, "Omega[0]", "-1.0", ">= 0"),
    (dict(Omega=(0.5, "x")), ValueError, "Omega[1]", "'x'", "a number"),
    (dict(Omega=(1.0,)), ValueError, "Omega[0]", "1.0", "resonance"),
]


@pytest.mark.parametrize("kw, err, arg, value, allowed", BAD_ARGUMENTS)
def test_bad_arguments(kw, err, arg, value, allowed):
    base = {**KW, "omega": 1.0, "d": 1.0, "Omega": (SQRT2,), "restitution": 0.8}
    assert_refuses(ensemble, [0.1, 0.2], 2, **{**base, **kw}, exc=err, arg=arg, value=value,
                   allowed=allowed)


def test_bad_sigmas_and_runs():
    assert_refuses(ensemble, 0.1, 2, **KW, exc=TypeError, arg="sigmas", value="float 0.1",
                   allowed="a sequence of numbers")
    assert_refuses(ensemble, "0.1", 2, **KW, exc=TypeError, arg="sigmas", value="str '0.1'",
                   allowed="a sequence of numbers")
    assert_refuses(ensemble, [], 2, **KW, arg="sigmas", value="[]",
                   allowed="a non-empty sequence of numbers >= 0")
    assert_refuses(ensemble, [0.1, -0.1], 2, **KW, arg="sigmas[1]", value="-0.1",
                   allowed=">= 0")
    assert_refuses(ensemble, [0.1, math.nan], 3, **KW, arg="sigmas[1]", value="nan")
    assert_refuses(ensemble, [-0.1], 3, **KW, arg="sigmas[0]", value="-0.1", allowed=">= 0")
    assert_refuses(ensemble, ["1e400"], 2, **KW, arg="sigmas[0]", value="1.0e+400",
                   allowed="float64 range")
    assert ensemble(np.array([0.0]), 1, **{**KW, "sigma0": 0.0}).sigmas.tolist() == [0.0]
    assert_refuses(ensemble, [0.1], 0, **KW, arg="runs", value="0", allowed=">= 1")
    assert_refuses(ensemble, [0.1], True, **KW, exc=TypeError, arg="runs", value="True")
    assert_refuses(ensemble, [0.1], 2.0, **KW, exc=TypeError, arg="runs", value="2.0")
    assert_refuses(ensemble, [0.1], E.MAX_RUNS + 1, **KW, arg="runs", value="100001",
                   allowed=["<= 100000 per sigma", "symhx.impact.ensemble.MAX_RUNS"])
    assert_refuses(ensemble, [0.1, 0.2], E.MAX_RUNS + 1, **KW, arg="runs", allowed="MAX_RUNS")
    k = E.MAX_TOTAL_RUNS // E.MAX_RUNS + 1
    assert_refuses(ensemble, [0.1] * k, E.MAX_RUNS, **KW, arg="runs",
                   value=f"len(sigmas) * runs = {k * E.MAX_RUNS}",
                   allowed="symhx.impact.ensemble.MAX_TOTAL_RUNS = 100000000")
    assert E.MAX_RUNS == 10**5 and E.MAX_TOTAL_RUNS == 10**8


def test_ensemble_progress_defaults_to_none(monkeypatch):
    # the progress bar: None by default (shown only on a terminal)
    got = []

    class Bar:
        def update(self, k):
            pass

        def close(self):
            pass

    monkeypatch.setattr(E, "_make_progress", lambda total, progress: got.append(progress) or
                        Bar())
    ensemble([0.0], 1, n=2, t_transient=1, t_window=1, sigma0=0.0)
    assert got == [None]
