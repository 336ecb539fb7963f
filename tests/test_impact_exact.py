"""Reference engine on exact inputs (issue 13): rows given as decimal strings are simulated as
those exact rationals, checked against an independent high-precision event-driven solver.

The independent solver below shares nothing with ``symhx.impact.engine``: it writes each pipe as
``j d + P cos(omega (t - t_j)) + Q sin(omega (t - t_j)) + forced_j(t)`` (time measured from the
pipe's last impact), finds crossings by a dense sign scan of every gap plus ``mpmath.findroot``
(Anderson) at 60 digits, and applies Newton's law pairwise.  It handles elastic/inelastic
impacts without sticking, which is what the rows below produce.
"""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest

from symhx.impact import IMPACT, PipeRow, simulate


def _mp(s: str) -> mpmath.mpf:
    fr = Fraction(s)
    return mpmath.mpf(fr.numerator) / fr.denominator


def _bind(f, i):
    return lambda s: f(i, s)


def independent_impacts(n, omega, d, r, Omega, alpha, beta, x0, v0, t_end, *, dps=60,
                        step="0.02"):
    """Impact times and sites of the row (all inputs decimal strings), to about ``dps`` digits."""
    with mpmath.workdps(dps):
        om, dd, rr, h = _mp(omega), _mp(d), _mp(r), _mp(step)
        Om = [_mp(w) for w in Omega]
        al = [[_mp(a) for a in row] for row in alpha]
        be = [[_mp(b) for b in row] for row in beta]
        T = _mp(t_end)

        def forced(j, t):      # pipe j = 1..n: forced displacement and velocity
            x = v = mpmath.mpf(0)
            for i, w in enumerate(Om):
                den = om**2 - w**2
                c, s = mpmath.cos(w * t), mpmath.sin(w * t)
                x += (al[j - 1][i] * c + be[j - 1][i] * s) / den
                v += w * (be[j - 1][i] * c - al[j - 1][i] * s) / den
            return x, v

        state = {}   # j -> (t_j, P, Q)

        def set_state(j, t, x, v):
            fx, fv = forced(j, t)
            state[j] = (t, x - j * dd - fx, (v - fv) / om)

        def pos(j, t):
            if j == 0:
                return mpmath.mpf(0), mpmath.mpf(0)
            if j == n + 1:
                return (n + 1) * dd, mpmath.mpf(0)
            tj, P, Q = state[j]
            c, s = mpmath.cos(om * (t - tj)), mpmath.sin(om * (t - tj))
            fx, fv = forced(j, t)
            return j * dd + P * c + Q * s + fx, om * (Q * c - P * s) + fv

        for j in range(1, n + 1):
            set_state(j, mpmath.mpf(0), _mp(x0[j - 1]), _mp(v0[j - 1]))

        def gap(i, t):
            return pos(i + 1, t)[0] - pos(i, t)[0]

        out = []
        t = mpmath.mpf(0)
        last = None
        while True:
            best = None
            for i in range(n + 1):
                a = t + (h / 1000 if i == last else 0)
                ga = gap(i, a)
                assert ga > 0
                b = a
                while b < T and (best is None or b < best[0]):
                    b2 = min(b + h, T)
                    if gap(i, b2) <= 0:
                        root = mpmath.findroot(_bind(gap, i), (b, b2), solver="anderson")
                        if best is None or root < best[0]:
                            best = (root, i)
                        break
                    b = b2
            if best is None:
                return out
            t, i = best
            out.append((t, i))
            xl, vl = pos(i, t)
            xr, vr = pos(i + 1, t)
            u = vr - vl
            assert u < 0
            if i == 0:
                set_state(1, t, xr, vr - (1 + rr) * u)
            elif i == n:
                set_state(n, t, xl, vl + (1 + rr) * u)
            else:
                set_state(i, t, xl, vl + (1 + rr) * u / 2)
                set_state(i + 1, t, xr, vr - (1 + rr) * u / 2)
            last = i


ONE_PIPE = dict(n=1, omega="1.3", d="0.7", r="0.9", Omega=("0.45",), alpha=[["0.11"]],
                beta=[["-0.07"]], x0=["0.61"], v0=["1.1"], t_end="12")
THREE_PIPES = dict(n=3, omega="1.1", d="1", r="0.85", Omega=("0.3", "2.7"),
                   alpha=[["0.2", "-0.15"], ["-0.1", "0.3"], ["0.25", "0.05"]],
                   beta=[["0.05", "0.1"], ["0.3", "-0.2"], ["-0.15", "0.12"]],
                   x0=["0.9", "2.05", "3.1"], v0=["1.2", "-1.3", "0.9"], t_end="12")


def _row(p):
    return PipeRow(p["n"], omega=p["omega"], d=p["d"], restitution=p["r"], Omega=p["Omega"],
                   alpha=p["alpha"], beta=p["beta"], x0=p["x0"], v0=p["v0"])


@pytest.mark.parametrize("case", [ONE_PIPE, THREE_PIPES], ids=["one-pipe", "three-pipes"])
def test_decimal_row_matches_independent_solution(case):
    ref = independent_impacts(**case)
    assert len(ref) >= 6
    row = _row(case)
    for dps in (30, 60):
        h = simulate(row, case["t_end"], dps=dps)
        assert h.kinds.tolist() == [IMPACT] * len(ref)
        assert h.sites.tolist() == [i for _, i in ref]
        with mpmath.workdps(120):
            err = max(abs(mpmath.mpf(a) - b) for a, (b, _) in zip(h.times, ref, strict=True))
        assert err < mpmath.mpf("1e-28"), (dps, err)


def test_decimal_inputs_are_not_rounded_to_float64():
    # the same row rounded to float64 differs from the decimal row by ~1e-17: the reference
    # engine must see the difference (it answered for the rounded row before)
    row = _row(ONE_PIPE)
    fl = PipeRow(1, omega=1.3, d=0.7, restitution=0.9, Omega=(0.45,), alpha=[[0.11]],
                 beta=[[-0.07]], x0=[0.61], v0=[1.1])
    a = simulate(row, 12, dps=40).times
    b = simulate(fl, 12, dps=40).times
    with mpmath.workdps(100):
        diff = max(abs(mpmath.mpf(x) - y) for x, y in zip(a, b, strict=True))
    assert mpmath.mpf("1e-20") < diff < mpmath.mpf("1e-12")


def test_exact_values_kept():
    row = _row(THREE_PIPES)
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
