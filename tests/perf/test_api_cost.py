"""Cost of :mod:`symhx.api`'s broadcasting: one distribution per distinct ``p``."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest

import symhx
from symhx import api
from tests.reference.distribution import ExactTable


def test_one_distribution_per_distinct_p(monkeypatch: pytest.MonkeyPatch) -> None:
    """The per-p cache: an array with repeated p builds one distribution per distinct value
    (and type)."""
    built: list = []
    real = api._build

    def counting(N, p, sp, dps):  # type: ignore[no-untyped-def]
        built.append(p)
        return real(N, p, sp, dps)

    monkeypatch.setattr(api, "_build", counting)
    got = symhx.mean(20, [0.1, 0.1, "0.1", 0.1], dps=None)
    assert len(built) == 2 and got[0] == got[1] == got[3]
    built.clear()
    got = symhx.cdf(20, [[0.1], [0.1], [0.2]], [1, 2, 3], dps=None)
    assert got.shape == (3, 3) and len(built) == 2
    t = ExactTable.simple(20, Fraction(0.2))
    assert math.isclose(got[2, 1], float(t.cdf(2)), rel_tol=1e-12)
