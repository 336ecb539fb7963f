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


@pytest.mark.parametrize("make", [
    lambda N, p: symhx.distribution_of(N, p, dps=None),
    lambda N, p: symhx.distribution_of(N, p, space="eq41", dps=None),
    lambda N, p: symhx.distribution_of(N, symhx.SiteClasses((2, N - 2), (p, p / 2)), dps=None),
], ids=["simple", "eq41", "site classes"])
def test_float_normaliser_is_inf_beyond_float64_without_a_warning(make):
    # the same contract in every space: a finite log, the normaliser inf once that log passes
    # log(float64 max) = 709.78, no RuntimeWarning; below it exp(log) to float64 rounding
    import math
    import warnings

    small, big = make(40, 0.05), make(3000, 0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert big.normaliser == math.inf and 709.8 < big.log_normaliser < math.inf
        assert abs(math.log(small.normaliser) - small.log_normaliser) < 1e-14 * abs(
            small.log_normaliser) + 1e-15
