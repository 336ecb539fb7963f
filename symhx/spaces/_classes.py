"""Sample spaces of circuits and their exact class counts (section 8, eqs. 28-41).

Vocabulary
----------
* A *visit pattern* ``v = (m_1 >= m_2 >= ...)`` lists how often a circuit visits each vertex it
  touches: ``k = len(v)`` distinct vertices (the value of X), length ``L = sum(v)``, *excess*
  ``e = L - k``.
* Its *class* (or *shape*) ``s`` is the tuple of the parts ``> 1``: ``()`` simple circuits,
  ``(2,)`` one vertex twice (the paper's phi^1), ``(3,)`` once three times (phi^{1,0}),
  ``(4,)`` (phi^{1,0,0}), ``(2, 2)`` two vertices twice (phi^2). A class with ``r`` parts and
  excess ``e`` occurs for every ``k >= r`` (``k - r`` vertices visited once).

The count, for ``k > r`` (at least one vertex visited once, so no rotation fixes a circuit), is

``count(N, s, k) = N!/(N-k)! * (k+e-1)! / ((k-r)! * C_s * S_s)``,
``C_s = prod_j c_j!`` (``c_j`` parts equal to ``j``), ``S_s = prod_i s_i!``;

relative to the simple count ``phi_N(k) = N!/(k (N-k)!)`` (eq. 5) this is the polynomial

``R_s(k) = rising(k, e) * falling(k, r) / (C_s * S_s)``

which does not depend on N. At ``k = r`` (every vertex repeated) rotations can fix a circuit and
the polynomial gives ``words / L`` instead of the number of necklaces: this is exactly where the
paper's eqs. (35), (38)-(40) fail. The boundary value comes from Burnside's
lemma (:func:`symhx.circuits.circuit_count`).

A space is a finite set of classes plus a weighting. With ``w_e = p**e`` (length weighting,
default) or ``w_e = 1`` (weighting by ``p**k``, "distinct"), the weight of ``X = k`` is

``W(k) = Phi_{N,p}(k) * Q*(k),  Q*(k) = sum_e w_e U_e(k) / D``

with integers ``U_e(k) = D * sum_{s: e_s = e} R*_s(k)`` (``R*`` includes the boundary values) and
one common denominator ``D``; only ``Phi`` depends on N.
"""

from __future__ import annotations

import math
import re
from collections import Counter
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache

from symhx import circuits as _circuits  # MAX_COUNT_BITS, read when called
from symhx.circuits import (
    necklaces_with_content,
    normalise_visits,
    partitions,
)
from symhx.validation import InputError, check_int, check_N

__all__ = [
    "EQ41_SHAPES",
    "MAX_EXCESS",
    "MAX_SPACE_WORK",
    "PRINTED_RANGES",
    "Space",
    "check_shape",
    "check_space_work",
    "class_count",
    "class_ratio",
    "eq41_terms",
    "paper_label",
    "parse_space",
    "printed_count",
    "shape_excess",
    "shapes_up_to",
    "space_n_limit",
]

#: the paper's five classes (eq. 41): simple, phi^1, phi^{1,0}, phi^2, phi^{1,0,0}
EQ41_SHAPES: tuple[tuple[int, ...], ...] = ((), (2,), (3,), (2, 2), (4,))

#: stated ranges of the printed formulas: eq -> (class, smallest valid length)
PRINTED_RANGES: dict[str, tuple[tuple[int, ...], int]] = {
    "35": ((2,), 3),
    "38": ((3,), 4),
    "39": ((4,), 5),
    "40": ((2, 2), 5),
}

WEIGHTINGS = ("length", "distinct")
#: Largest excess m of ``"excess<=m"`` (a documented work limit: the number of classes grows like
#: the partition numbers, 9296 classes at m = 25).  Raise it by assigning the constant.
MAX_EXCESS = 25
#: Work limit of every higher-order-space computation that scans ``k = 1..N`` (``critical_point``,
#: ``modes``, every distribution over the space, ``class_decomposition``): float64 arrays of
#: ``N * (m + 1)`` entries (``m`` the space's largest excess) are swept by the root search and
#: the screens, so ``N * (m + 1)`` must not exceed this.  Measured on 2 shared cores:
#: ``critical_point(10**6, space="eq41")`` (4e6) 9 s, ``critical_point(10**5,
#: space="excess<=25")`` (2.6e6) 6 s.  Checked before any work, the same for the API and the CLI;
#: raise it by assigning the constant.
MAX_SPACE_WORK = 4_000_000


def shape_excess(shape: tuple[int, ...]) -> int:
    """Excess ``L - k`` of a class: ``sum(s_i - 1)``.

    >>> shape_excess((2, 2)), shape_excess(())
    (2, 0)
    """
    return sum(s - 1 for s in shape)


def check_shape(shape: tuple[int, ...] | list[int]) -> tuple[int, ...]:
    """Validate a class (the parts ``> 1`` of a visit pattern); return it sorted decreasing.

    >>> check_shape([2, 3])
    (3, 2)
    """
    if isinstance(shape, (str, bytes)) or not hasattr(shape, "__iter__"):
        raise TypeError(f"shape must be a tuple of ints >= 2, got {type(shape).__name__} "
                        f"{shape!r:.80}")
    s = tuple(sorted((check_int(x, "shape entry") for x in shape), reverse=True))
    if any(x < 2 for x in s):
        raise InputError(f"shape (a class) must list the parts > 1 of a visit pattern (the "
                         f"vertices visited more than once), got shape={shape!r:.80}")
    return s


def shapes_up_to(m: int) -> tuple[tuple[int, ...], ...]:
    """All classes of excess ``<= m`` (partitions of ``e`` with each part increased by one).

    Their number is ``sum_{e<=m} p(e)``: 1, 2, 4, 7, 12, 19, 30, ... for m = 0, 1, 2, ...

    >>> shapes_up_to(2)
    ((), (2,), (3,), (2, 2))
    >>> [len(shapes_up_to(m)) for m in range(7)]
    [1, 2, 4, 7, 12, 19, 30]
    """
    m = check_int(m, "maximum excess m", minimum=0)
    if m > MAX_EXCESS:
        from symhx.validation import show_exact

        raise InputError(f"maximum excess m={show_exact(m)} is beyond the documented work limit "
                         f"{MAX_EXCESS} "
                         f"(symhx.spaces._classes.MAX_EXCESS: excess<=25 already has 9296 "
                         f"classes and takes seconds per distribution); raise that constant "
                         f"to allow it")
    out: list[tuple[int, ...]] = [()]
    for e in range(1, m + 1):
        out += [tuple(x + 1 for x in part) for part in partitions(e)]
    return tuple(out)


def space_n_limit(space: Space) -> int:
    """Largest ``N`` allowed by :data:`MAX_SPACE_WORK` over ``space``: ``MAX_SPACE_WORK // (m+1)``.

    >>> space_n_limit(parse_space("eq41"))
    1000000
    """
    return MAX_SPACE_WORK // (space.max_excess + 1)


def check_space_work(space: Space, N: int, what: str) -> None:
    """Refuse, before any work, ``what`` over ``space`` when ``N * (m + 1) > MAX_SPACE_WORK``.

    >>> check_space_work(parse_space("eq41"), 10**6, "critical_point")
    >>> check_space_work(parse_space("eq41"), 10**7, "critical_point")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    symhx.validation.InputError: N=10000000 is beyond the documented work limit ... N <= 1000000 ...
    """
    if space.base == "simple" or N * (space.max_excess + 1) <= MAX_SPACE_WORK:
        return
    from symhx.validation import show_exact

    raise InputError(
        f"N={show_exact(N)} is beyond the documented work limit of {what} over space "
        f"{space.name!r}: N <= {space_n_limit(space)} (N * (m + 1) <= MAX_SPACE_WORK = "
        f"{MAX_SPACE_WORK} with m = {space.max_excess}, symhx.spaces._classes.MAX_SPACE_WORK); "
        f"raise that constant to allow it")


def paper_label(shape: tuple[int, ...]) -> str:
    """The paper's notation (eq. 37) ``phi^{delta_j ...}``: ``delta_j`` vertices visited ``j+1``
    times, leading zeros omitted; ``phi`` for simple circuits.

    >>> [paper_label(s) for s in EQ41_SHAPES]
    ['phi', 'phi^1', 'phi^{1,0}', 'phi^2', 'phi^{1,0,0}']
    """
    s = check_shape(shape)
    if not s:
        return "phi"
    c = Counter(s)
    top = max(s)
    deltas = [c.get(j + 1, 0) for j in range(top - 1, 0, -1)]
    inner = ",".join(str(d) for d in deltas)
    return f"phi^{inner}" if len(deltas) == 1 else f"phi^{{{inner}}}"


def _C(shape: tuple[int, ...]) -> int:
    out = 1
    for c in Counter(shape).values():
        out *= math.factorial(c)
    return out


def _S(shape: tuple[int, ...]) -> int:
    out = 1
    for s in shape:
        out *= math.factorial(s)
    return out


def _rising(k: int, e: int) -> int:
    out = 1
    for i in range(e):
        out *= k + i
    return out


def _falling(k: int, r: int) -> int:
    out = 1
    for i in range(r):
        out *= k - i
    return out


def _poly_ratio(shape: tuple[int, ...], k: int) -> Fraction:
    """``R_s(k)`` from the ``k > r`` formula (also evaluated at the boundary ``k = r``)."""
    e, r = shape_excess(shape), len(shape)
    return Fraction(_rising(k, e) * _falling(k, r), _C(shape) * _S(shape))


def _true_boundary_ratio(shape: tuple[int, ...]) -> Fraction:
    """``count(N, s, r) / phi_N(r)`` at ``k = r`` (Burnside): ``r * necklaces(s) / C_s``."""
    r = len(shape)
    return Fraction(r * necklaces_with_content(shape), _C(shape))


def class_ratio(shape: tuple[int, ...], k: int, *, printed: bool = False) -> Fraction:
    """``count(N, s, k) / phi_N(k)``: N-independent; 0 for ``k < r``.

    ``printed=True`` gives the paper's counts: the formulas (35), (38)-(40) wherever they are
    stated to hold, (36) ``phi^1(2) = N``, and 0 for the other excluded boundary lengths.

    >>> class_ratio((2,), 1), class_ratio((2,), 3)     # phi^1(2)/phi(1) = N/N; phi^1(4)/phi(3)
    (Fraction(1, 1), Fraction(9, 2))
    >>> class_ratio((2, 2), 2), class_ratio((2, 2), 2, printed=True)
    (Fraction(2, 1), Fraction(0, 1))
    """
    return _ratio_unchecked(check_shape(shape), check_int(k, "k"), printed)


def _ratio_unchecked(s: tuple[int, ...], k: int, printed: bool) -> Fraction:
    """:func:`class_ratio` of a validated class ``s`` (sorted decreasing, parts >= 2)."""
    r = len(s)
    if k < max(r, 1):
        return Fraction(0)
    if k > r:
        return _poly_ratio(s, k)
    if printed:
        return Fraction(1) if s == (2,) else Fraction(0)
    return _true_boundary_ratio(s)


def class_count(N: int, shape: tuple[int, ...], k: int, *, printed: bool = False) -> int:
    """Number of circuits of class ``shape`` with ``k`` distinct vertices (length
    ``k + excess``) in the complete digraph with loops on ``N`` vertices.

    Equal to :func:`symhx.circuits.circuit_count` of the visit pattern ``shape + (1,)*(k-r)``;
    ``printed=True`` gives the paper's count instead (see :func:`class_ratio`).

    Raises
    ------
    ValueError
        A bad ``N``, ``shape`` or ``k``, or a count of more than about
        :data:`symhx.circuits.MAX_COUNT_BITS` bits (``k * bit_length(N)``, checked first).

    >>> class_count(100, (3,), 1), class_count(100, (3,), 1, printed=True)
    (100, 0)
    >>> class_count(10, (2, 2), 4)      # eq. (40) at length 6: (1/8) 5!/2! * 10!/6!
    37800
    """
    N = check_N(N, minimum=1)
    k = check_int(k, "k")
    shape = check_shape(shape)  # validated even where the count is 0 (k outside 1..N)
    if k < 1 or k > N:
        return 0
    if k * N.bit_length() > _circuits.MAX_COUNT_BITS:  # the count has about k log2(N) bits
        from symhx.validation import show_exact

        raise InputError(f"class_count(N={show_exact(N)}, k={show_exact(k)}) would have about "
                         f"k * bit_length(N) = {show_exact(k * N.bit_length())} bits, beyond "
                         f"the documented work limit k * bit_length(N) <= "
                         f"{_circuits.MAX_COUNT_BITS} "
                         f"(symhx.circuits.MAX_COUNT_BITS); use symhx.log_phi for the size of "
                         f"such counts")
    val = class_ratio(shape, k, printed=printed) * Fraction(math.perm(N, k), k)
    assert val.denominator == 1
    return int(val)


# --------------------------------------------------------------------------- printed formulas
def printed_count(eq: str, N: int, L: int, *, outside: str = "zero") -> Fraction:
    """The paper's printed count of eq. ``"35"``, ``"36"``, ``"38"``, ``"39"`` or ``"40"`` at
    length ``L`` (the paper's ``k`` is the length).

    ``outside="zero"`` returns 0 at lengths excluded by the stated range (except eq. 36, which
    *is* the ``L = 2`` value of phi^1); ``outside="formula"`` evaluates the formula anyway,
    showing what it would give there (``N/3``, ``N/4``, ``3N(N-1)/4``: words / L).

    >>> printed_count("38", 10, 3), printed_count("38", 10, 3, outside="formula")
    (Fraction(0, 1), Fraction(10, 3))
    >>> printed_count("40", 10, 4, outside="formula")
    Fraction(135, 2)
    """
    L = check_int(L, "L")
    N = check_N(N, minimum=1)
    if eq == "36":
        return Fraction(N) if L == 2 else Fraction(0)
    if eq not in PRINTED_RANGES:
        raise InputError(f"eq must be one of 35, 36, 38, 39, 40; got {eq!r}")
    shape, lo = PRINTED_RANGES[eq]
    if L < sum(shape) or (outside == "zero" and L < lo):
        return Fraction(0)
    if outside not in ("zero", "formula"):
        raise InputError(f"outside must be 'zero' or 'formula', got {outside!r}")

    def ff(n: int, j: int) -> int:  # n!/(n-j)!, 0 when j > n
        return math.perm(n, j) if 0 <= j <= n else 0

    if eq == "35":
        return Fraction(L - 1, 2) * ff(N, L - 1)
    if eq == "38":
        return Fraction(math.factorial(L - 1), 6 * math.factorial(L - 3)) * ff(N, L - 2)
    if eq == "39":
        return Fraction(math.factorial(L - 1), 24 * math.factorial(L - 4)) * ff(N, L - 3)
    return Fraction(math.factorial(L - 1), 8 * math.factorial(L - 4)) * ff(N, L - 2)


def eq41_terms(N: int, k: int, *, printed: bool = False) -> dict[str, int]:
    """The five terms of eq. (41) at ``k`` distinct vertices, as counts of circuits:
    ``phi(k)``, ``phi^1(k+1)``, ``phi^{1,0}(k+2)``, ``phi^2(k+2)``, ``phi^{1,0,0}(k+3)``
    (the limits of :func:`class_count` apply).

    >>> eq41_terms(5, 1)
    {'phi': 5, 'phi^1': 5, 'phi^{1,0}': 5, 'phi^2': 0, 'phi^{1,0,0}': 5}
    >>> eq41_terms(5, 1, printed=True)
    {'phi': 5, 'phi^1': 5, 'phi^{1,0}': 0, 'phi^2': 0, 'phi^{1,0,0}': 0}
    """
    return {paper_label(s): class_count(N, s, k, printed=printed) for s in EQ41_SHAPES}


# --------------------------------------------------------------------------- spaces
_SPACE_RE = re.compile(r"^\s*excess\s*<=\s*(\d+)\s*$")


@dataclass(frozen=True)
class Space:
    """A sample space of circuits: a set of classes and a weighting.

    Attributes
    ----------
    name : str
        Canonical name, e.g. ``"eq41"``, ``"excess<=3"``, ``"eq41;distinct"``.
    base : str
        ``"simple"``, ``"eq41"``, ``"eq41-printed"`` or ``"excess"``.
    max_excess : int
        Largest excess of a class in the space.
    weighting : str
        ``"length"`` (a circuit weighs ``p**length``) or ``"distinct"`` (``p**k``).
    shapes : tuple
        The classes.
    printed : bool
        Boundary counts as printed in the paper (``eq41-printed``).
    """

    name: str
    base: str
    max_excess: int
    weighting: str
    shapes: tuple[tuple[int, ...], ...]
    printed: bool = False
    _cache: dict = field(default_factory=dict, compare=False, repr=False, hash=False)

    @property
    def levels(self) -> tuple[int, ...]:
        """Excess levels ``0..max_excess``."""
        return tuple(range(self.max_excess + 1))

    @property
    def max_parts(self) -> int:
        """Largest number of repeated vertices ``r`` of a class; ``Q*`` is the polynomial for
        ``k > max_parts``."""
        got = self._cache.get("max_parts")
        if got is None:
            got = self._cache["max_parts"] = max(len(s) for s in self.shapes)
        return got

    def ratio(self, shape: tuple[int, ...], k: int) -> Fraction:
        """``count(N, shape, k) / phi_N(k)`` in this space (0 for a class not in it)."""
        s = check_shape(shape)
        if s not in self.shapes:
            return Fraction(0)
        return class_ratio(s, k, printed=self.printed)

    def count(self, N: int, shape: tuple[int, ...], k: int) -> int:
        """Circuits of class ``shape`` with ``k`` distinct vertices counted by this space."""
        s = check_shape(shape)
        if s not in self.shapes:
            return 0
        return class_count(N, s, k, printed=self.printed)

    # ------------------------------------------------------------- integer tables
    @property
    def denominator(self) -> int:
        """The common denominator ``D`` of every ``R*_s(k)``."""
        if "D" not in self._cache:
            D = 1
            for s in self.shapes:
                D = math.lcm(D, _C(s) * _S(s))
                for k in range(1, len(s) + 1):
                    D = math.lcm(D, _ratio_unchecked(s, k, self.printed).denominator)
            self._cache["D"] = D
        return self._cache["D"]

    @property
    def coefficients(self) -> tuple[tuple[tuple[int, int], ...], ...]:
        """For each excess ``e``: pairs ``(r, D * sum_{s: e_s=e, r_s=r} 1/(C_s S_s))``, so that
        ``D * sum_s R_s(k) = rising(k, e) * sum_r coef_r * falling(k, r)`` (all terms >= 0)."""
        if "coef" not in self._cache:
            D = self.denominator
            acc: list[dict[int, Fraction]] = [{} for _ in self.levels]
            for s in self.shapes:
                e, r = shape_excess(s), len(s)
                acc[e][r] = acc[e].get(r, Fraction(0)) + Fraction(1, _C(s) * _S(s))
            out = []
            for d in acc:
                pairs = []
                for r in sorted(d):
                    v = d[r] * D
                    assert v.denominator == 1
                    pairs.append((r, int(v.numerator)))
                out.append(tuple(pairs))
            self._cache["coef"] = tuple(out)
        return self._cache["coef"]

    def _shapes_with_parts(self, r: int) -> tuple[tuple[int, ...], ...]:
        """The classes of the space with exactly ``r`` repeated vertices."""
        by = self._cache.get("by_parts")
        if by is None:
            by = {}
            for s in self.shapes:
                by.setdefault(len(s), []).append(s)
            by = self._cache["by_parts"] = {j: tuple(v) for j, v in by.items()}
        return by.get(r, ())

    def U(self, k: int) -> tuple[int, ...]:
        """``U_e(k) = D * sum_{s: e_s = e} R*_s(k)`` for ``e = 0..max_excess`` (exact ints).

        >>> parse_space("eq41").U(3)     # D = 24
        (24, 108, 360, 180)
        """
        cache = self._cache.setdefault("U", {})
        got = cache.get(k)
        if got is not None:
            return got
        D = self.denominator
        if k <= self.max_parts:
            # boundary region: the polynomial of the classes with r < k (the others are 0 or,
            # at r = k, their Burnside value; r > k contributes 0)
            vals = [Fraction(0)] * (self.max_excess + 1)
            for s in self._shapes_with_parts(k):
                vals[shape_excess(s)] += _ratio_unchecked(s, k, self.printed)
            out = []
            for e, (v, pairs) in enumerate(zip(vals, self.coefficients, strict=True)):
                v *= D
                assert v.denominator == 1
                out.append(int(v.numerator) + _rising(k, e) * sum(
                    c * _falling(k, r) for r, c in pairs if r < k))
            res = tuple(out)
        else:  # falling(k, r) and rising(k, e) as running products, each once
            fall = [1]
            for i in range(self.max_parts):
                fall.append(fall[-1] * (k - i))
            out, rise = [], 1
            for e, pairs in enumerate(self.coefficients):
                if e:
                    rise *= k + e - 1
                out.append(rise * sum(c * fall[r] for r, c in pairs))
            res = tuple(out)
        if len(cache) < 200_000:
            cache[k] = res
        return res

    def Qstar(self, k: int, p: Fraction | int) -> Fraction:
        """``W(k) / Phi_{N,p}(k)`` exactly (N-independent): ``sum_e w_e U_e(k) / D``."""
        U = self.U(k)
        if self.weighting == "distinct":
            return Fraction(sum(U), self.denominator)
        p = Fraction(p)
        a, b = p.numerator, p.denominator
        m = self.max_excess
        num = sum(u * a**e * b ** (m - e) for e, u in enumerate(U))
        return Fraction(num, b**m * self.denominator)

    def Qnum(self, k: int, a: int, b: int) -> int:
        """Integer ``b**m * D * Q*(k)`` for ``p = a/b`` (``D * Q*`` for distinct weighting)."""
        U = self.U(k)
        if self.weighting == "distinct":
            return sum(U)
        m = self.max_excess
        return sum(u * a**e * b ** (m - e) for e, u in enumerate(U))

    def Qden(self, b: int) -> int:
        """The denominator matching :meth:`Qnum`."""
        if self.weighting == "distinct":
            return self.denominator
        return b**self.max_excess * self.denominator


def _split_weighting(space: str, weighting: str | None) -> tuple[str, str]:
    if not isinstance(space, str):
        raise TypeError(f"space must be a str, got {type(space).__name__}")
    base, _, suffix = space.partition(";")
    suffix = suffix.strip()
    if suffix.startswith("weight="):
        suffix = suffix[len("weight="):]
    if suffix and suffix not in WEIGHTINGS:
        raise InputError(f"unknown weighting {suffix!r} in space {space!r}; use "
                         f"';length' or ';distinct'")
    if weighting is not None and weighting not in WEIGHTINGS:
        raise InputError(f"weighting must be 'length' or 'distinct', got {weighting!r}")
    if suffix and weighting and suffix != weighting:
        raise InputError(f"space {space!r} conflicts with weighting={weighting!r}")
    return base.strip(), (suffix or weighting or "length")


@lru_cache(maxsize=256)
def _parse(base: str, weighting: str) -> Space:
    suffix = "" if weighting == "length" else ";distinct"
    if base == "simple":
        return Space("simple" + suffix, "simple", 0, weighting, ((),))
    if base == "eq41":
        return Space("eq41" + suffix, "eq41", 3, weighting, EQ41_SHAPES)
    if base == "eq41-printed":
        return Space("eq41-printed" + suffix, "eq41-printed", 3, weighting, EQ41_SHAPES,
                     printed=True)
    mt = _SPACE_RE.match(base)
    if mt:
        if len(mt.group(1)) > 6:
            raise InputError(f"maximum excess m in {base[:40]!r} is beyond the documented work "
                             f"limit {MAX_EXCESS} (symhx.spaces._classes.MAX_EXCESS)")
        m = int(mt.group(1))
        return Space(f"excess<={m}" + suffix, "excess", m, weighting, shapes_up_to(m))
    raise InputError(
        f"unknown sample space {base!r}: use 'simple', 'eq41', 'eq41-printed' or 'excess<=m' "
        f"(m >= 0), optionally followed by ';length' (default) or ';distinct'"
    )


def parse_space(space: str | Space, weighting: str | None = None) -> Space:
    """Parse a space string: ``"simple"``, ``"eq41"``, ``"eq41-printed"`` or ``"excess<=m"``,
    optionally with the weighting suffix ``";length"`` (default: a circuit weighs
    ``p**length``) or ``";distinct"`` (``p**k``, k distinct vertices). ``weighting=`` may be
    given instead of the suffix.

    >>> parse_space("excess<=2;distinct").shapes, parse_space("eq41", "distinct").name
    (((), (2,), (3,), (2, 2)), 'eq41;distinct')
    """
    if isinstance(space, Space):
        if weighting is not None and weighting != space.weighting:
            return _parse(space.base if space.base != "excess" else
                          f"excess<={space.max_excess}", weighting)
        return space
    base, w = _split_weighting(space, weighting)
    return _parse(base, w)


def visits_of(shape: tuple[int, ...], k: int) -> tuple[int, ...]:
    """The visit pattern of class ``shape`` with ``k`` distinct vertices.

    >>> visits_of((2,), 3)
    (2, 1, 1)
    """
    s = check_shape(shape)
    k = check_int(k, "k")
    if k < len(s):
        raise InputError(f"k must be >= {len(s)} for the class shape={s}: it needs at least "
                         f"{len(s)} distinct vertices, got k={k}")
    return normalise_visits(s + (1,) * (k - len(s))) if k else ()
