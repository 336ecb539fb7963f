"""symhx.graph against independent references: rows and lattices built cell by cell, their
contacts counted one by one (tests.reference.combinatorics)."""

from __future__ import annotations

import pytest

from symhx.graph import impacts_from_pipes, pipe_pipe_lattice, vertices_lattice, vertices_row
from tests.harness.errors import assert_refuses
from tests.reference.combinatorics import lattice_contacts, row_contacts


@pytest.mark.parametrize("n", [1, 2, 3, 4, 10, 57, 100])
def test_row_counts_contacts(n):
    assert vertices_row(n) == len(row_contacts(n)) == impacts_from_pipes(n)


def test_row_large():
    assert vertices_row(10**30) == 10**30 + 1


@pytest.mark.parametrize("m", range(1, 9))
def test_lattice_counts_contacts(m):
    pp, walls = lattice_contacts(m)
    assert walls == 4 * m  # one wall contact per boundary side of a boundary pipe
    assert pipe_pipe_lattice(m) == pp
    assert vertices_lattice(m) == pp + walls == 4 * m * m - 2 * m + 2


@pytest.mark.parametrize(("func", "arg"), [(vertices_row, "n"), (vertices_lattice, "m"),
                                           (pipe_pipe_lattice, "m"), (impacts_from_pipes, "n")])
def test_errors_name_argument_and_value(func, arg):
    for bad in (0, -5):
        assert_refuses(func, bad, arg=arg, value=str(bad), allowed=">= 1")
    assert_refuses(func, 2.5, exc=TypeError, arg=arg, value="float 2.5", allowed="an int")
    assert func("3") == func(3)  # decimal strings are exact integers (symhx.validation)
    assert_refuses(func, "three", arg=arg, value="'three'",
                   allowed="an integer such as 7, 10**100 or '1e100'")
