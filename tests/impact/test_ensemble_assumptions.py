"""The assumption checks of ``symhx.impact.ensemble``: the sequences of impact sites
(``site_transitions``) against the runs' full histories, their dependence statistic
(``transition_dependence``) against its definition and a shuffled null computed here, and the
free-flight closure fraction of eq. (27) against a brute-force scan of every gap
(``tests.reference.impact``) and against ``symhx.impact_probability``."""

from __future__ import annotations

import importlib
import math
import warnings

import numpy as np
import pytest

from symhx.forcing import impact_probability
from symhx.impact import IMPACT, STICK, PipeRow, SimulationError, simulate
from symhx.impact.ensemble import (
    free_flight_closure_fraction,
    site_transitions,
    transition_dependence,
)
from tests.harness.errors import assert_refuses
from tests.reference.impact import brute_min_of_gap, mutual_information_by_definition
from tests.reference.seeds import run_seed_ref

E = importlib.import_module("symhx.impact.ensemble")


# ----------------------------------------------------------------- site sequences
def test_site_transitions_equal_hand_sequences():
    kw = dict(n=5, t_transient=4.0, t_window=5.0, seed=6)
    seqs = site_transitions(0.35, 3, restitution=0.5, sigma0=0.3, **kw)
    assert len(seqs) == 3
    for k, s in enumerate(seqs):
        row = PipeRow.random(5, 0.35, seed=run_seed_ref(6, 0.35, k), restitution=0.5, sigma0=0.3)
        h = simulate(row, 9.0, engine="python")
        ref = [int(site) for site, kind, t in zip(h.sites, h.kinds, h.times, strict=True)
               if kind in (IMPACT, STICK) and float(t) >= 4.0]
        assert s.tolist() == ref and s.dtype == np.int64
    assert sum(len(s) for s in seqs) > 0
    # defaults: n = 100, t in [200, 300], seed 0: at rest nothing happens
    (quiet,) = site_transitions(0.0, 1, sigma0=0.0)
    assert quiet.tolist() == []
    d = site_transitions(0.3, 1, n=4, t_transient=2, t_window=3)[0]
    row = PipeRow.random(4, 0.3, seed=run_seed_ref(0, 0.3, 0))
    h = simulate(row, 5.0, engine="python")
    assert d.tolist() == [int(x) for x, kind, t in zip(h.sites, h.kinds, h.times, strict=True)
                          if kind in (IMPACT, STICK) and t >= 2]


def test_site_transitions_window_start_is_inclusive():
    # t_transient set to the exact time of an impact: that impact belongs to the window
    row = PipeRow.random(5, 0.35, seed=run_seed_ref(6, 0.35, 0))
    h = simulate(row, 9.0)
    k = next(i for i in range(len(h)) if h.kinds[i] == IMPACT and h.times[i] > 1.0)
    t_k = float(h.times[k])
    (seq,) = site_transitions(0.35, 1, n=5, t_transient=t_k, t_window=9.0 - t_k, seed=6)
    ref = [int(s) for s, kind, t in zip(h.sites, h.kinds, h.times, strict=True)
           if kind in (IMPACT, STICK) and t_k <= t]
    assert seq.tolist()[0] == int(h.sites[k]) and seq.tolist() == ref[:len(seq)]


def test_site_transitions_default_row_and_window(monkeypatch):
    # the defaults reach the simulation: 100 pipes, r = 0.8, the ensemble's row 0 of seed 0,
    # the window [200, 300] (impacts and sticks counted, from t = 200 inclusive)
    S = importlib.import_module("symhx.impact.simulate")
    calls = []

    class Hist:
        times = np.array([199.5, 200.0, 250.0, 260.0, 299.0])
        kinds = np.array([IMPACT, IMPACT, 1, STICK, 3])
        sites = np.array([3, 4, 5, 6, 7])

    def fake(row, t_end):
        calls.append((row, t_end))
        return Hist()

    monkeypatch.setattr(S, "simulate", fake)
    (seq,) = site_transitions(0.2, 1)
    row, t_end = calls[0]
    assert t_end == 300.0 and row.n == 100 and row.restitution == 0.8
    ref = PipeRow.random(100, 0.2, seed=run_seed_ref(0, 0.2, 0))
    assert np.array_equal(row.x0, ref.x0) and np.array_equal(row.v0, ref.v0)
    assert seq.tolist() == [4, 6]


def test_site_transitions_failures_and_arguments(monkeypatch):
    S = importlib.import_module("symhx.impact.simulate")

    monkeypatch.setattr(S, "simulate", lambda row, t: (_ for _ in ()).throw(
        SimulationError("no")))
    out = site_transitions(0.3, 2, n=3, t_transient=1, t_window=1)
    assert [s.tolist() for s in out] == [[], []] and out[0].dtype == np.int64
    monkeypatch.undo()
    assert_refuses(site_transitions, 0.3, 0, arg="runs", value="0", allowed=">= 1")
    assert_refuses(site_transitions, 0.3, 1, t_transient=-1, arg="t_transient", value="-1",
                   allowed=">= 0")
    assert_refuses(site_transitions, 0.3, 1, t_window=0, arg="t_window", value="0",
                   allowed="> 0")


def test_site_transitions_refuses_bad_input():
    assert_refuses(site_transitions, "abc", 1, n=3, arg="sigma", value="'abc'")
    assert_refuses(site_transitions, -0.1, 1, n=3, arg="sigma", value="-0.1", allowed=">= 0")
    assert_refuses(site_transitions, -1, 1, n=3, arg="sigma", value="-1", allowed=">= 0")
    assert_refuses(site_transitions, 0.2, 1, n=3, seed=None, exc=TypeError, arg="seed",
                   value="None", allowed=["an int >= 0", "the rows of ensemble() need one"])
    assert_refuses(site_transitions, 0.2, 1, n=3, seed=-1, arg="seed", value="-1")
    assert_refuses(site_transitions, 10**400, 1, n=3, arg="sigma", allowed="float64 range")
    assert_refuses(site_transitions, "1e400", 1, n=3, arg="sigma", value="1.0e+400",
                   allowed="float64 range")


# ----------------------------------------------------------------- dependence statistic
def test_transition_dependence_detects_order_and_accepts_iid():
    rng = np.random.default_rng(3)
    iid = [rng.integers(0, 10, size=300) for _ in range(5)]
    res = transition_dependence(iid, 10, shuffles=40, seed=1)
    assert abs(res["z"]) < 4
    assert abs(res["same"] - 0.1) < 0.05
    walk = [np.cumsum(rng.choice([-1, 1], size=400)) % 10 for _ in range(3)]
    dep = transition_dependence(walk, 10, shuffles=40, seed=1)
    # |step| = 1 except across the wrap 9 <-> 0 (probability 1/5)
    assert dep["z"] > 10 and dep["adjacent"] > 0.7 > 0.3 > dep["adjacent_null"]


def test_transition_dependence_by_hand():
    seqs = [np.array([0, 1, 0, 1, 2]), np.array([3]), np.array([2, 2, 1]), np.array([], int)]
    a = [0, 1, 0, 1, 2, 2]
    b = [1, 0, 1, 2, 2, 1]
    out = transition_dependence(seqs, 4, shuffles=7, seed=3)
    assert out["pairs"] == 6
    assert out["mi"] == pytest.approx(mutual_information_by_definition(a, b, 4), rel=1e-12)
    assert out["same"] == pytest.approx(1 / 6) and out["adjacent"] == pytest.approx(5 / 6)
    # the null by hand: each sequence permuted, in order, with the same generator
    rng = np.random.default_rng(3)
    null, same, adj = [], [], []
    for _ in range(7):
        perm = [rng.permutation(s) for s in seqs]
        pa = [x for s in perm if len(s) > 1 for x in s[:-1]]
        pb = [x for s in perm if len(s) > 1 for x in s[1:]]
        null.append(mutual_information_by_definition(pa, pb, 4))
        same.append(np.mean(np.array(pa) == np.array(pb)))
        adj.append(np.mean(np.abs(np.array(pa) - np.array(pb)) == 1))
    assert out["mi_null"] == pytest.approx(np.mean(null), rel=1e-12)
    assert out["mi_null_sd"] == pytest.approx(np.std(null, ddof=1), rel=1e-12)
    assert out["z"] == pytest.approx((out["mi"] - np.mean(null)) / np.std(null, ddof=1))
    assert out["same_null"] == pytest.approx(np.mean(same), rel=1e-12)
    assert out["adjacent_null"] == pytest.approx(np.mean(adj), rel=1e-12)
    assert set(out) == {"pairs", "mi", "mi_null", "mi_null_sd", "z", "same", "same_null",
                        "adjacent", "adjacent_null"}
    # defaults: 50 shuffles, seed 0
    assert transition_dependence(seqs, 4) == transition_dependence(seqs, 4, shuffles=50, seed=0)
    # no pairs at all: every statistic undefined
    empty = transition_dependence([np.array([1]), np.array([], int)], 3, shuffles=3)
    assert empty["pairs"] == 0
    for key in ("mi", "mi_null", "z", "same", "same_null", "adjacent", "adjacent_null"):
        assert math.isnan(empty[key])
    # a null without spread: z undefined
    const = transition_dependence([np.array([2, 2, 2])], 3, shuffles=4)
    assert const["mi_null_sd"] == 0 and math.isnan(const["z"]) and const["same"] == 1.0
    # a custom statistic
    custom = transition_dependence(seqs, 4, shuffles=2, stat=lambda x, y: float(len(x)))
    assert custom["mi"] == 6.0 and custom["mi_null"] == 6.0


def test_transition_dependence_short_sequences_and_empty_pairs():
    seqs = [np.array([4, 5]), np.array([1, 1, 2])]          # a sequence of length 2: one pair
    out = transition_dependence(seqs, 6, shuffles=3, seed=1)
    assert out["pairs"] == 3 and out["same"] == pytest.approx(1 / 3)
    assert out["mi"] == pytest.approx(mutual_information_by_definition([4, 1, 1], [5, 1, 2], 6),
                                      rel=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")       # no "mean of empty slice" on the way to nan
        empty = transition_dependence([np.array([1])], 3, shuffles=2)
    assert math.isnan(empty["same"]) and math.isnan(empty["adjacent_null"])
    seen = []

    def stat(a, b):
        seen.append((a.dtype, b.dtype, len(a), len(b)))
        return 0.0

    transition_dependence([np.array([1])], 3, shuffles=2, stat=stat)
    assert seen == [(np.int64, np.int64, 0, 0)] * 3


# ----------------------------------------------------------------- free flight (eq. 27)
@pytest.mark.parametrize("sigma", [0.2, 0.3])
def test_free_flight_closure_fraction_approaches_impact_probability(sigma):
    gaps = 3000
    f = free_flight_closure_fraction(sigma, gaps, horizon=600.0, seed=7)
    p = float(impact_probability(sigma))
    se = math.sqrt(p * (1 - p) / gaps)
    assert abs(f - p) < 4 * se


@pytest.mark.parametrize("kw", [
    dict(sigma=0.35, gaps=40, horizon=30.0, seed=4),
    dict(sigma=0.3, gaps=30, horizon=25.0, seed=1, omega=1.3, d=1.2, Omega=0.7),
])
def test_free_flight_closure_against_brute_force(kw):
    om, d, Om = kw.get("omega", 1.0), kw.get("d", 1.0), kw.get("Omega", math.sqrt(2))
    rng = np.random.default_rng(kw["seed"])
    den = om**2 - Om**2
    closed = 0
    margins = []
    for _ in range(kw["gaps"]):
        # a gap x_{j+1} - x_j of two independent pipes: differences of their coefficients
        a0, b0, a1, b1 = rng.normal(0.0, kw["sigma"], size=(4, 2)) @ np.array([1.0, -1.0])
        lo = brute_min_of_gap((d, a0, b0, a1 / den, b1 / den), om, Om, kw["horizon"])
        margins.append(abs(lo))
        closed += lo <= 0
    assert min(margins) > 1e-6           # no graze within the scan's resolution
    assert 0 < closed < kw["gaps"]
    assert free_flight_closure_fraction(**kw) == closed / kw["gaps"]


def test_free_flight_defaults_and_arguments(monkeypatch):
    f = free_flight_closure_fraction
    assert f(0.3, 50) == f(0.3, 50, horizon=400.0, seed=0, omega=1.0, d=1.0,
                           Omega=math.sqrt(2))
    assert f(0.3, 1, horizon=3.0) in (0.0, 1.0)
    assert E.MAX_GAPS == 20_000
    for kw, exc, arg, value, allowed in (
        (dict(sigma=0), ValueError, "sigma", "0", "> 0"),
        (dict(sigma=math.nan), ValueError, "sigma", "nan", None),
        (dict(sigma=True), TypeError, "sigma", "True", None),
        (dict(sigma=1e300), ValueError, "sigma", "1e+300", "too large for the float64 engine"),
        (dict(sigma="1e400"), ValueError, "sigma", "1.0e+400", "float64 range"),
        (dict(gaps=0), ValueError, "gaps", "0", ">= 1"),
        (dict(gaps=True), TypeError, "gaps", "True", None),
        (dict(gaps=E.MAX_GAPS + 1), ValueError, "gaps", "20001",
         ["<= 20000", "symhx.impact.ensemble.MAX_GAPS"]),
        (dict(omega=0), ValueError, "omega", "0", "> 0"),
        (dict(omega="1e400"), ValueError, "omega", "1.0e+400", "float64 range"),
        (dict(d=0), ValueError, "d", "0", "> 0"),
        (dict(d="1e400"), ValueError, "d", "1.0e+400", "float64 range"),
        (dict(Omega=-1), ValueError, "Omega", "-1", ">= 0"),
        (dict(Omega="1e400"), ValueError, "Omega", "1.0e+400", "float64 range"),
        (dict(Omega=1.0), ValueError, "Omega[0]", "1.0", "resonance"),
        (dict(horizon=0), ValueError, "horizon", "0", "> 0"),
        (dict(horizon=math.inf), ValueError, "horizon", None, None),
        (dict(horizon=10**1000), ValueError, "horizon", None, "MAX_HORIZON"),
        (dict(horizon=60000, omega=2.0), ValueError, "horizon", "60000", "omega = 2.0"),
        (dict(seed=-1), ValueError, "seed", "-1", None),
        (dict(seed=True), TypeError, "seed", "True", None),
        (dict(seed=[]), TypeError, "seed", "[]", None),
    ):
        args = {"sigma": 0.3, "gaps": 2, "horizon": 10.0, **kw}
        assert_refuses(f, **args, exc=exc, arg=arg, value=value, allowed=allowed)
    assert f(0.3, 2, horizon=40000, omega=2.0) >= 0 and f(0.3, 2, Omega=0) >= 0
    # the defaults reach the search: seed 0, horizon 400
    eng = importlib.import_module("symhx.impact.engine")
    seen = {"t_hi": [], "seeds": []}
    real_rng = np.random.default_rng

    def search(self, g, t0, t_hi, **kw):
        seen["t_hi"].append((t0, t_hi))
        return math.inf, eng.Outcome.NONE

    monkeypatch.setattr(eng.Engine, "search", search)
    monkeypatch.setattr(np.random, "default_rng", lambda s=None: seen["seeds"].append(s) or
                        real_rng(s))
    assert f(0.3, 2) == 0.0
    assert seen["t_hi"] == [(0.0, 400.0)] * 2 and seen["seeds"] == [0]


def test_free_flight_overflow_guard():
    f = free_flight_closure_fraction

    def too_large(value, **kw):
        assert_refuses(f, value, 1, horizon=1.0, **kw, arg="sigma", value=f"sigma = {value!r}",
                       allowed=["too large for the float64 engine", "use a smaller sigma"])

    # (4 sigma max(1, 1/|omega^2 - Omega^2|))**2 must be finite: sqrt(max float) / 4 = 3.35e153
    assert f(3e153, 1, horizon=1.0) in (0.0, 1.0)          # Omega = sqrt 2: |den| = 1
    too_large(3.4e153)
    # Omega = 0.5: 1 / |den| = 4 / 3 enlarges the forced amplitudes
    assert f(2.5e153, 1, horizon=1.0, Omega=0.5) in (0.0, 1.0)
    too_large(3e153, Omega=0.5)
    # Omega = 2: |den| = 3 > 1, the factor stays 1
    assert f(3e153, 1, horizon=1.0, Omega=2.0) in (0.0, 1.0)
    too_large(1e200)


def test_free_flight_checks_the_given_omega_and_d():
    assert_refuses(free_flight_closure_fraction, 0.3, 2, omega=2.0, Omega=2.0, horizon=5.0,
                   arg=["Omega[0]", "omega"], value="Omega[0] = 2.0",
                   allowed=["omega = 2.0", "resonance"])
    assert 0 <= free_flight_closure_fraction(0.3, 2, d=3.0, horizon=5.0) <= 1

