"""symhx.spaces._classes: the refusals and the excess cap met by the circuit-count tests
(moved here from the circuits tests; the classes' own tests are in ``test_classes*.py``)."""

from __future__ import annotations

from symhx.spaces import class_count, parse_space
from tests.harness.errors import assert_refuses


def test_class_count_and_excess_cap_are_clear_errors():
    assert_refuses(class_count, -3, (2,), 1, arg="N", value="-3", allowed=">= 1")
    cap = [" 25 ", "MAX_EXCESS"]
    assert_refuses(parse_space, "excess<=1000", arg="m", value="1000", allowed=cap)
    assert_refuses(parse_space, "excess<=" + "9" * 5000, arg="m", allowed=cap)
    assert len(parse_space("excess<=5").shapes) == 19
