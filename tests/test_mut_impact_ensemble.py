"""``symhx.impact.ensemble`` against independent references (issue 16, mutation testing).

Fast tests (a few seconds in all): every ensemble statistic is recomputed here from the full
event histories of the pure-Python engine (``simulate(..., engine="python")``; the ensemble
counts with the C kernel) of the same rows, counted by hand (impacting *pipes* vs impact
*sites*, the window ``[t_transient, t_transient + t_window]``); histogram statistics against
numpy and the documented bootstrap; thresholds on hand-made histograms; the free-flight closure
fraction against a brute-force scan of each gap; argument errors with their exact messages.
"""

from __future__ import annotations

import importlib
import json
import math
from concurrent.futures import Executor, Future, ThreadPoolExecutor

import numpy as np
import pytest

from symhx.impact import IMPACT, STICK, PipeRow, simulate
from symhx.impact.ensemble import (
    EnsembleResult,
    SigmaStats,
    describe_histogram,
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
from symhx.impact.model import SQRT2, SimulationError
from tests.reference.seeds import boot_seed_ref, run_seed_ref

E = importlib.import_module("symhx.impact.ensemble")

# a small ensemble with every model parameter away from its default
MODEL = dict(restitution=0.5, omega=1.3, d=1.2, Omega=(0.7,))
KW = dict(n=6, t_transient=6.0, t_window=5.0, seed=7, progress=False, **MODEL)
SIGMAS = [0.22, 0.4]
SIGMA0 = [0.3, 0.25]
RUNS = 5


def _hand(sigma, k, *, n, t_transient, t_window, seed, sigma0, restitution, omega, d, Omega):
    """One run counted by hand from the Python engine's full history."""
    row = PipeRow.random(n, sigma, seed=run_seed_ref(seed, sigma, k), restitution=restitution,
                         omega=omega, d=d, Omega=Omega, sigma0=sigma0)
    h = simulate(row, t_transient + t_window, engine="python")
    times = [float(t) for t in h.times]
    hits = [(int(s), t) for s, kind, t in zip(h.sites, h.kinds, times, strict=True)
            if kind in (IMPACT, STICK)]
    window = [s for s, t in hits if t >= t_transient]
    sites = set(window)
    pipes = {j for s in sites for j in (s, s + 1) if 1 <= j <= n}   # gap s: pipes s, s + 1
    return dict(pipes=len(pipes), sites=len(sites), impacts=len(window), events=len(h),
                where=sites, ever={s for s, _ in hits}, seqs=window)


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


# ----------------------------------------------------------------- failures and options
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


def test_failed_draws_are_named_draw():
    # sigma0 = 0: the pipes start at j d + forced(0); some rows overlap and cannot be drawn
    out = run_chunk(2.0, list(range(6)), 6, 1.0, 1.0, 0, 0.8, 1.0, 1.0, (1.05,), 0.0)
    assert out["failures"]
    for run, reason in out["failures"]:
        assert reason.startswith("draw: could not draw non-overlapping")
        k = list(range(6)).index(run)
        assert out["pipes"][k] == out["sites"][k] == out["impacts"][k] == -1


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


def test_sigma0_forms(hand):
    one = ensemble(SIGMAS, 3, sigma0=0.3, **KW)
    assert one.params["sigma0"] == [0.3, 0.3]
    assert one.per_sigma[0].pipes.tolist() == [r["pipes"] for r in hand[0][:3] if r["sites"]]
    arr = ensemble(SIGMAS, 2, sigma0=np.array(SIGMA0), **KW)
    assert arr.params["sigma0"] == SIGMA0
    scalar_omega = ensemble([0.3], 2, **{**KW, "Omega": 0.7})
    assert scalar_omega.params["Omega"] == ["0.7"]
    assert ensemble([0.3], 1, **{**KW, "Omega": (SQRT2,)}).params["Omega"] == ["sqrt(2)"]


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


# ----------------------------------------------------------------- argument errors
@pytest.mark.parametrize("kw, err, pattern", [
    (dict(restitution=-0.1), ValueError, r"^restitution must be >= 0, got -0.1$"),
    (dict(restitution=1.5), ValueError, r"^restitution must be <= 1, got 1.5$"),
    (dict(omega=0), ValueError, r"^omega must be > 0, got 0$"),
    (dict(omega="1e400"), ValueError, r"^omega = 1\.0e\+400 is beyond the float64 range$"),
    (dict(d=-1), ValueError, r"^d must be > 0, got -1$"),
    (dict(d="1e400"), ValueError, r"^d = 1\.0e\+400 is beyond the float64 range$"),
    (dict(sigma0=-1), ValueError, r"^sigma0 must be >= 0, got -1$"),
    (dict(sigma0="1e400"), ValueError, r"^sigma0 = 1\.0e\+400 is beyond the float64 range$"),
    (dict(sigma0=[0.1, -2]), ValueError, r"^sigma0\[1\] must be >= 0, got -2$"),
    (dict(sigma0=[0.1, "1e400"]), ValueError, r"^sigma0\[1\] = 1\.0e\+400 is beyond the"),
    (dict(sigma0=[0.1]), ValueError, r"^sigma0 must be None, a number or one number per sigma "
                                     r"\(2\), got 1 values$"),
    (dict(checkpoint_every=-1), ValueError, r"^checkpoint_every must be >= 0, got -1$"),
    (dict(checkpoint_every="1e400"), ValueError, r"^checkpoint_every = 1\.0e\+400 is beyond"),
    (dict(t_transient=-1), ValueError, r"^t_transient must be >= 0, got -1$"),
    (dict(t_window=0), ValueError, r"^t_window must be > 0, got 0$"),
    (dict(t_transient=60000, t_window=60000), ValueError,
     r"^\(t_transient \+ t_window\) = 120000.0 is too long: omega \* \(t_transient \+ t_window\)"
     r" must be <= 100000 .*got omega = 1.0$"),
    (dict(omega=2.0, t_window=50001), ValueError, r"^t_window = 50001 is too long: .* got "
                                                  r"omega = 2.0$"),
    (dict(omega=2.0, t_transient=50001), ValueError, r"^t_transient = 50001 is too long"),
    (dict(t_transient=1e17, t_window=1.0, omega=1e-12), ValueError,
     r"^t_window = 1.0 is too short: t_transient \+ t_window must exceed t_transient = 1e\+17 "
     r"in float64$"),
    (dict(seed=None), TypeError, r"^seed must be an int >= 0 \(an ensemble needs a fixed seed\), "
                                 r"got None$"),
    (dict(seed=-1), ValueError, r"^seed "),
    (dict(n=0), ValueError, r"^n must be >= 1, got 0$"),
    (dict(chunk=0), ValueError, r"^chunk must be >= 1, got 0$"),
    (dict(chunk=1.5), TypeError, r"^chunk "),
    (dict(executor=3), TypeError, r"^executor must be a concurrent.futures.Executor or None, got "
                                  r"int 3$"),
    (dict(progress=1), TypeError, r"^progress must be True, False or None, got 1$"),
    (dict(keep_runs="no"), TypeError, r"^keep_runs must be True, False or None, got 'no'$"),
    (dict(Omega=(-1.0,)), ValueError, r"^Omega\[0\] must be >= 0, got -1.0$"),
    (dict(Omega=(0.5, "x")), ValueError, r"^Omega\[1\] must be a number"),
    (dict(Omega=(1.0,)), ValueError, r"^Omega\[0\] = 1.0 equals omega = 1.0 \(resonance\)"),
])
def test_bad_arguments(kw, err, pattern):
    base = {**KW, "omega": 1.0, "d": 1.0, "Omega": (SQRT2,), "restitution": 0.8}
    with pytest.raises(err, match=pattern):
        ensemble([0.1, 0.2], 2, **{**base, **kw})


def test_bad_sigmas_and_runs_messages():
    with pytest.raises(TypeError, match=r"^sigmas must be a sequence of numbers, got float 0.1$"):
        ensemble(0.1, 2, **KW)
    with pytest.raises(TypeError, match=r"^sigmas must be a sequence of numbers, got str '0.1'$"):
        ensemble("0.1", 2, **KW)
    with pytest.raises(ValueError, match=r"^sigmas must be a non-empty sequence of numbers >= 0, "
                                         r"got \[\]$"):
        ensemble([], 2, **KW)
    with pytest.raises(ValueError, match=r"^sigmas\[1\] must be >= 0, got -0.1$"):
        ensemble([0.1, -0.1], 2, **KW)
    with pytest.raises(ValueError, match=r"^sigmas\[0\] = 1\.0e\+400 is beyond the float64 range$"):
        ensemble(["1e400"], 2, **KW)
    assert ensemble(np.array([0.0]), 1, **{**KW, "sigma0": 0.0}).sigmas.tolist() == [0.0]
    with pytest.raises(ValueError, match=r"^runs must be >= 1, got 0$"):
        ensemble([0.1], 0, **KW)
    with pytest.raises(ValueError, match=r"^runs must be <= 100000 per sigma \(the work cap "
                                         r"symhx.impact.ensemble.MAX_RUNS\), got 100001$"):
        ensemble([0.1], E.MAX_RUNS + 1, **KW)
    k = E.MAX_TOTAL_RUNS // E.MAX_RUNS + 1
    with pytest.raises(ValueError, match=rf"^runs: len\(sigmas\) \* runs = {k * E.MAX_RUNS} "
                                         r"exceeds the work cap symhx.impact.ensemble."
                                         r"MAX_TOTAL_RUNS = 100000000$"):
        ensemble([0.1] * k, E.MAX_RUNS, **KW)
    assert E.MAX_RUNS == 10**5 and E.MAX_TOTAL_RUNS == 10**8


# ----------------------------------------------------------------- histogram statistics
def _boot_reference(h, seed, boot):
    """The documented bootstrap: ``boot`` multinomial resamples of the histogram."""
    rng = np.random.default_rng(seed)
    k = int(h.sum())
    samples = rng.multinomial(k, h / k, size=boot)
    means = samples @ np.arange(len(h)) / k
    modes = np.argmax(samples, axis=1)
    return (np.percentile(means, [2.5, 97.5]).tolist(),
            np.percentile(modes, [2.5, 97.5], method="nearest").astype(int).tolist(),
            float(np.std(modes, ddof=1)))


@pytest.mark.parametrize("hist", [[0, 3, 1], [2, 5, 5, 1, 0, 7], [0, 0, 4], [1, 1]])
def test_describe_histogram_against_numpy_and_bootstrap(hist):
    h = np.array(hist)
    values = np.repeat(np.arange(len(h)), h)
    st = describe_histogram(hist, np.random.default_rng(9), boot=300)
    assert st["count"] == len(values) and st["hist"] == hist
    assert st["mean"] == pytest.approx(values.mean(), rel=1e-14)
    assert st["se"] == pytest.approx(values.std(ddof=1) / math.sqrt(len(values)), rel=1e-12)
    assert st["mode"] == int(np.flatnonzero(h == h.max())[0])
    mean_ci, mode_ci, mode_se = _boot_reference(h, 9, 300)
    assert st["mean_ci"] == pytest.approx(mean_ci, rel=1e-14)
    assert st["mode_ci"] == mode_ci and st["mode_se"] == pytest.approx(mode_se, rel=1e-14)
    assert isinstance(st["mode"], int) and all(isinstance(x, int) for x in st["mode_ci"])
    # the default generator and number of resamples
    d = describe_histogram(hist)
    assert d["mean_ci"] == pytest.approx(_boot_reference(h, 0, 2000)[0], rel=1e-14)
    assert E.BOOTSTRAP == 2000


def test_describe_histogram_degenerate():
    empty = describe_histogram([0, 0, 0])
    assert empty == {"count": 0, "hist": [0, 0, 0], "mean": None, "se": None, "mode": None,
                     "mode_se": None, "mean_ci": [None, None], "mode_ci": [None, None]}
    one = describe_histogram([0, 0, 1])
    assert (one["mean"], one["se"], one["mode"], one["mode_se"]) == (2.0, None, 2, None)
    assert one["mean_ci"] == [2.0, 2.0] and one["mode_ci"] == [2, 2]
    two = describe_histogram([1, 0, 1], np.random.default_rng(1), boot=50)
    assert two["se"] == pytest.approx(1.0) and two["mode"] == 0


def test_combine_statistics_use_their_own_bootstrap_stream(res, hand):
    # the bootstrap generator of sigma is SeedSequence([seed, 1, key(sigma)]); pipes first
    for i, st in enumerate(res.per_sigma):
        rng = np.random.default_rng(boot_seed_ref(KW["seed"], st.sigma))
        kept = [r for r in hand[i] if r["sites"]]
        hp = np.bincount([r["pipes"] for r in kept], minlength=KW["n"] + 1)
        hs = np.bincount([r["sites"] for r in kept], minlength=KW["n"] + 2)
        assert st.stats["pipes"] == describe_histogram(hp, rng)
        assert st.stats["sites"] == describe_histogram(hs, rng)


def test_combine_of_no_parts():
    st = E._combine(0.5, [], 4, 0, True)
    assert (st.runs, st.excluded, st.failed, st.events, st.impacts) == (0, 0, 0, 0, 0)
    assert st.site_hits.tolist() == [0] * 5 and st.pipes.tolist() == []
    assert st.stats["pipes"]["count"] == 0 and len(st.stats["sites"]["hist"]) == 6


# ----------------------------------------------------------------- SigmaStats / EnsembleResult
def _stats(sigma, hits, finished_runs, failed=0, hist_p=(0, 2, 1), hist_s=(0, 3, 0)):
    st = SigmaStats(sigma=sigma, runs=finished_runs + failed, excluded=1,
                    pipes=np.array([1, 1, 2]), sites=np.array([1, 1, 1]), events=7,
                    failed=failed, failures=[(0, "x")] * failed,
                    site_hits=np.array(hits, dtype=np.int64), impacts=5)
    st.stats = {"pipes": describe_histogram(list(hist_p), np.random.default_rng(0), 20),
                "sites": describe_histogram(list(hist_s), np.random.default_rng(0), 20)}
    return st


def test_gap_rate_by_hand():
    st = _stats(0.3, [4, 1, 2, 0, 3], 4, failed=2)
    assert st.finished == 4
    q = (1 + 2 + 0) / (4 * 3)                       # interior sites 1..3, 4 finished runs
    assert st.gap_rate() == pytest.approx((q, math.sqrt(q * (1 - q) / 12)), rel=1e-14)
    q = 10 / (4 * 5)
    assert st.gap_rate(False) == pytest.approx((q, math.sqrt(q * (1 - q) / 20)), rel=1e-14)
    nan = _stats(0.3, [0, 0, 0], 0, failed=3).gap_rate()
    assert math.isnan(nan[0]) and math.isnan(nan[1])
    one = _stats(0.3, [1, 0, 1], 1).gap_rate()
    assert one == (0.0, 0.0)
    res = EnsembleResult(params={"n": 4}, per_sigma=[st, _stats(0.5, [1, 1, 1, 1, 1], 2)])
    rate, se = res.gap_rates()
    assert rate.tolist() == pytest.approx([3 / 12, 3 / 6]) and se[1] == pytest.approx(
        math.sqrt(0.25 / 6))
    assert res.gap_rates(interior=False)[0].tolist() == pytest.approx([0.5, 0.5])


def test_result_columns_dicts_and_files(tmp_path, monkeypatch):
    a = _stats(0.3, [1, 0, 2], 3)
    b = _stats(0.5, [0, 0, 0], 2, hist_p=(0, 0, 0), hist_s=(0, 0, 0))
    res = EnsembleResult(params={"n": 2, "runs": 3}, per_sigma=[a, b], seconds=1.5)
    assert res.sigmas.tolist() == [0.3, 0.5]
    mean = res.column()
    assert mean[0] == pytest.approx(4 / 3) and math.isnan(mean[1]) and mean.dtype == float
    assert res.column("sites", "mode")[0] == 1.0
    ci = res.column("pipes", "mean_ci")
    assert ci.shape == (2, 2) and ci.dtype == float and np.isnan(ci[1]).all()
    assert ci[0].tolist() == a.stats["pipes"]["mean_ci"]
    d = a.as_dict()
    assert d == {"sigma": 0.3, "runs": 3, "excluded": 1, "failed": 0, "failures": [],
                 "events": 7, "impacts": 5, "site_hits": [1, 0, 2], **a.stats}
    whole = res.as_dict()
    assert whole == {"params": {"n": 2, "runs": 3}, "seconds": 1.5,
                     "per_sigma": [a.as_dict(), b.as_dict()]}
    moves = []
    real_replace = E.os.replace
    monkeypatch.setattr(E.os, "replace", lambda src, dst: moves.append((src, dst)) or
                        real_replace(src, dst))
    path = tmp_path / "r.json"
    res.save(path)
    assert moves == [(tmp_path / "r.json.tmp", path)]
    text = path.read_text()
    assert text == json.dumps(whole, indent=1) + "\n"
    back = EnsembleResult.load(path)
    assert back.as_dict() == json.loads(text) and back.seconds == 1.5
    for x, y in zip(back.per_sigma, res.per_sigma, strict=True):
        assert (x.sigma, x.runs, x.excluded, x.failed, x.events, x.impacts) == (
            y.sigma, y.runs, y.excluded, y.failed, y.events, y.impacts)
        assert x.site_hits.dtype == np.int64 and x.site_hits.tolist() == y.site_hits.tolist()
        assert x.pipes.tolist() == [] and x.stats == y.stats
    # files of older versions lack the optional keys: zeros, no failures, no hits
    old = {"params": {"n": 3}, "per_sigma": [{"sigma": 0.2, "runs": 4, "excluded": 4,
                                              "pipes": a.stats["pipes"],
                                              "sites": a.stats["sites"]}]}
    st = EnsembleResult.from_dict(old).per_sigma[0]
    assert (st.events, st.failed, st.failures, st.impacts) == (0, 0, [], 0)
    assert st.site_hits.tolist() == [0, 0, 0, 0] and st.site_hits.dtype == np.int64
    assert EnsembleResult.from_dict(old).seconds == 0.0
    failed = EnsembleResult.from_dict({"params": {"n": 1}, "per_sigma": [
        {**a.as_dict(), "failures": [[3, "why"]], "failed": 1}]}).per_sigma[0]
    assert failed.failures == [(3, "why")] and failed.failed == 1


# ----------------------------------------------------------------- thresholds
def _result(sigmas, hists):
    per = []
    for s, h in zip(sigmas, hists, strict=True):
        st = SigmaStats(sigma=s, runs=int(sum(h)), excluded=0, pipes=np.zeros(0, int),
                        sites=np.zeros(0, int))
        st.stats = {"pipes": {"hist": list(h)}}
        per.append(st)
    return EnsembleResult(params={}, per_sigma=per)


def _point(v, count, size=15):
    h = [0] * size
    h[v] = count
    return h


def test_thresholds_on_point_histograms():
    # every sigma's runs all have the same number of pipes: resampling changes nothing, so the
    # intervals collapse onto the estimate
    sig = [0.1, 0.2, 0.4, 0.5, 0.6]
    vals = [1, 2, 10, 11, 14]
    res = _result(sig, [_point(v, 30) for v in vals])
    out = thresholds(res, level=10, min_kept=20, boot=5)
    assert out["mode"] == [0.4, 0.4, 0.4]
    # mean slopes (the grid is not uniform): 10, 40, 10, 30 -> steepest on [0.2, 0.4]
    assert out["steep"] == pytest.approx([0.3, 0.3, 0.3])
    assert thresholds(res, level=11, min_kept=20, boot=3)["mode"] == [0.5, 0.5, 0.5]
    assert thresholds(res, level=2, min_kept=20, boot=3)["mode"] == [0.2, 0.2, 0.2]
    # the mode must stay >= level up to the last sigma; a dip resets it
    dip = _result(sig, [_point(v, 30) for v in (1, 12, 3, 11, 14)])
    assert thresholds(dip, level=10, boot=2)["mode"][0] == 0.5
    # sigmas with too few kept runs neither define the mode threshold nor a slope
    few = _result(sig, [_point(1, 30), _point(2, 30), _point(10, 30), _point(11, 19),
                        _point(14, 30)])
    out = thresholds(few, level=10, min_kept=20, boot=2)
    assert out["mode"][0] == 0.6
    assert out["steep"][0] == pytest.approx(0.3)
    assert thresholds(few, level=10, min_kept=19, boot=2)["mode"][0] == 0.4
    # nothing reaches the level; no slope at all with one usable sigma
    low = thresholds(_result(sig, [_point(1, 30)] * 5), level=10, boot=2)
    assert math.isnan(low["mode"][0]) and all(math.isnan(x) for x in low["mode"][1:])
    # (an unusable last sigma: "from which on" cannot be claimed)
    one = thresholds(_result([0.1, 0.2], [_point(3, 30), _point(5, 3)]), level=2, boot=2)
    assert math.isnan(one["steep"][0]) and math.isnan(one["mode"][0])
    one = thresholds(_result([0.1, 0.2], [_point(3, 3), _point(5, 30)]), level=2, boot=2)
    assert math.isnan(one["steep"][0]) and one["mode"] == [0.2, 0.2, 0.2]
    single = thresholds(_result([0.3], [_point(12, 30)]), boot=2)
    assert single["mode"] == [0.3, 0.3, 0.3] and math.isnan(single["steep"][0])


def test_thresholds_bootstrap_interval_by_hand():
    # two sigmas, the second one's runs split 50/50 between 9 and 11 pipes: its resampled mode
    # is 9 or 11 (ties go to 9); the threshold (level 10) is then 0.2 or nan
    res = _result([0.1, 0.2], [_point(1, 40), [0] * 9 + [20, 0, 20] + [0] * 3])
    out = thresholds(res, level=10, min_kept=20, boot=400, seed=5)
    assert math.isnan(out["mode"][0])          # tie: the smallest mode, 9 < 10
    rng = np.random.default_rng(5)
    hists = [np.array(_point(1, 40), float), np.array([0] * 9 + [20, 0, 20] + [0] * 3, float)]
    modes = []
    for _ in range(400):
        hb = [rng.multinomial(int(h.sum()), h / h.sum()).astype(float) for h in hists]
        modes.append(0.2 if int(np.argmax(hb[1])) >= 10 else math.nan)
    ok = [m for m in modes if not math.isnan(m)]
    assert 100 < len(ok) < 300
    assert out["mode"][1:] == [0.2, 0.2]
    assert out["steep"] == pytest.approx([0.15, 0.15, 0.15])
    assert thresholds(res, level=10, boot=3)["steep"][0] == pytest.approx(0.15)


def test_thresholds_of_a_real_ensemble_match_its_histograms():
    res = ensemble([0.1, 0.3, 0.5], 8, n=6, t_transient=3, t_window=4, seed=2, progress=False)
    out = thresholds(res, level=2, min_kept=1, boot=4)
    modes = [s.stats["pipes"]["mode"] for s in res.per_sigma]
    means = [s.stats["pipes"]["mean"] for s in res.per_sigma]
    m = math.nan
    for s, mode in zip(res.sigmas[::-1], modes[::-1], strict=True):
        if mode is None or mode < 2:
            break
        m = float(s)
    assert out["mode"][0] == m or (math.isnan(m) and math.isnan(out["mode"][0]))
    usable = [(s, mu) for s, mu in zip(res.sigmas, means, strict=True) if mu is not None]
    if len(usable) == 3:
        slopes = [(usable[j + 1][1] - usable[j][1]) / (usable[j + 1][0] - usable[j][0])
                  for j in range(2)]
        j = int(np.argmax(slopes))
        assert out["steep"][0] == pytest.approx((usable[j][0] + usable[j + 1][0]) / 2)


# ----------------------------------------------------------------- site sequences
def test_site_transitions_equal_hand_sequences():
    kw = dict(n=5, t_transient=4.0, t_window=5.0, seed=6)
    seqs = site_transitions(0.35, 3, restitution=0.5, sigma0=0.3, **kw)
    assert len(seqs) == 3
    for k, s in enumerate(seqs):
        row = PipeRow.random(5, 0.35, seed=run_seed_ref(6, 0.35, k), restitution=0.5, sigma0=0.3)
        h = simulate(row, 9.0, engine="python")
        ref = [int(site) for site, kind, t in zip(h.sites, h.kinds, h.times, strict=True)
               if kind in (IMPACT, STICK) and float(t) >= 4.0]
        assert s.tolist() == ref and s.dtype == np.int64
    assert sum(len(s) for s in seqs) > 0
    # defaults: n = 100, t in [200, 300], seed 0: at rest nothing happens
    (quiet,) = site_transitions(0.0, 1, sigma0=0.0)
    assert quiet.tolist() == []
    d = site_transitions(0.3, 1, n=4, t_transient=2, t_window=3)[0]
    row = PipeRow.random(4, 0.3, seed=run_seed_ref(0, 0.3, 0))
    h = simulate(row, 5.0, engine="python")
    assert d.tolist() == [int(x) for x, kind, t in zip(h.sites, h.kinds, h.times, strict=True)
                          if kind in (IMPACT, STICK) and t >= 2]


def test_site_transitions_failures_and_arguments(monkeypatch):
    S = importlib.import_module("symhx.impact.simulate")

    monkeypatch.setattr(S, "simulate", lambda row, t: (_ for _ in ()).throw(
        SimulationError("no")))
    out = site_transitions(0.3, 2, n=3, t_transient=1, t_window=1)
    assert [s.tolist() for s in out] == [[], []] and out[0].dtype == np.int64
    monkeypatch.undo()
    with pytest.raises(ValueError, match=r"^runs must be >= 1, got 0$"):
        site_transitions(0.3, 0)
    with pytest.raises(ValueError, match=r"^t_transient must be >= 0, got -1$"):
        site_transitions(0.3, 1, t_transient=-1)
    with pytest.raises(ValueError, match=r"^t_window must be > 0, got 0$"):
        site_transitions(0.3, 1, t_window=0)


def _mi(a, b, size):
    """Mutual information (nats) of pooled pairs, by its definition."""
    n = len(a)
    out = 0.0
    for x in range(size):
        for y in range(size):
            pxy = sum(1 for u, v in zip(a, b, strict=True) if u == x and v == y) / n
            if pxy:
                px = sum(1 for u in a if u == x) / n
                py = sum(1 for v in b if v == y) / n
                out += pxy * math.log(pxy / (px * py))
    return out


def test_transition_dependence_by_hand():
    seqs = [np.array([0, 1, 0, 1, 2]), np.array([3]), np.array([2, 2, 1]), np.array([], int)]
    a = [0, 1, 0, 1, 2, 2]
    b = [1, 0, 1, 2, 2, 1]
    out = transition_dependence(seqs, 4, shuffles=7, seed=3)
    assert out["pairs"] == 6
    assert out["mi"] == pytest.approx(_mi(a, b, 4), rel=1e-12)
    assert out["same"] == pytest.approx(1 / 6) and out["adjacent"] == pytest.approx(5 / 6)
    # the null by hand: each sequence permuted, in order, with the same generator
    rng = np.random.default_rng(3)
    null, same, adj = [], [], []
    for _ in range(7):
        perm = [rng.permutation(s) for s in seqs]
        pa = [x for s in perm if len(s) > 1 for x in s[:-1]]
        pb = [x for s in perm if len(s) > 1 for x in s[1:]]
        null.append(_mi(pa, pb, 4))
        same.append(np.mean(np.array(pa) == np.array(pb)))
        adj.append(np.mean(np.abs(np.array(pa) - np.array(pb)) == 1))
    assert out["mi_null"] == pytest.approx(np.mean(null), rel=1e-12)
    assert out["mi_null_sd"] == pytest.approx(np.std(null, ddof=1), rel=1e-12)
    assert out["z"] == pytest.approx((out["mi"] - np.mean(null)) / np.std(null, ddof=1))
    assert out["same_null"] == pytest.approx(np.mean(same), rel=1e-12)
    assert out["adjacent_null"] == pytest.approx(np.mean(adj), rel=1e-12)
    assert set(out) == {"pairs", "mi", "mi_null", "mi_null_sd", "z", "same", "same_null",
                        "adjacent", "adjacent_null"}
    # defaults: 50 shuffles, seed 0
    assert transition_dependence(seqs, 4) == transition_dependence(seqs, 4, shuffles=50, seed=0)
    # no pairs at all: every statistic undefined
    empty = transition_dependence([np.array([1]), np.array([], int)], 3, shuffles=3)
    assert empty["pairs"] == 0
    for key in ("mi", "mi_null", "z", "same", "same_null", "adjacent", "adjacent_null"):
        assert math.isnan(empty[key])
    # a null without spread: z undefined
    const = transition_dependence([np.array([2, 2, 2])], 3, shuffles=4)
    assert const["mi_null_sd"] == 0 and math.isnan(const["z"]) and const["same"] == 1.0
    # a custom statistic
    custom = transition_dependence(seqs, 4, shuffles=2, stat=lambda x, y: float(len(x)))
    assert custom["mi"] == 6.0 and custom["mi_null"] == 6.0


# ----------------------------------------------------------------- free flight (eq. 27)
def _brute_closes(g, om, Om, horizon, step=0.01):
    """min over [0, horizon] of d + a0 cos + b0 sin (omega) + a1 cos + b1 sin (Omega) <= 0,
    by a dense scan refined with a golden-section search around every sampled local min."""
    d, a0, b0, a1, b1 = g

    def f(t):
        return d + a0 * np.cos(om * t) + b0 * np.sin(om * t) + a1 * np.cos(Om * t) + \
            b1 * np.sin(Om * t)

    t = np.arange(0.0, horizon + step, step)
    t[-1] = min(t[-1], horizon)
    y = f(t)
    lo = float(y.min())
    idx = np.flatnonzero((y[1:-1] <= y[:-2]) & (y[1:-1] <= y[2:])) + 1
    for i in idx[np.argsort(y[idx])[:5]]:
        a, b = t[i - 1], t[i + 1]
        for _ in range(60):
            m1, m2 = a + (b - a) * 0.382, a + (b - a) * 0.618
            if f(m1) < f(m2):
                b = m2
            else:
                a = m1
        lo = min(lo, float(f((a + b) / 2)))
    return lo


@pytest.mark.parametrize("kw", [
    dict(sigma=0.35, gaps=40, horizon=30.0, seed=4),
    dict(sigma=0.3, gaps=30, horizon=25.0, seed=1, omega=1.3, d=1.2, Omega=0.7),
])
def test_free_flight_closure_against_brute_force(kw):
    om, d, Om = kw.get("omega", 1.0), kw.get("d", 1.0), kw.get("Omega", math.sqrt(2))
    rng = np.random.default_rng(kw["seed"])
    den = om**2 - Om**2
    closed = 0
    margins = []
    for _ in range(kw["gaps"]):
        # a gap x_{j+1} - x_j of two independent pipes: differences of their coefficients
        a0, b0, a1, b1 = rng.normal(0.0, kw["sigma"], size=(4, 2)) @ np.array([1.0, -1.0])
        lo = _brute_closes((d, a0, b0, a1 / den, b1 / den), om, Om, kw["horizon"])
        margins.append(abs(lo))
        closed += lo <= 0
    assert min(margins) > 1e-6           # no graze within the scan's resolution
    assert 0 < closed < kw["gaps"]
    assert free_flight_closure_fraction(**kw) == closed / kw["gaps"]


def test_free_flight_defaults_and_arguments():
    f = free_flight_closure_fraction
    assert f(0.3, 50) == f(0.3, 50, horizon=400.0, seed=0, omega=1.0, d=1.0,
                           Omega=math.sqrt(2))
    assert f(0.3, 1, horizon=3.0) in (0.0, 1.0)
    assert E.MAX_GAPS == 20_000
    for kw, pattern in (
        (dict(sigma=0), r"^sigma must be > 0, got 0$"),
        (dict(sigma="1e400"), r"^sigma = 1\.0e\+400 is beyond the float64 range$"),
        (dict(gaps=0), r"^gaps must be >= 1, got 0$"),
        (dict(gaps=E.MAX_GAPS + 1), r"^gaps must be <= 20000 \(the work cap "
                                    r"symhx.impact.ensemble.MAX_GAPS\), got 20001$"),
        (dict(omega=0), r"^omega must be > 0, got 0$"),
        (dict(omega="1e400"), r"^omega = 1\.0e\+400 is beyond the float64 range$"),
        (dict(d=0), r"^d must be > 0, got 0$"),
        (dict(d="1e400"), r"^d = 1\.0e\+400 is beyond the float64 range$"),
        (dict(Omega=-1), r"^Omega must be >= 0, got -1$"),
        (dict(Omega="1e400"), r"^Omega = 1\.0e\+400 is beyond the float64 range$"),
        (dict(Omega=1.0), r"resonance"),
        (dict(horizon=0), r"^horizon must be > 0, got 0$"),
        (dict(horizon=60000, omega=2.0), r"^horizon = 60000 is too long: .*omega = 2.0$"),
        (dict(seed=-1), r"^seed "),
    ):
        args = {"sigma": 0.3, "gaps": 2, **kw}
        with pytest.raises(ValueError, match=pattern):
            f(**args)
    assert f(0.3, 2, horizon=40000, omega=2.0) >= 0 and f(0.3, 2, Omega=0) >= 0


def test_free_flight_overflow_guard():
    f = free_flight_closure_fraction
    msg = (r"^sigma = {} is too large for the float64 engine \(the amplitudes overflow\); use a "
           r"smaller sigma$")
    # (4 sigma max(1, 1/|omega^2 - Omega^2|))**2 must be finite: sqrt(max float) / 4 = 3.35e153
    assert f(3e153, 1, horizon=1.0) in (0.0, 1.0)          # Omega = sqrt 2: |den| = 1
    with pytest.raises(ValueError, match=msg.format("3.4e\\+153")):
        f(3.4e153, 1, horizon=1.0)
    # Omega = 0.5: 1 / |den| = 4 / 3 enlarges the forced amplitudes
    assert f(2.5e153, 1, horizon=1.0, Omega=0.5) in (0.0, 1.0)
    with pytest.raises(ValueError, match=msg.format("3e\\+153")):
        f(3e153, 1, horizon=1.0, Omega=0.5)
    # Omega = 2: |den| = 3 > 1, the factor stays 1
    assert f(3e153, 1, horizon=1.0, Omega=2.0) in (0.0, 1.0)
    with pytest.raises(ValueError, match=msg.format("1e\\+200")):
        f(1e200, 1, horizon=1.0)


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


# ----------------------------------------------------------------- second round (survivors)
def test_documented_defaults():
    import inspect

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
    assert defaults(describe_histogram) == {"rng": None, "boot": 2000}


def test_site_transitions_window_start_is_inclusive():
    # t_transient set to the exact time of an impact: that impact belongs to the window
    row = PipeRow.random(5, 0.35, seed=run_seed_ref(6, 0.35, 0))
    h = simulate(row, 9.0)
    k = next(i for i in range(len(h)) if h.kinds[i] == IMPACT and h.times[i] > 1.0)
    t_k = float(h.times[k])
    (seq,) = site_transitions(0.35, 1, n=5, t_transient=t_k, t_window=9.0 - t_k, seed=6)
    ref = [int(s) for s, kind, t in zip(h.sites, h.kinds, h.times, strict=True)
           if kind in (IMPACT, STICK) and t_k <= t]
    assert seq.tolist()[0] == int(h.sites[k]) and seq.tolist() == ref[:len(seq)]


def test_thresholds_more_cases():
    # every sigma above the level: the threshold is the smallest sigma of the grid
    res = _result([0.1, 0.2], [_point(12, 30), _point(13, 30)])
    assert thresholds(res, boot=2)["mode"] == [0.1, 0.1, 0.1]
    # steepest slope, not largest rise: rises 5 (over 0.1) and 4 (over 0.4) -> slopes 50, 10
    res = _result([0.1, 0.2, 0.6], [_point(1, 30), _point(6, 30), _point(10, 30)])
    assert thresholds(res, level=20, boot=2)["steep"] == pytest.approx([0.15, 0.15, 0.15])
    # means are per run: different numbers of kept runs per sigma do not weigh them
    res = _result([0.1, 0.2, 0.3], [_point(2, 100), _point(3, 20), _point(6, 20)])
    assert thresholds(res, level=20, boot=2)["steep"][0] == pytest.approx(0.25)
    res = _result([0.1, 0.2, 0.3], [_point(2, 20), _point(5, 100), _point(6, 20)])
    assert thresholds(res, level=20, boot=2)["steep"][0] == pytest.approx(0.15)
    res = _result([0.1, 0.2, 0.3], [_point(2, 20), _point(5, 20), _point(6, 100)])
    assert thresholds(res, level=20, boot=2)["steep"][0] == pytest.approx(0.15)


def _est_reference(sig, hists, level, min_kept):
    """The two estimates as documented (written out independently of the package)."""
    ok = [h.sum() >= min_kept for h in hists]
    mode = math.nan
    for j in reversed(range(len(sig))):
        if not ok[j] or int(np.argmax(hists[j])) < level:
            break
        mode = sig[j]
    pts = [(s, (h * np.arange(len(h))).sum() / h.sum()) for s, h, k in zip(sig, hists, ok,
                                                                           strict=True)]
    slopes = []
    for (s0, m0), (s1, m1), k0, k1 in zip(pts, pts[1:], ok, ok[1:], strict=False):
        slopes.append((m1 - m0) / (s1 - s0) if k0 and k1 else -math.inf)
    if not slopes or max(slopes) == -math.inf:
        return mode, math.nan
    j = int(np.argmax(slopes))
    return mode, (sig[j] + sig[j + 1]) / 2


def test_thresholds_bootstrap_percentiles_by_hand():
    rng = np.random.default_rng(21)
    sig = [0.1 + 0.02 * i for i in range(12)]
    hists = [np.bincount(rng.binomial(14, p, size=25), minlength=15).astype(float)
             for p in np.linspace(0.2, 0.8, 12)]
    res = _result(sig, [h.astype(int).tolist() for h in hists])
    out = thresholds(res, level=8, min_kept=20, boot=60, seed=123)
    m0, s0 = _est_reference(sig, hists, 8, 20)
    brng = np.random.default_rng(123)
    bm, bs = [], []
    for _ in range(60):
        hb = [brng.multinomial(int(h.sum()), h / h.sum()).astype(float) for h in hists]
        a, b = _est_reference(sig, hb, 8, 20)
        bm.append(a)
        bs.append(b)

    def q(x):
        x = [v for v in x if not math.isnan(v)]
        return np.percentile(x, [16, 84]).tolist()

    assert out["mode"][0] == m0 and out["steep"][0] == pytest.approx(s0)
    assert out["mode"][1:] == pytest.approx(q(bm)) and out["steep"][1:] == pytest.approx(q(bs))
    # (this seed separates the 16th from the 17th and the 84th from the 85th percentile)
    assert q(bs)[0] != np.percentile(bs, 17) and q(bs)[1] != np.percentile(bs, 85)
    assert thresholds(res, level=8, min_kept=20, boot=60, seed=123) == out   # reproducible


def test_transition_dependence_short_sequences_and_empty_pairs():
    import warnings

    seqs = [np.array([4, 5]), np.array([1, 1, 2])]          # a sequence of length 2: one pair
    out = transition_dependence(seqs, 6, shuffles=3, seed=1)
    assert out["pairs"] == 3 and out["same"] == pytest.approx(1 / 3)
    assert out["mi"] == pytest.approx(_mi([4, 1, 1], [5, 1, 2], 6), rel=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")       # no "mean of empty slice" on the way to nan
        empty = transition_dependence([np.array([1])], 3, shuffles=2)
    assert math.isnan(empty["same"]) and math.isnan(empty["adjacent_null"])
    seen = []

    def stat(a, b):
        seen.append((a.dtype, b.dtype, len(a), len(b)))
        return 0.0

    transition_dependence([np.array([1])], 3, shuffles=2, stat=stat)
    assert seen == [(np.int64, np.int64, 0, 0)] * 3


def test_result_dtypes_and_failures_in_dicts():
    a = _stats(0.3, [1, 0, 2], 3, failed=2, hist_p=(0, 2, 1), hist_s=(0, 3, 0))
    res = EnsembleResult(params={"n": 2}, per_sigma=[a, _stats(0.4, [1, 1, 1], 3)])
    assert res.column("pipes", "mode").dtype == float
    assert res.column("pipes", "mode_ci").dtype == float
    assert a.as_dict()["failures"] == [[0, "x"], [0, "x"]]
    back = EnsembleResult.from_dict(json.loads(json.dumps(res.as_dict())))
    st = back.per_sigma[0]
    assert st.pipes.dtype == np.int64 and st.sites.dtype == np.int64
    assert st.pipes.tolist() == [] and st.sites.tolist() == []
    assert st.failures == [(0, "x"), (0, "x")] and st.failed == 2


def test_defaults_used_by_calls(monkeypatch):
    # default arguments are checked through calls (a mutated default does not show in the
    # signature of the wrapper that mutation testing puts around a function)
    S = importlib.import_module("symhx.impact.simulate")
    calls = []

    class Hist:
        times = np.array([199.5, 200.0, 250.0, 260.0, 299.0])
        kinds = np.array([IMPACT, IMPACT, 1, STICK, 3])
        sites = np.array([3, 4, 5, 6, 7])

    def fake(row, t_end):
        calls.append((row, t_end))
        return Hist()

    monkeypatch.setattr(S, "simulate", fake)
    (seq,) = site_transitions(0.2, 1)
    row, t_end = calls[0]
    assert t_end == 300.0 and row.n == 100 and row.restitution == 0.8
    ref = PipeRow.random(100, 0.2, seed=run_seed_ref(0, 0.2, 0))
    assert np.array_equal(row.x0, ref.x0) and np.array_equal(row.v0, ref.v0)
    assert seq.tolist() == [4, 6]
    monkeypatch.undo()
    # thresholds: level 10, min_kept 20, 400 resamples from seed 0
    res = _result([0.1, 0.2, 0.3], [_point(5, 30), [0] * 9 + [9, 11] + [0] * 4,
                                    _point(12, 30)])
    out = thresholds(res)
    assert out == thresholds(res, level=10, min_kept=20, boot=400, seed=0)
    assert out["mode"][0] == 0.2
    assert thresholds(res, level=11)["mode"][0] == 0.3
    assert thresholds(res, min_kept=21)["mode"][0] == 0.3
    real_rng = np.random.default_rng
    made = []

    class Counting:
        def __init__(self, seed):
            made.append(seed)
            self.rng, self.calls = real_rng(seed), 0
            made.append(self)

        def multinomial(self, *a, **kw):
            self.calls += 1
            return self.rng.multinomial(*a, **kw)

    monkeypatch.setattr(np.random, "default_rng", Counting)
    thresholds(res)
    assert made[0] == 0 and made[1].calls == 400 * 3       # 400 resamples of 3 histograms
    monkeypatch.undo()
    # free_flight_closure_fraction: seed 0, horizon 400
    eng = importlib.import_module("symhx.impact.engine")
    seen = {"t_hi": [], "seeds": []}
    real_rng = np.random.default_rng

    def search(self, g, t0, t_hi, **kw):
        seen["t_hi"].append((t0, t_hi))
        return math.inf, eng.Outcome.NONE

    monkeypatch.setattr(eng.Engine, "search", search)
    monkeypatch.setattr(np.random, "default_rng", lambda s=None: seen["seeds"].append(s) or
                        real_rng(s))
    assert free_flight_closure_fraction(0.3, 2) == 0.0
    assert seen["t_hi"] == [(0.0, 400.0)] * 2 and seen["seeds"] == [0]
    monkeypatch.undo()
    # the progress bar: None by default
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


def test_caps_are_inclusive(monkeypatch):
    monkeypatch.setattr(E, "MAX_RUNS", 2)
    monkeypatch.setattr(E, "MAX_TOTAL_RUNS", 4)
    res = ensemble([0.0, 0.0], 2, n=2, t_transient=1, t_window=1, sigma0=0.0, progress=False)
    assert [s.runs for s in res.per_sigma] == [2, 2]
    with pytest.raises(ValueError, match=r"^runs must be <= 2 per sigma"):
        ensemble([0.0], 3, n=2, t_transient=1, t_window=1, sigma0=0.0, progress=False)
    with pytest.raises(ValueError, match=r"^runs: len\(sigmas\) \* runs = 6 exceeds"):
        ensemble([0.0] * 3, 2, n=2, t_transient=1, t_window=1, sigma0=0.0, progress=False)


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


def test_model_parameters_checked_up_front_with_their_values():
    # the up-front check uses the given omega and d (resonance at omega = 2, walls at 3 d)
    with pytest.raises(ValueError, match=r"^Omega\[0\] = 2.0 equals omega = 2.0 \(resonance\)"):
        ensemble([0.1], 2, **{**KW, "omega": 2.0, "Omega": (2.0,)})
    res = ensemble([0.0], 1, **{**KW, "d": 3.0, "sigma0": 0.0})
    assert res.params["d"] == 3.0 and res.per_sigma[0].failed == 0


@pytest.mark.parametrize("hist, seed", [([10, 5, 4], 0), ([4, 6, 3, 8, 8], 1), ([4, 6, 5, 11], 0)])
def test_mode_interval_percentiles(hist, seed):
    # histograms whose resampled modes separate the 2.5th from the 3.5th percentile, the 97.5th
    # from the 98.5th, or the nearest-rank percentile from the interpolated one
    st = describe_histogram(hist, np.random.default_rng(seed))
    assert st["mode_ci"] == _boot_reference(np.array(hist), seed, 2000)[1]


def test_describe_histogram_types_and_default_stream():
    st = describe_histogram([0.0, 3.0, 1.0])
    assert st["hist"] == [0, 3, 1] and all(type(x) is int for x in st["hist"])
    rng = np.random.default_rng(5)
    big = np.bincount(rng.binomial(30, 0.3, size=4000), minlength=31)
    assert describe_histogram(big) == describe_histogram(big, np.random.default_rng(0))
    assert describe_histogram(big)["mean_ci"] != describe_histogram(
        big, np.random.default_rng(1))["mean_ci"]


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


def test_bootstrap_stream_of_each_sigma():
    # enough kept runs for the bootstrap to depend on its stream: SeedSequence([seed, 1, key])
    kw = dict(n=5, t_transient=2.0, t_window=4.0, seed=9, progress=False)
    res = ensemble([0.3, 0.5], 12, chunk=5, **kw)
    for i, st in enumerate(res.per_sigma):
        assert len(st.pipes) >= 6
        rng = np.random.default_rng(boot_seed_ref(9, st.sigma))
        assert st.stats["pipes"] == describe_histogram(np.bincount(st.pipes, minlength=6), rng)
        assert st.stats["sites"] == describe_histogram(np.bincount(st.sites, minlength=7), rng)
        assert st.stats["pipes"]["mode_se"] is not None
        other = np.random.default_rng(boot_seed_ref(9, res.per_sigma[1 - i].sigma))
        assert st.stats["pipes"] != describe_histogram(np.bincount(st.pipes, minlength=6), other)


def test_progress_bar_resizes_and_gap_cap(monkeypatch):
    bar = E._make_progress(3, True)
    assert callable(bar.dynamic_ncols)       # dynamic_ncols=True: the width follows the terminal
    bar.close()
    monkeypatch.setattr(E, "MAX_GAPS", 3)
    assert free_flight_closure_fraction(0.3, 3, horizon=5.0) in (0, 1 / 3, 2 / 3, 1)
    with pytest.raises(ValueError, match=r"^gaps must be <= 3 "):
        free_flight_closure_fraction(0.3, 4, horizon=5.0)


def test_free_flight_checks_the_given_omega_and_d():
    with pytest.raises(ValueError, match=r"^Omega\[0\] = 2.0 equals omega = 2.0 \(resonance\)"):
        free_flight_closure_fraction(0.3, 2, omega=2.0, Omega=2.0, horizon=5.0)
    assert 0 <= free_flight_closure_fraction(0.3, 2, d=3.0, horizon=5.0) <= 1


# ----------------------------------------------------------------- seeds keyed by sigma
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


def test_site_transitions_refuses_bad_input():
    with pytest.raises(ValueError, match="sigma"):
        site_transitions("abc", 1, n=3)
    with pytest.raises(ValueError, match="sigma"):
        site_transitions(-0.1, 1, n=3)
    with pytest.raises(TypeError, match="seed must be an int >= 0"):
        site_transitions(0.2, 1, n=3, seed=None)
    with pytest.raises(ValueError, match="seed"):
        site_transitions(0.2, 1, n=3, seed=-1)
    with pytest.raises(ValueError, match="beyond the float64 range"):
        site_transitions(10**400, 1, n=3)


def test_site_transitions_refusals_are_worded_whole():
    """The errors name the argument in full sentences (matched whole, so a renamed argument in a
    message is noticed)."""
    with pytest.raises(ValueError, match=r"^sigma must be >= 0, got -1$"):
        site_transitions(-1, 1, n=3)
    with pytest.raises(ValueError, match=r"^sigma = 1\.0e\+400 is beyond the float64 range"):
        site_transitions("1e400", 1, n=3)
    with pytest.raises(TypeError, match=r"^seed must be an int >= 0 \(the rows of ensemble\(\) "
                                        r"need one\), got None$"):
        site_transitions(0.3, 1, n=3, seed=None)
