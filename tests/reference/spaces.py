"""Independent references for the higher-order sample spaces (section 8), none of them the
package's class tables:

* the classes of a space written out by hand (eq. 41's five; ``excess<=m`` as every partition of
  an excess ``e <= m`` with each part increased by one, partitions generated here);
* the weight polynomial of ``X = k`` -- ``{degree of p: number of circuits}`` -- from Burnside's
  count of each visit pattern (:func:`symhx.circuits.circuit_count`, itself checked against
  brute-force enumeration in the circuits tests), or from explicit closed walks up to rotation
  (:func:`tests.reference.combinatorics.necklaces`) for small N;
* the roots ``c_k`` of ``W(k) = W(j)`` by plain bisection in mpmath, by polynomial roots, and
  rational roots by the rational-root theorem; argmax scans in exact ``Fraction`` arithmetic.

A space is named as in symhx (``"simple"``, ``"eq41"``, ``"eq41-printed"``, ``"excess<=m"``,
optionally ``";distinct"``); ``weighting=`` overrides the suffix.

>>> from fractions import Fraction
>>> weight_poly(3, "eq41", 1)        # k = 1: one vertex visited 1, 2, 3 or 4 times
{1: 3, 2: 3, 3: 3, 4: 3}
>>> space_weights(2, Fraction(1, 2), "simple")
[Fraction(1, 1), Fraction(1, 4)]
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import Any

import mpmath
import numpy as np

from symhx.circuits import circuit_count, enumerate_circuits
from tests.reference.combinatorics import necklaces
from tests.reference.distribution import ExactTable

#: the paper's five classes of eq. (41): simple, phi^1, phi^{1,0}, phi^2, phi^{1,0,0}
EQ41 = ((), (2,), (3,), (2, 2), (4,))

#: digits of the bisection roots
ROOT_DIGITS = 70


# --------------------------------------------------------------------------- classes
def partitions_of(e: int, largest: int | None = None) -> Iterator[tuple[int, ...]]:
    """The partitions of ``e`` into parts ``<= largest``, parts decreasing (recursion)."""
    largest = e if largest is None else largest
    if e == 0:
        yield ()
        return
    for first in range(min(e, largest), 0, -1):
        for rest in partitions_of(e - first, first):
            yield (first, *rest)


def partition_counts(m: int) -> list[int]:
    """``p(e)`` for ``e = 0..m`` by the coin-change recurrence (another route than listing)."""
    p = [1] + [0] * m
    for part in range(1, m + 1):
        for e in range(part, m + 1):
            p[e] += p[e - part]
    return p


def classes_up_to(m: int) -> frozenset[tuple[int, ...]]:
    """Every class of excess ``<= m``: a partition of ``e <= m``, each part increased by one."""
    return frozenset(tuple(x + 1 for x in part) for e in range(m + 1) for part in partitions_of(e))


def excess(shape: tuple[int, ...]) -> int:
    return sum(x - 1 for x in shape)


@dataclass(frozen=True)
class Members:
    """What a space counts: its classes, whether the boundary terms are the printed ones (the
    paper drops every ``k = r`` term except phi^1(2), eq. 36), its largest excess and weighting."""

    shapes: frozenset[tuple[int, ...]]
    printed: bool
    max_excess: int
    weighting: str

    def counts(self, shape: tuple[int, ...], k: int) -> bool:
        """Does the space count class ``shape`` at ``k`` distinct vertices?"""
        if shape not in self.shapes or k < max(len(shape), 1):
            return False
        return not (self.printed and shape and k == len(shape) and shape != (2,))


@cache
def members(space: str, weighting: str | None = None) -> Members:
    base, _, suffix = space.partition(";")
    w = weighting or suffix.strip() or "length"
    base = base.strip()
    if base in ("eq41", "eq41-printed"):
        return Members(frozenset(EQ41), base == "eq41-printed", 3, w)
    m = 0 if base == "simple" else int(base.split("<=")[1])
    return Members(classes_up_to(m), False, m, w)


def visits(shape: tuple[int, ...], k: int) -> tuple[int, ...]:
    """The visit pattern of class ``shape`` with ``k`` distinct vertices (decreasing)."""
    return (*shape, *(1,) * (k - len(shape)))


# --------------------------------------------------------------------------- weights
@cache
def _burnside_poly(N: int, space: str, weighting: str | None, k: int
                   ) -> tuple[tuple[int, int], ...]:
    mem = members(space, weighting)
    poly: dict[int, int] = {}
    for s in mem.shapes:
        if not mem.counts(s, k):
            continue
        deg = k + excess(s) if mem.weighting == "length" else k
        poly[deg] = poly.get(deg, 0) + circuit_count(N, visits(s, k))
    return tuple(sorted(poly.items()))


def weight_poly(N: int, space: str, k: int, weighting: str | None = None) -> dict[int, int]:
    """``{degree of p: circuits}`` of ``X = k`` in ``space``, from Burnside's count of each
    visit pattern (any N)."""
    return dict(_burnside_poly(N, space, weighting, k))


def weight_polys(N: int, space: str, weighting: str | None = None) -> dict[int, dict[int, int]]:
    """:func:`weight_poly` for every ``k = 1..N``."""
    return {k: weight_poly(N, space, k, weighting) for k in range(1, N + 1)}


def evaluate(poly: dict[int, int], p: Any) -> Any:
    """``W = sum c p**d`` of a weight polynomial, at an exact or mpf ``p``."""
    if isinstance(p, Fraction):
        return sum((c * p**d for d, c in poly.items()), Fraction(0))
    return mpmath.fsum(c * p**d for d, c in poly.items())


def weights_at(polys: dict[int, dict[int, int]], p: Any) -> list[Any]:
    """``[W(k) for k in sorted(polys)]``."""
    return [evaluate(polys[k], p) for k in sorted(polys)]


def space_weights(N: int, p: Fraction, space: str) -> list[Fraction]:
    """Unnormalised exact weights of X = 1..N in ``space``: Burnside circuit counts of every
    visit pattern of the space, times p to the power of its length (or of k)."""
    return weights_at(weight_polys(N, space), Fraction(p))


def exact_table(N: int, p: Fraction, space: str = "simple") -> ExactTable:
    """The exact distribution of X in ``space``: the factorial form for ``"simple"``, else the
    Burnside weights of :func:`space_weights`."""
    if space == "simple":
        return ExactTable.simple(N, Fraction(p))
    return ExactTable.of(space_weights(N, p, space))


def argmax(N: int, space: str, p: Fraction, weighting: str | None = None) -> tuple[int, ...]:
    """Every maximiser of the exact weights ``W(k)`` (an exhaustive scan)."""
    W = weights_at(weight_polys(N, space, weighting), p)
    top = max(W)
    return tuple(k for k, x in enumerate(W, 1) if x == top)


def weight_sign(N: int, space: str, k: int, p: Fraction, j: int = 1,
                weighting: str | None = None) -> int:
    """Sign of ``W(k) - W(j)`` in exact arithmetic."""
    d = evaluate(weight_poly(N, space, k, weighting), p) - evaluate(
        weight_poly(N, space, j, weighting), p)
    return (d > 0) - (d < 0)


def not_below_one(N: int, space: str, p: Fraction, best: int,
                  weighting: str | None = None) -> list[int]:
    """Every ``k = 2..N``, ``k != best``, with ``W(k) >= W(1)`` (exact)."""
    W = weights_at(weight_polys(N, space, weighting), p)
    return [k for k in range(2, N + 1) if k != best and W[k - 1] >= W[0]]


def qstar(N: int, p: Fraction, k: int, poly: dict[int, int]) -> Fraction:
    """``Q*(k) = W(k) / Phi_{N,p}(k)`` from a weight polynomial (N-independent)."""
    phi = p**k * Fraction(math.perm(N, k), k)
    return evaluate(poly, p) / phi


# --------------------------------------------------------------------------- explicit walks
def shape_of_word(word: tuple[int, ...]) -> tuple[tuple[int, ...], int]:
    """(class, k) of an explicit circuit: the parts > 1 of its visit pattern, distinct vertices."""
    mult = sorted(Counter(word).values(), reverse=True)
    return tuple(m for m in mult if m > 1), len(mult)


@cache
def walk_classes(N: int, max_len: int) -> Counter:
    """Counter of ``(class, k, L)`` over every closed walk up to rotation of length ``<= max_len``
    on ``N`` vertices (explicit enumeration: every word, least rotation)."""
    out: Counter = Counter()
    for L in range(1, max_len + 1):
        for w in necklaces(N, L):
            shape, k = shape_of_word(w)
            out[(shape, k, L)] += 1
    return out


def class_counts_by_walks(N: int, max_len: int) -> Counter:
    """Counter of ``(class, k)`` over the walks of :func:`walk_classes`."""
    out: Counter = Counter()
    for (shape, k, _), n in walk_classes(N, max_len).items():
        out[(shape, k)] += n
    return out


def walk_class_polys(N: int, space: str, weighting: str | None = None
                     ) -> dict[tuple[int, ...], dict[int, dict[int, int]]]:
    """``{class: {k: {degree of p: circuits}}}`` of the space, from explicit walks."""
    mem = members(space, weighting)
    out: dict = {}
    for (shape, k, L), n in walk_classes(N, N + mem.max_excess).items():
        if excess(shape) > mem.max_excess or not mem.counts(shape, k):
            continue
        deg = L if mem.weighting == "length" else k
        row = out.setdefault(shape, {}).setdefault(k, {})
        row[deg] = row.get(deg, 0) + n
    return out


def walk_polys(N: int, space: str, weighting: str | None = None) -> dict[int, dict[int, int]]:
    """``{k: {degree of p: circuits}}`` of the space, from explicit walks."""
    polys: dict[int, dict[int, int]] = {k: {} for k in range(1, N + 1)}
    for rows in walk_class_polys(N, space, weighting).values():
        for k, row in rows.items():
            for d, n in row.items():
                polys[k][d] = polys[k].get(d, 0) + n
    return polys


def classes_by_fkm(N: int, L: int) -> Counter:
    """Counter of ``(class, k)`` over the circuits of length ``L`` listed one by one by
    :func:`symhx.circuits.enumerate_circuits` (FKM: distinct cyclic sequences, periodic words
    once; itself checked against brute force in the circuits tests): fast enough for
    ``N**L`` in the millions; remembered per ``(N, L)``)."""
    return Counter(dict(_classes_by_fkm(N, L)))


@cache
def _classes_by_fkm(N: int, L: int) -> tuple[tuple[tuple[tuple[int, ...], int], int], ...]:
    out: Counter = Counter()
    for w in enumerate_circuits(N, L):
        out[shape_of_word(w)] += 1
    return tuple(out.items())


def pmf_by_enumeration(N: int, p: Fraction, space: str, weighting: str | None = None
                       ) -> dict[int, Fraction]:
    """``{k: P(X = k)}`` summed circuit by circuit (:func:`classes_by_fkm`) over the lengths
    ``1..N + max excess``."""
    mem = members(space, weighting)
    W: dict[int, Fraction] = {k: Fraction(0) for k in range(1, N + 1)}
    for L in range(1, N + mem.max_excess + 1):
        for (s, k), n in classes_by_fkm(N, L).items():
            if mem.counts(s, k) and excess(s) <= mem.max_excess:
                W[k] += n * (p**L if mem.weighting == "length" else p**k)
    tot = sum(W.values())
    return {k: W[k] / tot for k in range(1, N + 1)}


# --------------------------------------------------------------------------- roots c_k
def root(N: int, space: str, k: int, digits: int = ROOT_DIGITS, j: int = 1,
         weighting: str | None = None) -> mpmath.mpf:
    """The root of ``W(k) = W(j)`` (one sign change, ``W(k) < W(j)`` below it) by plain bisection
    at ``digits`` digits, to a relative width ``10**(8 - digits)``."""
    pk, pj = weight_poly(N, space, k, weighting), weight_poly(N, space, j, weighting)
    with mpmath.workdps(digits):
        lo, hi = mpmath.mpf(1) / (1000 * N), mpmath.mpf(1000)
        assert evaluate(pk, lo) < evaluate(pj, lo) and evaluate(pk, hi) > evaluate(pj, hi)
        while hi - lo > mpmath.mpf(10) ** (8 - digits) * lo:
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if evaluate(pk, mid) < evaluate(pj, mid) else (lo, mid)
        return (lo + hi) / 2


def monomial_root(N: int, space: str, k: int, weighting: str | None = None,
                  digits: int = 60) -> mpmath.mpf:
    """``c_k = (S_1 / S_k)**(1/(k-1))`` in closed form where every ``W(k) = S_k p**k`` is a
    monomial (``excess<=0``, or the ``;distinct`` weighting); ``S_k`` the circuits with k
    distinct vertices (Burnside)."""
    (d1, S1), = weight_poly(N, space, 1, weighting).items()
    (dk, Sk), = weight_poly(N, space, k, weighting).items()
    assert (d1, dk) == (1, k)
    with mpmath.workdps(digits):
        return (mpmath.mpf(S1) / Sk) ** (mpmath.mpf(1) / (k - 1))


@cache
def _roots(N: int, space: str, weighting: str | None) -> tuple[tuple[int, mpmath.mpf], ...]:
    return tuple((k, root(N, space, k, weighting=weighting)) for k in range(2, N + 1))


def roots(N: int, space: str, weighting: str | None = None) -> dict[int, mpmath.mpf]:
    """``{k: c_k}`` for ``k = 2..N`` (:func:`root` at 70 digits)."""
    return dict(_roots(N, space, weighting))


def critical_by_bisection(N: int, space: str, weighting: str | None = None
                          ) -> tuple[tuple[int, ...], mpmath.mpf]:
    """``(argmins, p_c)``: the smallest root and every k whose root is within ``10**-50``
    (relative) of it."""
    rs = roots(N, space, weighting)
    with mpmath.workdps(ROOT_DIGITS):
        pc = min(rs.values())
        return tuple(k for k, c in rs.items() if c - pc <= mpmath.mpf(10) ** -50 * pc), pc


def critical_by_polyroots(N: int, space: str, weighting: str | None = None
                          ) -> tuple[mpmath.mpf, int]:
    """``(p_c, argmin)`` from the positive roots of the integer polynomials ``W(k) - W(1)``
    (``mpmath.polyroots`` at 40 digits); asserts Descartes' single positive root for each k."""
    w1 = weight_poly(N, space, 1, weighting)
    best = None
    for k in range(2, N + 1):
        diff = weight_poly(N, space, k, weighting)
        for d, c in w1.items():
            diff[d] = diff.get(d, 0) - c
        top = max(diff)
        coeffs = [diff.get(d, 0) for d in range(top, -1, -1)]
        with mpmath.workdps(40):
            rts = mpmath.polyroots(coeffs, maxsteps=200, extraprec=200)
            pos = [mpmath.re(r) for r in rts
                   if abs(mpmath.im(r)) < 1e-25 and mpmath.re(r) > 1e-30]
        assert len(pos) == 1, (N, k, pos)  # Descartes: exactly one positive root
        if best is None or pos[0] < best[0] - mpmath.mpf(10) ** -30:
            best = (pos[0], k)
    assert best is not None
    return best


def rational_roots(coeffs: dict[int, int]) -> set[Fraction]:
    """Positive rational roots of an integer polynomial ``{degree: coefficient}`` (rational-root
    theorem, each candidate checked exactly)."""
    lo = min(d for d, c in coeffs.items() if c)
    c = {d - lo: v for d, v in coeffs.items() if v}
    top = max(c)
    a0, an = abs(c[0]), abs(c[top])

    def divisors(n: int) -> list[int]:
        return [i for i in range(1, n + 1) if n % i == 0]

    out = set()
    for num in divisors(a0):
        for den in divisors(an):
            x = Fraction(num, den)
            if sum(v * x**d for d, v in c.items()) == 0:
                out.add(x)
    return out


def rational_root(N: int, space: str, k: int, approx: mpmath.mpf,
                  weighting: str | None = None) -> Fraction | None:
    """The root ``c_k`` if it is rational: the best rational approximation of ``approx`` with a
    denominator up to 10**20, checked exactly."""
    man, exp = approx.man_exp
    cand = (Fraction(int(man)) * Fraction(2) ** int(exp)).limit_denominator(10**20)
    if weight_sign(N, space, k, cand, weighting=weighting) == 0:
        return cand
    return None


def tie_points(spaces: tuple[str, ...] = ("eq41", "eq41-printed", "excess<=1", "excess<=2"),
               Ns: tuple[int, ...] = (2, 3, 4)) -> list[tuple[str, str, int, Fraction]]:
    """``(space, weighting, N, p)`` where two weights ``W(j) = W(k)`` tie exactly: the rational
    roots of the differences of the walk polynomials."""
    pts = []
    for base in spaces:
        for w in ("length", "distinct"):
            for N in Ns:
                poly = walk_polys(N, base, w)
                for j in range(1, N + 1):
                    for k in range(j + 1, N + 1):
                        diff = dict(poly[k])
                        for dg, c in poly[j].items():
                            diff[dg] = diff.get(dg, 0) - c
                        if any(diff.values()) and max(abs(v) for v in diff.values()) < 10**5:
                            pts += [(base, w, N, x) for x in rational_roots(diff)]
    return sorted(set(pts))


def log_U_exact(space: Any, K: int) -> np.ndarray:
    """``math.log`` of a space's exact integers ``U_e(k)`` (``space.U(k)``), ``e = 0..m`` by
    ``k = 1..K``; ``-inf`` for 0."""
    out = np.full((space.max_excess + 1, K), -np.inf)
    for k in range(1, K + 1):
        for e, u in enumerate(space.U(k)):
            if u:
                out[e, k - 1] = math.log(u)
    return out
