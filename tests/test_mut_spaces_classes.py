"""Refusals and limits of ``symhx.spaces._classes`` matched whole (found by mutation testing: a
renamed argument in a message, or a dropped ``minimum``, went unnoticed), and the documented
work limit ``MAX_EXCESS`` as an inclusive bound. References: the messages as documented, and
the number of classes ``sum_{e <= m} p(e)`` with p(e) from the coin-change recurrence."""

from __future__ import annotations

import pytest

from symhx.spaces._classes import (
    MAX_EXCESS,
    check_shape,
    class_count,
    class_ratio,
    printed_count,
    shapes_up_to,
)

INT_WORDS = r"must be an integer such as 7, 10\*\*100 or '1e100', got "


@pytest.mark.parametrize("shape, shown", [("ab", "str 'ab'"), (5, "int 5"), (b"x", "bytes b'x'")])
def test_check_shape_refuses_non_sequences(shape, shown):
    with pytest.raises(TypeError, match=rf"^shape must be a tuple of ints >= 2, got {shown}$"):
        check_shape(shape)


def test_check_shape_names_a_bad_entry():
    with pytest.raises(ValueError, match=rf"^shape entry {INT_WORDS}'x'$"):
        check_shape([2, "x"])


@pytest.mark.parametrize("fn", [lambda k: class_count(5, (2,), k), lambda k: class_ratio((2,), k)])
def test_k_is_named(fn):
    with pytest.raises(ValueError, match=rf"^k {INT_WORDS}'a'$"):
        fn("a")


def test_printed_count_names_L():
    with pytest.raises(ValueError, match=rf"^L {INT_WORDS}'x'$"):
        printed_count("35", 5, "x")


@pytest.mark.parametrize("N", [0, -3])
def test_N_at_least_one(N):
    for call in (lambda: class_count(N, (2,), 2), lambda: printed_count("35", N, 3)):
        with pytest.raises(ValueError, match=rf"^N must be >= 1, got {N}$"):
            call()


def _partitions(m: int) -> list[int]:
    p = [1] + [0] * m
    for part in range(1, m + 1):
        for e in range(part, m + 1):
            p[e] += p[e - part]
    return p


def test_max_excess_is_an_inclusive_limit():
    shapes = shapes_up_to(MAX_EXCESS)
    assert len(shapes) == sum(_partitions(MAX_EXCESS)) == 9296
    with pytest.raises(ValueError, match=rf"^maximum excess m={MAX_EXCESS + 1} is beyond the "
                                         rf"documented work limit {MAX_EXCESS} "):
        shapes_up_to(MAX_EXCESS + 1)
