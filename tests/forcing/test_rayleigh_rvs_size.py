"""``RayleighSum.rvs`` checks its size like every ``rvs`` (issue 28, item 7): a negative or
fractional size names ``size``; more than ``MAX_SAMPLE_SIZE`` draws (the limit of every ``rvs``)
are refused at once."""

from __future__ import annotations

import time

import numpy as np

import symhx
from symhx.validation import MAX_SAMPLE_SIZE
from tests.harness.errors import assert_refuses


def test_rayleigh_sum_rvs_refuses_bad_sizes_naming_size():
    r = symhx.RayleighSum([1, 1])
    assert_refuses(r.rvs, -1, arg="size", value="-1", allowed=">= 0")
    assert_refuses(r.rvs, 2.5, exc=TypeError, arg="size", value="2.5")
    t0 = time.perf_counter()
    assert_refuses(r.rvs, 10**12, arg="size", allowed="MAX_SAMPLE_SIZE")
    assert time.perf_counter() - t0 < 1.0


def test_rayleigh_sum_rvs_keeps_shapes_and_the_distribution():
    r = symhx.RayleighSum([1, 2])
    x = r.rvs((200, 50), random_state=3)
    assert x.shape == (200, 50) and isinstance(r.rvs(random_state=3), float)
    # independent: E[Rayleigh(s)] = s sqrt(pi/2), so E[S] = 3 sqrt(pi/2); 1e4 draws, sd ~ 1.3
    assert abs(x.mean() - 3 * np.sqrt(np.pi / 2)) < 5 * 1.3 / 100


def test_rayleigh_sum_rvs_refuses_a_string_size_naming_size():
    r = symhx.RayleighSum([1, 2])
    for bad in ("3", b"3"):
        assert_refuses(r.rvs, bad, exc=TypeError, arg="size", value=repr(bad),
                       allowed=["None", "int >= 0", "tuple"])


def test_rayleigh_sum_rvs_has_the_sample_size_limit_of_every_rvs():
    """The same size rules and limit as the distributions' ``rvs``: a shape is a tuple (a list,
    empty or not, is refused naming ``size``), at most ``MAX_SAMPLE_SIZE`` draws in any shape,
    one more refused before any draw."""
    r = symhx.RayleighSum([1, 2])
    assert r.rvs((3, 2), random_state=1).shape == (3, 2)
    for bad in ([3, 2], []):
        assert_refuses(r.rvs, bad, exc=TypeError, arg="size")
    for too_many in (MAX_SAMPLE_SIZE + 1, (MAX_SAMPLE_SIZE // 2 + 1, 2)):
        t0 = time.perf_counter()
        assert_refuses(r.rvs, too_many, arg="size", allowed="MAX_SAMPLE_SIZE")
        assert time.perf_counter() - t0 < 0.5
    big = symhx.distribution_of(10, 0.1)
    assert_refuses(big.rvs, MAX_SAMPLE_SIZE + 1, arg="size", allowed="MAX_SAMPLE_SIZE")
