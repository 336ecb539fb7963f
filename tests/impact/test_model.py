"""``symhx.impact.model``: the pipe row (eqs. 17-21), its exact inputs and its caps.

* :data:`SQRT2` and :func:`exact_to_mpf` against correctly rounded values computed in exact
  integer arithmetic (``tests.reference.impact``);
* every validation boundary (``MAX_PIPES``, ``MAX_HORIZON``, ``MAX_SCALE``, restitution ``[0, 1]``
  exactly, resonance, overlapping pipes, walls) on both sides; refusals name the argument, show
  the value and say what is allowed.

:meth:`PipeRow.random` has its own file (``test_model_random.py``).
"""

from __future__ import annotations

import math
import pickle
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
from tests.harness.errors import assert_refuses
from tests.reference.impact import nearest_binary, sqrt2_rounded


def _row(n=1, **kw):
    base = dict(restitution=1, alpha=[[0.0]] * n, beta=[[0.0]] * n,
                x0=[float(j + 1) for j in range(n)], v0=[0.0] * n)
    base.update(kw)
    return PipeRow(n, **base)


def _refuses_scale(fn, name, value, positive, *args, **kw):
    """The scale refusal: names the input, shows it, gives the range and the cap's name."""
    rng = "[1e-100, 1e+100]" if positive else "<= 1e+100 in size"
    assert_refuses(fn, *args, arg=name, value=f"{name} = {value!r}",
                   allowed=[rng, "symhx.impact.model.MAX_SCALE"], **kw)


# ----------------------------------------------------------------- exact numbers
@pytest.mark.parametrize("prec", [2, 3, 24, 53, 54, 100, 333, 1401, 2000])
def test_sqrt2_correctly_rounded_at_every_precision(prec):
    with mpmath.workprec(prec):
        got = mpmath.mpf(SQRT2)
    assert got == sqrt2_rounded(prec)
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
                assert got == nearest_binary(p, q, prec) and neg == -got   # negation: exact
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


def test_exact_to_mpf_sympy_rationals_rounded_once():
    # p/q just below or above the midpoint of two doubles: rounding it first to dps + 10
    # decimal digits and then to 53 bits gives the wrong neighbour; sympy's own conversion
    # (mpmath's _mpmath_ protocol) rounds once
    sympy = pytest.importorskip("sympy")
    for m, sgn in ((2**52 + 1, -1), (2**52 + 2, 1)):
        p, q = (2 * m + 1) * 10**30 + sgn, 2**53 * 10**30
        with mpmath.workprec(53):
            assert exact_to_mpf(sympy.Rational(p, q)) == nearest_binary(p, q, 53)


def test_exact_to_mpf_fallback_types():
    with mpmath.workdps(20):     # anything else goes to mpmath (decimal strings)
        assert exact_to_mpf("0.1") == mpmath.mpf(1) / 10


# ----------------------------------------------------------------- caps
def test_check_horizon_bounds_and_messages():
    assert check_horizon("2.5", "t") == Fraction(5, 2)
    assert check_horizon("0.5", "t") == Fraction(1, 2)
    assert check_horizon(MAX_HORIZON, "t") == MAX_HORIZON            # omega = 1 by default
    assert check_horizon(Fraction(MAX_HORIZON, 4), "t", 4.0) == Fraction(MAX_HORIZON, 4)
    assert check_horizon(0, "t", allow_zero=True) == 0
    assert_refuses(check_horizon, 0, "t", arg="t", value="0", allowed="> 0")
    assert_refuses(check_horizon, -1, "t_end", arg="t_end", value="-1", allowed="> 0")
    assert_refuses(check_horizon, -1, "t", allow_zero=True, arg="t", value="-1", allowed=">= 0")
    assert_refuses(check_horizon, 2e5, "t", arg="t", value="200000.0",
                   allowed=["omega * t must be <= 100000", "16,666 periods",
                            "symhx.impact.model.MAX_HORIZON", "omega = 1.0"])
    over = Fraction(MAX_HORIZON) + Fraction(1, 10**9)
    assert_refuses(check_horizon, over, "t", arg="t", allowed="MAX_HORIZON")
    msg = assert_refuses(check_horizon, Fraction(MAX_HORIZON, 4) + Fraction(1, 10**9), "t", 4.0,
                         arg="t", allowed="MAX_HORIZON")
    assert msg.endswith("got omega = 4.0")


def test_check_pipes_bounds_and_messages():
    assert check_pipes(1) == 1 and check_pipes(MAX_PIPES) == MAX_PIPES
    assert_refuses(check_pipes, 0, arg="n", value="0", allowed=">= 1")
    assert_refuses(check_pipes, 0, "pipes", arg="pipes", value="0", allowed=">= 1")
    assert_refuses(check_pipes, MAX_PIPES + 1, arg="n", value="10001",
                   allowed=["<= 10000 pipes", "symhx.impact.model.MAX_PIPES"])


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


def test_energy_by_hand_at_another_omega():
    row = PipeRow(2, omega=3.0, d=0.75, restitution=1, Omega=(1.0,), alpha=[[0], [0]],
                  beta=[[0], [0]], x0=[0.25, 2.0], v0=[0.5, -2.0])
    # j d = 0.75, 1.5: displacements -0.5, 0.5
    assert row.energy0() == 0.5 * (0.25 + 4.0) + 0.5 * 9.0 * (0.25 + 0.25)


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
    assert_refuses(row.exact, "bogus", arg="name", value="'bogus'",
                   allowed="['Omega', 'alpha', 'beta', 'd', 'omega', 'restitution', 'v0', 'x0']")


def test_exact_values_of_decimal_strings_and_mpf():
    row = PipeRow(3, omega="1.1", d="1", restitution="0.85", Omega=("0.3", "2.7"),
                  alpha=[["0.2", "-0.15"], ["-0.1", "0.3"], ["0.25", "0.05"]],
                  beta=[["0.05", "0.1"], ["0.3", "-0.2"], ["-0.15", "0.12"]],
                  x0=["0.9", "2.05", "3.1"], v0=["1.2", "-1.3", "0.9"])
    assert row.exact("x0")[1] == Fraction(41, 20)
    assert row.exact("Omega")[1] == Fraction(27, 10)
    assert row.exact("restitution") == Fraction(17, 20)
    mp60 = mpmath.mpf(1) / 3
    with mpmath.workdps(60):
        third = mpmath.mpf(1) / 3
    r = PipeRow(1, restitution=1, alpha=[[third]], beta=[[0]], x0=[mp60], v0=[0])
    man, exp = third.man_exp
    assert r.exact("alpha")[0, 0] == Fraction(int(man)) * Fraction(2) ** int(exp)
    assert r.exact("x0")[0] == Fraction(*float(mp60).as_integer_ratio())


def test_scalar_parameters_refused_with_messages():
    sympy = pytest.importorskip("sympy")
    assert_refuses(_row, omega=0, arg="omega", value="0", allowed="> 0")
    assert_refuses(_row, d=-1, arg="d", value="-1", allowed="> 0")
    assert_refuses(_row, omega=math.nan, arg="omega", value="nan", allowed="finite")
    assert_refuses(_row, omega=sympy.exp(1000), arg="omega", value="exp(1000)", allowed="finite")
    assert_refuses(_row, x0=[sympy.exp(1000)], arg="x0[0]", value="exp(1000)", allowed="finite")
    assert_refuses(_row, x0=["1e400"], arg="x0[0]", value="'1e400'", allowed="float64 range")
    assert_refuses(_row, d="1e400", arg="d", value="'1e400'", allowed="float64 range")
    assert_refuses(_row, restitution="1.5", arg="restitution", value="'1.5'", allowed="[0, 1]")
    assert_refuses(_row, restitution=SQRT2, arg="restitution", value="sqrt(2)", allowed="[0, 1]")
    # exact check: 1 + 1e-22 rounds to 1.0 in float64 but is not in [0, 1]
    assert_refuses(_row, restitution="1.0000000000000000000001", arg="restitution",
                   value="'1.0000000000000000000001'", allowed="[0, 1]")
    assert_refuses(_row, restitution=True, exc=TypeError, arg="restitution", value="True")
    assert_refuses(_row, d=True, exc=TypeError, arg="d", value="True")
    for r in (0, 1, "0.5", 0.5, sympy.sqrt(2) / 2):
        assert _row(restitution=r).restitution == float(r)
    assert _row(omega=0.5, d=0.5, x0=[0.5]).omega == 0.5


@pytest.mark.parametrize("kwargs, name", [
    (dict(Omega=(1.0,)), "Omega[0]"),
    (dict(restitution=1.5), "restitution"),
    (dict(restitution=-0.1), "restitution"),
    (dict(x0=[2.0, 1.5]), "x0"),
    (dict(x0=[0.0, 1.5]), "x0"),
    (dict(x0=[1.0, float("nan")]), "x0"),
    (dict(v0=[1.0, float("inf")]), "v0"),
    (dict(alpha=[[1.0], [float("nan")]]), "alpha[1][0]"),
    (dict(beta=[[1.0]]), "beta"),
    (dict(omega=0.0), "omega"),
    (dict(d=-1.0), "d"),
])
def test_bad_row_values_name_the_argument(kwargs, name):
    base = dict(restitution=1.0, alpha=[[0.0], [0.0]], beta=[[0.0], [0.0]], x0=[1.0, 2.0],
                v0=[0.0, 0.0])
    base.update(kwargs)
    assert_refuses(PipeRow, 2, arg=name, **base)


def test_bad_row_values_named_with_their_index():
    assert_refuses(PipeRow, 1, restitution=1, alpha=[["nan"]], beta=[[0]], x0=[1], v0=[0],
                   arg="alpha[0][0]", value="nan")
    assert_refuses(PipeRow, 2, restitution=1, alpha=[[0], [0]], beta=[[0], [math.inf]],
                   x0=[1, 2], v0=[0, 0], arg="beta[1][0]", value="inf", allowed="finite")
    assert_refuses(PipeRow, 1, restitution=True, alpha=[[0]], beta=[[0]], x0=[1], v0=[0],
                   exc=TypeError, arg="restitution")
    assert_refuses(PipeRow, 1, restitution="1.5", alpha=[[0]], beta=[[0]], x0=[1], v0=[0],
                   arg="restitution", value="1.5")
    assert_refuses(PipeRow, 1, restitution=1, Omega=("1",), alpha=[[0]], beta=[[0]], x0=[1],
                   v0=[0], arg="Omega[0]", allowed="resonance")


def test_zero_pipes_refused():
    assert_refuses(PipeRow, 0, restitution=1, alpha=[], beta=[], x0=[], v0=[], arg="n",
                   value="0", allowed=">= 1")


def test_scale_bounds_and_messages():
    lo, hi = 1 / MAX_SCALE, MAX_SCALE
    for name in ("omega", "d"):
        for ok in (lo, hi):
            kw = {name: ok, "x0": [ok if name == "d" else 1.0]}
            assert getattr(_row(**kw), name) == ok
        for bad in (np.nextafter(lo, 0), np.nextafter(hi, np.inf)):
            _refuses_scale(_row, name, float(bad), True,
                           **{name: float(bad), "x0": [float(bad) if name == "d" else 1.0]})
    big = float(np.nextafter(hi, np.inf))
    assert _row(alpha=[[hi]], beta=[[-hi]], v0=[hi], Omega=(hi,)).alpha[0, 0] == hi
    assert _row(alpha=[[1e-300]]).alpha[0, 0] == 1e-300        # no lower bound on amplitudes
    _refuses_scale(_row, "Omega[1]", big, False, Omega=(2.0, big), alpha=[[0, 0]],
                   beta=[[0, 0]])
    _refuses_scale(_row, "alpha[1, 0]", -big, False, 2, alpha=[[1.0], [-big]])
    _refuses_scale(_row, "beta[0, 1]", big, False, Omega=(2.0, 3.0), alpha=[[0, 0]],
                   beta=[[0.5, big]])
    _refuses_scale(_row, "v0[2]", big, False, 3, v0=[0, 1, big])


def test_omega_sequence_forms_and_resonance():
    assert _row(Omega=2.0).Omega == (2.0,)
    assert _row(Omega="2").exact("Omega") == (Fraction(2),)
    assert _row(Omega=np.array([0.5, 2.0]), alpha=[[0, 0]], beta=[[0, 0]]).Omega == (0.5, 2.0)
    assert _row(Omega=(0,)).Omega == (0,) and _row(Omega=(0.5,)).Omega == (0.5,)
    assert_refuses(_row, Omega=(), arg="Omega", allowed="at least one forcing frequency")
    assert_refuses(_row, Omega=(2.0, -1.0), alpha=[[0, 0]], beta=[[0, 0]], arg="Omega[1]",
                   value="-1.0", allowed=">= 0")

    def res(i, wf, om, **kw):
        assert_refuses(_row, arg=[f"Omega[{i}]", "omega"], value=f"Omega[{i}] = {wf!r}",
                       allowed=[f"omega = {om!r}", "resonance", "Omega[i] != omega"], **kw)

    res(0, 1.0, 1.0, Omega=(1.0,))
    third = 1 / 3
    res(0, third, third, omega="1/3", Omega=("1/3",))
    # within 1e-12 (relative, in omega^2) of omega is resonance too; 1e-11 is not
    for om in (1.0, 2.0, 10.0):
        near = om * (1 + 1e-13)
        res(0, near, om, omega=om, Omega=(near,))
        far = om * (1 + 1e-11)
        assert _row(omega=om, Omega=(far,)).Omega == (far,)
    assert _row(omega=2.0, Omega=(1.0,)).Omega == (1.0,)


def test_resonance_boundary_is_inclusive():
    # omega = 1e6: 1e-12 omega^2 == 1.0 exactly, and 999999.9999995**2 == 1e12 - 1 in float64
    om, w = 1e6, 999999.9999995
    assert abs(w * w - om * om) == 1e-12 * om * om == 1.0
    assert_refuses(_row, omega=om, Omega=(w,), x0=[1.0], arg="Omega[0]", allowed="resonance")


def test_array_shapes_types_and_values():
    # a 1-D array is a column when there is one forcing frequency
    for alpha in (np.array([0.1, 0.2]), [0.1, 0.2]):
        row = _row(2, alpha=alpha)
        assert row.alpha.shape == (2, 1) and row.alpha[:, 0].tolist() == [0.1, 0.2]
    row = _row(2, alpha=np.array([[1], [2]], dtype=np.int32))
    assert row.alpha.dtype == np.float64 and row.alpha.tolist() == [[1.0], [2.0]]
    assert row.exact("alpha") is row.alpha
    assert_refuses(_row, 2, Omega=(0.5, 2.0), alpha=np.array([0.1, 0.2]),
                   beta=[[0, 0], [0, 0]], arg="alpha", value="(2,)", allowed="shape (2, 2)")
    assert_refuses(_row, 2, Omega=(0.5, 2.0), alpha=[[0, 0], [0, 0]], beta=[0.1, 0.2],
                   arg="beta", value="(2,)", allowed="shape (2, 2)")
    assert_refuses(_row, alpha=np.zeros((1, 2)), arg="alpha", value="(1, 2)",
                   allowed="shape (1, 1)")
    assert_refuses(_row, 2, x0=np.array([1., 2, 2.5]), arg="x0", value="(3,)",
                   allowed="shape (2,)")
    assert_refuses(_row, 2, v0=[0.0], arg="v0", value="(1,)", allowed="shape (2,)")
    assert_refuses(_row, 2, alpha=np.array([[0.0], [np.inf]]), arg="alpha",
                   value="inf) at index (1, 0)", allowed="finite")
    assert_refuses(_row, beta=[[math.nan]], arg="beta[0][0]", value="nan", allowed="finite")
    assert_refuses(_row, alpha=True, exc=TypeError, arg="alpha", value="True",
                   allowed="an array of real numbers")
    assert_refuses(_row, x0="1", exc=TypeError, arg="x0", value="'1'",
                   allowed="an array of real numbers")

    class NoArray:
        def __array__(self, *args, **kw):
            raise TypeError("refused")

    assert_refuses(_row, 2, v0=NoArray(), exc=TypeError, arg="v0", value="refused",
                   allowed="an array of real numbers")


def test_walls_and_overlaps():
    assert _row(x0=[0.5]).x0[0] == 0.5 and _row(x0=[1.9]).x0[0] == 1.9
    assert _row(d=2.0, x0=[3.5]).x0[0] == 3.5           # right wall at (n + 1) d = 4

    def overlap(wall, site, *args, **kw):
        assert_refuses(_row, *args, arg="x0", value=f"pipes overlap at site {site}",
                       allowed=f"strictly increasing inside (0, (n + 1) d) = (0, {wall})", **kw)

    overlap(2.0, 1, x0=[2.0])
    overlap(2.0, 1, x0=[2.5])
    overlap(2.0, 0, x0=[0.0])
    overlap(4.0, 1, d=2.0, x0=[4.5])
    overlap(3.0, 1, 2, x0=[1.0, 1.0])
    overlap(4.0, 2, 3, x0=[1.0, 2.0, 1.5])


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
    assert_refuses(_row, d=0, arg="d", value="0", allowed="> 0")
    assert_refuses(_row, Omega=(2.0, "1e400"), alpha=[[0, 0]], beta=[[0, 0]], arg="Omega[1]",
                   value="'1e400'", allowed="float64 range")
