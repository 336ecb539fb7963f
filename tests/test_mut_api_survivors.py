"""symhx.api: the class chosen for the simple space, the wording of a wrong-kind ``space`` and
where the deprecation warning of ``symhx.variance`` points (mutation survivors, issue 16)."""

from __future__ import annotations

import os
import warnings
from fractions import Fraction

import pytest

import symhx
from symhx.distribution import SimpleDistribution
from symhx.spaces import SpaceDistribution
from tests.reference.distribution import pmf_table


@pytest.mark.parametrize("space", ["simple", symhx.spaces.parse_space("simple")])
def test_simple_space_gets_the_simple_distribution(space):
    """``space="simple"`` (a name or a parsed Space) builds the eq. 7-8 distribution itself,
    not the general higher-order one; its pmf is p**k N!/(k (N-k)!) normalised (exact)."""
    N, p = 9, Fraction(2, 7)
    d = symhx.distribution_of(N, p, space=space)
    assert type(d) is SimpleDistribution and not isinstance(d, SpaceDistribution)
    assert [d.pmf(k) for k in range(1, N + 1)] == pmf_table(N, p)
    assert type(symhx.distribution_of(N, p, space="eq41")) is SpaceDistribution


@pytest.mark.parametrize("bad,kind", [(3.5, "float"), (None, "NoneType"), (["eq41"], "list")])
def test_space_of_a_wrong_kind_names_its_type(bad, kind):
    with pytest.raises(TypeError, match=rf"^space must be a str such as 'simple', 'eq41' or "
                                        rf"'excess<=3' \(or a symhx\.spaces\.Space\), got "
                                        rf"{kind} "):
        symhx.distribution_of(10, 0.1, space=bad)


@pytest.mark.skipif("MUTANT_UNDER_TEST" in os.environ,
                    reason="mutmut's trampoline adds a frame between the caller and symhx")
def test_variance_deprecation_points_at_the_caller():
    """The DeprecationWarning of ``symhx.variance`` is reported at the line that called it
    (stacklevel 2), not inside symhx or pytest."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        v = symhx.variance(10, Fraction(1, 3))
    assert v == symhx.var(10, Fraction(1, 3))
    dep = [w for w in caught if issubclass(w.category, DeprecationWarning)]
    assert len(dep) == 1 and dep[0].filename == __file__
    assert str(dep[0].message) == "symhx.variance is deprecated: use symhx.var (scipy's name)"
