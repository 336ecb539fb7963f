"""symhx.impact.site_theory: the model distributions against exact class weights
(tests.reference.sites), the fitted scale against a scan, the thresholds against the certified
modes on either side, the simulated side against numpy over the histograms, the bootstrap's
reproducibility, and the stored comparison against a recomputation."""

from __future__ import annotations

import json
import math
from fractions import Fraction
from importlib import resources

import numpy as np
import pytest

import symhx
from symhx.impact.site_theory import (
    MODELS,
    SimulatedX,
    compare_site_models,
    fit_models,
    model_pmfs,
    simulated_x,
)
from symhx.impact.sites import SiteHitResult, SiteHitTable
from symhx.site_distribution import site_modes
from symhx.sites import SiteClasses
from tests.harness.errors import assert_refuses
from tests.reference.sites import mode_weights

PARAMS = {"n": 10, "omega": 1.0, "d": 1.0, "Omega": ["sqrt(2)"], "sigma0": "sigma"}


def stored_sites() -> SiteHitResult:
    data = json.loads(resources.files("symhx.data").joinpath("ensemble_sites.json").read_text())
    return SiteHitResult(data["params"], [SiteHitTable.from_dict(t) for t in data["tables"]])


def synthetic(seed: int = 0) -> SiteHitResult:
    """Tables of a row of 10 pipes whose runs hit sites as a random draw would (every site
    independently, walls at half the interior rate), at 8 values of sigma."""
    rng = np.random.default_rng(seed)
    tables = []
    for s, q in zip(np.linspace(0.15, 0.4, 8), np.linspace(0.05, 0.9, 8), strict=True):
        runs = rng.random((400, 11)) < np.r_[q / 2, np.full(9, q), q / 2]
        tables.append(SiteHitTable.from_counts(float(s), runs.astype(int)))
    return SiteHitResult(dict(PARAMS), tables)


@pytest.mark.parametrize(("pw", "pp"), [("1/50", "1/30"), ("1/7", "1/3"), ("1/1000", "1/20"),
                                         ("1/4", "1/4")])
def test_model_distributions_are_the_exact_class_weights(pw, pp):
    n = 10
    W = mode_weights((2, n - 1), (Fraction(pw), Fraction(pp)))
    exact = [w / sum(W) for w in W]
    got = model_pmfs([float(Fraction(pw))], [float(Fraction(pp))], n)[0]
    assert np.allclose(got, [float(x) for x in exact], rtol=1e-12, atol=0)


def test_one_class_is_the_papers_distribution():
    got = model_pmfs([0.02], [0.02], 100)[0]
    assert np.array_equal(got, symhx.pmf(101, 0.02, np.arange(1, 102), dps=None))


def test_simulated_side_from_the_histograms():
    res = synthetic()
    sim = simulated_x(res, min_kept=20)
    for j, t in enumerate(t for t in res.tables if t.sites_histogram()[1:].sum() >= 20):
        h = t.sites_histogram()
        x = np.repeat(np.arange(len(h)), h)[h[0]:]          # the runs with an impact
        assert sim.means[j] == pytest.approx(x.mean(), rel=1e-14)
        assert sim.cdfs[j, 2] == pytest.approx(np.mean(x <= 3), rel=1e-14)
        assert sim.modes[j] == np.bincount(x).argmax()
        assert sim.ratios[j] == t.rate_ratio()[0]
    modes = SimulatedX(np.array([0.1, 0.2, 0.3, 0.4]), np.zeros((4, 3)), np.ones(4), 1)
    assert math.isnan(modes.threshold())


def test_simulated_threshold_is_where_the_mode_stays_above_one():
    hists = np.zeros((4, 5), dtype=int)
    hists[[0, 1, 2, 3], [1, 3, 1, 4]] = 10     # modes 1, 3, 1, 4: above 1 from the last on
    sim = SimulatedX(np.array([0.1, 0.2, 0.3, 0.4]), hists, np.ones(4), 3)
    assert sim.threshold() == 0.4
    hists[2] = 0
    hists[2, 2] = 10
    assert SimulatedX(sim.sigmas, hists, np.ones(4), 3).threshold() == 0.2
    # above 1 at every sigma: the first sigma; never above 1 at the last: NaN
    hists[:] = 0
    hists[:, 3] = 10
    assert SimulatedX(sim.sigmas, hists, np.ones(4), 3).threshold() == 0.1
    hists[3] = 0
    hists[3, 1] = 10
    assert math.isnan(SimulatedX(sim.sigmas, hists, np.ones(4), 3).threshold())


def test_fitted_scale_minimises_the_mean_distance():
    sim = simulated_x(synthetic())
    fits = fit_models(sim, thresholds=False)
    lam = fits["scaled"].scale
    k = np.arange(1, sim.n + 2)

    def rms(scale):
        pp = scale * np.asarray(fits["uniform"].p_pipe)
        m = model_pmfs(sim.ratios * pp, pp, sim.n) @ k
        return math.sqrt(np.mean((sim.means - m) ** 2))

    assert rms(lam) == pytest.approx(fits["scaled"].rms_mean, rel=1e-12)
    scan = np.exp(np.linspace(math.log(0.05), math.log(20), 200))
    assert rms(lam) <= min(rms(x) for x in scan) + 1e-9
    assert rms(lam) <= min(rms(lam * 1.001), rms(lam / 1.001))
    # the geometry model is the scaled one at lambda = 1 with eq. (27)'s own ratio
    geo = fits["geometry"]
    assert np.array_equal(geo.p_pipe, fits["uniform"].p_pipe)
    assert np.all(geo.p_wall < geo.p_pipe)


def test_thresholds_separate_mode_one_from_the_jump():
    sim = simulated_x(stored_sites())
    fits = fit_models(sim)
    cp = symhx.critical_point(101, dps=20)
    assert float(symhx.impact_probability(fits["uniform"].threshold)) == pytest.approx(
        float(cp.p), rel=1e-12)
    for model in ("geometry", "scaled"):
        f = fits[model]
        for factor, above in ((1 - 1e-4, False), (1 + 1e-4, True)):
            s = f.threshold * factor
            pp = float(symhx.impact_probability(s)) * f.scale
            if model == "geometry":
                pw = float(symhx.forcing.sites.contact_probability(s, bodies=1))
            else:
                pw = float(np.interp(s, sim.sigmas, sim.ratios)) * pp
            modes = site_modes(101, SiteClasses((2, 99), (pw, pp)))
            assert (modes[0] > 1) is above, (model, s, modes)


def test_bootstrap_is_reproducible_and_moves_with_the_seed():
    res = synthetic()
    a = compare_site_models(res, replicates=3, seed=4)
    b = compare_site_models(res, replicates=3, seed=4)
    c = compare_site_models(res, replicates=3, seed=5)
    assert a.as_dict() == b.as_dict()
    assert a.boot["scaled"]["rms_mean"] != c.boot["scaled"]["rms_mean"]
    summary = a.summary()
    assert set(summary) == set(MODELS)
    assert summary["uniform"]["rms_mean_sd"] > 0 and summary["uniform"]["scale_sd"] == 0
    json.dumps(a.as_dict(), allow_nan=False)     # strict JSON: no NaN


def test_stored_comparison_is_current():
    data = json.loads(resources.files("symhx.data").joinpath("site_calibration.json").read_text())
    sim = simulated_x(stored_sites(), min_kept=data["min_kept"])
    assert sim.sigmas.tolist() == data["sigmas"]
    for m, f in fit_models(sim).items():
        stored = data["models"][m]
        assert f.scale == pytest.approx(stored["scale"], rel=1e-6)
        assert f.rms_mean == pytest.approx(stored["rms_mean"], rel=1e-6)
        assert f.rms_ks == pytest.approx(stored["rms_ks"], rel=1e-6)
        assert f.threshold == pytest.approx(stored["threshold"], rel=1e-6)
    assert len(data["models"]["scaled"]["boot"]["scale"]) == data["replicates"] >= 100


@pytest.mark.slow
def test_stored_bootstrap_is_recomputed_replicate_by_replicate():
    """The stored replicates are the seeded bootstrap's (its first two rerun: the same resampled
    runs and fits, to 1e-9; the float64 class distribution's last bits may move with its code),
    and the stored summary (the chapter's uncertainties) is computed from the stored replicates."""
    data = json.loads(resources.files("symhx.data").joinpath("site_calibration.json").read_text())
    again = compare_site_models(stored_sites(), min_kept=data["min_kept"], replicates=2,
                                seed=data["seed"]).as_dict()
    for m in MODELS:
        for key, values in again["models"][m]["boot"].items():
            assert values == pytest.approx(data["models"][m]["boot"][key][:2], rel=1e-9), \
                (m, key)
    assert again["simulation"]["boot"]["threshold"] == \
        data["simulation"]["boot"]["threshold"][:2]        # grid values: exact
    for m in MODELS:
        boot, summary = data["models"][m]["boot"], data["summary"][m]
        for key in ("rms_mean", "rms_ks", "scale"):
            sd = math.sqrt(sum((x - sum(boot[key]) / len(boot[key])) ** 2 for x in boot[key])
                           / (len(boot[key]) - 1))
            assert summary[f"{key}_sd"] == pytest.approx(sd, rel=1e-9, abs=1e-15), (m, key)
        assert summary["rms_mean"] == data["models"][m]["rms_mean"]
        th = sorted(boot["threshold"])
        assert th[0] <= summary["threshold_lo"] <= summary["threshold_hi"] <= th[-1]


def test_refusals_name_the_argument():
    res = synthetic()
    assert_refuses(simulated_x, 1, exc=TypeError, arg="result", value="int")
    assert_refuses(simulated_x, res, min_kept=0, arg="min_kept", value="0", allowed=">= 1")
    assert_refuses(simulated_x, res, min_kept=10**6, arg="min_kept", value="1000000")
    assert_refuses(fit_models, 1, exc=TypeError, arg="sim", value="int")
    assert_refuses(compare_site_models, res, replicates=1, arg="replicates", value="1",
                   allowed=">= 2")
    assert_refuses(compare_site_models, res, replicates=10**4, arg="replicates", value="10000",
                   allowed="<= 2000")
    assert_refuses(compare_site_models, res, seed=None, exc=TypeError, arg="seed",
                   value="None")
    bad = SiteHitResult({**PARAMS, "sigma0": [0.1]}, res.tables)
    assert_refuses(fit_models, simulated_x(bad), arg="params", value="sigma0")
    two = SiteHitResult({**PARAMS, "Omega": [1.0, 2.5]}, res.tables)
    assert_refuses(fit_models, simulated_x(two), arg="params", value="Omega=[1.0, 2.5]",
                   allowed="one forcing component")


def test_a_model_whose_mode_stays_one_over_the_range_has_no_threshold_band():
    """Forcing far below the jump: the geometric model's mode is 1 at every kept sigma (checked
    by the certified modes), so every replicate's threshold is NaN and so are its 16-84 %
    bounds (``None`` in the JSON form, which also keeps the bootstrap's seed and size)."""
    rng = np.random.default_rng(1)
    tables = [SiteHitTable.from_counts(float(s), (rng.random((200, 11)) < 0.1).astype(int))
              for s in np.linspace(0.02, 0.04, 4)]
    cmp = compare_site_models(SiteHitResult(dict(PARAMS), tables), replicates=2, seed=3)
    geo = cmp.fits["geometry"]
    for pw, pp in zip(geo.p_wall, geo.p_pipe, strict=True):
        assert site_modes(11, SiteClasses((2, 9), (float(pw), float(pp)))) == (1,)
    assert math.isnan(geo.threshold)
    assert all(math.isnan(x) for x in cmp.boot["geometry"]["threshold"])
    band = cmp.summary()["geometry"]
    assert math.isnan(band["threshold_lo"]) and math.isnan(band["threshold_hi"])
    d = cmp.as_dict()
    assert d["summary"]["geometry"]["threshold_lo"] is None
    assert d["summary"]["geometry"]["threshold_hi"] is None
    assert (d["seed"], d["replicates"]) == (3, 2)
    json.dumps(d, allow_nan=False)
