"""Large-N derivations: the series of ``p_d`` in ``N**(-1/2)``, the expansion of ``log(N c_k)``
for ``k << N`` and the Lambert-W minimiser of its leading part.

These feed :mod:`symhx.asymptotics` (which is mpmath-only and never imports sympy): the
coefficients of :func:`pd_series` are checked there against closed-form binomial coefficients.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from symhx.symbolic._core import Check, Derivation, N, Step, k, mp_lambdify, register, rhs
from symhx.symbolic.jump import p_d

__all__ = ["log_Nc_expansion", "pd_series", "pd_series_coefficients"]

eps = sp.Symbol("epsilon", positive=True)  # eps = N**(-1/2)
_K = sp.Symbol("K", positive=True, integer=True)
_i = sp.Symbol("i", positive=True, integer=True)


@lru_cache(maxsize=8)
def pd_series_coefficients(n_terms: int = 6) -> tuple[tuple[int, sp.Rational], ...]:
    """The first ``n_terms`` non-zero terms of ``p_d`` as ``((power of eps, coefficient), ...)``
    with ``eps = N**(-1/2)``: ``p_d = sum c * eps**power``.

    >>> pd_series_coefficients(5)
    ((2, 1), (3, 2), (4, 2), (5, 1), (7, -1/4))
    """
    e = p_d().subs(N, eps**-2)
    order = 2 * n_terms + 4
    while True:
        s = sp.series(e, eps, 0, order).removeO()
        terms = sorted(sp.Poly(s, eps).terms(), key=lambda t: t[0][0])
        terms = [(t[0][0], sp.Rational(t[1])) for t in terms if t[1] != 0]
        if len(terms) >= n_terms + 1:  # one more than asked, so the last one is complete
            return tuple(terms[:n_terms])
        order += 4


def pd_series(n_terms: int = 5) -> sp.Expr:
    """``p_d`` (eq. 16) as a series in ``N**(-1/2)``, first ``n_terms`` non-zero terms.

    >>> pd_series(5)
    1/N + 2/N**2 + 2/N**(3/2) + N**(-5/2) - 1/(4*N**(7/2))
    """
    return sum(c * N ** sp.Rational(-pw, 2) for pw, c in pd_series_coefficients(n_terms))


def log_Nc_expansion(order: int = 3) -> sp.Expr:
    """``log(N c_k)`` for ``k << N``: ``log k/(k-1) + sum_{m<=order} S_m(k-1)/(m (k-1) N**m)``
    with ``S_m(K) = sum_{i<=K} i**m`` (from ``-log(1 - i/N) = sum_m (i/N)**m / m``).

    >>> log_Nc_expansion(1)
    log(k)/(k - 1) + k/(2*N)
    """
    tail = 0
    for m in range(1, order + 1):
        tail += sp.factor((sp.Sum(_i**m, (_i, 1, _K)).doit() / (m * _K * N**m)).subs(_K, k - 1))
    return sp.log(k) / (k - 1) + tail


@lru_cache(maxsize=1)
def _lambert() -> dict[str, sp.Expr]:
    h0 = sp.log(k) / k + k / (2 * N)  # leading part of log(N c_k) for 1 << k << N
    sols = sp.solve(sp.diff(h0, k), k)  # sympy returns the principal branch (local max near e)
    assert len(sols) == 1
    k0 = sols[0].replace(sp.LambertW, lambda x: sp.LambertW(x, -1))  # the minimiser
    return {"h0": h0, "k0_principal": sols[0], "k0": k0, "q0": 1 / k0 + k0 / N}


@register("16-series", 6, "p_d as a series in N^(-1/2), five terms; the error is below the first "
          "omitted term, (1/8) N^(-9/2), for every N >= 1 (alternating binomial series)",
          r"$p_d$ as a series in $N^{-1/2}$, five terms; the error is below the first omitted "
          r"term, $\tfrac18 N^{-9/2}$, for every $N \ge 1$ (an alternating binomial series)")
def _d_series() -> dict:
    from symhx._mpctx import mp

    def series_limit(d: Derivation) -> bool:
        s = rhs(d).removeO() if isinstance(rhs(d), sp.Add) else rhs(d)
        s = sp.sympify(s).subs(N, eps**-2)
        rem = sp.expand(p_d().subs(N, eps**-2) - s)
        nxt = pd_series_coefficients(7)[5]  # the sixth term: eps**9 * 1/8
        return bool(sp.limit(rem / eps ** nxt[0], eps, 0) == nxt[1])

    def series_numeric(d: Derivation) -> bool:
        s = mp_lambdify(N, rhs(d))
        ex = mp_lambdify(N, p_d())
        nxt_pw, nxt_c = pd_series_coefficients(7)[5]
        ctx = mp()
        with ctx.workdps(80):
            for n in (10**3, 10**6, 10**10):
                nn = ctx.mpf(n)
                err = abs(ex(nn) - s(nn))
                bound = abs(nxt_c) * nn ** (-ctx.mpf(nxt_pw) / 2)
                if not (bound / 2 < err <= bound):
                    return False
        return True

    return dict(
        result=sp.Eq(sp.Symbol("p_d"), pd_series(5)),
        checks=(
            Check("(p_d - series) / N^(-9/2) -> 1/8 as N -> oo, symbolic limit", "symbolic",
                  series_limit, r"$(p_d - \text{series})/N^{-9/2} \to 1/8$ as $N \to \infty$ "
                  "(a symbolic limit)"),
            Check("error lies in (T/2, T] with T = N^(-9/2)/8 at N = 1e3, 1e6, 1e10 "
                  "(80 digits)", "numeric", series_numeric,
                  r"the error lies in $(T/2, T]$ with $T = N^{-9/2}/8$ at $N = 10^3, 10^6, "
                  r"10^{10}$ (80 digits)"),
        ),
    )


@register("log-Nc-expansion", 6, "log(N c_k) for k << N: log k/(k-1) + k/(2N) + O(k^2/N^2)",
          r"$\log(N c_k)$ for $k \ll N$: $\log k/(k-1) + k/(2N) + O(k^2/N^2)$")
def _d_expansion() -> dict:
    from symhx._mpctx import mp

    def expansion_numeric(d: Derivation) -> bool:
        e = mp_lambdify((N, k), rhs(d))
        ctx = mp()
        with ctx.workdps(50):
            for n, kk in ((10**4, 50), (10**6, 400), (10**8, 3000)):
                exact = (ctx.log(kk) + ctx.loggamma(n - kk + 1)
                         - ctx.loggamma(n)) / (kk - 1) + ctx.log(n)
                err = abs(e(n, kk) - exact)
                nxt = ctx.mpf(kk) ** 4 / (4 * 5 * ctx.mpf(n) ** 4)  # next term ~ K^4/(20 N^4)
                # two-sided: the error is the next term's size (a result of another order,
                # more precise or less, fails)
                if not nxt / 2 < err < 2 * nxt:
                    return False
        return True

    return dict(
        result=sp.Eq(sp.log(N * sp.Symbol("c_k")), log_Nc_expansion(3)),
        checks=(Check("differs from log-gamma by the next term's size (within a factor 2) at "
                      "(N, k) = (1e4, 50), (1e6, 400), (1e8, 3000), 50 digits", "numeric",
                      expansion_numeric,
                      r"differs from $\log\Gamma$ by the next term's size (within a factor 2) "
                      r"at $(N, k) = (10^4, 50)$, $(10^6, 400)$, $(10^8, 3000)$, 50 digits"),),
    )


@register("pc-lambert", 6, "Minimiser of the leading part log k/k + k/(2N) of log(N c_k): "
          "k_0 = exp(1 - W_{-1}(-e^2/N)/2) ~ sqrt(N ln N), minimum 1/k_0 + k_0/N ~ sqrt(ln N/N)",
          r"Minimiser of the leading part $\log k/k + k/(2N)$ of $\log(N c_k)$: "
          r"$k_0 = \exp\bigl(1 - W_{-1}(-e^2/N)/2\bigr) \sim \sqrt{N \ln N}$, with minimum "
          r"$1/k_0 + k_0/N \sim \sqrt{\ln N/N}$")
def _d_lambert() -> dict:
    from symhx._mpctx import mp

    lam = _lambert()

    def lambert_numeric(d: Derivation) -> bool:
        k0e, q0e = rhs(d)
        h0 = lam["h0"]
        dh = mp_lambdify((N, k), sp.diff(h0, k))
        d2h = mp_lambdify((N, k), sp.diff(h0, k, 2))
        fk = mp_lambdify(N, k0e)
        fq = mp_lambdify(N, q0e)
        hf = mp_lambdify((N, k), h0)
        ctx = mp()
        with ctx.workdps(50):
            for n in (10**3, 10**6, 10**20):
                nn = ctx.mpf(n)
                kk = fk(nn)
                if abs(ctx.im(kk)) > 0 or abs(dh(nn, kk)) > ctx.mpf(10) ** -45 / kk:
                    return False
                if not d2h(nn, kk) > 0 or abs(fq(nn) - hf(nn, kk)) > ctx.mpf(10) ** -45:
                    return False
        return True

    return dict(
        result=sp.Eq(sp.Tuple(sp.Symbol("k_0"), sp.Symbol("q_0")), sp.Tuple(lam["k0"], lam["q0"])),
        checks=(Check("k_0 is a stationary point and a minimum of the leading part, q_0 its "
                      "value, N = 1e3, 1e6, 1e20 (50 digits)", "numeric", lambert_numeric,
                      r"$k_0$ is a stationary point and a minimum of the leading part and $q_0$ "
                      r"its value, at $N = 10^3, 10^6, 10^{20}$ (50 digits)"),),
        steps=(Step("leading part of log(N c_k)", lam["h0"],
                    r"The leading part of $\log(N c_k)$:"),
               Step("sympy.solve (principal branch: the local maximum near k = e)",
                    lam["k0_principal"], r"`sympy.solve` of its derivative (the principal branch "
                    r"$W_0$: the local *maximum* near $k = e$):"),
               Step("the minimiser is on the branch W_{-1}", lam["k0"],
                    r"The minimiser is on the branch $W_{-1}$:")),
    )
