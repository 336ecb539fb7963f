"""Symbolic derivations of the paper with sympy (sections 3-6 and 8), each verifying itself.

This is the only part of symhx that imports sympy (``import symhx`` does not import it).

>>> from symhx.symbolic import derivations
>>> d = derivations()["16"]
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
"""

from __future__ import annotations

from functools import lru_cache

from symhx.symbolic._core import Check, CheckResult, Derivation, N, k, p, sym_equal

__all__ = [
    "Check",
    "CheckResult",
    "Derivation",
    "N",
    "derivation",
    "derivations",
    "k",
    "labels",
    "p",
    "sym_equal",
    "verify_all",
]


def _label_key(label: str) -> tuple[int, str]:
    head = label.split("-")[0]
    return (int(head), label) if head.isdigit() else (1000, label)


@lru_cache(maxsize=1)
def _registry() -> dict[str, Derivation]:
    from symhx.symbolic import asymptotic, higher, jump, simple

    out: dict[str, Derivation] = {}
    for mod in (simple, jump, higher, asymptotic):
        for d in mod.build():
            if d.label in out:  # pragma: no cover - programming error
                raise RuntimeError(f"duplicate derivation label {d.label!r}")
            out[d.label] = d
    return dict(sorted(out.items(), key=lambda kv: _label_key(kv[0])))


def derivations() -> dict[str, Derivation]:
    """All derivations, keyed by the paper's equation label (a string) or a descriptive key.

    Returns
    -------
    dict of str to Derivation
        In equation order; built once (a few seconds) and cached. Each value has ``.result``,
        ``.verify()``, ``.latex()``, ``.description``, ``.verified_by``.

    >>> sorted(derivations())[:3]
    ['10', '11', '12']
    >>> derivations()["15"].result
    Eq(Derivative(f_{N,p}(k), p), k*(N - k))
    """
    return dict(_registry())


def derivation(label: str) -> Derivation:
    """One derivation by label (``"16"``, ``"crossing"``, ...).

    >>> derivation("13").result
    Eq(f_{N,p}(N), -N - 1)
    """
    reg = _registry()
    try:
        return reg[str(label)]
    except KeyError:
        raise ValueError(f"unknown derivation {label!r}; known: {', '.join(reg)}") from None


def labels() -> list[str]:
    """All labels, in equation order.

    >>> labels()[:5]
    ['4', '5', '6', '7', '8']
    """
    return list(_registry())


def verify_all() -> dict[str, bool]:
    """Run every derivation's checks: ``{label: passed}`` (about 10 s).

    """
    return {lab: d.verify() for lab, d in _registry().items()}
