"""symhx.graph's site classes: the lattice's classes against its contacts listed cell by cell
(tests.reference.geometry), the row's against the pipe-row model of symhx.impact (which gaps move
with which pipes)."""

from __future__ import annotations

import numpy as np
import pytest

from symhx.graph import SiteLayout, lattice_sites, row_sites, vertices_lattice, vertices_row
from symhx.impact import PipeRow
from tests.harness.errors import assert_refuses
from tests.reference.geometry import lattice_contact_classes


@pytest.mark.parametrize("m", range(1, 13))
def test_lattice_classes_are_its_contacts_by_kind(m):
    layout = lattice_sites(m)
    ref = lattice_contact_classes(m)
    assert {name: layout.size_of(name) for name in ref} == ref
    assert dict(zip(layout.names, layout.sizes, strict=True)) == {k: v for k, v in ref.items()
                                                                 if v}
    assert layout.N == vertices_lattice(m) == 4 * m * m - 2 * m + 2
    assert layout.bodies == tuple(1 if name == "wall" else 2 for name in layout.names)


def bodies_of_each_gap(n: int) -> list[int]:
    """How many pipes move gap i = 0..n of a row of the impact model: shift one pipe's start
    and see which initial gaps change."""
    base = dict(restitution=1, alpha=[[0.0]] * n, beta=[[0.0]] * n, v0=[0.0] * n)
    x0 = np.arange(1, n + 1, dtype=float)
    g0 = PipeRow(n, x0=x0, **base).gap0()
    moved = np.zeros(n + 1, dtype=int)
    for j in range(n):
        x = x0.copy()
        x[j] += 0.25
        moved += PipeRow(n, x0=x, **base).gap0() != g0
    return moved.tolist()


@pytest.mark.parametrize("n", [1, 2, 3, 7, 20])
def test_row_classes_are_the_gaps_of_the_impact_model(n):
    layout = row_sites(n)
    moved = bodies_of_each_gap(n)
    assert len(moved) == layout.N == vertices_row(n)
    by_bodies = {b: moved.count(b) for b in set(moved)}
    assert by_bodies == dict(zip(layout.bodies, layout.sizes, strict=True))
    # the model's wall sites are the first and the last gap
    assert [i for i, b in enumerate(moved) if b == 1] == [0, n]
    assert layout.size_of("wall") == 2


def test_huge_sizes_are_exact_ints():
    assert row_sites(10**100).sizes == (2, 10**100 - 1)
    assert lattice_sites(10**50).N == vertices_lattice(10**50)


def test_layout_is_a_frozen_value():
    a, b = row_sites(5), row_sites("5")
    assert a == b and hash(a) == hash(b) and a != row_sites(6)
    with pytest.raises(AttributeError):
        a.sizes = (1,)  # type: ignore[misc]
    assert isinstance(a, SiteLayout) and a.size_of("diagonal") == 0


@pytest.mark.parametrize(("func", "arg"), [(row_sites, "n"), (lattice_sites, "m")])
def test_refusals_name_the_argument(func, arg):
    assert_refuses(func, 0, arg=arg, value="0", allowed=">= 1")
    assert_refuses(func, 2.5, exc=TypeError, arg=arg, value="2.5", allowed="an int")
    assert_refuses(row_sites(3).size_of, 3, exc=TypeError, arg="name", value="3",
                   allowed="a str")
