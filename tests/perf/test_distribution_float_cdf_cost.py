"""Cost of the float64 cdf family beyond the table (``dps=None``, ``N > FLOAT_N_LIMIT``): after
the one 17-digit pass for the normaliser, 1000 distinct k call no partial sum of the engine,
and each k costs a bounded number of float evaluations of ``log Phi`` (counted, not timed)."""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
import pytest

import symhx
import symhx.float_sums as float_sums
from symhx.simple_sums import SimpleSums
from tests.reference.distribution_large_n import critical_p

#: float evaluations of log Phi per distinct k (windows of far tails are the dearest: ~20 Newton
#: steps and up to a few hundred terms); measured 30-170 on the grid below
PER_K = 400
#: the structure of one distribution (panels, direct blocks, totals): measured 8e3-2.5e4
STRUCTURE = 60_000


@pytest.mark.parametrize("N", [10**10, 10**100, 10**300], ids=["1e10", "1e100", "1e300"])
@pytest.mark.parametrize("ratio", ["0.5", "2", "10"])
def test_thousand_k_cost_no_engine_sums_and_bounded_float_work(
        N: int, ratio: str, monkeypatch: pytest.MonkeyPatch) -> None:
    d = symhx.distribution_of(N, critical_p(N) * Fraction(ratio), dps=None)
    d.log_normaliser  # noqa: B018 - the one pass of the 17-digit engine
    engine_sums = [0]
    evals = [0]
    sums = SimpleSums.sums
    direct = float_sums.log_phi_diff_real

    def count_sums(self: SimpleSums, *a: Any, **kw: Any) -> Any:
        engine_sums[0] += 1
        return sums(self, *a, **kw)

    def count_evals(c: int, lpx: float, x: float, k: Any, dd: Any, y: Any) -> Any:
        evals[0] += int(np.size(k))
        return direct(c, lpx, x, k, dd, y)

    monkeypatch.setattr(SimpleSums, "sums", count_sums)
    monkeypatch.setattr(float_sums, "log_phi_diff_real", count_evals)
    d.cdf(N // 3)  # builds the structure
    assert evals[0] <= STRUCTURE
    ks = np.array(sorted({int(v) for v in np.geomspace(1, float(N) / 1.0000001, 1000)}),
                  dtype=object)
    evals[0] = 0
    for name in ("cdf", "sf", "logcdf", "logsf"):
        getattr(d, name)(ks)
    assert engine_sums[0] == 0
    assert evals[0] <= 4 * PER_K * len(ks)
