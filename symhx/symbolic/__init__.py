"""Symbolic derivations of the paper with sympy (sections 3-6 and 8), each verifying itself.

This is the only part of symhx that imports sympy (``import symhx`` does not import it).

>>> from symhx.symbolic import derivation
>>> d = derivation("16")
>>> d.result
Eq(p_d, (N + 2*sqrt(N + 1) + 2)/N**2)
>>> d.verify()
True
>>> d.latex()
'p_{d} = \\\\frac{N + 2 \\\\sqrt{N + 1} + 2}{N^{2}}'

Keys are the paper's equation labels ``"4"`` ... ``"16"``, ``"29"`` ... ``"41"`` plus new
results: ``"16-spurious"``, ``"16-k"``, ``"16-series"``, ``"crossing"``, ``"crossing-ratio"``,
``"crossing-relaxed"``, ``"41-weighted"``, ``"41-truncation"``, ``"log-Nc-expansion"``,
``"pc-lambert"``. See :class:`Derivation` for the attributes of each value and
:attr:`Derivation.verified_by` for how it is checked (``symbolic`` for symbolic ``N``, ``p``,
``k``; ``exact`` over a stated integer range; ``numeric`` at high precision, only for the
Lambert-W and series results).

Derivations are built on demand: :func:`derivation` builds one label (and the intermediate
results it depends on) the first time it is asked for and caches it; :func:`derivations` is a
read-only mapping that does the same per key, so ``derivations()["16"]`` costs a fraction of a
second where building all of them takes a few seconds. :func:`labels` and the descriptions
(:func:`catalogue`) need no building at all.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator, Mapping

from symhx.symbolic import asymptotic, higher, jump, simple
from symhx.symbolic._core import (
    SPECS,
    Check,
    CheckResult,
    Derivation,
    N,
    Step,
    k,
    latex,
    p,
    sym_equal,
)

__all__ = [
    "Check",
    "CheckResult",
    "Derivation",
    "Derivations",
    "N",
    "Step",
    "catalogue",
    "derivation",
    "derivations",
    "k",
    "labels",
    "latex",
    "p",
    "sym_equal",
    "verify_all",
]

# the modules above register their derivations when imported
_MODULES = (simple, jump, higher, asymptotic)
_BUILT: dict[str, Derivation] = {}
_LOCK = threading.RLock()


def _label_key(label: str) -> tuple[int, str]:
    head = label.split("-")[0]
    return (int(head), label) if head.isdigit() else (1000, label)


def labels() -> list[str]:
    """All labels, in equation order (nothing is built).

    >>> labels()[:5]
    ['4', '5', '6', '7', '8']
    """
    return sorted(SPECS, key=_label_key)


def catalogue() -> dict[str, tuple[int, str, str]]:
    """``{label: (section, plain description, Markdown description)}`` in equation order, without
    building any derivation (what ``symhx derive --list`` prints).

    >>> catalogue()["16"][:2]
    (6, 'p_d: the discriminant of f vanishes, double root of f inside 0 < k < N')
    """
    return {lab: (SPECS[lab].section, SPECS[lab].description, SPECS[lab].text)
            for lab in labels()}


def derivation(label: str) -> Derivation:
    """One derivation by label (``"16"``, ``"crossing"``, ...), built on first use and cached.

    Parameters
    ----------
    label : str
        A key of :func:`labels` (an int such as ``16`` is accepted and read as ``"16"``).

    Returns
    -------
    Derivation

    Raises
    ------
    ValueError
        For an unknown label (the message lists the known ones).

    >>> derivation("13").result
    Eq(f_{N,p}(N), -N - 1)
    """
    key = str(label)
    try:
        return _BUILT[key]
    except KeyError:
        pass
    if key not in SPECS:
        raise ValueError(f"unknown derivation {label!r}; known: {', '.join(labels())}")
    with _LOCK:  # sympy's caches are not built for concurrent first use
        if key not in _BUILT:
            _BUILT[key] = SPECS[key].make()
        return _BUILT[key]


class Derivations(Mapping[str, Derivation]):
    """Read-only mapping ``label -> Derivation`` that builds each value when it is first read.

    Iterating over it, ``len`` and ``in`` build nothing; ``values()`` and ``items()`` build every
    derivation (a few seconds the first time).
    """

    def __getitem__(self, label: str) -> Derivation:
        if str(label) not in SPECS:
            raise KeyError(label)
        return derivation(label)

    def __iter__(self) -> Iterator[str]:
        return iter(labels())

    def __len__(self) -> int:
        return len(SPECS)

    def __contains__(self, label: object) -> bool:
        return isinstance(label, str) and label in SPECS

    def __repr__(self) -> str:
        built = sum(lab in _BUILT for lab in SPECS)
        return f"<Derivations: {len(SPECS)} labels, {built} built>"


def derivations() -> Derivations:
    """All derivations, keyed by the paper's equation label (a string) or a descriptive key.

    Returns
    -------
    Derivations
        A read-only mapping in equation order whose values are built on first access (only the
        derivation asked for and the intermediate results it depends on) and cached. Each value
        has ``.result``, ``.verify()``, ``.latex()``, ``.description``, ``.text``,
        ``.verified_by``.

    >>> D = derivations()
    >>> list(D)[:3]
    ['4', '5', '6']
    >>> D["15"].result
    Eq(Derivative(f_{N,p}(k), p), k*(N - k))
    """
    return Derivations()


def verify_all() -> dict[str, bool]:
    """Build every derivation and run its checks: ``{label: passed}`` (about 10 s)."""
    return {lab: derivation(lab).verify() for lab in labels()}
