"""symhx.circuits against independent references: explicit walks up to rotation
(tests.reference.combinatorics), MacMahon's necklace formula, brute-force partitions, exact
integer products and known sequences. The work limits and refusals are in
``test_circuits_limits.py``."""

from __future__ import annotations

import math
from collections import Counter

import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symhx import circuits as C
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


# --------------------------------------------------------------------------- pattern counts
@pytest.mark.parametrize(("N", "L"), SMALL)
def test_pattern_counts_match_explicit_walks(N, L):
    brute = pattern_counts(N, L)
    got = circuits_of_length(N, L)
    assert got == brute
    for v in integer_partitions(L):
        assert circuit_count(N, v) == brute.get(v, 0), v


@pytest.mark.parametrize("N", range(1, 6))
def test_pattern_counts_match_the_fkm_enumeration(N):
    for L in range(1, 8 if N <= 4 else 7):
        brute = C.brute_force_pattern_counts(N, L)
        assert brute == Counter(C.circuits_of_length(N, L)), (N, L)


@pytest.mark.parametrize(("N", "L"), SMALL)
def test_enumeration_is_every_circuit_once(N, L):
    words = list(enumerate_circuits(N, L))
    assert len(words) == len(set(words))
    assert set(words) == necklaces(N, L)
    assert words == sorted(words)  # FKM yields least rotations in lexicographic order
    assert brute_force_pattern_counts(N, L) == Counter(pattern_counts(N, L))


def test_enumeration_counts_periodic_words_once():
    # (0,1,0,1) is one circuit of length 4 with pattern (2,2): rotations give only 2 words
    words = [w for w in C.enumerate_circuits(2, 4) if Counter(w) == Counter((0, 0, 1, 1))]
    assert sorted(words) == [(0, 0, 1, 1), (0, 1, 0, 1)]
    assert C.circuit_count(2, (2, 2)) == 2


@pytest.mark.parametrize(("N", "L"), SMALL)
def test_necklace_count_brute(N, L):
    assert necklace_count(N, L) == len(necklaces(N, L)) == necklace_formula(N, L)


@pytest.mark.parametrize("N", BOUNDARY_N)
@pytest.mark.parametrize("L", range(1, 8))
def test_patterns_sum_to_macmahons_necklace_count(N, L):
    """sum over visit patterns of length L == all necklaces (MacMahon), at large N too."""
    assert sum(circuit_count(N, v) for v in integer_partitions(L)) == necklace_formula(N, L)
    assert sum(circuits_of_length(N, L).values()) == necklace_count(N, L)


@given(st.integers(1, 40), st.integers(1, 12))
def test_patterns_sum_to_necklace_count(N, L):
    total = sum(C.circuit_count(N, v) for v in C.partitions(L))
    assert total == C.necklace_count(N, L)


visit_patterns = st.lists(st.integers(1, 4), min_size=1, max_size=5).filter(
    lambda v: sum(v) <= 9)


@settings(max_examples=40, deadline=None)
@given(N=st.sampled_from(BOUNDARY_N) | st.integers(1, 12), v=visit_patterns)
def test_circuit_count_by_choosing_vertices(N, v):
    assert circuit_count(N, v) == pattern_count_by_choice(N, tuple(sorted(v, reverse=True)))


def test_boundary_counts_of_the_errata():
    for N in range(1, 12):
        assert C.circuit_count(N, (3,)) == N  # not N/3
        assert C.circuit_count(N, (4,)) == N  # not N/4
        assert C.circuit_count(N, (2, 2)) == N * (N - 1)  # not 3N(N-1)/4
        assert C.circuit_count(N, (2,)) == N  # eq. (36)


def test_paper_eq35_in_range():
    # eq. (35): phi^1_N(k) = (k-1)/2 * N!/(N-(k-1))! for 2 < k <= N+1
    for N in range(2, 12):
        for k in range(3, N + 2):
            assert 2 * C.circuit_count(N, (2,) + (1,) * (k - 2)) == (k - 1) * math.perm(N, k - 1)


def test_circuit_count_too_many_vertices():
    assert circuit_count(2, (1, 1, 1)) == 0
    assert circuit_count(3, (1, 1, 1)) == 2
    assert circuit_count(1, (4,)) == 1
    assert C.circuit_count(3, (1, 1, 1, 1)) == 0


# --------------------------------------------------------------------------- simple circuits
@pytest.mark.parametrize("N", range(1, 7))
def test_phi_counts_the_simple_circuits_of_the_fkm_enumeration(N):
    for L in range(1, N + 2):
        simple = sum(1 for w in C.enumerate_circuits(N, L) if len(set(w)) == L)
        assert simple == C.phi(N, L)


@pytest.mark.parametrize("N", range(1, 7))
def test_phi_is_simple_circuits(N):
    for k in range(1, N + 1):
        if N**k <= 50000:
            simple = sum(1 for w in necklaces(N, k) if len(set(w)) == k)
            assert phi(N, k) == simple
        assert phi(N, k) == math.factorial(N) // (k * math.factorial(N - k))
    for k in (-1, 0, N + 1, N + 5):
        assert phi(N, k) == 0


@given(st.integers(1, 200), st.integers(1, 30))
def test_simple_pattern_is_phi(N, k):
    assert C.circuit_count(N, (1,) * k) == C.phi(N, k)


@settings(max_examples=25, deadline=None)
@given(N=st.sampled_from(BOUNDARY_N), k=st.integers(1, 40))
def test_phi_large_N(N, k):
    want = 0 if k > N else math.prod(range(N - k + 1, N + 1)) // k
    assert phi(N, k) == want
    assert circuit_count(N, (1,) * k) == want


@pytest.mark.parametrize("N", [1, 2, 3, 4, 5, 6, 7, 12, 40])
def test_total_simple_circuits(N):
    want = sum(math.factorial(N) // (k * math.factorial(N - k)) for k in range(1, N + 1))
    assert total_simple_circuits(N) == want
    if N <= 5:
        assert want == sum(1 for L in range(1, N + 1) for w in necklaces(N, L)
                           if len(set(w)) == L)


def test_total_simple_known_sequence():
    # complete digraph with loops: 1, 3, 8, 24, 89, 415, 2372 (brute force below for N <= 5)
    assert [C.total_simple_circuits(N) for N in range(1, 8)] == [1, 3, 8, 24, 89, 415, 2372]
    for N in range(1, 6):
        brute = sum(
            1 for L in range(1, N + 1) for w in C.enumerate_circuits(N, L) if len(set(w)) == L
        )
        assert brute == C.total_simple_circuits(N)


# --------------------------------------------------------------------------- log_phi
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


def test_log_phi_huge():
    N = 10**100
    with mpmath.workdps(80):
        direct = mpmath.log(N) + mpmath.log(N - 1) + mpmath.log(N - 2) - mpmath.log(3)
    assert mpmath.almosteq(C.log_phi(N, 3, dps=60), direct, rel_eps=mpmath.mpf(10) ** -58)
    with mpmath.workdps(60):
        exact_log = mpmath.log(C.phi(30, 7))
    assert mpmath.almosteq(C.log_phi(30, 7, dps=40), exact_log, rel_eps=mpmath.mpf(10) ** -38)
    # a huge N in log_phi (more digits than Python's int->str limit) still works
    assert C.log_phi(10**5000, 2, dps=20) > 0


def test_log_phi_k_equals_N():
    with mpmath.workdps(60):
        assert abs(log_phi(20, 20, dps=40) - mpmath.log(math.factorial(19))) < mpmath.mpf(10)**-35


def test_log_phi_default_precision_is_50_digits():
    for N, k in ((10**6, 7), (37, 5), (10**40, 3)):
        assert log_phi(N, k) == log_phi(N, k, dps=50)  # exact mpf equality: same rounding
        assert log_phi(N, k) != log_phi(N, k, dps=51)


# --------------------------------------------------------------------------- partitions, visits
def test_partitions_brute():
    p = [1, 1, 2, 3, 5, 7, 11, 15, 22, 30, 42]
    for L in range(0, 11):
        got = list(partitions(L))
        assert got == integer_partitions(L)
        assert len(got) == p[L]
        for mp_ in range(1, L + 1):
            assert list(partitions(L, max_part=mp_)) == [x for x in got if max(x, default=0) <= mp_]
            assert list(partitions(L, max_parts=mp_)) == [x for x in got if len(x) <= mp_]
    # 0 is allowed: no parts at all (only the empty partition of 0)
    assert list(C.partitions(5, max_part=0)) == []
    assert list(C.partitions(5, max_parts=0)) == []


def test_normalise_visits():
    assert normalise_visits([1, 3, 2, 1]) == (3, 2, 1, 1)
    assert normalise_visits((5,)) == (5,)


# ------------------------------------------------- rounding, messages of the work limits
@pytest.mark.parametrize("dps", [5, 20, 50])
@pytest.mark.parametrize(("N", "k"), [(7, 3), (10**6, 999), (10**100, 2), (10**1000, 10**3)])
def test_log_phi_is_rounded_to_dps_and_correct_to_dps_digits(N, k, dps):
    v = C.log_phi(N, k, dps=dps)
    with mpmath.workdps(dps):
        assert v == +v          # rounded once to dps digits, no guard digits handed out
    with mpmath.workdps(2 * dps + 40 + len(str(N))):   # independent: loggamma, twice the digits
        ref = mpmath.loggamma(N + 1) - mpmath.loggamma(N - k + 1) - mpmath.log(k)
        assert abs(v - ref) <= abs(ref) * mpmath.mpf(10) ** (1 - dps)


def test_count_refusals_name_the_constant_to_raise():
    for call in (lambda: C.phi(10**30, 10**30),
                 lambda: C.circuit_count(2**C.MAX_COUNT_BITS, [1, 1])):
        with pytest.raises(ValueError) as info:
            call()
        assert "(symhx.circuits.MAX_COUNT_BITS)" in str(info.value)


def test_short_length_shows_the_power_of_ten_below_L():
    for e in [*range(15, 60), 299, 300, 1000, 4299, 4300, 4301, 10_000]:
        for L in (10**e, 10**e + 1, 10**(e + 1) - 1, 2 * 10**e):   # floor(log10 L) = e
            assert C._short_length(L) == f"~10**{e}", e
    assert C._short_length(10**15 - 1) == 10**15 - 1
