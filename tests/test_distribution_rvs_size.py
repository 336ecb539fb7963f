"""``Distribution.rvs`` refuses, before any work, more draws than ``MAX_SAMPLE_SIZE`` and a size
that is not a non-negative int (issue 28, item 7)."""

from __future__ import annotations

import time

import numpy as np

import symhx
from symhx.validation import MAX_SAMPLE_SIZE
from tests.harness.errors import assert_refuses


def test_rvs_refuses_a_huge_size_at_once_without_allocating():
    d = symhx.distribution_of(101, 0.02)
    t0 = time.perf_counter()
    assert_refuses(d.rvs, 10**12, arg="size", value="1000000000000",
                   allowed="MAX_SAMPLE_SIZE")
    assert_refuses(d.rvs, (10**6, 10**6), arg="size", allowed="MAX_SAMPLE_SIZE")
    assert time.perf_counter() - t0 < 1.0


def test_rvs_refuses_negative_and_fractional_sizes_naming_size():
    d = symhx.distribution_of(101, 0.02, space="eq41")
    assert_refuses(d.rvs, -1, arg="size", value="-1", allowed=">= 0")
    assert_refuses(d.rvs, 2.5, exc=TypeError, arg="size", value="2.5")


def test_rvs_shapes_and_seeds_are_kept():
    d = symhx.distribution_of(101, 0.02)
    a = d.rvs((2, 3), random_state=7)
    assert a.shape == (2, 3) and a.dtype == np.int64
    assert (a == d.rvs((2, 3), random_state=7)).all()
    assert d.rvs(0).shape == (0,) and isinstance(d.rvs(random_state=1), int)
    assert MAX_SAMPLE_SIZE >= 10**6
