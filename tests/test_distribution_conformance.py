"""The simple space's frozen distribution passes the conformance checks of every frozen discrete
distribution (:mod:`tests.harness.discrete`) on a log grid of N and p, on its three paths: exact
``p``, float ``p`` at ``dps`` digits, and float64 (``dps=None``).

Reference: ``Phi_{N,p}(k)`` from factorials (eq. 8), every derived quantity by its definition
(:class:`tests.reference.distribution.ExactTable`); a float ``p`` is taken at its exact binary
value.
"""

from __future__ import annotations

from fractions import Fraction

import pytest

import symhx
from tests.harness import discrete
from tests.harness.discrete import NS, PS, Path
from tests.reference.distribution import ExactTable

CASES = [(N, p) for N in NS for p in PS]
PATHS = [Path.exact(30), Path.mp(25), Path.mp(60), Path.float64(rtol=1e-11)]


def _simple(N: int):
    return lambda p, dps: symhx.distribution_of(N, p, dps=dps)


def _id(case: tuple[int, Fraction]) -> str:
    return f"N{case[0]}-p{case[1]}"


@pytest.mark.parametrize("path", PATHS, ids=lambda x: f"{x.kind}{x.dps or ''}")
@pytest.mark.parametrize("case", CASES, ids=_id)
def test_every_method_agrees_with_the_exact_table(case: tuple[int, Fraction], path: Path) -> None:
    d, p = discrete.frozen_on_path(_simple(case[0]), case[1], path)
    discrete.check_frozen(d, ExactTable.simple(case[0], p), path)


@pytest.mark.parametrize("path", [Path.exact(30), Path.mp(30)], ids=["exact", "mp30"])
@pytest.mark.parametrize("case", [c for c in CASES if c[0] in (7, 60)], ids=_id)
def test_ppf_inverts_cdf_and_isf_inverts_sf(case: tuple[int, Fraction], path: Path) -> None:
    d, p = discrete.frozen_on_path(_simple(case[0]), case[1], path)
    discrete.check_ppf_inverts_cdf(d, ExactTable.simple(case[0], p),
                                   path.dps if path.kind == "mp" else None)


@pytest.mark.parametrize("path", [Path.exact(20), Path.mp(20), Path.float64()],
                         ids=["exact", "mp20", "float"])
def test_arrays_in_arrays_out_and_refusals(path: Path) -> None:
    d, _ = discrete.frozen_on_path(_simple(10), Fraction(3, 10), path)
    discrete.check_array_shapes(d, path)
    discrete.check_refusals(d)


@pytest.mark.parametrize(("N", "p"), [(10**3, 1e-3), (3 * 10**4, 4e-5), (3 * 10**4, 1e-3)])
def test_large_N_paths_agree(N: int, p: float) -> None:
    """No Fraction reference at this N: the paths agree with each other (see the check)."""
    discrete.check_paths_agree(lambda dps: symhx.distribution_of(N, p, dps=dps))
