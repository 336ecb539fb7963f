"""``symhx.impact.fast`` and its C extension ``_fast``: the C port runs the same IEEE operations in
the same order as the Python float64 engine (``engine.py``), so the two are equal bit for bit --
a promise checked here on named rows that reach rare paths and on a few hundred seeded random
rows (``tests.harness.twins``); the float64 engines against the mpmath engine impact by impact;
the C row set-up; the ensemble kernel ``count_impacts``; and that the loaded extension was built
from the ``_fast.c`` on disk.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np
import pytest

import symhx.impact
from symhx.impact import IMPACT, SQRT2, STICK, PipeRow, SimulationError, simulate
from symhx.impact import fast as fast_mod
from symhx.impact.engine import FloatContext, default_v_stick, row_arrays
from symhx.impact.fast import available, count_impacts
from tests.harness.twins import check_twins

pytestmark = pytest.mark.skipif(not available(), reason="C extension not built")

# the C engine's event rules are also run, against the Python port, by the rules' and twins'
# tests of engine.py: mutation testing of _fast.c runs them too (scripts/mutation.py)
MUTATION_ALSO = ("tests/impact/test_engine_rules.py", "tests/impact/test_engine_twin.py",
                 "tests/impact/test_simulate.py")


def _table(h):
    return np.column_stack([h.times, h.sites, h.kinds, h.u_before, h.u_after, h.aux])


def _bit_identical(a, b, case=None):
    """Every number of every event and of every closed-form piece equal, not close."""
    assert np.array_equal(_table(a), _table(b)), "event tables differ"
    (sa, ca), (sb, cb) = a.pieces(), b.pieces()
    assert len(sa) == len(sb)
    for j in range(len(sa)):
        assert sa[j] == sb[j], f"piece start times of body {j} differ"
        assert np.array_equal(np.asarray(ca[j], dtype=float), np.asarray(cb[j], dtype=float)), j


# ----------------------------------------------------------------- the build
def test_loaded_extension_is_built_from_the_source_on_disk():
    src = Path(symhx.impact.__file__).with_name("_fast.c")
    if not src.exists():
        pytest.skip("installed without its C source (nothing to compare)")
    want = hashlib.sha256(src.read_bytes()).hexdigest()
    got = fast_mod.source_sha256()
    assert got == want, (
        f"the loaded C extension symhx.impact._fast was built from another _fast.c (its SHA-256 "
        f"{got}, the file's {want}): it is stale. Rebuild it with "
        "`python setup.py build_ext --inplace` (or `pip install -e .`) and rerun the tests.")


# ----------------------------------------------------------------- C = Python, named rows
def _rows():
    # forced elastic, inelastic, plastic (r = 0: sticking, releases), chatter-prone r = 0.5,
    # two forcing frequencies (one of them 0: a constant force), omega and d not 1
    yield PipeRow.random(10, 0.3, seed=1, restitution=0.8), 30.0
    yield PipeRow.random(12, 0.5, seed=4, restitution=0.0), 40.0
    yield PipeRow.random(8, 0.6, seed=5, restitution=0.5), 60.0
    yield PipeRow.random(6, 0.4, seed=7, restitution=1.0, Omega=(0.0, 2.3), omega=1.7,
                         d=0.6), 25.0
    yield PipeRow.random(30, 1.0, seed=3, restitution=0.3, Omega=(SQRT2, 0.37), d=3.0), 15.0
    # twelve pipes over a longer run: plastic, chatter-prone, elastic
    yield PipeRow.random(12, 0.5, seed=4, restitution=0.0), 60.0
    yield PipeRow.random(12, 0.6, seed=5, restitution=0.5), 60.0
    yield PipeRow.random(12, 0.4, seed=6, restitution=1.0), 60.0


@pytest.mark.parametrize("k", range(8))
def test_c_and_python_float_engines_bit_identical(k):
    row, t_end = list(_rows())[k]
    a = simulate(row, t_end, engine="python")
    b = simulate(row, t_end, engine="c")
    assert len(a) >= 20
    # same IEEE operations in the same order: every number of every event equal, not close
    _bit_identical(a, b)
    ts = np.linspace(0.0, t_end, 37)
    xa, va = a.states(ts)
    xb, vb = b.states(ts)
    assert np.array_equal(xa, xb) and np.array_equal(va, vb)


def _chatter_row(r, alpha, d=1.0):
    # one pipe under a constant force alpha (Omega = 0) started at rest at x0 = d/2
    return PipeRow(1, d=d, restitution=r, Omega=(0.0,), alpha=[[alpha]], beta=[[0.0]],
                   x0=[d / 2], v0=[0.0])


def _rare_rows():
    yield PipeRow.random(6, 2.0, seed=0, restitution=0.0, Omega=(0.0, 2.3, 0.37), omega=1.7,
                         d=0.6), 25.0, {}
    yield PipeRow.random(6, 0.5, seed=2, restitution=0.5, Omega=(0.0, 2.3, 0.37), omega=1.7,
                         d=0.6), 25.0, {}
    yield PipeRow.random(6, 2.0, seed=1, restitution=0.0, Omega=(0.0, 2.3, 0.37), omega=1.7,
                         d=0.6), 25.0, {}
    yield PipeRow.random(5, 10.0, seed=0, restitution=0.3), 30.0, {}
    yield PipeRow.random(7, 1.0, seed=1, restitution=0.0, omega=0.5, d=6.0,
                         Omega=(1.3, 0.9)), 100.0, {}
    yield _chatter_row(0.4, 3.0, d=0.6), 6.0, {}
    yield PipeRow(2, restitution=0.1, alpha=np.zeros((2, 1)), beta=np.zeros((2, 1)),
                  x0=[1.0, 2.0], v0=[-2.0, -4.0]), 0.6, {"v_stick": 1e-300}


@pytest.mark.parametrize("k", range(7))
def test_rare_paths_c_equals_python(k):
    # K = 3 forcing frequencies with a constant one, d != 1, plastic rows, a huge sigma, a
    # chatter, a 1e-300 chatter threshold (a cascade at one instant)
    row, t_end, kw = list(_rare_rows())[k]
    a = simulate(row, t_end, engine="c", **kw)
    b = simulate(row, t_end, engine="python", **kw)
    assert len(a) > 3
    _bit_identical(a, b)


def test_fortran_ordered_inputs():
    row = PipeRow.random(9, 0.4, seed=2, restitution=0.8, Omega=(SQRT2, 0.3, 2.2))
    rowF = PipeRow(9, restitution=0.8, Omega=(SQRT2, 0.3, 2.2), alpha=np.asfortranarray(row.alpha),
                   beta=np.asfortranarray(row.beta), x0=row.x0, v0=row.v0)
    assert not rowF.alpha.flags.c_contiguous
    a, b = simulate(row, 20.0), simulate(rowF, 20.0)
    assert len(a) > 10 and np.array_equal(_table(a), _table(b))
    # the contiguous copies made for the C engine keep the caller's event cap (and no cap)
    with pytest.raises(SimulationError, match="max_events=10 "):
        simulate(rowF, 20.0, max_events=10)
    assert len(simulate(rowF, 20.0, max_events=len(a))) == len(a)
    vs = default_v_stick(row, None)
    c = fast_mod.simulate_c(rowF, 20.0, v_stick=vs)
    assert np.array_equal(_table(c), _table(fast_mod.simulate_c(row, 20.0, v_stick=vs)))


# ----------------------------------------------------------------- C = Python, seeded twins
def _twin_rows(count, seed):
    """``count`` seeded random rows over every regime the float64 engines serve cheaply: 1..14
    pipes, restitution 0 .. 1, sigma 0.1 .. 2 (times d), omega 0.3 .. 3 (away from resonance:
    ``|omega^2 - Omega^2| >= omega^2 / 4``), one or two forcing frequencies (a constant force
    among them), d != 1."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        n = int(rng.integers(1, 15))
        r = float(rng.choice([0.0, 0.3, 0.5, 0.8, 1.0]))
        sigma = float(np.exp(rng.uniform(np.log(0.1), np.log(2.0))))
        omega = float(np.exp(rng.uniform(np.log(0.3), np.log(3.0))))
        Omega = ((SQRT2,), (0.0, 2.3), (0.37, 1.9))[len(out) % 3]
        d = float(rng.choice([1.0, 0.6, 2.5]))
        seed_k = int(rng.integers(2**31))
        if min(abs(omega**2 - float(w) ** 2) for w in Omega) < omega**2 / 4:
            continue
        try:
            row = PipeRow.random(n, sigma * d, seed=seed_k, restitution=r, omega=omega, d=d,
                                 Omega=Omega)
        except ValueError:      # no non-overlapping start: not a case
            continue
        out.append((row, 12.0 / omega))
    return out


@pytest.mark.slow
def test_twins_c_equals_python_on_seeded_random_rows():
    cases = _twin_rows(300, 20261127)
    # and exact grazes (x = 1 + sin t touches both walls with zero velocity), any restitution
    cases += [(PipeRow(1, restitution=r, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[1.0]), 20.0)
              for r in (0.0, 0.5, 1.0)]
    checked = check_twins(lambda row, t: simulate(row, t, engine="c"),
                          lambda row, t: simulate(row, t, engine="python"), cases,
                          _bit_identical)
    assert checked == len(cases)
    # the cases reach sticking, releases and grazes, not only impacts
    kinds = np.concatenate([simulate(row, t).kinds for row, t in cases])
    assert all(np.any(kinds == k) for k in range(4))


def _clusters(h, tol=1e-9):
    """Events grouped into clusters closer than ``tol`` in time: near-simultaneous events (a
    plastic cascade 1e-16 apart in mpmath is one instant in float64) may be resolved in a
    different order, but each cluster must involve the same contact sites at the same time."""
    out = []
    for t, site, kind in zip(h.times, h.sites, h.kinds, strict=True):
        t = float(t)
        if out and t - out[-1][1] <= tol:
            out[-1][1] = t
            out[-1][2].add((int(site), kind == 1))
        else:
            out.append([t, t, {(int(site), kind == 1)}])
    return out


def _same_clusters(ref, fl, case=None):
    a, b = _clusters(ref), _clusters(fl)
    assert [c[2] for c in a] == [c[2] for c in b], "event clusters differ"
    err = max((abs(x[0] - y[0]) for x, y in zip(a, b, strict=True)), default=0.0)
    assert err < 1e-9, err
    if len(a) == len(ref):      # no near-simultaneous events: event by event
        assert fl.kinds.tolist() == ref.kinds.tolist()


def _rows50():
    rng = np.random.default_rng(5)
    for k in range(50):
        yield PipeRow.random(int(rng.integers(2, 12)), float(rng.uniform(0.1, 0.6)), seed=k,
                             restitution=float(rng.choice([0.0, 0.5, 0.8, 1.0])))


@pytest.mark.parametrize("chunk", range(5))
def test_float_and_mpmath_engines_agree_on_50_rows(chunk):
    # equal v_stick in both engines: the same event clusters (sites; graze or contact), times
    # within 1e-9; rows without near-simultaneous events must match event by event
    cases = [(row,) for idx, row in enumerate(_rows50()) if idx % 5 == chunk]
    check_twins(lambda row: simulate(row, 8.0, dps=20, v_stick=1e-6),
                lambda row: simulate(row, 8.0, v_stick=1e-6), cases, _same_clusters)


@pytest.mark.parametrize("seed, r", [(1, 1.0), (2, 0.8), (3, 0.95)])
def test_fast_matches_reference_impact_by_impact(seed, r):
    row = PipeRow.random(10, 0.3, seed=seed, restitution=r)
    ref = simulate(row, 25.0, dps=30)
    fast = simulate(row, 25.0)
    assert len(ref) >= 30
    assert fast.sites.tolist() == ref.sites.tolist()
    assert fast.kinds.tolist() == ref.kinds.tolist()
    err = max(abs(float(a) - b) for a, b in zip(ref.times, fast.times, strict=True))
    assert err < 1e-9


# ----------------------------------------------------------------- the C row set-up
@pytest.mark.parametrize("k", range(5))
def test_c_row_setup_bit_identical_to_row_arrays(k):
    row, _ = list(_rows())[k]
    F, out = fast_mod._call(row, 1e-9, 0.0, 1e-6, True, None)
    coef0 = np.frombuffer(out[4], dtype=np.float64).reshape(row.n + 2, -1)
    ra = row_arrays(row, FloatContext())
    assert F == ra.F.tolist()
    assert np.array_equal(coef0, ra.coef)


def test_row_setup_independent_closed_form():
    # x_j(0) and x_j'(0) of every pipe from the coefficients equal the row's x0, v0 (eq. 21)
    row = PipeRow.random(7, 0.8, seed=11, restitution=0.8, Omega=(SQRT2, 0.5), omega=1.3)
    _, out = fast_mod._call(row, 1e-9, 0.0, 1e-6, True, None)
    c = np.frombuffer(out[4], dtype=np.float64).reshape(row.n + 2, -1)
    F = np.array([row.omega, *row.omega_float()])
    x = c[:, 0] + c[:, 1::2].sum(axis=1)
    v = (c[:, 2::2] * F).sum(axis=1)
    np.testing.assert_allclose(x[1:-1], row.x0, rtol=0, atol=1e-13)
    np.testing.assert_allclose(v[1:-1], row.v0, rtol=0, atol=1e-13)
    assert x[0] == 0.0 and x[-1] == (row.n + 1) * row.d
    # the forced part: amplitudes alpha / (omega^2 - Omega^2) straight from the row
    den = row.omega**2 - F[1:] ** 2
    np.testing.assert_allclose(c[1:-1, 3::2], row.alpha / den, rtol=1e-15)
    np.testing.assert_allclose(c[1:-1, 4::2], row.beta / den, rtol=1e-15)


# ----------------------------------------------------------------- the ensemble kernel
def test_count_impacts_matches_history():
    row = PipeRow.random(30, 0.3, seed=9, restitution=0.8)
    h = simulate(row, 80.0)
    counts, nev = count_impacts(row, 80.0, 40.0)
    assert nev == len(h)
    sel = np.isin(h.kinds, (IMPACT, STICK)) & (h.times >= 40.0)
    assert counts.tolist() == np.bincount(h.sites[sel], minlength=31).tolist()


@pytest.mark.parametrize("v_stick", [None, 0.05])
def test_count_impacts_takes_v_stick_and_falls_back_to_the_python_engine(v_stick, monkeypatch):
    # a chattering row whose counts depend on v_stick (63 impacts by default, 32 at 0.05): the
    # counts are those of simulate() with the same v_stick, from the C kernel and, without the
    # extension, from the Python engine; the events are the history's rows but the sticks
    # (a stick is part of the impact it ends: it used to count twice without the extension)
    row = PipeRow.random(6, 0.5, seed=6, restitution=0.5, Omega=(0.37, 2.1))
    h = simulate(row, 30.0, v_stick=v_stick)
    assert np.any(h.kinds == STICK)
    sel = np.isin(h.kinds, (IMPACT, STICK)) & (h.times >= 5.0)
    want = (np.bincount(h.sites[sel], minlength=7).tolist(), int(np.sum(h.kinds != STICK)))
    counts, nev = count_impacts(row, 30.0, 5.0, v_stick=v_stick)
    assert (counts.tolist(), nev) == want
    monkeypatch.setattr(fast_mod, "_fast", None)
    counts, nev = count_impacts(row, 30.0, 5.0, v_stick=v_stick)
    assert (counts.tolist(), nev) == want
    assert sum(count_impacts(row, 30.0, 0.0)[0]) != sum(count_impacts(row, 30.0, 0.0,
                                                                      v_stick=0.05)[0])


def test_max_events_guard():
    row = PipeRow.random(20, 0.4, seed=1, restitution=1.0)
    with pytest.raises(RuntimeError, match="max_events"):
        simulate(row, 100.0, max_events=10)


def test_the_c_engine_without_its_extension_says_it_is_not_built(monkeypatch):
    row = PipeRow.random(3, 0.4, seed=1)
    monkeypatch.setattr(fast_mod, "_fast", None)
    assert not available() and fast_mod.source_sha256() is None
    with pytest.raises(SimulationError, match=r"C extension symhx\.impact\._fast is not built"):
        fast_mod.simulate_c(row, 5.0, v_stick=0.01)


def test_simulation_error_is_runtime_error():
    row = PipeRow.random(20, 0.4, seed=1, restitution=1.0)
    with pytest.raises(SimulationError, match="max_events"):
        count_impacts(row, 100.0, 0.0, max_events=10)
    assert issubclass(SimulationError, RuntimeError)
