"""Thread safety of ``symhx.impact``: the mpmath engine computes in its thread's own mpmath
context, so runs at different precisions in 8 threads -- next to a thread that keeps changing
mpmath's global precision -- give the serial results bit for bit; ensembles on thread pools (a
``ThreadPoolExecutor``, dask's threaded workers) give the serial numbers."""

from __future__ import annotations

import json
import threading
from concurrent.futures import ThreadPoolExecutor

import mpmath
import numpy as np
import pytest

from symhx.impact import PipeRow, simulate
from symhx.impact.ensemble import ensemble


def _rows():
    return [PipeRow.random(n, 0.5, seed=seed, restitution=r)
            for n, seed, r in ((2, 1, 0.8), (3, 2, 0.5), (2, 3, 0.0), (4, 4, 1.0))]


def _fingerprint(row, dps):
    """Every number of a short run of the mpmath engine, bit for bit: event times, velocities,
    the accumulation times and the state at t = 1.5 (its mantissas and exponents)."""
    h = simulate(row, 3.0, dps=dps)
    x, v = h.state(1.5)
    bits = [t._mpf_ for t in (*h.times, *h.u_before, *h.u_after, *h.aux, *x, *v)]
    return len(h), h.kinds.tolist(), h.sites.tolist(), bits


def test_mpmath_engine_in_eight_threads_with_mixed_dps_is_bit_identical_to_serial():
    rows = _rows()
    tasks = [(i, dps) for i in range(len(rows)) for dps in (8, 15, 27, 40)] * 3   # 48 runs
    serial = {(i, dps): _fingerprint(rows[i], dps) for i, dps in set(tasks)}
    assert len({serial[(0, d)][3][0] for d in (8, 15, 27, 40)}) == 4   # dps matters
    stop = threading.Event()

    def meddle():   # a user's code changing mpmath's global precision all the time
        while not stop.is_set():
            for d in (3, 60, 11):
                with mpmath.workdps(d):
                    mpmath.mpf(1) / 3

    spoiler = threading.Thread(target=meddle)
    spoiler.start()
    try:
        with ThreadPoolExecutor(8) as ex:
            got = list(ex.map(lambda task: (task, _fingerprint(rows[task[0]], task[1])), tasks))
    finally:
        stop.set()
        spoiler.join()
    bad = [task for task, fp in got if fp != serial[task]]
    assert bad == [], f"{len(bad)} of {len(got)} threaded runs differ from the serial ones"
    assert mpmath.mp.dps == 15


def test_history_states_in_threads_are_bit_identical():
    # a history made in one thread, read in eight others at other working precisions
    row = _rows()[1]
    h = simulate(row, 3.0, dps=30)
    ts = ["0.25", "1", "1.75", "2.5"]
    ref = [tuple(a._mpf_ for a in h.state(t)[0]) for t in ts]

    def read(k):
        return [tuple(a._mpf_ for a in h.state(t)[0]) for t in ts]

    before = mpmath.mp.dps
    try:
        mpmath.mp.dps = 7          # the user's global precision is irrelevant to the readers
        with ThreadPoolExecutor(8) as ex:
            outs = list(ex.map(read, range(16)))
    finally:
        mpmath.mp.dps = before
    assert all(out == ref for out in outs)


KW = dict(n=20, t_transient=30.0, t_window=20.0, seed=123, progress=False)
SIGMAS = [0.12, 0.2, 0.35]


def _key(res):
    return [(s.sigma, s.runs, s.excluded, s.failed, s.pipes.tolist(), s.sites.tolist(),
             s.site_hits.tolist(), s.events, s.impacts, json.dumps(s.stats, sort_keys=True))
            for s in res.per_sigma]


def test_ensemble_on_thread_pools_equals_the_serial_ensemble():
    serial = ensemble(SIGMAS, 12, chunk=5, **KW)
    with ThreadPoolExecutor(8) as ex:
        threaded = ensemble(SIGMAS, 12, chunk=1, executor=ex, **KW)
    assert _key(threaded) == _key(serial)
    # two ensembles at once in threads of one pool: each still its own serial numbers
    other = ensemble([0.3], 6, chunk=3, **{**KW, "seed": 5})
    with ThreadPoolExecutor(2) as outer, ThreadPoolExecutor(4) as inner:
        a = outer.submit(ensemble, SIGMAS, 12, chunk=2, executor=inner, **KW)
        b = outer.submit(ensemble, [0.3], 6, chunk=1, executor=inner, **{**KW, "seed": 5})
        assert _key(a.result()) == _key(serial) and _key(b.result()) == _key(other)


@pytest.mark.slow
def test_ensemble_on_dask_threaded_workers_equals_the_serial_ensemble():
    distributed = pytest.importorskip("distributed")
    serial = ensemble(SIGMAS, 12, chunk=5, **KW)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=4, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        res = ensemble(SIGMAS, 12, chunk=2, executor=client.get_executor(), **KW)
    assert _key(res) == _key(serial)
    assert np.isfinite(res.column("pipes", "mean")).any()
