"""The statistics of ``symhx.impact.ensemble``: ``describe_histogram`` (mean, standard error,
quantiles, mode, bootstrap intervals and the bootstrap probability of the mode) against numpy and
the documented bootstrap (``tests.reference.impact``), the per-sigma bootstrap streams,
``SigmaStats`` / ``EnsembleResult`` (columns, dictionaries, files) and the three simulated
thresholds on hand-made histograms."""

from __future__ import annotations

import importlib
import json
import math

import numpy as np
import pytest

from symhx.impact.ensemble import (
    EnsembleResult,
    SigmaStats,
    describe_histogram,
    ensemble,
    thresholds,
)
from tests.reference.impact import documented_bootstrap, documented_thresholds_estimate
from tests.reference.seeds import boot_seed_ref

E = importlib.import_module("symhx.impact.ensemble")
KW = dict(n=6, t_transient=6.0, t_window=5.0, seed=7, progress=False, restitution=0.5,
          omega=1.3, d=1.2, Omega=(0.7,))


# ----------------------------------------------------------------- describe_histogram
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
    # the quantiles: numpy's inverted-cdf quantile of the runs' values
    assert st["quantiles"] == [int(np.quantile(values, q, method="inverted_cdf"))
                               for q in E.QUANTILE_LEVELS]
    # intervals never leave the observed values (no error bar below 0 pipes)
    st0 = describe_histogram([5, 1, 0, 0], np.random.default_rng(2))
    assert st0["mean_ci"][0] >= 0 and st0["mode_ci"] == [0, 0]
    # ties: the smallest most frequent value, as in the paper's k* = min argmax
    assert describe_histogram([0, 3, 1, 3], np.random.default_rng(0))["mode"] == 1
    empty = describe_histogram([0, 0, 0])
    assert empty["mode"] is None and empty["mean"] is None and empty["mean_ci"] == [None, None]
    one = describe_histogram([0, 1])   # a single run: no spread, so no standard errors
    assert one["mean"] == 1 and one["se"] is None and one["mode_se"] is None


@pytest.mark.parametrize("hist", [[0, 3, 1], [2, 5, 5, 1, 0, 7], [0, 0, 4], [1, 1]])
def test_describe_histogram_against_numpy_and_bootstrap(hist):
    h = np.array(hist)
    values = np.repeat(np.arange(len(h)), h)
    st = describe_histogram(hist, np.random.default_rng(9), boot=300)
    assert st["count"] == len(values) and st["hist"] == hist
    assert st["mean"] == pytest.approx(values.mean(), rel=1e-14)
    assert st["se"] == pytest.approx(values.std(ddof=1) / math.sqrt(len(values)), rel=1e-12)
    assert st["mode"] == int(np.flatnonzero(h == h.max())[0])
    ref = documented_bootstrap(h, 9, 300)
    assert st["mean_ci"] == pytest.approx(ref["mean_ci"], rel=1e-14)
    assert st["mode_ci"] == ref["mode_ci"] and st["mode_se"] == pytest.approx(ref["mode_se"],
                                                                             rel=1e-14)
    assert st["mode_prob"] == ref["mode_prob"]
    assert isinstance(st["mode"], int) and all(isinstance(x, int) for x in st["mode_ci"])
    # the default generator and number of resamples
    d = describe_histogram(hist)
    assert d["mean_ci"] == pytest.approx(documented_bootstrap(h, 0, 2000)["mean_ci"], rel=1e-14)
    assert E.BOOTSTRAP == 2000


def test_mode_probability_tells_a_clear_mode_from_a_near_tie():
    # a mode far ahead is the bootstrap mode every time; two values 155 against 159 of 9237
    # runs (the stored sigma = 0.16 column near its jump) are each the mode about half the time
    clear = describe_histogram([0, 900, 100, 50], np.random.default_rng(3))
    assert clear["mode"] == 1 and clear["mode_prob"] == 1.0
    h = np.zeros(101, dtype=int)
    h[2], h[52] = 155, 159
    h[10:50] = 100                                 # the other runs spread below both peaks
    h[53:101] = 100
    st = describe_histogram(h, np.random.default_rng(4))
    ref = documented_bootstrap(h, 4, 2000)
    assert st["mode"] == 52 and st["mode_prob"] == ref["mode_prob"]
    assert 0.3 < st["mode_prob"] < 0.8             # a near-tie: far from certain
    # an exact two-way tie: the smaller value is the mode, in about half of the resamples
    tie = describe_histogram([0, 500, 0, 500], np.random.default_rng(5))
    assert tie["mode"] == 1 and 0.4 < tie["mode_prob"] < 0.6
    assert describe_histogram([0, 0, 7])["mode_prob"] == 1.0       # one value only


@pytest.mark.parametrize("hist", [[0, 3, 1], [4, 0, 0, 4], [1, 2, 3, 4, 5], [0, 0, 1]])
def test_quantiles_are_the_smallest_values_reaching_each_level(hist):
    st = describe_histogram(hist, np.random.default_rng(0), boot=10)
    cum = np.cumsum(hist) / sum(hist)
    want = [next(v for v in range(len(hist)) if cum[v] >= q) for q in E.QUANTILE_LEVELS]
    assert st["quantiles"] == want and all(type(x) is int for x in want)
    assert E.QUANTILE_LEVELS == (0.1, 0.25, 0.5, 0.75, 0.9)


def test_describe_histogram_degenerate():
    empty = describe_histogram([0, 0, 0])
    assert empty == {"count": 0, "hist": [0, 0, 0], "mean": None, "se": None, "mode": None,
                     "mode_se": None, "mean_ci": [None, None], "mode_ci": [None, None],
                     "mode_prob": None, "quantiles": [None] * 5}
    one = describe_histogram([0, 0, 1])
    assert (one["mean"], one["se"], one["mode"], one["mode_se"]) == (2.0, None, 2, None)
    assert one["mean_ci"] == [2.0, 2.0] and one["mode_ci"] == [2, 2]
    assert one["mode_prob"] == 1.0 and one["quantiles"] == [2] * 5
    two = describe_histogram([1, 0, 1], np.random.default_rng(1), boot=50)
    assert two["se"] == pytest.approx(1.0) and two["mode"] == 0


@pytest.mark.parametrize("hist, seed", [([10, 5, 4], 0), ([4, 6, 3, 8, 8], 1), ([4, 6, 5, 11], 0)])
def test_mode_interval_percentiles(hist, seed):
    # histograms whose resampled modes separate the 2.5th from the 3.5th percentile, the 97.5th
    # from the 98.5th, or the nearest-rank percentile from the interpolated one
    st = describe_histogram(hist, np.random.default_rng(seed))
    assert st["mode_ci"] == documented_bootstrap(np.array(hist), seed, 2000)["mode_ci"]


def test_describe_histogram_types_and_default_stream():
    st = describe_histogram([0.0, 3.0, 1.0])
    assert st["hist"] == [0, 3, 1] and all(type(x) is int for x in st["hist"])
    rng = np.random.default_rng(5)
    big = np.bincount(rng.binomial(30, 0.3, size=4000), minlength=31)
    assert describe_histogram(big) == describe_histogram(big, np.random.default_rng(0))
    assert describe_histogram(big)["mean_ci"] != describe_histogram(
        big, np.random.default_rng(1))["mean_ci"]


# ----------------------------------------------------------------- per-sigma statistics
def test_statistics_match_per_run_arrays():
    res = ensemble([0.12, 0.2, 0.35], 12, chunk=5, n=20, t_transient=30.0, t_window=20.0,
                   seed=123, progress=False)
    for s in res.per_sigma:
        kept = s.runs - s.excluded - s.failed
        assert len(s.sites) == kept and len(s.pipes) == kept
        if kept:
            st = s.stats["sites"]
            assert sum(st["hist"]) == kept
            assert st["mean"] == pytest.approx(np.mean(s.sites), rel=1e-12)
            assert st["mode"] == int(np.argmax(np.bincount(s.sites)))
            assert np.all(s.sites >= 1) and np.all(s.sites <= 21)
            assert np.all(s.pipes <= 2 * s.sites) and np.all(s.pipes >= s.sites - 1)
    back = EnsembleResult.from_dict(res.as_dict())
    assert np.allclose(back.column("pipes", "mean"), res.column("pipes", "mean"),
                       equal_nan=True)
    assert back.column("pipes", "mode_ci").shape == (3, 2)
    assert np.array_equal(back.column("pipes", "mode_prob"), res.column("pipes", "mode_prob"),
                          equal_nan=True)


def test_combine_statistics_use_their_own_bootstrap_stream():
    # the bootstrap generator of sigma is SeedSequence([seed, 1, key(sigma)]); pipes first
    res = ensemble([0.22, 0.4], 5, chunk=2, sigma0=[0.3, 0.25], **KW)
    for st in res.per_sigma:
        rng = np.random.default_rng(boot_seed_ref(KW["seed"], st.sigma))
        hp = np.bincount(st.pipes, minlength=KW["n"] + 1)
        hs = np.bincount(st.sites, minlength=KW["n"] + 2)
        assert st.stats["pipes"] == describe_histogram(hp, rng)
        assert st.stats["sites"] == describe_histogram(hs, rng)


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


def test_result_dtypes_and_failures_in_dicts():
    a = _stats(0.3, [1, 0, 2], 3, failed=2, hist_p=(0, 2, 1), hist_s=(0, 3, 0))
    res = EnsembleResult(params={"n": 2}, per_sigma=[a, _stats(0.4, [1, 1, 1], 3)])
    assert res.column("pipes", "mode").dtype == float
    assert res.column("pipes", "mode_ci").dtype == float
    assert res.column("pipes", "mode_prob").dtype == float
    assert a.as_dict()["failures"] == [[0, "x"], [0, "x"]]
    back = EnsembleResult.from_dict(json.loads(json.dumps(res.as_dict())))
    st = back.per_sigma[0]
    assert st.pipes.dtype == np.int64 and st.sites.dtype == np.int64
    assert st.pipes.tolist() == [] and st.sites.tolist() == []
    assert st.failures == [(0, "x"), (0, "x")] and st.failed == 2


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
    # the mean reaches half the row (7 of 14 pipes) between 0.2 (2) and 0.4 (10): 0.2 + 5/8 0.2
    assert out["half"] == pytest.approx([0.325, 0.325, 0.325])
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
    assert math.isnan(low["half"][0])             # the mean never reaches half the row
    # (an unusable last sigma: "from which on" cannot be claimed)
    one = thresholds(_result([0.1, 0.2], [_point(3, 30), _point(5, 3)]), level=2, boot=2)
    assert math.isnan(one["steep"][0]) and math.isnan(one["mode"][0])
    one = thresholds(_result([0.1, 0.2], [_point(3, 3), _point(5, 30)]), level=2, boot=2)
    assert math.isnan(one["steep"][0]) and one["mode"] == [0.2, 0.2, 0.2]
    single = thresholds(_result([0.3], [_point(12, 30)]), boot=2)
    assert single["mode"] == [0.3, 0.3, 0.3] and math.isnan(single["steep"][0])
    assert math.isnan(single["half"][0])          # above half at the first usable sigma


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
    # the mean (10 pipes, resampled: 9..11) crosses 7 between 0.1 and 0.2, near 0.1 + 6/9 0.1
    assert out["half"][0] == pytest.approx(0.1 + 6 / 9 * 0.1)
    assert out["half"][1] < out["half"][0] < out["half"][2]


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


def test_thresholds_bootstrap_percentiles_by_hand():
    rng = np.random.default_rng(21)
    sig = [0.1 + 0.02 * i for i in range(12)]
    hists = [np.bincount(rng.binomial(14, p, size=25), minlength=15).astype(float)
             for p in np.linspace(0.2, 0.8, 12)]
    res = _result(sig, [h.astype(int).tolist() for h in hists])
    out = thresholds(res, level=8, min_kept=20, boot=60, seed=123)
    m0, h0, s0 = documented_thresholds_estimate(sig, hists, 8, 20)
    brng = np.random.default_rng(123)
    bm, bh, bs = [], [], []
    for _ in range(60):
        hb = [brng.multinomial(int(h.sum()), h / h.sum()).astype(float) for h in hists]
        a, b, c = documented_thresholds_estimate(sig, hb, 8, 20)
        bm.append(a)
        bh.append(b)
        bs.append(c)

    def q(x):
        x = [v for v in x if not math.isnan(v)]
        return np.percentile(x, [16, 84]).tolist()

    assert out["mode"][0] == m0 and out["steep"][0] == pytest.approx(s0)
    assert out["half"][0] == pytest.approx(h0, rel=1e-12)
    assert out["mode"][1:] == pytest.approx(q(bm)) and out["steep"][1:] == pytest.approx(q(bs))
    assert out["half"][1:] == pytest.approx(q(bh), rel=1e-12)
    # (this seed separates the 16th from the 17th and the 84th from the 85th percentile)
    assert q(bs)[0] != np.percentile(bs, 17) and q(bs)[1] != np.percentile(bs, 85)
    assert thresholds(res, level=8, min_kept=20, boot=60, seed=123) == out   # reproducible


def test_thresholds_defaults_used_by_calls(monkeypatch):
    # level 10, min_kept 20, 400 resamples from seed 0 (a mutated default does not show in
    # the signature of the wrapper that mutation testing puts around a function)
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
