"""The work limits and refusals of ``symhx.circuits``: every refusal names the argument (or the
quantity limited), shows its value and the documented limit with its constant
(``symhx.circuits.CONSTANT``); each limit is inclusive. References: the decimal length of
``str(value)``, sympy's totient for the necklace counts at a boundary, and the sum of
``N!/(k (N-k)!)``."""

from __future__ import annotations

from math import factorial

from sympy import totient

import symhx.circuits as c
from tests.harness.errors import assert_refuses

INTEGER_FORMS = "an integer such as 7, 10**100 or '1e100'"
NOT_EXACT_FLOAT = ["an int", "floats above 2**53 are not exact"]


def _limit(limit: int, constant: str) -> list[str]:
    """The allowed part of a work-limit refusal: the limit and the constant that sets it."""
    return [f" {limit} ", f"symhx.circuits.{constant}", "raise that constant"]


# --------------------------------------------------------------------------- bad arguments
def test_errors_name_argument_and_value():
    assert_refuses(c.phi, 0, 1, arg="N", value="0", allowed=">= 1")
    assert_refuses(c.phi, 2.5, 1, exc=TypeError, arg="N", value="float 2.5",
                   allowed=NOT_EXACT_FLOAT)
    assert_refuses(c.circuit_count, -2, (1,), arg="N", value="-2", allowed=">= 1")
    assert_refuses(c.necklace_count, 2, 0, arg="L", value="0", allowed=">= 1")
    assert_refuses(c.total_simple_circuits, 0, arg="N", value="0", allowed=">= 1")
    assert_refuses(lambda: list(c.enumerate_circuits(2, 0)), arg="L", value="0", allowed=">= 1")
    assert_refuses(lambda: list(c.partitions(-1)), arg="L", value="-1", allowed=">= 0")
    # decimal strings are exact integers (symhx.validation); anything else is refused
    assert c.necklace_count(2, "3") == c.necklace_count(2, 3)
    assert_refuses(c.necklace_count, 2, "three", arg="L", value="'three'",
                   allowed=INTEGER_FORMS)
    for func in (c.circuits_of_length, c.necklace_count, c.enumerate_circuits):
        assert_refuses(lambda f=func: list(f(0, 2)), arg="N", value="0", allowed=">= 1")
        assert_refuses(lambda f=func: list(f(2.0, 2)), exc=TypeError, arg="N",
                       value="float 2.0", allowed=NOT_EXACT_FLOAT)


def test_bad_input():
    assert_refuses(c.circuit_count, 5, (0, 1), arg="visit multiplicity", value="(1, 0)",
                   allowed=">= 1")
    assert_refuses(c.circuit_count, 5, (), arg="visits", allowed="empty")
    assert_refuses(c.circuit_count, 5, (1.5,), exc=TypeError, arg="visits entry",
                   value="float 1.5", allowed=NOT_EXACT_FLOAT)
    assert_refuses(c.phi, 0, 1, arg="N", value="0", allowed=">= 1")
    assert c.phi(5, 6) == 0 and c.phi(5, 0) == 0


def test_bad_inputs_are_clear_errors():
    assert_refuses(c.phi, 10, 2.5, exc=TypeError, arg="k", value="float 2.5",
                   allowed=NOT_EXACT_FLOAT)
    assert_refuses(c.phi, True, 1, exc=TypeError, arg="N", value="bool True",
                   allowed="an integer")
    assert_refuses(c.circuit_count, 3, "21", exc=TypeError, arg="visits", value="str '21'",
                   allowed="an iterable of positive integers")
    assert_refuses(c.log_phi, 10, 2, dps=True, exc=TypeError, arg="dps", value="bool True",
                   allowed="an int between 1 and 5000")


def test_log_phi_refusals():
    msg = assert_refuses(c.log_phi, 3, 4, arg="k", value="k=4", allowed="<= N")
    assert "N=3" in msg
    assert_refuses(c.log_phi, 3, 0, arg="k", value="0", allowed=">= 1")
    assert_refuses(c.log_phi, 0, 1, arg="N", value="0", allowed=">= 1")


def test_normalise_visits_refusals():
    assert_refuses(c.normalise_visits, [], arg="visits", allowed="empty")
    # the message names the entries ("visit multiplicity"), shows the sorted pattern
    assert_refuses(c.normalise_visits, [0, 2], arg="visit multiplicity", value="(2, 0)",
                   allowed=">= 1")
    assert_refuses(c.normalise_visits, [1.5], exc=TypeError, arg="visits entry",
                   value="float 1.5", allowed="an int")


def test_visits_refusal_names_the_type():
    assert_refuses(c.normalise_visits, 5, exc=TypeError, arg="visits", value="int 5",
                   allowed="an iterable of positive integers")


def test_partition_bounds_are_named():
    for name in ("max_part", "max_parts"):
        assert_refuses(lambda n=name: list(c.partitions(5, **{n: "x"})), arg=name,
                       value="'x'", allowed=INTEGER_FORMS)
        assert_refuses(lambda n=name: list(c.partitions(5, **{n: -1})), arg=name, value="-1",
                       allowed=">= 0")


# --------------------------------------------------------------------------- work limits
def test_work_limits_are_clear_errors():
    assert_refuses(c.total_simple_circuits, 10**1000, arg="N",
                   allowed=_limit(c.MAX_TOTAL_N, "MAX_TOTAL_N"))
    assert c.total_simple_circuits(c.MAX_TOTAL_N // 100) > 0  # below the cap: works
    assert_refuses(c.circuits_of_length, 10, 10**6, arg="L", value=str(10**6),
                   allowed=_limit(c.MAX_PATTERN_LENGTH, "MAX_PATTERN_LENGTH"))
    assert_refuses(lambda: next(c.enumerate_circuits(10, 10**6)), arg="L",
                   allowed="MAX_ENUMERATION")
    assert_refuses(c.circuit_count, 3, (10**9,), arg="sum(visits)", value=str(10**9),
                   allowed=_limit(c.MAX_CIRCUIT_LENGTH, "MAX_CIRCUIT_LENGTH"))
    assert_refuses(c.necklace_count, 10, 10**9, arg="L * bit_length(N)",
                   allowed=_limit(c.MAX_COUNT_BITS, "MAX_COUNT_BITS"))


def test_circuit_length_limit():
    assert_refuses(c.circuit_count, 3, (c.MAX_CIRCUIT_LENGTH, 1), arg="sum(visits)",
                   value=f"={c.MAX_CIRCUIT_LENGTH + 1} ",
                   allowed=_limit(c.MAX_CIRCUIT_LENGTH, "MAX_CIRCUIT_LENGTH"))


def test_pattern_length_limit_is_inclusive():
    assert_refuses(c.circuits_of_length, 3, c.MAX_PATTERN_LENGTH + 1, arg="L",
                   value=f"={c.MAX_PATTERN_LENGTH + 1} ",
                   allowed=_limit(c.MAX_PATTERN_LENGTH, "MAX_PATTERN_LENGTH"))
    assert_refuses(c.circuits_of_length, 3, "x", arg="L", value="'x'", allowed=INTEGER_FORMS)
    assert_refuses(c.circuits_of_length, 3, 0, arg="L", value="0", allowed=">= 1")
    # at the limit: N = 1 has the single pattern (L,) of the loop
    assert c.circuits_of_length(1, c.MAX_PATTERN_LENGTH) == {(c.MAX_PATTERN_LENGTH,): 1}


def test_enumeration_limits():
    assert_refuses(c.enumerate_circuits, 10, 30, arg="N**L", value="10**30",
                   allowed=_limit(c.MAX_ENUMERATION, "MAX_ENUMERATION"))
    length_limit = [" 500 ", "symhx.circuits.MAX_ENUMERATION_LENGTH"]
    assert_refuses(c.enumerate_circuits, 2, 10**20, arg="L", value="=~10**20 ",
                   allowed=length_limit)
    assert_refuses(c.enumerate_circuits, 1, 501, arg="L", value="=501 ", allowed=length_limit)
    big = 10**15   # shown as ~10**15 from 10**15 on, as the number below it
    assert_refuses(c.enumerate_circuits, 2, big, arg="L", value="=~10**15 ")
    assert_refuses(c.enumerate_circuits, 2, big - 1, arg="L", value="=999999999999999 ")
    # N**L == MAX_ENUMERATION exactly is allowed
    assert 10**8 == c.MAX_ENUMERATION
    assert next(iter(c.enumerate_circuits(10, 8))) is not None


def test_enumerate_circuits_work_limit_exact():
    """The N**L cap is an exact integer test: no float overflow for huge L, and N = 1 counts."""
    for N, L in ((3, 10**1000), (1, 10**1000), (1, c.MAX_ENUMERATION_LENGTH + 1), (2, 27)):
        # refused at the call, before iterating
        assert_refuses(c.enumerate_circuits, N, L, arg="L", allowed="MAX_ENUMERATION")
    # below the cap it still enumerates (2**27 words > 1e8 is refused above, 2**20 is fine)
    # and the count agrees with the independent Burnside formula
    assert sum(1 for _ in c.enumerate_circuits(2, 20)) == sum(c.circuits_of_length(2, 20).values())
    assert list(c.enumerate_circuits(1, 5)) == [(0,) * 5]
    L = c.MAX_ENUMERATION_LENGTH  # the longest allowed still runs (no RecursionError)
    assert list(c.enumerate_circuits(1, L)) == [(0,) * L]


def test_count_bits_limit_is_inclusive():
    assert_refuses(c.necklace_count, 2**40, 10**6, arg="L * bit_length(N)", value="=41000000 ",
                   allowed=_limit(c.MAX_COUNT_BITS, "MAX_COUNT_BITS"))
    L = c.MAX_COUNT_BITS // 2   # N = 2 has bit_length 2: exactly at the limit
    got = c.necklace_count(2, L)
    ref = sum(int(totient(d)) * 2 ** (L // d) for d in range(1, L + 1) if L % d == 0) // L
    assert got == ref


def test_total_simple_circuits_limit_shows_huge_N_shortly():
    allowed = _limit(c.MAX_TOTAL_N, "MAX_TOTAL_N")
    assert_refuses(c.total_simple_circuits, c.MAX_TOTAL_N + 1, arg="N",
                   value=f"={c.MAX_TOTAL_N + 1} ", allowed=allowed)
    assert_refuses(c.total_simple_circuits, 10**70, arg="N",
                   value="=<an integer of 71 digits> ", allowed=allowed)
    big = 2**200 - 1   # 200 bits: written out; 2**200 (201 bits): shortened
    assert_refuses(c.total_simple_circuits, big, arg="N", value=f"={big} ", allowed=allowed)
    assert_refuses(c.total_simple_circuits, 2**200, arg="N",
                   value=f"=<an integer of {len(str(2**200))} digits> ", allowed=allowed)


def test_enumeration_refuses_a_huge_L_without_forming_N_to_the_L(monkeypatch):
    """With MAX_ENUMERATION_LENGTH raised by the user, a huge L reaches the N**L test: it is
    refused from 2**L > MAX_ENUMERATION before N**L is formed (2**(10**5000) would never
    finish), and the message shows L as ~10**k (str() refuses ints over 4300 digits)."""
    monkeypatch.setattr(c, "MAX_ENUMERATION_LENGTH", 10**6000)
    for N, L, shown in ((2, 10**5000, "~10**5000"), (3, 10**5000 - 1, "~10**4999"),
                        (2, 10**15, "~10**15"), (7, 10**15 - 1, "999999999999999"),
                        (2, 28, "28")):
        assert_refuses(c.enumerate_circuits, N, L, arg="N**L", value=f" {N}**{shown} ",
                       allowed=_limit(100000000, "MAX_ENUMERATION"))
    assert 2**26 <= c.MAX_ENUMERATION < 2**27  # L = 26 is allowed for N = 2, 27 is not
    assert next(iter(c.enumerate_circuits(2, 26))) == (0,) * 26
    assert_refuses(c.enumerate_circuits, 2, 27, arg="N**L", value=" 2**27 ")


def test_total_and_circuit_length_limits_are_inclusive(monkeypatch):
    """The limits are the largest accepted values (checked with the constants lowered, as the
    module documents for raising them): N = MAX_TOTAL_N and a length of MAX_CIRCUIT_LENGTH are
    computed (against the sum of N!/(k (N-k)!) and Burnside's formula), one more is refused."""
    monkeypatch.setattr(c, "MAX_TOTAL_N", 12)
    assert c.total_simple_circuits(12) == sum(
        factorial(12) // (k * factorial(12 - k)) for k in range(1, 13))
    assert_refuses(c.total_simple_circuits, 13, arg="N", value="=13 ",
                   allowed=_limit(12, "MAX_TOTAL_N"))
    monkeypatch.setattr(c, "MAX_CIRCUIT_LENGTH", 9)
    # one vertex visited 9 times: the circuits are the N loops repeated
    assert c.circuit_count(5, (9,)) == 5
    # visits (3, 3, 3) on 3 vertices: necklaces of length 9 with content (3,3,3) = 188
    assert c.circuit_count(3, (3, 3, 3)) == sum(
        int(totient(d)) * factorial(9 // d) // factorial(3 // d) ** 3
        for d in (1, 3)) // 9
    assert_refuses(c.circuit_count, 5, (5, 5), arg="sum(visits)", value="=10 ",
                   allowed=_limit(9, "MAX_CIRCUIT_LENGTH"))


def test_short_length_is_floor_log10_without_str():
    """The ``~10**k`` form of a length in the refusals: k = floor(log10 L), found from the bit
    length and one exact power of ten, checked against len(str(L)) - 1 at every power of two and
    of ten (and one below) from 10**15 to 2**400."""
    Ls = [10**k + d for k in range(15, 121) for d in (-1, 0, 1)]
    Ls += [2**b + d for b in range(50, 401) for d in (-1, 0)]
    for L in Ls:
        assert c._short_length(L) == (L if L < 10**15 else f"~10**{len(str(L)) - 1}"), L
