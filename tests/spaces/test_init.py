"""The package namespace :mod:`symhx.spaces`: every public name resolves, and the top-level
names of symhx for the higher-order spaces are the same objects."""

from __future__ import annotations

import symhx
import symhx.spaces as spaces


def test_every_public_name_resolves() -> None:
    for name in spaces.__all__:
        assert getattr(spaces, name) is not None, name


def test_top_level_names_are_the_spaces_functions() -> None:
    names = ("class_count", "class_decomposition", "class_probabilities", "convergence_study",
             "pattern_count_symbolic", "parse_space", "eq41_terms")
    for name in names:
        assert name in spaces.__all__ and name in symhx.__all__
        assert getattr(symhx, name) is getattr(spaces, name), name
