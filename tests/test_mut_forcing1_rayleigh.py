"""RayleighSum (``symhx.forcing.rayleigh``) against an independent quadrature of the convolution.

Reference (no package code): one and two Rayleigh scales have the closed form of eq. (27)
(written out here); three scales integrate the density of the *largest* scale against the pair
tail of the other two; four scales integrate the density of the pair (first, third largest)
(the derivative of the closed form, by ``mpmath.diff``) against the tail of the pair (second,
fourth) -- the package pairs adjacent scales instead. Composite Gauss-Legendre on uniform panels
plus panels at multiples of every scale from both ends, two rule orders that must agree (the
reference certifies itself). Five scales (two nested levels in the package) are checked in
float64 against scipy's adaptive ``quad`` of the density of the largest scale against the
four-scale reference tail. Values are cached in a file keyed by a hash of the reference code.
"""

from __future__ import annotations

import hashlib
import inspect
import json
import math
import os
import tempfile
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx.forcing import RayleighSum
from symhx.forcing.rayleigh import rayleigh_scales, rayleigh_sum_probability, scales_of
from tests.test_forcing_rayleigh import gl_sum, pair_tail

EPS = float(np.finfo(float).eps)
REF_DPS = 24


# ------------------------------------------------------------------------------ the reference
def _pair_pdf(s, a, b):
    if s <= 0:
        return mpmath.mpf(0)
    with mpmath.workdps(mpmath.mp.dps + 20):
        return -mpmath.diff(lambda z: pair_tail(z, a, b, True), s)


def _one_tail(s, c, upper):
    if s <= 0:
        return mpmath.mpf(1) if upper else mpmath.mpf(0)
    e = s * s / (2 * c * c)
    return mpmath.exp(-e) if upper else -mpmath.expm1(-e)


def _one_pdf(s, c):
    return s / c**2 * mpmath.exp(-s * s / (2 * c * c)) if s > 0 else mpmath.mpf(0)


def _ref_value(scales, x, kind):
    """P(S > x) ('sf'), P(S <= x) ('cdf') or the density ('pdf') at REF_DPS digits."""
    with mpmath.workdps(REF_DPS + 6):
        s = sorted((mpmath.mpf(v) for v in scales), reverse=True)
        x = mpmath.mpf(x)
        up = kind == "sf"
        if len(s) == 1:
            return _one_pdf(x, s[0]) if kind == "pdf" else _one_tail(x, s[0], up)
        if len(s) == 2:
            return _pair_pdf(x, *s) if kind == "pdf" else pair_tail(x, *s, up)
        if len(s) == 3:
            fa, fa_tail = (lambda t: _one_pdf(t, s[0])), _one_tail(x, s[0], True)
            rest = s[1:]
        else:
            fa = lambda t: _pair_pdf(t, s[0], s[2])  # noqa: E731
            fa_tail = pair_tail(x, s[0], s[2], True)
            rest = [s[1], s[3]]
        if kind == "pdf":
            def g(t):
                return fa(t) * _pair_pdf(x - t, *rest)
        else:
            def g(t):
                return fa(t) * pair_tail(x - t, *rest, up)
        pts = {x * k / 24 for k in range(25)}
        va, vr = sum(v * v for v in s) - rest[0] ** 2 - rest[1] ** 2, rest[0] ** 2 + rest[1] ** 2
        ts, w = x * va / (va + vr), mpmath.sqrt(va * vr / (va + vr))  # the Gaussian saddle
        pts |= {ts + k * w / 2 for k in range(-16, 17) if 0 < ts + k * w / 2 < x}
        # geometric grading from both ends down to below the smallest scale
        lo_exp = int(mpmath.floor(2 * mpmath.log10(s[-1]))) - 2
        for j in range(lo_exp, int(mpmath.ceil(2 * mpmath.log10(x))) + 1):
            gr = mpmath.mpf(10) ** (mpmath.mpf(j) / 2)
            pts |= {q for q in (gr, x - gr) if 0 < q < x}
        for sc in s:
            for k in (0.25, 0.5, 1, 2, 3, 4, 6, 8, 12, 16, 24, 32):
                for q in (k * sc, x - k * sc):
                    if 0 < q < x:
                        pts.add(q)
        pts = sorted(pts)
        lo, hi = gl_sum(g, pts, 10), gl_sum(g, pts, 20)
        assert abs(hi - lo) <= mpmath.mpf(10) ** -(REF_DPS - 2) * abs(hi), (scales, x, kind)
        if up:
            hi += fa_tail
        return hi


_CACHE: dict | None = None
_CACHE_FILE = ""


def ref(scales, x, kind):
    global _CACHE, _CACHE_FILE
    if _CACHE is None:
        src = "".join(inspect.getsource(f) for f in (pair_tail, _pair_pdf, _one_tail, _one_pdf,
                                                      gl_sum, _ref_value))
        h = hashlib.sha256(src.encode()).hexdigest()[:16]
        _CACHE_FILE = os.path.join(tempfile.gettempdir(), f"symhx-mut-forcing1-ray-{h}.json")
        try:
            with open(_CACHE_FILE) as fh:
                _CACHE = json.load(fh)
        except (OSError, ValueError):
            _CACHE = {}
    key = repr((tuple(scales), x, kind))
    if key not in _CACHE:
        with mpmath.workdps(REF_DPS + 6):
            _CACHE[key] = mpmath.nstr(_ref_value(scales, x, kind), REF_DPS + 6)
        tmp = f"{_CACHE_FILE}.{os.getpid()}"
        with open(tmp, "w") as fh:
            json.dump(_CACHE, fh)
        os.replace(tmp, _CACHE_FILE)
    with mpmath.workdps(REF_DPS + 6):
        return mpmath.mpf(_CACHE[key])


def rel(a, b):
    with mpmath.workdps(60):
        return abs(mpmath.mpf(a) / mpmath.mpf(b) - 1)


# ------------------------------------------------------------------------------ cases
#: scales (spread over 1e-8 .. 1e8) and thresholds reaching both tails and the body
CASES = [
    ([0.5, 0.3, 0.2], [0.05, 0.4, 1.0, 2.5, 5.0]),
    ([1e8, 0.4, 1e-8], [0.3, 1.0]),
    ([3.0, 1e-4, 2.0], [0.01, 1.0, 30.0]),
    ([0.6, 0.45, 0.3, 0.1], [0.02, 1.5, 6.0]),
    ([1e4, 7e3, 1.0, 0.5], [3.0, 1e4, 8e4]),
    ([0.7, 0.2], [0.1, 1.0, 9.0]),
    ([0.7], [0.1, 1.0, 9.0]),
]


def _points():
    return [(tuple(sc), x) for sc, xs in CASES for x in xs]


@pytest.mark.parametrize(("scales", "x"), _points())
def test_float64_three_kinds_and_error_estimate(scales, x):
    """sf, cdf, pdf within ~1e-13 relative (and ~eps times the digits of the exponent), the
    error estimate above the true error and itself small; logs of both tails."""
    S = RayleighSum(list(scales))
    vals = {k: getattr(S, k)(x) for k in ("sf", "cdf", "pdf")}
    refs = {k: ref(scales, x, k) for k in ("sf", "cdf", "pdf")}
    n = len(scales)
    for k in ("sf", "cdf", "pdf"):
        r = refs[k]
        if r < 1e-300:
            assert vals[k] < 1e-290, (k, vals[k], r)
            continue
        bound = 1e-13 + 8 * EPS * (n + 2 * abs(math.log(float(r))))
        assert rel(vals[k], r) < bound, (k, scales, x, vals[k], r)
    for tail, kind in (("upper", "sf"), ("lower", "cdf")):
        res = S.probability(x, tail=tail)
        assert res.value == vals[kind]
        assert res.method == ("closed form" if n <= 2 else "nested Gauss-Legendre (1-D)")
        r = refs[kind]
        if r > 1e-300:
            true = float(abs(mpmath.mpf(res.value) - r))
            assert res.error >= true, (tail, res.error, true)
            assert res.error <= 1e-12 * float(r) * (1 + abs(math.log(float(r)))), (tail, res)
    # logs: log1p of the other tail where the tail is above 1/2
    for fn, main, other in ((S.logsf, "sf", "cdf"), (S.logcdf, "cdf", "sf")):
        r, ro = refs[main], refs[other]
        if not r > 1e-300:
            continue
        with mpmath.workdps(40):
            lr = mpmath.log(r) if r <= 0.5 else mpmath.log1p(-ro)
        v = fn(x)
        assert abs(v - float(lr)) <= 1e-13 * abs(float(lr)) + 8 * EPS * (n + abs(float(lr))), (
            fn.__name__, scales, x, v, lr)


@pytest.mark.parametrize(("scales", "x"), [((0.5, 0.3, 0.2), 0.4), ((0.5, 0.3, 0.2), 2.5),
                                           ((1e8, 0.4, 1e-8), 1.0),
                                           ((0.6, 0.45, 0.3, 0.1), 1.5),
                                           ((0.6, 0.45, 0.3, 0.1), 6.0),
                                           ((0.7, 0.2), 9.0), ((0.7,), 1.0)])
def test_mpmath_meets_dps(scales, x):
    """dps = 20 against the 24-digit reference: all five functions and the error estimate."""
    S = RayleighSum(list(scales))
    refs = {k: ref(scales, x, k) for k in ("sf", "cdf", "pdf")}
    for k in ("sf", "cdf", "pdf"):
        v = getattr(S, k)(x, dps=20)
        assert rel(v, refs[k]) < 1e-20, (k, scales, x)
    with mpmath.workdps(40):
        lsf = mpmath.log(refs["sf"]) if refs["sf"] <= 0.5 else mpmath.log1p(-refs["cdf"])
        lcdf = mpmath.log(refs["cdf"]) if refs["cdf"] <= 0.5 else mpmath.log1p(-refs["sf"])
    assert rel(S.logsf(x, dps=20), lsf) < 1e-20
    assert rel(S.logcdf(x, dps=20), lcdf) < 1e-20
    for tail, kind in (("upper", "sf"), ("lower", "cdf")):
        res = S.probability(x, tail=tail, dps=20)
        with mpmath.workdps(40):
            true = abs(res.value - refs[kind])
            assert res.error + mpmath.mpf(10) ** -(REF_DPS - 1) * refs[kind] >= true
            assert res.error <= mpmath.mpf(10) ** -20 * abs(refs[kind])


def _f_pair_tail(s, a, b):
    """float64 closed form of P(Ra + Rb > s) (moderate arguments only)."""
    if s <= 0:
        return 1.0
    x, y = s * s / (2 * a * a), s * s / (2 * b * b)
    r = math.sqrt(x + y)
    u, v = x / r, y / r
    return math.exp(-u * v) * (v * math.exp(-u * u) + u * math.exp(-v * v) + math.sqrt(
        math.pi) * u * v * (math.erf(u) + math.erf(v))) / r


def _f_one_pdf(t, c):
    return t / (c * c) * math.exp(-t * t / (2 * c * c)) if t > 0 else 0.0


def test_five_scales_two_nested_levels():
    """Five scales (the package's groups: pair, single, pair -- the single moved second to last)
    against scipy's adaptive quad grouped differently: the pair A = (0.8, 0.35) with density
    f_A(t) = int f_0.8(w) f_0.35(t - w) dw, convolved with the three-scale tail
    T(s) = P(R_0.5 + B > s), B the pair (0.2, 0.1) with its closed-form tail:
    P(S > x) = P(A > x) + int_0^x f_A(t) T(x - t) dt (float64, moderate tails)."""
    from scipy import integrate

    S = RayleighSum([0.8, 0.5, 0.35, 0.2, 0.1])
    kw = dict(epsabs=0, epsrel=1e-12, limit=100)

    def f_a(t):
        return integrate.quad(lambda w: _f_one_pdf(w, 0.8) * _f_one_pdf(t - w, 0.35), 0, t,
                              **kw)[0]

    def t3(s):
        if s <= 0:
            return 1.0
        return math.exp(-s * s / (2 * 0.25)) + integrate.quad(
            lambda w: _f_one_pdf(w, 0.5) * _f_pair_tail(s - w, 0.2, 0.1), 0, s, **kw)[0]

    for x in (0.9, 2.4):
        up = _f_pair_tail(x, 0.8, 0.35) + integrate.quad(lambda t, x=x: f_a(t) * t3(x - t), 0, x,
                                                         **kw)[0]
        assert abs(S.sf(x) / up - 1) < 1e-10, (x, S.sf(x), up)
        assert abs(S.cdf(x) - (1 - up)) < 1e-10 * up, (x, S.cdf(x), 1 - up)
        assert abs(S.sf(x) + S.cdf(x) - 1) < 8 * EPS
        assert S.probability(x).method == "nested Gauss-Legendre (2-D)"


def test_edges_far_tail_and_arrays():
    S = RayleighSum([0.5, 0.3, 0.2])
    xs = np.array([-1.0, 0.0, 1.0, 1e4, 3e4])
    sf, cdf, pdf = S.sf(xs), S.cdf(xs), S.pdf(xs)
    assert list(sf[:2]) == [1.0, 1.0] and list(cdf[:2]) == [0.0, 0.0] and pdf[0] == 0 == pdf[1]
    assert sf[3] == 0.0 and cdf[3] == 1.0 and pdf[3] == 0.0 and sf[4] == 0.0 and cdf[4] == 1.0
    assert rel(sf[2], ref((0.5, 0.3, 0.2), 1.0, "sf")) < 1e-13
    assert S.sf(np.array([[1.0, 2.5]])).shape == (1, 2)
    assert S.sf(np.array([])).shape == (0,)
    assert isinstance(S.sf(1.0), float) and isinstance(S.logsf([1.0]), np.ndarray)
    assert S.logsf(-1.0) == 0.0 and S.logcdf(0.0) == -math.inf
    # sf underflows at 1e4 but log sf is finite (the mpmath path, 30 digits, is the reference)
    with mpmath.workdps(30):
        assert abs(S.logsf(1e4) / S.logsf(1e4, dps=30) - 1) < 1e-14 and S.logcdf(1e4) == 0.0
    for k in ("sf", "cdf", "pdf"):
        res = S.probability(1e4, tail="upper" if k == "sf" else "lower")
        assert res.error == 0.0
    # x <= 0 in mpmath; arrays in mpmath; exact decimal thresholds
    assert S.sf(-2, dps=20) == 1 and S.cdf(0, dps=20) == 0 and S.pdf("-0.5", dps=20) == 0
    two = RayleighSum([0.7, 0.2])
    assert two.sf(0, dps=15) == 1 and two.cdf(-1, dps=15) == 0 and two.pdf(0, dps=15) == 0
    one = RayleighSum([0.7])
    assert one.pdf(-1.0) == 0.0 and one.sf(-1, dps=15) == 1 and one.pdf(0, dps=15) == 0
    out = S.sf([[0.4, 1]], dps=20)
    assert out.shape == (1, 2) and out.dtype == object
    assert rel(out[0, 0], ref((0.5, 0.3, 0.2), 0.4, "sf")) < 1e-20
    # far upper tail in mpmath: E = x^2/(2 sum s^2) ~ 1e6 needs its extra digits
    p = S.sf(300, dps=20)
    with mpmath.workdps(40):
        c = mpmath.mpf(0.5)
        assert 0 < p < mpmath.exp(-300**2 / (2 * 3 * c * c)) * 1e10
    sympy = pytest.importorskip("sympy")
    v = S.sf(sympy.sqrt(2) / 2, dps=20)
    with mpmath.workdps(40):
        h = mpmath.sqrt(2) / 2
    w = S.sf(h, dps=20)
    assert rel(v, w) < 1e-19


def test_moments_and_rvs():
    sc = ["0.5", "0.3", "0.2"]
    S = RayleighSum(sc)
    assert S.mean() == math.sqrt(math.pi / 2) * 1.0
    assert abs(S.var() - (2 - math.pi / 2) * 0.38) < 4 * EPS
    assert abs(S.std() - math.sqrt((2 - math.pi / 2) * 0.38)) < 4 * EPS
    with mpmath.workdps(60):
        m = mpmath.sqrt(mpmath.pi / 2) * 1
        v = (2 - mpmath.pi / 2) * (mpmath.mpf(38) / 100)
        assert abs(S.mean(dps=40) - m) < mpmath.mpf(10) ** -40
        assert abs(S.var(dps=40) - v) < mpmath.mpf(10) ** -40
        assert abs(S.std(dps=40) - mpmath.sqrt(v)) < mpmath.mpf(10) ** -40
        # the mean is the integral of the survival function (independent of the formula)
        mi = mpmath.quad(lambda t: pair_tail(t, mpmath.mpf(0.7), mpmath.mpf(0.2), True),
                         [0, 0.5, 1, 2, 4, 8])
        assert abs(RayleighSum([0.7, 0.2]).mean(dps=30) - mi) < mpmath.mpf(10) ** -25
    r = S.rvs(size=4000, random_state=3)
    assert r.shape == (4000,) and np.array_equal(r, S.rvs(size=4000, random_state=3))
    assert not np.array_equal(r, S.rvs(size=4000, random_state=4))
    assert np.array_equal(r, S.rvs(size=4000, random_state=np.random.default_rng(3)))
    assert isinstance(S.rvs(random_state=1), float)
    from scipy import stats

    assert stats.kstest(r, S.cdf).pvalue > 1e-3
    # each summand is Rayleigh(s): the sample mean of a one-scale sum
    r1 = RayleighSum([2.0]).rvs(size=20000, random_state=5)
    assert abs(r1.mean() - 2.0 * math.sqrt(math.pi / 2)) < 5 * 2.0 * 0.66 / math.sqrt(20000)


def test_rayleigh_scales_and_groups():
    # s_0 = sqrt(2) sigma, s_i = sqrt(2) sigma_i/|omega^2 - Omega_i^2| (exact rationals here)
    got = rayleigh_scales("0.5", sigma1=["0.25", "0.1"], omega="1.5", Omega=["0.5", 3])
    want = [0.5, 0.25 / 2.0, 0.1 / 6.75]
    assert all(abs(g / (math.sqrt(2) * w) - 1) < 2 * EPS for g, w in zip(got, want, strict=True))
    got = rayleigh_scales("0.5", sigma1=["0.25", "0.1"], omega="1.5", Omega=["0.5", 3], dps=30)
    with mpmath.workdps(40):
        for g, w in zip(got, ("0.5", "0.125", "0.1/6.75"), strict=True):
            wv = mpmath.sqrt(2) * (mpmath.mpf(0.1) / mpmath.mpf(6.75) if "/" in w else
                                   mpmath.mpf(w))
            if "/" in w:
                wv = mpmath.sqrt(2) * mpmath.mpf(1) / 10 / (mpmath.mpf(27) / 4)
            assert abs(g / wv - 1) < mpmath.mpf(10) ** -29
    assert [round(s, 12) for s in rayleigh_scales(0.5)] == [0.707106781187] * 2
    two = rayleigh_scales(0.5, omega=2, dps=25)  # Omega^2 = 2 exactly: |4 - 2| = 2
    with mpmath.workdps(30):
        assert abs(two[1] - mpmath.sqrt(2) / 4) < mpmath.mpf(10) ** -25
    assert rayleigh_scales(0.5, sigma1=0.1, Omega=[3, 2])[1:] == pytest.approx(
        [math.sqrt(2) * 0.1 / 8, math.sqrt(2) * 0.1 / 3], rel=4 * EPS)
    for kw, msg in ((dict(Omega=[3, 1]), r"^Omega\[1\]: resonance"),
                    (dict(Omega=1), r"^Omega: resonance")):
        with pytest.raises(ValueError, match=msg):
            rayleigh_scales(0.5, **kw)
        with pytest.raises(ValueError, match=msg):
            rayleigh_scales(0.5, **kw, dps=20)
    with pytest.raises(TypeError, match="sigma must be a scalar"):
        rayleigh_scales([0.5])
    with pytest.raises(TypeError, match="omega must be a scalar"):
        rayleigh_scales(0.5, omega=[1.0])
    with pytest.raises(TypeError, match="sigma1: a list needs a list"):
        rayleigh_scales(0.5, sigma1=[0.1])
    fp = F.ForcingParams.validated("0.5", None, 1, [3, 2], dps=20)
    sc = scales_of(fp, 30)
    with mpmath.workdps(40):
        assert abs(sc[2] - mpmath.sqrt(2) * mpmath.mpf(1) / 2 / 3) < mpmath.mpf(10) ** -29


def test_several_components_match_rayleigh_sum():
    """The forcing with two components is the three-scale sum at d (both tails, float and
    mpmath)."""
    sc = rayleigh_scales(0.3, Omega=[2.0, 0.5])
    for x in (0.7,):
        p = F.impact_probability(0.3, Omega=[2.0, 0.5], d=x)
        assert rel(p, ref(tuple(sc), x, "sf")) < 1e-13
        q = F.no_impact_probability(0.3, Omega=[2.0, 0.5], d=x)
        assert rel(q, ref(tuple(sc), x, "cdf")) < 1e-13


def test_bad_input():
    with pytest.raises(TypeError, match="scales must be a sequence"):
        RayleighSum("0.5")
    with pytest.raises(TypeError, match="scales must be a sequence"):
        RayleighSum(0.5)
    with pytest.raises(ValueError, match=r"^scales: need at least one"):
        RayleighSum([])
    with pytest.raises(ValueError, match=r"scales\[1\] must be > 0"):
        RayleighSum([0.5, -1])
    big = RayleighSum([Fraction(10) ** 400, 1])
    with pytest.raises(ValueError, match=r"^scales\[0\] = 1\.0e\+400 is outside the float64 "
                                         r"range; use dps=$"):
        big.sf(1.0)
    assert big.sf(1, dps=15) == 1
    tiny = RayleighSum(["1e-400", 1])
    with pytest.raises(ValueError, match=r"^scales\[0\] = .* outside the float64 range"):
        tiny.mean()
    S = RayleighSum([0.5, 0.2, 0.1])
    assert repr(S) == "RayleighSum([0.5, 0.2, 0.1])"
    with pytest.raises(TypeError, match="x must be a scalar here"):
        S.probability([1.0])
    with pytest.raises(ValueError, match="tail"):
        S.probability(1.0, tail="both")
    with pytest.raises(ValueError, match="tail"):
        rayleigh_sum_probability([0.5, 0.2], 1.0, tail="middle")
    with pytest.raises(ValueError, match=r"^d must be > 0"):
        rayleigh_sum_probability([0.5, 0.2], -1.0)
    res = rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0, tail="lower", dps=20)
    assert rel(res.value, ref((0.5, 0.3, 0.2), 1.0, "cdf")) < 1e-20
    res = rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0)
    assert rel(res.value, ref((0.5, 0.3, 0.2), 1.0, "sf")) < 1e-13


# ---------------------------------------------------------------- small print of the public API
def test_moments_closed_forms_and_types():
    # E R = s sqrt(pi/2), Var R = (2 - pi/2) s**2 for one Rayleigh variable; sums add
    sc = [0.5, 0.3, 0.2]
    S = RayleighSum(sc)
    m, v = S.mean(), S.var()
    assert type(m) is float and type(v) is float and type(S.std()) is float
    assert m == pytest.approx(sum(sc) * math.sqrt(math.pi / 2), rel=1e-15)
    assert v == pytest.approx((2 - math.pi / 2) * sum(s * s for s in sc), rel=1e-15)
    assert S.std() == pytest.approx(math.sqrt(v), rel=1e-15)
    with mpmath.workdps(50):
        ref = mpmath.sqrt(mpmath.pi / 2) * (mpmath.mpf(0.5) + mpmath.mpf(0.3) + mpmath.mpf(0.2))
        assert abs(S.mean(dps=40) - ref) < mpmath.mpf(10) ** -40
        assert isinstance(S.std(dps=30), mpmath.mpf)
    x = S.rvs(random_state=3)
    assert type(x) is float and x > 0
    assert S.rvs(size=4, random_state=3).shape == (4,)
    with pytest.raises((TypeError, ValueError), match="random_state"):
        S.rvs(random_state="seed")


def test_small_print_of_the_functions():
    # d defaults to 1; the tail choice and the scalar-only arguments are named in errors
    assert rayleigh_sum_probability([0.5, 0.3, 0.2]) == rayleigh_sum_probability([0.5, 0.3, 0.2],
                                                                                  1.0)
    with pytest.raises(ValueError, match="tail"):
        rayleigh_sum_probability([0.5, 0.3], 1.0, tail="both")
    with pytest.raises(TypeError, match=r"sigma must be a scalar here, got list"):
        rayleigh_scales([0.5, 0.6])
    with pytest.raises(TypeError, match=r"^sigma1: a list needs a list of forcing components "
                                        r"Omega$"):
        rayleigh_scales(0.5, sigma1=[0.1, 0.2])
    with pytest.raises(ValueError, match=r"Omega\[1\]: resonance Omega == omega \(infinite "
                                         r"forced amplitude\)$"):
        rayleigh_scales(0.5, omega=1.5, Omega=[2.0, 1.5])


def test_float_routes_under_any_numpy_error_state():
    # underflow, division by zero and overflow are expected inside (tiny x, huge x, subnormal
    # ratios): every float64 entry point handles them itself, whatever the caller's error state
    xs = np.array([5e-324, 1e-310, 1e-100, 1e-5, 0.7, 30.0, 1e5, 1e12])
    for sc in ([1.0], [1.0, 0.5], [1.0, 0.5, 0.3], [1e-170, 2e-170, 3e-170]):
        S = RayleighSum(sc)
        x = xs * sc[0]
        plain = {k: getattr(S, k)(x) for k in ("sf", "cdf", "pdf", "logsf", "logcdf")}
        with np.errstate(all="raise"):
            for k, v in plain.items():
                np.testing.assert_array_equal(getattr(S, k)(x), v)


def test_log_cdf_leading_power_takes_logs_of_ratios():
    # log P(S <= x) = sum 2 log(x / s_i) - log((2n)!) far in: with x = 2**-1074 and scales
    # ~1e-314 the ratios are ~1e-10 (normal); log x - log s_i would lose ~1e-13 per term to the
    # rounding of log x ~ -744 (3e-15 relative here); the ratio is only avoided when it
    # underflows
    S = RayleighSum([1e-314, 2e-314, 3e-314])
    got = S.logcdf(5e-324)
    ref = S.logcdf(mpmath.mpf(5e-324), dps=30)
    with mpmath.workdps(40):
        assert abs(got / ref - 1) < 4e-16
    # a ratio below 1e-300 (x / 1e10): log x - log s, still to a few ulp of each log
    S2 = RayleighSum([1e10, 2e10, 3e10])
    got = S2.logcdf(5e-300)
    ref = S2.logcdf(mpmath.mpf(5e-300), dps=30)
    with mpmath.workdps(40):
        assert abs(got / ref - 1) < 1e-15


def test_one_scale_against_the_rayleigh_closed_form():
    # P(R <= x) = 1 - exp(-x**2/(2 s**2)), density x/s**2 exp(-x**2/(2 s**2)), both 0 at x <= 0
    S = RayleighSum(["0.7"])
    with mpmath.workdps(50):
        s = mpmath.mpf(7) / 10
        for x in ("0.1", "1", "5"):
            xm = mpmath.mpf(x)
            cdf = -mpmath.expm1(-xm**2 / (2 * s**2))
            pdf = xm / s**2 * mpmath.exp(-xm**2 / (2 * s**2))
            for got, ref in ((S.cdf(x, dps=30), cdf), (S.sf(x, dps=30), 1 - cdf),
                             (S.pdf(x, dps=30), pdf)):
                assert abs(got / ref - 1) < mpmath.mpf(10) ** -29, x
            sf_, xf = mpmath.mpf(0.7), mpmath.mpf(float(x))   # float64 takes the binary 0.7
            cdf_f = -mpmath.expm1(-xf**2 / (2 * sf_**2))
            pdf_f = xf / sf_**2 * mpmath.exp(-xf**2 / (2 * sf_**2))
            assert abs(S.cdf(float(x)) / cdf_f - 1) < 1e-15
            # exp(-E) carries the rounding of E = x**2/(2 s**2) (25.5 at x = 5): E eps relative
            assert abs(S.pdf(float(x)) / pdf_f - 1) < (2 + float(xf**2 / (2 * sf_**2))) * 2e-16
        for x in ("0", "-1"):
            assert S.cdf(x, dps=30) == 0 and S.pdf(x, dps=30) == 0 and S.sf(x, dps=30) == 1
            assert S.cdf(float(x)) == 0 and S.pdf(float(x)) == 0
