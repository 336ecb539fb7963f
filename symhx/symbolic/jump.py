"""Section 6 of the paper: the jump of the mode, eqs. (9)-(16), and the crossing condition.

Derivation chain (each step by sympy from the previous one, starting at eq. 8):

* the ratio ``Phi(k+1)/Phi(k) = p k (N-k)/(k+1)``;
* (9) ``Phi(k+1) - Phi(k) = Phi(k)/(k+1) * (k+1)(ratio - 1)`` and (10) the bracket is the quadratic
  ``f_{N,p}(k)``;
* (11) its roots (``sympy.solve``), (12)-(15) evaluations and the p-derivative;
* (16) the zeros in ``p`` of the discriminant of ``f``: the root whose repeated ``k`` is positive
  is ``p_d``; the other one (``"16-spurious"``) has its repeated root at ``k = -(1 + sqrt(N+1))``;
* ``"crossing"``: ``Phi(k)/Phi(1) = (p/c_k)**(k-1)`` with ``c_k = (k (N-k)!/(N-1)!)**(1/(k-1))``,
  so ``Phi(k) > Phi(1)`` exactly when ``p > c_k`` and the mode leaves ``k = 1`` at
  ``p_c = min_{k>=2} c_k``; ``"crossing-relaxed"`` is its continuous relaxation in ``k``.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

import sympy as sp

from symhx.symbolic._core import (
    Check,
    Derivation,
    N,
    Step,
    all_exact,
    k,
    log_equal,
    mp_lambdify,
    p,
    register,
    rhs,
    sym_equal,
)
from symhx.symbolic.simple import Phi, Phi_sym

__all__ = ["c_k", "f", "kappa", "p_d"]

f_sym = sp.Function("f_{N,p}")
kappa = sp.Symbol("kappa", positive=True)
#: helper: N = t**2 + 2 t  <=>  sqrt(N + 1) = 1 + t, t > 0 (lets sympy decide signs)
_t = sp.Symbol("t", positive=True)


def _in_t(e: sp.Expr) -> sp.Expr:
    """Rewrite ``e`` with ``N = t**2 + 2t`` (``t > 0``), so that ``sqrt(N + 1) = 1 + t``."""
    e = sp.sympify(e).subs(N, _t**2 + 2 * _t)
    e = e.replace(lambda x: x.is_Pow and x.exp == sp.S.Half,
                  lambda x: sp.sqrt(sp.factor(x.base)))
    return sp.simplify(e)

_P_GRID = (Fraction(1, 50), Fraction(1, 7), Fraction(1, 2), Fraction(3, 1))


@lru_cache(maxsize=1)
def _chain() -> dict[str, sp.Expr]:
    ratio = sp.factor(sp.gammasimp(Phi(k + 1) / Phi(k)))
    prefactor = sp.gammasimp(Phi(k) / (k + 1)).rewrite(sp.factorial)
    bracket = sp.collect(sp.expand(sp.cancel((k + 1) * (ratio - 1))), k)
    return {"ratio": ratio, "prefactor": prefactor, "f": bracket}


def f() -> sp.Expr:
    """Eq. (10): the quadratic ``f_{N,p}(k)`` whose sign is that of ``Phi(k+1) - Phi(k)``.

    >>> f()
    -k**2*p + k*(N*p - 1) - 1
    """
    return _chain()["f"]


@lru_cache(maxsize=1)
def _disc_roots() -> dict[str, sp.Expr]:
    disc = sp.discriminant(f(), k)
    roots = sp.solve(disc, p)
    info = {}
    for r in roots:
        krep = sp.radsimp((N * r - 1) / (2 * r))  # repeated root -b/(2a) of f at p = r
        sign = _in_t(krep)
        key = "pos" if sign.is_positive else ("neg" if sign.is_negative else "unknown")
        info[key] = r
        info[key + "_k"] = sp.simplify(krep)
    info["disc"] = disc
    info["n_roots"] = len(roots)
    return info


def p_d() -> sp.Expr:
    """Eq. (16): the ``p`` at which ``f`` first gets a (double) root in ``0 < k < N``.

    >>> p_d()
    (N + 2*sqrt(N + 1) + 2)/N**2
    """
    return _disc_roots()["pos"]


def c_k(kk: sp.Expr = k) -> sp.Expr:
    """Crossing value ``c_k``: ``Phi(k) = Phi(1)`` exactly at ``p = c_k``.

    >>> c_k(2).subs(N, 5)
    1/2
    """
    return _crossing()["c"].subs(k, kk)


@lru_cache(maxsize=1)
def _crossing() -> dict[str, sp.Expr]:
    ratio = sp.gammasimp(Phi(k) / Phi(1))
    sols = sp.solve(sp.Eq(ratio, 1), p)
    assert len(sols) == 1
    c = sp.powsimp(sp.gammasimp(sols[0]))
    base, ex = c.as_base_exp()
    c = sp.Pow(sp.gammasimp(base).rewrite(sp.factorial), ex)
    return {"ratio": ratio.rewrite(sp.factorial), "c": c}


# ------------------------------------------------------------------------- checks helpers
def _phi_int(n: int, kk: int) -> int:
    from symhx.circuits import phi

    return phi(n, kk)


def _diff_exact(d: Derivation) -> bool:
    e = rhs(d)
    pairs = []
    for n in range(2, 11):
        for kk in range(1, n):
            for pv in _P_GRID:
                want = _phi_int(n, kk + 1) * pv ** (kk + 1) - _phi_int(n, kk) * pv**kk
                pairs.append((e.subs({N: n, k: kk, p: sp.Rational(pv.numerator,
                                                                  pv.denominator)}), want))
    return all_exact(pairs)


def _sign_exact(d: Derivation) -> bool:
    e = rhs(d)
    for n in range(2, 15):
        for kk in range(1, n):
            for pv in (*_P_GRID, Fraction(1, n), Fraction(2, n), Fraction(4, n)):
                diff = _phi_int(n, kk + 1) * pv ** (kk + 1) - _phi_int(n, kk) * pv**kk
                val = e.subs({N: n, k: kk, p: sp.Rational(pv.numerator, pv.denominator)})
                if not val.is_Rational or sp.sign(val) != sp.sign(sp.Rational(diff.numerator,
                                                                           diff.denominator)):
                    return False
    return True


def _positive_for_0_lt_k_lt_N(e: sp.Expr) -> bool:
    m = sp.Symbol("m", positive=True)
    return bool(sp.factor(sp.expand(e.subs(N, k + m))).is_positive)


# ---------------------------------------------------------------------------- derivations
@register("9", 6, "Difference of neighbouring Phi_{N,p}: positive prefactor times a quadratic",
          r"Difference of neighbouring $\Phi_{N,p}$: a positive prefactor times a quadratic")
def _d9() -> dict:
    ch = _chain()
    derived = sp.Mul(ch["prefactor"], ch["f"], evaluate=False)
    paper = (p**k * sp.factorial(N) / (sp.factorial(N - k) * k * (k + 1))
             * (-p * k**2 + (N * p - 1) * k - 1))
    lhs = sp.Add(Phi_sym(k + 1), -Phi_sym(k), evaluate=False)
    return dict(
        result=sp.Eq(lhs, derived),
        checks=(
            Check("equals Phi(k+1) - Phi(k) from eq. (8), symbolic N, p, k", "symbolic",
                  lambda d: sym_equal(rhs(d), Phi(k + 1) - Phi(k)),
                  r"equals $\Phi(k+1) - \Phi(k)$ from eq. (8), for symbolic $N, p, k$"),
            Check("equals the paper's printed form, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), paper),
                  "equals the paper's printed form, symbolically"),
            Check("equals phi(N,k+1)p^(k+1) - phi(N,k)p^k exactly, 1 <= k < N <= 10, "
                  "p in {1/50, 1/7, 1/2, 3}", "exact", _diff_exact,
                  r"equals $\phi(N,k+1)\,p^{k+1} - \phi(N,k)\,p^k$ exactly for "
                  r"$1 \le k < N \le 10$, $p \in \{1/50, 1/7, 1/2, 3\}$"),
        ),
        steps=(Step("ratio Phi(k+1)/Phi(k)", ch["ratio"], r"The ratio $\Phi(k+1)/\Phi(k)$:"),
               Step("Phi(k+1) - Phi(k) = Phi(k)/(k+1) * (k+1)(ratio - 1)", derived,
                    r"$\Phi(k+1) - \Phi(k) = \frac{\Phi(k)}{k+1}\,(k+1)(\text{ratio} - 1)$:")),
        paper=paper,
    )


@register("10", 6, "The quadratic f_{N,p}(k) with the sign of Phi(k+1) - Phi(k)",
          r"The quadratic $f_{N,p}(k)$ with the sign of $\Phi(k+1) - \Phi(k)$")
def _d10() -> dict:
    paper = -p * k**2 + (N * p - 1) * k - 1
    return dict(
        result=sp.Eq(f_sym(k), f()),
        checks=(
            Check("equals the paper's -p k^2 + (Np-1)k - 1, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), paper),
                  r"equals the paper's $-p k^2 + (Np-1)k - 1$, symbolically"),
            Check("(k+1) * (Phi(k+1)/Phi(k) - 1) from eq. (8), symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), (k + 1) * (Phi(k + 1) / Phi(k) - 1)),
                  r"equals $(k+1)\,\bigl(\Phi(k+1)/\Phi(k) - 1\bigr)$ from eq. (8), "
                  "symbolically"),
            Check("sign equals sign of Phi(k+1) - Phi(k), exact, 1 <= k < N <= 14, 7 p each",
                  "exact", _sign_exact,
                  r"its sign is the sign of $\Phi(k+1) - \Phi(k)$, exactly, for "
                  r"$1 \le k < N \le 14$ and 7 values of $p$ each"),
        ),
        paper=paper,
    )


def _roots() -> tuple[sp.Expr, sp.Expr]:
    r = sp.solve(f(), k)
    assert len(r) == 2
    # order: k_- < k_+ wherever both are real (they never cross there); decide at one point
    at = {N: 100, p: sp.Rational(1, 2)}
    r = sorted(r, key=lambda e: float(e.subs(at)))
    return r[0], r[1]


@register("11", 6, "Roots k_- <= k_+ of f_{N,p}: turning points of Phi_{N,p}",
          r"Roots $k_- \le k_+$ of $f_{N,p}$: the turning points of $\Phi_{N,p}$")
def _d11() -> dict:
    km, kp = _roots()
    disc = (N * p - 1) ** 2 - 4 * p
    paper = (((N * p - 1) - sp.sqrt(disc)) / (2 * p), ((N * p - 1) + sp.sqrt(disc)) / (2 * p))
    kms, kps = sp.symbols("k_- k_+")

    def roots_of_f(d: Derivation) -> bool:
        a, b = rhs(d)
        return all(sp.expand(f().subs(k, r)) == 0 for r in (a, b))

    def vs_paper(d: Derivation) -> bool:
        a, b = rhs(d)
        return sym_equal(a, paper[0]) and sym_equal(b, paper[1])

    def vieta(d: Derivation) -> bool:
        a, b = rhs(d)
        return sym_equal(a + b, (N * p - 1) / p) and sym_equal(sp.expand(a * b), 1 / p)

    return dict(
        result=sp.Eq(sp.Tuple(kms, kps), sp.Tuple(km, kp)),
        checks=(
            Check("both are zeros of f (eq. 10), symbolic", "symbolic", roots_of_f,
                  "both are zeros of $f$ (eq. 10), symbolically"),
            Check("equal the paper's [(Np-1) -+ sqrt((Np-1)^2 - 4p)]/(2p), symbolic", "symbolic",
                  vs_paper, r"equal the paper's "
                  r"$\bigl[(Np-1) \mp \sqrt{(Np-1)^2 - 4p}\bigr]/(2p)$, symbolically"),
            Check("Vieta: sum (Np-1)/p, product 1/p, symbolic", "symbolic", vieta,
                  r"Vieta: sum $(Np-1)/p$, product $1/p$, symbolically"),
        ),
        paper=sp.Tuple(*paper),
    )


def _simple_eval(lhs: sp.Expr, derived: sp.Expr, definition: sp.Expr, paper: sp.Expr,
                 extra_checks: tuple[Check, ...] = ()) -> dict:
    return dict(
        result=sp.Eq(lhs, derived),
        checks=(
            Check("equals eq. (10) evaluated, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), definition),
                  "equals eq. (10) evaluated there, symbolically"),
            Check(f"equals the paper's {sp.sstr(paper)}, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), paper),
                  f"equals the paper's ${sp.latex(paper)}$, symbolically"),
            *extra_checks,
        ),
        paper=paper,
    )


@register("12", 6, "f_{N,p} at k = 0", r"$f_{N,p}$ at $k = 0$")
def _d12() -> dict:
    return _simple_eval(f_sym(0), sp.expand(f().subs(k, 0)), f().subs(k, 0), sp.Integer(-1))


@register("13", 6, "f_{N,p} at k = N", r"$f_{N,p}$ at $k = N$")
def _d13() -> dict:
    return _simple_eval(f_sym(N), sp.factor(f().subs(k, N)), f().subs(k, N), -(N + 1))


@register("14", 6, "f_{N,0}(k) (no impacts): negative for every k > 0",
          r"$f_{N,0}(k)$ (no impacts): negative for every $k > 0$")
def _d14() -> dict:
    return _simple_eval(
        sp.Function("f_{N,0}")(k), sp.factor(f().subs(p, 0)), f().subs(p, 0), -(k + 1),
        (Check("negative for k > 0 (sympy assumptions)", "symbolic",
               lambda d: bool(rhs(d).is_negative), r"negative for $k > 0$ (sympy assumptions)"),))


@register("15", 6, "Derivative of f_{N,p}(k) in p: positive for 0 < k < N",
          r"Derivative of $f_{N,p}(k)$ in $p$: positive for $0 < k < N$")
def _d15() -> dict:
    fx = f()
    dfdp = sp.factor(sp.diff(fx, p))
    dfdp = sp.Mul(k, sp.expand(dfdp / k))  # display as k (N - k)
    return _simple_eval(
        sp.Derivative(f_sym(k), p), dfdp, sp.diff(fx, p), k * (N - k),
        (Check("positive for 0 < k < N (N = k + m, m > 0)", "symbolic",
               lambda d: _positive_for_0_lt_k_lt_N(rhs(d)),
               r"positive for $0 < k < N$ (with $N = k + m$, $m > 0$)"),))


@register("16", 6, "p_d: the discriminant of f vanishes, double root of f inside 0 < k < N",
          r"$p_d$: the discriminant of $f$ vanishes, with the double root of $f$ inside "
          r"$0 < k < N$")
def _d16() -> dict:
    info = _disc_roots()
    disc = info["disc"]
    paper = ((1 + sp.sqrt(N + 1)) / N) ** 2

    def disc_zero(d: Derivation) -> bool:
        return sp.simplify(sp.expand(disc.subs(p, rhs(d)))) == 0

    def repeated_root_inside(d: Derivation) -> bool:
        r = rhs(d)
        krep = _in_t((N * r - 1) / (2 * r))
        n_t = _t**2 + 2 * _t
        return bool(krep.is_positive) and bool(sp.factor(n_t - krep).is_positive)

    def both_roots(d: Derivation) -> bool:
        got = {sp.simplify(r - rhs(d)) == 0 for r in sp.solve(disc, p)}
        return info["n_roots"] == 2 and got == {True, False}

    return dict(
        result=sp.Eq(sp.Symbol("p_d"), p_d()),
        checks=(
            Check("the discriminant of f in k vanishes there, symbolic", "symbolic", disc_zero,
                  r"the discriminant of $f$ in $k$ vanishes there, symbolically"),
            Check("equals the paper's ((1 + sqrt(N+1))/N)^2, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), paper),
                  r"equals the paper's $\bigl((1 + \sqrt{N+1})/N\bigr)^2$, symbolically"),
            Check("its double root k = -b/(2a) lies in (0, N) for every N > 0, symbolic",
                  "symbolic", repeated_root_inside,
                  r"its double root $k = -b/(2a)$ lies in $(0, N)$ for every $N > 0$, "
                  "symbolically"),
            Check("it is one of exactly two zeros of the discriminant, symbolic", "symbolic",
                  both_roots, "it is one of exactly two zeros of the discriminant, symbolically"),
        ),
        steps=(Step("discriminant of f in k", disc, r"The discriminant of $f$ in $k$:"),
               Step("zeros in p", sp.Tuple(info["pos"], info["neg"]), r"Its zeros in $p$:")),
        paper=paper,
    )


@register("16-spurious", 6, "The other zero of the discriminant: its double root has k < 0",
          r"The other zero of the discriminant: its double root has $k < 0$")
def _d16_spurious() -> dict:
    info = _disc_roots()
    disc = info["disc"]

    def spurious_disc_zero(d: Derivation) -> bool:
        pr, _ = rhs(d)
        return sp.simplify(sp.expand(disc.subs(p, pr))) == 0

    def spurious_negative(d: Derivation) -> bool:
        pr, kr = rhs(d)
        krep = _in_t((N * pr - 1) / (2 * pr))
        return sp.simplify(krep - _in_t(kr)) == 0 and bool(krep.is_negative)

    return dict(
        result=sp.Eq(sp.Tuple(sp.Symbol("p_s"), sp.Symbol("k_s")),
                     sp.Tuple(info["neg"], info["neg_k"])),
        checks=(
            Check("the discriminant vanishes at p_s, symbolic", "symbolic", spurious_disc_zero,
                  r"the discriminant vanishes at $p_s$, symbolically"),
            Check("k_s is the double root there and is negative for every N > 0, symbolic",
                  "symbolic", spurious_negative,
                  r"$k_s$ is the double root there and is negative for every $N > 0$, "
                  "symbolically"),
            Check("equals ((1 - sqrt(N+1))/N)^2, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d)[0], ((1 - sp.sqrt(N + 1)) / N) ** 2),
                  r"equals $\bigl((1 - \sqrt{N+1})/N\bigr)^2$, symbolically"),
        ),
        paper=((1 - sp.sqrt(N + 1)) / N) ** 2,
    )


@register("16-k", 6, "Where the double root of f appears at p = p_d: k_d = sqrt(N+1) - 1",
          r"Where the double root of $f$ appears at $p = p_d$: $k_d = \sqrt{N+1} - 1$")
def _d16_k() -> dict:
    info = _disc_roots()

    def kd_double(d: Derivation) -> bool:
        kd = rhs(d)
        fx = f().subs(p, p_d())
        return (sp.simplify(sp.expand(fx.subs(k, kd))) == 0
                and sp.simplify(sp.expand(sp.diff(fx, k).subs(k, kd))) == 0)

    return dict(
        result=sp.Eq(sp.Symbol("k_d"), info["pos_k"]),
        checks=(
            Check("f and df/dk vanish at (k_d, p_d), symbolic", "symbolic", kd_double,
                  r"$f$ and $\partial f/\partial k$ vanish at $(k_d, p_d)$, symbolically"),
            Check("0 < k_d < N for N > 0, symbolic", "symbolic", lambda d: (
                bool(sp.factor(_in_t(rhs(d))).is_positive)
                and bool(sp.factor(_in_t(N - rhs(d))).is_positive)),
                r"$0 < k_d < N$ for $N > 0$, symbolically"),
        ),
    )


@register("crossing", 6, "Crossing condition of the jump: Phi(k) = Phi(1) exactly at p = c_k",
          r"Crossing condition of the jump: $\Phi(k) = \Phi(1)$ exactly at $p = c_k$")
def _d_crossing() -> dict:
    cr = _crossing()
    c = cr["c"]

    def back_subst(d: Derivation) -> bool:
        val = cr["ratio"].subs(p, rhs(d))
        return log_equal(val, 1)  # all factors positive for 2 <= k <= N

    def exact(d: Derivation) -> bool:
        e = rhs(d)
        for n in range(2, 26):
            for kk in range(2, n + 1):
                ck_pow = sp.simplify(e.subs({N: n, k: kk}) ** (kk - 1))
                if not ck_pow.is_Rational:
                    return False
                # Phi(k)/Phi(1) at p with p**(k-1) = ck_pow
                ratio = Fraction(_phi_int(n, kk), n) * Fraction(int(ck_pow.p), int(ck_pow.q))
                if ratio != 1:
                    return False
        return True

    paper = (k * sp.factorial(N - k) / sp.factorial(N - 1)) ** (1 / (k - 1))
    return dict(
        result=sp.Eq(sp.Symbol("c_k"), c),
        checks=(
            Check("Phi(k)/Phi(1) = 1 at p = c_k, symbolic (positive base, 2 <= k <= N)",
                  "symbolic", back_subst,
                  r"$\Phi(k)/\Phi(1) = 1$ at $p = c_k$, symbolically (positive base, "
                  r"$2 \le k \le N$)"),
            Check("equals (k (N-k)!/(N-1)!)^(1/(k-1)), symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), paper),
                  r"equals $\bigl(k\,(N-k)!/(N-1)!\bigr)^{1/(k-1)}$, symbolically"),
            Check("c_k^(k-1) * phi(N,k)/phi(N,1) == 1 exactly, 2 <= k <= N <= 25", "exact",
                  exact, r"$c_k^{k-1}\,\phi(N,k)/\phi(N,1) = 1$ exactly for "
                  r"$2 \le k \le N \le 25$"),
        ),
        steps=(Step("Phi(k)/Phi(1) from eq. (8)", cr["ratio"],
                    r"$\Phi(k)/\Phi(1)$ from eq. (8):"),
               Step("solve = 1 for p", c, r"Solved for $p$ where it equals 1:")),
        paper=paper,
    )


@register("crossing-ratio", 6, "Phi(k)/Phi(1) = (p/c_k)^(k-1): the mode leaves k = 1 at "
          "p_c = min_{k>=2} c_k", r"$\Phi(k)/\Phi(1) = (p/c_k)^{k-1}$: the mode leaves $k = 1$ "
          r"at $p_c = \min_{k\ge 2} c_k$")
def _d_crossing_ratio() -> dict:
    cr = _crossing()
    c_s = sp.Symbol("c_k")

    def ratio_identity(d: Derivation) -> bool:
        return log_equal(rhs(d).subs(c_s, cr["c"]), cr["ratio"])  # both sides positive

    return dict(
        result=sp.Eq(Phi_sym(k) / Phi_sym(1), (p / c_s) ** (k - 1)),
        checks=(Check("equals Phi(k)/Phi(1) from eq. (8) with c_k of 'crossing', symbolic",
                      "symbolic", ratio_identity,
                      r"equals $\Phi(k)/\Phi(1)$ from eq. (8) with the $c_k$ of `crossing`, "
                      "symbolically"),),
    )


@lru_cache(maxsize=1)
def _relaxed() -> tuple[sp.Expr, sp.Expr]:
    """log(N c_kappa) with factorials -> Gamma (expanded in loggamma) and its stationarity
    condition (kappa - 1)^2 d/dkappa = 0."""
    c = _crossing()["c"]
    relaxed = sp.expand_log(sp.log(N * c.rewrite(sp.gamma).subs(k, kappa)), force=True)
    relaxed = sp.expand(sp.expand_log(relaxed.rewrite(sp.loggamma), force=True))
    relaxed = sp.collect(relaxed, 1 / (kappa - 1))
    stationary = sp.simplify(sp.diff(relaxed, kappa) * (kappa - 1) ** 2)
    return relaxed, stationary


@register("crossing-relaxed", 6, "Continuous relaxation of log(N c_k) in k (factorials -> "
          "Gamma) and its stationarity condition",
          r"Continuous relaxation of $\log(N c_k)$ in $k$ (factorials $\to$ $\Gamma$) and its "
          "stationarity condition")
def _d_crossing_relaxed() -> dict:
    relaxed, stationary = _relaxed()
    lhs = sp.log(N * sp.Function("c")(kappa))

    def relaxed_integer(d: Derivation) -> bool:
        from symhx.circuits import phi

        e = rhs(d)
        for n in range(3, 30, 3):
            for kk in range(2, n + 1):
                val = sp.simplify(sp.exp(sp.expand((kk - 1) * e.subs({N: n, kappa: kk}))))
                want = Fraction(n ** (kk - 1) * n, phi(n, kk))  # (N c_k)^(k-1)
                if not all_exact([(val, want)]):
                    return False
        return True

    def stationary_numeric(d: Derivation) -> bool:
        from symhx._mpctx import mp

        e = rhs(d)
        n = 1000
        fun = mp_lambdify(kappa, e.subs(N, n))
        dfun = mp_lambdify(kappa, sp.diff(e, kappa).subs(N, n))
        st = mp_lambdify(kappa, d.extra["stationary"].lhs.subs(N, n))
        ctx = mp()
        with ctx.workdps(40):
            root = ctx.findroot(dfun, (40, 200), solver="anderson")
            # golden-section minimum of the relaxed function, independent of the derivative
            a, b = ctx.mpf(40), ctx.mpf(200)
            g = (ctx.sqrt(5) - 1) / 2
            for _ in range(150):
                x1, x2 = b - g * (b - a), a + g * (b - a)
                if fun(x1) < fun(x2):
                    b = x2
                else:
                    a = x1
            return bool(abs(root - a) < ctx.mpf(10) ** -12
                        and abs(st(root)) < ctx.mpf(10) ** -30)

    return dict(
        result=sp.Eq(lhs, relaxed),
        checks=(
            Check("exp((k-1) * value) == (N c_k)^(k-1) exactly at integer k, N = 3..27",
                  "exact", relaxed_integer,
                  r"$\exp\bigl((k-1)\cdot\text{value}\bigr) = (N c_k)^{k-1}$ exactly at integer "
                  r"$k$, $N = 3, 6, \dots, 27$"),
            Check("the stationarity condition's root is the relaxed minimum (N = 1000, "
                  "40 digits, golden section)", "numeric", stationary_numeric,
                  r"the root of the stationarity condition is the relaxed minimum "
                  r"($N = 1000$, 40 digits, golden-section search)"),
        ),
        extra={"stationary": sp.Eq(stationary, 0)},
    )
