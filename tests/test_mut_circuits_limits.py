"""The work limits and refusals of ``symhx.circuits`` matched whole, each limit inclusive
(found by a mutation run after the limits were added: a renamed argument, a moved bound or a
wrong digit count in a message went unnoticed). References: the documented message form
``what=value is beyond the documented work limit LIMIT (symhx.circuits.CONSTANT)``, the decimal
length of ``str(value)``, and sympy's totient for the necklace count at a boundary."""

from __future__ import annotations

import re
from math import factorial

import pytest
from sympy import totient

import symhx.circuits as c

INT_WORDS = r"must be an integer such as 7, 10\*\*100 or '1e100', got "


def _limit(what: str, value: str, limit: int, constant: str) -> str:
    return (rf"^{re.escape(what)}={re.escape(value)} is beyond the documented work limit {limit} "
            rf"\(symhx\.circuits\.{constant}\); raise that constant to allow it$")


def test_circuit_length_limit():
    with pytest.raises(ValueError, match=_limit("circuit length sum(visits)",
                                                str(c.MAX_CIRCUIT_LENGTH + 1),
                                                c.MAX_CIRCUIT_LENGTH, "MAX_CIRCUIT_LENGTH")):
        c.circuit_count(3, (c.MAX_CIRCUIT_LENGTH, 1))


def test_pattern_length_limit_is_inclusive():
    with pytest.raises(ValueError, match=_limit("L", str(c.MAX_PATTERN_LENGTH + 1),
                                                c.MAX_PATTERN_LENGTH, "MAX_PATTERN_LENGTH")):
        c.circuits_of_length(3, c.MAX_PATTERN_LENGTH + 1)
    with pytest.raises(ValueError, match=rf"^L {INT_WORDS}'x'$"):
        c.circuits_of_length(3, "x")
    with pytest.raises(ValueError, match=r"^L must be >= 1, got 0$"):
        c.circuits_of_length(3, 0)
    # at the limit: N = 1 has the single pattern (L,) of the loop
    assert c.circuits_of_length(1, c.MAX_PATTERN_LENGTH) == {(c.MAX_PATTERN_LENGTH,): 1}


def test_enumeration_limits():
    with pytest.raises(ValueError, match=_limit("N**L ", " 10**30 words", c.MAX_ENUMERATION,
                                                "MAX_ENUMERATION")):
        c.enumerate_circuits(10, 30)
    with pytest.raises(ValueError, match=r"^L=~10\*\*20 is beyond the documented limit 500 "):
        c.enumerate_circuits(2, 10**20)
    with pytest.raises(ValueError, match=r"^L=501 is beyond the documented limit 500 "):
        c.enumerate_circuits(1, 501)
    big = 10**15   # shown as ~10**15 from 10**15 on, as the number below it
    with pytest.raises(ValueError, match=r"^L=~10\*\*15 is beyond"):
        c.enumerate_circuits(2, big)
    with pytest.raises(ValueError, match=r"^L=999999999999999 is beyond"):
        c.enumerate_circuits(2, big - 1)
    # N**L == MAX_ENUMERATION exactly is allowed
    assert 10**8 == c.MAX_ENUMERATION
    assert next(iter(c.enumerate_circuits(10, 8))) is not None


def test_count_bits_limit_is_inclusive():
    with pytest.raises(ValueError, match=_limit("L * bit_length(N)", "41000000",
                                                c.MAX_COUNT_BITS, "MAX_COUNT_BITS")):
        c.necklace_count(2**40, 10**6)
    L = c.MAX_COUNT_BITS // 2   # N = 2 has bit_length 2: exactly at the limit
    got = c.necklace_count(2, L)
    ref = sum(int(totient(d)) * 2 ** (L // d) for d in range(1, L + 1) if L % d == 0) // L
    assert got == ref


def test_total_simple_circuits_limit_shows_huge_N_shortly():
    with pytest.raises(ValueError, match=_limit("N", str(c.MAX_TOTAL_N + 1), c.MAX_TOTAL_N,
                                                "MAX_TOTAL_N")):
        c.total_simple_circuits(c.MAX_TOTAL_N + 1)
    with pytest.raises(ValueError, match=_limit("N", "<an integer of 71 digits>", c.MAX_TOTAL_N,
                                                "MAX_TOTAL_N")):
        c.total_simple_circuits(10**70)
    big = 2**200 - 1   # 200 bits: written out; 2**200 (201 bits): shortened
    with pytest.raises(ValueError, match=_limit("N", str(big), c.MAX_TOTAL_N, "MAX_TOTAL_N")):
        c.total_simple_circuits(big)
    with pytest.raises(ValueError, match=_limit("N", f"<an integer of {len(str(2**200))} digits>",
                                                c.MAX_TOTAL_N, "MAX_TOTAL_N")):
        c.total_simple_circuits(2**200)


@pytest.mark.parametrize("N", [1, 2, 5, 12])
def test_total_simple_circuits_is_the_sum_of_phi(N):
    assert c.total_simple_circuits(N) == sum(factorial(N) // (k * factorial(N - k))
                                             for k in range(1, N + 1))


def test_partition_bounds_are_named():
    for name in ("max_part", "max_parts"):
        with pytest.raises(ValueError, match=rf"^{name} {INT_WORDS}'x'$"):
            list(c.partitions(5, **{name: "x"}))
        with pytest.raises(ValueError, match=rf"^{name} must be >= 0, got -1$"):
            list(c.partitions(5, **{name: -1}))
    # 0 is allowed: no parts at all (only the empty partition of 0)
    assert list(c.partitions(5, max_part=0)) == []
    assert list(c.partitions(5, max_parts=0)) == []


def test_visits_refusal_names_the_type():
    with pytest.raises(TypeError, match=r"^visits must be an iterable of positive integers, "
                                        r"got int 5$"):
        c.normalise_visits(5)


def test_enumeration_refuses_a_huge_L_without_forming_N_to_the_L(monkeypatch):
    """With MAX_ENUMERATION_LENGTH raised by the user, a huge L reaches the N**L test: it is
    refused from 2**L > MAX_ENUMERATION before N**L is formed (2**(10**5000) would never
    finish), and the message shows L as ~10**k (str() refuses ints over 4300 digits)."""
    monkeypatch.setattr(c, "MAX_ENUMERATION_LENGTH", 10**6000)
    for N, L, shown in ((2, 10**5000, r"~10\*\*5000"), (3, 10**5000 - 1, r"~10\*\*4999"),
                        (2, 10**15, r"~10\*\*15"), (7, 10**15 - 1, "999999999999999"),
                        (2, 28, "28")):
        with pytest.raises(ValueError, match=rf"^N\*\*L = {N}\*\*{shown} words is beyond the "
                                             r"documented work limit 100000000 \(symhx\.circuits"
                                             r"\.MAX_ENUMERATION\); raise that constant to "
                                             r"allow it$"):
            c.enumerate_circuits(N, L)
    assert 2**26 <= c.MAX_ENUMERATION < 2**27  # L = 26 is allowed for N = 2, 27 is not
    assert next(iter(c.enumerate_circuits(2, 26))) == (0,) * 26
    with pytest.raises(ValueError, match=r"^N\*\*L = 2\*\*27 words"):
        c.enumerate_circuits(2, 27)


def test_total_and_circuit_length_limits_are_inclusive(monkeypatch):
    """The limits are the largest accepted values (checked with the constants lowered, as the
    module documents for raising them): N = MAX_TOTAL_N and a length of MAX_CIRCUIT_LENGTH are
    computed (against the sum of N!/(k (N-k)!) and Burnside's formula), one more is refused."""
    monkeypatch.setattr(c, "MAX_TOTAL_N", 12)
    assert c.total_simple_circuits(12) == sum(
        factorial(12) // (k * factorial(12 - k)) for k in range(1, 13))
    with pytest.raises(ValueError, match=r"^N=13 is beyond the documented work limit 12 "):
        c.total_simple_circuits(13)
    monkeypatch.setattr(c, "MAX_CIRCUIT_LENGTH", 9)
    # one vertex visited 9 times: the circuits are the N loops repeated
    assert c.circuit_count(5, (9,)) == 5
    # visits (3, 3, 3) on 3 vertices: necklaces of length 9 with content (3,3,3) = 188
    assert c.circuit_count(3, (3, 3, 3)) == sum(
        int(totient(d)) * factorial(9 // d) // factorial(3 // d) ** 3
        for d in (1, 3)) // 9
    with pytest.raises(ValueError, match=r"^circuit length sum\(visits\)=10 is beyond the "
                                         r"documented work limit 9 "):
        c.circuit_count(5, (5, 5))


def test_short_length_is_floor_log10_without_str():
    """The ``~10**k`` form of a length in the refusals: k = floor(log10 L), found from the bit
    length and one exact power of ten, checked against len(str(L)) - 1 at every power of two and
    of ten (and one below) from 10**15 to 2**400."""
    Ls = [10**k + d for k in range(15, 121) for d in (-1, 0, 1)]
    Ls += [2**b + d for b in range(50, 401) for d in (-1, 0)]
    for L in Ls:
        assert c._short_length(L) == (L if L < 10**15 else f"~10**{len(str(L)) - 1}"), L
