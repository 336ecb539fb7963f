"""Brute-force references for circuit counts, independent of symhx's formulas and its FKM
enumeration: every word of length L over N letters, reduced to its least rotation; exact
Bernoulli numbers and p-adic valuations; the contacts of pipe rows and lattices counted one by
one."""

from __future__ import annotations

import itertools
import math
from collections import Counter
from fractions import Fraction
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


def bernoulli_numbers(n: int) -> list[Fraction]:
    """``B_0 .. B_n`` exactly (Akiyama-Tanigawa algorithm; ``B_1 = +1/2``, only even indices
    are used by Stirling's series)."""
    out = []
    a = [Fraction(0)] * (n + 1)
    for m in range(n + 1):
        a[m] = Fraction(1, m + 1)
        for j in range(m, 0, -1):
            a[j - 1] = j * (a[j - 1] - a[j])
        out.append(a[0])
    return out


def valuation(n: int, p: int) -> int:
    """The exponent of the prime ``p`` in the positive int ``n``, by repeated division."""
    v = 0
    while n % p == 0:
        n //= p
        v += 1
    return v


# ------------------------------------------------------------------ the graph of impacts
def row_contacts(n: int) -> set[tuple[str, str]]:
    """The contacts of a row: walls L and R with pipes 1..n between them, neighbours touch."""
    line = ["L", *[str(i) for i in range(1, n + 1)], "R"]
    return set(itertools.pairwise(line))


def lattice_contacts(m: int) -> tuple[int, int]:
    """``(pipe-pipe, pipe-wall)`` contacts of an ``m x m`` grid with 8-neighbour contact; a pipe
    on the boundary touches the wall it faces (one contact per boundary side of a boundary
    pipe)."""
    cells = [(i, j) for i in range(m) for j in range(m)]
    pp = {frozenset((a, b)) for a in cells for b in cells
          if a != b and max(abs(a[0] - b[0]), abs(a[1] - b[1])) == 1}
    walls = sum((i == 0) + (i == m - 1) + (j == 0) + (j == m - 1) for i, j in cells)
    return len(pp), walls
