"""Independent references for the higher-order sample spaces (section 8): the weight ``W(k)`` of
``X = k`` as a sum over the classes of the space of Burnside circuit counts
(:func:`symhx.circuit_count` of each visit pattern) times ``p**length`` (or ``p**k``), written
out here without the class-ratio tables of :mod:`symhx.spaces`.

>>> weights(4, Fraction(1, 2), "eq41")[0]   # k = 1: one vertex visited 1..4 times, N each
Fraction(15, 4)
"""

from __future__ import annotations

from fractions import Fraction

from symhx import circuit_count
from symhx.spaces import EQ41_SHAPES, shapes_up_to

__all__ = ["brute_space_modes", "weights"]


def _shapes(space: str) -> list[tuple[int, ...]]:
    base = space.split(";")[0]
    if base == "eq41":
        return list(EQ41_SHAPES)
    if base.startswith("excess<="):
        return list(shapes_up_to(int(base.split("<=")[1])))
    raise ValueError(f"no reference for space {space!r}")


def weights(N: int, p: Fraction, space: str) -> list[Fraction]:
    """``[W(1), ..., W(N)]`` exactly: circuits of the space with k distinct vertices, each
    weighted by ``p**length`` (``p**k`` with ``;distinct``)."""
    distinct = space.endswith(";distinct")
    out = []
    for k in range(1, N + 1):
        total = Fraction(0)
        for s in _shapes(space):
            if k < max(len(s), 1):
                continue
            excess = sum(x - 1 for x in s)
            visits = tuple(sorted(s + (1,) * (k - len(s)), reverse=True))
            total += circuit_count(N, visits) * Fraction(p) ** (k if distinct else k + excess)
        out.append(total)
    return out


def brute_space_modes(N: int, p: Fraction, space: str) -> tuple[int, ...]:
    """Every maximiser of ``W(k)`` (exact Fractions)."""
    w = weights(N, p, space)
    m = max(w)
    return tuple(k for k, x in enumerate(w, 1) if x == m)
