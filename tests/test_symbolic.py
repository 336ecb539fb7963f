"""The symbolic derivations: every one verifies, every tampered one fails, and lambdified results
agree with the numeric modules (exact integers / rationals or the exact critical-point solver)."""

from __future__ import annotations

import subprocess
import sys
from fractions import Fraction

import mpmath
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symhx import circuits
from symhx.symbolic import N, derivation, derivations, k, labels, p

PAPER_LABELS = [str(i) for i in range(4, 17)] + [str(i) for i in range(29, 42)]


def test_registry_has_every_paper_equation():
    reg = derivations()
    for lab in PAPER_LABELS:
        assert lab in reg, lab
    for d in reg.values():
        assert d.description and "\n" not in d.description
        assert isinstance(d.latex(), str) and d.latex()
        assert d.checks, d.label
        assert set(d.verification_kinds) <= {"symbolic", "exact", "numeric"}


@pytest.mark.parametrize("label", labels())
def test_every_derivation_verifies(label):
    d = derivation(label)
    rep = d.report()
    assert all(r.passed for r in rep), [r for r in rep if not r.passed]
    assert d.verify() is True


def _tamper(result):
    lhs, rhs = (result.lhs, result.rhs) if isinstance(result, sp.Equality) else (None, result)
    if isinstance(rhs, sp.Tuple):
        new = sp.Tuple(rhs[0] * 2 + 1, *rhs[1:])
    else:
        new = rhs + 1
    return sp.Eq(lhs, new, evaluate=False) if lhs is not None else new


@pytest.mark.parametrize("label", labels())
def test_tampered_result_fails_verification(label):
    d = derivation(label)
    assert d.with_result(_tamper(d.result)).verify() is False


def test_paper_boundary_errata_are_corrected():
    reg = derivations()
    assert reg["36"].result.rhs == N
    assert reg["38"].result.rhs.subs(k, 3) == N
    assert reg["39"].result.rhs.subs(k, 4) == N
    assert sp.expand(reg["40"].result.rhs.subs(k, 4) - N * (N - 1)) == 0
    # the paper's own formulas give words/k at the boundary
    assert sp.simplify(reg["38"].paper.subs(k, 3) - N / 3) == 0


def test_key_results_have_the_papers_form():
    reg = derivations()
    assert sp.simplify(reg["16"].result.rhs - ((1 + sp.sqrt(N + 1)) / N) ** 2) == 0
    assert sp.expand(reg["10"].result.rhs - (-p * k**2 + (N * p - 1) * k - 1)) == 0
    assert sp.simplify(reg["16-k"].result.rhs - (sp.sqrt(N + 1) - 1)) == 0


def test_verify_is_not_cached_and_reports_kinds():
    d = derivation("16")
    assert d.verification_kinds == ("symbolic",)
    assert "symbolic" in d.verified_by
    assert derivation("37").verification_kinds == ("exact",)


# ------------------------------------------------------------------ agreement with numerics
@settings(max_examples=25, deadline=None)
@given(st.integers(1, 60), st.data())
def test_phi_lambdified_equals_circuits(n, data):
    kk = data.draw(st.integers(1, n))
    val = derivation("5").result.rhs.subs({N: n, k: kk})
    assert val == circuits.phi(n, kk)


@settings(max_examples=25, deadline=None)
@given(st.lists(st.integers(2, 4), min_size=1, max_size=3), st.integers(1, 4),
       st.integers(1, 14))
def test_general_pattern_count_equals_circuit_count(repeats, singles, n):
    from symhx.symbolic.higher import pattern_count

    repeats = tuple(sorted(repeats, reverse=True))
    L = sum(repeats) + singles
    got = pattern_count(repeats, L).subs(N, n)
    assert got == circuits.circuit_count(n, repeats + (1,) * singles)


@settings(max_examples=20, deadline=None)
@given(st.integers(2, 25), st.integers(1, 40), st.integers(1, 40), st.data())
def test_pmf_lambdified_equals_distribution(n, a, b, data):
    from symhx import api as distribution

    kk = data.draw(st.integers(1, n))
    pv = Fraction(a, b)
    expr = derivation("7").result.rhs.subs({N: n}).doit()
    f = sp.lambdify((k, p), expr, "mpmath")
    with mpmath.workdps(40):
        got = f(kk, mpmath.mpf(a) / b)
        exact = distribution.pmf(n, pv, kk)  # a Fraction for rational p
        assert expr.subs({k: kk, p: sp.Rational(a, b)}) == sp.Rational(exact.numerator,
                                                                        exact.denominator)
        want = mpmath.mpf(exact.numerator) / exact.denominator
        assert abs(got - want) <= mpmath.mpf(10) ** -35 * abs(want)


@settings(max_examples=20, deadline=None)
@given(st.integers(2, 10**6))
def test_discriminant_root_lambdified_equals_critical(n):
    from symhx.critical import discriminant_root

    f = sp.lambdify(N, derivation("16").result.rhs, "mpmath")
    with mpmath.workdps(40):
        assert abs(f(mpmath.mpf(n)) / discriminant_root(n, dps=40) - 1) < mpmath.mpf(10) ** -35


@settings(max_examples=15, deadline=None)
@given(st.integers(3, 60))
def test_crossing_values_give_the_exact_critical_point(n):
    from symhx.critical import critical_point

    c = sp.lambdify((N, k), derivation("crossing").result.rhs, "mpmath")
    with mpmath.workdps(40):
        vals = [c(mpmath.mpf(n), mpmath.mpf(kk)) for kk in range(2, n + 1)]
        cp = critical_point(n, dps=40)
        assert abs(min(vals) - cp.p) < mpmath.mpf(10) ** -30
        best = max(kk for kk, v in zip(range(2, n + 1), vals, strict=True)
                   if abs(v - min(vals)) < mpmath.mpf(10) ** -30)
        assert best == cp.k_after


def test_eq41_weighted_agrees_with_eq41_space():
    from symhx import api as distribution

    w = derivation("41-weighted").result.rhs
    n, pv = 9, Fraction(1, 5)
    weights = [w.subs({N: n, k: kk, p: sp.Rational(1, 5)}) for kk in range(1, n + 1)]
    tot = sum(weights)
    for kk in range(1, n + 1):
        want = distribution.pmf(n, pv, kk, space="eq41")
        assert abs(float(weights[kk - 1] / tot) - float(want)) < 1e-12


def test_import_symhx_does_not_import_sympy():
    code = ("import sys, symhx\n"
            "from symhx.asymptotics import asymptotic_critical_point, error_table\n"
            "asymptotic_critical_point(10**6); error_table((10**3,), dps=20)\n"
            "assert 'sympy' not in sys.modules, 'sympy imported'")
    subprocess.run([sys.executable, "-c", code], check=True)
