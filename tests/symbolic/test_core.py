"""symhx.symbolic._core: a check that cannot run has not verified anything, a derivation with no
check is not verified, checks see the derivation as it stands (its tampered result too), and the
helpers prove identities and exact equalities without floating point."""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from symhx.symbolic._core import (
    Check,
    Derivation,
    N,
    all_exact,
    k,
    log_equal,
    rhs,
    sym_equal,
)


def _square() -> Derivation:
    return Derivation("sq", "N squared", sp.Eq(sp.Symbol("y"), N**2), checks=(
        Check("equals N*N, symbolic", "symbolic", lambda d: sym_equal(rhs(d), N * N)),
        Check("equals n**2 for n <= 5", "exact",
              lambda d: all_exact((rhs(d).subs(N, n), n * n) for n in range(1, 6))),
    ))


def test_a_check_that_raises_has_not_passed():
    res = Check("divides by zero", "exact", lambda d: 1 / 0).run(_square())
    assert res.passed is False and res.error.startswith("ZeroDivisionError")
    ok = Check("truthy", "exact", lambda d: 1).run(_square())
    assert ok.passed is True and ok.error is None


def test_verify_needs_at_least_one_check_and_every_check():
    d = _square()
    assert d.verify() is True and [r.passed for r in d.report()] == [True, True]
    assert Derivation("none", "no checks", N).verify() is False
    failing = Derivation("f", "one check fails", N, checks=(
        *d.checks, Check("never", "exact", lambda d: False)))
    assert failing.verify() is False


def test_checks_see_the_result_as_it_stands():
    d = _square()
    bad = d.with_result(sp.Eq(sp.Symbol("y"), N**2 + 1))
    assert bad.label == d.label and bad.checks == d.checks
    assert [r.passed for r in bad.report()] == [False, False]
    assert d.verify() is True  # nothing is cached


def test_kinds_summary_and_dict():
    d = _square()
    assert d.verification_kinds == ("symbolic", "exact")
    assert d.verified_by == "[symbolic] equals N*N, symbolic; [exact] equals n**2 for n <= 5"
    out = d.as_dict(verify=True)
    assert out["verified"] is True and out["result"] == "Eq(y, N**2)"
    assert [c["passed"] for c in out["checks"]] == [True, True]
    assert "verified" not in d.as_dict()
    assert str(d) == "(sq) N squared: Eq(y, N**2)"


def test_sym_equal_and_log_equal():
    assert sym_equal(sp.factorial(N) / sp.factorial(N - 1), N)
    assert not sym_equal(N + 1, N)
    assert sym_equal(sp.gamma(N + 1) / sp.gamma(N), N)
    # a gamma ratio at half-integer arguments (proved through gammasimp)
    assert sym_equal(sp.gamma(N + sp.Rational(1, 2)) / sp.gamma(N - sp.Rational(1, 2)),
                     N - sp.Rational(1, 2))
    assert not sym_equal(sp.gamma(N + sp.Rational(1, 2)) / sp.gamma(N - sp.Rational(1, 2)), N)
    assert log_equal((N ** (1 / (k - 1))) ** (k - 1), N)
    assert not log_equal(2 * N, N)


def test_all_exact_refuses_anything_inexact():
    assert all_exact([(sp.Rational(1, 3), Fraction(1, 3)), (sp.Integer(4), 4)])
    assert not all_exact([(sp.Rational(1, 3), Fraction(1, 4))])
    assert not all_exact([(sp.Float(0.5), Fraction(1, 2))])  # a float is never exact
    assert not all_exact([(sp.sqrt(2), 1)])
    assert all_exact([(sp.sqrt(4) / 2, 1)])  # an exact number that simplifies to a rational
    assert rhs(Derivation("x", "x", N + 1)) == N + 1


def test_a_derivation_with_extra_equations_prints_them_after_a_quad():
    from symhx.symbolic import derivation

    d = derivation("8")
    text = d.latex()
    parts = text.split(r",\quad ")
    assert len(parts) == 2 and parts[0].startswith(r"\Phi_{N,p}") and parts[1].startswith(r"\Gamma")


def test_exp_of_a_compound_argument_is_printed_as_exp():
    """e^{x} and e^{-x} stay superscripts; a compound argument (a fraction, a product of more
    than a sign and an atom) is printed \\exp(...), readable at the book's size."""
    import sympy as sp

    from symhx.symbolic._core import latex

    x, y = sp.symbols("x y")
    assert latex(sp.exp(x)) == "e^{x}" and latex(sp.exp(-x)) == "e^{- x}"
    assert latex(sp.exp(x / y)) == r"\exp\left(\frac{x}{y}\right)"
    assert latex(sp.exp(-x * y)) == r"\exp\left(- x y\right)"
    assert latex(sp.exp(2 * x)) == r"\exp\left(2 x\right)"


def test_polygamma_is_printed_as_psi_with_its_order_and_power():
    import sympy as sp

    from symhx.symbolic._core import latex

    x = sp.Symbol("x")
    assert latex(sp.polygamma(0, x)) == r"\psi\left(x\right)"
    assert latex(sp.polygamma(1, x)) == r"\psi^{(1)}\left(x\right)"
    assert latex(sp.polygamma(1, x) ** 2) == r"\psi^{(1)}\left(x\right)^{2}"


def test_as_dict_names_label_section_and_result():
    from symhx.symbolic import derivation

    d = derivation("12")
    out = d.as_dict()
    assert out["label"] == "12" and out["section"] == d.section and out["latex"] == d.latex()
    assert set(out) >= {"label", "section", "description", "text", "result", "latex", "kinds"}
