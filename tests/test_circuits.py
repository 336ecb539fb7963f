"""Circuit counts against brute-force enumeration and known sequences."""

from collections import Counter

import pytest
from hypothesis import given
from hypothesis import strategies as st

from symhx import circuits as C
from symhx.graph import vertices_lattice, vertices_row


def test_graph_conventions():
    assert vertices_row(100) == 101
    # 2-D lattice: brute-force count of 8-neighbour contacts + 4m wall contacts
    for m in range(1, 7):
        cells = [(i, j) for i in range(m) for j in range(m)]
        contacts = {
            frozenset({a, b})
            for a in cells
            for b in cells
            if a != b and max(abs(a[0] - b[0]), abs(a[1] - b[1])) == 1
        }
        assert vertices_lattice(m) == len(contacts) + 4 * m == 4 * m * m - 2 * m + 2
    with pytest.raises(ValueError, match="n"):
        vertices_row(0)


@pytest.mark.parametrize("N", range(1, 7))
def test_phi_against_enumeration(N):
    for L in range(1, N + 2):
        simple = sum(1 for w in C.enumerate_circuits(N, L) if len(set(w)) == L)
        assert simple == C.phi(N, L)


def test_total_simple_known_sequence():
    # complete digraph with loops: 1, 3, 8, 24, 89, 415, 2372 (brute force below for N <= 5)
    assert [C.total_simple_circuits(N) for N in range(1, 8)] == [1, 3, 8, 24, 89, 415, 2372]
    for N in range(1, 6):
        brute = sum(
            1 for L in range(1, N + 1) for w in C.enumerate_circuits(N, L) if len(set(w)) == L
        )
        assert brute == C.total_simple_circuits(N)


@pytest.mark.parametrize("N", range(1, 6))
def test_pattern_counts_against_enumeration(N):
    for L in range(1, 8 if N <= 4 else 7):
        brute = C.brute_force_pattern_counts(N, L)
        assert brute == Counter(C.circuits_of_length(N, L)), (N, L)


def test_enumeration_counts_periodic_words_once():
    # (0,1,0,1) is one circuit of length 4 with pattern (2,2): rotations give only 2 words
    words = [w for w in C.enumerate_circuits(2, 4) if Counter(w) == Counter((0, 0, 1, 1))]
    assert sorted(words) == [(0, 0, 1, 1), (0, 1, 0, 1)]
    assert C.circuit_count(2, (2, 2)) == 2


def test_design_errata_boundary_counts():
    for N in range(1, 12):
        assert C.circuit_count(N, (3,)) == N  # not N/3
        assert C.circuit_count(N, (4,)) == N  # not N/4
        assert C.circuit_count(N, (2, 2)) == N * (N - 1)  # not 3N(N-1)/4
        assert C.circuit_count(N, (2,)) == N  # eq. (36)


@given(st.integers(1, 40), st.integers(1, 12))
def test_patterns_sum_to_necklaces(N, L):
    total = sum(C.circuit_count(N, v) for v in C.partitions(L))
    assert total == C.necklace_count(N, L)


@given(st.integers(1, 200), st.integers(1, 30))
def test_simple_pattern_is_phi(N, k):
    assert C.circuit_count(N, (1,) * k) == C.phi(N, k)


def test_paper_eq35_in_range():
    # eq. (35): phi^1_N(k) = (k-1)/2 * N!/(N-(k-1))! for 2 < k <= N+1
    from math import perm

    for N in range(2, 12):
        for k in range(3, N + 2):
            assert 2 * C.circuit_count(N, (2,) + (1,) * (k - 2)) == (k - 1) * perm(N, k - 1)


def test_bad_input():
    with pytest.raises(ValueError):
        C.circuit_count(5, (0, 1))
    with pytest.raises(ValueError):
        C.circuit_count(5, ())
    with pytest.raises(TypeError):
        C.circuit_count(5, (1.5,))
    with pytest.raises(ValueError):
        C.phi(0, 1)
    assert C.phi(5, 6) == 0 and C.phi(5, 0) == 0
    assert C.circuit_count(3, (1, 1, 1, 1)) == 0


def test_log_phi_huge():
    import mpmath

    N = 10**100
    with mpmath.workdps(80):
        direct = mpmath.log(N) + mpmath.log(N - 1) + mpmath.log(N - 2) - mpmath.log(3)
    assert mpmath.almosteq(C.log_phi(N, 3, dps=60), direct, rel_eps=mpmath.mpf(10) ** -58)
    with mpmath.workdps(60):
        exact_log = mpmath.log(C.phi(30, 7))
    assert mpmath.almosteq(C.log_phi(30, 7, dps=40), exact_log, rel_eps=mpmath.mpf(10) ** -38)


def test_bad_inputs_and_work_limits_are_clear_errors():
    import pytest

    from symhx import circuits as C
    from symhx.spaces import class_count, parse_space

    with pytest.raises(TypeError, match="k must be an int"):
        C.phi(10, 2.5)
    with pytest.raises(TypeError, match="N"):
        C.phi(True, 1)
    with pytest.raises(ValueError, match="N must be >= 1, got -3"):
        class_count(-3, (2,), 1)
    with pytest.raises(ValueError, match="MAX_TOTAL_N"):
        C.total_simple_circuits(10**1000)
    assert C.total_simple_circuits(C.MAX_TOTAL_N // 100) > 0  # below the cap: works
    with pytest.raises(ValueError, match="MAX_EXCESS"):
        parse_space("excess<=1000")
    with pytest.raises(ValueError, match="MAX_EXCESS"):
        parse_space("excess<=" + "9" * 5000)
    assert len(parse_space("excess<=5").shapes) == 19
    with pytest.raises(ValueError, match="MAX_PATTERN_LENGTH"):
        C.circuits_of_length(10, 10**6)
    with pytest.raises(ValueError, match="MAX_ENUMERATION"):
        next(C.enumerate_circuits(10, 10**6))
    with pytest.raises(ValueError, match="MAX_CIRCUIT_LENGTH"):
        C.circuit_count(3, (10**9,))
    with pytest.raises(ValueError, match="MAX_COUNT_BITS"):
        C.necklace_count(10, 10**9)
    with pytest.raises(TypeError, match="visits"):
        C.circuit_count(3, "21")
    with pytest.raises(TypeError, match="dps"):
        C.log_phi(10, 2, dps=True)
    # a huge N in log_phi (more digits than Python's int->str limit) still works
    assert C.log_phi(10**5000, 2, dps=20) > 0


def test_enumerate_circuits_work_limit_exact():
    """The N**L cap is an exact integer test: no float overflow for huge L, and N = 1 counts."""
    for N, L in ((3, 10**1000), (1, 10**1000), (1, C.MAX_ENUMERATION_LENGTH + 1), (2, 27)):
        with pytest.raises(ValueError, match="MAX_ENUMERATION"):
            C.enumerate_circuits(N, L)  # refused at the call, before iterating
    # below the cap it still enumerates (2**27 words > 1e8 is refused above, 2**20 is fine)
    # and the count agrees with the independent Burnside formula
    assert sum(1 for _ in C.enumerate_circuits(2, 20)) == sum(C.circuits_of_length(2, 20).values())
    assert list(C.enumerate_circuits(1, 5)) == [(0,) * 5]
    L = C.MAX_ENUMERATION_LENGTH  # the longest allowed still runs (no RecursionError)
    assert list(C.enumerate_circuits(1, L)) == [(0,) * L]
