"""The simple frozen distribution (eqs. 7-8), method by method, on its three paths (exact ``p``,
float ``p`` at ``dps`` digits, float64), its exact sums (binary splitting), arrays of ``k``, the
table and the deprecated names.

References, none of which uses symhx's distribution code: ``Phi(k) = p**k N! / (k (N-k)!)`` from
factorials, normalised by its brute-force sum, every derived quantity (cdf, sf, moments,
quantiles, modes) by definition (:class:`tests.reference.distribution.ExactTable`).

Ties and boundaries are explicit strategies: ``p = (k + 1) / (k (N - k))`` makes
``Phi(k) = Phi(k + 1)`` exactly, ``p = 2 / (N - 1)`` ties ``Phi(1)`` with ``Phi(2)``,
``(N, p) = (t**2 + 2 t, 1/t**2)`` is a double root of ``f_{N,p}``, ``p = 1 / (2N)`` the edge of
the hump test, N = 1, 2, 3, 5, p near 0 and 1.
"""

from __future__ import annotations

import math
import sys
import warnings
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import symhx
import symhx.distribution as dist
from symhx.distribution import SimpleDistribution, binary_split
from tests.harness.discrete import (
    Path,
    check_array_shapes,
    check_frozen,
    check_quantiles_at_midpoints,
)
from tests.harness.errors import assert_refuses
from tests.reference.distribution import (
    ExactTable,
    moments_of,
    pmf_by_downward_ratio,
    pmf_by_loggamma,
    pmf_table,
    small_cases,
    to_mp,
)

fractions_p = st.fractions(min_value=Fraction(1, 10**4), max_value=1).filter(lambda x: x > 0)


# --------------------------------------------------------------------------- exact path
@given(st.integers(1, 60), fractions_p)
def test_exact_pmf_sums_to_one_and_matches_direct(N, p):
    d = symhx.distribution_of(N, p)
    pm = [d.pmf(k) for k in range(1, d.N + 1)]
    assert sum(pm) == 1
    assert pm == pmf_table(N, p)


@given(st.integers(1, 60), fractions_p)
def test_exact_moments(N, p):
    mu, var = moments_of(pmf_table(N, p))
    assert symhx.mean(N, p) == mu
    assert symhx.var(N, p) == var


@given(small_cases)
@example((1, Fraction(1, 2)))
@example((2, Fraction(2)))  # Phi(1) = Phi(2)
@example((3, Fraction(1)))  # double root at 1: modes (1, 2)
@example((5, Fraction(1, 2)))  # modes (1, 2, 3)
@example((8, Fraction(1, 4)))  # double root at 2, but Phi(1) is larger
@example((101, Fraction(1, 50)))  # modes (50, 51)
@example((10, Fraction(1, 20)))  # p = 1/(2N) exactly
def test_exact_path_every_method(case: tuple[int, Fraction]) -> None:
    """Every method equals the exact table (logs, std and entropy to 30 digits), quantiles at
    every cdf value and every midpoint between two."""
    N, p = case
    d = symhx.distribution_of(N, p, dps=30)
    assert d.exact and d.N == N and d.fr == p
    ref = ExactTable.simple(N, p)
    check_frozen(d, ref, Path.exact(30), qs=ref.quantile_grid())
    check_array_shapes(d, Path.exact(30))


def test_p_equal_one_and_N_two():
    assert symhx.pmf(2, 1, 1) == Fraction(2, 3)
    assert symhx.modes(2, 1) == (1,)
    assert symhx.modes(3, 1) == (1, 2)  # N = 3 ties at p = p_c = 1
    assert symhx.mean(5, 1) == moments_of(pmf_table(5, Fraction(1)))[0]


def test_sympy_rational_is_exact():
    sympy = pytest.importorskip("sympy")
    assert symhx.mean(7, sympy.Rational(1, 3)) == symhx.mean(7, Fraction(1, 3))
    # an irrational sympy number goes through mpmath
    v = symhx.mean(7, sympy.sqrt(2) / 10, dps=30)
    with mpmath.workdps(40):
        want = moments_of(pmf_by_loggamma(7, mpmath.sqrt(2) / 10, 40))[0]
        assert abs(v - want) < mpmath.mpf(10) ** -28


# --------------------------------------------------------------------------- mpmath path
MP_CASES = [(1, 0.5), (2, 0.5), (2, 2.0), (3, 1.0), (5, 0.5), (7, 1e-300), (10, 1e-5),
            (10, 0.05), (10, 1 - 2.0**-40), (10, 3.0), (30, 0.1), (24, 0.25)]


@pytest.mark.parametrize("dps", [20, 45])
@pytest.mark.parametrize(("N", "pf"), MP_CASES)
def test_mpmath_path_every_method(N: int, pf: float, dps: int) -> None:
    """Every method within ``10**(1 - dps)`` of the exact table of the float's binary value;
    quantiles at the midpoints between resolvable cdf values."""
    d = symhx.distribution_of(N, pf, dps=dps)
    assert not d.exact and d.dps == dps
    ref = ExactTable.simple(N, Fraction(pf))
    check_frozen(d, ref, Path.mp(dps), qs=())
    check_quantiles_at_midpoints(d, ref, dps)
    arr = d.cdf([1, N])
    assert arr.dtype == object and isinstance(arr[0], mpmath.mpf)


@pytest.mark.parametrize(("N", "p"), [(2, 0.5), (100, 0.02), (101, 1e-300), (300, 0.9)])
def test_table_matches_exact(N, p):
    exact = pmf_table(N, Fraction(p)) if N <= 101 or p > 1e-10 else None
    tab = symhx.distribution_of(N, p, dps=30).table()
    assert [k for k, _ in tab] == list(range(1, N + 1))
    if exact is None:
        return
    with mpmath.workdps(50):
        for (_, got), want in zip(tab, exact, strict=True):
            w = to_mp(want)
            assert abs(got - w) <= mpmath.mpf(10) ** -29 * w


def test_object_k_arrays_keep_their_shape_and_name_k() -> None:
    d = symhx.distribution_of(6, 0.4, dps=20)
    t = ExactTable.simple(6, Fraction(0.4))
    k = np.array([[1, 2], [6, 10**30]], dtype=object)
    got = d.pmf(k)
    assert got.shape == (2, 2)
    Path.mp(20).value(got[1, 0], t.pmf[5])
    assert got[1, 1] == 0
    f = symhx.distribution_of(6, 0.4, dps=None).cdf(k)
    assert f.shape == (2, 2) and f[1, 1] == 1.0
    assert_refuses(d.pmf, np.array([1, 2.5], dtype=object), exc=TypeError, arg="k", value="2.5",
                   allowed="an int")


# --------------------------------------------------------------------------- float64 path
@given(small_cases)
@example((1, Fraction(1, 2)))
@example((5, Fraction(1, 2)))
@example((10, Fraction(1, 10**20)))
def test_float_path_every_method(case: tuple[int, Fraction]) -> None:
    """float64 values within 1e-12 (var and std 1e-9) of the exact table of the float's binary
    value, logs within 1e-12 max(1, |log|), quantiles away from the float cdf's values."""
    N, p0 = case
    pf = float(p0)
    d = symhx.distribution_of(N, pf, dps=None)
    assert d.dps is None and not d.exact
    path = Path.float64(rtol=1e-12, log_tol=1e-12, var_rtol=1e-9, std_atol=1e-150,
                        entropy_atol=1e-12)
    ref = ExactTable.simple(N, Fraction(pf))
    check_frozen(d, ref, path, qs=ref.quantile_grid())
    check_array_shapes(d, path)


def test_float_arrays_far_outside_the_support() -> None:
    d = symhx.distribution_of(5, 0.5, dps=None)
    t = pmf_table(5, Fraction(0.5))
    got = d.pmf(np.array([-100, -6, 1, 5, 6, 100]))
    assert got.dtype == np.float64
    assert got.tolist()[:2] == [0.0, 0.0] and got.tolist()[4:] == [0.0, 0.0]
    assert math.isclose(got[2], float(t[0]), rel_tol=1e-12)
    assert d.cdf(np.array([-100, 100])).tolist() == [0.0, 1.0]
    assert d.sf(np.array([-100, 100])).tolist() == [1.0, 0.0]
    assert d.logsf(np.array([-100, 100])).tolist() == [0.0, -math.inf]


def test_float_path_empty_object_array() -> None:
    """An empty object-dtype array of k on the float64 path gives an empty float64 array (an
    empty list without an int64 dtype would be float64 and could not index the table)."""
    d = SimpleDistribution(10, 0.3, dps=None)
    for shape in ((0,), (0, 3)):
        k = np.empty(shape, dtype=object)
        for f in (d.pmf, d.logpmf, d.cdf, d.sf, d.logcdf, d.logsf):
            got = f(k)
            assert got.shape == shape and got.dtype == np.float64, f
    got = d.cdf(np.array([10**30, -5, 3], dtype=object))
    t = ExactTable.simple(10, Fraction(0.3))
    assert got.dtype == np.float64 and np.allclose(got, [1.0, 0.0, float(t.cdf(3))], rtol=1e-13,
                                                   atol=0)


def test_float_entropy_with_underflowing_pmf() -> None:
    """dps=None: pmf values that underflow to 0.0 contribute nothing (not nan, not 1)."""
    N, pf = 3000, 1e-4
    d = symhx.distribution_of(N, pf, dps=None)
    assert d.pmf(N) == 0.0  # underflows
    ref = pmf_by_downward_ratio(N, Fraction(pf), 30)
    with mpmath.workdps(30):
        h = -mpmath.fsum(x * mpmath.log(x) for x in ref if x > mpmath.mpf(10) ** -40)
    assert abs(d.entropy() - float(h)) <= 1e-16 * N * math.log(N) * float(h)  # documented


# --------------------------------------------------------------------------- exact sums
@given(st.integers(0, 25), st.integers(1, 9), st.integers(1, 9), st.integers(-1, 30))
def test_binary_split_against_direct_sum(N: int, a: int, b: int, stop: int) -> None:
    def w(j: int) -> tuple[int, int]:
        return j * j + 1, 2 * j + 3

    want = Fraction(0)
    prod = Fraction(1)
    for j in range(1, min(stop, N) + 1):
        prod *= Fraction(a * (N - j + 1), b)
        want += Fraction(*w(j)) * prod
    assert binary_split(N, a, b, w, min(stop, N)) == want
    full = sum((Fraction(*w(j)) * Fraction(a, b) ** j * math.perm(N, j)
                for j in range(1, N + 1)), Fraction(0))
    assert binary_split(N, a, b, w) == full


def test_repr_names_the_path() -> None:
    d = SimpleDistribution(10, 0.3, dps=20)
    assert repr(d) == "SimpleDistribution(N=10, p=0.3, space='simple', dps=20, exact=False)"


# --------------------------------------------------------------------------- deprecated names
def test_moved_names_forward_with_a_warning() -> None:
    with pytest.warns(DeprecationWarning, match=r"symhx\.mean"):
        f = dist.mean
    assert f(3, "1/2") == Fraction(3, 2)
    with pytest.raises(AttributeError, match="no_such"):
        dist.no_such  # noqa: B018
    with pytest.warns(DeprecationWarning, match="var"):
        assert SimpleDistribution(3, "1/2").variance() == moments_of(
            pmf_table(3, Fraction(1, 2)))[1]


def test_deprecation_warnings_name_the_calling_line() -> None:
    """``variance()`` and the moved module attributes (``symhx.distribution.mode``, ``.mean``)
    warn at the line that called them, not one frame further up (inside pytest), with their
    documented messages."""
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        SimpleDistribution(3, "1/2").variance(), dist.mean, dist.mode
    assert [r.category for r in rec] == [DeprecationWarning] * 3
    assert str(rec[0].message).startswith("Distribution.variance() is deprecated: use var()")
    assert str(rec[2].message).startswith("symhx.distribution.mode moved")
    where = {(r.filename, r.lineno) for r in rec}
    # under mutmut its trampoline calls the warning functions: they must then name one frame
    if hasattr(dist, "_mutmut_mutated"):
        assert len(where) == 1, where
    else:
        assert where == {(__file__, line)}
