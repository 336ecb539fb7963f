"""Exact circuit counts in the complete directed graph with self-loops (sections 3 and 8).

A *circuit* is a closed walk up to rotation (a necklace over the vertex alphabet). Its *visit
pattern* is the multiset of how often it visits each vertex it touches: ``(1, 1, 1)`` is a simple
3-circuit, ``(2, 1, 1)`` visits one vertex twice and two others once (length 4, 3 distinct
vertices).

All counts are exact Python ints.

* :func:`phi` -- eq. (5): simple circuits of length ``k``, ``N! / (k (N - k)!)``.
* :func:`circuit_count` -- any visit pattern, by Burnside's lemma: the number of necklaces with a
  given content, times the number of ways to pick the labelled vertices.
* :func:`necklace_count` -- all circuits of length ``L`` (``(1/L) sum_{d|L} phi(d) N**(L/d)``).
* :func:`enumerate_circuits` -- brute-force enumeration (FKM necklace generation) for small ``N``,
  an independent check used by the tests.

>>> phi(100, 1), phi(4, 4)
(100, 6)
>>> circuit_count(7, (3,))      # one vertex three times: N circuits (not N/3 as printed)
7
>>> circuit_count(7, (2, 2))    # two vertices twice each: N (N - 1)
42
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterable, Iterator
from functools import lru_cache

import mpmath

from symhx._mpctx import export, mp
from symhx.validation import DEFAULT_DPS, check_dps, check_int

__all__ = [
    "MAX_CIRCUIT_LENGTH",
    "MAX_COUNT_BITS",
    "MAX_ENUMERATION",
    "MAX_ENUMERATION_LENGTH",
    "MAX_PATTERN_LENGTH",
    "MAX_TOTAL_N",
    "brute_force_pattern_counts",
    "circuit_count",
    "circuits_of_length",
    "enumerate_circuits",
    "log_phi",
    "necklace_count",
    "necklaces_with_content",
    "normalise_visits",
    "partitions",
    "phi",
    "total_simple_circuits",
]

# Documented work limits: inputs beyond them are refused up front (they would run for hours or
# exhaust memory).  Raise a limit by assigning the constant, e.g.
# ``symhx.circuits.MAX_TOTAL_N = 10**6``, if you really need it.
#: largest N of :func:`total_simple_circuits` (an O(N) loop on numbers of ~N log2 N bits: ~6 s)
MAX_TOTAL_N = 50_000
#: largest circuit length of :func:`circuit_count` (Burnside needs (length)!)
MAX_CIRCUIT_LENGTH = 100_000
#: largest length of :func:`circuits_of_length` (it lists every partition: p(50) = 204226)
MAX_PATTERN_LENGTH = 50
#: largest size in bits of a result of :func:`phi` (~k log2 N), :func:`circuit_count` (its
#: ``N!/(N - r)!`` factor, ~r log2 N for r distinct vertices) and :func:`necklace_count` (~N**L)
MAX_COUNT_BITS = 10_000_000
#: largest number of words ``N**L`` that :func:`enumerate_circuits` may walk
MAX_ENUMERATION = 10**8
#: :func:`enumerate_circuits` refuses longer circuits (its recursion nests L generators)
MAX_ENUMERATION_LENGTH = 500


def _int(value: object, name: str, minimum: int) -> int:
    return check_int(value, name, minimum=minimum)


def _short(value: int) -> str:
    if value.bit_length() > 200:
        return f"<an integer of {int(value.bit_length() * 0.30103) + 1} digits>"
    return str(value)


def _refuse(what: str, value: int, limit: int, constant: str) -> ValueError:
    return ValueError(f"{what}={_short(value)} is beyond the documented work limit {limit} "
                      f"(symhx.circuits.{constant}); raise that constant to allow it")


def phi(N: int, k: int) -> int:
    """Number of simple circuits of length ``k`` in the complete digraph with loops, eq. (5).

    ``phi_N(k) = N! / (k (N - k)!)``: choose the ordered ``k`` distinct vertices
    (``N! / (N - k)!`` ways, eq. 4 times ``N``), then divide by the ``k`` rotations.

    Parameters
    ----------
    N : int
        Number of vertices (possible impacts), ``N >= 1``.
    k : int
        Circuit length; ``0`` is returned for ``k < 1`` or ``k > N``.

    Returns
    -------
    int
        The exact count. For huge ``N`` and ``k`` use :func:`log_phi`.

    Raises
    ------
    ValueError
        For ``N < 1``, and when the count would have more than about
        :data:`MAX_COUNT_BITS` bits (``k * bit_length(N)``, checked before any work).

    >>> [phi(5, k) for k in range(1, 6)]
    [5, 10, 20, 30, 24]
    """
    N = _int(N, "N", 1)
    k = check_int(k, "k")
    if k < 1 or k > N:
        return 0
    if k * N.bit_length() > MAX_COUNT_BITS:  # the count has about k log2(N) bits
        raise _refuse("k * bit_length(N)", k * N.bit_length(), MAX_COUNT_BITS, "MAX_COUNT_BITS")
    return math.perm(N, k) // k


def log_phi(N: int, k: int, *, dps: int = DEFAULT_DPS) -> mpmath.mpf:
    """Natural log of :func:`phi` to ``dps`` significant digits, for any size of ``N``.

    >>> float(log_phi(10**100, 2, dps=30) - 2 * mpmath.log(10**100) + mpmath.log(2)) < 1e-90
    True
    """
    N = _int(N, "N", 1)
    k = _int(k, "k", 1)
    dps = check_dps(dps)
    if k > N:
        raise ValueError(f"k must be <= N, got k={k}, N={N}")
    # loggamma(N+1) - loggamma(N-k+1) cancels ~log10(N) digits
    guard = 10 + int(N.bit_length() * 0.30103) + 1
    ctx = mp()  # this thread's context (symhx._mpctx): threads never share a precision
    with ctx.workdps(dps + guard):
        val = ctx.loggamma(N + 1) - ctx.loggamma(N - k + 1) - ctx.log(k)
    return export(val, dps)


def total_simple_circuits(N: int) -> int:
    """Total number of simple circuits ``sum_k phi_N(k)``: 1, 3, 8, 24, 89, 415, ... (N >= 1).

    The result has about ``N log2 N`` bits; ``N`` above :data:`MAX_TOTAL_N` is refused.

    >>> [total_simple_circuits(N) for N in range(1, 7)]
    [1, 3, 8, 24, 89, 415]
    """
    N = _int(N, "N", 1)
    if N > MAX_TOTAL_N:
        raise _refuse("N", N, MAX_TOTAL_N, "MAX_TOTAL_N")
    total, perm = 0, 1
    for k in range(1, N + 1):
        perm *= N - k + 1
        total += perm // k
    return total


def normalise_visits(visits: Iterable[int]) -> tuple[int, ...]:
    """Validate a visit pattern and return it sorted in decreasing order.

    >>> normalise_visits([1, 2, 1])
    (2, 1, 1)
    """
    if isinstance(visits, (str, bytes)) or not isinstance(visits, Iterable):
        raise TypeError(f"visits must be an iterable of positive integers, got "
                        f"{type(visits).__name__} {visits!r}")
    vs = tuple(sorted((check_int(v, "visits entry") for v in visits), reverse=True))
    if not vs:
        raise ValueError("visits must not be empty")
    if vs[-1] < 1:
        raise ValueError(f"every visit multiplicity must be >= 1, got {vs}")
    return vs


@lru_cache(maxsize=4096)
def necklaces_with_content(content: tuple[int, ...]) -> int:
    """Necklaces (words up to rotation) whose letters are distinct labelled symbols used
    ``content[i]`` times each. Burnside: (1/L) sum_{d | gcd} phi(d) (L/d)! / prod (m_i/d)!.

    >>> necklaces_with_content((2, 2)), necklaces_with_content((1, 1, 1))
    (2, 2)
    """
    L = sum(content)
    g = 0
    for m in content:
        g = math.gcd(g, m)
    total = 0
    for d in range(1, g + 1):
        if g % d:
            continue
        words = math.factorial(L // d)
        for m in content:
            words //= math.factorial(m // d)
        total += _euler_phi(d) * words
    assert total % L == 0
    return total // L


def _euler_phi(n: int) -> int:
    result, m, p = n, n, 2
    while p * p <= m:
        if m % p == 0:
            while m % p == 0:
                m //= p
            result -= result // p
        p += 1
    if m > 1:
        result -= result // m
    return result


def circuit_count(N: int, visits: Iterable[int]) -> int:
    """Number of circuits whose vertex-visit multiplicities are the multiset ``visits``.

    A circuit with pattern ``(m_1, ..., m_r)`` touches ``r`` distinct vertices, visiting the
    ``i``-th one ``m_i`` times; its length is ``L = sum(m_i)``. The count is

    ``N! / ((N - r)! prod_j c_j!)``  (labelled vertices for each multiplicity, ``c_j`` of them
    visited ``j`` times) times ``(1/L) sum_{d | gcd(m)} phi(d) (L/d)! / prod_i (m_i/d)!``
    (Burnside's lemma for necklaces of given content).

    The paper's section-8 classes are special cases (eqs. 35-40; see :mod:`symhx.spaces`), and
    unlike those formulas this one is right at every length, including the boundary cases.

    Parameters
    ----------
    N : int
        Number of vertices, ``N >= 1``.
    visits : iterable of int
        Visit multiplicities, each ``>= 1``; order does not matter.

    Returns
    -------
    int
        Exact count; ``0`` if the pattern needs more than ``N`` distinct vertices.

    Raises
    ------
    ValueError
        For a length above :data:`MAX_CIRCUIT_LENGTH`, or a count whose ``N!/(N - r)!`` factor
        would exceed :data:`MAX_COUNT_BITS` bits (``r * bit_length(N)``, checked before any
        work).

    >>> circuit_count(10, (1, 1, 1)) == phi(10, 3)
    True
    >>> circuit_count(5, (2, 1))   # eq. (35) at k = 3: (1/2)(k-1) N!/(N-(k-1))! = 2*20/2
    20
    """
    N = _int(N, "N", 1)
    vs = normalise_visits(visits)
    if sum(vs) > MAX_CIRCUIT_LENGTH:
        raise _refuse("circuit length sum(visits)", sum(vs), MAX_CIRCUIT_LENGTH,
                      "MAX_CIRCUIT_LENGTH")
    r = len(vs)
    if r > N:
        return 0
    if r * N.bit_length() > MAX_COUNT_BITS:  # N!/(N - r)! alone has about r log2 N bits
        raise _refuse("len(visits) * bit_length(N)", r * N.bit_length(), MAX_COUNT_BITS,
                      "MAX_COUNT_BITS")
    choose = math.perm(N, r)
    for c in Counter(vs).values():
        choose //= math.factorial(c)
    return choose * necklaces_with_content(vs)


def necklace_count(N: int, L: int) -> int:
    """All circuits of length ``L`` (necklaces of length ``L`` over ``N`` letters).

    ``(1/L) sum_{d | L} phi(d) N**(L/d)``; equals the sum of :func:`circuit_count` over all
    partitions of ``L``.

    >>> necklace_count(2, 4), sum(circuit_count(2, v) for v in partitions(4))
    (6, 6)
    """
    N = _int(N, "N", 1)
    L = _int(L, "L", 1)
    if L * N.bit_length() > MAX_COUNT_BITS:
        raise _refuse("L * bit_length(N)", L * N.bit_length(), MAX_COUNT_BITS, "MAX_COUNT_BITS")
    total = sum(_euler_phi(d) * N ** (L // d) for d in range(1, L + 1) if L % d == 0)
    return total // L


def partitions(L: int, max_part: int | None = None, max_parts: int | None = None
               ) -> Iterator[tuple[int, ...]]:
    """Integer partitions of ``L`` in decreasing order (parts <= max_part, at most max_parts parts).

    >>> list(partitions(4))
    [(4,), (3, 1), (2, 2), (2, 1, 1), (1, 1, 1, 1)]
    """
    L = _int(L, "L", 0)
    top = L if max_part is None else min(L, _int(max_part, "max_part", 0))
    limit = L if max_parts is None else _int(max_parts, "max_parts", 0)

    def rec(rem: int, top: int, left: int) -> Iterator[tuple[int, ...]]:
        if rem == 0:
            yield ()
            return
        if left == 0:
            return
        for part in range(min(rem, top), 0, -1):
            for rest in rec(rem - part, part, left - 1):
                yield (part, *rest)

    yield from rec(L, top, limit)


def circuits_of_length(N: int, L: int) -> dict[tuple[int, ...], int]:
    """Circuits of length ``L`` split by visit pattern: ``{pattern: count}`` (non-zero counts only).

    >>> circuits_of_length(3, 3)
    {(3,): 3, (2, 1): 6, (1, 1, 1): 2}
    """
    N = _int(N, "N", 1)
    L = _int(L, "L", 1)
    if L > MAX_PATTERN_LENGTH:
        raise _refuse("L", L, MAX_PATTERN_LENGTH, "MAX_PATTERN_LENGTH")
    return {v: circuit_count(N, v) for v in partitions(L, max_parts=N)}


# --------------------------------------------------------------------------- brute force
def _short_length(L: int) -> int | str:
    """``L`` for a message: as is below 10**15, else ``~10**k`` with ``k = floor(log10 L)``
    (found without str(), which refuses ints of more than 4300 digits)."""
    if L < 10**15:
        return L
    k = int((L.bit_length() - 1) * 0.30102999566398)  # floor(log10 L) or one less
    return f"~10**{k + 1 if 10 ** (k + 1) <= L else k}"


def enumerate_circuits(N: int, L: int) -> Iterator[tuple[int, ...]]:
    """Every circuit of length ``L`` on vertices ``0..N-1``, as its least rotation.

    Brute force (the Fredricksen-Kessler-Maiorana algorithm), independent of the Burnside count;
    intended for small ``N**L`` (tests and teaching).

    >>> list(enumerate_circuits(2, 3))
    [(0, 0, 0), (0, 0, 1), (0, 1, 1), (1, 1, 1)]
    """
    N = _int(N, "N", 1)
    L = _int(L, "L", 1)
    # exact integer tests (L may be huge)
    if L > MAX_ENUMERATION_LENGTH:
        raise ValueError(f"L={_short_length(L)} is beyond the documented limit "
                         f"{MAX_ENUMERATION_LENGTH} (symhx.circuits.MAX_ENUMERATION_LENGTH: the "
                         f"enumeration nests L generators)")
    # N**L >= 2**L: a long L is refused before N**L is formed (MAX_ENUMERATION_LENGTH may
    # have been raised by the user)
    if N > 1 and (L > MAX_ENUMERATION.bit_length() or N**L > MAX_ENUMERATION):
        raise ValueError(f"N**L = {N}**{_short_length(L)} words is beyond the documented work "
                         f"limit {MAX_ENUMERATION} (symhx.circuits.MAX_ENUMERATION); raise that "
                         f"constant to allow it")
    return _enumerate(N, L)


def _enumerate(N: int, L: int) -> Iterator[tuple[int, ...]]:
    a = [0] * (L + 1)

    def gen(t: int, p: int) -> Iterator[tuple[int, ...]]:
        if t > L:
            if L % p == 0:
                yield tuple(a[1:])
            return
        a[t] = a[t - p]
        yield from gen(t + 1, p)
        for j in range(a[t - p] + 1, N):
            a[t] = j
            yield from gen(t + 1, t)

    yield from gen(1, 1)


def brute_force_pattern_counts(N: int, L: int) -> Counter[tuple[int, ...]]:
    """Count enumerated circuits of length ``L`` by visit pattern (brute force).

    >>> brute_force_pattern_counts(3, 3) == Counter(circuits_of_length(3, 3))
    True
    """
    counts: Counter[tuple[int, ...]] = Counter()
    for word in enumerate_circuits(N, L):
        counts[tuple(sorted(Counter(word).values(), reverse=True))] += 1
    return counts
