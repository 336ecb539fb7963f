"""Independent references for symhx.circuits: explicit walks up to rotation, other formulas."""

from __future__ import annotations

import math
from collections import Counter

import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symhx.circuits import (
    brute_force_pattern_counts,
    circuit_count,
    circuits_of_length,
    enumerate_circuits,
    log_phi,
    necklace_count,
    normalise_visits,
    partitions,
    phi,
    total_simple_circuits,
)
from tests.reference.combinatorics import (
    integer_partitions,
    necklace_formula,
    necklaces,
    pattern_count_by_choice,
    pattern_counts,
)

SMALL = [(N, L) for N in range(1, 6) for L in range(1, 7) if N**L <= 16000]
BOUNDARY_N = [2, 3, 5, 10, 100, 10**3, 10**6, 10**20]


@pytest.mark.parametrize(("N", "L"), SMALL)
def test_pattern_counts_match_explicit_walks(N, L):
    brute = pattern_counts(N, L)
    got = circuits_of_length(N, L)
    assert got == brute
    for v in integer_partitions(L):
        assert circuit_count(N, v) == brute.get(v, 0), v


@pytest.mark.parametrize(("N", "L"), SMALL)
def test_enumeration_is_every_circuit_once(N, L):
    words = list(enumerate_circuits(N, L))
    assert len(words) == len(set(words))
    assert set(words) == necklaces(N, L)
    assert words == sorted(words)  # FKM yields least rotations in lexicographic order
    assert brute_force_pattern_counts(N, L) == Counter(pattern_counts(N, L))


@pytest.mark.parametrize(("N", "L"), SMALL)
def test_necklace_count_brute(N, L):
    assert necklace_count(N, L) == len(necklaces(N, L)) == necklace_formula(N, L)


@pytest.mark.parametrize("N", range(1, 7))
def test_phi_is_simple_circuits(N):
    for k in range(1, N + 1):
        if N**k <= 50000:
            simple = sum(1 for w in necklaces(N, k) if len(set(w)) == k)
            assert phi(N, k) == simple
        assert phi(N, k) == math.factorial(N) // (k * math.factorial(N - k))
    for k in (-1, 0, N + 1, N + 5):
        assert phi(N, k) == 0


@pytest.mark.parametrize("N", [1, 2, 3, 4, 5, 6, 7, 12, 40])
def test_total_simple_circuits(N):
    want = sum(math.factorial(N) // (k * math.factorial(N - k)) for k in range(1, N + 1))
    assert total_simple_circuits(N) == want
    if N <= 5:
        assert want == sum(1 for L in range(1, N + 1) for w in necklaces(N, L)
                           if len(set(w)) == L)


@pytest.mark.parametrize("N", BOUNDARY_N)
@pytest.mark.parametrize("L", range(1, 8))
def test_patterns_sum_to_necklaces(N, L):
    """sum over visit patterns of length L == all necklaces (MacMahon), at large N too."""
    assert sum(circuit_count(N, v) for v in integer_partitions(L)) == necklace_formula(N, L)
    assert sum(circuits_of_length(N, L).values()) == necklace_count(N, L)


visit_patterns = st.lists(st.integers(1, 4), min_size=1, max_size=5).filter(
    lambda v: sum(v) <= 9)


@settings(max_examples=40, deadline=None)
@given(N=st.sampled_from(BOUNDARY_N) | st.integers(1, 12), v=visit_patterns)
def test_circuit_count_by_choosing_vertices(N, v):
    assert circuit_count(N, v) == pattern_count_by_choice(N, tuple(sorted(v, reverse=True)))


@settings(max_examples=25, deadline=None)
@given(N=st.sampled_from(BOUNDARY_N), k=st.integers(1, 40))
def test_phi_large_N(N, k):
    want = 0 if k > N else math.prod(range(N - k + 1, N + 1)) // k
    assert phi(N, k) == want
    assert circuit_count(N, (1,) * k) == want


@pytest.mark.parametrize("N", [2, 3, 10, 1000, 10**30, 10**100])
@pytest.mark.parametrize("k", [1, 2, 3, 7])
@pytest.mark.parametrize("dps", [15, 40])
def test_log_phi_against_exact_int(N, k, dps):
    if k > N:
        return
    exact = math.prod(range(N - k + 1, N + 1))  # N!/(N-k)! exactly
    with mpmath.workdps(dps + 40):
        want = mpmath.log(exact) - mpmath.log(k)
        got = log_phi(N, k, dps=dps)
        assert abs(got - want) <= max(abs(want), 1) * mpmath.mpf(10) ** (1 - dps)
    assert mpmath.mp.dps == 15


def test_log_phi_k_equals_N_and_errors():
    with mpmath.workdps(60):
        assert abs(log_phi(20, 20, dps=40) - mpmath.log(math.factorial(19))) < mpmath.mpf(10)**-35
    with pytest.raises(ValueError, match=r"k must be <= N, got k=4, N=3"):
        log_phi(3, 4)
    with pytest.raises(ValueError, match=r"k must be >= 1, got 0"):
        log_phi(3, 0)
    with pytest.raises(ValueError, match=r"N must be >= 1, got 0"):
        log_phi(0, 1)


def test_partitions_brute():
    p = [1, 1, 2, 3, 5, 7, 11, 15, 22, 30, 42]
    for L in range(0, 11):
        got = list(partitions(L))
        assert got == integer_partitions(L)
        assert len(got) == p[L]
        for mp_ in range(1, L + 1):
            assert list(partitions(L, max_part=mp_)) == [x for x in got if max(x, default=0) <= mp_]
            assert list(partitions(L, max_parts=mp_)) == [x for x in got if len(x) <= mp_]


def test_normalise_visits():
    assert normalise_visits([1, 3, 2, 1]) == (3, 2, 1, 1)
    assert normalise_visits((5,)) == (5,)
    with pytest.raises(ValueError, match=r"^visits must not be empty$"):
        normalise_visits([])
    with pytest.raises(ValueError, match=r"multiplicity must be >= 1, got \(2, 0\)"):
        normalise_visits([0, 2])
    with pytest.raises(TypeError, match=r"^visits entry must be an int, got float 1\.5"):
        normalise_visits([1.5])


def test_errors_name_argument_and_value():
    with pytest.raises(ValueError, match=r"^N must be >= 1, got 0$"):
        phi(0, 1)
    with pytest.raises(TypeError, match=r"^N must be an int, got float "):
        phi(2.5, 1)
    with pytest.raises(ValueError, match=r"^N must be >= 1, got -2$"):
        circuit_count(-2, (1,))
    with pytest.raises(ValueError, match=r"^L must be >= 1, got 0$"):
        necklace_count(2, 0)
    with pytest.raises(ValueError, match=r"^N must be >= 1, got 0$"):
        total_simple_circuits(0)
    with pytest.raises(ValueError, match=r"^L must be >= 1, got 0$"):
        list(enumerate_circuits(2, 0))
    with pytest.raises(ValueError, match=r"^L must be >= 0, got -1$"):
        list(partitions(-1))
    # decimal strings are exact integers (symhx.validation); anything else is refused
    assert necklace_count(2, "3") == necklace_count(2, 3)
    with pytest.raises(ValueError, match=r"^L must be an integer such as 7, 10\*\*100 "
                                         r"or '1e100', got 'three'$"):
        necklace_count(2, "three")
    for func in (circuits_of_length, necklace_count, enumerate_circuits):
        with pytest.raises(ValueError, match=r"^N must be >= 1, got 0$"):
            list(func(0, 2))
        with pytest.raises(TypeError, match=r"^N must be an int, got float "):
            list(func(2.0, 2))


def test_log_phi_default_precision_is_50_digits():
    for N, k in ((10**6, 7), (37, 5), (10**40, 3)):
        assert log_phi(N, k) == log_phi(N, k, dps=50)  # exact mpf equality: same rounding
        assert log_phi(N, k) != log_phi(N, k, dps=51)


def test_circuit_count_too_many_vertices():
    assert circuit_count(2, (1, 1, 1)) == 0
    assert circuit_count(3, (1, 1, 1)) == 2
    assert circuit_count(1, (4,)) == 1
