"""Brute-force references for circuit counts, independent of symhx's formulas and its FKM
enumeration: every word of length L over N letters, reduced to its least rotation."""

from __future__ import annotations

import itertools
import math
from collections import Counter
from functools import cache


def least_rotation(word: tuple[int, ...]) -> tuple[int, ...]:
    return min(word[i:] + word[:i] for i in range(len(word)))


@cache
def necklaces(N: int, L: int) -> frozenset[tuple[int, ...]]:
    """All closed walks of length L on N vertices up to rotation (least rotations)."""
    return frozenset(least_rotation(w) for w in itertools.product(range(N), repeat=L))


def pattern(word: tuple[int, ...]) -> tuple[int, ...]:
    """Visit multiplicities in decreasing order."""
    return tuple(sorted(Counter(word).values(), reverse=True))


@cache
def pattern_counts(N: int, L: int) -> dict[tuple[int, ...], int]:
    return dict(Counter(pattern(w) for w in necklaces(N, L)))


@cache
def necklaces_with_content(content: tuple[int, ...]) -> int:
    """Words using letter i exactly content[i] times, up to rotation (explicit enumeration)."""
    letters = [i for i, m in enumerate(content) for _ in range(m)]
    return len({least_rotation(w) for w in set(itertools.permutations(letters))})


def pattern_count_by_choice(N: int, visits: tuple[int, ...]) -> int:
    """Choose the r vertices (C(N, r)), give them the multiplicities (distinct arrangements of the
    multiset), then count the necklaces with that content by enumeration."""
    r = len(visits)
    if r > N:
        return 0
    arrangements = math.factorial(r)
    for c in Counter(visits).values():
        arrangements //= math.factorial(c)
    return math.comb(N, r) * arrangements * necklaces_with_content(tuple(visits))


def totient(n: int) -> int:
    return sum(1 for j in range(1, n + 1) if math.gcd(j, n) == 1)


def necklace_formula(N: int, L: int) -> int:
    """MacMahon's count (1/L) sum_{d | L} phi(d) N^(L/d), with a gcd-count totient."""
    s = sum(totient(d) * N ** (L // d) for d in range(1, L + 1) if L % d == 0)
    assert s % L == 0
    return s // L


def integer_partitions(L: int) -> list[tuple[int, ...]]:
    """Partitions of L by filtering all compositions (brute force), decreasing parts."""
    if L == 0:
        return [()]
    out = set()
    for cuts in itertools.product((0, 1), repeat=L - 1):
        parts, cur = [], 1
        for c in cuts:
            if c:
                parts.append(cur)
                cur = 1
            else:
                cur += 1
        parts.append(cur)
        out.add(tuple(sorted(parts, reverse=True)))
    return sorted(out, reverse=True)
