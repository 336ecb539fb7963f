"""Independent references for symhx.graph: build the rows and lattices and count the contacts."""

from __future__ import annotations

import itertools

import pytest

from symhx.graph import impacts_from_pipes, pipe_pipe_lattice, vertices_lattice, vertices_row


def row_contacts(n: int) -> set[tuple[str, str]]:
    """Walls L and R with pipes 1..n between them: neighbours in the row touch."""
    line = ["L", *[str(i) for i in range(1, n + 1)], "R"]
    return {(a, b) for a, b in itertools.pairwise(line)}


def lattice_contacts(m: int) -> tuple[int, int]:
    """(pipe-pipe, pipe-wall) contacts of an m x m grid, 8-neighbour contact; a pipe on the
    boundary touches the wall it faces (one contact per boundary side of a boundary pipe)."""
    cells = [(i, j) for i in range(m) for j in range(m)]
    pp = {frozenset((a, b)) for a in cells for b in cells
          if a != b and max(abs(a[0] - b[0]), abs(a[1] - b[1])) == 1}
    walls = sum((i == 0) + (i == m - 1) + (j == 0) + (j == m - 1) for i, j in cells)
    return len(pp), walls


@pytest.mark.parametrize("n", [1, 2, 3, 4, 10, 57, 100])
def test_row_counts_contacts(n):
    assert vertices_row(n) == len(row_contacts(n)) == impacts_from_pipes(n)


def test_row_large():
    assert vertices_row(10**30) == 10**30 + 1


@pytest.mark.parametrize("m", range(1, 9))
def test_lattice_counts_contacts(m):
    pp, walls = lattice_contacts(m)
    assert pipe_pipe_lattice(m) == pp
    assert vertices_lattice(m) == pp + walls


@pytest.mark.parametrize(("func", "arg"), [(vertices_row, "n"), (vertices_lattice, "m"),
                                           (pipe_pipe_lattice, "m"), (impacts_from_pipes, "n")])
def test_errors_name_argument_and_value(func, arg):
    with pytest.raises(ValueError, match=rf"^{arg} must be >= 1, got 0$"):
        func(0)
    with pytest.raises(ValueError, match=rf"^{arg} must be >= 1, got -5$"):
        func(-5)
    with pytest.raises(TypeError, match=rf"^{arg} must be an int, got float "):
        func(2.5)
    assert func("3") == func(3)  # decimal strings are exact integers (symhx.validation)
    with pytest.raises(ValueError, match=rf"^{arg} must be an integer such as 7, 10\*\*100 "
                                         r"or '1e100', got 'three'$"):
        func("three")
