"""Sections 3-5 of the paper: simple circuits and their distribution, eqs. (4)-(8).

Everything is derived from the definitions:

* (4) a simple closed path of length ``k`` through a fixed vertex is the fixed vertex followed by
  ``k - 1`` further *distinct* vertices: the product ``(N-1)(N-2)...(N-(k-1))``, which sympy
  evaluates as a rising factorial and rewrites with factorials;
* (5) ``N`` choices of the starting vertex, each circuit counted ``k`` times (once per rotation);
* (6) the ratio of (5) at ``k`` and at ``N``;
* (7)-(8) weights ``p**k`` (independent impacts) normalised over the simple circuits.
"""

from __future__ import annotations

import itertools
import math
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
    p,
    register,
    rhs,
    sym_equal,
)

__all__ = ["Gamma_sym", "Phi", "Phi_sym", "paths", "phi", "phi_sym"]

m = sp.Symbol("m", integer=True, positive=True)
j = sp.Symbol("j", integer=True, positive=True)

#: Display symbols for the left-hand sides.
P_sym = sp.Function("P_{N}")
phi_sym = sp.Function(r"\phi_{N}")
Phi_sym = sp.Function(r"\Phi_{N,p}")
Gamma_sym = sp.Symbol(r"\Gamma_{N,p}")
PX_sym = sp.Symbol(r"P(X=k)")


@lru_cache(maxsize=1)
def _paths_steps() -> tuple[Step, ...]:
    prod = sp.Product(N - m, (m, 1, k - 1))
    # re-index m -> N - m: the product of the integers N-k+1, ..., N-1
    reindexed = sp.Product(m, (m, N - k + 1, N - 1))
    evaluated = reindexed.doit()  # RisingFactorial(N - k + 1, k - 1)
    as_fact = sp.gammasimp(evaluated.rewrite(sp.gamma))
    as_fact = sp.piecewise_fold(as_fact)
    if isinstance(as_fact, sp.Piecewise):  # branch valid for N - k > -1, i.e. 1 <= k <= N
        as_fact = as_fact.args[0].expr
    as_fact = as_fact.rewrite(sp.factorial)
    return (
        Step("choose k-1 further distinct vertices", prod,
             r"Choose the $k - 1$ further vertices, in order, all distinct:"),
        Step("re-index m -> N - m", reindexed, r"Re-index $m \to N - m$:"),
        Step("evaluate", evaluated, "Evaluate the product:"),
        Step("as factorials (1 <= k <= N)", as_fact, r"As factorials ($1 \le k \le N$):"),
    )


def paths() -> sp.Expr:
    """Eq. (4): number of simple closed paths of length ``k`` through a given vertex.

    >>> paths()
    factorial(N - 1)/factorial(N - k)
    """
    return _paths_steps()[-1][1]


def phi(kk: sp.Expr = k) -> sp.Expr:
    """Eq. (5): ``phi_N(kk)``, derived as ``N * paths / k`` (``N`` starts, ``k`` rotations).

    >>> phi()
    factorial(N)/(k*factorial(N - k))
    >>> phi(3).subs(N, 5)
    20
    """
    return _phi().subs(k, kk)


@lru_cache(maxsize=1)
def _phi() -> sp.Expr:
    return sp.gammasimp(N * paths() / k).rewrite(sp.factorial)


def Phi(kk: sp.Expr = k) -> sp.Expr:
    """Eq. (8), numerator: ``Phi_{N,p}(kk) = p**kk * phi_N(kk)``.

    >>> Phi(2)
    p**2*factorial(N)/(2*factorial(N - 2))
    """
    return p**kk * phi(kk)


def _perm_count(n: int, r: int) -> int:
    """Brute force: ordered selections of ``r`` distinct items from ``n`` (itertools)."""
    return sum(1 for _ in itertools.permutations(range(n), r))


def _brute_simple(n: int, length: int) -> int:
    from symhx.circuits import enumerate_circuits

    return sum(1 for c in enumerate_circuits(n, length) if len(set(c)) == length)


# ----------------------------------------------------------------------------- builders
@register("4", 3, "Simple closed paths of length k through a fixed vertex of the complete digraph",
          r"Simple closed paths of length $k$ through a fixed vertex of the complete digraph")
def _d4() -> dict:
    paper = sp.factorial(N - 1) / sp.factorial(N - k)

    def sym(d: Derivation) -> bool:
        return sym_equal(rhs(d), paper)

    def exact(d: Derivation) -> bool:
        e = rhs(d)
        return all_exact(
            (e.subs({N: n, k: kk}), math.perm(n - 1, kk - 1))
            for n in range(1, 13) for kk in range(1, n + 1)
        )

    def brute(d: Derivation) -> bool:
        e = rhs(d)
        return all_exact((e.subs({N: n, k: kk}), _perm_count(n - 1, kk - 1))
                         for n in range(1, 7) for kk in range(1, n + 1))

    return dict(
        result=sp.Eq(P_sym(k), paths()),
        checks=(
            Check("equals the paper's (N-1)!/(N-k)! for symbolic N, k", "symbolic", sym,
                  r"equals the paper's $(N-1)!/(N-k)!$ for symbolic $N, k$"),
            Check("equals math.perm(N-1, k-1) for 1 <= k <= N <= 12", "exact", exact,
                  r"equals `math.perm(N-1, k-1)` for $1 \le k \le N \le 12$"),
            Check("equals an itertools enumeration of paths for N <= 6", "exact", brute,
                  r"equals an `itertools` enumeration of the paths for $N \le 6$"),
        ),
        steps=_paths_steps(), paper=paper,
    )


@register("5", 3, "Number of simple circuits of length k, phi_N(k)",
          r"Number of simple circuits of length $k$, $\phi_N(k)$")
def _d5() -> dict:
    paper = sp.factorial(N) / (k * sp.factorial(N - k))

    def exact(d: Derivation) -> bool:
        from symhx.circuits import phi as phi_int

        e = rhs(d)
        return all_exact((e.subs({N: n, k: kk}), phi_int(n, kk))
                         for n in range(1, 16) for kk in range(1, n + 1))

    def brute(d: Derivation) -> bool:
        e = rhs(d)
        return all_exact((e.subs({N: n, k: kk}), _brute_simple(n, kk))
                         for n in range(1, 6) for kk in range(1, n + 1))

    return dict(
        result=sp.Eq(phi_sym(k), phi()),
        checks=(
            Check("equals the paper's N!/(k (N-k)!) for symbolic N, k", "symbolic",
                  lambda d: sym_equal(rhs(d), paper),
                  r"equals the paper's $N!/(k\,(N-k)!)$ for symbolic $N, k$"),
            Check("equals symhx.circuits.phi for 1 <= k <= N <= 15", "exact", exact,
                  r"equals `symhx.circuits.phi` for $1 \le k \le N \le 15$"),
            Check("equals brute-force circuit enumeration (FKM) for N <= 5", "exact", brute,
                  r"equals brute-force circuit enumeration (FKM) for $N \le 5$"),
        ),
        steps=(Step("N starting vertices times eq. (4), each circuit counted k times",
                    N * sp.Symbol("P_N(k)") / k,
                    r"$N$ starting vertices times eq. (4), each circuit counted $k$ times:"),
               Step("", phi())),
        paper=paper,
    )


@register("6", 3, "Ratio phi_N(k) / phi_N(N): all but the longest circuits are rare",
          r"Ratio $\phi_N(k)/\phi_N(N)$: all but the longest circuits are rare")
def _d6() -> dict:
    derived = sp.gammasimp(phi() / phi(N)).rewrite(sp.factorial)
    paper = N / (k * sp.factorial(N - k))

    def exact(d: Derivation) -> bool:
        from symhx.circuits import phi as phi_int

        e = rhs(d)
        return all_exact((e.subs({N: n, k: kk}), Fraction(phi_int(n, kk), phi_int(n, n)))
                         for n in range(1, 16) for kk in range(1, n + 1))

    return dict(
        result=sp.Eq(phi_sym(k) / phi_sym(N), derived),
        checks=(
            Check("equals the paper's N/(k (N-k)!) for symbolic N, k", "symbolic",
                  lambda d: sym_equal(rhs(d), paper),
                  r"equals the paper's $N/(k\,(N-k)!)$ for symbolic $N, k$"),
            Check("equals phi(N,k)/phi(N,N) (exact Fractions) for 1 <= k <= N <= 15", "exact",
                  exact, r"equals $\phi(N,k)/\phi(N,N)$ (exact fractions) for "
                  r"$1 \le k \le N \le 15$"),
        ),
        steps=(Step("ratio of eq. (5) at k and at N", phi() / phi(N),
                    r"The ratio of eq. (5) at $k$ and at $N$:"),
               Step("simplified", derived, "Simplified:")),
        paper=paper,
    )


def _gamma_expr() -> sp.Expr:
    return sp.Sum(Phi(j), (j, 1, N))


def _pmf_sums_to_one(d: Derivation) -> bool:
    # Sum over k of the pmf is identically 1 in p (rational-function identity) for each N.
    e = rhs(d)
    for n in range(1, 9):
        total = sum(e.subs({N: n, k: kk}).doit() for kk in range(1, n + 1))
        if sp.cancel(sp.together(total) - 1) != 0:
            return False
    return True


def _pmf_brute(d: Derivation) -> bool:
    # p**length-weighted simple circuits from the brute-force enumerator, at rational p.
    from symhx.circuits import enumerate_circuits

    e = rhs(d)
    for n in range(1, 6):
        for pv in (Fraction(1, 3), Fraction(2, 7), Fraction(5, 2)):
            w = {kk: Fraction(0) for kk in range(1, n + 1)}
            for length in range(1, n + 1):
                for c in enumerate_circuits(n, length):
                    if len(set(c)) == length:
                        w[length] += pv**length
            tot = sum(w.values())
            ps = sp.Rational(pv.numerator, pv.denominator)
            if not all_exact((e.subs({N: n, k: kk, p: ps}).doit(), w[kk] / tot)
                             for kk in range(1, n + 1)):
                return False
    return True


@register("7", 5, "Distribution of the number X of distinct impacts over simple circuits",
          r"Distribution of the number $X$ of distinct impacts over the simple circuits")
def _d7() -> dict:
    pmf = Phi() / _gamma_expr()
    return dict(
        result=sp.Eq(PX_sym, pmf),
        checks=(
            Check("sums to 1 identically in p for N = 1..8", "exact", _pmf_sums_to_one,
                  r"sums to 1 identically in $p$ for $N = 1, \dots, 8$"),
            Check("equals p**length-weighted brute-force enumeration, N <= 5, p in "
                  "{1/3, 2/7, 5/2}", "exact", _pmf_brute,
                  r"equals a brute-force enumeration weighted by $p^{\text{length}}$, "
                  r"$N \le 5$, $p \in \{1/3, 2/7, 5/2\}$"),
        ),
        steps=(Step("weight p**k per circuit, phi_N(k) circuits, normalised", pmf,
                    r"Weight $p^k$ per circuit, $\phi_N(k)$ circuits, normalised:"),),
    )


@register("8", 5, "Numerator Phi_{N,p}(k) and normaliser Gamma_{N,p} of eq. (7)",
          r"Numerator $\Phi_{N,p}(k)$ and normaliser $\Gamma_{N,p}$ of eq. (7)")
def _d8() -> dict:
    paper_Phi = p**k * sp.factorial(N) / (k * sp.factorial(N - k))
    paper_Gamma = sp.Sum(p**j * sp.factorial(N) / (j * sp.factorial(N - j)), (j, 1, N))
    gamma_eq = sp.Eq(Gamma_sym, _gamma_expr())

    def gamma_poly(d: Derivation) -> bool:
        from symhx.circuits import phi as phi_int

        g = d.extra["Gamma"].rhs
        for n in range(1, 11):
            want = sum(phi_int(n, jj) * p**jj for jj in range(1, n + 1))
            if sp.expand(g.subs(N, n).doit() - want) != 0:
                return False
            if sp.expand(g.subs(N, n).doit() - paper_Gamma.subs(N, n).doit()) != 0:
                return False
        return True

    def phi_exact(d: Derivation) -> bool:
        from symhx.circuits import phi as phi_int

        e = rhs(d)
        return all(sp.expand(e.subs({N: n, k: kk}) - phi_int(n, kk) * p**kk) == 0
                   for n in range(1, 11) for kk in range(1, n + 1))

    return dict(
        result=sp.Eq(Phi_sym(k), Phi()),
        checks=(
            Check("Phi equals the paper's p^k N!/(k (N-k)!) for symbolic N, p, k", "symbolic",
                  lambda d: sym_equal(rhs(d), paper_Phi),
                  r"$\Phi$ equals the paper's $p^k N!/(k\,(N-k)!)$ for symbolic $N, p, k$"),
            Check("Phi equals phi(N,k) p^k (polynomial in p) for 1 <= k <= N <= 10", "exact",
                  phi_exact, r"$\Phi$ equals $\phi(N,k)\,p^k$ (a polynomial in $p$) for "
                  r"$1 \le k \le N \le 10$"),
            Check("Gamma equals sum_k phi(N,k) p^k and the paper's sum, N = 1..10", "exact",
                  gamma_poly, r"$\Gamma$ equals $\sum_k \phi(N,k)\,p^k$ and the paper's sum, "
                  r"$N = 1, \dots, 10$"),
        ),
        extra={"Gamma": gamma_eq},
        paper=paper_Phi,
    )
