"""symhx.spaces.critical_point (``_critical``) against independent references (issue 16).

References: the weight polynomial of ``X = k`` from Burnside's count of every visit pattern of
the space (:func:`symhx.circuits.circuit_count`, not the class tables), each root ``c_k`` of
``W(k) = W(1)`` by plain bisection in mpmath at 70 digits, exhaustive exact argmax scans in
``Fraction`` arithmetic on either side of the enclosure, and the rational-root theorem for
exact critical points.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx.spaces._critical as crit
from symhx._mpctx import local, mp
from symhx.circuits import circuit_count
from symhx.critical import discriminant_root, discriminant_root_q
from symhx.spaces import EQ41_SHAPES, critical_point, parse_space, root_estimates, shapes_up_to
from symhx.spaces._classes import visits_of
from symhx.validation import mpf_to_fraction

WP = 70  # digits of the reference roots


def _members(base: str) -> tuple[set, bool]:
    if base in ("eq41", "eq41-printed"):
        return set(EQ41_SHAPES), base == "eq41-printed"
    return set(shapes_up_to(int(base.split("<=")[1]))), False


def _poly(N: int, base: str, w: str, k: int) -> dict[int, int]:
    """{degree: circuits} of W(k; p), Burnside counts of each visit pattern."""
    shapes, printed = _members(base)
    out: dict[int, int] = {}
    for s in shapes:
        if k < max(len(s), 1):
            continue
        if printed and s and k == len(s) and s != (2,):
            continue
        deg = k + sum(x - 1 for x in s) if w == "length" else k
        out[deg] = out.get(deg, 0) + circuit_count(N, visits_of(s, k))
    return out


def _Wx(poly: dict[int, int], p):
    return sum(c * p**d for d, c in poly.items())


def _roots(N: int, base: str, w: str) -> dict[int, mpmath.mpf]:
    """{k: c_k} for k = 2..N: bisection on log W(k) - log W(1) (increasing in p)."""
    p1 = _poly(N, base, w, 1)
    out = {}
    with mpmath.workdps(WP):
        for k in range(2, N + 1):
            pk = _poly(N, base, w, k)

            def f(p, pk=pk):
                return mpmath.log(_Wx(pk, p)) - mpmath.log(_Wx(p1, p))

            lo, hi = mpmath.mpf(1) / (1000 * N), mpmath.mpf(1000)
            assert f(lo) < 0 < f(hi)
            while hi - lo > mpmath.mpf(10) ** (8 - WP) * lo:
                mid = (lo + hi) / 2
                if f(mid) < 0:
                    lo = mid
                else:
                    hi = mid
            out[k] = (lo + hi) / 2
    return out


def _rational_root(N: int, base: str, w: str, k: int, approx: mpmath.mpf) -> Fraction | None:
    """The root c_k if it is rational (a candidate from the reference, checked exactly)."""
    with mpmath.workdps(WP):
        cand = mpf_to_fraction(approx).limit_denominator(10**20)
    if _Wx(_poly(N, base, w, k), cand) == _Wx(_poly(N, base, w, 1), cand):
        return cand
    return None


def _argmax(N: int, base: str, w: str, p: Fraction) -> tuple[int, ...]:
    W = [_Wx(_poly(N, base, w, k), p) for k in range(1, N + 1)]
    return tuple(k for k, x in enumerate(W, 1) if x == max(W))


CASES = [(b, w) for b in ("eq41", "eq41-printed", "excess<=1", "excess<=3")
         for w in ("length", "distinct")]


@pytest.mark.parametrize("base,w", CASES)
def test_critical_point_against_bisection(base, w):
    for N in (2, 3, 5, 12, 30):
        roots = _roots(N, base, w)
        with mpmath.workdps(WP):
            pc = min(roots.values())
            argmins = tuple(k for k, c in roots.items() if c - pc <= mpmath.mpf(10) ** -50 * pc)
        exact = _rational_root(N, base, w, argmins[0], pc)
        if exact is not None:
            with mpmath.workdps(WP):
                pc = mpmath.mpf(exact.numerator) / exact.denominator
        for dps in (15, 35):
            cp = critical_point(N, space=base, weighting=w, dps=dps)
            assert (cp.N, cp.dps, cp.k_before) == (N, dps, 1)
            assert cp.argmins == argmins, (base, w, N)
            with mpmath.workdps(dps):
                assert cp.p == +pc, (base, w, N, dps)      # correctly rounded to dps digits
            with mpmath.workdps(WP):
                q = N * pc - 1
            with mpmath.workdps(dps):
                assert cp.q == +q
            lo, hi = cp.p_bounds
            qlo, qhi = cp.q_bounds
            with mpmath.workdps(WP):
                assert lo <= pc <= hi and lo <= cp.p <= hi
                assert hi - lo <= mpmath.mpf(10) ** -dps * pc
                assert qlo <= q <= qhi and qlo <= cp.q <= qhi
                assert qhi - qlo <= mpmath.mpf(10) ** -dps * N * pc
            assert cp.p_d == discriminant_root(N, dps=dps)
            assert cp.q_d == discriminant_root_q(N, dps=dps)
            assert cp.p_exact == exact, (base, w, N)
            if exact is not None:
                assert mpf_to_fraction(lo) <= exact <= mpf_to_fraction(hi)
        # exhaustive exact scans just outside the enclosure: mode 1 below, k_after above
        flo, fhi = mpf_to_fraction(cp.p_bounds[0]), mpf_to_fraction(cp.p_bounds[1])
        below, above = flo * (1 - Fraction(1, 10**25)), fhi * (1 + Fraction(1, 10**25))
        assert _argmax(N, base, w, below) == (1,)
        assert _argmax(N, base, w, above) == (cp.k_after,)
        assert cp.k_after in cp.argmins


def test_rational_critical_points():
    """Distinct weighting: c_2 = W1/W2 coefficients is rational; found exactly, bounds collapse
    onto it, and the modes at p_exact tie."""
    from symhx.spaces import modes

    for base in ("eq41", "eq41-printed", "excess<=2"):
        for N in (2, 3):
            cp = critical_point(N, space=base, weighting="distinct", dps=20)
            c2 = Fraction(sum(_poly(N, base, "distinct", 1).values()),
                          sum(_poly(N, base, "distinct", 2).values()))
            assert cp.argmins == (2,) and cp.p_exact == c2
            with mpmath.workdps(20):
                assert cp.p == mpmath.mpf(c2.numerator) / c2.denominator
                assert cp.q == mpmath.mpf(N * c2.numerator - c2.denominator) / c2.denominator
            assert mpf_to_fraction(cp.p_bounds[0]) <= c2 <= mpf_to_fraction(cp.p_bounds[1])
            assert modes(N, c2, space=base, weighting="distinct") == (1, 2)


def test_exact_tie_of_two_argmins():
    """excess<=0 at N = 5: c_2 = c_3 = 1/2 exactly; both argmins, the faster-growing h_3 wins."""
    for w in ("length", "distinct"):
        cp = critical_point(5, space="excess<=0", weighting=w, dps=30)
        assert cp.argmins == (2, 3) and cp.p_exact == Fraction(1, 2) and cp.k_after == 3
        with mpmath.workdps(30):
            assert cp.p == mpmath.mpf(1) / 2 and cp.q == mpmath.mpf(3) / 2
        assert cp.p_bounds[0] <= 0.5 <= cp.p_bounds[1]
        assert _argmax(5, "excess<=0", w, Fraction(1, 2)) == (1, 2, 3)
        assert _argmax(5, "excess<=0", w, Fraction(1, 2) + Fraction(1, 10**20)) == (3,)


def test_tie_without_rational_raises(monkeypatch):
    monkeypatch.setattr(crit, "_try_rational", lambda *a: None)
    with pytest.raises(crit.UndecidedError, match=r"k in \[2, 3\] agree to 33 digits"):
        critical_point(5, space="excess<=0", dps=30)


def test_unbracketed_root_raises(monkeypatch):
    monkeypatch.setattr(crit, "_sign_h", lambda *a: 0)
    with pytest.raises(crit.UndecidedError, match=r"could not bracket c_\d+ for N=12, "
                                                  r"space=eq41"):
        critical_point(12, space="eq41", dps=15)


def test_sign_evaluations_count_the_certified_signs(monkeypatch):
    real = crit._sign_h
    calls = []

    def counting(*a):
        calls.append(a[2])
        return real(*a)

    monkeypatch.setattr(crit, "_sign_h", counting)
    for base, N in (("eq41", 30), ("excess<=3;distinct", 12), ("excess<=0", 5)):
        calls.clear()
        cp = critical_point(N, space=base, dps=20)
        assert cp.sign_evaluations == len(calls) >= 2


def test_simple_space_is_delegated():
    from symhx.critical import critical_point as simple_cp

    for N in (2, 5, 101):
        assert critical_point(N, space="simple", dps=25) == simple_cp(N, dps=25)


# --------------------------------------------------------------------------- the pieces
@pytest.mark.parametrize("base,w", [*CASES, ("excess<=0", "length")])
def test_root_estimates_against_bisection(base, w):
    space = base if w == "length" else base + ";distinct"
    for N in (2, 3, 12, 30):
        s = root_estimates(space, N)
        assert s.shape == (N - 1,)
        roots = _roots(N, base, w)
        for k, c in roots.items():
            with mpmath.workdps(30):
                ref = float(mpmath.log(N * c))
            assert abs(s[k - 2] - ref) <= 1e-10 * max(1.0, abs(ref)), (N, k)


def test_log_Q_h_and_dh_against_polynomials():
    for base, w in (("eq41", "length"), ("eq41-printed", "length"), ("excess<=3", "distinct")):
        sp = parse_space(base, w)
        N = 12
        p1 = _poly(N, base, w, 1)
        # the helpers compute in this thread's symhx context (symhx._mpctx): set both
        with mpmath.workdps(50), mp().workdps(50):
            for k in (1, 2, 3, 5, 12):
                pk = _poly(N, base, w, k)
                for s in (mpmath.mpf(-1), mpmath.mpf("0.3"), mpmath.mpf(2)):
                    p = mpmath.exp(s) / N

                    def h(t, pk=pk, p1=p1, N=N):
                        pp = mpmath.exp(t) / N
                        return mpmath.log(_Wx(pk, pp)) - mpmath.log(_Wx(p1, pp))

                    assert mpmath.almosteq(crit._h_mp(sp, N, k, local(s)), h(s), 1e-45)
                    dref = mpmath.diff(h, s)
                    assert mpmath.almosteq(crit._dh_mp(sp, N, k, local(s)), dref, 1e-35)
                    # log Q*: W(k) / (p**k N!/(k (N-k)!)) up to the constant denominator D
                    phi = p**k * mpmath.mpf(math.perm(N, k)) / k
                    q = _Wx(pk, p) / phi
                    ref = mpmath.log(q * sp.denominator)
                    assert mpmath.almosteq(crit._log_Q_mp(sp, k, local(p)), ref, 1e-45)
                    fr = mpf_to_fraction(p)
                    with mpmath.workdps(80):
                        exact = mpmath.log(_Wx(pk, fr)) - mpmath.log(_Wx(p1, fr))
                    ball = crit._h_arb(sp, N, k, fr)
                    assert float(ball.rad()) < 1e-12 and ball.contains(
                        crit.to_arb(mpf_to_fraction(exact)))


def test_bracket_brackets_at_the_documented_gap():
    sp = parse_space("eq41")
    for dps in (10, 30):
        with mpmath.workdps(80):
            s = mpmath.mpf("-0.25")
            p = mpmath.exp(s) / 40
        lo, hi = crit._bracket(sp, 40, s, dps, 80)
        assert isinstance(lo, Fraction) and isinstance(hi, Fraction)
        with mpmath.workdps(80):
            pf = mpf_to_fraction(p)
        assert lo < pf < hi
        gap = (hi - lo) / pf
        assert Fraction(1, 10 ** (dps + 4)) < gap < Fraction(1, 10 ** (dps + 2))
        assert abs((lo + hi) / 2 - pf) < pf * Fraction(1, 10 ** (dps + 20))


def test_try_rational():
    sp = parse_space("excess<=0")
    with mpmath.workdps(60):
        s_half = mpmath.log(mpmath.mpf(5) / 2)          # p = e**s / 5 = 1/2
        s_off = mpmath.log(mpmath.mpf(5) / 2 * (1 + mpmath.mpf(10) ** -30))
    assert crit._try_rational(sp, 5, s_half, [2, 3], 60) == Fraction(1, 2)
    assert crit._try_rational(sp, 5, s_half, [2], 60) == Fraction(1, 2)
    assert crit._try_rational(sp, 5, s_off, [2, 3], 60) is None   # not the rational within wp
    assert crit._try_rational(sp, 5, s_half, [4], 60) is None       # no tie with k = 4
    # a candidate that is not even close to p (low precision limit_denominator) is refused
    with mpmath.workdps(60):
        s_irr = mpmath.log(5 * mpmath.sqrt(2) / 7)
    assert crit._try_rational(sp, 5, s_irr, [2], 60) is None


def test_try_rational_undecided(monkeypatch):
    sp = parse_space("excess<=0")

    def boom(*a):
        raise crit.UndecidedError("too big")

    monkeypatch.setattr(crit, "compare_weights", boom)
    with mpmath.workdps(60):
        s_half = mpmath.log(mpmath.mpf(5) / 2)
    assert crit._try_rational(sp, 5, s_half, [2, 3], 60) is None


def test_unexcluded_is_exactly_the_non_excluded_set():
    """At generic rationals (no near ties) the running product lists exactly the k != best
    with W(k) >= W(1) (exact Fractions over all k), never best itself."""
    for base, w, N in (("eq41", "length", 30), ("excess<=3", "distinct", 20),
                       ("eq41-printed", "length", 25)):
        sp = parse_space(base, w)
        polys = {k: _poly(N, base, w, k) for k in range(1, N + 1)}
        for p in (Fraction(1, 2 * N), Fraction(2, N), Fraction(1, 4), Fraction(3, 2)):
            W = {k: _Wx(polys[k], p) for k in polys}
            for best in (2, 5, N):
                got = crit._unexcluded(sp, N, p, best)
                assert best not in got
                want = [k for k in range(2, N + 1) if k != best and W[k] >= W[1]]
                assert got == want, (base, N, p, best)


def test_root_mp_against_bisection():
    for base, w, N in (("eq41", "length", 30), ("excess<=3", "distinct", 12)):
        sp = parse_space(base, w)
        roots = _roots(N, base, w)
        est = root_estimates(sp, N)
        for k in (2, 7, N):
            for wp in (20, 50):
                s = crit._root_mp(sp, N, k, float(est[k - 2]) + 0.01, wp)
                with mpmath.workdps(WP):
                    ref = mpmath.log(N * roots[k])
                    assert abs(s - ref) <= mpmath.mpf(10) ** (4 - wp) * max(1, abs(ref)), (k, wp)


def test_wrong_seed_is_still_certified(monkeypatch):
    """A float seed pointing at the largest root: the certified passes walk down to p_c."""
    base, N = "eq41", 30
    right = critical_point(N, space=base, dps=20)
    real = crit.root_estimates

    def fake(sp, n):
        s = np.array(real(sp, n))
        s[:] = s.max() + 1.0
        s[-1] = s.max() - 0.5  # argmin at k = N, whose root is far above p_c
        return s

    monkeypatch.setattr(crit, "root_estimates", fake)
    got = crit.critical_point(N, space=base, dps=20)
    assert got.argmins == right.argmins and got.p == right.p
    assert got.p_bounds == right.p_bounds and got.k_after == right.k_after
    assert got.sign_evaluations > right.sign_evaluations


def test_root_estimates_widen_a_narrow_bracket(monkeypatch):
    """Start from a bracket (-0.01, 0.01) that misses roots on both sides: the doubling widens
    each side until it brackets, and the estimates still match the bisection roots."""
    monkeypatch.setattr(crit, "ROOT_BRACKET", 0.01)
    for base, w, N in (("eq41", "length", 12), ("excess<=3", "distinct", 30)):
        space = base if w == "length" else base + ";distinct"
        s = root_estimates(space, N)
        roots = _roots(N, base, w)
        with mpmath.workdps(30):
            refs = [float(mpmath.log(N * roots[k])) for k in range(2, N + 1)]
        assert min(refs) < -0.01 or base == "eq41"
        assert max(refs) > 0.01
        for k, ref in zip(range(2, N + 1), refs, strict=True):
            assert abs(s[k - 2] - ref) <= 1e-10 * max(1.0, abs(ref)), (base, N, k)
