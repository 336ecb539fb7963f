"""Ensembles: reproducibility across executors/chunking, statistics, and the p(sigma) link."""

from __future__ import annotations

import math
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

from symhx.forcing import impact_probability
from symhx.impact.ensemble import EnsembleResult, ensemble, free_flight_closure_fraction

KW = dict(n=20, t_transient=30.0, t_window=20.0, seed=123, progress=False)
SIGMAS = [0.12, 0.2, 0.35]


def _key(res):
    return [(s.sigma, s.excluded, s.pipes.tolist(), s.sites.tolist()) for s in res.per_sigma]


@pytest.fixture(scope="module")
def serial():
    return ensemble(SIGMAS, 12, chunk=5, **KW)


def test_reproducible_across_executors_and_chunking(serial):
    with ProcessPoolExecutor(2) as ex:
        par = ensemble(SIGMAS, 12, chunk=3, executor=ex, **KW)
    with ThreadPoolExecutor(3) as ex:
        thr = ensemble(SIGMAS, 12, chunk=7, executor=ex, **KW)
    assert _key(par) == _key(serial) == _key(thr)
    other = ensemble(SIGMAS, 12, chunk=5, **{**KW, "seed": 124})
    assert _key(other) != _key(serial)


def test_dask_distributed_executor_gives_serial_numbers(serial):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        res = ensemble(SIGMAS, 12, chunk=4, executor=client.get_executor(), **KW)
    assert _key(res) == _key(serial)


def test_statistics_are_consistent(serial):
    for s in serial.per_sigma:
        kept = s.runs - s.excluded
        assert len(s.sites) == kept and len(s.pipes) == kept
        if kept:
            st = s.stats["sites"]
            assert sum(st["hist"]) == kept
            assert st["mean"] == pytest.approx(np.mean(s.sites))
            assert st["mode"] == int(np.argmax(np.bincount(s.sites)))
            assert np.all(s.sites >= 1) and np.all(s.sites <= 21)
            # a site count k involves between ceil(k/2)... at most 2k and at least k - 1 pipes
            assert np.all(s.pipes <= 2 * s.sites) and np.all(s.pipes >= s.sites - 1)
    # more forcing, more impacts
    means = serial.column("sites", "mean")
    assert means[-1] > means[0] or math.isnan(means[0])
    back = EnsembleResult.from_dict(serial.as_dict())
    assert np.allclose(back.column("pipes", "mean"), serial.column("pipes", "mean"),
                       equal_nan=True)


def test_progress_bar(capsys):
    ensemble([0.2], 3, **{**KW, "progress": True})
    err = capsys.readouterr().err
    assert "3/3 runs" in err


@pytest.mark.parametrize("sigma", [0.2, 0.3])
def test_free_flight_closure_fraction_approaches_impact_probability(sigma):
    gaps = 3000
    f = free_flight_closure_fraction(sigma, gaps, horizon=600.0, seed=7)
    p = float(impact_probability(sigma))
    se = math.sqrt(p * (1 - p) / gaps)
    assert abs(f - p) < 4 * se


def test_bad_input():
    with pytest.raises(ValueError, match="sigmas"):
        ensemble([], 3, **KW)
    with pytest.raises(ValueError, match="runs"):
        ensemble([0.1], 0, **KW)
    with pytest.raises(ValueError, match="t_window"):
        ensemble([0.1], 2, **{**KW, "t_window": 0.0})
