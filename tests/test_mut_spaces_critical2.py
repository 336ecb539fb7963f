"""symhx.spaces.critical_point (``_critical``), second file: the pieces at their limits (issue 16).

References as in ``test_mut_spaces_critical``: weight polynomials from Burnside's circuit counts
(``_poly``), roots by plain bisection at 70 digits (``_roots``), exact ``Fraction`` comparisons of
the weights; for the ``;distinct`` weighting the closed form ``c_k = (S_1 / S_k)**(1/(k-1))`` with
``S_k`` the exact number of circuits with ``k`` distinct vertices.
"""

from __future__ import annotations

import warnings
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx.spaces._critical as crit
from symhx.spaces import critical_point, parse_space, root_estimates
from symhx.validation import mpf_to_fraction
from tests.test_mut_spaces_critical import WP, _poly, _roots, _Wx


def _root1(N: int, base: str, k: int, digits: int = WP) -> mpmath.mpf:
    """c_k by plain bisection of W(k) - W(1) (one sign change) at ``digits`` digits."""
    pk, p1 = _poly(N, base, "length", k), _poly(N, base, "length", 1)
    with mpmath.workdps(digits):
        lo, hi = mpmath.mpf(1) / (1000 * N), mpmath.mpf(1000)
        assert _Wx(pk, lo) < _Wx(p1, lo) and _Wx(pk, hi) > _Wx(p1, hi)
        while hi - lo > mpmath.mpf(10) ** (8 - digits) * lo:
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if _Wx(pk, mid) < _Wx(p1, mid) else (lo, mid)
        return (lo + hi) / 2


def _log_Nc(N: int, c) -> float:
    with mpmath.workdps(30):
        return float(mpmath.log(N * c))


# --------------------------------------------------------------------------- root_estimates
@pytest.mark.parametrize("base,Ns", [("eq41", (2, 3, 5, 12)), ("excess<=3", (2, 3, 5, 12)),
                                     ("excess<=12", (2, 3, 5)), ("excess<=20", (2, 3, 5)),
                                     ("excess<=25", (2, 3))])
def test_root_estimates_to_float64_accuracy(base, Ns):
    """Small N (every term of h_k is O(10)): the safeguarded Newton iteration ends at the float64
    root, within a few dozen ulps of the 70-digit bisection root, also for large excess where
    the mean-excess part of the slope dominates (k = 2)."""
    for N in Ns:
        s = root_estimates(base, N)
        for k, c in _roots(N, base, "length").items():
            assert abs(s[k - 2] - _log_Nc(N, c)) <= 1e-14, (base, N, k)


@pytest.mark.parametrize("base", ["excess<=6", "excess<=12"])
def test_root_estimates_many_columns(base):
    """N = 200: 199 roots iterated together; each column's slope is its own mean excess."""
    N = 200
    s = root_estimates(base, N)
    p1 = _poly(N, base, "length", 1)
    for k in (2, 3, 6):
        pk = _poly(N, base, "length", k)
        with mpmath.workdps(40):
            lo, hi = mpmath.mpf(1) / N, mpmath.mpf(5) / N   # plain bisection
            assert _Wx(pk, lo) < _Wx(p1, lo) and _Wx(pk, hi) > _Wx(p1, hi)
            for _ in range(110):
                mid = (lo + hi) / 2
                lo, hi = (mid, hi) if _Wx(pk, mid) < _Wx(p1, mid) else (lo, mid)
        assert abs(s[k - 2] - _log_Nc(N, lo)) <= 1e-12, (base, k)


@pytest.mark.parametrize("base,Ns", [("excess<=20", (2, 3, 5, 12)), ("excess<=25", (2, 3)),
                                     ("eq41-printed", (2, 3, 5, 12))])
def test_root_estimates_distinct_closed_form(base, Ns):
    """``;distinct``: h_k is linear in log p, c_k = (S_1/S_k)**(1/(k-1)) exactly."""
    for N in Ns:
        s = root_estimates(base + ";distinct", N)
        S1 = sum(_poly(N, base, "distinct", 1).values())
        for k in range(2, N + 1):
            Sk = sum(_poly(N, base, "distinct", k).values())
            with mpmath.workdps(30):
                ref = float(mpmath.log(N) + (mpmath.log(S1) - mpmath.log(Sk)) / (k - 1))
            assert abs(s[k - 2] - ref) <= 1e-14 * max(1.0, abs(ref)), (base, N, k)


def test_root_estimates_emit_no_float_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for space in ("eq41", "excess<=20", "excess<=3;distinct"):
            for N in (2, 3, 30):
                assert np.all(np.isfinite(root_estimates(space, N)))


def test_root_estimates_widen_the_lower_end(monkeypatch):
    """excess<=20 has roots below N c = 1 (log(N c_2) < 0 at N = 2, log(N c_3) < 0 at N = 3):
    from (-0.001, 0.001) the lower end is doubled until it brackets them too."""
    monkeypatch.setattr(crit, "ROOT_BRACKET", 0.001)
    for N in (2, 3):
        s = root_estimates("excess<=20", N)
        refs = {k: _log_Nc(N, c) for k, c in _roots(N, "excess<=20", "length").items()}
        assert min(refs.values()) < -0.009
        for k, ref in refs.items():
            assert abs(s[k - 2] - ref) <= 1e-14, (N, k)


def test_root_estimates_double_at_most_twenty_times(monkeypatch):
    """ROOT_BRACKET's contract: each end is doubled up to 20 times. From 2**-40 the ends stop at
    -+2**-20, short of every root (|log(N c_k)| > 0.009 here), and the iteration stays inside."""
    monkeypatch.setattr(crit, "ROOT_BRACKET", 2.0**-40)
    for N in (3, 5):
        s = root_estimates("excess<=20", N)
        for k, c in _roots(N, "excess<=20", "length").items():
            ref = _log_Nc(N, c)
            assert abs(ref) > 0.009
            assert abs(s[k - 2] - np.copysign(2.0**-20, ref)) <= 1e-12   # at the end nearest
    # from 2**-25 the twenty doublings reach 2**-5 > |log(2 c_2)| = 0.028...: the root is found
    monkeypatch.setattr(crit, "ROOT_BRACKET", 2.0**-25)
    (c2,) = _roots(2, "excess<=20", "length").values()
    assert abs(root_estimates("excess<=20", 2)[0] - _log_Nc(2, c2)) <= 1e-14


# --------------------------------------------------------------------------- mpmath refinement
def _count_h_mp(monkeypatch) -> list[int]:
    calls: list[int] = []
    real = crit._h_mp

    def counting(sp, N, k, s):
        calls.append(k)
        return real(sp, N, k, s)

    monkeypatch.setattr(crit, "_h_mp", counting)
    return calls


def test_root_mp_newton_is_quadratic_from_the_float_seed(monkeypatch):
    """From the float64 seed (~16 digits) Newton doubles the digits per step: at most 5 steps up
    to 200 digits, and the root agrees with the 70-digit bisection root."""
    calls = _count_h_mp(monkeypatch)
    for base, N in (("eq41", 30), ("excess<=3", 12), ("excess<=20", 3)):
        sp = parse_space(base)
        est = root_estimates(sp, N)
        for k in (2, 3, N):
            ck = _root1(N, base, k)
            for wp in (20, 50, 200):
                calls.clear()
                s = crit._root_mp(sp, N, k, float(est[k - 2]), wp)
                assert 1 <= len(calls) <= 5, (base, N, k, wp, len(calls))
                with mpmath.workdps(WP):
                    ref = mpmath.log(N * ck)
                    assert abs(s - ref) <= mpmath.mpf(10) ** (3 - min(wp, WP - 8)), (k, wp)


def test_critical_point_refines_each_root_from_its_own_seed(monkeypatch):
    """critical_point refines c_best from the float64 seed of the same k (error ~1e-15): at
    dps = 30 (wp ~ 50) two Newton steps reach 1e-60 and the third, below 10**(3-wp), stops; a
    neighbour's seed (0.05 to 0.15 off in log p) needs two more."""
    calls = _count_h_mp(monkeypatch)
    for base, N in (("eq41", 12), ("eq41", 30), ("excess<=3", 30), ("excess<=6", 100),
                    ("excess<=1", 200)):
        calls.clear()
        critical_point(N, space=base, dps=30)
        assert calls and all(calls.count(k) <= 3 for k in set(calls)), (base, calls)


def test_bracket_relative_gap_is_two_times_ten_to_minus_dps_plus_3():
    """_bracket: p (1 -+ 10**-(dps+3)), so the relative gap is 2e-(dps+3), not 10x narrower."""
    sp = parse_space("eq41")
    for dps in (10, 30):
        with mpmath.workdps(80):
            s = mpmath.mpf("-0.25")
            pf = mpf_to_fraction(mpmath.exp(s) / 40)
        lo, hi = crit._bracket(sp, 40, s, dps, 80)
        gap = (hi - lo) / pf * 10 ** (dps + 3)
        assert abs(gap - 2) < Fraction(1, 10**20)


# --------------------------------------------------------------------------- certified signs
def _near_root(N: int, base: str, k: int, rel_exp: int) -> tuple[Fraction, Fraction]:
    """Rationals c_k (1 -+ 2**-rel_exp), c_k to 250 digits."""
    with mpmath.workdps(260):
        cf = mpf_to_fraction(_root1(N, base, k, 260))
    d = Fraction(1, 2**rel_exp)
    return cf * (1 - d), cf * (1 + d)


def _exact_sign(N: int, base: str, k: int, fr: Fraction) -> int:
    d = _Wx(_poly(N, base, "length", k), fr) - _Wx(_poly(N, base, "length", 1), fr)
    return (d > 0) - (d < 0)


def test_sign_h_exact_tie_is_zero():
    """excess<=0, N = 5: W(1) = W(2) = W(3) at p = 1/2 exactly; the Arb balls cannot decide and
    the exact comparison returns 0."""
    sp = parse_space("excess<=0")
    for k in (2, 3):
        assert _exact_sign(5, "excess<=0", k, Fraction(1, 2)) == 0
        assert crit._sign_h(sp, 5, k, Fraction(1, 2), 64) == 0
    assert crit._sign_h(sp, 5, 4, Fraction(1, 2), 64) == _exact_sign(5, "excess<=0", 4,
                                                                      Fraction(1, 2)) == -1


def test_sign_h_exact_fallback_beyond_eight_times_the_bits():
    """eq41, N = 12, k = 3 (c_3 < c_2): 2**-700 from c_3 the balls at up to 8 * 64 bits cannot
    decide, the exact comparison of W(3) with W(1) does, on both sides."""
    sp = parse_space("eq41")
    for fr in _near_root(12, "eq41", 3, 700):
        want = _exact_sign(12, "eq41", 3, fr)
        assert want != 0
        assert crit._sign_h(sp, 12, 3, fr, 64) == want


def test_sign_h_raises_the_ball_precision_before_the_exact_fallback(monkeypatch):
    """2**-200 from c_3 a 64-bit ball is too wide but the doubling precision (up to 8 * 64 bits)
    decides without the exact comparison."""
    sp = parse_space("eq41")

    def no_exact(*a):
        raise AssertionError("exact comparison not needed")

    monkeypatch.setattr(crit, "compare_weights", no_exact)
    for fr in _near_root(12, "eq41", 3, 200):
        assert crit._sign_h(sp, 12, 3, fr, 64) == _exact_sign(12, "eq41", 3, fr) != 0
    with pytest.raises(AssertionError, match="not needed"):   # and 64 bits alone do not suffice
        crit.certified_sign(lambda: crit._h_arb(sp, 12, 3, fr), start_bits=64, max_bits=64,
                            exact_fn=lambda: no_exact())


# --------------------------------------------------------------------------- exclusion product
def _exact_unexcluded(N: int, base: str, w: str, p: Fraction, best: int) -> list[int]:
    W = {k: _Wx(_poly(N, base, w, k), p) for k in range(1, N + 1)}
    return [k for k in range(2, N + 1) if k != best and W[k] >= W[1]]


def test_unexcluded_lists_exact_ties():
    """excess<=0, N = 5, p = 1/2: W(2) = W(3) = W(1) exactly, so the tied k != best is listed
    (W(k) < W(1) is false); the ball of W(2)/W(1) is exactly 1 here."""
    sp = parse_space("excess<=0")
    for best in (2, 3, 5):
        want = _exact_unexcluded(5, "excess<=0", "length", Fraction(1, 2), best)
        assert crit._unexcluded(sp, 5, Fraction(1, 2), best) == want
        assert set(want) | {best} >= {2, 3}


def test_unexcluded_does_not_stop_while_W_still_rises():
    """excess<=0, N = 8 and 10, p a little above c_3 and best = 2: W(k)/W(1) dips below 1 and
    rises again; the stopping bound rho(k) = p (N-k)(k+m)/(k+1-R) keeps the product going."""
    sp = parse_space("excess<=0")
    for N, p in ((8, Fraction(136013, 509292)), (8, Fraction(107760, 403201)),
                 (10, Fraction(169876, 851639))):
        want = _exact_unexcluded(N, "excess<=0", "length", p, 2)
        assert want and crit._unexcluded(sp, N, p, 2) == want


def _convergents_below(c: Fraction, min_bits: int, count: int) -> list[Fraction]:
    """Continued-fraction convergents a/b < c with b >= 2**min_bits (|a/b - c| < 1/b**2)."""
    out, (h0, h1), (k0, k1), x = [], (0, 1), (1, 0), c
    while len(out) < count and x.denominator != 0:
        a = x.numerator // x.denominator
        h0, h1, k0, k1 = h1, a * h1 + h0, k1, a * k1 + k0
        if k1 >= 2**min_bits and Fraction(h1, k1) < c:
            out.append(Fraction(h1, k1))
        if x == a:
            break
        x = 1 / (x - a)
    return out


def test_unexcluded_resolves_near_ties_at_the_bits_of_p():
    """Continued-fraction convergents a/b of c_k just below it (W(k)/W(1) = 1 - O(b**-2)): the
    product's precision grows with the bits of a and b, so such a k is still excluded."""
    cases = 0
    for base, N, k in (("eq41", 12, 3), ("eq41", 30, 6), ("excess<=3", 20, 4)):
        sp = parse_space(base)
        with mpmath.workdps(120):
            c = mpf_to_fraction(_root1(N, base, k, 120))
        for fr in _convergents_below(c, 60, 2):
            want = _exact_unexcluded(N, base, "length", fr, 2)
            assert k not in want
            assert crit._unexcluded(sp, N, fr, 2) == want, (base, N, fr)
            cases += 1
    assert cases == 6


# --------------------------------------------------------------------------- exact rationals
def test_try_rational_finds_denominators_up_to_ten_to_wp_over_3():
    """eq41;distinct: c_2 = S_1/S_2 = 8/(9(N-1)); N = 3000 gives a 5-digit denominator, found at
    wp = 18 (limit 10**6) and verified exactly; at wp = 30 a 4-digit one (N = 300)."""
    for N, wp in ((3000, 18), (300, 30)):
        sp = parse_space("eq41", "distinct")
        c2 = Fraction(sum(_poly(N, "eq41", "distinct", 1).values()),
                      sum(_poly(N, "eq41", "distinct", 2).values()))
        assert 10 * (wp // 3) < c2.denominator <= 10 ** (wp // 3)
        assert N == 300 or c2.denominator > 10 ** (wp // 4)
        with mpmath.workdps(wp):
            s = mpmath.log(N * mpmath.mpf(c2.numerator) / c2.denominator)
        assert crit._try_rational(sp, N, s, [2], wp) == c2


def test_try_rational_at_400_digits():
    """p = 1/2 from s = log(N p) known to wp - 4 digits (what _root_mp delivers, 10**(3-wp)):
    the closeness test, 10**(8-wp) relative, still accepts the exact candidate at wp = 400."""
    sp = parse_space("excess<=0")
    with mpmath.workdps(396):
        s = mpmath.log(mpmath.mpf(5) / 2)
    with mpmath.workdps(420):
        assert abs(mpmath.exp(s) / 5 - mpmath.mpf(1) / 2) > mpmath.mpf(10) ** -405
    assert crit._try_rational(sp, 5, s, [2, 3], 400) == Fraction(1, 2)


# --------------------------------------------------------------------------- critical_point logic
def _bisection_pc(N: int, base: str) -> tuple[tuple[int, ...], mpmath.mpf]:
    roots = _roots(N, base, "length")
    with mpmath.workdps(WP):
        pc = min(roots.values())
        return tuple(k for k, c in roots.items() if c - pc <= mpmath.mpf(10) ** -50 * pc), pc


def test_weak_exclusion_and_a_wrong_seed_still_certify(monkeypatch):
    """The exclusion step may list more k than needed (its contract is a superset). With every
    k listed and the float seed pointing at k = 5 (c_5 between c_2 and p_c), the k with
    c_k > p_hi are skipped, not taken as the end of the list: the passes reach p_c."""
    N, base = 30, "eq41"
    argmins, pc = _bisection_pc(N, base)
    real = crit.root_estimates

    def seed(sp, n):
        s = np.array(real(sp, n))
        s[3] = s.min() - 0.5   # argmin at k = 5
        return s

    monkeypatch.setattr(crit, "root_estimates", seed)
    monkeypatch.setattr(crit, "_unexcluded",
                        lambda sp, n, fr, best: [k for k in range(2, n + 1) if k != best])
    cp = crit.critical_point(N, space=base, dps=20)
    assert argmins != (5,) and cp.argmins == argmins
    with mpmath.workdps(20):
        assert cp.p == +pc


def test_zero_sign_at_p_hi_counts_as_a_tie(monkeypatch):
    """h_k(p_hi) = 0 means c_k = p_hi, inside the bracket: k is a tied argmin, not a k with
    c_k > p_hi. excess<=0, N = 5;distinct (c_2 = c_3 = 1/2): report h_k(p_hi) as an exact 0 for
    the k other than the seed's; it must still be an argmin and the faster-growing k_after."""
    real = crit._sign_h
    first = int(np.argmin(root_estimates("excess<=0;distinct", 5))) + 2
    other = 5 - first   # {2, 3}

    def sign(sp, N, k, fr, bits):
        if k == other and fr > Fraction(1, 2):
            return 0
        return real(sp, N, k, fr, bits)

    monkeypatch.setattr(crit, "_sign_h", sign)
    cp = crit.critical_point(5, space="excess<=0", weighting="distinct", dps=25)
    assert cp.argmins == (2, 3) and cp.k_after == 3 and cp.p_exact == Fraction(1, 2)


def test_zero_sign_at_p_lo_starts_a_new_pass(monkeypatch):
    """h_k(p_lo) = 0 means c_k = p_lo < c_best: a better k, so a new pass refines c_k (here a
    one-off false report; the new pass around the true c_k = 1/2 finds the tie again)."""
    real = crit._sign_h
    first = int(np.argmin(root_estimates("excess<=0;distinct", 5))) + 2
    other = 5 - first
    told = []

    def sign(sp, N, k, fr, bits):
        if k == other and fr < Fraction(1, 2) and not told:
            told.append(fr)
            return 0
        return real(sp, N, k, fr, bits)

    refined = []
    real_root = crit._root_mp

    def root(sp, N, k, s0, wp):
        refined.append(k)
        return real_root(sp, N, k, s0, wp)

    monkeypatch.setattr(crit, "_sign_h", sign)
    monkeypatch.setattr(crit, "_root_mp", root)
    cp = crit.critical_point(5, space="excess<=0", weighting="distinct", dps=25)
    assert told and sorted(set(refined)) == [2, 3]
    assert cp.argmins == (2, 3) and cp.p_exact == Fraction(1, 2)


def test_endless_lower_claims_stop_after_N_passes(monkeypatch):
    """c_best strictly decreases from pass to pass, so at most N passes; signs that claim a lower
    k on every pass end in UndecidedError naming N and the space."""
    state = {"lo": None, "best": None}
    real_bracket = crit._bracket

    def bracket(*a):
        state["lo"], hi = real_bracket(*a)
        state["best"] = None
        return state["lo"], hi

    def sign(sp, N, k, fr, bits):
        if state["best"] is None:
            state["best"] = k
        if k == state["best"]:
            return -1 if fr == state["lo"] else 1
        return 1   # c_k <= p_lo: "a better k", every time

    monkeypatch.setattr(crit, "_bracket", bracket)
    monkeypatch.setattr(crit, "_sign_h", sign)
    monkeypatch.setattr(crit, "_unexcluded",
                        lambda sp, n, fr, best: [k for k in range(2, n + 1) if k != best])
    with pytest.raises(crit.UndecidedError, match=r"no certified argmin for N=5, space=eq41"):
        crit.critical_point(5, space="eq41", dps=15)


def _assert_excess0_closed_form(cp, N, k, dps):
    """excess<=0 has W(k) = A_k p**k: c_k = (A_1/A_k)**(1/(k-1)) in closed form, inside the
    certified bracket and equal to p at dps digits."""
    (A1,) = _poly(N, "excess<=0", "length", 1).values()
    (Ak,) = _poly(N, "excess<=0", "length", k).values()
    with mpmath.workdps(60):
        c = (mpmath.mpf(A1) / Ak) ** (mpmath.mpf(1) / (k - 1))
        assert cp.p_bounds[0] <= c <= cp.p_bounds[1]
    with mpmath.workdps(dps):
        assert cp.p == +c


def test_k_after_is_the_tied_k_whose_h_grows_fastest(monkeypatch):
    """Among tied argmins k_after maximises (slope of h_k, k). ;distinct weighting (roots in
    closed form, _dh_mp only gives the slopes): real slopes k - 1 pick 3; reversed slopes pick 2;
    equal slopes pick the larger k."""
    def at(slopes):
        monkeypatch.setattr(crit, "_dh_mp", lambda sp, N, k, s: mpmath.mpf(slopes[k]))
        return crit.critical_point(5, space="excess<=0", weighting="distinct", dps=20)

    assert at({2: 1, 3: 2}).k_after == 3
    cp = at({2: 2, 3: 1})
    assert cp.argmins == (2, 3) and cp.k_after == 2
    assert at({2: 1, 3: 1}).k_after == 3


def test_guard_digits_grow_with_the_digits_of_N():
    """N = 10**6 (7 digits, lgamma terms ~ 10**7 cancel): still correctly rounded and bracketed.
    excess<=0 has W(k) = A_k p**k, so c_k = (A_1/A_k)**(1/(k-1)) in closed form."""
    N = 10**6
    cp = critical_point(N, space="excess<=0", dps=15)
    (k,) = cp.argmins
    _assert_excess0_closed_form(cp, N, k, 15)


@pytest.mark.parametrize("N,k", [(20000, 14000), (40000, 12500)])
def test_no_rational_search_beyond_its_work_limit(monkeypatch, N, k):
    """The exact rational search is skipped when best * bitlen(N) >= 200000 (in practice
    N >~ 4e6); the result is then the certified bracket with p_exact None. Reached here at
    N = 20000 (15 bits) by a seed at k = 14000, and at the limit itself (16 bits, k = 12500),
    with an exclusion step reporting every other k excluded (a stub: the point is the last
    branch, not the argmin); c_k of excess<=0 in closed form."""
    real = crit.root_estimates

    def seed(sp, n):
        s = np.array(real(sp, n))
        s[k - 2] = s.min() - 1.0
        return s

    def no_search(*a):
        raise AssertionError("rational search beyond its work limit")

    monkeypatch.setattr(crit, "root_estimates", seed)
    monkeypatch.setattr(crit, "_unexcluded", lambda *a: [])
    monkeypatch.setattr(crit, "_try_rational", no_search)
    cp = crit.critical_point(N, space="excess<=0", dps=20)
    assert cp.argmins == (k,) and cp.p_exact is None
    _assert_excess0_closed_form(cp, N, k, 20)


def test_root_estimates_from_bracket_ends_where_h_is_one(monkeypatch):
    """The iteration stops on a small step (or h == 0), never on any other value of h: started
    from the upper end of the bracket (the simple-space start, 1.39, is clipped to it) at 201
    consecutive floats around the point where h_2 = 1 (bisection on the Burnside polynomials;
    the float h there hits 1.0 exactly for many of them), every estimate reaches the root."""
    N = 2
    p1, p2 = _poly(N, "excess<=20", "length", 1), _poly(N, "excess<=20", "length", 2)
    with mpmath.workdps(40):
        def h(s):
            p = mpmath.exp(s) / N
            return mpmath.log(_Wx(p2, p)) - mpmath.log(_Wx(p1, p))

        lo, hi = mpmath.mpf(-1), mpmath.mpf(1)
        for _ in range(100):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if h(mid) < 1 else (lo, mid)
    (c2,) = _roots(N, "excess<=20", "length").values()
    root = _log_Nc(N, c2)
    ends = float(lo) + np.arange(-100, 101) * np.spacing(float(lo))
    assert root < ends.min() and ends.max() < 0.2
    for r in ends:
        monkeypatch.setattr(crit, "ROOT_BRACKET", float(r))
        assert abs(root_estimates("excess<=20", N)[0] - root) <= 1e-14, r


def test_try_rational_refuses_a_close_rational_that_is_no_root():
    """At wp = 18 the candidate (denominator <= 10**6) of an irrational c_2 lies within the
    closeness test (10**-10 relative); only the exact comparison of W(2) with W(1) refuses it."""
    N = 2
    sp = parse_space("eq41")
    c2 = _root1(N, "eq41", 2)
    with mpmath.workdps(18):
        s = mpmath.log(N * c2)
        cand = mpf_to_fraction(mpmath.exp(s) / N).limit_denominator(10**6)
    with mpmath.workdps(30):
        assert abs(mpmath.mpf(cand.numerator) / cand.denominator / c2 - 1) < mpmath.mpf(10) ** -11
    assert _Wx(_poly(N, "eq41", "length", 2), cand) != _Wx(_poly(N, "eq41", "length", 1), cand)
    assert crit._try_rational(sp, N, s, [2], 18) is None
