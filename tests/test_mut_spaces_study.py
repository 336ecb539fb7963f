"""symhx.spaces.convergence_study against independent references (issue 16): the jump from
bisection roots of Burnside polynomials, E[X] from exact Fractions, exhaustive argmax scans."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx.spaces import MAX_EXCESS, convergence_study
from symhx.spaces.study import DEFAULT_PS, STUDY_N_LIMIT, ConvergenceRow
from tests.test_mut_spaces_critical import _poly, _roots, _Wx


def _exact_mean(N: int, base: str, w: str, p: Fraction) -> Fraction:
    W = [_Wx(_poly(N, base, w, k), p) for k in range(1, N + 1)]
    return sum(k * x for k, x in enumerate(W, 1)) / sum(W)


@pytest.mark.parametrize("w", ["length", "distinct"])
def test_rows_against_references(w):
    sympy = pytest.importorskip("sympy")
    N, dps = 12, 20
    ps = ["0.01", Fraction(1, 20), 0.03, sympy.Rational(3, 40), "1/3"]
    exact_ps = [Fraction(1, 100), Fraction(1, 20), Fraction(0.03), Fraction(3, 40),
                Fraction(1, 3)]
    rows = convergence_study(N, ms=[0, 1, 3], ps=ps, dps=dps, weighting=w)
    suffix = "" if w == "length" else ";distinct"
    assert [r.space for r in rows] == [f"{s}{suffix}" for s in
                                       ("excess<=0", "excess<=1", "excess<=3", "eq41",
                                        "eq41-printed")]
    for r, base in zip(rows, ("excess<=0", "excess<=1", "excess<=3", "eq41", "eq41-printed"),
                       strict=True):
        assert isinstance(r, ConvergenceRow)
        roots = _roots(N, base, w)
        with mpmath.workdps(60):
            pc = min(roots.values())
            assert abs(r.p_c - pc) <= mpmath.mpf(10) ** (1 - dps) * pc, r.space
        # the jump lands on the exact argmax just above p_c
        above = Fraction(mpmath.nstr(pc * (1 + mpmath.mpf(10) ** -15), 40))
        W = [_Wx(_poly(N, base, w, k), above) for k in range(1, N + 1)]
        assert r.k_after == W.index(max(W)) + 1
        assert list(r.means) == ps
        for p, fr in zip(ps, exact_ps, strict=True):
            ref = _exact_mean(N, base, w, fr)
            with mpmath.workdps(60):
                refm = mpmath.mpf(ref.numerator) / ref.denominator
                assert abs(r.means[p] - refm) <= mpmath.mpf(10) ** (1 - dps) * refm, (base, p)
        d = r.as_dict()
        assert d == {"space": r.space, "p_c": r.p_c, "k_after": r.k_after, "means": r.means}
        assert d["means"] is not r.means


def test_defaults_and_empty_ms():
    assert DEFAULT_PS == ("0.005", "0.01", "0.015", "0.04", "0.05")
    rows = convergence_study(10, ms=range(0), ps=["0.05"], extra=("eq41",), dps=15)
    assert [r.space for r in rows] == ["eq41"]
    rows = convergence_study(10, ms=np.array([2]), ps=("0.05",), extra=[], dps=15)
    assert [r.space for r in rows] == ["excess<=2"]


def test_refusals_name_the_limits():
    good = dict(N=20, ms=(0,), ps=("0.01",), dps=15, extra=())
    with pytest.raises(ValueError, match=f"N={STUDY_N_LIMIT + 1} is beyond .* N <= "
                                         f"{STUDY_N_LIMIT}"):
        convergence_study(**{**good, "N": STUDY_N_LIMIT + 1})
    with pytest.raises(ValueError, match=r"N=~10\*\*20 is beyond"):
        convergence_study(**{**good, "N": 10**20})
    with pytest.raises(ValueError, match=r"N=999999999999999 is beyond"):
        convergence_study(**{**good, "N": 10**15 - 1})
    for ms in (range(MAX_EXCESS + 5, 0, -1), range(0, MAX_EXCESS + 2)):
        with pytest.raises(ValueError, match=f"m <= {MAX_EXCESS}"):
            convergence_study(**{**good, "ms": ms})
    assert convergence_study(**{**good, "ms": range(MAX_EXCESS, MAX_EXCESS - 1, -1),
                                "N": 3})[0].space == f"excess<={MAX_EXCESS}"
    with pytest.raises(ValueError, match="at least one p"):
        convergence_study(**{**good, "ps": ()})
    with pytest.raises(TypeError, match="ms must be a list, tuple or range"):
        convergence_study(**{**good, "ms": np.zeros((2, 2), dtype=int)})
    with pytest.raises(TypeError, match="ps must be a list, tuple or range"):
        convergence_study(**{**good, "ps": "0.01"})
    with pytest.raises(TypeError, match="extra must be a list"):
        convergence_study(**{**good, "extra": "eq41"})


def test_defaults_are_N_100_and_dps_20():
    # the documented defaults: the same rows as with N=100, dps=20 spelled out, and not dps=21
    kw = dict(ms=[0], ps=["0.05"], extra=())
    rows = convergence_study(**kw)
    assert rows == convergence_study(100, dps=20, **kw)
    assert rows != convergence_study(101, dps=20, **kw)
    assert rows[0].p_c != convergence_study(100, dps=21, **kw)[0].p_c


def test_limit_is_inclusive_and_shown_exactly():
    rows = convergence_study(STUDY_N_LIMIT, ms=[0], ps=["0.05"], extra=(), dps=15)
    assert [r.space for r in rows] == ["excess<=0"] and 0 < rows[0].p_c < mpmath.mpf("0.05")
    good = dict(ms=(0,), ps=("0.01",), dps=15, extra=())
    with pytest.raises(ValueError, match=r"N=~10\*\*15 is beyond"):
        convergence_study(10**15, **good)


def test_refusals_name_the_argument():
    import array

    good = dict(N=10, ms=(0,), ps=("0.01",), dps=15, extra=())
    with pytest.raises(TypeError, match="ms must be a list, tuple or range"):
        convergence_study(**{**good, "ms": array.array("i", [0])})  # tolist() but no ndim
    for kw, msg in [({"weighting": "x"}, "^weighting must be one of"),
                    ({"ms": [-1]}, "^each maximum excess m of ms must be >= 0"),
                    ({"ms": [MAX_EXCESS + 1]},
                     f"^each maximum excess m of ms must be <= {MAX_EXCESS}"),
                    ({"ps": ["0.01", "-1"]}, "^each p of ps must be > 0"),
                    ({"extra": ["x"]}, "^each extra space must be one of"),
                    ({"ps": []}, r"^ps must hold at least one p value \(decimal strings\), "
                                 "got none$")]:
        with pytest.raises(ValueError, match=msg):
            convergence_study(**{**good, **kw})


def test_dps_60_reaches_the_critical_point_and_means():
    # dps is passed on to the critical-point search and to the distributions (60 is above
    # their default 50)
    sympy = pytest.importorskip("sympy")
    N, dps, base, w = 12, 60, "excess<=1", "length"
    p_irr = sympy.sqrt(2) / 40
    with mpmath.workdps(100):
        p_fr = Fraction(mpmath.nstr(mpmath.sqrt(2) / 40, 90))
    rows = convergence_study(N, ms=[1], ps=["0.05", p_irr], extra=(), dps=dps)
    r, = rows
    with mpmath.workdps(70):  # the reference roots have 62 digits
        pc = min(_roots(N, base, w).values())
        assert abs(r.p_c - pc) <= mpmath.mpf(10) ** (1 - dps) * pc
        for p, fr in (("0.05", Fraction(1, 20)), (p_irr, p_fr)):
            ref = _exact_mean(N, base, w, fr)
            refm = mpmath.mpf(ref.numerator) / ref.denominator
            assert abs(r.means[p] - refm) <= mpmath.mpf(10) ** (1 - dps) * refm, p
