"""Every higher-order space's frozen distribution passes the conformance checks of every frozen
discrete distribution (:mod:`tests.harness.discrete`) on a log grid of N and p, on its three
paths: exact ``p``, float ``p`` at ``dps`` digits, and float64 (``dps=None``).

Reference: the weight of ``X = k`` summed from Burnside circuit counts of every visit pattern of
the space times ``p**length`` (or ``p**k``), exactly (:func:`tests.reference.spaces.space_weights`);
every derived quantity by its definition. A float ``p`` is taken at its exact binary value.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import symhx
from tests.harness.discrete import (
    NS,
    PS,
    Path,
    check_array_shapes,
    check_frozen,
    check_paths_agree,
    check_ppf_inverts_cdf,
    check_refusals,
    check_rvs,
    frozen_on_path,
)
from tests.reference.distribution import ExactTable
from tests.reference.spaces import space_weights

SPACES = ("eq41", "eq41-printed", "excess<=2", "eq41;distinct", "excess<=1;distinct")
CASES = [(s, N, p) for s in SPACES for N in NS for p in PS
         if not (N == 60 and p in (Fraction(1), Fraction(3)))]
PATHS = [Path.exact(30), Path.mp(25), Path.mp(60), Path.float64(rtol=1e-11)]


def _space(space: str, N: int):
    return lambda p, dps: symhx.distribution_of(N, p, space=space, dps=dps)


def _table(space: str, N: int, p: Fraction) -> ExactTable:
    return ExactTable.of(space_weights(N, p, space))


def _id(case: tuple[str, int, Fraction]) -> str:
    return f"{case[0]}-N{case[1]}-p{case[2]}"


@pytest.mark.parametrize("path", PATHS, ids=lambda x: f"{x.kind}{x.dps or ''}")
@pytest.mark.parametrize("case", CASES, ids=_id)
def test_every_method_agrees_with_burnside_weights(case: tuple[str, int, Fraction],
                                                    path: Path) -> None:
    space, N, p0 = case
    d, p = frozen_on_path(_space(space, N), p0, path)
    check_frozen(d, _table(space, N, p), path)


@pytest.mark.parametrize("path", [Path.exact(30), Path.mp(30)], ids=["exact", "mp30"])
@pytest.mark.parametrize("case", [c for c in CASES if c[1] in (7, 60)], ids=_id)
def test_ppf_inverts_cdf_and_isf_inverts_sf(case: tuple[str, int, Fraction], path: Path) -> None:
    space, N, p0 = case
    d, p = frozen_on_path(_space(space, N), p0, path)
    check_ppf_inverts_cdf(d, _table(space, N, p), path.dps if path.kind == "mp" else None)


@pytest.mark.parametrize("space", SPACES)
@pytest.mark.parametrize("path", [Path.exact(20), Path.mp(20), Path.float64()],
                         ids=["exact", "mp20", "float"])
def test_arrays_in_arrays_out_and_refusals(space: str, path: Path) -> None:
    d, _ = frozen_on_path(_space(space, 10), Fraction(3, 10), path)
    check_array_shapes(d, path)
    check_refusals(d)


def test_rvs_follows_the_pmf_and_its_seed() -> None:
    """N = 30, p = 0.05 in eq. (41): 40000 draws against the exact pmf of the float's value."""
    d = symhx.distribution_of(30, 0.05, space="eq41", dps=20)
    check_rvs(d, _table("eq41", 30, Fraction(0.05)), size=40_000, seed=123)


def test_exact_cdf_plus_sf_is_one_exactly_on_random_rationals() -> None:
    rng = np.random.default_rng(5)
    for _ in range(30):
        N = int(rng.integers(1, 200))
        p = Fraction(int(rng.integers(1, 10**6)), int(rng.integers(1, 10**7)))
        d = symhx.distribution_of(N, p, space=str(rng.choice(["simple", "eq41"])))
        k = int(rng.integers(0, N + 2))
        assert d.cdf(k) + d.sf(k) == 1


@pytest.mark.parametrize(("N", "p"), [(10**3, 1e-3), (3 * 10**4, 4e-5), (3 * 10**4, 1e-3)])
def test_large_N_paths_agree(N: int, p: float) -> None:
    """No Fraction reference at this N: the paths agree with each other (see the check)."""
    check_paths_agree(lambda dps: symhx.distribution_of(N, p, space="eq41", dps=dps))
