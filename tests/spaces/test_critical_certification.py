"""The certified steps of ``symhx.spaces.critical_point`` (``symhx.spaces._critical``, see its
module docstring): the mpmath functions ``h_k``, its slope and ``log Q*``, the Newton refinement
of a root, the bracket, the certified sign of ``h_k`` (Arb balls with an exact fall-back), the
exclusion product, the search for an exact rational root, and the seed-and-verify loop itself
when a step misbehaves (a wrong float64 seed, a weak exclusion, zero signs, endless claims).

References (:mod:`tests.reference.spaces`): weight polynomials from Burnside's counts, roots by
plain bisection at 70 (up to 260) digits, exact ``Fraction`` comparisons of the weights, the
closed form ``c_k = (S_1/S_k)**(1/(k-1))`` of monomial weights, numerical derivatives
(``mpmath.diff``).
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx.spaces._critical as crit
from symhx._mpctx import local, mp
from symhx.spaces import critical_point, parse_space, root_estimates
from symhx.validation import mpf_to_fraction
from tests.reference.spaces import (
    ROOT_DIGITS,
    critical_by_bisection,
    evaluate,
    monomial_root,
    not_below_one,
    root,
    roots,
    weight_poly,
    weight_sign,
)

WP = ROOT_DIGITS


def _log_Nc(N: int, c) -> float:
    with mpmath.workdps(30):
        return float(mpmath.log(N * c))


def _near_root(N: int, base: str, k: int, rel_exp: int) -> tuple[Fraction, Fraction]:
    """Rationals c_k (1 -+ 2**-rel_exp), c_k to 250 digits."""
    with mpmath.workdps(260):
        cf = mpf_to_fraction(root(N, base, k, 260))
    d = Fraction(1, 2**rel_exp)
    return cf * (1 - d), cf * (1 + d)


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


def _assert_monomial_root(cp, N: int, k: int, dps: int) -> None:
    c = monomial_root(N, "excess<=0", k)
    assert cp.p_bounds[0] <= c <= cp.p_bounds[1]
    with mpmath.workdps(dps):
        assert cp.p == +c


# --------------------------------------------------------------------------- h_k and its roots
def test_log_Q_h_and_dh_against_polynomials():
    for base, w in (("eq41", "length"), ("eq41-printed", "length"), ("excess<=3", "distinct")):
        sp = parse_space(base, w)
        N = 12
        p1 = weight_poly(N, base, 1, w)
        # the helpers compute in this thread's symhx context (symhx._mpctx): set both
        with mpmath.workdps(50), mp().workdps(50):
            for k in (1, 2, 3, 5, 12):
                pk = weight_poly(N, base, k, w)
                for s in (mpmath.mpf(-1), mpmath.mpf("0.3"), mpmath.mpf(2)):
                    p = mpmath.exp(s) / N

                    def h(t, pk=pk, p1=p1, N=N):
                        pp = mpmath.exp(t) / N
                        return mpmath.log(evaluate(pk, pp)) - mpmath.log(evaluate(p1, pp))

                    assert mpmath.almosteq(crit._h_mp(sp, N, k, local(s)), h(s), 1e-45)
                    dref = mpmath.diff(h, s)
                    assert mpmath.almosteq(crit._dh_mp(sp, N, k, local(s)), dref, 1e-35)
                    # log Q*: W(k) / (p**k N!/(k (N-k)!)) up to the constant denominator D
                    phi = p**k * mpmath.mpf(math.perm(N, k)) / k
                    q = evaluate(pk, p) / phi
                    ref = mpmath.log(q * sp.denominator)
                    assert mpmath.almosteq(crit._log_Q_mp(sp, k, local(p)), ref, 1e-45)
                    fr = mpf_to_fraction(p)
                    with mpmath.workdps(80):
                        exact = mpmath.log(evaluate(pk, fr)) - mpmath.log(evaluate(p1, fr))
                    ball = crit._h_arb(sp, N, k, fr)
                    assert float(ball.rad()) < 1e-12 and ball.contains(
                        crit.to_arb(mpf_to_fraction(exact)))


def test_root_mp_against_bisection():
    for base, w, N in (("eq41", "length", 30), ("excess<=3", "distinct", 12)):
        sp = parse_space(base, w)
        rts = roots(N, base, w)
        est = root_estimates(sp, N)
        for k in (2, 7, N):
            for wp in (20, 50):
                s = crit._root_mp(sp, N, k, float(est[k - 2]) + 0.01, wp)
                with mpmath.workdps(WP):
                    ref = mpmath.log(N * rts[k])
                    assert abs(s - ref) <= mpmath.mpf(10) ** (4 - wp) * max(1, abs(ref)), (k, wp)


def test_bracket_brackets_at_the_documented_gap():
    """_bracket: exact binary rationals p (1 -+ 10**-(dps+3)) around p = e**s/N: the relative
    gap is 2e-(dps+3) (not 10x narrower), centred on p."""
    sp = parse_space("eq41")
    for dps in (10, 30):
        with mpmath.workdps(80):
            s = mpmath.mpf("-0.25")
            pf = mpf_to_fraction(mpmath.exp(s) / 40)
        lo, hi = crit._bracket(sp, 40, s, dps, 80)
        assert isinstance(lo, Fraction) and isinstance(hi, Fraction)
        assert lo < pf < hi
        gap = (hi - lo) / pf
        assert Fraction(1, 10 ** (dps + 4)) < gap < Fraction(1, 10 ** (dps + 2))
        assert abs(gap * 10 ** (dps + 3) - 2) < Fraction(1, 10**20)
        assert abs((lo + hi) / 2 - pf) < pf * Fraction(1, 10 ** (dps + 20))


# --------------------------------------------------------------------------- certified signs
def test_sign_h_exact_tie_is_zero():
    """excess<=0, N = 5: W(1) = W(2) = W(3) at p = 1/2 exactly; the Arb balls cannot decide and
    the exact comparison returns 0."""
    sp = parse_space("excess<=0")
    for k in (2, 3):
        assert weight_sign(5, "excess<=0", k, Fraction(1, 2)) == 0
        assert crit._sign_h(sp, 5, k, Fraction(1, 2), 64) == 0
    assert crit._sign_h(sp, 5, 4, Fraction(1, 2), 64) == weight_sign(
        5, "excess<=0", 4, Fraction(1, 2)) == -1


def test_sign_h_exact_fallback_beyond_eight_times_the_bits():
    """eq41, N = 12, k = 3 (c_3 < c_2): 2**-700 from c_3 the balls at up to 8 * 64 bits cannot
    decide, the exact comparison of W(3) with W(1) does, on both sides."""
    sp = parse_space("eq41")
    for fr in _near_root(12, "eq41", 3, 700):
        want = weight_sign(12, "eq41", 3, fr)
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
        assert crit._sign_h(sp, 12, 3, fr, 64) == weight_sign(12, "eq41", 3, fr) != 0
    with pytest.raises(AssertionError, match="not needed"):   # and 64 bits alone do not suffice
        crit.certified_sign(lambda: crit._h_arb(sp, 12, 3, fr), start_bits=64, max_bits=64,
                            exact_fn=lambda: no_exact())


# --------------------------------------------------------------------------- exclusion product
def test_unexcluded_is_exactly_the_non_excluded_set():
    """At generic rationals (no near ties) the running product lists exactly the k != best
    with W(k) >= W(1) (exact Fractions over all k), never best itself."""
    for base, w, N in (("eq41", "length", 30), ("excess<=3", "distinct", 20),
                       ("eq41-printed", "length", 25)):
        sp = parse_space(base, w)
        for p in (Fraction(1, 2 * N), Fraction(2, N), Fraction(1, 4), Fraction(3, 2)):
            for best in (2, 5, N):
                got = crit._unexcluded(sp, N, p, best)
                assert best not in got
                assert got == not_below_one(N, base, p, best, w), (base, N, p, best)


def test_exclusion_stop_bound_against_exhaustive():
    """The certified running product lists every k that it cannot exclude; the k it skips
    (after its stopping bound) really have W(k) < W(1): exact check over all k."""
    for space, N in (("eq41", 40), ("excess<=4", 30), ("eq41-printed", 35)):
        sp = parse_space(space)
        cp = critical_point(N, space=space, dps=20)
        for p in (Fraction(1, N), Fraction(3, 2 * N), Fraction(1, 3), Fraction(9, 10)):
            listed = set(crit._unexcluded(sp, N, p, cp.k_after))
            assert set(not_below_one(N, space, p, cp.k_after)) <= listed, (space, N, p)


def test_exclusion_with_any_best_over_a_p_grid():
    """_unexcluded with best=2 over a fine p grid: everything it skips is below W(1)."""
    for space, N in (("eq41", 40), ("excess<=4", 25)):
        sp = parse_space(space)
        for i in range(10, 80):
            p = Fraction(i, 20 * N)
            listed = set(crit._unexcluded(sp, N, p, 2))
            assert set(not_below_one(N, space, p, 2)) <= listed, (space, N, p)


def test_unexcluded_lists_exact_ties():
    """excess<=0, N = 5, p = 1/2: W(2) = W(3) = W(1) exactly, so the tied k != best is listed
    (W(k) < W(1) is false); the ball of W(2)/W(1) is exactly 1 here."""
    sp = parse_space("excess<=0")
    for best in (2, 3, 5):
        want = not_below_one(5, "excess<=0", Fraction(1, 2), best)
        assert crit._unexcluded(sp, 5, Fraction(1, 2), best) == want
        assert set(want) | {best} >= {2, 3}


def test_unexcluded_does_not_stop_while_W_still_rises():
    """excess<=0, N = 8 and 10, p a little above c_3 and best = 2: W(k)/W(1) dips below 1 and
    rises again; the stopping bound rho(k) = p (N-k)(k+m)/(k+1-R) keeps the product going."""
    sp = parse_space("excess<=0")
    for N, p in ((8, Fraction(136013, 509292)), (8, Fraction(107760, 403201)),
                 (10, Fraction(169876, 851639))):
        want = not_below_one(N, "excess<=0", p, 2)
        assert want and crit._unexcluded(sp, N, p, 2) == want


def test_unexcluded_resolves_near_ties_at_the_bits_of_p():
    """Continued-fraction convergents a/b of c_k just below it (W(k)/W(1) = 1 - O(b**-2)): the
    product's precision grows with the bits of a and b, so such a k is still excluded."""
    cases = 0
    for base, N, k in (("eq41", 12, 3), ("eq41", 30, 6), ("excess<=3", 20, 4)):
        sp = parse_space(base)
        with mpmath.workdps(120):
            c = mpf_to_fraction(root(N, base, k, 120))
        for fr in _convergents_below(c, 60, 2):
            want = not_below_one(N, base, fr, 2)
            assert k not in want
            assert crit._unexcluded(sp, N, fr, 2) == want, (base, N, fr)
            cases += 1
    assert cases == 6


# --------------------------------------------------------------------------- exact rationals
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


def test_try_rational_finds_denominators_up_to_ten_to_wp_over_3():
    """eq41;distinct: c_2 = S_1/S_2 = 8/(9(N-1)); N = 3000 gives a 5-digit denominator, found at
    wp = 18 (limit 10**6) and verified exactly; at wp = 30 a 4-digit one (N = 300)."""
    for N, wp in ((3000, 18), (300, 30)):
        sp = parse_space("eq41", "distinct")
        c2 = Fraction(sum(weight_poly(N, "eq41", 1, "distinct").values()),
                      sum(weight_poly(N, "eq41", 2, "distinct").values()))
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


def test_try_rational_refuses_a_close_rational_that_is_no_root():
    """At wp = 18 the candidate (denominator <= 10**6) of an irrational c_2 lies within the
    closeness test (10**-10 relative); only the exact comparison of W(2) with W(1) refuses it."""
    N = 2
    sp = parse_space("eq41")
    c2 = root(N, "eq41", 2)
    with mpmath.workdps(18):
        s = mpmath.log(N * c2)
        cand = mpf_to_fraction(mpmath.exp(s) / N).limit_denominator(10**6)
    with mpmath.workdps(30):
        assert abs(mpmath.mpf(cand.numerator) / cand.denominator / c2 - 1) < mpmath.mpf(10) ** -11
    assert weight_sign(N, "eq41", 2, cand) != 0
    assert crit._try_rational(sp, N, s, [2], 18) is None


# --------------------------------------------------------------------------- the loop
def test_tie_without_rational_raises(monkeypatch):
    monkeypatch.setattr(crit, "_try_rational", lambda *a: None)
    with pytest.raises(crit.UndecidedError, match=r"k in \[2, 3\] agree to 33 digits"):
        critical_point(5, space="excess<=0", dps=30)


def test_unbracketed_root_raises(monkeypatch):
    monkeypatch.setattr(crit, "_sign_h", lambda *a: 0)
    with pytest.raises(crit.UndecidedError, match=r"could not bracket c_\d+ for N=12, "
                                                  r"space=eq41"):
        critical_point(12, space="eq41", dps=15)


def test_wrong_seed_is_corrected(monkeypatch):
    """The float64 seed decides nothing: a seed whose argmin is wrong still gives the
    certified answer (the exclusion step finds the smaller root and restarts)."""
    for space, N in (("eq41", 101), ("excess<=3", 60)):
        right = critical_point(N, space=space, dps=25)
        real = crit.root_estimates

        def fake(sp, n, real=real, k=right.k_after):
            s = np.array(real(sp, n))
            s[k + 3 - 2] = s.min() - 1e-3  # pretend c_{k+3} is the smallest
            return s

        monkeypatch.setattr(crit, "root_estimates", fake)
        got = crit.critical_point(N, space=space, dps=25)
        monkeypatch.setattr(crit, "root_estimates", real)
        assert got.argmins == right.argmins and got.p_bounds == right.p_bounds


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


def test_weak_exclusion_and_a_wrong_seed_still_certify(monkeypatch):
    """The exclusion step may list more k than needed (its contract is a superset). With every
    k listed and the float seed pointing at k = 5 (c_5 between c_2 and p_c), the k with
    c_k > p_hi are skipped, not taken as the end of the list: the passes reach p_c."""
    N, base = 30, "eq41"
    argmins, pc = critical_by_bisection(N, base)
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

    def root_mp(sp, N, k, s0, wp):
        refined.append(k)
        return real_root(sp, N, k, s0, wp)

    monkeypatch.setattr(crit, "_sign_h", sign)
    monkeypatch.setattr(crit, "_root_mp", root_mp)
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
    _assert_monomial_root(cp, N, k, 20)


# --------------------------------------------------------------------------- the float64 seed
def test_root_estimates_widen_a_narrow_bracket(monkeypatch):
    """Start from a bracket (-0.01, 0.01) that misses roots on both sides: the doubling widens
    each side until it brackets, and the estimates still match the bisection roots."""
    monkeypatch.setattr(crit, "ROOT_BRACKET", 0.01)
    for base, w, N in (("eq41", "length", 12), ("excess<=3", "distinct", 30)):
        space = base if w == "length" else base + ";distinct"
        s = root_estimates(space, N)
        rts = roots(N, base, w)
        refs = [_log_Nc(N, rts[k]) for k in range(2, N + 1)]
        assert min(refs) < -0.01 or base == "eq41"
        assert max(refs) > 0.01
        for k, ref in zip(range(2, N + 1), refs, strict=True):
            assert abs(s[k - 2] - ref) <= 1e-10 * max(1.0, abs(ref)), (base, N, k)


def test_root_estimates_widen_the_lower_end(monkeypatch):
    """excess<=20 has roots below N c = 1 (log(N c_2) < 0 at N = 2, log(N c_3) < 0 at N = 3):
    from (-0.001, 0.001) the lower end is doubled until it brackets them too."""
    monkeypatch.setattr(crit, "ROOT_BRACKET", 0.001)
    for N in (2, 3):
        s = root_estimates("excess<=20", N)
        refs = {k: _log_Nc(N, c) for k, c in roots(N, "excess<=20").items()}
        assert min(refs.values()) < -0.009
        for k, ref in refs.items():
            assert abs(s[k - 2] - ref) <= 1e-14, (N, k)


def test_root_estimates_double_at_most_twenty_times(monkeypatch):
    """ROOT_BRACKET's contract: each end is doubled up to 20 times. From 2**-40 the ends stop at
    -+2**-20, short of every root (|log(N c_k)| > 0.009 here), and the iteration stays inside."""
    monkeypatch.setattr(crit, "ROOT_BRACKET", 2.0**-40)
    for N in (3, 5):
        s = root_estimates("excess<=20", N)
        for k, c in roots(N, "excess<=20").items():
            ref = _log_Nc(N, c)
            assert abs(ref) > 0.009
            assert abs(s[k - 2] - np.copysign(2.0**-20, ref)) <= 1e-12   # at the end nearest
    # from 2**-25 the twenty doublings reach 2**-5 > |log(2 c_2)| = 0.028...: the root is found
    monkeypatch.setattr(crit, "ROOT_BRACKET", 2.0**-25)
    (c2,) = roots(2, "excess<=20").values()
    assert abs(root_estimates("excess<=20", 2)[0] - _log_Nc(2, c2)) <= 1e-14


def test_root_estimates_from_bracket_ends_where_h_is_one(monkeypatch):
    """The iteration stops on a small step (or h == 0), never on any other value of h: started
    from the upper end of the bracket (the simple-space start, 1.39, is clipped to it) at 201
    consecutive floats around the point where h_2 = 1 (bisection on the Burnside polynomials;
    the float h there hits 1.0 exactly for many of them), every estimate reaches the root."""
    N = 2
    p1, p2 = weight_poly(N, "excess<=20", 1), weight_poly(N, "excess<=20", 2)
    with mpmath.workdps(40):
        def h(s):
            p = mpmath.exp(s) / N
            return mpmath.log(evaluate(p2, p)) - mpmath.log(evaluate(p1, p))

        lo, hi = mpmath.mpf(-1), mpmath.mpf(1)
        for _ in range(100):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if h(mid) < 1 else (lo, mid)
    (c2,) = roots(N, "excess<=20").values()
    rt = _log_Nc(N, c2)
    ends = float(lo) + np.arange(-100, 101) * np.spacing(float(lo))
    assert rt < ends.min() and ends.max() < 0.2
    for r in ends:
        monkeypatch.setattr(crit, "ROOT_BRACKET", float(r))
        assert abs(root_estimates("excess<=20", N)[0] - rt) <= 1e-14, r
