"""``PipeRow.random`` (section 7): the documented draw, its non-overlap rule and draw budgets,
its sample statistics and its refusals.

The references (``tests.reference.impact``) write the draw out from the docstring: the forcing
``alpha, beta ~ N(0, sigma^2)``, then ``x_j(0) = j d + alpha_0j + forced_j(0)``, ``v_j(0) = omega
beta_0j + forced_j'(0)`` with the forced part recomputed from eq. 21, and the redraw rule.
"""

from __future__ import annotations

import inspect
import math

import numpy as np
import pytest

from symhx.impact.model import MAX_PIPES, MAX_SCALE, SQRT2, PipeRow
from tests.harness.errors import assert_refuses
from tests.reference.impact import documented_draw, documented_redraws, forced_at_zero


class _CountingRng:
    """A numpy Generator that counts its draws: forcing matrices and (alpha_0j, beta_0j) pairs."""

    def __init__(self, rng, log):
        self.rng, self.log = rng, log

    def normal(self, loc, scale, size=None):
        self.log.append("pair" if size == 2 else "forcing")
        return self.rng.normal(loc, scale, size=size)


@pytest.fixture
def draws(monkeypatch):
    log = []
    real = np.random.default_rng
    monkeypatch.setattr(np.random, "default_rng", lambda seed=None: _CountingRng(real(seed),
                                                                                 log))
    return log


def _pairs_per_forcing(log):
    """Pair draws after each forcing (a forcing is two matrices, alpha then beta)."""
    out = []
    for item in log:
        if item == "forcing":
            if not out or out[-1] is not None:
                out.append(None)          # alpha: a new forcing starts
            else:
                out[-1] = 0               # beta: its pairs follow
        else:
            out[-1] += 1
    return out


def _refuses_undrawable(n, sigma, *, scale, **kw):
    """``PipeRow.random(n, sigma, **kw)`` cannot be drawn: the message shows the inputs (omega,
    Omega and d at their defaults unless given), the displacement scale and what to change."""
    shown = dict(sigma0=None, omega=1.0, Omega=(SQRT2,), d=1.0)
    shown.update({k: v for k, v in kw.items() if k in shown})
    assert_refuses(PipeRow.random, n, sigma, **kw, arg=["sigma", "sigma0", "d"],
                   value=(f"sigma={sigma!r}, sigma0={shown['sigma0']!r}, "
                          f"omega={shown['omega']!r}, Omega={shown['Omega']!r}"),
                   allowed=[f"(scale ~{scale:.3g})", f"spacing d={shown['d']!r}",
                            "use a smaller sigma/sigma0, a larger d, or Omega further from omega"])


# ----------------------------------------------------------------- the documented draw
@pytest.mark.parametrize("kw", [
    dict(n=6, sigma=0.05, seed=3),
    dict(n=4, sigma=0.02, seed=8, omega=2.0, d=3.0, Omega=(0.5, 3.0)),
    dict(n=3, sigma=0.03, seed=1, sigma0=0.01),
    dict(n=3, sigma=0.0, seed=2, sigma0=0.02),
    dict(n=5, sigma=0.04, seed=4, sigma0=0.0),
])
def test_random_row_is_the_documented_draw(kw):
    row = PipeRow.random(**kw)
    n, d, om = kw["n"], kw.get("d", 1.0), kw.get("omega", 1.0)
    alpha, beta, free = documented_draw(**kw)
    assert np.array_equal(row.alpha, alpha) and np.array_equal(row.beta, beta)
    f0, fv0 = forced_at_zero(row)
    j = np.arange(1, n + 1) * d
    assert np.allclose(row.x0, j + free[:, 0] + f0, rtol=0, atol=1e-14 * d)
    assert np.allclose(row.v0, om * free[:, 1] + fv0, rtol=0, atol=1e-14 * d)
    assert row.restitution == 0.8 and row.omega == om and row.d == d
    assert row.Omega == kw.get("Omega", (SQRT2,))


def test_random_row_statistics():
    # many pipes, small sigma (no redraws needed): the amplitudes are N(0, sigma^2) and the
    # free-oscillation parts (x_j - j d - forced_j) / sigma0, (v_j - forced_j') / (omega sigma0)
    # are standard normal
    n, sigma, sigma0, om = 3000, 0.02, 0.05, 1.5
    row = PipeRow.random(n, sigma, seed=12, sigma0=sigma0, omega=om, Omega=(0.5, 3.0),
                         restitution=0.3)
    assert row.restitution == 0.3
    se = 1 / math.sqrt(2 * n * 2)
    for arr in (row.alpha, row.beta):
        assert abs(arr.std() / sigma - 1) < 5 * se and abs(arr.mean()) < 5 * sigma / 100
    f0, fv0 = forced_at_zero(row)
    a0 = (row.x0 - np.arange(1, n + 1) - f0) / sigma0
    b0 = (row.v0 - fv0) / (om * sigma0)
    for z in (a0, b0):
        assert abs(z.std() - 1) < 5 / math.sqrt(2 * n) and abs(z.mean()) < 5 / math.sqrt(n)
    assert abs(np.corrcoef(a0, b0)[0, 1]) < 5 / math.sqrt(n)


def test_random_rows_with_redraws_never_overlap():
    # sigma0 comparable to d: many pipes need redraws; every row is valid, reproducible, and
    # the redraws keep the marginal spread of the free part below its untruncated sigma0
    rows = [PipeRow.random(8, 0.1, seed=s, sigma0=0.6) for s in range(20)]
    for s, row in enumerate(rows):
        gaps = row.gap0()
        assert np.all(gaps > 0) and gaps.sum() == pytest.approx(9.0, rel=1e-12)
        again = PipeRow.random(8, 0.1, seed=np.random.SeedSequence(s), sigma0=0.6)
        assert np.array_equal(again.x0, row.x0) and np.array_equal(again.v0, row.v0)
    assert len({row.x0.tobytes() for row in rows}) == 20
    # the rows are drawn independently of the restitution
    a = PipeRow.random(4, 0.3, seed=7, restitution=0.0)
    b = PipeRow.random(4, 0.3, seed=7, restitution=1)
    assert np.array_equal(a.x0, b.x0) and (a.restitution, b.restitution) == (0.0, 1.0)
    # a generator is used as given (its stream continues)
    g = np.random.default_rng(5)
    first, second = PipeRow.random(3, 0.1, seed=g), PipeRow.random(3, 0.1, seed=g)
    assert not np.array_equal(first.alpha, second.alpha)
    assert np.array_equal(first.alpha, PipeRow.random(3, 0.1, seed=5).alpha)


def test_random_rows_reproducible_and_valid():
    a = PipeRow.random(50, 0.5, seed=42)
    b = PipeRow.random(50, 0.5, seed=42)
    assert np.array_equal(a.x0, b.x0) and np.array_equal(a.alpha, b.alpha)
    assert np.all(a.gap0() > 0)
    assert not np.array_equal(a.x0, PipeRow.random(50, 0.5, seed=43).x0)
    c = PipeRow.random(4, 0.3, seed=5)
    d = PipeRow.random(4, 0.3, seed=np.random.SeedSequence(5))   # numpy: the same stream
    assert np.array_equal(c.x0, d.x0) and np.array_equal(c.alpha, d.alpha)


def test_random_scalar_omega_and_defaults():
    row = PipeRow.random(3, 0.1, seed=4, Omega=2.0)
    assert row.Omega == (2.0,)
    row = PipeRow.random(3, 0.1, seed=4, Omega="1/2")
    assert row.exact("Omega")[0] == 0.5
    row = PipeRow.random(3, 0.1, seed=4)
    assert (row.omega, row.d, row.Omega, row.restitution) == (1.0, 1.0, (SQRT2,), 0.8)


def test_documented_defaults():
    sig = inspect.signature(PipeRow.random).parameters
    assert {k: sig[k].default for k in ("seed", "restitution", "omega", "d", "Omega",
                                        "sigma0", "max_redraws")} == {
        "seed": None, "restitution": 0.8, "omega": 1.0, "d": 1.0, "Omega": (SQRT2,),
        "sigma0": None, "max_redraws": 10_000}
    sig = inspect.signature(PipeRow.__init__).parameters
    assert (sig["omega"].default, sig["d"].default, sig["Omega"].default) == (1.0, 1.0,
                                                                              (SQRT2,))


# ----------------------------------------------------------------- redraws and budgets
@pytest.mark.parametrize("n, sigma, seed, sigma0, max_redraws", [
    (2, 0.05, 3, 0.45, 1), (3, 0.1, 1, 0.6, 2), (5, 0.1, 2, 0.5, 1), (4, 0.2, 7, 0.7, 3),
    (6, 0.05, 4, 0.4, 5), (8, 0.1, 0, 0.6, 10_000), (3, 0.3, 9, 0.9, 1),
])
def test_random_redraws_follow_the_documented_rule(n, sigma, seed, sigma0, max_redraws):
    ref = documented_redraws(n, sigma, seed, sigma0, max_redraws)
    if ref is None:
        assert_refuses(PipeRow.random, n, sigma, seed=seed, sigma0=sigma0,
                       max_redraws=max_redraws, arg="sigma", allowed="could not draw")
        return
    row = PipeRow.random(n, sigma, seed=seed, sigma0=sigma0, max_redraws=max_redraws)
    for got, want in zip((row.alpha, row.beta, row.x0, row.v0), ref, strict=True):
        assert np.array_equal(got, want)


def test_random_redraws_the_forcing_as_documented(draws):
    # a row whose first forcing leaves no room for the free parts of some pipe (it used to spend
    # the whole budget of 4000 n draws on that forcing and fail, while seed + 1 succeeded): the
    # forcing is drawn again, as the docstring says, and the row is the documented one
    kw = dict(restitution=0.5, omega=0.3, Omega=(0.5, 1.1))
    for seed in (337715592, 337715593):
        draws.clear()
        row = PipeRow.random(20, 0.06, seed=seed, **kw)
        ref = documented_redraws(20, 0.06, seed, 0.06, 10_000, omega=0.3, Omega=(0.5, 1.1))
        assert ref is not None and np.array_equal(row.x0, ref[2])
        assert np.all(row.gap0() > 0)
        per = _pairs_per_forcing(draws)
        assert all(k <= 400 * 20 for k in per)          # each forcing: its share 400 n at most
        if seed == 337715592:
            assert len(per) > 1                          # ... and then a new forcing


def test_random_redraw_budgets():
    # max_redraws = 1: each pipe gets one draw per pass; with sigma0 ~ d most passes fail and a
    # new pass starts; the row still comes out valid when some pass succeeds
    row = PipeRow.random(2, 0.05, seed=3, sigma0=0.45, max_redraws=1)
    assert np.all(row.gap0() > 0)
    # hopeless within the budgets: 10 forcings, each at most 20 max_redraws draws
    assert_refuses(PipeRow.random, 40, 0.05, seed=3, sigma0=2.0, max_redraws=1, arg="sigma",
                   allowed="could not draw")


def test_random_draw_budgets_counted(draws):
    # hopeless rows within the documented budgets; the draws are counted
    # (a) max_redraws = 1: 20 max_redraws = 20 pair draws per forcing, 10 forcings
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(40, 0.05, seed=3, sigma0=2.0, max_redraws=1)
    assert draws.count("forcing") == 20 and draws.count("pair") == 200
    assert _pairs_per_forcing(draws) == [20] * 10
    draws.clear()
    # (b) the forced displacement puts the single pipe far outside the walls: each of the 10
    # forcings gets its share 400 n of the 4000 n draws, then the row is refused
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(1, 100.0, seed=0, sigma0=0.1, Omega=(1.05,))
    assert draws.count("forcing") == 20 and draws.count("pair") == 4000
    assert _pairs_per_forcing(draws) == [400] * 10
    draws.clear()
    # (c) sigma0 = 0: one deterministic try per pipe and pass, all 10 forcings are drawn
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(6, 3.0, sigma0=0.0, Omega=(1.05,), seed=0)
    assert draws.count("forcing") == 20 and draws.count("pair") == 0
    draws.clear()
    # (d) a forced velocity beyond float64 (beta Omega overflows, alpha / den does not):
    # refused at the first forcing, before any pair is drawn
    den = 1.0 - 1e5**2
    with np.errstate(over="ignore"):
        _refuses_undrawable(2, 1e304, seed=0, Omega=(1e5,), sigma0=0.1,
                            scale=1e304 / abs(den) + 0.1)
    assert draws == ["forcing", "forcing"]
    draws.clear()
    # (e) refused up front (each draw would land with probability < 1e-3): nothing drawn
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(1, 0.0, seed=0, sigma0=0.5, d=1e-4)
    assert draws == []
    # (f) just above that bound the draw is attempted: (n + 1) d / (sigma0 sqrt(2 pi)) =
    # 1.2e-3 (it would be 0.98e-3 with sqrt(3 pi) in place of sqrt(2 pi))
    sig0 = 2.0 / (1.2e-3 * math.sqrt(2 * math.pi))
    try:
        PipeRow.random(1, 0.0, seed=0, sigma0=sig0)
    except ValueError:
        pass
    assert draws.count("pair") > 0
    draws.clear()
    # (g) far above it (probability ~ 0.8 per draw) the row is drawn at once
    assert PipeRow.random(1, 0.0, seed=0, sigma0=1.0).n == 1 and len(draws) == 1


def test_random_budget_boundaries(draws):
    # a share of 400 draws for one pipe, 399 per pass: the second pass still gets the last draw
    # of each forcing's share
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(1, 100.0, seed=0, sigma0=0.1, Omega=(1.05,), max_redraws=399)
    assert draws.count("pair") == 4000 and draws.count("forcing") == 20
    draws.clear()
    # the up-front refusal is strict: (n + 1) d / (sigma0 sqrt(2 pi)) == 1e-3 exactly is drawn
    sig0 = 797.8845608028654
    assert 2.0 / (sig0 * math.sqrt(2 * math.pi)) == 1e-3
    try:
        PipeRow.random(1, 0.0, seed=0, sigma0=sig0)
    except ValueError:
        pass
    assert draws.count("pair") > 0


def test_random_resonance_refused_before_any_draw(draws):
    # omega = 1e6: 1e-12 omega^2 == 1.0 exactly, and 999999.9999995**2 == 1e12 - 1 in float64
    assert_refuses(PipeRow.random, 1, 0.1, omega=1e6, Omega=(999999.9999995,), seed=0,
                   arg="Omega[0]", allowed="resonance")
    assert draws == []          # refused before anything is drawn


# ----------------------------------------------------------------- refusals
@pytest.mark.parametrize("kwargs, name", [
    (dict(n=True, sigma=0.3), "n"), (dict(n=2, sigma=True), "sigma"),
    (dict(n=2, sigma=0.3, d=0), "d"), (dict(n=2, sigma=-0.3), "sigma"),
    (dict(n=2, sigma=0.3, omega=math.sqrt(2)), "Omega[0]"),
    (dict(n=2, sigma=float("nan")), "sigma"),
])
def test_bad_random_rows(kwargs, name):
    assert_refuses(PipeRow.random, exc=(ValueError, TypeError), arg=name, **kwargs)


def test_undrawable_row_clear_error():
    assert_refuses(PipeRow.random, 30, 3.0, seed=1, d=0.01, omega=1.4, arg=["sigma", "d"],
                   value="sigma=3.0", allowed="too large for the spacing d=0.01")


def test_random_refusals_and_messages():
    # up front: a pipe must land in (0, (n + 1) d), probability < (n + 1) d / (sigma0 sqrt(2 pi))
    # per draw: below 1e-3 the draw is refused before any work
    sig0 = 3 * 1.0 / (1e-3 * math.sqrt(2 * math.pi))        # (n + 1) d = 3, probability 1e-3 / 1
    _refuses_undrawable(2, 0.0, sigma0=sig0 * 1.01, seed=1, scale=0.0 * 1.0 + sig0 * 1.01)
    # forced displacements alone overlap (sigma0 = 0, strong forcing near resonance): each of
    # the 10 forcings fails at once; scale = sigma sum 1 / |omega^2 - Omega^2| + sigma0
    den = abs(1.0 - 1.05**2)
    _refuses_undrawable(6, 3.0, sigma0=0.0, Omega=(1.05,), seed=0, scale=3.0 / den)
    # forced parts that overflow float64 are refused, not turned into NaN positions
    assert_refuses(PipeRow.random, 2, 1e100, seed=0, Omega=(1.0 + 1e-11,), arg="sigma",
                   allowed="could not draw")
    assert_refuses(PipeRow.random, 2, 0.1, omega=-1, arg="omega", value="-1", allowed="> 0")
    assert_refuses(PipeRow.random, 2, 0.1, d=0, arg="d", value="0", allowed="> 0")
    for name, bad in (("omega", 1e101), ("d", 1e-101)):
        assert_refuses(PipeRow.random, 2, 0.1, **{name: bad}, arg=name,
                       value=f"{name} = {bad!r}",
                       allowed=["[1e-100, 1e+100]", "symhx.impact.model.MAX_SCALE"])
    assert_refuses(PipeRow.random, 2, 0.1, Omega=(), arg="Omega",
                   allowed="at least one forcing frequency")
    assert_refuses(PipeRow.random, 2, 0.1, Omega=(2.0, 1.0), arg=["Omega[1]", "omega"],
                   value="Omega[1] = 1.0", allowed=["omega = 1.0", "resonance",
                                                    "Omega[i] != omega"])
    assert_refuses(PipeRow.random, 2, 0.1, omega=2.0, Omega=(2.0 * (1 + 1e-13),),
                   arg=["Omega[0]", "omega"], value="Omega[0] = 2.0000000000002",
                   allowed=["omega = 2.0", "resonance"])
    assert PipeRow.random(2, 1e-12, omega=10.0, Omega=(10.0 * (1 + 1e-11),), sigma0=0.1,
                          seed=0).n == 2
    assert_refuses(PipeRow.random, 2, 0.1, restitution=2, arg="restitution", value="2",
                   allowed="[0, 1]")
    assert_refuses(PipeRow.random, 2, 0.1, restitution=True, exc=TypeError, arg="restitution",
                   value="True")
    assert_refuses(PipeRow.random, 2, -0.1, arg="sigma", value="-0.1", allowed=">= 0")
    assert_refuses(PipeRow.random, 2, 0.1, sigma0=-0.1, arg="sigma0", value="-0.1",
                   allowed=">= 0")
    assert_refuses(PipeRow.random, 2, 0.1, sigma0=True, exc=TypeError, arg="sigma0",
                   value="True")
    assert_refuses(PipeRow.random, 2, 0.1, max_redraws=0, arg="max_redraws", value="0",
                   allowed=">= 1")
    assert_refuses(PipeRow.random, 0, 0.1, arg="n", value="0", allowed=">= 1")
    for name, kw in (("sigma", {}), ("omega", {"omega": "1e400"}), ("d", {"d": "1e400"}),
                     ("Omega[0]", {"Omega": ("1e400",)}), ("sigma0", {"sigma0": "1e400"})):
        args = (2, "1e400") if name == "sigma" else (2, 0.1)
        assert_refuses(PipeRow.random, *args, **kw, arg=name, value="'1e400'",
                       allowed="float64 range")
    assert_refuses(PipeRow.random, 2, 0.1, omega=0, arg="omega", value="0", allowed="> 0")
    assert_refuses(PipeRow.random, 2, 0.1, omega=10.0, Omega=(10.0 * (1 + 1e-14),),
                   arg=["Omega[0]", "omega"], value="Omega[0] = 10.0000000000001",
                   allowed=["omega = 10.0", "resonance"])


def test_random_hopeless_and_bad_seeds_refused():
    for seed in (True, [], -1, 2.5):
        with pytest.raises((ValueError, TypeError), match="seed"):
            PipeRow.random(3, 0.3, seed=seed)
    for kw in (dict(sigma=1e6), dict(sigma=1e308), dict(sigma=0.3, d=1e308),
               dict(sigma=0.3, d=5e-324), dict(sigma=0.3, omega=10**1000)):
        with pytest.raises(ValueError):
            PipeRow.random(3, seed=0, **kw)
    assert_refuses(PipeRow.random, MAX_PIPES + 1, 0.3, arg="n", allowed="MAX_PIPES")
    assert MAX_SCALE == 1e100
