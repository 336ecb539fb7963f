"""The float64 table path (``dps=None``, ``N <= FLOAT_N_LIMIT``) at the top of the support:
``cdf``/``logcdf`` at and beyond ``N`` are exactly ``1`` and ``+0.0`` (``log 1``, as scipy
returns), ``sf``/``logsf`` exactly ``0`` and ``-inf``, for scalars and arrays alike."""

from __future__ import annotations

import numpy as np
import pytest

import symhx


@pytest.mark.parametrize(("N", "p", "space"), [(10, 0.3, "simple"), (40, 0.9, "simple"),
                                               (12, 0.5, "eq41")])
def test_float_tails_at_and_beyond_n_are_exact_limits(N, p, space):
    d = symhx.distribution_of(N, p, space=space, dps=None)
    for k in (N, N + 1, 10**30):
        lc = d.logcdf(k)
        assert lc == 0.0 and not np.signbit(lc), (k, lc)
        assert d.cdf(k) == 1.0
        assert d.sf(k) == 0.0
        assert d.logsf(k) == -np.inf
    arr = d.logcdf(np.array([N, N + 1]))
    assert arr.dtype == np.float64
    assert not np.signbit(arr).any() and (arr == 0.0).all()
    assert d.logcdf(N - 1) < 0 < d.sf(N - 1)
