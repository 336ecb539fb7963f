"""``symhx.impact.model`` against independent references (issue 16, mutation testing).

* :data:`SQRT2` and :func:`exact_to_mpf` against correctly rounded values computed here in exact
  integer arithmetic (``math.isqrt``, integer division with round-half-even);
* every validation boundary (``MAX_PIPES``, ``MAX_HORIZON``, ``MAX_SCALE``, restitution ``[0, 1]``
  exactly, resonance, overlapping pipes, walls) on both sides, with the complete error message;
* :meth:`PipeRow.random` against the documented draw (section 7: ``alpha, beta ~ N(0, sigma^2)``,
  ``x_j(0) = j d + alpha_0j + forced_j(0)``, ``v_j(0) = omega beta_0j + forced_j'(0)``), the
  forced part recomputed here from eq. 21, and its sample statistics.
"""

from __future__ import annotations

import math
import pickle
import re
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx.impact.model import (
    MAX_HORIZON,
    MAX_PIPES,
    MAX_SCALE,
    SQRT2,
    PipeRow,
    check_horizon,
    check_pipes,
    exact_to_mpf,
)


def _row(n=1, **kw):
    base = dict(restitution=1, alpha=[[0.0]] * n, beta=[[0.0]] * n,
                x0=[float(j + 1) for j in range(n)], v0=[0.0] * n)
    base.update(kw)
    return PipeRow(n, **base)


def _raises(exc, message, fn, *args, **kw):
    """``fn`` raises ``exc`` with exactly ``message``."""
    with pytest.raises(exc) as info:
        fn(*args, **kw)
    assert str(info.value) == message


def _scale_msg(name, value, positive):
    rng = "[1e-100, 1e+100]" if positive else "<= 1e+100 in size"
    return (f"{name} = {value!r} is outside the range {rng} that the engines resolve "
            "(symhx.impact.model.MAX_SCALE); rescale the units")


# ----------------------------------------------------------------- exact numbers
def _nearest_binary(p: int, q: int, prec: int) -> mpmath.mpf:
    """p/q > 0 rounded to ``prec`` bits, half to even, in integer arithmetic only."""
    e = p.bit_length() - q.bit_length() - prec
    while True:   # find e with 2**(prec-1) <= p / (q 2**e) < 2**prec
        num, den = (p, q << e) if e >= 0 else (p << -e, q)
        m, rem = divmod(num, den)
        if m >= 1 << prec:
            e += 1
        elif m < 1 << (prec - 1):
            e -= 1
        else:
            break
    if 2 * rem > den or (2 * rem == den and m % 2):
        m += 1
    with mpmath.workprec(prec + 2):
        return mpmath.ldexp(mpmath.mpf(m), e)


@pytest.mark.parametrize("prec", [2, 3, 24, 53, 54, 100, 333, 1401, 2000])
def test_sqrt2_correctly_rounded_at_every_precision(prec):
    # sqrt(2) 2**(prec-1) lies in [2**(prec-1), 2**prec): its floor is isqrt(2 * 4**(prec-1))
    m = math.isqrt(2 << (2 * (prec - 1)))
    if (2 * m + 1) ** 2 < 8 << (2 * (prec - 1)):   # nearest (no ties: sqrt 2 is irrational)
        m += 1
    with mpmath.workprec(prec + 2):
        ref = mpmath.ldexp(mpmath.mpf(m), -(prec - 1))
    with mpmath.workprec(prec):
        got = mpmath.mpf(SQRT2)
    assert got == ref
    assert got > 0


def test_sqrt2_float_repr_pickle():
    assert float(SQRT2) == math.sqrt(2.0) == 1.4142135623730951
    assert repr(SQRT2) == "sqrt(2)"
    assert pickle.loads(pickle.dumps(SQRT2)) is SQRT2


def test_exact_to_mpf_rounds_fractions_once():
    rng = np.random.default_rng(11)
    for prec in (53, 80, 200):
        for _ in range(150):
            p = int.from_bytes(rng.bytes(int(rng.integers(1, 60))), "big") | 1
            q = int.from_bytes(rng.bytes(int(rng.integers(1, 60))), "big") | 1
            with mpmath.workprec(prec):
                got = exact_to_mpf(Fraction(p, q))
                neg = exact_to_mpf(Fraction(-p, q))
                assert got == _nearest_binary(p, q, prec) and neg == -got   # negation: exact
    with mpmath.workdps(30):
        assert exact_to_mpf(Fraction(1, 3)) == mpmath.mpf(1) / 3
        assert exact_to_mpf(Fraction(7, 2)) == mpmath.mpf("3.5")


def test_exact_to_mpf_other_types():
    with mpmath.workprec(53):
        assert exact_to_mpf(0.1) == mpmath.mpf(0.1) and exact_to_mpf(-3) == -3
        with mpmath.workprec(300):
            third = mpmath.mpf(1) / 3
        assert exact_to_mpf(third) == mpmath.mpf(1) / 3   # rounded to the current precision
        assert exact_to_mpf(SQRT2) == mpmath.sqrt(2)


def test_exact_to_mpf_sympy_numbers():
    sympy = pytest.importorskip("sympy")
    for dps in (30, 60):
        with mpmath.workdps(dps):
            got = exact_to_mpf(sympy.pi)
            ref = mpmath.pi()
            one_ulp = mpmath.ldexp(1, 2 - mpmath.mp.prec)
            assert abs(got - ref) <= one_ulp and got > 0
            got2 = exact_to_mpf(sympy.sqrt(3) / 7)
            assert abs(got2 - mpmath.sqrt(3) / 7) <= one_ulp
            assert exact_to_mpf(sympy.Rational(1, 3)) == mpmath.mpf(1) / 3


# ----------------------------------------------------------------- caps
def test_check_horizon_bounds_and_messages():
    assert check_horizon("2.5", "t") == Fraction(5, 2)
    assert check_horizon("0.5", "t") == Fraction(1, 2)
    assert check_horizon(MAX_HORIZON, "t") == MAX_HORIZON            # omega = 1 by default
    assert check_horizon(Fraction(MAX_HORIZON, 4), "t", 4.0) == Fraction(MAX_HORIZON, 4)
    assert check_horizon(0, "t", allow_zero=True) == 0
    _raises(ValueError, "t must be > 0, got 0", check_horizon, 0, "t")
    _raises(ValueError, "t_end must be > 0, got -1", check_horizon, -1, "t_end")
    _raises(ValueError, "t must be >= 0, got -1", check_horizon, -1, "t", allow_zero=True)
    _raises(ValueError, "t = 200000.0 is too long: omega * t must be <= 100000 (about 16,666 "
            "periods; the work cap symhx.impact.model.MAX_HORIZON), got omega = 1.0",
            check_horizon, 2e5, "t")
    over = Fraction(MAX_HORIZON) + Fraction(1, 10**9)
    with pytest.raises(ValueError, match="MAX_HORIZON"):
        check_horizon(over, "t")
    with pytest.raises(ValueError, match=r"^t = .* got omega = 4.0$"):
        check_horizon(Fraction(MAX_HORIZON, 4) + Fraction(1, 10**9), "t", 4.0)


def test_check_pipes_bounds_and_messages():
    assert check_pipes(1) == 1 and check_pipes(MAX_PIPES) == MAX_PIPES
    _raises(ValueError, "n must be >= 1, got 0", check_pipes, 0)
    _raises(ValueError, "pipes must be >= 1, got 0", check_pipes, 0, "pipes")
    _raises(ValueError, "n must be <= 10000 pipes (the work cap symhx.impact.model.MAX_PIPES), "
            "got 10001", check_pipes, MAX_PIPES + 1)


# ----------------------------------------------------------------- PipeRow validation
def test_defaults_and_stored_values():
    row = _row(x0=[1.5])
    assert row.omega == 1.0 and row.d == 1.0 and row.Omega == (SQRT2,)
    assert row.gap0().tolist() == [1.5, 0.5]
    row = PipeRow(2, omega=2.0, d=3.0, restitution=0.25, Omega=(0.5, 3.5),
                  alpha=[[1, 2], [3, 4]], beta=[[5, 6], [7, 8]], x0=[2.0, 7.5], v0=[-1, 1])
    assert (row.n, row.omega, row.d, row.restitution, row.Omega) == (2, 2.0, 3.0, 0.25,
                                                                      (0.5, 3.5))
    assert row.alpha.tolist() == [[1, 2], [3, 4]] and row.beta.tolist() == [[5, 6], [7, 8]]
    assert row.x0.tolist() == [2.0, 7.5] and row.v0.tolist() == [-1, 1]
    assert row.gap0().tolist() == [2.0, 5.5, 1.5]          # walls at 0 and (n + 1) d = 9
    assert row.omega_float().tolist() == [0.5, 3.5]
    # energy of the unforced row: sum v^2 / 2 + omega^2 (x - j d)^2 / 2, by hand
    assert row.energy0() == 0.5 * (1 + 1) + 0.5 * 4 * ((2 - 3) ** 2 + (7.5 - 6) ** 2)
    for arr in (row.alpha, row.beta, row.x0, row.v0):
        assert arr.dtype == np.float64 and not arr.flags.writeable
        with pytest.raises(ValueError):
            arr[0] = 0


def test_exact_values_are_kept():
    sympy = pytest.importorskip("sympy")
    row = PipeRow(2, omega="1/3", d="0.7", restitution="0.3", Omega=("1/7", SQRT2),
                  alpha=[["0.1", 0], [1, "2/3"]], beta=[[0, "0.5"], [0, 0]], x0=["0.5", "1.1"],
                  v0=["0.2", -1])
    assert row.exact("omega") == Fraction(1, 3) and row.omega == 1 / 3
    assert row.exact("d") == Fraction(7, 10) and row.exact("restitution") == Fraction(3, 10)
    assert row.exact("Omega") == (Fraction(1, 7), SQRT2)
    assert row.exact("alpha").tolist() == [[Fraction(1, 10), 0], [1, Fraction(2, 3)]]
    assert row.exact("beta").tolist() == [[0, Fraction(1, 2)], [0, 0]]
    assert row.exact("x0").tolist() == [Fraction(1, 2), Fraction(11, 10)]
    assert row.exact("v0").tolist() == [Fraction(1, 5), -1]
    # float arrays are exact as they are: the float64 arrays come back
    row = _row(2, x0=np.array([0.5, 1.25]), v0=np.array([0.1, 0.0]))
    assert row.exact("x0") is row.x0 and row.exact("v0") is row.v0
    # integer arrays beyond 2**53 keep their exact integers
    big = np.array([2**60 + 1], dtype=np.int64)
    row = _row(d=2.0**61, x0=big, v0=np.array([2**53], dtype=np.int64))
    assert row.exact("x0").tolist() == [2**60 + 1] and row.x0[0] == float(2**60)
    assert row.exact("v0") is row.v0
    # a sympy irrational is kept as the object, its float is its own evaluation
    row = _row(omega=sympy.sqrt(3), Omega=(1,))
    assert row.exact("omega") is not None and row.exact("omega") == sympy.sqrt(3)
    assert row.omega == math.sqrt(3)
    _raises(ValueError, "name must be one of ['Omega', 'alpha', 'beta', 'd', 'omega', "
            "'restitution', 'v0', 'x0'], got 'bogus'", row.exact, "bogus")


def test_scalar_parameters_refused_with_messages():
    sympy = pytest.importorskip("sympy")
    _raises(ValueError, "omega must be > 0, got 0", _row, omega=0)
    _raises(ValueError, "d must be > 0, got -1", _row, d=-1)
    _raises(ValueError, "omega must be finite, got nan", _row, omega=math.nan)
    _raises(ValueError, "omega must be finite, got exp(1000)", _row, omega=sympy.exp(1000))
    _raises(ValueError, "x0[0] must be finite, got exp(1000)", _row, x0=[sympy.exp(1000)])
    _raises(ValueError, "x0[0] = '1e400' is beyond the float64 range", _row, x0=["1e400"])
    _raises(ValueError, "d = '1e400' is beyond the float64 range", _row, d="1e400")
    _raises(ValueError, "restitution must lie in [0, 1], got '1.5'", _row, restitution="1.5")
    _raises(ValueError, "restitution must lie in [0, 1], got sqrt(2)", _row, restitution=SQRT2)
    # exact check: 1 + 1e-22 rounds to 1.0 in float64 but is not in [0, 1]
    _raises(ValueError, "restitution must lie in [0, 1], got '1.0000000000000000000001'",
            _row, restitution="1.0000000000000000000001")
    with pytest.raises(TypeError, match=r"^restitution must be"):
        _row(restitution=True)
    with pytest.raises(TypeError, match=r"^d must be"):
        _row(d=True)
    for r in (0, 1, "0.5", 0.5, sympy.sqrt(2) / 2):
        assert _row(restitution=r).restitution == float(r)
    assert _row(omega=0.5, d=0.5, x0=[0.5]).omega == 0.5


def test_scale_bounds_and_messages():
    lo, hi = 1 / MAX_SCALE, MAX_SCALE
    for name in ("omega", "d"):
        for ok in (lo, hi):
            kw = {name: ok, "x0": [ok if name == "d" else 1.0]}
            assert getattr(_row(**kw), name) == ok
        for bad in (np.nextafter(lo, 0), np.nextafter(hi, np.inf)):
            _raises(ValueError, _scale_msg(name, float(bad), True), _row,
                    **{name: float(bad), "x0": [float(bad) if name == "d" else 1.0]})
    big = float(np.nextafter(hi, np.inf))
    assert _row(alpha=[[hi]], beta=[[-hi]], v0=[hi], Omega=(hi,)).alpha[0, 0] == hi
    assert _row(alpha=[[1e-300]]).alpha[0, 0] == 1e-300        # no lower bound on amplitudes
    _raises(ValueError, _scale_msg("Omega[1]", big, False), _row, Omega=(2.0, big),
            alpha=[[0, 0]], beta=[[0, 0]])
    _raises(ValueError, _scale_msg("alpha[1, 0]", -big, False), _row, 2, alpha=[[1.0], [-big]])
    _raises(ValueError, _scale_msg("beta[0, 1]", big, False), _row, Omega=(2.0, 3.0),
            alpha=[[0, 0]], beta=[[0.5, big]])
    _raises(ValueError, _scale_msg("v0[2]", big, False), _row, 3, v0=[0, 1, big])


def test_omega_sequence_forms_and_resonance():
    assert _row(Omega=2.0).Omega == (2.0,)
    assert _row(Omega="2").exact("Omega") == (Fraction(2),)
    assert _row(Omega=np.array([0.5, 2.0]), alpha=[[0, 0]], beta=[[0, 0]]).Omega == (0.5, 2.0)
    assert _row(Omega=(0,)).Omega == (0,) and _row(Omega=(0.5,)).Omega == (0.5,)
    _raises(ValueError, "Omega must hold at least one forcing frequency", _row, Omega=())
    _raises(ValueError, "Omega[1] must be >= 0, got -1.0", _row, Omega=(2.0, -1.0),
            alpha=[[0, 0]], beta=[[0, 0]])

    def res(i, wf, om):
        return (f"Omega[{i}] = {wf!r} equals omega = {om!r} (resonance): the forced response "
                "is unbounded; choose Omega[i] != omega")

    _raises(ValueError, res(0, 1.0, 1.0), _row, Omega=(1.0,))
    third = 1 / 3
    _raises(ValueError, res(0, third, third), _row, omega="1/3", Omega=("1/3",))
    # within 1e-12 (relative, in omega^2) of omega is resonance too; 1e-11 is not
    for om in (1.0, 2.0, 10.0):
        near = om * (1 + 1e-13)
        _raises(ValueError, res(0, near, om), _row, omega=om, Omega=(near,))
        far = om * (1 + 1e-11)
        assert _row(omega=om, Omega=(far,)).Omega == (far,)
    assert _row(omega=2.0, Omega=(1.0,)).Omega == (1.0,)


def test_array_shapes_types_and_values():
    # a 1-D array is a column when there is one forcing frequency
    for alpha in (np.array([0.1, 0.2]), [0.1, 0.2]):
        row = _row(2, alpha=alpha)
        assert row.alpha.shape == (2, 1) and row.alpha[:, 0].tolist() == [0.1, 0.2]
    row = _row(2, alpha=np.array([[1], [2]], dtype=np.int32))
    assert row.alpha.dtype == np.float64 and row.alpha.tolist() == [[1.0], [2.0]]
    assert row.exact("alpha") is row.alpha
    _raises(ValueError, "alpha must have shape (2, 2), got (2,)", _row, 2,
            Omega=(0.5, 2.0), alpha=np.array([0.1, 0.2]), beta=[[0, 0], [0, 0]])
    _raises(ValueError, "beta must have shape (2, 2), got (2,)", _row, 2,
            Omega=(0.5, 2.0), alpha=[[0, 0], [0, 0]], beta=[0.1, 0.2])
    _raises(ValueError, "alpha must have shape (1, 1), got (1, 2)", _row, alpha=np.zeros((1, 2)))
    _raises(ValueError, "x0 must have shape (2,), got (3,)", _row, 2, x0=np.array([1., 2, 2.5]))
    _raises(ValueError, "v0 must have shape (2,), got (1,)", _row, 2, v0=[0.0])
    _raises(ValueError, "alpha must be finite, got np.float64(inf) at index (1, 0)", _row, 2,
            alpha=np.array([[0.0], [np.inf]]))
    _raises(ValueError, "beta[0][0] must be finite, got nan", _row, beta=[[math.nan]])
    _raises(TypeError, "alpha must be an array of real numbers, got True", _row, alpha=True)
    _raises(TypeError, "x0 must be an array of real numbers, got '1'", _row, x0="1")

    class NoArray:
        def __array__(self, *args, **kw):
            raise TypeError("refused")

    _raises(TypeError, "v0 must be an array of real numbers (refused)", _row, 2, v0=NoArray())


def test_walls_and_overlaps():
    assert _row(x0=[0.5]).x0[0] == 0.5 and _row(x0=[1.9]).x0[0] == 1.9
    assert _row(d=2.0, x0=[3.5]).x0[0] == 3.5           # right wall at (n + 1) d = 4
    msg = "x0 must be strictly increasing inside (0, (n + 1) d) = (0, {}): pipes overlap at site {}"
    _raises(ValueError, msg.format(2.0, 1), _row, x0=[2.0])
    _raises(ValueError, msg.format(2.0, 1), _row, x0=[2.5])
    _raises(ValueError, msg.format(2.0, 0), _row, x0=[0.0])
    _raises(ValueError, msg.format(4.0, 1), _row, d=2.0, x0=[4.5])
    _raises(ValueError, msg.format(3.0, 1), _row, 2, x0=[1.0, 1.0])
    _raises(ValueError, msg.format(4.0, 2), _row, 3, x0=[1.0, 2.0, 1.5])


# ----------------------------------------------------------------- PipeRow.random
def _forced0(row):
    """Forced displacement and velocity at t = 0 (eq. 21), from the row's own amplitudes:
    sum_i alpha_ji / (omega^2 - Omega_i^2) and sum_i Omega_i beta_ji / (omega^2 - Omega_i^2)."""
    Om = np.array([float(w) for w in row.Omega])
    den = row.omega**2 - Om**2
    return (row.alpha / den).sum(axis=1), (row.beta * Om / den).sum(axis=1)


def _documented_draw(n, sigma, seed, *, omega=1.0, d=1.0, Omega=(SQRT2,), sigma0=None):
    """The documented draw when no pipe needs a redraw: forcing first, then (alpha_0j, beta_0j)
    pipe by pipe from one generator."""
    rng = np.random.default_rng(seed)
    Omega = tuple(float(w) for w in Omega)
    s0 = sigma if sigma0 is None else sigma0
    k = len(Omega)
    alpha = rng.normal(0.0, sigma, size=(n, k)) if sigma > 0 else np.zeros((n, k))
    beta = rng.normal(0.0, sigma, size=(n, k)) if sigma > 0 else np.zeros((n, k))
    free = [rng.normal(0.0, s0, size=2) if s0 > 0 else (0.0, 0.0) for _ in range(n)]
    return alpha, beta, np.array(free, dtype=float).reshape(n, 2)


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
    alpha, beta, free = _documented_draw(**kw)
    assert np.array_equal(row.alpha, alpha) and np.array_equal(row.beta, beta)
    f0, fv0 = _forced0(row)
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
    f0, fv0 = _forced0(row)
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


def _too_large_msg(sigma, sigma0, omega, Omega, d, scale):
    return (f"could not draw non-overlapping initial positions: with sigma={sigma!r}, "
            f"sigma0={sigma0!r}, omega={omega!r}, Omega={Omega!r} the random displacements "
            f"(scale ~{scale:.3g}) are too large for the spacing d={d!r}; use a smaller "
            "sigma/sigma0, a larger d, or Omega further from omega")


def test_random_refusals_and_messages():
    # up front: a pipe must land in (0, (n + 1) d), probability < (n + 1) d / (sigma0 sqrt(2 pi))
    # per draw: below 1e-3 the draw is refused before any work
    sig0 = 3 * 1.0 / (1e-3 * math.sqrt(2 * math.pi))        # (n + 1) d = 3, probability 1e-3 / 1
    scale = 0.0 * 1.0 + sig0 * 1.01
    _raises(ValueError, _too_large_msg(0.0, sig0 * 1.01, 1.0, (SQRT2,), 1.0, scale),
            PipeRow.random, 2, 0.0, sigma0=sig0 * 1.01, seed=1)
    # forced displacements alone overlap (sigma0 = 0, strong forcing near resonance): each of
    # the 10 forcings fails at once; scale = sigma sum 1 / |omega^2 - Omega^2| + sigma0
    den = abs(1.0 - 1.05**2)
    _raises(ValueError, _too_large_msg(3.0, 0.0, 1.0, (1.05,), 1.0, 3.0 / den),
            PipeRow.random, 6, 3.0, sigma0=0.0, Omega=(1.05,), seed=0)
    # forced parts that overflow float64 are refused, not turned into NaN positions
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(2, 1e100, seed=0, Omega=(1.0 + 1e-11,))
    _raises(ValueError, "omega must be > 0, got -1", PipeRow.random, 2, 0.1, omega=-1)
    _raises(ValueError, "d must be > 0, got 0", PipeRow.random, 2, 0.1, d=0)
    _raises(ValueError, _scale_msg("omega", 1e101, True), PipeRow.random, 2, 0.1, omega=1e101)
    _raises(ValueError, _scale_msg("d", 1e-101, True), PipeRow.random, 2, 0.1, d=1e-101)
    _raises(ValueError, "Omega must hold at least one forcing frequency", PipeRow.random, 2,
            0.1, Omega=())
    _raises(ValueError, "Omega[1] = 1.0 equals omega = 1.0 (resonance): the forced response "
            "is unbounded; choose Omega[i] != omega", PipeRow.random, 2, 0.1, Omega=(2.0, 1.0))
    _raises(ValueError, "Omega[0] = 2.0000000000002 equals omega = 2.0 (resonance): the forced "
            "response "
            "is unbounded; choose Omega[i] != omega", PipeRow.random, 2, 0.1, omega=2.0,
            Omega=(2.0 * (1 + 1e-13),))
    assert PipeRow.random(2, 1e-12, omega=10.0, Omega=(10.0 * (1 + 1e-11),), sigma0=0.1,
                          seed=0).n == 2
    _raises(ValueError, "restitution must lie in [0, 1], got 2", PipeRow.random, 2, 0.1,
            restitution=2)
    with pytest.raises(TypeError, match=r"^restitution must be"):
        PipeRow.random(2, 0.1, restitution=True)
    with pytest.raises(ValueError, match=r"^sigma must be >= 0"):
        PipeRow.random(2, -0.1)
    with pytest.raises(ValueError, match=r"^sigma0 must be >= 0"):
        PipeRow.random(2, 0.1, sigma0=-0.1)
    with pytest.raises(TypeError, match=r"^sigma0 must be"):
        PipeRow.random(2, 0.1, sigma0=True)
    with pytest.raises(ValueError, match=r"^max_redraws must be >= 1, got 0$"):
        PipeRow.random(2, 0.1, max_redraws=0)
    with pytest.raises(ValueError, match=r"^n must be >= 1"):
        PipeRow.random(0, 0.1)
    with pytest.raises(ValueError, match=r"^sigma = '1e400' is beyond the float64 range$"):
        PipeRow.random(2, "1e400")
    with pytest.raises(ValueError, match=r"^omega = '1e400' is beyond the float64 range$"):
        PipeRow.random(2, 0.1, omega="1e400")
    with pytest.raises(ValueError, match=r"^d = '1e400' is beyond the float64 range$"):
        PipeRow.random(2, 0.1, d="1e400")
    with pytest.raises(ValueError, match=re.escape("Omega[0] = '1e400' is beyond")):
        PipeRow.random(2, 0.1, Omega=("1e400",))


def test_random_scalar_omega_and_defaults():
    row = PipeRow.random(3, 0.1, seed=4, Omega=2.0)
    assert row.Omega == (2.0,)
    row = PipeRow.random(3, 0.1, seed=4, Omega="1/2")
    assert row.exact("Omega") == (Fraction(1, 2),)
    row = PipeRow.random(3, 0.1, seed=4)
    assert (row.omega, row.d, row.Omega, row.restitution) == (1.0, 1.0, (SQRT2,), 0.8)


def test_random_redraw_budgets():
    # max_redraws = 1: each pipe gets one draw per pass; with sigma0 ~ d most passes fail and a
    # new pass starts; the row still comes out valid when some pass succeeds
    row = PipeRow.random(2, 0.05, seed=3, sigma0=0.45, max_redraws=1)
    assert np.all(row.gap0() > 0)
    # hopeless within the budgets: 10 forcings, each at most 20 max_redraws draws
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(40, 0.05, seed=3, sigma0=2.0, max_redraws=1)


def test_energy_by_hand_at_another_omega():
    row = PipeRow(2, omega=3.0, d=0.75, restitution=1, Omega=(1.0,), alpha=[[0], [0]],
                  beta=[[0], [0]], x0=[0.25, 2.0], v0=[0.5, -2.0])
    # j d = 0.75, 1.5: displacements -0.5, 0.5
    assert row.energy0() == 0.5 * (0.25 + 4.0) + 0.5 * 9.0 * (0.25 + 0.25)


def test_documented_defaults():
    import inspect

    sig = inspect.signature(PipeRow.random).parameters
    assert {k: sig[k].default for k in ("seed", "restitution", "omega", "d", "Omega",
                                        "sigma0", "max_redraws")} == {
        "seed": None, "restitution": 0.8, "omega": 1.0, "d": 1.0, "Omega": (SQRT2,),
        "sigma0": None, "max_redraws": 10_000}
    sig = inspect.signature(PipeRow.__init__).parameters
    assert (sig["omega"].default, sig["d"].default, sig["Omega"].default) == (1.0, 1.0,
                                                                              (SQRT2,))


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


def test_random_draw_budgets_counted(draws):
    # hopeless rows within the documented budgets; the draws are counted
    # (a) max_redraws = 1: 20 max_redraws = 20 pair draws per forcing, 10 forcings
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(40, 0.05, seed=3, sigma0=2.0, max_redraws=1)
    assert draws.count("forcing") == 20 and draws.count("pair") == 200
    draws.clear()
    # (b) the forced displacement puts the single pipe far outside the walls: all
    # _DRAWS_PER_PIPE * n = 4000 draws go to the first forcing, then the row is refused
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(1, 100.0, seed=0, sigma0=0.1, Omega=(1.05,))
    assert draws.count("forcing") == 2 and draws.count("pair") == 4000
    draws.clear()
    # (c) sigma0 = 0: one deterministic try per pipe and pass, all 10 forcings are drawn
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(6, 3.0, sigma0=0.0, Omega=(1.05,), seed=0)
    assert draws.count("forcing") == 20 and draws.count("pair") == 0
    draws.clear()
    # (d) a forced velocity beyond float64 (beta Omega overflows, alpha / den does not):
    # refused at the first forcing, before any pair is drawn
    den = 1.0 - 1e5**2
    with pytest.raises(ValueError) as info, np.errstate(over="ignore"):
        PipeRow.random(2, 1e304, seed=0, Omega=(1e5,), sigma0=0.1)
    scale = 1e304 / abs(den) + 0.1
    assert str(info.value) == _too_large_msg(1e304, 0.1, 1.0, (1e5,), 1.0, scale)
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


def _documented_redraws(n, sigma, seed, sigma0, max_redraws, *, d=1.0, omega=1.0,
                        Omega=(1.4142135623730951,)):
    """The documented non-overlap rule, written out from the docstring: per forcing up to 100
    passes over the pipes from the left, each pipe at most max_redraws draws per pass, at most
    20 max_redraws draws per forcing and 4000 n in all; at most 10 forcings.  Returns
    (alpha, beta, x0, v0) or None."""
    rng = np.random.default_rng(seed)
    Om = np.array(Omega)
    den = omega**2 - Om**2
    right = (n + 1) * d
    left_in_all = 4000 * n
    for _ in range(10):
        alpha = rng.normal(0.0, sigma, size=(n, len(Om)))
        beta = rng.normal(0.0, sigma, size=(n, len(Om)))
        f0, fv0 = (alpha / den).sum(axis=1), (beta * Om / den).sum(axis=1)
        left = 20 * max_redraws
        for _ in range(100):
            x0, v0, prev = [], [], 0.0
            for j in range(n):
                placed = False
                for _ in range(min(max_redraws, left, left_in_all)):
                    left -= 1
                    left_in_all -= 1
                    a0, b0 = rng.normal(0.0, sigma0, size=2)
                    xj = (j + 1) * d + a0 + f0[j]
                    if prev < xj < right:
                        placed = True
                        break
                if not placed:
                    break
                x0.append(xj)
                v0.append(omega * b0 + fv0[j])
                prev = xj
            else:
                return alpha, beta, np.array(x0), np.array(v0)
            if left_in_all <= 0:
                return None
    return None


@pytest.mark.parametrize("n, sigma, seed, sigma0, max_redraws", [
    (2, 0.05, 3, 0.45, 1), (3, 0.1, 1, 0.6, 2), (5, 0.1, 2, 0.5, 1), (4, 0.2, 7, 0.7, 3),
    (6, 0.05, 4, 0.4, 5), (8, 0.1, 0, 0.6, 10_000), (3, 0.3, 9, 0.9, 1),
])
def test_random_redraws_follow_the_documented_rule(n, sigma, seed, sigma0, max_redraws):
    ref = _documented_redraws(n, sigma, seed, sigma0, max_redraws)
    if ref is None:
        with pytest.raises(ValueError, match="could not draw"):
            PipeRow.random(n, sigma, seed=seed, sigma0=sigma0, max_redraws=max_redraws)
        return
    row = PipeRow.random(n, sigma, seed=seed, sigma0=sigma0, max_redraws=max_redraws)
    for got, want in zip((row.alpha, row.beta, row.x0, row.v0), ref, strict=True):
        assert np.array_equal(got, want)


def test_more_refusals():
    _raises(ValueError, "omega must be > 0, got 0", PipeRow.random, 2, 0.1, omega=0)
    _raises(ValueError, "Omega[0] = 10.0000000000001 equals omega = 10.0 (resonance): the "
            "forced response is unbounded; choose Omega[i] != omega", PipeRow.random, 2, 0.1,
            omega=10.0, Omega=(10.0 * (1 + 1e-14),))
    with pytest.raises(ValueError, match=r"^sigma0 = '1e400' is beyond the float64 range$"):
        PipeRow.random(2, 0.1, sigma0="1e400")


def test_exact_to_mpf_sympy_rationals_rounded_once():
    # p/q just below or above the midpoint of two doubles: rounding it first to dps + 10
    # decimal digits and then to 53 bits gives the wrong neighbour; sympy's own conversion
    # (mpmath's _mpmath_ protocol) rounds once
    sympy = pytest.importorskip("sympy")
    for m, sgn in ((2**52 + 1, -1), (2**52 + 2, 1)):
        p, q = (2 * m + 1) * 10**30 + sgn, 2**53 * 10**30
        with mpmath.workprec(53):
            assert exact_to_mpf(sympy.Rational(p, q)) == _nearest_binary(p, q, 53)


def test_exact_to_mpf_fallback_types():
    with mpmath.workdps(20):     # anything else goes to mpmath (decimal strings)
        assert exact_to_mpf("0.1") == mpmath.mpf(1) / 10


def test_integer_arrays_beyond_2_53_and_omega_types():
    big = np.array([2**53 + 1], dtype=np.int64)      # not a float64: kept exactly
    row = _row(d=2.0**55, x0=big)
    assert row.exact("x0").tolist() == [2**53 + 1] and row.x0[0] == 2.0**53
    exact = np.array([2**53], dtype=np.int64)        # a float64 already: no object array
    assert _row(d=2.0**55, x0=exact).exact("x0").dtype == np.float64
    row = _row(Omega=(0.5, 2.0), alpha=[[0, 0]], beta=[[0, 0]])
    assert repr(row.Omega) == "(0.5, 2.0)"           # floats stay floats
    row = _row(Omega=("1/2", 2.0, SQRT2), alpha=[[0, 0, 0]], beta=[[0, 0, 0]])
    assert row.Omega == (Fraction(1, 2), 2.0, SQRT2) and isinstance(row.Omega[0], Fraction)
    assert row.omega_float().tolist() == [0.5, 2.0, math.sqrt(2)]
    _raises(ValueError, "d must be > 0, got 0", _row, d=0)
    _raises(ValueError, "Omega[1] = '1e400' is beyond the float64 range", _row,
            Omega=(2.0, "1e400"), alpha=[[0, 0]], beta=[[0, 0]])


def test_resonance_boundary_is_inclusive(draws):
    # omega = 1e6: 1e-12 omega^2 == 1.0 exactly, and 999999.9999995**2 == 1e12 - 1 in float64
    om, w = 1e6, 999999.9999995
    assert abs(w * w - om * om) == 1e-12 * om * om == 1.0
    with pytest.raises(ValueError, match="resonance"):
        _row(omega=om, Omega=(w,), x0=[1.0])
    with pytest.raises(ValueError, match="resonance"):
        PipeRow.random(1, 0.1, omega=om, Omega=(w,), seed=0)
    assert draws == []          # refused before anything is drawn


def test_random_budget_boundaries(draws):
    # total = 4000 draws for one pipe, 3999 per pass: the second pass still gets the last draw
    with pytest.raises(ValueError, match="could not draw"):
        PipeRow.random(1, 100.0, seed=0, sigma0=0.1, Omega=(1.05,), max_redraws=3999)
    assert draws.count("pair") == 4000 and draws.count("forcing") == 2
    draws.clear()
    # the up-front refusal is strict: (n + 1) d / (sigma0 sqrt(2 pi)) == 1e-3 exactly is drawn
    sig0 = 797.8845608028654
    assert 2.0 / (sig0 * math.sqrt(2 * math.pi)) == 1e-3
    try:
        PipeRow.random(1, 0.0, seed=0, sigma0=sig0)
    except ValueError:
        pass
    assert draws.count("pair") > 0
