"""Brute-force references for per-site probabilities: every circuit of the complete digraph with
loops (closed walks up to rotation, enumerated word by word) weighted by the product of its sites'
probabilities, grouped by the number of distinct sites, for each sample space's *definition* of
which circuits it contains.  Independent of symhx's symmetric-polynomial formulas.

Space definitions (section 8 and ``symhx.spaces``):

* ``simple``: every site visited once;
* ``eq41``: the parts > 1 of the visit pattern are one of (), (2,), (3,), (2, 2), (4,);
* ``eq41-printed``: the same classes, but a circuit that visits no site only once is counted
  only when it is a site visited twice (eq. 36); the paper's formulas drop the others;
* ``excess<=m``: length minus distinct sites at most m.

Weighting ``length``: a circuit weighs ``prod`` over its impacts of ``p_(site)``; ``distinct``:
``prod`` over its distinct sites.
"""

from __future__ import annotations

import math
from collections import Counter
from fractions import Fraction
from functools import cache

from tests.reference.combinatorics import necklaces

EQ41 = {(), (2,), (3,), (2, 2), (4,)}


def space_rule(space: str) -> tuple[str, int, object]:
    """``(weighting, max_excess, contains)`` for a space name; ``contains(pattern)`` decides a
    visit pattern (multiplicities, decreasing)."""
    base, _, w = space.partition(";")
    weighting = w or "length"
    if base == "simple":
        return weighting, 0, lambda pat: all(m == 1 for m in pat)
    if base == "eq41":
        return weighting, 3, lambda pat: tuple(m for m in pat if m > 1) in EQ41
    if base == "eq41-printed":
        def printed(pat: tuple[int, ...]) -> bool:
            shape = tuple(m for m in pat if m > 1)
            if shape not in EQ41:
                return False
            if all(m > 1 for m in pat):  # no site visited once: only a loop visited twice
                return pat == (2,)
            return True
        return weighting, 3, printed
    if base.startswith("excess<="):
        m = int(base[len("excess<="):])
        return weighting, m, lambda pat: sum(pat) - len(pat) <= m
    raise ValueError(space)


@cache
def _circuits(N: int, Lmax: int) -> tuple[tuple[int, ...], ...]:
    out: list[tuple[int, ...]] = []
    for L in range(1, Lmax + 1):
        out.extend(sorted(necklaces(N, L)))
    return tuple(out)


def brute_weights(probs: tuple[Fraction, ...], space: str, Lmax: int = 7
                  ) -> dict[int, Fraction]:
    """``{k: total weight of the circuits of the space with k distinct sites}`` over every
    circuit of length ``<= Lmax``, complete for ``k <= Lmax - max_excess`` (only those keys are
    returned)."""
    N = len(probs)
    weighting, excess, contains = space_rule(space)
    out: dict[int, Fraction] = {}
    for word in _circuits(N, Lmax):
        counts = Counter(word)
        pat = tuple(sorted(counts.values(), reverse=True))
        if not contains(pat):
            continue
        w = Fraction(1)
        for site, m in counts.items():
            w *= probs[site] ** (m if weighting == "length" else 1)
        k = len(counts)
        out[k] = out.get(k, Fraction(0)) + w
    kmax = min(N, Lmax - excess)
    return {k: out.get(k, Fraction(0)) for k in range(1, kmax + 1)}


def elementary(probs: tuple[Fraction, ...], k: int) -> Fraction:
    """``e_k`` by summing over all k-subsets (no recurrence)."""
    from itertools import combinations

    return sum((math.prod(c, start=Fraction(1)) for c in combinations(probs, k)), Fraction(0))


def simple_weight(probs: tuple[Fraction, ...], k: int) -> Fraction:
    """``(k-1)! e_k``: the simple circuits on k distinct sites."""
    return math.factorial(k - 1) * elementary(probs, k)


def expand(sizes: tuple[int, ...], probs: tuple[Fraction, ...]) -> tuple[Fraction, ...]:
    """One probability per site from classes."""
    return tuple(p for n, p in zip(sizes, probs, strict=True) for _ in range(n))


def direction_c(w: tuple[Fraction, ...], k: int) -> Fraction:
    """``c_k**(k-1) = e_1 / ((k-1)! e_k)`` exactly (the direction's critical value of k, raised
    to ``k - 1``)."""
    return elementary(w, 1) / simple_weight(w, k)


def direction_argmins(w: tuple[Fraction, ...]) -> tuple[int, ...]:
    """Every argmin of ``c_k`` (:func:`direction_c`), compared exactly: ``c_j <= c_k`` iff
    ``(c_j**(j-1))**(k-1) <= (c_k**(k-1))**(j-1)``."""
    N = len(w)
    powers = {k: direction_c(w, k) for k in range(2, N + 1)}

    def le(j: int, k: int) -> bool:
        return powers[j] ** (k - 1) <= powers[k] ** (j - 1)

    return tuple(k for k in powers if all(le(k, j) for j in powers))


def site_pmf(sizes: tuple[int, ...], probs: tuple[Fraction, ...]) -> list[Fraction]:
    """``P(X = k)``, k = 1..N, exactly from the class convolution :func:`mode_weights`."""
    w = mode_weights(sizes, probs)
    g = sum(w)
    return [x / g for x in w]


def mode_weights(sizes: tuple[int, ...], probs: tuple[Fraction, ...]) -> list[Fraction]:
    """``W(k)``, ``k = 1..N``, of the simple space for classes, from the class convolution
    ``e_k = sum prod C(n_i, k_i) q_i**k_i`` written out over compositions of k."""
    N = sum(sizes)
    out = []
    for k in range(1, N + 1):
        total = Fraction(0)
        for comp in _compositions(k, len(sizes)):
            if all(kk <= n for kk, n in zip(comp, sizes, strict=True)):
                term = Fraction(1)
                for kk, n, q in zip(comp, sizes, probs, strict=True):
                    term *= math.comb(n, kk) * q**kk
                total += term
        out.append(math.factorial(k - 1) * total)
    return out


def _compositions(n: int, c: int):  # type: ignore[no-untyped-def]
    if c == 1:
        yield (n,)
        return
    for first in range(n + 1):
        for rest in _compositions(n - first, c - 1):
            yield (first, *rest)
