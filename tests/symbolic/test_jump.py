"""symhx.symbolic.jump (section 6, eqs. 9-16 and the crossing condition): every derivation
verifies, each of its checks rejects a tampered result on its own, the key results have the
paper's form, and the lambdified results agree with symhx.critical (the certified solver)."""

from __future__ import annotations

from fractions import Fraction
from math import factorial

import mpmath
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symhx.critical import critical_point, discriminant_root
from symhx.symbolic import N, derivation, k, p
from symhx.symbolic.jump import c_k, kappa
from tests.harness.derivations import contract_tests, tamper_part, tamper_rhs

#: every derivation of the module and its number of checks
CHECKS = {"9": 3, "10": 3, "11": 3, "12": 2, "13": 2, "14": 3, "15": 3, "16": 4, "16-k": 2,
          "16-spurious": 3, "crossing": 3, "crossing-ratio": 1, "crossing-relaxed": 2}
#: checks of a property that a generic change keeps, given a change aimed at it
TAMPER = {
    # f_{N,0} = -(k+1) + 1 is still negative, k (N-k) + 1 still positive: flip the sign
    ("14", 2): tamper_rhs(lambda d: -d.result.rhs),
    ("15", 2): tamper_rhs(lambda d: -d.result.rhs),
    # p_d + 1 still has its double root inside (0, N): the other zero of the discriminant
    # (the wrong root of the quadratic in p) has it at k < 0
    ("16", 2): tamper_rhs(lambda d: ((1 - sp.sqrt(N + 1)) / N) ** 2),
    # a constant added to log(N c) keeps its minimiser: move the minimiser
    ("crossing-relaxed", 1): tamper_rhs(lambda d: d.result.rhs + kappa / 1000),
}


(test_the_table_lists_every_derivation_of_the_module, test_every_derivation_verifies,
 test_each_check_rejects_a_tampered_result) = contract_tests("jump", CHECKS, TAMPER)


@pytest.mark.parametrize("label", ["11", "16-spurious"])
def test_every_entry_of_a_tuple_result_is_verified(label):
    d = derivation(label)
    for j in range(len(d.result.rhs)):
        assert tamper_part(d, j).verify() is False, j


def test_key_results_have_the_papers_form():
    assert sp.simplify(derivation("16").result.rhs - ((1 + sp.sqrt(N + 1)) / N) ** 2) == 0
    assert sp.expand(derivation("10").result.rhs - (-p * k**2 + (N * p - 1) * k - 1)) == 0
    assert sp.simplify(derivation("16-k").result.rhs - (sp.sqrt(N + 1) - 1)) == 0


def test_verify_reports_the_kinds_of_check():
    d = derivation("16")
    assert d.verification_kinds == ("symbolic",)
    assert "symbolic" in d.verified_by


# ------------------------------------------------------------------ agreement with numerics
@settings(max_examples=20, deadline=None)
@given(st.integers(2, 10**6))
def test_discriminant_root_lambdified_equals_critical(n):
    f = sp.lambdify(N, derivation("16").result.rhs, "mpmath")
    with mpmath.workdps(40):
        assert abs(f(mpmath.mpf(n)) / discriminant_root(n, dps=40) - 1) < mpmath.mpf(10) ** -35


@settings(max_examples=15, deadline=None)
@given(st.integers(3, 60))
def test_crossing_values_give_the_exact_critical_point(n):
    c = sp.lambdify((N, k), derivation("crossing").result.rhs, "mpmath")
    with mpmath.workdps(40):
        vals = [c(mpmath.mpf(n), mpmath.mpf(kk)) for kk in range(2, n + 1)]
        cp = critical_point(n, dps=40)
        assert abs(min(vals) - cp.p) < mpmath.mpf(10) ** -30
        best = max(kk for kk, v in zip(range(2, n + 1), vals, strict=True)
                   if abs(v - min(vals)) < mpmath.mpf(10) ** -30)
        assert best == cp.k_after


def test_c_k_is_the_crossing_value_at_each_length():
    # Phi(k) = Phi(1) at p = c_k: c_k**(k-1) = k (N-k)! / (N-1)!, from the factorials
    for n in (3, 5, 8):
        for kk in range(2, n + 1):
            c = c_k(kk).subs(N, n)
            want = Fraction(kk * factorial(n - kk), factorial(n - 1))
            assert c.is_positive and sp.simplify(c ** (kk - 1)) == sp.Rational(
                want.numerator, want.denominator), (n, kk, c)
