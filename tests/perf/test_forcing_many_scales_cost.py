"""Cost of sums of many Rayleigh amplitudes (issue 28, item 4): time per threshold, memory
against the number of thresholds, and ``MAX_SCALES`` refused before any work.

Times are CPU times of this process (``time.process_time``), the best of a few repeats, so a
machine shared with other jobs does not make them flaky; the targets are the issue's.
"""

from __future__ import annotations

import time
import tracemalloc

import numpy as np
import pytest

import symhx
from symhx.cli import main as cli_main
from symhx.forcing import MAX_SCALES


def cpu_time(fn, repeats=3):
    best = float("inf")
    for _ in range(repeats):
        t = time.process_time()
        fn()
        best = min(best, time.process_time() - t)
    return best


def spread_scales(m, seed=1):
    return [float(s) for s in 10 ** np.random.default_rng(seed).uniform(-8, 0, m)]


@pytest.mark.parametrize("m", [7, MAX_SCALES])
def test_cost_of_float64_is_below_50_ms_a_threshold(m):
    """float64 with up to MAX_SCALES scales spread over 1e-8..1: at most 50 ms a threshold,
    for one threshold and per threshold of a 20-threshold array, from the far lower to the far
    upper tail (the issue: seven unit scales took 18 s and ended in MemoryError)."""
    S = symhx.RayleighSum(spread_scales(m))
    mean, std = S.mean(), S.std()
    xs = np.concatenate([mean * np.geomspace(1e-3, 0.9, 10), mean + std * np.linspace(0, 30, 10)])
    S.sf(xs)   # the one-off Taylor table of L is not the cost of a threshold
    assert cpu_time(lambda: S.sf(float(mean))) < 0.05
    assert cpu_time(lambda: S.sf(xs)) / xs.size < 0.05
    assert cpu_time(lambda: symhx.RayleighSum([1.0] * 7).sf(5.29)) < 0.05


def test_cost_of_dps_30_for_eight_scales_is_below_2_s():
    """dps=30 with eight distinct scales (spread over 1e-8..1): below 2 s for each of sf, cdf,
    pdf at a bulk and a far-tail threshold."""
    S = symhx.RayleighSum(spread_scales(8))
    mean, std = S.mean(), S.std()
    for x in (mean, mean + 20 * std):
        for kind in ("sf", "cdf", "pdf"):
            t = cpu_time(lambda kind=kind, x=x: getattr(S, kind)(x, dps=30), repeats=1)
            assert t < 2.0, (kind, x, t)


def peak_bytes(fn):
    tracemalloc.start()
    try:
        fn()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


@pytest.mark.slow
def test_memory_does_not_grow_with_the_number_of_thresholds():
    """Five scales: the evaluation works in chunks of a fixed number of contour values, so the
    peak memory of 2700 thresholds exceeds that of 900 (already two chunks) by no more than
    128 float arrays of the thresholds (measured: ~66 MiB, +0.3-0.6 kB a threshold), and
    stays below 128 MiB (the issue's five scales and 500 thresholds built a 1.9 GiB array).
    Five forcing components and 200 sigmas stay below the same bound."""
    S = symhx.RayleighSum([1.0, 0.7, 0.5, 0.3, 0.2])
    small, large = np.linspace(0.5, 8, 900), np.linspace(0.5, 8, 2700)
    S.sf(small[:10])
    base = peak_bytes(lambda: S.sf(small))
    grown = peak_bytes(lambda: S.sf(large)) - base
    assert grown < 128 * 8 * (large.size - small.size), (base, grown)   # measured ~600 B
    assert base < 128 * 2**20
    sig = np.linspace(0.05, 0.6, 200)
    om = [1.5, 2, 2.5, 3, 3.5]
    assert peak_bytes(lambda: symhx.impact_probability(sig, Omega=om)) < 128 * 2**20


def test_cost_of_a_refused_scale_count_is_nothing():
    """MAX_SCALES is checked before any conversion or evaluation: a million scales (or
    components) are refused at once by the API and by the CLI."""
    many = [1.0] * 10**6
    t = time.process_time()
    with pytest.raises(ValueError, match="MAX_SCALES"):
        symhx.RayleighSum(many)
    with pytest.raises(ValueError, match="MAX_SCALES"):
        symhx.rayleigh_sum_probability(many, 1.0, dps=30)
    with pytest.raises(ValueError, match="MAX_SCALES"):
        symhx.impact_probability(0.2, Omega=many, dps=30)
    assert time.process_time() - t < 1.0
    t = time.process_time()
    assert cli_main(["p-sigma", "0.2", "--dps", "30", "--Omega",
                     ",".join(["1.5"] * MAX_SCALES)]) == 2
    assert time.process_time() - t < 1.0
