"""Convergence of the truncated sample spaces (beyond the paper): how E[X] and the jump of the
mode move as the maximum excess ``m`` of ``"excess<=m"`` grows, compared with eq. (41).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import mpmath

from symhx._mpctx import export, mp
from symhx._numeric import mp_value
from symhx.spaces import _classes  # MAX_EXCESS, read when called
from symhx.spaces._classes import WEIGHTINGS
from symhx.spaces._critical import critical_point
from symhx.spaces._dist import distribution
from symhx.validation import InputError, check_choice, check_dps, check_int, check_N, check_p

__all__ = ["DEFAULT_PS", "STUDY_N_LIMIT", "ConvergenceRow", "convergence_study"]

#: largest N of :func:`convergence_study` (a documented work limit: it runs one certified
#: critical-point search per space, about a second each at N = 10**6)
STUDY_N_LIMIT = 100_000

#: the p values of the paper's figures 11 and 12 (as exact decimals)
DEFAULT_PS: tuple[str, ...] = ("0.005", "0.01", "0.015", "0.04", "0.05")


def _sequence(x: Any, name: str) -> tuple[Any, ...]:
    """The items of a list / tuple / range / 1-d array (a string is not a sequence of values)."""
    if hasattr(x, "ndim") and hasattr(x, "tolist"):  # a numpy array
        x = x.tolist() if x.ndim == 1 else None
    if not isinstance(x, (list, tuple, range)):
        raise TypeError(f"{name} must be a list, tuple or range, got {x!r:.60}")
    return tuple(x)


@dataclass(frozen=True)
class ConvergenceRow:
    """One space of the study: its jump ``p_c -> k_after`` and ``E[X]`` at each ``p``."""

    space: str
    p_c: mpmath.mpf
    k_after: int
    means: dict[str, mpmath.mpf]

    def as_dict(self) -> dict[str, Any]:
        return {"space": self.space, "p_c": self.p_c, "k_after": self.k_after,
                "means": dict(self.means)}


def _mp_input(p: Any, fr: Fraction | None, dps: int) -> Any:
    """An exact ``p`` rounded to ``dps + 10`` digits (an mpf sends the distribution down the
    mpmath path); a sympy irrational as it is (the distribution evaluates it rigorously at its
    own working precision)."""
    if fr is None:
        return p
    ctx = mp()
    with ctx.workdps(dps + 10):
        return export(mp_value(p, fr))


def convergence_study(N: int = 100, ms: Iterable[int] = range(0, 7), *,
                      ps: Iterable[str] = DEFAULT_PS, dps: int = 20,
                      extra: Iterable[str] = ("eq41", "eq41-printed"),
                      weighting: str = "length") -> list[ConvergenceRow]:
    """``E[X]`` at each ``p`` and the jump ``p_c`` for ``"excess<=m"``, ``m`` in ``ms``, plus the
    ``extra`` spaces (eq. 41 corrected and as printed).

    ``p`` values are decimal strings (or any exact number or float), given to the mpmath path at
    ``dps + 10`` digits; ``E[X]`` is returned to ``dps`` digits. With
    ``weighting="length"`` the untruncated space converges only while ``p k < 1`` for the
    relevant k (circuits of length L on k vertices grow like ``k**L``), so the columns at larger
    ``p`` keep moving with ``m``; see the book chapter "Higher-order circuits".

    >>> rows = convergence_study(20, ms=[0, 1], ps=["0.05"], extra=())
    >>> [r.space for r in rows], [r.k_after for r in rows]
    (['excess<=0', 'excess<=1'], [7, 7])
    """
    N = check_N(N)
    if N > STUDY_N_LIMIT:
        shown = N if N < 10**15 else f"~10**{len(str(N)) - 1}"
        raise InputError(f"N={shown} is beyond the documented work limit N <= {STUDY_N_LIMIT} "
                         f"of convergence_study (symhx.spaces.study.STUDY_N_LIMIT: one "
                         f"critical-point search per space); raise that constant to allow it")
    dps = check_dps(dps)
    weighting = check_choice(weighting, "weighting", WEIGHTINGS)
    if isinstance(ms, range) and ms \
            and max(ms[0], ms[-1]) > _classes.MAX_EXCESS:  # refuse a huge range before listing
        raise InputError(f"ms={ms!r:.60} goes beyond the documented work limit m <= "
                         f"{_classes.MAX_EXCESS} (symhx.spaces._classes.MAX_EXCESS)")
    ms = tuple(check_int(m, "each maximum excess m of ms", minimum=0,
                         maximum=_classes.MAX_EXCESS, limit="symhx.spaces._classes.MAX_EXCESS")
               for m in _sequence(ms, "ms"))
    ps = tuple(_sequence(ps, "ps"))
    if not ps:
        raise InputError("ps must hold at least one p value (decimal strings), got none")
    exact = [check_p(p, "each p of ps")[0] for p in ps]
    extra = tuple(check_choice(s, "each extra space", ("eq41", "eq41-printed"))
                  for s in _sequence(extra, "extra"))
    rows = []
    suffix = "" if weighting == "length" else ";distinct"
    spaces = [f"excess<={m}{suffix}" for m in ms] + [f"{s}{suffix}" for s in extra]
    for sp in spaces:
        cp = critical_point(N, space=sp, dps=dps)
        means = {p: distribution(N, _mp_input(p, fr, dps), space=sp, dps=dps).mean()
                 for p, fr in zip(ps, exact, strict=True)}
        rows.append(ConvergenceRow(sp, cp.p, cp.k_after, means))
    return rows
