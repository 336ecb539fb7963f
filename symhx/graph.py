"""The graph of possible impacts (section 2 of the paper).

Every possible impact is a vertex of a *complete* directed graph with self-loops: after any impact
the next one may be any impact, including the same one again.

* A row of ``n`` pipes between two walls has ``n - 1`` pipe-pipe and 2 pipe-wall impacts, so
  ``N = n + 1`` vertices.
* An ``m x m`` square lattice of pipes with 8-neighbour contact has ``2 (2m - 1)(m - 1)``
  pipe-pipe and ``4 m`` pipe-wall impacts, ``4 m**2 - 2 m + 2`` vertices in all.

The sites come in *classes* that differ physically (section 4 of the paper: "perhaps pipe-wall
impacts are less likely than pipe-pipe impacts"): :func:`row_sites` and :func:`lattice_sites`
give their sizes and names as a :class:`SiteLayout`, in the order that
:class:`symhx.SiteClasses` takes them, and :mod:`symhx.forcing.sites` gives each class its
impact probability.

>>> vertices_row(100)
101
>>> vertices_lattice(3)
32
>>> lattice_sites(3)
SiteLayout(sizes=(12, 12, 8), names=('wall', 'orthogonal', 'diagonal'), bodies=(1, 2, 2))
"""

from __future__ import annotations

from dataclasses import dataclass

from symhx.validation import check_int

__all__ = ["SiteLayout", "impacts_from_pipes", "lattice_sites", "pipe_pipe_lattice", "row_sites",
           "vertices_lattice", "vertices_row"]


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


@dataclass(frozen=True)
class SiteLayout:
    """The classes of impact sites of a geometry: their sizes, names and moving bodies.

    A *site* is a possible impact (a vertex of the graph); sites of one class share their gap
    and the bodies that close it, hence (:mod:`symhx.forcing.sites`) their impact probability.
    Classes of size 0 are left out (a row of one pipe has no pipe-pipe site), so every layout
    can be handed to :class:`symhx.SiteClasses`: ``SiteClasses(layout.sizes, probabilities,
    names=layout.names)``.

    Attributes
    ----------
    sizes : tuple of int
        Number of sites of each class (each ``>= 1``).
    names : tuple of str
        Name of each class: ``"wall"`` (a pipe against a fixed wall), ``"pipe-pipe"`` (the row),
        ``"orthogonal"`` and ``"diagonal"`` (lattice neighbours along a row or column, and along
        a diagonal).
    bodies : tuple of int
        Moving bodies whose motion closes the gap of each class: 1 for a wall site (one pipe),
        2 for a pipe pair (eq. 21: the gap is the *difference* of two pipes' motions).

    Examples
    --------
    >>> layout = row_sites(100)
    >>> layout.N, layout.sizes, layout.names
    (101, (2, 99), ('wall', 'pipe-pipe'))
    >>> layout.size_of("wall")
    2
    """

    sizes: tuple[int, ...]
    names: tuple[str, ...]
    bodies: tuple[int, ...]

    @property
    def N(self) -> int:
        """The number of sites, ``sum(sizes)`` (the vertices of the graph)."""
        return sum(self.sizes)

    def size_of(self, name: str) -> int:
        """The size of the class ``name`` (``0`` for a class this geometry does not have).

        >>> row_sites(1).size_of("pipe-pipe")
        0
        """
        if not isinstance(name, str):
            raise TypeError(f"name must be a str such as 'wall', got {type(name).__name__} "
                            f"{name!r}")
        return self.sizes[self.names.index(name)] if name in self.names else 0


def _layout(classes: tuple[tuple[int, str, int], ...]) -> SiteLayout:
    kept = [c for c in classes if c[0] > 0]
    return SiteLayout(tuple(c[0] for c in kept), tuple(c[1] for c in kept),
                      tuple(c[2] for c in kept))


def row_sites(n: int) -> SiteLayout:
    """The site classes of a row of ``n >= 1`` pipes between two walls (section 2).

    2 wall sites (sites ``0`` and ``n`` of :mod:`symhx.impact`: the left wall with pipe 1, pipe
    ``n`` with the right wall; one moving body each) and ``n - 1`` pipe-pipe sites (two bodies);
    ``N = n + 1`` in all (:func:`vertices_row`). For ``n = 1`` only the wall class remains.

    Parameters
    ----------
    n : int
        Number of pipes, ``>= 1`` (any size: the sizes are Python ints).

    Returns
    -------
    SiteLayout
        Classes ``("wall", "pipe-pipe")`` with sizes ``(2, n - 1)``.

    Raises
    ------
    ValueError, TypeError
        For ``n`` that is not an int ``>= 1``.

    Examples
    --------
    >>> row_sites(3)
    SiteLayout(sizes=(2, 2), names=('wall', 'pipe-pipe'), bodies=(1, 2))
    >>> row_sites(1).sizes
    (2,)
    """
    n = _positive_int(n, "n")
    return _layout(((2, "wall", 1), (n - 1, "pipe-pipe", 2)))


def lattice_sites(m: int) -> SiteLayout:
    """The site classes of an ``m x m`` square lattice of pipes with 8-neighbour contact.

    ``4 m`` wall sites (one per side of a boundary pipe that faces a wall; a corner pipe faces
    two), ``2 m (m - 1)`` orthogonal pipe-pipe sites (neighbours along a row or a column, at one
    pitch) and ``2 (m - 1)**2`` diagonal ones (at ``sqrt(2)`` pitches): ``4 m**2 - 2 m + 2`` in
    all, the paper's count (section 2, :func:`vertices_lattice`). For ``m = 1`` only the wall
    class remains.

    Parameters
    ----------
    m : int
        Pipes per side, ``>= 1``.

    Returns
    -------
    SiteLayout
        Classes ``("wall", "orthogonal", "diagonal")``.

    Raises
    ------
    ValueError, TypeError
        For ``m`` that is not an int ``>= 1``.

    Examples
    --------
    >>> lattice_sites(2)
    SiteLayout(sizes=(8, 4, 2), names=('wall', 'orthogonal', 'diagonal'), bodies=(1, 2, 2))
    >>> lattice_sites(10).N == vertices_lattice(10)
    True
    """
    m = _positive_int(m, "m")
    return _layout(((4 * m, "wall", 1), (2 * m * (m - 1), "orthogonal", 2),
                    (2 * (m - 1) ** 2, "diagonal", 2)))
