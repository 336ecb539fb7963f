"""symhx.spaces' critical point refuses a bad ``dps`` like the simple space's (moved here from
the simple critical-point tests; the spaces' own tests are in ``test_critical*.py``)."""

from __future__ import annotations

import pytest

import symhx.spaces
from tests.harness.errors import assert_refuses


@pytest.mark.parametrize("bad", [0, -1, 2.5, True, 10**6, "50", None])
def test_bad_dps(bad):
    exc = ValueError if type(bad) is int else TypeError
    assert_refuses(symhx.spaces.critical_point, 20, space="eq41", dps=bad, exc=exc, arg="dps",
                   allowed="an int between 1 and 5000")
