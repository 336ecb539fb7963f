"""symhx.symbolic.simple (sections 3-5, eqs. 4-8): every derivation verifies, each of its
checks rejects a tampered result on its own, and the lambdified results agree with the numeric
modules (exact integers / rationals)."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import mpmath
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import symhx
from symhx import circuits
from symhx.symbolic import N, derivation, k, p
from tests.harness.derivations import assert_check_rejects, contract_tests, tamper, tamper_rhs

#: every derivation of the module and its number of checks
CHECKS = {"4": 3, "5": 3, "6": 2, "7": 2, "8": 3}
#: checks a generic change of the result cannot fail: eq. (8)'s third check verifies the
#: derived normaliser Gamma (``extra``), not Phi
TAMPER = {
    ("8", 2): lambda d: dataclasses.replace(d, extra={"Gamma": tamper(d.extra["Gamma"])}),
}


(test_the_table_lists_every_derivation_of_the_module, test_every_derivation_verifies,
 test_each_check_rejects_a_tampered_result) = contract_tests("simple", CHECKS, TAMPER)


# ------------------------------------------------------------------ agreement with numerics
@settings(max_examples=25, deadline=None)
@given(st.integers(1, 60), st.data())
def test_phi_lambdified_equals_circuits(n, data):
    kk = data.draw(st.integers(1, n))
    val = derivation("5").result.rhs.subs({N: n, k: kk})
    assert val == circuits.phi(n, kk)


@settings(max_examples=20, deadline=None)
@given(st.integers(2, 25), st.integers(1, 40), st.integers(1, 40), st.data())
def test_pmf_lambdified_equals_distribution(n, a, b, data):
    kk = data.draw(st.integers(1, n))
    pv = Fraction(a, b)
    expr = derivation("7").result.rhs.subs({N: n}).doit()
    f = sp.lambdify((k, p), expr, "mpmath")
    with mpmath.workdps(40):
        got = f(kk, mpmath.mpf(a) / b)
        exact = symhx.pmf(n, pv, kk)  # a Fraction for rational p
        assert expr.subs({k: kk, p: sp.Rational(a, b)}) == sp.Rational(exact.numerator,
                                                                        exact.denominator)
        want = mpmath.mpf(exact.numerator) / exact.denominator
        assert abs(got - want) <= mpmath.mpf(10) ** -35 * abs(want)


def test_eq8_carries_the_papers_printed_form():
    from symhx.symbolic import sym_equal

    d = derivation("8")
    assert d.paper is not None
    assert sym_equal(d.paper, p**k * sp.factorial(N) / (k * sp.factorial(N - k)))
    assert sym_equal(d.result.rhs, d.paper)


def test_eq7_brute_force_check_compares_every_length_including_one():
    # a pmf wrong only at k = 1 (the other lengths untouched) is rejected by the brute force
    d = derivation("7")
    index = next(i for i, c in enumerate(d.checks) if "brute-force" in c.description)
    wrong_at_one = tamper_rhs(lambda d: d.result.rhs + sp.KroneckerDelta(k, 1))(d)
    assert wrong_at_one.result.rhs.subs({N: 3, k: 2}) == d.result.rhs.subs({N: 3, k: 2})
    assert_check_rejects(d, index, wrong_at_one)
