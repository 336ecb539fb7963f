"""Twins: two implementations of one contract (C against Python engine, raw libmp against mpf,
float64 against mpmath) run on the same seeded random cases and compared.

A twin check is ``check_twins(first, second, cases, compare)``: ``cases`` is a list of argument
tuples (draw it from a seeded ``numpy.random.Generator`` so a failure names a reproducible case),
``compare(a, b, case)`` raises ``AssertionError`` on a disagreement (bit for bit, or within a
stated error).  All disagreements are collected and reported together, with their cases.

>>> check_twins(lambda x: x + x, lambda x: 2 * x, [(i,) for i in range(5)], assert_identical)
5
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

__all__ = ["assert_identical", "check_twins"]


def assert_identical(a: Any, b: Any, case: Any = None) -> None:
    """Bit-for-bit equality (``==`` on the results, which for mpf compares the exact values and
    for numpy arrays every element; NaN equals NaN)."""
    import numpy as np

    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        assert np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True), (a, b)
        return
    if a != a and b != b:  # NaN twins
        return
    assert a == b, (a, b)


def check_twins(first: Callable[..., Any], second: Callable[..., Any],
                cases: Sequence[tuple[Any, ...]],
                compare: Callable[[Any, Any, Any], None] = assert_identical,
                *, max_report: int = 5) -> int:
    """Run both twins on every case; raise ``AssertionError`` listing (up to ``max_report``)
    the cases where ``compare`` failed.  Returns the number of cases checked."""
    bad = []
    for case in cases:
        a, b = first(*case), second(*case)
        try:
            compare(a, b, case)
        except AssertionError as e:
            bad.append((case, e))
    if bad:
        lines = [f"  {c!r}: {e}" for c, e in bad[:max_report]]
        head = f"{len(bad)} of {len(cases)} twin cases disagree:\n"
        raise AssertionError(head + "\n".join(lines))
    return len(cases)
