"""Work limits of the higher-order spaces (issue 28, item 5): ``MAX_SPACE_WORK`` bounds
``N * (m + 1)`` for every computation that scans ``k = 1..N``, checked before any work by the
API and the CLI alike; class counts beyond ``MAX_COUNT_BITS`` and bad ``k`` / ``shape`` are
refusals that name the argument."""

from __future__ import annotations

import time
from fractions import Fraction

import pytest

import symhx
import symhx.spaces as S
from symhx.circuits import circuit_count
from symhx.cli import main
from tests.harness.errors import assert_refuses
from tests.reference.spaces import members, visits

REFUSALS = [
    (S.critical_point, dict(space="eq41", dps=20)),
    (S.root_estimates, dict(space="eq41")),
    (S.modes, dict(p=Fraction(1, 50), space="eq41")),
    (S.distribution, dict(p=0.02, space="eq41", dps=20)),
    (S.distribution, dict(p=0.02, space="eq41", dps=None)),
]


@pytest.mark.parametrize("fn, kw", REFUSALS, ids=lambda x: getattr(x, "__name__", ""))
@pytest.mark.parametrize("N", [2 * 10**7, 10**20, 10**1000])
def test_every_scan_over_a_space_refuses_N_beyond_the_work_limit_at_once(fn, kw, N):
    kw = dict(kw)
    if fn is S.root_estimates:
        args: tuple = (kw.pop("space"), N)
    elif fn in (S.modes, S.distribution):
        args = (N, kw.pop("p"))
    else:
        args = (N,)
    t0 = time.perf_counter()
    assert_refuses(fn, *args, **kw, arg="N", allowed=["N <= 1000000", "MAX_SPACE_WORK"])
    assert time.perf_counter() - t0 < 1.0


def test_the_limit_scales_with_the_largest_excess():
    # N * (m + 1) <= MAX_SPACE_WORK: excess<=25 has 26 levels
    assert S.space_n_limit(S.parse_space("excess<=25")) == S.MAX_SPACE_WORK // 26
    t0 = time.perf_counter()
    assert_refuses(S.critical_point, 10**6, space="excess<=25", dps=20, arg="N",
                   value="N=1000000", allowed=f"N <= {S.MAX_SPACE_WORK // 26}")
    assert time.perf_counter() - t0 < 2.0


def test_the_limit_is_inclusive_and_the_constant_is_honoured(monkeypatch):
    monkeypatch.setattr(S._classes, "MAX_SPACE_WORK", 4 * 60)
    cp = S.critical_point(60, space="eq41", dps=15)  # N * 4 == limit: allowed
    assert cp.k_before == 1
    assert_refuses(S.critical_point, 61, space="eq41", dps=15, arg="N", value="N=61",
                   allowed="N <= 60")
    # the simple space has no such scan: it is never refused by this limit
    assert S.critical_point(10**30, space="simple", dps=15).k_before == 1


def test_the_cli_uses_the_same_limit(capsys):
    assert main(["spaces", str(2 * 10**6), "--space", "eq41"]) == 2
    err = capsys.readouterr().err
    assert "N <= 1000000" in err and "MAX_SPACE_WORK" in err


def test_exact_sums_over_a_space_refuse_a_huge_rational_p_at_once():
    d = S.distribution(101, Fraction(1, 10**5000), space="eq41")
    t0 = time.perf_counter()
    for method in (d.mean, d.var, lambda: d.cdf(3)):
        msg = assert_refuses(method, arg="p", value="1.0e-5000",
                             allowed="EXACT_WORK_LIMIT")
        assert len(msg) < 600
    assert time.perf_counter() - t0 < 1.0


def test_the_cli_refuses_a_tiny_exact_p_over_eq41_quickly(capsys):
    t0 = time.perf_counter()
    assert main(["spaces", "101", "1e-5000", "--space", "eq41"]) == 2
    assert time.perf_counter() - t0 < 10.0
    assert "EXACT_WORK_LIMIT" in capsys.readouterr().err


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=4", "excess<=6;distinct"])
def test_boundary_values_of_U_match_burnside_counts(space):
    """``U_e(k) phi_N(k) = D * (circuits of the space with k distinct vertices and excess e)``
    at every k, the boundary region included, against Burnside's count of each pattern."""
    sp = S.parse_space(space)
    mem = members(space)
    N = 9
    for k in range(1, N + 1):
        want = [0] * (sp.max_excess + 1)
        for s in mem.shapes:
            if mem.counts(s, k):
                want[sum(x - 1 for x in s)] += circuit_count(N, visits(s, k))
        got = [Fraction(u * symhx.phi(N, k), sp.denominator) for u in sp.U(k)]
        assert got == want, (space, k)


def test_class_count_beyond_the_count_bits_is_a_refusal_naming_k():
    for fn, args in ((S.class_count, (10**30, (2,), 10**30)), (S.eq41_terms, (10**30, 10**30)),
                     (S.class_count, (2**64, (3,), 2**63 + 1))):
        assert_refuses(fn, *args, arg="k", allowed="MAX_COUNT_BITS")


def test_class_count_of_a_large_but_allowed_k_is_exact():
    N, k = 10**6, 50
    assert S.class_count(N, (2,), k) == circuit_count(N, visits((2,), k))


def test_bad_shape_and_k_refusals_name_the_argument():
    assert_refuses(S.class_count, 10, (1, 2), 3, arg="shape", value="(1, 2)",
                   allowed="parts > 1")
    assert_refuses(S._classes.visits_of, (2, 2), 1, arg="k", value="k=1",
                   allowed="k must be >= 2")
