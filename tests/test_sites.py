"""SiteClasses: the validated value object of per-class site probabilities (issue 30)."""

from __future__ import annotations

import pickle
from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx.sites import (
    MAX_SITE_SEQUENCE,
    SiteClasses,
    as_site_classes,
    is_site_input,
    show_int,
)
from tests.harness.errors import assert_refuses


def test_inputs_keep_the_meaning_of_the_conversion_layer():
    s = SiteClasses((2, 99), ("0.01", 0.02), names=("wall", "pipe"))
    assert s.values == (Fraction(1, 100), Fraction(0.02))  # the string is 1/100, the float binary
    assert s.values[1] != Fraction(1, 50)
    assert not s.exact and s.N == 101 and len(s) == 2
    assert list(s) == [(2, "0.01"), (99, 0.02)]
    e = SiteClasses([3, 4], [Fraction(1, 3), Decimal("0.25")])
    assert e.exact and e.values == (Fraction(1, 3), Fraction(1, 4))
    m = SiteClasses((1,), (mpmath.mpf("0.1"),))
    assert m.values[0] == Fraction(mpmath.mpf("0.1").man) * Fraction(2) ** mpmath.mpf("0.1").exp


def test_huge_sizes_are_exact_and_shown_readably():
    s = SiteClasses((2, 10**100 - 2), (1, 2))
    assert s.N == 10**100
    assert "10**100" not in repr(s) and "~" in repr(s)
    shown = "SiteClasses(sizes=(10**100,), probabilities=(1,))"
    assert repr(SiteClasses((10**100,), (1,))) == shown


def test_shown_ints_are_exact_below_10_to_the_30_and_never_longer():
    for n in (0, 7, 10**29, 10**30 - 1):
        assert show_int(n) == str(n)
    for n in (10**30, 10**30 + 1, 3 * 10**30 - 1, 10**31, 10**400 + 1):
        assert len(show_int(n)) <= 30 and show_int(n) != str(n)
    assert show_int(10**30) == "10**30" and show_int(10**31 + 1) == "~1.0e+31"


def test_long_probabilities_are_shown_in_at_most_60_characters():
    long = Fraction(1, 3**200)
    r = repr(SiteClasses((1, 2), (long, "1/2")))
    start = r.index("probabilities=(") + len("probabilities=(")
    shown, after = r[start:start + 60], r[start + 60:]
    assert shown == repr(long)[:57] + "..." and after.startswith(", '1/2')")


def test_equality_and_hash_follow_values_kinds_and_names():
    a = SiteClasses((2, 3), ("1/2", "0.25"))
    assert a == SiteClasses([2, 3], [Fraction(1, 2), Fraction(1, 4)])
    assert hash(a) == hash(SiteClasses([2, 3], [Fraction(1, 2), Fraction(1, 4)]))
    assert a != SiteClasses((2, 3), (0.5, 0.25))  # same values, binary kind: mpmath results
    assert a != SiteClasses((2, 3), ("1/2", "0.25"), names=("x", "y"))
    assert a != SiteClasses((3, 2), ("0.25", "1/2"))  # order is part of the value
    assert (a == 3) is False
    assert len({a, SiteClasses((2, 3), ("1/2", "1/4"))}) == 1


def test_value_object_is_immutable_and_pickles():
    a = SiteClasses((2, 3), (0.1, "1/3"), names=("w", "p"))
    with pytest.raises(AttributeError):
        a.sizes = (1, 4)  # type: ignore[misc]
    with pytest.raises(AttributeError):
        del a.names
    b = pickle.loads(pickle.dumps(a))
    assert b == a and hash(b) == hash(a) and b.probabilities == a.probabilities


def test_scaled_multiplies_exactly():
    a = SiteClasses((1, 2), ("1/4", 0.1))
    b = a.scaled("2/3")
    assert b.probabilities[0] == Fraction(1, 6) and not b.exact
    exact = Fraction(0.1) * Fraction(2, 3)  # not dyadic: an mpf of 256 bits, as documented
    assert abs(b.values[1] - exact) <= exact * Fraction(1, 2**255)
    c = SiteClasses((1, 2), (0.25, 0.1)).scaled(3)
    assert c.values == (Fraction(3, 4), 3 * Fraction(0.1))  # dyadic: the mpf holds it exactly
    assert all(isinstance(p, mpmath.mpf) for p in c.probabilities)
    assert SiteClasses((2,), ("1/2",)).scaled(Fraction(4)).probabilities == (Fraction(2),)


def test_per_site_sequences_group_into_classes_in_order():
    s = SiteClasses.from_sites(["0.5", 0.25, Fraction(1, 2), "1/4", 3])
    assert s.sizes == (2, 2, 1)
    assert s.values == (Fraction(1, 2), Fraction(1, 4), Fraction(3))
    assert s._exact_flags == (True, False, True)  # one binary entry makes its class binary
    assert SiteClasses.from_sites(np.array([0.5, 0.5])).sizes == (2,)


def test_merged_joins_equal_values():
    s = SiteClasses((2, 3, 4), ("1/2", 0.5, "1/3"), names=("a", "b", "c"))
    m = s.merged()
    assert m.sizes == (5, 4) and m.values == (Fraction(1, 2), Fraction(1, 3)) and m.names is None
    assert not m._exact_flags[0]
    u = SiteClasses((2, 3), (1, 2), names=("a", "b"))
    assert u.merged() is u


def test_site_input_coercion():
    assert is_site_input([0.1, 0.2]) and is_site_input(SiteClasses((1,), (1,)))
    assert not is_site_input(0.1) and not is_site_input("0.1")
    assert not is_site_input(np.array(0.1))
    s = as_site_classes((0.1, 0.1, 0.2), 3)
    assert s.sizes == (2, 1)


@pytest.mark.parametrize("args, kwargs, exc, arg, value, allowed", [
    (("12", (1,)), {}, TypeError, "sizes", "'12'", "positive ints"),
    ((5, (1,)), {}, TypeError, "sizes", "5", "positive ints"),
    (((), ()), {}, ValueError, "sizes", "empty", "at least one class"),
    (((2, 3), (1,)), {}, ValueError, "probabilities", "1 values", "one value per class"),
    (((0, 3), (1, 1)), {}, ValueError, "sizes[0]", "0", ">= 1"),
    (((2.0, 3), (1, 1)), {}, TypeError, "sizes[0]", "2.0", "int"),
    (((True, 3), (1, 1)), {}, TypeError, "sizes[0]", "True", "integer"),
    (((2, 3), (1, 0)), {}, ValueError, "probabilities[1]", "0", "> 0"),
    (((2, 3), (1, "-0.1")), {}, ValueError, "probabilities[1]", "-0.1", "> 0"),
    (((2, 3), (1, float("nan"))), {}, ValueError, "probabilities[1]", "nan", "finite"),
    (((2, 3), (1, "abc")), {}, ValueError, "probabilities[1]", "'abc'", "a number"),
    (((2, 3), (1, True)), {}, TypeError, "probabilities[1]", "True", "real number"),
    (((2, 3), (1, 2)), {"names": ("a",)}, ValueError, "names", "names has 1", "one str"),
    (((2, 3), (1, 2)), {"names": ("a", "a")}, ValueError, "names", "'a'", "distinct"),
    (((2, 3), (1, 2)), {"names": ("a", 3)}, TypeError, "names[1]", "3", "str"),
    (((2, 3), (1, 2)), {"names": ("a", " ")}, ValueError, "names[1]", "' '", "non-empty"),
])
def test_bad_input_is_refused_clearly(args, kwargs, exc, arg, value, allowed):
    assert_refuses(SiteClasses, *args, exc=exc, arg=arg, value=value, allowed=allowed, **kwargs)


def test_irrational_probabilities_are_refused():
    sympy = pytest.importorskip("sympy")
    assert_refuses(SiteClasses, (1, 2), (1, sympy.sqrt(2) / 10), exc=TypeError,
                   arg="probabilities[1]", value="sqrt(2)/10", allowed="rational, float or mpf")
    assert_refuses(SiteClasses.from_sites, [0.5, sympy.sqrt(2) / 10], exc=TypeError,
                   arg="sites[1]", value="sqrt(2)/10", allowed="rational, float or mpf")


def test_site_sequences_are_refused_clearly():
    assert_refuses(as_site_classes, [0.1, 0.2], 3, arg="p", value="sequence of 2",
                   allowed="one probability per site")
    assert_refuses(as_site_classes, SiteClasses((2,), (1,)), 3, arg="p", value="N = 2",
                   allowed="add up to N")
    assert_refuses(as_site_classes, 0.5, 1, exc=TypeError, arg="p", value="0.5",
                   allowed="SiteClasses")
    assert_refuses(SiteClasses.from_sites, [], arg="sites", value="empty",
                   allowed="at least one")
    assert_refuses(SiteClasses.from_sites, [0.1, -1], arg="sites[1]", value="-1", allowed="> 0")
    assert_refuses(SiteClasses((1,), (1,)).scaled, 0, arg="t", value="0", allowed="> 0")


def test_the_per_site_sequence_cap_is_checked_before_any_work():
    class Long(list):
        def __len__(self):
            return MAX_SITE_SEQUENCE + 1

        def __iter__(self):
            raise AssertionError("iterated a sequence beyond the cap")

    with pytest.raises(ValueError, match="MAX_SITE_SEQUENCE"):
        SiteClasses.from_sites(Long())


def test_command_line_form_parses_exactly():
    s = SiteClasses.parse("wall=2:0.01, pipe=99:1/50")
    assert s == SiteClasses((2, 99), ("0.01", Fraction(1, 50)), names=("wall", "pipe"))
    assert s.exact and SiteClasses.parse("3:1e-3").values == (Fraction(1, 1000),)


@pytest.mark.parametrize("text, value, allowed", [
    ("2:0.1,", "item 1 is ''", "size:probability"),
    ("x", "'x'", "size:probability"),
    ("=2:1", "'=2:1'", "name=size:probability"),
    ("a=2:1,3:1", "'a=2:1,3:1'", "every class or none"),
    ("0:1", "0", ">= 1"),
    ("2:-1", "'-1'", "> 0"),
    ("2:abc", "'abc'", "a number"),
])
def test_command_line_form_refusals(text, value, allowed):
    assert_refuses(SiteClasses.parse, text, arg="--sites", value=value, allowed=allowed)


def test_parse_reads_a_rest_size_against_N():
    sc = SiteClasses.parse("wall=2:0.01,pipe=rest:1/50", N=101)
    assert sc == SiteClasses((2, 99), ("0.01", "1/50"), names=("wall", "pipe"))
    assert_refuses(SiteClasses.parse, "2:0.01,rest:0.02", arg="--sites", value="rest",
                   allowed="where N is known")
    assert_refuses(SiteClasses.parse, "2:0.01,rest:0.02,rest:1", N=10, arg="--sites",
                   allowed="one size 'rest'")
    assert_refuses(SiteClasses.parse, "9:0.01,rest:0.02", N=9, arg="--sites", value="0",
                   allowed=">= 1")
