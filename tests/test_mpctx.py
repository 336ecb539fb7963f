"""symhx._mpctx: one private mpmath context per thread, and the conversions at its borders."""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor

import mpmath
import pytest
import sympy

import symhx
import symhx.asymptotics
import symhx.circuits
import symhx.spaces
from symhx._mpctx import export, is_mpf, local, make_mpf, mp, prec_of_dps


def test_each_thread_has_its_own_context():
    seen: dict[str, int] = {}
    barrier = threading.Barrier(2)

    def work(name: str, dps: int) -> None:
        ctx = mp()
        with ctx.workdps(dps):
            barrier.wait()  # both are inside their blocks now
            seen[name] = ctx.dps
            seen[name + " id"] = id(ctx)
            barrier.wait()

    before = mpmath.mp.prec
    with ThreadPoolExecutor(2) as ex:
        list(ex.map(lambda a: work(*a), [("a", 10), ("b", 70)]))
    assert seen["a"] == 10 and seen["b"] == 70 and seen["a id"] != seen["b id"]
    assert mp() is mp() and mpmath.mp.prec == before


def test_export_and_local_keep_the_bits():
    ctx = mp()
    with ctx.workdps(40):
        x = ctx.mpf(2) / 3
    g = export(x)
    assert type(g) is mpmath.mpf and g._mpf_ == x._mpf_
    assert type(local(g)) is ctx.mpf and local(g)._mpf_ == x._mpf_
    assert export((x, [x], {"a": x}, 7)) == (g, [g], {"a": g}, 7)
    z = mpmath.mpc(1, 2)
    assert type(local(z)) is ctx.mpc and export(local(z)) == z
    assert type(export(local(z))) is mpmath.mpc
    assert local("text") == "text" and make_mpf(x._mpf_) == g


@pytest.mark.parametrize("dps", [1, 5, 15, 16, 50, 1000])
def test_export_rounds_like_workdps(dps):
    ctx = mp()
    with ctx.workdps(dps + 30):
        x = ctx.pi() / 7
    with mpmath.workdps(dps):
        ref = +mpmath.mp.make_mpf(x._mpf_)
    assert export(x, dps)._mpf_ == ref._mpf_
    assert prec_of_dps(dps) == mpmath.libmp.dps_to_prec(dps)
    # containers element-wise, each value rounded once
    got = export({"a": x, "b": [x, (x,)]}, dps)
    assert got["a"]._mpf_ == got["b"][0]._mpf_ == got["b"][1][0]._mpf_ == ref._mpf_
    # a complex value: both parts rounded once, as +z inside workdps(dps) rounds them
    with ctx.workdps(dps + 30):
        z = ctx.mpc(x, ctx.e() / 3)
    with mpmath.workdps(dps):
        zref = +mpmath.mp.make_mpc(z._mpc_)
    got = export(z, dps)
    assert type(got) is mpmath.mpc and got._mpc_ == zref._mpc_


def test_is_mpf_of_every_context_and_nothing_else():
    ctx = mp()
    assert is_mpf(mpmath.mpf(1)) and is_mpf(ctx.mpf(1)) and is_mpf(mpmath.MPContext().mpf(3))
    assert not is_mpf(sympy.Float(1.5)) and not is_mpf(1.5) and not is_mpf(mpmath.mpc(1))


def test_the_users_global_precision_has_no_effect():
    ref = (symhx.critical_point(10**40, dps=30).p, symhx.asymptotic_critical_point(10**9).q,
           symhx.pmf(50, 0.03, 20, space="eq41", dps=25))
    old = mpmath.mp.dps
    try:
        for dps in (3, 200):
            mpmath.mp.dps = dps
            got = (symhx.critical_point(10**40, dps=30).p,
                   symhx.asymptotic_critical_point(10**9).q,
                   symhx.pmf(50, 0.03, 20, space="eq41", dps=25))
            assert [g._mpf_ for g in got] == [r._mpf_ for r in ref]
    finally:
        mpmath.mp.dps = old


def _mpfs(x):
    """Every mpmath number inside a result (dataclass fields, containers, arrays)."""
    import dataclasses

    import numpy as np

    if hasattr(x, "_mpf_") and not isinstance(x, sympy.Basic):
        yield x
    elif isinstance(x, np.ndarray):
        for v in x.ravel().tolist():
            yield from _mpfs(v)
    elif isinstance(x, (list, tuple)):
        for v in x:
            yield from _mpfs(v)
    elif isinstance(x, dict):
        for v in x.values():
            yield from _mpfs(v)
    elif dataclasses.is_dataclass(x) and not isinstance(x, type):
        for f in dataclasses.fields(x):
            yield from _mpfs(getattr(x, f.name))


def test_public_results_are_plain_global_mpf():
    results = [
        symhx.critical_point(10**20, dps=25), symhx.critical_point(60, space="eq41", dps=20),
        symhx.mode_path(200, p_max="0.05", dps=20).breakpoints, symhx.discriminant_root(99),
        symhx.asymptotic_critical_point(10**8, order="relaxed"),
        symhx.asymptotics.pd_series(10**5), symhx.error_table((10**3,), dps=20),
        symhx.circuits.log_phi(10**9, 7), symhx.pmf(40, 0.03, [1, 5], space="eq41", dps=20),
        symhx.logpmf(40, 0.03, 5, space="eq41", dps=20),
        symhx.distribution_of(30, 0.05, space="excess<=2", dps=15).table(),
        symhx.spaces.class_decomposition(20, 0.05, dps=20).joint,
        symhx.spaces.class_probabilities(20, 0.05, dps=20),
    ]
    found = [v for r in results for v in _mpfs(r)]
    assert len(found) > 100 and all(type(v) is mpmath.mpf for v in found)
