"""Float64 C engine: impact-by-impact agreement with the mpmath reference and the Python port."""

from __future__ import annotations

import numpy as np
import pytest

from symhx.impact import IMPACT, STICK, PipeRow, simulate
from symhx.impact.fast import available, count_impacts

pytestmark = pytest.mark.skipif(not available(), reason="C extension not built")


@pytest.mark.parametrize("seed, r", [(1, 1.0), (2, 0.8), (3, 0.95)])
def test_fast_matches_reference_impact_by_impact(seed, r):
    row = PipeRow.random(10, 0.3, seed=seed, restitution=r)
    ref = simulate(row, 25.0, dps=30)
    fast = simulate(row, 25.0)
    assert len(ref) >= 30
    assert fast.sites.tolist() == ref.sites.tolist()
    assert fast.kinds.tolist() == ref.kinds.tolist()
    err = max(abs(float(a) - b) for a, b in zip(ref.times, fast.times, strict=True))
    assert err < 1e-9


@pytest.mark.parametrize("seed, r, sigma", [(4, 0.0, 0.5), (5, 0.5, 0.6), (6, 1.0, 0.4)])
def test_c_port_identical_to_python_float_engine(seed, r, sigma):
    # same algorithm, same IEEE arithmetic: identical events, including chatter and sticking
    row = PipeRow.random(12, sigma, seed=seed, restitution=r)
    a = simulate(row, 60.0, engine="python")
    b = simulate(row, 60.0, engine="c")
    assert a.sites.tolist() == b.sites.tolist() and a.kinds.tolist() == b.kinds.tolist()
    np.testing.assert_allclose(a.times, b.times, rtol=0, atol=1e-12)
    x1, v1 = a.state(59.0)
    x2, v2 = b.state(59.0)
    np.testing.assert_allclose(x1, x2, atol=1e-10)
    np.testing.assert_allclose(v1, v2, atol=1e-10)


def test_count_impacts_matches_history():
    row = PipeRow.random(30, 0.3, seed=9, restitution=0.8)
    h = simulate(row, 80.0)
    counts, nev = count_impacts(row, 80.0, 40.0)
    assert nev == len(h)
    sel = np.isin(h.kinds, (IMPACT, STICK)) & (h.times >= 40.0)
    assert counts.tolist() == np.bincount(h.sites[sel], minlength=31).tolist()


def test_max_events_guard():
    row = PipeRow.random(20, 0.4, seed=1, restitution=1.0)
    with pytest.raises(RuntimeError, match="max_events"):
        simulate(row, 100.0, max_events=10)
