"""The graph of possible impacts (section 2 of the paper).

Every possible impact is a vertex of a *complete* directed graph with self-loops: after any impact
the next one may be any impact, including the same one again.

* A row of ``n`` pipes between two walls has ``n - 1`` pipe-pipe and 2 pipe-wall impacts, so
  ``N = n + 1`` vertices.
* An ``m x m`` square lattice of pipes with 8-neighbour contact has ``2 (2m - 1)(m - 1)``
  pipe-pipe and ``4 m`` pipe-wall impacts, ``4 m**2 - 2 m + 2`` vertices in all.

>>> vertices_row(100)
101
>>> vertices_lattice(3)
32
"""

from __future__ import annotations

from symhx.validation import check_int

__all__ = ["impacts_from_pipes", "pipe_pipe_lattice", "vertices_lattice", "vertices_row"]


def _positive_int(value: int, name: str, minimum: int = 1) -> int:
    return check_int(value, name, minimum=minimum)


def vertices_row(n: int) -> int:
    """Number of possible impacts ``N = n + 1`` for a 1-D row of ``n >= 1`` pipes.

    ``n - 1`` pipe-pipe impacts plus one impact with each wall.

    >>> vertices_row(3)   # figure 2 of the paper: L-1, 1-2, 2-3, 3-R
    4
    """
    return _positive_int(n, "n") + 1


impacts_from_pipes = vertices_row


def pipe_pipe_lattice(m: int) -> int:
    """Pipe-pipe contacts ``2 (2m - 1)(m - 1)`` in an ``m x m`` lattice with 8-neighbour contact."""
    m = _positive_int(m, "m")
    return 2 * (2 * m - 1) * (m - 1)


def vertices_lattice(m: int) -> int:
    """Vertices ``4 m**2 - 2 m + 2`` of the graph of an ``m x m`` pipe lattice (section 2).

    ``m - 1`` horizontal and vertical contacts per line (``2 m (m - 1)``), ``2 (m - 1)**2``
    diagonal ones, and ``4 m`` pipe-wall impacts (one per boundary pipe side).

    >>> vertices_lattice(1)
    4
    """
    m = _positive_int(m, "m")
    return pipe_pipe_lattice(m) + 4 * m
