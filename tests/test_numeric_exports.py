"""``symhx._numeric`` exports only what it defines: the validation and certify names have one
address each (``symhx.validation``, ``symhx.certify``), not a second one here."""

from __future__ import annotations

import symhx._numeric as numeric
from symhx import certify, validation


def test_every_exported_name_is_defined_in_the_module():
    for name in numeric.__all__:
        assert getattr(numeric, name).__module__ == "symhx._numeric", name


def test_no_validation_or_certify_name_is_exported_again():
    again = set(numeric.__all__) & (set(validation.__all__) | set(dir(certify)))
    assert not again
