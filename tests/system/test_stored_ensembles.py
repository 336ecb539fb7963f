"""The stored ensembles (symhx/data/ensemble_*.json) are what the current engine computes.

The book's figures and tables of the simulation are read from these files, so a change of the
engine that moves any trajectory must come with regenerated data.  A run's seed depends only on
its sigma (``symhx.impact.ensemble.run_seed``), so one column of a stored grid is recomputed alone
and compared bit for bit: the histograms, the site hits, the event and impact counts.
"""

from __future__ import annotations

import json
from importlib import resources

import pytest

from symhx.impact import EnsembleResult
from symhx.impact.ensemble import (
    column_stats,
    ensemble,
    sigma_key,
    site_transitions,
    transition_dependence,
)
from symhx.impact.model import SQRT2


def _load(name):
    return json.loads(resources.files("symhx.data").joinpath(name).read_text())


def _recompute(params, sigma, sigma0):
    p = params
    Omega = tuple(SQRT2 if w == repr(SQRT2) else float(w) for w in p["Omega"])
    return ensemble([sigma], p["runs"], n=p["n"], t_transient=p["t_transient"],
                    t_window=p["t_window"], seed=p["seed"], restitution=p["restitution"],
                    omega=p["omega"], d=p["d"], Omega=Omega, sigma0=sigma0, progress=False,
                    keep_runs=False).per_sigma[0]


def _same(stored, got):
    assert (got.runs, got.excluded, got.failed, got.events, got.impacts) == (
        stored.runs, stored.excluded, stored.failed, stored.events, stored.impacts)
    assert got.site_hits.tolist() == stored.site_hits.tolist()
    assert got.stats == stored.stats      # histograms, and the bootstrap keyed by sigma too


@pytest.mark.parametrize("label, sigma", [
    ("base r=0.8 T=200 W=100 sigma0=sigma", 0.12),
    ("base r=0.8 T=200 W=100 sigma0=sigma", 0.15),
    ("r=1", 0.12),
    ("sigma0=2 sigma", 0.11),
])
def test_calibration_columns_are_reproduced(label, sigma):
    d = _load("ensemble_calibration.json")["configs"][label]
    res = EnsembleResult.from_dict(d)
    i = next(i for i, s in enumerate(res.per_sigma) if s.sigma == sigma)
    s0 = d["params"]["sigma0"]
    _same(res.per_sigma[i], _recompute(d["params"], sigma, None if s0 == "sigma" else s0[i]))


@pytest.mark.parametrize("name", ["ensemble_fig7_8.json", "ensemble_calibration.json"])
def test_stored_statistics_are_those_of_the_stored_histograms(name):
    # every column of every stored ensemble: mean, quantiles, mode, mode_prob and the bootstrap
    # intervals are what the ensemble computes from the column's two histograms and (seed, sigma)
    data = _load(name)
    for ens in data["configs"].values() if "configs" in data else [data]:
        for col in ens["per_sigma"]:
            got = column_stats(col["pipes"]["hist"], col["sites"]["hist"], ens["params"]["seed"],
                               col["sigma"])
            assert json.loads(json.dumps(got)) == {"pipes": col["pipes"], "sites": col["sites"]}
            assert set(col["pipes"]) >= {"mode_prob", "quantiles"}


def test_production_column_is_reproduced():
    d = _load("ensemble_fig7_8.json")
    res = EnsembleResult.from_dict(d)
    assert "partial" not in d["params"] and d["params"]["runs"] == 10**4
    assert [s.runs for s in res.per_sigma] == [10**4] * len(res.per_sigma)
    st = next(s for s in res.per_sigma if s.sigma == 0.1)
    assert st.impacts > 0                      # a column with impacts, cheap to recompute
    _same(st, _recompute(d["params"], 0.1, None))


def test_assumption_sequences_are_reproduced():
    d = _load("ensemble_assumptions.json")
    p = d["params"]
    a = d["per_sigma"][0]
    seqs = site_transitions(a["sigma"], p["runs"], n=p["pipes"], t_transient=p["t_transient"],
                            t_window=p["t_window"], seed=p["seed"],
                            restitution=p["restitution"])
    dep = transition_dependence(seqs, p["pipes"] + 1, shuffles=p["shuffles"],
                                seed=sigma_key(a["sigma"]))
    for key in ("pairs", "mi", "mi_null", "same", "adjacent"):
        assert dep[key] == a[key], key
