"""symhx.impact.sites: per-site and joint per-run hit statistics against a direct count over
simulated histories (the same rows, simulated and counted event by event), against the ensemble of
the same seed, and against statistics computed run by run with numpy; the stored per-run file
against the stored ensemble."""

from __future__ import annotations

import json
import math
from importlib import resources

import numpy as np
import pytest

from symhx.impact import EnsembleResult, PipeRow, ensemble, simulate
from symhx.impact.engine import IMPACT, STICK
from symhx.impact.ensemble import run_seed
from symhx.impact.sites import (
    SiteHitResult,
    SiteHitTable,
    SiteRates,
    hit_table_chunk,
    site_hit_tables,
)
from tests.harness.errors import assert_refuses

SETTING = dict(n=12, t_transient=30.0, t_window=30.0, seed=5)


def direct_counts(sigma: float, runs: int, n: int, t_transient: float, t_window: float,
                  seed: int) -> list[np.ndarray]:
    """Impacts per site in the window of each run, counted event by event from full histories of
    the rows of run_seed (kinds impact and stick, t >= t_transient)."""
    out = []
    for k in range(runs):
        row = PipeRow.random(n, sigma, seed=run_seed(seed, sigma, k))
        h = simulate(row, t_transient + t_window)
        c = np.zeros(n + 1, dtype=int)
        for t, site, kind in zip(h.times, h.sites, h.kinds, strict=True):
            if kind in (IMPACT, STICK) and float(t) >= t_transient:
                c[site] += 1
        out.append(c)
    return out


@pytest.mark.parametrize("sigma", [0.15, 0.25, 0.4])
def test_tables_are_the_direct_count_over_simulated_histories(sigma):
    runs = 25
    counts = direct_counts(sigma, runs, **SETTING)
    table = site_hit_tables([sigma], runs, **SETTING).table(sigma)
    hit = np.array([c > 0 for c in counts])
    assert table.runs == runs and table.failed == 0
    assert table.site_hits.tolist() == hit.sum(axis=0).tolist()
    w = hit[:, 0].astype(int) + hit[:, -1]
    i = hit[:, 1:-1].sum(axis=1)
    joint = np.zeros((3, SETTING["n"]), dtype=int)
    np.add.at(joint, (w, i), 1)
    assert table.joint.tolist() == joint.tolist()
    assert table.sites_histogram().tolist() == np.bincount(w + i, minlength=14).tolist()
    # run-level statistics against numpy over the runs
    wall, interior = w / 2, i / (SETTING["n"] - 1)
    assert table.wall_rate()[0] == pytest.approx(wall.mean(), rel=1e-14)
    assert table.wall_rate()[1] == pytest.approx(wall.std(ddof=1) / math.sqrt(runs), rel=1e-12)
    assert table.interior_rate()[1] == pytest.approx(interior.std(ddof=1) / math.sqrt(runs),
                                                     rel=1e-12)
    from_hist = SiteHitTable.from_histories(
        [simulate(PipeRow.random(12, sigma, seed=run_seed(5, sigma, k)), 60.0)
         for k in range(runs)], t_from=30.0, sigma=sigma)
    assert from_hist.joint.tolist() == joint.tolist()


def test_tables_are_the_runs_of_the_ensemble_with_the_same_seed():
    sig = [0.12, 0.2, 0.3]
    res = site_hit_tables(sig, 40, **SETTING, chunk=7)
    ens = ensemble(sig, 40, **SETTING, progress=False)
    assert res.matches(ens)
    for st, t in zip(ens.per_sigma, res.tables, strict=True):
        rates = SiteRates.from_stats(st)
        assert rates.runs == t.runs and rates.site_hits.tolist() == t.site_hits.tolist()
    other = ensemble(sig, 40, **{**SETTING, "seed": 6}, progress=False)
    assert not res.matches(other)


def test_the_ratio_error_agrees_with_the_bootstrap():
    table = site_hit_tables([0.2], 400, **SETTING).table(0.2)
    r, se = table.rate_ratio()
    rng = np.random.default_rng(1)
    boots = [table.resample(rng).rate_ratio()[0] for _ in range(2000)]
    assert abs(np.mean(boots) - r) < 0.2 * se
    assert 0.85 < np.std(boots) / se < 1.15


def test_the_ratio_error_is_the_delta_method_over_the_runs():
    """rate_ratio's error from per-run arrays and numpy's moments: var(W/I) ~ (var W / mI**2 +
    var I mW**2 / mI**4 - 2 cov(W, I) mW / mI**3) / (R - 1), W = walls hit / 2, I = interior
    sites hit / (n - 1); a table with a strong (negative) correlation, so the covariance term
    matters."""
    joint = np.array([[0, 1, 6, 9], [2, 8, 3, 0], [7, 2, 0, 0]])  # walls 0-2 x interior 0-3
    table = SiteHitTable(0.3, joint, np.zeros(5))
    rows, cols = np.nonzero(joint)
    W = np.repeat(rows / 2.0, joint[rows, cols])
    interior = np.repeat(cols / 3.0, joint[rows, cols])
    R = len(W)
    mw, mi = W.mean(), interior.mean()
    cov = np.cov(W, interior, bias=True)
    var = (cov[0, 0] / mi**2 + cov[1, 1] * mw**2 / mi**4 - 2 * cov[0, 1] * mw / mi**3) / (R - 1)
    r, se = table.rate_ratio()
    assert abs(r - mw / mi) < 1e-12 and abs(se - math.sqrt(var)) < 1e-12 * math.sqrt(var)
    assert abs(table.wall_rate()[1] - math.sqrt(cov[0, 0] / (R - 1))) < 1e-12


def test_rates_by_position_pool_the_mirror_sites():
    hits = np.array([4, 9, 7, 8, 10, 8, 6, 9, 5])    # n = 8
    r = SiteRates(0.3, 10, hits)
    pos, rate, se = r.by_position()
    assert pos.tolist() == [0, 1, 2, 3, 4]
    assert rate.tolist() == pytest.approx([0.45, 0.9, 0.65, 0.8, 1.0])
    q = hits / 10
    se_site = np.sqrt(q * (1 - q) / 10)
    assert se[0] == pytest.approx(math.hypot(se_site[0], se_site[8]) / 2)
    assert se[4] == 0
    assert r.wall_rate() == pytest.approx(0.45) and r.interior_rate() == pytest.approx(57 / 70)


def test_json_round_trip_and_failed_runs(tmp_path):
    res = site_hit_tables([0.3, 1e4], 4, n=5, t_transient=5.0, t_window=5.0, seed=0)
    bad = res.table(1e4)   # displacements far beyond the spacing: no row can be drawn
    assert bad.failed == 4 and bad.runs == 0 and "draw" in bad.failures[0][1]
    with pytest.raises(ValueError, match="no finished run"):
        bad.wall_rate()
    path = tmp_path / "sites.json"
    res.save(path)
    back = SiteHitResult.load(path)
    assert back.params == res.params
    for a, b in zip(back.tables, res.tables, strict=True):
        assert a.as_dict() == b.as_dict()
    assert hit_table_chunk(0.3, [], 5, 1.0, 1.0, 0, 0.8, 1.0, 1.0, (2.0,)) == {
        "counts": [], "failures": []}


def test_stored_file_is_the_stored_ensemble_run_by_run():
    def load(name):
        return json.loads(resources.files("symhx.data").joinpath(name).read_text())

    stored = EnsembleResult.from_dict(load("ensemble_fig7_8.json"))
    sites = SiteHitResult(**{"params": load("ensemble_sites.json")["params"], "tables": [
        SiteHitTable.from_dict(t) for t in load("ensemble_sites.json")["tables"]]})
    assert sites.sigmas.tolist() == stored.sigmas.tolist()
    assert sites.matches(stored)


@pytest.mark.slow
def test_one_stored_column_is_recomputed():
    data = json.loads(resources.files("symhx.data").joinpath("ensemble_sites.json").read_text())
    P = data["params"]
    stored = SiteHitTable.from_dict(next(t for t in data["tables"] if t["sigma"] == 0.1))
    again = site_hit_tables([0.1], P["runs"], n=P["n"], t_transient=P["t_transient"],
                            t_window=P["t_window"], seed=P["seed"]).table(0.1)
    assert again.as_dict() == stored.as_dict()


def test_refusals_name_the_argument():
    assert_refuses(site_hit_tables, [0.1], 0, arg="runs", value="0", allowed=">= 1")
    assert_refuses(site_hit_tables, [-0.1], 3, arg="sigmas[0]", value="-0.1", allowed=">= 0")
    assert_refuses(site_hit_tables, [], 3, arg="sigmas", value="[]")
    # the same checks as ensemble's: a sigma beyond float64 is refused, not run as inf
    assert_refuses(site_hit_tables, ["1e400"], 2, arg="sigmas[0]", value="1.0e+400",
                   allowed="float64 range")
    assert_refuses(site_hit_tables, "0.1", 3, exc=TypeError, arg="sigmas", value="str")
    assert_refuses(site_hit_tables, [0.1], 3, seed=None, exc=TypeError, arg="seed",
                   value="None")
    assert_refuses(site_hit_tables, [0.1], 3, n=0, arg="n", value="0", allowed=">= 1")
    assert_refuses(site_hit_tables, [0.1], 3, restitution=2, arg="restitution", value="2",
                   allowed="<= 1")
    assert_refuses(site_hit_tables, [0.1], 3, executor=1, exc=TypeError, arg="executor",
                   value="int")
    assert_refuses(SiteRates, 0.1, 0, np.array([0, 0]), arg="runs", value="0", allowed=">= 1")
    assert_refuses(SiteRates, 0.1, 2, np.array([3, 0]), arg="site_hits", value="0..3",
                   allowed="[0, runs = 2]")
    assert_refuses(SiteHitTable, 0.1, np.zeros((2, 3)), np.zeros(4), arg="joint",
                   value="(2, 3)", allowed="(3, n)")
    assert_refuses(SiteHitTable.from_histories, [1], exc=TypeError, arg="histories")
    assert_refuses(SiteRates.from_stats, 1, exc=TypeError, arg="stats", value="int")


def test_site_rates_take_any_sequence_of_counts():
    r = SiteRates(0.2, 10, [2, 6, 8, 6, 3])  # a list: stored as an int64 array
    assert isinstance(r.site_hits, np.ndarray) and r.site_hits.dtype == np.int64
    assert r.rate.tolist() == [0.2, 0.6, 0.8, 0.6, 0.3] and r.n == 4
