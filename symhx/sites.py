"""Impact sites with their own probabilities: the value object :class:`SiteClasses`.

Section 4 of the paper gives every edge of the graph of impacts its own probability ``p_ij`` and
then sets them all equal "for simplicity".  symhx takes the next step the paper calls "an obvious
area for further work": every *site* (vertex) ``v = 1..N`` has its own impact probability
``p_v``, and a circuit weighs the product over its impacts of ``p_(site)`` (a site visited ``m``
times contributes ``p_v**m`` under the default length weighting, ``p_v`` under ``;distinct``).
An edge weight that factors, ``p_ij = a_i b_j`` (rank one), is of this form too: along a closed
walk every visit of a vertex enters it once and leaves it once, so the walk weighs
``prod_visits a_v b_v``, the site weight ``p_v = a_v b_v``.

Sites come in a few *classes* of equal probability (a row of pipes: 2 wall sites and ``n - 1``
pipe-pipe sites).  ``SiteClasses(sizes, probabilities)`` holds them: positive int sizes summing to
``N``, one probability per class, converted by the same layer as a scalar ``p``
(:func:`symhx.validation.check_p`): ints, ``Fraction``, ``Decimal``, sympy ``Rational`` and
decimal strings are exact; floats and ``mpf`` are taken at their exact binary value.  One class
is the paper's scalar ``p``, and every symhx function gives it bit-identical results.

>>> wall_and_pipes = SiteClasses((2, 99), ("0.01", "0.02"), names=("wall", "pipe"))
>>> wall_and_pipes
SiteClasses(sizes=(2, 99), probabilities=('0.01', '0.02'), names=('wall', 'pipe'))
>>> wall_and_pipes.N, wall_and_pipes.values
(101, (Fraction(1, 100), Fraction(1, 50)))
>>> SiteClasses.from_sites(["0.5", "0.25", "0.5"])
SiteClasses(sizes=(2, 1), probabilities=('0.5', '0.25'))
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

from symhx.validation import InputError, check_int, check_p, is_exact_type, short_value

__all__ = ["MAX_SITE_SEQUENCE", "SiteClasses", "as_site_classes", "is_site_input", "show_int"]

#: a per-site probability sequence longer than this is refused (it is grouped into classes one
#: entry at a time; give :class:`SiteClasses` directly for larger N)
MAX_SITE_SEQUENCE = 10_000_000


def show_int(n: int) -> str:
    """A readable int for reprs and messages (``10**100`` for exact powers of ten, no str() of
    huge ints).

    >>> show_int(101), show_int(10**100), show_int(10**100 - 2)
    ('101', '10**100', '~1.0e+100')
    """
    if n < 10**30:
        return str(n)
    e = int((n.bit_length() - 1) * 0.30102999566398120)
    if n >= 10 ** (e + 1):
        e += 1
    if n == 10**e:
        return f"10**{e}"
    lead = mpmath.libmp.to_str(mpmath.libmp.from_int(n, 60, "n"), 6)  # no mpmath context
    return f"~{lead}"


def _dyadic_mpf(fr: Fraction) -> Any:
    """An mpf holding the exact value of a dyadic rational (denominator a power of two), or the
    value rounded to 256 bits otherwise (only :meth:`SiteClasses.scaled` of an exact factor and
    a binary probability lands there)."""
    num, den = fr.numerator, fr.denominator  # num > 0: probabilities are positive
    if den & (den - 1) == 0:
        raw = mpmath.libmp.from_man_exp(num, -(den.bit_length() - 1), num.bit_length(), "n")
        return mpmath.mp.make_mpf(raw)
    raw = mpmath.libmp.from_rational(num, den, 256, "n")
    return mpmath.mp.make_mpf(raw)


class SiteClasses:
    """Classes of impact sites with one probability per class (a frozen, hashable value).

    Parameters
    ----------
    sizes : sequence of int
        Number of sites of each class, each ``>= 1``; ``N = sum(sizes)``.
    probabilities : sequence of numbers
        One impact probability ``> 0`` per class (``> 1`` is accepted, as for a scalar ``p``):
        ints, ``Fraction``, ``Decimal``, sympy ``Rational`` and decimal strings are exact,
        floats and ``mpf`` are taken at their exact binary value.
    names : sequence of str, optional
        Distinct names of the classes (``("wall", "pipe")``).

    Attributes
    ----------
    sizes, probabilities, names : tuple
        As given (the probabilities as the original objects, so one class behaves exactly as
        the scalar ``p`` it holds).
    values : tuple of Fraction
        The exact value of each probability.
    exact : bool
        Every probability is of an exact type (results are Fractions where rational).
    N : int
        The number of sites.

    Raises
    ------
    TypeError
        For a wrong kind of object (a str for ``sizes``, a bool, a sympy irrational).
    ValueError
        For an empty or mismatched ``probabilities``, a size below 1, a probability ``<= 0``,
        repeated or empty names.

    Examples
    --------
    >>> s = SiteClasses((2, 99), (0.01, 0.02))
    >>> s.N, s.exact, len(s)
    (101, False, 2)
    >>> s.scaled(2).values == (2 * Fraction(0.01), 2 * Fraction(0.02))    # exact products
    True
    >>> SiteClasses([3], ["1/4"]) == SiteClasses((3,), (Fraction(1, 4),))
    True
    """

    __slots__ = ("_exact_flags", "_key", "exact", "names", "probabilities", "sizes", "values")

    sizes: tuple[int, ...]
    probabilities: tuple[Any, ...]
    names: tuple[str, ...] | None
    values: tuple[Fraction, ...]
    exact: bool
    _exact_flags: tuple[bool, ...]
    _key: tuple[Any, ...]

    def __init__(self, sizes: Sequence[Any], probabilities: Sequence[Any],
                 names: Sequence[str] | None = None) -> None:
        sz = self._sequence(sizes, "sizes", "a sequence of positive ints such as (2, 99)")
        pr = self._sequence(probabilities, "probabilities",
                            "a sequence of one probability per class such as (0.01, '0.02')")
        if not sz:
            raise InputError("sizes must hold at least one class, got an empty sequence")
        if len(pr) != len(sz):
            raise InputError(f"probabilities must hold one value per class: sizes has {len(sz)} "
                             f"classes, probabilities has {len(pr)} values")
        sizes_t = tuple(check_int(n, f"sizes[{i}]", minimum=1) for i, n in enumerate(sz))
        values = []
        for i, p in enumerate(pr):
            fr, _ = check_p(p, f"probabilities[{i}]")
            if fr is None:
                raise TypeError(f"probabilities[{i}] must be a rational, float or mpf number, "
                                f"got the irrational {p!r} (a sympy irrational is accepted as "
                                f"a scalar p only)")
            values.append(fr)
        names_t: tuple[str, ...] | None = None
        if names is not None:
            nm = self._sequence(names, "names", "a sequence of one str per class")
            if len(nm) != len(sz):
                raise InputError(f"names must hold one str per class: sizes has {len(sz)} "
                                 f"classes, names has {len(nm)}")
            for i, x in enumerate(nm):
                if not isinstance(x, str):
                    raise TypeError(f"names[{i}] must be a str, got {type(x).__name__} {x!r}")
                if not x.strip():
                    raise InputError(f"names[{i}] must be a non-empty str, got {x!r}")
            if len(set(nm)) != len(nm):
                raise InputError(f"names must be distinct, got {tuple(nm)!r}")
            names_t = tuple(nm)
        flags = tuple(is_exact_type(p) for p in pr)
        object.__setattr__(self, "sizes", sizes_t)
        object.__setattr__(self, "probabilities", tuple(pr))
        object.__setattr__(self, "names", names_t)
        object.__setattr__(self, "values", tuple(values))
        object.__setattr__(self, "_exact_flags", flags)
        object.__setattr__(self, "exact", all(flags))
        object.__setattr__(self, "_key", (sizes_t, tuple(values), flags, names_t))

    @staticmethod
    def _sequence(x: Any, name: str, allowed: str) -> list[Any]:
        if isinstance(x, (str, bytes)) or not hasattr(x, "__iter__") or isinstance(x, dict):
            raise TypeError(f"{name} must be {allowed}, got {type(x).__name__} {x!r}"[:300])
        if isinstance(x, np.ndarray) and x.ndim != 1:
            raise InputError(f"{name} must be one-dimensional, got an array of shape {x.shape}")
        return list(x)

    # ------------------------------------------------------------------ value semantics
    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("SiteClasses is immutable")

    def __delattr__(self, name: str) -> None:
        raise AttributeError("SiteClasses is immutable")

    def __eq__(self, other: object) -> bool:
        """Equal when the sizes, the exact values, their kinds (exact or binary) and the names
        agree (``Fraction(1, 2)`` and the float ``0.5`` differ: one gives Fraction results)."""
        if not isinstance(other, SiteClasses):
            return NotImplemented
        return self._key == other._key

    def __hash__(self) -> int:
        return hash(self._key)

    def __len__(self) -> int:
        """The number of classes."""
        return len(self.sizes)

    def __iter__(self) -> Iterator[tuple[int, Any]]:
        """``(size, probability)`` of each class."""
        return iter(zip(self.sizes, self.probabilities, strict=True))

    def __repr__(self) -> str:
        sizes = ", ".join(show_int(n) for n in self.sizes)
        sizes = f"({sizes}{',' if len(self.sizes) == 1 else ''})"
        probs = ", ".join(self._show_p(p) for p in self.probabilities)
        probs = f"({probs}{',' if len(self.probabilities) == 1 else ''})"
        names = f", names={self.names!r}" if self.names is not None else ""
        return f"SiteClasses(sizes={sizes}, probabilities={probs}{names})"

    @staticmethod
    def _show_p(p: Any) -> str:
        r = repr(p)
        return r if len(r) <= 60 else r[:57] + "..."

    def __reduce__(self) -> tuple[Any, ...]:
        return SiteClasses, (self.sizes, self.probabilities, self.names)

    # ------------------------------------------------------------------ derived values
    @property
    def N(self) -> int:
        """The number of sites, ``sum(sizes)``."""
        return sum(self.sizes)

    def scaled(self, t: Any) -> SiteClasses:
        """The classes with every probability multiplied by ``t > 0`` (read like ``p``):
        Fractions when ``t`` and the probabilities are exact, else ``mpf`` holding the exact
        product (rounded to 256 bits only when an exact non-dyadic ``t`` meets a binary
        probability).

        >>> SiteClasses((1, 2), ("1/4", "1/2")).scaled("2/3").probabilities
        (Fraction(1, 6), Fraction(1, 3))
        """
        fr, _ = check_p(t, "t")
        if fr is None:
            raise TypeError(f"t must be a rational, float or mpf number, got the irrational "
                            f"{t!r}")
        exact_t = is_exact_type(t)
        probs = []
        for v, flag in zip(self.values, self._exact_flags, strict=True):
            prod = fr * v
            probs.append(prod if (flag and exact_t) else _dyadic_mpf(prod))
        return SiteClasses(self.sizes, probs, self.names)

    @classmethod
    def from_sites(cls, probabilities: Sequence[Any], name: str = "sites") -> SiteClasses:
        """Group a sequence of one probability per site into classes of equal value (in order
        of first appearance); a class is exact only when all its entries are.

        >>> SiteClasses.from_sites([0.25, "1/4", 0.5]).sizes
        (2, 1)
        """
        size = len(probabilities) if hasattr(probabilities, "__len__") else None
        if size is not None and size > MAX_SITE_SEQUENCE:
            raise InputError(f"{name} has {size} entries, more than "
                             f"symhx.sites.MAX_SITE_SEQUENCE = {MAX_SITE_SEQUENCE}; give "
                             f"SiteClasses(sizes, probabilities) instead")
        seq = cls._sequence(probabilities, name, "a sequence of one probability per site")
        if not seq:
            raise InputError(f"{name} must hold at least one probability, got an empty sequence")
        order: dict[Fraction, list[Any]] = {}
        for i, p in enumerate(seq):
            fr, _ = check_p(p, f"{name}[{i}]")
            if fr is None:
                raise TypeError(f"{name}[{i}] must be a rational, float or mpf number, got the "
                                f"irrational {p!r}")
            slot = order.get(fr)
            if slot is None:
                order[fr] = [1, p]
            else:
                slot[0] += 1
                if is_exact_type(slot[1]) and not is_exact_type(p):
                    slot[1] = p  # one binary entry makes the class binary
        return cls([c for c, _ in order.values()], [p for _, p in order.values()])

    @classmethod
    def parse(cls, text: str, name: str = "--sites", N: int | None = None) -> SiteClasses:
        """Classes from the command-line form ``"2:0.01,99:0.02"`` (``size:probability``, comma
        separated; ``"wall=2:0.01,pipe=99:0.02"`` names them).  Probabilities are read as
        exact decimal strings, as ``p`` is on the command line.  Given ``N``, one size may be
        ``rest``: ``N`` minus the other sizes (``2:0.01,rest:0.02`` is a row at any ``N``).

        >>> SiteClasses.parse("wall=2:0.01,pipe=99:1/50")
        SiteClasses(sizes=(2, 99), probabilities=('0.01', '1/50'), names=('wall', 'pipe'))
        >>> SiteClasses.parse("2:1/2,rest:1", N=10**100).sizes[1] == 10**100 - 2
        True
        """
        if not isinstance(text, str):
            raise TypeError(f"{name} must be a str such as '2:0.01,99:0.02', got "
                            f"{type(text).__name__} {text!r}")
        sizes: list[int | None] = []
        probs: list[str] = []
        names: list[str] = []
        items = [x.strip() for x in text.split(",")]
        for i, item in enumerate(items):
            label, eq, rest = item.rpartition("=") if "=" in item else ("", "", item)
            size, colon, prob = rest.partition(":")
            if not colon or not size.strip() or not prob.strip() or (eq and not label.strip()):
                raise InputError(f"{name} must be size:probability pairs separated by commas, "
                                 f"optionally named (name=size:probability), such as "
                                 f"'2:0.01,99:0.02'; item {i} is {item!r}")
            if size.strip() == "rest":
                sizes.append(None)
            else:
                sizes.append(check_int(size.strip(), f"{name} item {i} size", minimum=1))
            check_p(prob.strip(), f"{name} item {i} probability")
            probs.append(prob.strip())
            names.append(label.strip())
        if any(names) and not all(names):
            raise InputError(f"{name} must name every class or none, got {text!r}")
        if None in sizes:
            if sizes.count(None) > 1 or N is None:
                raise InputError(f"{name} may hold one size 'rest' (N minus the other sizes) "
                                 f"where N is known, got {text!r}")
            left = N - sum(n for n in sizes if n is not None)
            if left < 1:
                raise InputError(f"{name}: the size 'rest' would be {show_int(left)} (N = "
                                 f"{show_int(N)} minus the other sizes); it must be >= 1")
            sizes = [left if n is None else n for n in sizes]
        return cls(sizes, probs, names if all(names) else None)

    def merged(self) -> SiteClasses:
        """Classes of equal exact value merged (names dropped when anything merges); a merged
        class is exact only when all its parts are.

        >>> SiteClasses((2, 3), ("1/2", 0.5)).merged()
        SiteClasses(sizes=(5,), probabilities=(0.5,))
        """
        groups: dict[Fraction, list[Any]] = {}
        for n, p, v, flag in zip(self.sizes, self.probabilities, self.values,
                                 self._exact_flags, strict=True):
            g = groups.get(v)
            if g is None:
                groups[v] = [n, p, flag]
            else:
                g[0] += n
                if g[2] and not flag:
                    g[1], g[2] = p, False
        if len(groups) == len(self.sizes):
            return self
        return SiteClasses([g[0] for g in groups.values()], [g[1] for g in groups.values()])

    def value_show(self, i: int) -> str:
        """Class ``i``'s probability in 5 significant digits (for messages)."""
        return short_value(self.values[i])


def is_site_input(x: Any) -> bool:
    """Whether ``x`` is read as site probabilities (a :class:`SiteClasses`, or a sequence of
    per-site values) rather than a scalar ``p``."""
    if isinstance(x, SiteClasses):
        return True
    if isinstance(x, np.ndarray):
        return x.ndim == 1
    return isinstance(x, (list, tuple))


def as_site_classes(x: Any, N: int, name: str = "p") -> SiteClasses:
    """``x`` (a :class:`SiteClasses` or a sequence of ``N`` per-site probabilities) as
    :class:`SiteClasses` with ``N`` sites, else a clear error.

    >>> as_site_classes([0.5, 0.5, 0.25], 3).sizes
    (2, 1)
    >>> as_site_classes(SiteClasses((2,), (1,)), 3)
    Traceback (most recent call last):
        ...
    symhx.validation.InputError: p has sizes summing to N = 2, but N = 3: ...
    """
    if isinstance(x, SiteClasses):
        if x.N != N:
            raise InputError(f"{name} has sizes summing to N = {show_int(x.N)}, but "
                             f"N = {show_int(N)}: the class sizes must add up to N")
        return x
    if not is_site_input(x):
        raise TypeError(f"{name} must be a symhx.SiteClasses or a sequence of N per-site "
                        f"probabilities, got {type(x).__name__} {x!r}"[:300])
    n = len(x)
    if n != N:
        raise InputError(f"{name} must hold one probability per site (N = {show_int(N)}), got "
                         f"a sequence of {n}; use symhx.SiteClasses(sizes, probabilities) for "
                         f"classes")
    return SiteClasses.from_sites(x, name)
