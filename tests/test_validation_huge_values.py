"""Refusals show huge values in a short scientific form (issue 28, item 7): no message formats
thousands of digits or crashes on Python's 4300-digit ``str`` limit; ``check_size`` caps the
draws of one ``rvs`` call at ``MAX_SAMPLE_SIZE``."""

from __future__ import annotations

from fractions import Fraction

import pytest

import symhx
from symhx import validation as V
from tests.harness.errors import assert_refuses

HUGE = 10**5000


def test_show_exact_and_brief_repr_are_short_for_huge_values_and_exact_for_small_ones():
    assert V.show_exact(101) == "101" and V.show_exact(Fraction(1, 50)) == "1/50"
    assert V.show_exact(Fraction(1, HUGE)) == "1.0e-5000"
    assert V.show_exact(3 * HUGE) == "3.0e+5000"
    assert V.brief_repr(Fraction(-1, 3)) == "Fraction(-1, 3)"
    assert V.brief_repr(-HUGE) == "-1.0e+5000"


@pytest.mark.parametrize("call, arg, value", [
    (lambda: V.check_int(-HUGE, "x", minimum=0), "x", "-1.0e+5000"),
    (lambda: V.check_int(HUGE, "x", maximum=5), "x", "1.0e+5000"),
    (lambda: symhx.critical_point(-HUGE), "N", "-1.0e+5000"),
    (lambda: symhx.critical_point(10, dps=HUGE), "dps", "1.0e+5000"),
    (lambda: symhx.pmf(101, -Fraction(1, HUGE), 3), "p", "-1.0e-5000"),
    (lambda: symhx.pmf(HUGE, "1e-5000", 3), "N", "1.0e+5000"),
    (lambda: symhx.distribution_of(HUGE, Fraction(1, 2)).mean(), "N", "1.0e+5000"),
    (lambda: symhx.distribution_of(HUGE, 0.5, dps=None).mean(), "N", "1.0e+5000"),
    (lambda: symhx.log_phi(HUGE, HUGE + 1), "k", None),
    (lambda: symhx.impact_probability(Fraction(1, HUGE)), "sigma", "1.0e-5000"),
])
def test_refusals_of_huge_values_show_them_briefly(call, arg, value):
    msg = assert_refuses(call, arg=arg, value=value)
    assert len(msg) < 600


def test_a_distribution_of_a_huge_N_or_p_has_a_short_repr():
    d = symhx.distribution_of(HUGE, Fraction(1, HUGE))
    assert repr(d).startswith("SimpleDistribution(N=1.0e+5000, p=1.0e-5000,")
    assert "N=100000000000000000000," in repr(symhx.distribution_of(10**20, 0.5))


def test_check_size_accepts_shapes_and_caps_the_number_of_draws():
    assert V.check_size(None) is None
    assert V.check_size(0) == (0,) and V.check_size((2, 3)) == (2, 3)
    assert V.check_size(V.MAX_SAMPLE_SIZE) == (V.MAX_SAMPLE_SIZE,)
    assert_refuses(V.check_size, V.MAX_SAMPLE_SIZE + 1, arg="size", allowed="MAX_SAMPLE_SIZE")
    assert_refuses(V.check_size, (10**4, 10**4), arg="size", value="(10000, 10000)",
                   allowed="MAX_SAMPLE_SIZE")
    assert_refuses(V.check_size, -1, arg="size", value="-1", allowed=">= 0")
    assert_refuses(V.check_size, 2.5, exc=TypeError, arg="size", value="2.5")
