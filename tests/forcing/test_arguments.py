"""Arguments of the forcing functions (``symhx.forcing.arguments``): exact conversion, every bad
input as a clear error naming the argument (and the first bad index), the value object's
broadcasting. References are exact rational arithmetic and hand-written expectations."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx._mpctx import mp as thread_mp
from symhx.forcing.arguments import (
    ForcingParams,
    bad_index,
    elementwise,
    float_arg,
    is_array,
    is_components,
    mp_arg,
    mpf_of,
    rational_arg,
)
from tests.harness.errors import assert_refuses


def test_kinds():
    for v in ([1], (1,), np.array(1.0), np.zeros((2, 2))):
        assert is_array(v)
    for v in (1, 1.0, "0.5", Fraction(1, 2), None, mpmath.mpf(1)):
        assert not is_array(v)
    assert is_components([1.5]) and is_components((1.5, 2.0))
    assert not is_components(np.array([1.5])) and not is_components(1.5)


def test_bad_index():
    assert bad_index(np.array(1.0), np.array(True)) == ""
    assert bad_index(np.array([1.0, 2.0, 3.0]), np.array([False, False, True])) == " at index 2"
    a = np.zeros((2, 3))
    bad = np.zeros((2, 3), dtype=bool)
    bad[1, 2] = True
    bad[1, 1] = True
    assert bad_index(a, bad) == " at index (1, 1)"


def test_rational_arg():
    f = Fraction(3, 7)
    assert rational_arg("s", f) is f
    assert rational_arg("s", "0.05") == Fraction(1, 20)
    assert rational_arg("s", 3) == Fraction(3)
    assert rational_arg("s", 0.1) == Fraction(0.1)
    sympy = pytest.importorskip("sympy")
    got = rational_arg("s", sympy.sqrt(2))
    assert abs(got - Fraction(14142135623730950488016887242096980785696718753769, 10**49)) \
        < Fraction(1, 10**39)
    assert rational_arg("s", sympy.Rational(2, 3)) == Fraction(2, 3)
    for bad in (0, -1, "-0.5", Fraction(0), Fraction(-1, 2), -1e-300, 0.0):
        assert_refuses(rational_arg, "s", bad, arg="s", allowed="> 0")
    with pytest.raises((TypeError, ValueError), match="s"):
        rational_arg("s", True)


def test_float_arg_arrays():
    a = np.array([0.5, 2.0])
    out = float_arg("x", a)
    assert out.dtype == np.float64 and (out == a).all()
    out = float_arg("x", np.array([0.5, 2.0], dtype=np.float32))
    assert out.dtype == np.float64
    assert_refuses(float_arg, "x", np.array([1.0, np.inf, np.nan]), arg="x",
                   value="inf at index 1", allowed="finite")
    assert_refuses(float_arg, "x", np.array([[1.0, -2.0], [0.0, 1.0]]), arg="x",
                   value="-2.0 at index (0, 1)", allowed="> 0")
    assert (float_arg("x", np.array([-1.0, 0.0]), positive=False) == [-1.0, 0.0]).all()
    assert (float_arg("x", [1, 0.5]) == [1.0, 0.5]).all()
    with pytest.raises(ValueError, match="x"):
        float_arg("x", [1.0, -1.0])
    assert float_arg("x", [], positive=True).shape == (0,)
    assert float_arg("x", np.array([]), positive=True).shape == (0,)


def test_float_arg_scalars():
    out = float_arg("x", "0.1")
    assert out.shape == () and float(out) == 0.1
    assert float(float_arg("x", Fraction(1, 3))) == 1 / 3
    assert float(float_arg("x", -2, positive=False)) == -2.0
    assert float(float_arg("x", 0, positive=False)) == 0.0
    assert_refuses(float_arg, "x", 0, arg="x", allowed="> 0")
    with pytest.raises(ValueError, match=r"x = '1e400' is outside the float64 range; use dps="):
        float_arg("x", "1e400")
    with pytest.raises(ValueError, match=r"x = '1e-400' underflows float64; use dps="):
        float_arg("x", "1e-400")
    with pytest.raises(ValueError, match="underflows"):
        float_arg("x", "-1e-400", positive=False)
    sympy = pytest.importorskip("sympy")
    assert float(float_arg("x", sympy.sqrt(2))) == 2**0.5
    assert float(float_arg("x", sympy.sqrt(2), positive=False)) == 2**0.5


def test_mpf_of_and_mp_arg():
    tctx = thread_mp()   # mpf_of and mp_arg compute in the calling thread's context
    with mpmath.workdps(30), tctx.workdps(30):
        v = mpf_of(Fraction(3, 1 << 200))
        assert v == mpmath.ldexp(3, -200)
        assert mpf_of(Fraction(5)) == 5
        third = mpf_of(Fraction(1, 3))
        assert abs(third * 3 - 1) < mpmath.mpf(10) ** -29 and third != mpmath.mpf(1) / 3 + \
            mpmath.eps
        big = Fraction((1 << 300) + 1, 1 << 10)  # dyadic, more bits than 30 digits: rounded
        assert mpf_of(big) == mpmath.ldexp(mpmath.mpf((1 << 300) + 1), -10)
    with mpmath.workdps(60), tctx.workdps(60):
        assert abs(mpf_of(Fraction(1, 3)) - mpmath.mpf(1) / 3) < mpmath.mpf(10) ** -59
    with mpmath.workdps(20), tctx.workdps(20):
        x = mpmath.mpf("0.1")
    with mpmath.workdps(50), tctx.workdps(50):
        y = mp_arg("s", x)
        assert y == x and y.context is tctx   # this thread's context
        assert mp_arg("s", "0.1") == mpmath.mpf(1) / 10
        assert mp_arg("s", 0.25) == mpmath.mpf(0.25)
        other = mpmath.MPContext()
        other.dps = 40
        x3 = other.mpf("0.3")  # another context's mpf (a thread's, issue 28): its exact value
        assert mp_arg("s", x3) == mpmath.mp.make_mpf(x3._mpf_)
        with mpmath.workdps(80), tctx.workdps(80):
            w = mpmath.mpf(1) / 3
        assert mp_arg("s", w) == mpmath.mpf(1) / 3  # rounded to the current precision
        for bad in (mpmath.mpf(0), mpmath.mpf(-1), mpmath.inf, mpmath.nan):
            with pytest.raises((ValueError, TypeError), match="s"):
                mp_arg("s", bad)


def test_validated_exact_and_float():
    fp = ForcingParams.validated("0.05", dps=30)
    assert (fp.sigma, fp.sigma1, fp.omega, fp.Omega, fp.d, fp.exact) == (
        Fraction(1, 20), None, Fraction(1), None, Fraction(1), True)
    assert not fp.components and fp.broadcast_fields() == []
    fp = ForcingParams.validated(0.5, 0.25, 2, 3, "0.5")
    assert not fp.exact
    for k, v in (("sigma", 0.5), ("sigma1", 0.25), ("omega", 2.0), ("Omega", 3.0), ("d", 0.5)):
        a = getattr(fp, k)
        assert isinstance(a, np.ndarray) and a.shape == () and float(a) == v
    # a one-component list is one component (with a one-element sigma1 list)
    fp = ForcingParams.validated(0.5, [0.25], 1, [3], dps=10)
    assert fp.Omega == 3 and fp.sigma1 == Fraction(1, 4) and not fp.components
    fp = ForcingParams.validated(0.5, 0.25, 1, [3], dps=10)
    assert fp.Omega == 3 and fp.sigma1 == Fraction(1, 4)
    assert_refuses(ForcingParams.validated, 0.5, [0.25, 0.5], 1, [3], arg=["sigma1", "Omega"],
                   value="2 values", allowed="1 forcing component")
    # several components
    fp = ForcingParams.validated("0.5", ["0.25", 2], 1, (3, "1.5"), dps=10)
    assert fp.components and fp.Omega == (3, Fraction(3, 2)) and fp.sigma1 == (Fraction(1, 4), 2)
    fp = ForcingParams.validated(0.5, None, 1, [3, 1.5])
    assert fp.components and fp.sigma1 is None and len(fp.Omega) == 2
    fp = ForcingParams.validated(0.5, 0.1, 1, [3, 1.5])
    assert float(fp.sigma1) == 0.1
    assert_refuses(ForcingParams.validated, 0.5, [1, 2, 3], 1, [3, 1.5], arg=["sigma1", "Omega"],
                   value="3 values", allowed="2 forcing components")
    assert_refuses(ForcingParams.validated, 0.5, None, 1, [], arg="Omega", value="empty list",
                   allowed="forcing components")
    assert_refuses(ForcingParams.validated, 0.5, None, 1, [3, [1.5]], exc=TypeError, arg="Omega",
                   allowed="each forcing component must be a scalar")
    with pytest.raises(ValueError, match=r"Omega: an empty array of forcing frequencies"):
        ForcingParams.validated(0.5, None, 1, np.array([]))
    for i, name in enumerate(("sigma", "omega", "d")):
        args = [0.5, None, 1, None, 1]
        args[(0, 2, 4)[i]] = None
        assert_refuses(ForcingParams.validated, *args, exc=TypeError, arg=name, value="None",
                       allowed="a real number")
    with pytest.raises(ValueError, match=r"Omega\[1\] must be > 0"):
        ForcingParams.validated(0.5, None, 1, [3, -1], dps=10)
    with pytest.raises(ValueError, match=r"sigma1\[0\] must be > 0"):
        ForcingParams.validated(0.5, [-1, 1], 1, [3, 2])


def test_validated_arrays_and_scalars_iteration():
    fp = ForcingParams.validated(["0.5", 2], None, 1, None, [[1], [3]], dps=20)
    assert fp.sigma.dtype == object and fp.sigma[0] == Fraction(1, 2)
    assert fp.broadcast_fields() == ["sigma", "d"]
    shape, items = fp.scalars()
    assert shape == (2, 2)
    got = {idx: (one.sigma, one.d) for idx, one in items}
    assert got == {(0, 0): (Fraction(1, 2), 1), (0, 1): (2, 1), (1, 0): (Fraction(1, 2), 3),
                   (1, 1): (2, 3)}
    assert_refuses(ForcingParams.validated, ["0.5", "-1"], dps=20, arg="sigma",
                   value="'-1' at index 1", allowed="> 0")
    with pytest.raises(ValueError, match=r"at index \(1, 0\)"):
        ForcingParams.validated([["0.5"], ["-1"]], dps=20)
    fpf = ForcingParams.validated(np.array([0.5, 2.0]), None, np.array([1.0]), 3.0)
    assert fpf.broadcast_fields() == ["sigma", "omega"]
    shape, items = fpf.scalars()
    items = list(items)
    assert shape == (2,) and [i for i, _ in items] == [(0,), (1,)]
    for (_, one), s in zip(items, (0.5, 2.0), strict=True):
        assert isinstance(one.sigma, np.ndarray) and one.sigma.shape == () and one.sigma == s
        assert isinstance(one.omega, np.ndarray) and one.omega == 1.0 and one.Omega == 3.0
        assert not one.exact
    shape, items = ForcingParams.validated(0.5).scalars()
    assert shape is None and [i for i, _ in items] == [()]


def test_elementwise():
    fp = ForcingParams.validated(0.5, dps=10)
    assert elementwise(fp, lambda f: f.sigma * 2) == 1
    fp = ForcingParams.validated([0.5, 1, 2], dps=10)
    out = elementwise(fp, lambda f: f.sigma * 2)
    assert out.dtype == object and list(out) == [1, 2, 4]
    out = elementwise(fp, lambda f: float(f.sigma), dtype=float)
    assert out.dtype == float and list(out) == [0.5, 1.0, 2.0]

    def fail_at_two(f):
        if f.sigma == 2:
            raise ValueError("boom")
        return 0

    # the element's own message, then where it happened
    msg = assert_refuses(elementwise, fp, fail_at_two, exc=ValueError, arg="boom",
                         value="at index 2")
    assert msg.startswith("boom")
    fp2 = ForcingParams.validated([[0.5, 2]], dps=10)
    msg = assert_refuses(elementwise, fp2, fail_at_two, exc=ValueError, arg="boom",
                         value="at index (0, 1)")
    assert msg.startswith("boom")


@pytest.mark.parametrize("dps", [None, 10])
def test_every_argument_is_named_in_its_error(dps):
    base = dict(sigma=0.5, sigma1=0.25, omega=1.0, Omega=3.0, d=1.0)
    for comps in (False, True):
        for name in base:
            kw = dict(base)
            if comps:
                kw["Omega"] = [3.0, 2.0]
                kw["sigma1"] = 0.25
            kw[name] = -1.0 if not (comps and name == "Omega") else [3.0, -1.0]
            label = "Omega[1]" if comps and name == "Omega" else name
            assert_refuses(ForcingParams.validated, kw["sigma"], kw["sigma1"], kw["omega"],
                           kw["Omega"], kw["d"], dps=dps, arg=label, value="-1.0",
                           allowed="> 0")


def test_components_keep_every_field():
    fp = ForcingParams.validated("0.5", "0.25", "1.5", ["3", "2"], "0.75", dps=10)
    assert (fp.sigma, fp.sigma1, fp.omega, fp.Omega, fp.d, fp.exact) == (
        Fraction(1, 2), Fraction(1, 4), Fraction(3, 2), (3, 2), Fraction(3, 4), True)
    fp = ForcingParams.validated(0.5, 0.25, 1.5, [3.0, 2.0], 0.75)
    assert [float(v) for v in (fp.sigma, fp.sigma1, fp.omega, fp.d)] == [0.5, 0.25, 1.5, 0.75]
    assert [float(v) for v in fp.Omega] == [3.0, 2.0] and fp.exact is False


def test_zero_dimensional_object_input_has_no_index():
    msg = assert_refuses(ForcingParams.validated, np.array(-1.0), dps=10, arg="sigma",
                         value="-1.0", allowed="> 0")
    assert "index" not in msg
    fp = ForcingParams.validated(np.array(0.5), dps=10)
    assert fp.sigma.shape == () and fp.sigma[()] == Fraction(1, 2)


def test_float_arg_zero_and_names():
    assert_refuses(float_arg, "x", np.array([1.0, 0.0]), arg="x", value="0.0 at index 1",
                   allowed="> 0")
    with pytest.raises(ValueError, match=r"\bx\b"):
        float_arg("x", [1.0, -1.0])
    with pytest.raises(TypeError, match=r"\bx\b"):
        float_arg("x", True, positive=False)
    assert (float_arg("x", np.array([1.0, 0.0]), positive=False) == [1.0, 0.0]).all()


def test_sympy_irrationals_take_40_digits():
    sympy = pytest.importorskip("sympy")
    got = rational_arg("s", sympy.sqrt(2))
    assert got == Fraction("1.414213562373095048801688724209698078570")  # 40 digits
    assert float(float_arg("x", sympy.pi)) == 3.141592653589793


@pytest.mark.parametrize("dps", [15, 60, 200])
def test_sympy_irrationals_are_taken_to_dps_plus_the_extra_digits(dps):
    """Scalars and arrays of sympy irrationals become Fractions within 10**-(dps + 320) of the
    irrational (reference: sympy's own evaluation at more digits)."""
    import sympy

    from symhx.forcing.arguments import IRRATIONAL_EXTRA_DIGITS, ForcingParams

    assert IRRATIONAL_EXTRA_DIGITS >= 320
    s, om = sympy.sqrt(2) / 10, sympy.pi / 3
    fp = ForcingParams.validated(s, None, om, None, np.array([sympy.sqrt(3), sympy.E],
                                                            dtype=object), dps=dps)
    assert isinstance(fp.sigma, Fraction) and isinstance(fp.omega, Fraction)
    assert fp.d.dtype == object and all(isinstance(v, Fraction) for v in fp.d)
    tol = sympy.Rational(1, 10 ** (dps + 320))
    for got, exact in ((fp.sigma, s), (fp.omega, om), (fp.d[0], sympy.sqrt(3)),
                       (fp.d[1], sympy.E)):
        err = abs(sympy.Rational(got.numerator, got.denominator) - exact)
        assert sympy.N(err - tol * exact, dps + 400) < 0, (exact, dps)


def test_empty_Omega_array_message():
    assert_refuses(ForcingParams.validated, 0.3, Omega=np.array([]), arg="Omega",
                   value="an empty array",
                   allowed=["a scalar", "a list of components", "None for the paper's sqrt(2)"])
