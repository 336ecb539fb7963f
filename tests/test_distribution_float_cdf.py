"""cdf, sf, logcdf and logsf of the simple distribution on the float64 path (``dps=None``)
beyond the table (``N > FLOAT_N_LIMIT``), through the public API, against independent
references: the mpmath engine at 30 digits (another method), the log-series law below the
jump and the Poisson law near ``k = N`` (closed forms, exact to ``j**2/N``)."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx
from tests.reference.distribution_large_n import (
    critical_p,
    log_poisson_side_tails,
    log_series_tails,
)

GRID_N = [10**7 + 1, 10**8, 10**10, 10**15, 10**20, 10**50, 10**100, 10**300]
NAMES = ("cdf", "sf", "logcdf", "logsf")


def _nid(v: object) -> str:
    """Short test ids: 10**300 as '1e300'."""
    if isinstance(v, int) and v > 10**6:
        return f"N~1e{len(str(v)) - 1}"
    return str(v)


def _float_family(N: int, p: Fraction, ks: list[int]) -> dict[str, np.ndarray]:
    d = symhx.distribution_of(N, p, dps=None)
    arr = np.array(ks, dtype=object)
    return {name: np.asarray(getattr(d, name)(arr), dtype=float) for name in NAMES}


def _check(got: dict[str, np.ndarray], i: int, log_lo: mpmath.mpf, log_up: mpmath.mpf,
           what: str) -> None:
    """Log forms to 1e-13 (1 + |value|) absolute; cdf and sf to 1e-13 relative where they are
    at least 1e-300; cdf + sf = 1 to 1e-15."""
    for name, want in (("logcdf", log_lo), ("logsf", log_up)):
        g = got[name][i]
        if want == mpmath.ninf:
            assert g == -np.inf, (what, name, g)
            continue
        assert abs(g - float(want)) <= 1e-13 * (1 + abs(float(want))), (what, name, g, want)
    for name, want in (("cdf", log_lo), ("sf", log_up)):
        w = mpmath.exp(want)
        if w >= 1e-300:
            assert abs(got[name][i] - float(w)) <= 1e-13 * float(w), (what, name, got[name][i], w)
    assert abs(got["cdf"][i] + got["sf"][i] - 1) <= 1e-15, what


def _engine_ks(N: int, p: Fraction) -> list[int]:
    """The bulk (median and its neighbours, +-3 sigma) and both far tails."""
    med = int(symhx.distribution_of(N, p, dps=None).median())
    sd = int(symhx.distribution_of(N, p, dps=None).std()) + 1
    ks = {1, 2, med - 1, med, med + 1, med - 3 * sd, med + 3 * sd, max(1, med // 10**3),
          N - 1, N - 2, med + 40 * sd}
    return sorted(k for k in ks if 1 <= k <= N - 1)


def _engine_case(N: int, p: Fraction) -> None:
    ks = _engine_ks(N, p)
    got = _float_family(N, p, ks)
    ref = symhx.distribution_of(N, p, dps=30)
    for i, k in enumerate(ks):
        _check(got, i, ref.logcdf(k), ref.logsf(k), f"N={N} p={p} k={k}")


FAST_ENGINE = [(10**7 + 1, "2"), (10**10, "1.001"), (10**10, "1e3"), (10**100, "10"),
               (10**300, "2")]


@pytest.mark.parametrize(("N", "ratio"), FAST_ENGINE, ids=_nid)
def test_cdf_family_matches_the_30_digit_engine(N: int, ratio: str) -> None:
    _engine_case(N, critical_p(N) * Fraction(ratio))


@pytest.mark.slow
@pytest.mark.parametrize("N", GRID_N, ids=_nid)
@pytest.mark.parametrize("ratio", ["1e-3", "0.5", "0.999", "1.001", "2", "10", "1e3"])
def test_cdf_family_matches_the_30_digit_engine_on_the_grid(N: int, ratio: str) -> None:
    if (N, ratio) in FAST_ENGINE:
        pytest.skip("in the fast set")
    _engine_case(N, critical_p(N) * Fraction(ratio))


@pytest.mark.slow
@pytest.mark.parametrize("N", GRID_N, ids=_nid)
@pytest.mark.parametrize("p", [Fraction(1, 2), Fraction(1), Fraction(3)])
def test_p_of_order_one_matches_the_30_digit_engine_on_the_grid(N: int, p: Fraction) -> None:
    _engine_case(N, p)


@pytest.mark.parametrize("N", [10**50, 10**100, 10**300], ids=_nid)
@pytest.mark.parametrize("ratio", ["1e-3", "0.5", "0.999"])
def test_below_the_jump_follows_the_log_series_law(N: int, ratio: str) -> None:
    """``P(X = j) ~ x**j / j`` with ``x = N p`` (exact to ``j**2/N``): the tails are Lerch's
    transcendent; sf reaches exp(-7e6) at k = 1e6 for p = 1e-3 p_c."""
    p = critical_p(N) * Fraction(ratio)
    ks = [1, 2, 10, 100, 1000, 10**4, 10**5, 10**6]
    got = _float_family(N, p, ks)
    for i, k in enumerate(ks):
        lo, up = log_series_tails(N, p, k, 30)
        _check(got, i, lo, up, f"N={N} p/p_c={ratio} k={k}")


@pytest.mark.parametrize("N", [10**15, 10**20, 10**50, 10**300], ids=_nid)
@pytest.mark.parametrize("p", [Fraction(1, 2), Fraction(1), Fraction(3)])
def test_p_of_order_one_follows_the_poisson_law_from_the_top(N: int, p: Fraction) -> None:
    """``Phi(N - j)/Phi(N) = lam**j/j! N/(N - j)`` with ``lam = 1/p``: k = N - j."""
    js = [1, 2, 3, 5, 8, 13, 30, 60, 120]
    ks = [N - j for j in js]
    got = _float_family(N, p, ks)
    for i, k in enumerate(ks):
        lo, up = log_poisson_side_tails(N, p, k, 30, 400)
        _check(got, i, lo, up, f"N={N} p={p} k={k}")


def test_logsf_is_finite_where_sf_underflows() -> None:
    """sf far beyond 1e-300 (N = 1e10, p = 2 p_c: k 60 sigma above the median)."""
    N = 10**10
    p = critical_p(N) * 2
    d = symhx.distribution_of(N, p, dps=None)
    ks = [N // 2 + 6 * 10**6, N // 2 + 10**7]
    ls = d.logsf(np.array(ks))
    assert np.all(np.isfinite(ls)) and np.all(ls < -700)
    assert np.all(d.sf(np.array(ks)) == 0.0)
    ref = symhx.distribution_of(N, p, dps=30)
    for k, v in zip(ks, ls, strict=True):
        assert abs(v - float(ref.logsf(k))) <= 1e-13 * abs(v)


def test_edges_and_scalars_keep_their_values() -> None:
    """k < 1 and k >= N give the limits; a scalar k gives a float equal to the array value."""
    N = 10**20
    p = critical_p(N) * 2
    d = symhx.distribution_of(N, p, dps=None)
    ks = np.array([-5, 0, N, N + 7], dtype=object)
    assert list(d.cdf(ks)) == [0.0, 0.0, 1.0, 1.0]
    assert list(d.sf(ks)) == [1.0, 1.0, 0.0, 0.0]
    assert list(d.logcdf(ks)) == [-np.inf, -np.inf, 0.0, 0.0]
    assert list(d.logsf(ks)) == [0.0, 0.0, -np.inf, -np.inf]
    k = N // 2 + 12345
    assert d.cdf(k) == d.cdf(np.array([k], dtype=object))[0]
    assert symhx.logsf(N, p, k, dps=None) == d.logsf(k)
    many = np.array([k] * 3 + [k + 1], dtype=object).reshape(2, 2)
    assert d.sf(many).shape == (2, 2)


def test_cdf_is_monotone_and_sf_its_complement_over_the_support() -> None:
    N = 10**15
    p = critical_p(N) * Fraction("1.001")
    d = symhx.distribution_of(N, p, dps=None)
    ks = np.unique(np.geomspace(1, N - 1, 400).astype(np.int64))
    c, s = d.cdf(ks), d.sf(ks)
    assert np.all(np.diff(c) >= 0) and np.all(np.diff(s) <= 0)
    assert np.all(np.abs(c + s - 1) <= 1e-15)


def test_largest_float_n_matches_the_engine() -> None:
    """N = 1.7e308 (x + y and 2 y overflow float64 in the term formula's pieces)."""
    N = 17 * 10**307
    p = critical_p(N) * 2
    top = symhx.mode(N, p)
    sd = int(symhx.distribution_of(N, p, dps=None).std()) + 1
    ks = [top - 3 * sd, top, top + sd, top + 5 * sd]
    got = _float_family(N, p, ks)
    ref = symhx.distribution_of(N, p, dps=30)
    for i, k in enumerate(ks):
        _check(got, i, ref.logcdf(k), ref.logsf(k), f"k = top + {(k - top) // sd} sd")
