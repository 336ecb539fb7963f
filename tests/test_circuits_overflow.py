"""``phi(N, k)`` for huge ``k``: the exact count up to the documented size limit
``symhx.circuits.MAX_COUNT_BITS`` (checked as ``k * bit_length(N)`` before any work), and above it
a ValueError naming ``k`` and ``N``, never ``math.perm``'s OverflowError (any ``N >= k > 2**63 - 1``
raised it) or a computation of hours."""

from __future__ import annotations

import math
import time

import pytest

import symhx
import symhx.circuits
from tests.harness.errors import assert_refuses

HUGE = [(10**30, 10**30), (2**63, 2**63), (2**63 + 5, 2**63), (10**1000, 10**999),
        (10**6, 10**6)]


@pytest.mark.parametrize("N, k", HUGE, ids=["1e30,1e30", "2**63,2**63", "2**63+5,2**63",
                                            "1e1000,1e999", "1e6,1e6"])
def test_phi_refuses_a_count_beyond_the_size_limit_at_once(N, k):
    t0 = time.perf_counter()
    assert_refuses(symhx.phi, N, k, arg=("k", "N"), allowed=("MAX_COUNT_BITS", "10000000"))
    assert time.perf_counter() - t0 < 0.5  # refused before the work (10**6! alone takes 17 s)


def test_phi_limit_is_exact_on_both_sides(monkeypatch):
    # k * bit_length(N) == limit is computed, limit + bit_length(N) is refused; the count is
    # checked against the falling factorial written out as a product
    monkeypatch.setattr(symhx.circuits, "MAX_COUNT_BITS", 7 * (1000).bit_length())
    assert symhx.phi(1000, 7) == math.prod(range(994, 1001)) // 7
    assert_refuses(symhx.phi, 1000, 8, arg=("k", "N"), value="80",
                   allowed=("MAX_COUNT_BITS", "70"))


def test_phi_huge_N_small_k_is_still_the_number():
    N = 10**100
    assert symhx.phi(N, 2) == N * (N - 1) // 2
    assert symhx.phi(N, 3) == N * (N - 1) * (N - 2) // 3
    assert symhx.phi(2**63 + 5, 1) == 2**63 + 5


def test_phi_outside_one_to_N_is_zero_for_any_size():
    assert symhx.phi(10**30, 10**30 + 1) == 0
    assert symhx.phi(5, 2**63) == 0
    assert symhx.phi(10**30, -(2**63)) == 0


def test_circuit_count_refuses_a_count_beyond_the_size_limit_at_once():
    # 20000 distinct vertices out of 10**1000: N!/(N - r)! alone has ~6.6e7 bits (it took 253 s)
    t0 = time.perf_counter()
    assert_refuses(symhx.circuit_count, 10**1000, (1,) * 20000,
                   arg=("len(visits)", "bit_length(N)"), allowed=("MAX_COUNT_BITS", "10000000"))
    assert time.perf_counter() - t0 < 0.5


def test_circuit_count_limit_is_exact_on_both_sides(monkeypatch):
    # r * bit_length(N) == limit is computed, one more distinct vertex is refused; the count of
    # all-distinct patterns is phi (eq. 5), written out as a falling factorial over k
    monkeypatch.setattr(symhx.circuits, "MAX_COUNT_BITS", 7 * (1000).bit_length())
    assert symhx.circuit_count(1000, (1,) * 7) == math.prod(range(994, 1001)) // 7
    assert symhx.circuit_count(1000, (3, 2, 1, 1, 1, 1, 1)) > 0
    assert_refuses(symhx.circuit_count, 1000, (1,) * 8, arg="len(visits)", value="80",
                   allowed=("MAX_COUNT_BITS", "70"))
