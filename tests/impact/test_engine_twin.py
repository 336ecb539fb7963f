"""The Python float64 engine (``engine.py`` in :class:`FloatContext`) and its C port
(``_fast.c``) run the same IEEE operations in the same order: on a few rows (forced elastic,
chatter-prone, plastic, two forcing frequencies with omega and d not 1) their event tables and
closed-form pieces are equal bit for bit. A step of the certified search that differs from the
documented one (a bound, a tolerance, a branch at a rounding limit) moves some event or resume
point and shows here, even where both answers would be within rounding of the truth. The longer
twin campaign (hundreds of seeded rows) is ``tests/impact/test_fast.py``."""

from __future__ import annotations

import numpy as np
import pytest

from symhx.impact import SQRT2, PipeRow, simulate
from symhx.impact.fast import available

pytestmark = pytest.mark.skipif(not available(), reason="C extension not built")

ROWS = [
    (PipeRow.random(10, 0.3, seed=1, restitution=0.8), 20.0),
    (PipeRow.random(8, 0.6, seed=5, restitution=0.5), 30.0),
    (PipeRow.random(12, 0.5, seed=4, restitution=0.0), 20.0),
    (PipeRow.random(6, 0.4, seed=7, restitution=1.0, Omega=(0.0, 2.3), omega=1.7, d=0.6), 20.0),
    (PipeRow.random(10, 1.0, seed=3, restitution=0.3, Omega=(SQRT2, 0.37), d=3.0), 10.0),
    # rare paths: plastic under a constant force and three frequencies (contacts that start on
    # the third derivative), a violent inelastic row, a chatter under a constant force
    (PipeRow.random(6, 2.0, seed=0, restitution=0.0, Omega=(0.0, 2.3, 0.37), omega=1.7, d=0.6),
     25.0),
    (PipeRow.random(5, 10.0, seed=0, restitution=0.3), 30.0),
    (PipeRow(1, d=0.6, restitution=0.4, Omega=(0.0,), alpha=[[3.0]], beta=[[0.0]], x0=[0.3],
             v0=[0.0]), 6.0),
    # two rows of the seeded twin campaign of test_fast.py whose cubic-improved search steps
    # stop doubling on the bound's interior minimum
    (PipeRow.random(9, 0.35789410755460677, seed=1433274860, restitution=0.8,
                    omega=0.6122246581527426, d=1.0, Omega=(0.37, 1.9)), 19.600647965090857),
    (PipeRow.random(8, 0.8026490311094782, seed=1561042993, restitution=0.5,
                    omega=2.0836765649861246, d=1.0, Omega=(SQRT2,)), 5.759051189444034),
]


@pytest.mark.parametrize("k", range(len(ROWS)))
def test_python_float_engine_equals_its_c_port_bit_for_bit(k):
    row, t_end = ROWS[k]
    a = simulate(row, t_end, engine="python")
    b = simulate(row, t_end, engine="c")
    assert len(a) >= 10
    ta = np.column_stack([a.times, a.sites, a.kinds, a.u_before, a.u_after, a.aux])
    tb = np.column_stack([b.times, b.sites, b.kinds, b.u_before, b.u_after, b.aux])
    assert np.array_equal(ta, tb), "event tables differ"
    (sa, ca), (sb, cb) = a.pieces(), b.pieces()
    assert len(sa) == len(sb)
    for j in range(len(sa)):
        assert sa[j] == sb[j], j
        assert np.array_equal(np.asarray(ca[j], dtype=float), np.asarray(cb[j], dtype=float)), j
