"""Section 8 of the paper: higher-order circuits, eqs. (29)-(41), from one general count.

The paper counts each class by hand and its formulas fail at the boundary lengths (see the
book's errata chapter). Here every class is a special case of one derived count (key ``"37"``):
for a circuit of length ``k`` whose repeated vertices have multiplicities ``m_1, ..., m_r``
(total ``M``) and whose other ``k - M`` vertices are visited once,

* choose the labelled vertices: ``N! / (N - r)!`` ordered choices for the repeated ones, divided by
  ``nu = prod_j c_j!`` (``c_j`` repeated vertices share multiplicity ``j``), times
  ``binomial(N - r, k - M)`` for the once-visited ones;
* arrange them: ``k! / mu`` words, ``mu = prod_i m_i!``;
* divide by the ``k`` rotations, which act freely when ``k > M`` (a once-visited vertex breaks
  every rotational symmetry).

At ``k = M`` (no once-visited vertex) rotations are not free and Burnside's lemma gives the count
``(1/M) sum_{d | gcd(m)} totient(d) (M/d)! / prod (m_i/d)!`` of necklaces times the vertex choices;
:func:`pattern_count` returns the ``Piecewise`` of both.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction
from functools import lru_cache, partial

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
from symhx.symbolic.simple import phi as phi_simple
from symhx.validation import InputError

__all__ = ["pattern_count", "pattern_count_general"]

i_ = sp.Symbol("i", integer=True, positive=True)
g1, g2 = sp.symbols("gamma_1 gamma_2", integer=True, nonnegative=True)
n_, j_ = sp.symbols("n j", integer=True, positive=True)
M_, r_ = sp.symbols("M r", integer=True, positive=True)
mu_, nu_ = sp.symbols("mu nu", integer=True, positive=True)
x_ = sp.Symbol("x")
gam = sp.IndexedBase(r"\gamma")
gamma_fn = sp.Function(r"\gamma")
phi1_i = sp.Function(r"\phi^{1}_{N,i}")


# --------------------------------------------------------------------------- general count
@lru_cache(maxsize=1)
def _general_steps() -> tuple[Step, ...]:
    vertices = sp.ff(N, r_) / nu_ * sp.binomial(N - r_, k - M_)
    words = sp.factorial(k) / mu_
    circuits = vertices * words / k
    simplified = sp.gammasimp(circuits.rewrite(sp.gamma)).rewrite(sp.factorial)
    return (
        Step("labelled vertices", vertices, "The labelled vertices:"),
        Step("words of length k with that content", words,
             r"The words of length $k$ with that content:"),
        Step("circuits: divide by the k free rotations (k > M)", circuits,
             r"Circuits: divide by the $k$ free rotations ($k > M$):"),
        Step("simplified", simplified, "Simplified:"),
    )


def pattern_count_general() -> sp.Expr:
    """Eq. (37) generalised: circuits of length ``k > M`` with a given repeat pattern.

    In the symbols ``M`` (visits of the repeated vertices), ``r`` (number of repeated vertices),
    ``mu = prod m_i!`` and ``nu = prod_j c_j!``.

    >>> pattern_count_general()
    factorial(N)*factorial(k - 1)/(mu*nu*factorial(-M + k)*factorial(M + N - k - r))
    """
    return _general_steps()[-1][1]


def _burnside_necklaces(content: tuple[int, ...]) -> sp.Integer:
    L = sum(content)
    g = 0
    for m in content:
        g = math.gcd(g, m)
    total = sp.Integer(0)
    for d in sp.divisors(g):
        term = sp.totient(d) * sp.factorial(L // d)
        for m in content:
            term /= sp.factorial(m // d)
        total += term
    return total / L


def _pattern_symbols(repeats: tuple[int, ...]) -> dict[sp.Symbol, sp.Expr]:
    nu = sp.Integer(1)
    for c in {m: repeats.count(m) for m in repeats}.values():
        nu *= sp.factorial(c)
    mu = sp.Integer(1)
    for m in repeats:
        mu *= sp.factorial(m)
    return {M_: sum(repeats), r_: len(repeats), mu_: mu, nu_: nu}


def pattern_count(repeats: tuple[int, ...], kk: sp.Expr = k) -> sp.Expr:
    """Circuits of length ``kk`` whose repeated vertices have multiplicities ``repeats`` and whose
    other vertices are visited once (exact at every length, boundary included).

    Parameters
    ----------
    repeats : tuple of int
        Multiplicities ``>= 2`` of the repeated vertices, e.g. ``(2,)``, ``(3,)``, ``(2, 2)``;
        ``()`` gives the simple circuits.
    kk : sympy expression
        The circuit length (default the symbol ``k``).

    Returns
    -------
    sympy.Piecewise
        The generic formula for ``kk > M``, the Burnside value at ``kk = M`` and 0 below.

    >>> pattern_count((3,), 3)
    N
    >>> pattern_count((2, 2), 4)
    N*(N - 1)
    """
    repeats = tuple(sorted(repeats, reverse=True))
    if any(m < 2 for m in repeats):
        raise InputError("repeats must be multiplicities >= 2")
    return _pattern_piecewise(repeats).subs(k, kk)


@lru_cache(maxsize=32)
def _pattern_piecewise(repeats: tuple[int, ...]) -> sp.Expr:
    subs = _pattern_symbols(repeats)
    M = sum(repeats)
    generic = sp.gammasimp(pattern_count_general().subs(subs)).rewrite(sp.factorial)
    if not repeats:
        return generic
    boundary = sp.factor(sp.ff(N, len(repeats)) / subs[nu_] * _burnside_necklaces(repeats))
    return sp.Piecewise((generic, k > M), (boundary, sp.Eq(k, M)), (0, True))


def _circuit_count(n: int, pattern: tuple[int, ...]) -> int:
    from symhx.circuits import circuit_count

    return circuit_count(n, pattern)


@lru_cache(maxsize=64)
def _brute(n: int, L: int) -> dict[tuple[int, ...], list[tuple[int, ...]]]:
    """Brute-force circuits of length L on n vertices, grouped by visit pattern."""
    from collections import Counter

    from symhx.circuits import enumerate_circuits

    out: dict[tuple[int, ...], list[tuple[int, ...]]] = {}
    for c in enumerate_circuits(n, L):
        pat = tuple(sorted(Counter(c).values(), reverse=True))
        out.setdefault(pat, []).append(c)
    return out


def _pattern_exact(repeats: tuple[int, ...], nmax: int = 10, brute_n: int = 4,
                   brute_L: int = 7):
    def check(d: Derivation) -> bool:
        e = rhs(d)
        M = sum(repeats)
        pairs = []
        for n in range(1, nmax + 1):
            # below the boundary (length k < M) no circuit has the pattern: the count is 0
            pairs += [(e.subs({N: n, k: kk}), 0) for kk in range(0, M)]
            for kk in range(max(M, 1), n + M + 1):
                pat = repeats + (1,) * (kk - M)
                pairs.append((e.subs({N: n, k: kk}), _circuit_count(n, pat)))
        for n in range(1, brute_n + 1):
            for kk in range(max(M, 1), brute_L + 1):
                pat = repeats + (1,) * (kk - M)
                pairs.append((e.subs({N: n, k: kk}), len(_brute(n, kk).get(pat, []))))
        return all_exact(pairs)
    return check


# ------------------------------------------------------------------------ eqs. 29-34
@lru_cache(maxsize=1)
def _d29_parts() -> tuple[sp.Expr, sp.Expr]:
    from sympy.simplify.simplify import product_simplify

    left = sp.Product(N - i_, (i_, 1, g1)) * sp.Integer(1) * sp.Product(N - i_, (i_, g1 + 1,
                                                                                 g1 + g2))
    return left, product_simplify(left)


@register("29", 8, "Paths i -> (gamma_1 new vertices) -> i -> (gamma_2 new vertices) -> i",
          r"Paths $i \to (\gamma_1$ new vertices$) \to i \to (\gamma_2$ new vertices$) \to i$")
def _d29() -> dict:
    left, combined = _d29_parts()

    def perm_brute(n: int, r: int) -> int:
        return sum(1 for _ in itertools.permutations(range(1, n), r))

    def c29_sym(d: Derivation) -> bool:
        # both sides evaluate to rising factorials; their ratio simplifies to exactly 1
        return bool(sp.combsimp(d.result.lhs.doit() / rhs(d).doit()) == 1)

    def c29_exact(d: Derivation) -> bool:
        e = rhs(d)
        return all_exact((e.subs({N: n, g1: a, g2: b}).doit(), perm_brute(n, a + b))
                         for n in range(1, 7) for a in range(n) for b in range(n - a))

    return dict(
        result=sp.Eq(left, combined),
        checks=(
            Check("both sides agree after evaluation, symbolic N, gamma_1, gamma_2", "symbolic",
                  c29_sym, r"both sides agree after evaluation, for symbolic "
                  r"$N, \gamma_1, \gamma_2$"),
            Check("equals an itertools count of the vertex choices, N <= 6", "exact",
                  c29_exact, r"equals an `itertools` count of the vertex choices, $N \le 6$"),
        ),
        paper=sp.Product(N - i_, (i_, 1, g1 + g2)),
    )


@register("30", 8, "The same with the length constraint (28): gamma_1 + gamma_2 = k - 2",
          r"The same with the length constraint (28): $\gamma_1 + \gamma_2 = k - 2$")
def _d30() -> dict:
    _, combined = _d29_parts()
    sub = combined.subs(g2, k - 2 - g1)  # eq. (28): (gamma_1 + 1) + (gamma_2 + 1) = k
    return dict(
        result=sp.Eq(combined, sub),
        checks=(
            Check("equals eq. (29) with gamma_2 = k - 2 - gamma_1, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d).doit(), combined.doit().subs(g2, k - 2 - g1)),
                  r"equals eq. (29) with $\gamma_2 = k - 2 - \gamma_1$, symbolically"),
            Check("equals perm(N-1, k-2), 2 <= k <= N+1 <= 9", "exact", lambda d: all_exact(
                (rhs(d).subs({N: n, k: kk}).doit(), math.perm(n - 1, kk - 2))
                for n in range(1, 9) for kk in range(2, n + 2)),
                r"equals `math.perm(N-1, k-2)` for $2 \le k \le N+1 \le 9$"),
        ),
        paper=sp.Product(N - i_, (i_, 1, k - 2)),
    )


@register("31", 8, "Number of such paths for a fixed split gamma_1: (N-1)!/(N-(k-1))!",
          r"Number of such paths for a fixed split $\gamma_1$: $(N-1)!/(N-(k-1))!$")
def _d31() -> dict:
    evaluated = sp.Product(i_, (i_, N - k + 2, N - 1)).doit()  # re-indexed i -> N - i
    evaluated = sp.piecewise_fold(sp.gammasimp(evaluated.rewrite(sp.gamma)))
    if isinstance(evaluated, sp.Piecewise):
        evaluated = evaluated.args[0].expr
    evaluated = evaluated.rewrite(sp.factorial)
    paper31 = sp.factorial(N - 1) / sp.factorial(N - (k - 1))

    def c31_brute(d: Derivation) -> bool:
        # eq. (30)'s product multiplied out term by term for integer N, k
        e = rhs(d)
        return all_exact((e.subs({N: n, k: kk}), math.prod(n - t for t in range(1, kk - 1)))
                         for n in range(1, 9) for kk in range(2, n + 2))

    def c31_enum(d: Derivation) -> bool:
        e = rhs(d)
        for n in range(1, 6):
            for kk in range(3, n + 2):
                for gg1 in range(kk - 1):
                    cnt = 0
                    for w in itertools.product(range(n), repeat=kk - 1):
                        word = (0, *w)
                        if word.count(0) == 2 and word[gg1 + 1] == 0 and len(set(w)) == kk - 1:
                            cnt += 1
                    if not all_exact([(e.subs({N: n, k: kk}), cnt)]):
                        return False
        return True

    return dict(
        result=sp.Eq(sp.Product(N - i_, (i_, 1, k - 2)), evaluated),
        checks=(
            Check("equals the paper's (N-1)!/(N-(k-1))!, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), paper31),
                  r"equals the paper's $(N-1)!/(N-(k-1))!$, symbolically"),
            Check("equals eq. (30) multiplied out, 2 <= k <= N+1 <= 9", "exact", c31_brute,
                  r"equals eq. (30) multiplied out, $2 \le k \le N+1 \le 9$"),
            Check("equals a brute-force count of words (fixed gamma_1), N <= 5", "exact",
                  c31_enum, r"equals a brute-force count of words (fixed $\gamma_1$), $N \le 5$"),
        ),
        paper=paper31,
    )


@register("32", 8, "Circuits of length k > 2 visiting a given vertex i twice, others at most once",
          r"Circuits of length $k > 2$ visiting a given vertex $i$ twice, the others at most once")
def _d32() -> dict:
    per_split = sp.factorial(N - 1) / sp.factorial(N - (k - 1))
    total = sp.Sum(per_split, (g1, 0, k - 2))
    derived = sp.factor(sp.Rational(1, 2) * total.doit())
    paper = sp.binomial(k - 1, 1) / 2 * per_split  # gamma(k, 2)/2 with eq. (34)

    def brute(d: Derivation) -> bool:
        e = rhs(d)
        pairs = []
        for n in range(1, 6):
            for kk in range(3, n + 2):
                pat = (2,) + (1,) * (kk - 2)
                cnt = sum(1 for c in _brute(n, kk).get(pat, []) if c.count(0) == 2)
                pairs.append((e.subs({N: n, k: kk}), cnt))
        return all_exact(pairs)

    return dict(
        result=sp.Eq(phi1_i(k), derived),
        checks=(
            Check("equals the paper's gamma(k,2)/2 (N-1)!/(N-(k-1))!, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), paper),
                  r"equals the paper's $\frac12\gamma(k,2)\,(N-1)!/(N-(k-1))!$, symbolically"),
            Check("equals brute-force enumeration (vertex 0 twice), 3 <= k <= N+1 <= 6",
                  "exact", brute, r"equals brute-force enumeration (vertex 0 twice), "
                  r"$3 \le k \le N+1 \le 6$"),
        ),
        steps=(Step("(1/2) sum over the splits gamma_1 = 0..k-2 of eq. (31)",
                    sp.Rational(1, 2) * total,
                    r"$\frac12\times$ the sum of eq. (31) over the splits "
                    r"$\gamma_1 = 0, \dots, k-2$:"),
               Step("evaluated", derived, "Evaluated:")),
        paper=paper,
    )


def _power_series_coefficient(n: int, j: int) -> int:
    """Coefficient of ``x**n`` in ``(x/(1-x))**j = (x + x**2 + ...)**j``, by multiplying the
    truncated integer series ``j`` times (independent of the closed form of eq. 34)."""
    base = [0] + [1] * n  # x + x^2 + ... + x^n
    acc = [1] + [0] * n
    for _ in range(j):
        acc = [sum(acc[i] * base[m - i] for i in range(m + 1)) for m in range(n + 1)]
    return acc[n]


@register("33", 8, "gamma(n, j): number of solutions of this equation in positive integers",
          r"$\gamma(n, j)$: the number of solutions of this equation in positive integers")
def _d33() -> dict:
    relation = sp.Eq(sp.Sum(gam[i_], (i_, 1, j_)), n_)

    def count_solutions(d: Derivation, n: int, j: int) -> int:
        rel = d.result.subs(j_, j).doit()
        syms = [gam[t] for t in range(1, j + 1)]
        fn = sp.lambdify([*syms, n_], rel.lhs - rel.rhs)
        return sum(1 for vals in itertools.product(range(1, n + 1), repeat=j)
                   if fn(*vals, n) == 0)

    def c33(d: Derivation) -> bool:
        for n in range(1, 8):
            for j in range(1, min(n, 4) + 1):
                gf = _power_series_coefficient(n, j)
                if count_solutions(d, n, j) != gf:
                    return False
        return True

    return dict(
        result=relation,
        checks=(Check("number of positive solutions equals the x^n coefficient of "
                      "(x/(1-x))^j, n <= 7, j <= 4 (brute force)", "exact", c33,
                      r"the number of positive solutions equals the coefficient of $x^n$ in "
                      r"$\bigl(x/(1-x)\bigr)^j$, $n \le 7$, $j \le 4$ (brute force)"),),
    )


@register("34", 8, "gamma(n, j) = binomial(n-1, j-1) (compositions of n into j parts)",
          r"$\gamma(n, j) = \binom{n-1}{j-1}$ (compositions of $n$ into $j$ parts)")
def _d34() -> dict:
    derived = sp.binomial(n_ - 1, j_ - 1)  # (j-1) cut points among the n-1 inner gaps

    def pascal(d: Derivation) -> bool:
        e = rhs(d)
        G = sp.Lambda((n_, j_), e)
        # first part = 1 (drop it) or > 1 (decrease it): gamma(n,j) = gamma(n-1,j-1) + gamma(n-1,j)
        step = sp.simplify(sp.combsimp((G(n_ - 1, j_ - 1) + G(n_ - 1, j_)) / G(n_, j_))) == 1
        base = sp.simplify(G(n_, 1)) == 1 and sp.simplify(G(j_, j_)) == 1
        return bool(step and base)

    def brute(d: Derivation) -> bool:
        e = rhs(d)
        pairs = []
        for n in range(1, 11):
            for j in range(1, n + 1):
                cnt = sum(1 for cuts in itertools.combinations(range(1, n), j - 1))
                # independent: count compositions directly for small n
                if n <= 8:
                    cnt = sum(1 for c in itertools.product(range(1, n + 1), repeat=j)
                              if sum(c) == n) if j <= 4 else cnt
                pairs.append((e.subs({n_: n, j_: j}), cnt))
        return all_exact(pairs)

    return dict(
        result=sp.Eq(gamma_fn(n_, j_), derived),
        checks=(
            Check("satisfies gamma(n,j) = gamma(n-1,j-1) + gamma(n-1,j), gamma(n,1) = "
                  "gamma(j,j) = 1 (induction), symbolic", "symbolic", pascal,
                  r"satisfies $\gamma(n,j) = \gamma(n-1,j-1) + \gamma(n-1,j)$ and "
                  r"$\gamma(n,1) = \gamma(j,j) = 1$ (induction), symbolically"),
            Check("equals brute-force composition counts, n <= 10", "exact", brute,
                  r"equals brute-force composition counts, $n \le 10$"),
        ),
        steps=(Step("(j-1) cut points among the n-1 inner gaps of n units", derived,
                    r"Choose $j - 1$ cut points among the $n - 1$ inner gaps of $n$ units:"),),
        paper=sp.binomial(n_ - 1, j_ - 1),
    )


# ------------------------------------------------------------------------ eqs. 35-41
_PAPER35 = sp.Rational(1, 2) * (k - 1) * sp.factorial(N) / sp.factorial(N - (k - 1))


@register("35", 8, "phi^1_N(k): one vertex visited twice, others at most once (valid for k > 2)",
          r"$\phi^1_N(k)$: one vertex visited twice, the others at most once (valid for $k > 2$)")
def _d35() -> dict:
    per_vertex = sp.factor(sp.Rational(1, 2) * sp.Sum(
        sp.factorial(N - 1) / sp.factorial(N - (k - 1)), (g1, 0, k - 2)).doit())
    derived = sp.gammasimp(N * per_vertex).rewrite(sp.factorial)
    general = pattern_count((2,))

    def exact35(d: Derivation) -> bool:
        e = rhs(d)
        return all_exact((e.subs({N: n, k: kk}), _circuit_count(n, (2,) + (1,) * (kk - 2)))
                         for n in range(1, 11) for kk in range(3, n + 2))

    return dict(
        result=sp.Eq(sp.Function(r"\phi^{1}_{N}")(k), derived),
        checks=(
            Check("equals the paper's (1/2)(k-1) N!/(N-(k-1))!, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), _PAPER35),
                  r"equals the paper's $\frac12 (k-1)\,N!/(N-(k-1))!$, symbolically"),
            Check("equals the general pattern count (37) for k > 2, symbolic", "symbolic",
                  lambda d: sym_equal(rhs(d), general.args[0].expr),
                  r"equals the general pattern count (37) for $k > 2$, symbolically"),
            Check("equals symhx.circuits.circuit_count, 3 <= k <= N+1 <= 11", "exact", exact35,
                  r"equals `symhx.circuits.circuit_count` for $3 \le k \le N+1 \le 11$"),
        ),
        steps=(Step("N choices of the repeated vertex times eq. (32)", N * per_vertex,
                    r"$N$ choices of the repeated vertex times eq. (32):"),),
        paper=_PAPER35,
    )


@register("36", 8, "phi^1_N(2) = N: the boundary case, where eq. (35) would give N/2",
          r"$\phi^1_N(2) = N$: the boundary case, where eq. (35) would give $N/2$")
def _d36() -> dict:
    value2 = pattern_count((2,)).subs(k, 2)

    def exact36(d: Derivation) -> bool:
        e = rhs(d)
        ok = all_exact((e.subs(N, n), _circuit_count(n, (2,))) for n in range(1, 21))
        ok = ok and all_exact((e.subs(N, n), len(_brute(n, 2).get((2,), [])))
                              for n in range(1, 7))
        return ok

    return dict(
        result=sp.Eq(sp.Function(r"\phi^{1}_{N}")(2), value2),
        checks=(
            Check("equals circuit_count(N, (2,)) for N <= 20 and brute force for N <= 6",
                  "exact", exact36, r"equals `circuit_count(N, (2,))` for $N \le 20$ and brute "
                  r"force for $N \le 6$"),
            Check("differs from eq. (35) at k = 2 (N/2), symbolic", "symbolic",
                  lambda d: not sym_equal(rhs(d), _PAPER35.subs(k, 2)),
                  r"differs from eq. (35) at $k = 2$ (which gives $N/2$), symbolically"),
        ),
        paper=N,
    )


@register("37", 8, "General count: circuits of length k > M with repeated multiplicities m_i "
          "(sum M, r of them), the others visited once",
          r"General count: circuits of length $k > M$ whose $r$ repeated vertices have "
          r"multiplicities $m_i$ (sum $M$), the others visited once")
def _d37() -> dict:
    lhs = sp.Function(r"\phi^{(m_1,\dots,m_r)}_{N}")(k)

    def exact(d: Derivation) -> bool:
        from symhx.circuits import partitions

        e = rhs(d)
        pairs = []
        for L in range(2, 9):
            for pat in partitions(L):
                if 1 not in pat or pat[0] == 1:
                    continue  # generic branch: at least one repeated and one single vertex
                repeats = tuple(m for m in pat if m > 1)
                sub = _pattern_symbols(repeats)
                for n in range(1, 10):
                    pairs.append((e.subs(sub).subs({N: n, k: L}), _circuit_count(n, pat)))
        return all_exact(pairs)

    def brute(d: Derivation) -> bool:
        e = rhs(d)
        pairs = []
        for n in range(1, 4):
            for L in range(2, 8):
                for pat, circs in _brute(n, L).items():
                    if 1 not in pat or pat[0] == 1:
                        continue
                    sub = _pattern_symbols(tuple(m for m in pat if m > 1))
                    pairs.append((e.subs(sub).subs({N: n, k: L}), len(circs)))
        return all_exact(pairs)

    return dict(
        result=sp.Eq(lhs, pattern_count_general()),
        checks=(
            Check("equals symhx.circuits.circuit_count for every pattern of length <= 8 with "
                  "a single vertex, N <= 9", "exact", exact,
                  r"equals `symhx.circuits.circuit_count` for every pattern of length $\le 8$ "
                  r"with a vertex visited once, $N \le 9$"),
            Check("equals brute-force enumeration (FKM) by pattern, N <= 3, length <= 7",
                  "exact", brute, r"equals brute-force enumeration (FKM) by pattern, $N \le 3$, "
                  r"length $\le 7$"),
        ),
        steps=_general_steps(),
    )


_CLASSES = {
    "38": ((3,), r"\phi^{1,0}_{N}", "one vertex visited three times",
           sp.Rational(1, 6) * sp.factorial(k - 1) / sp.factorial(k - 3)
           * sp.factorial(N) / sp.factorial(N - (k - 2))),
    "39": ((4,), r"\phi^{1,0,0}_{N}", "one vertex visited four times",
           sp.Rational(1, 24) * sp.factorial(k - 1) / sp.factorial(k - 4)
           * sp.factorial(N) / sp.factorial(N - (k - 3))),
    "40": ((2, 2), r"\phi^{2}_{N}", "two vertices visited twice",
           sp.Rational(1, 8) * sp.factorial(k - 1) / sp.factorial(k - 4)
           * sp.factorial(N) / sp.factorial(N - (k - 2))),
}


def _class_derivation(label: str) -> dict:
    """The derivation of one class of :data:`_CLASSES` (built when first asked for; a plain
    module function, so each build runs the current code)."""
    repeats, name, _, paper = _CLASSES[label]
    M = sum(repeats)

    def generic_vs_paper(d: Derivation) -> bool:
        e = rhs(d)
        return isinstance(e, sp.Piecewise) and sym_equal(e.args[0].expr, paper)

    def erratum(d: Derivation) -> bool:
        e = rhs(d)
        # at the boundary k = M the paper's formula gives (words)/M, not the circuit count
        return all(e.subs({N: n, k: M}) != paper.subs({N: n, k: M}) for n in range(2, 8))

    return dict(
        result=sp.Eq(sp.Function(name)(k), pattern_count(repeats)),
        checks=(
            Check(f"generic branch (k > {M}) equals the paper's formula, symbolic",
                  "symbolic", generic_vs_paper,
                  f"the generic branch ($k > {M}$) equals the paper's formula, symbolically"),
            Check("equals circuit_count for all k, N <= 10, and brute force for N <= 4, "
                  "length <= 7", "exact", _pattern_exact(repeats),
                  r"equals `circuit_count` for all $k$ and $N \le 10$, and brute force for "
                  r"$N \le 4$, length $\le 7$"),
            Check(f"at k = {M} differs from the paper's formula (corrected boundary), "
                  "N = 2..7", "exact", erratum,
                  f"at $k = {M}$ differs from the paper's formula (the corrected boundary), "
                  r"$N = 2, \dots, 7$"),
        ),
        paper=paper,
    )


for _label, _spec in _CLASSES.items():
    register(_label, 8, f"Circuits of length k with {_spec[2]}, others at most once (all k, "
             "boundary corrected)", rf"Circuits of length $k$ with {_spec[2]}, the others at "
             "most once (all $k$, boundary corrected)")(partial(_class_derivation, _label))


_EQ41_TERMS = (((), 0), ((2,), 1), ((3,), 2), ((4,), 3), ((2, 2), 2))


@lru_cache(maxsize=2)
def _eq41_parts(weighted: bool) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """(generic k >= 3, value at k = 2, value at k = 1) of eq. (41)."""
    generic: sp.Expr = sp.Integer(0)
    for repeats, extra in _EQ41_TERMS:
        if repeats:
            term = pattern_count(repeats).args[0].expr.subs(k, k + extra)
        else:
            term = phi_simple(k)
        generic += term * (p ** (k + extra) if weighted else 1)
    total = sum((pattern_count(r, k + e) if r else phi_simple(k)) * (p ** (k + e) if weighted
                                                                       else 1)
                for r, e in _EQ41_TERMS)
    at2 = sp.factor(sp.expand(total.subs(k, 2)))
    at1 = sp.factor(sp.expand(total.subs(k, 1)))
    generic = sp.factor(sp.gammasimp(generic.rewrite(sp.gamma)).rewrite(sp.factorial))
    return generic, at2, at1


def _eq41_brute(weighted: bool):
    def check(d: Derivation) -> bool:
        e = rhs(d)
        pv = Fraction(1, 3)
        pairs = []
        for n in range(1, 5):
            for kk in range(1, n + 1):
                want = Fraction(0)
                for repeats, extra in _EQ41_TERMS:
                    if kk < len(repeats):
                        continue
                    L = kk + extra
                    pat = repeats + (1,) * (kk - len(repeats))
                    cnt = len(_brute(n, L).get(pat, [])) if L <= 7 else _circuit_count(n, pat)
                    want += cnt * (pv**L if weighted else 1)
                pairs.append((e.subs({N: n, k: kk, p: sp.Rational(1, 3)}), want))
        return all_exact(pairs)
    return check


def _eq41_exact(weighted: bool):
    def check(d: Derivation) -> bool:
        e = rhs(d)
        pv = Fraction(2, 7)
        pairs = []
        for n in range(1, 13):
            for kk in range(1, n + 1):
                want = Fraction(0)
                for repeats, extra in _EQ41_TERMS:
                    if kk < len(repeats):
                        continue  # needs more distinct vertices than k
                    pat = repeats + (1,) * (kk - len(repeats))
                    want += _circuit_count(n, pat) * (pv ** (kk + extra) if weighted else 1)
                pairs.append((e.subs({N: n, k: kk, p: sp.Rational(2, 7)}), want))
        return all_exact(pairs)
    return check


def _paper41() -> sp.Expr:
    return (phi_simple(k) + _PAPER35.subs(k, k + 1) + _CLASSES["38"][3].subs(k, k + 2)
            + _CLASSES["39"][3].subs(k, k + 3) + _CLASSES["40"][3].subs(k, k + 2))


def _eq41(weighted: bool) -> dict:
    generic, at2, at1 = _eq41_parts(weighted)
    result = sp.Piecewise((generic, k > 2), (at2, sp.Eq(k, 2)), (at1, sp.Eq(k, 1)))
    name = "W_{N,p}" if weighted else "n_{N}"
    checks = [
        Check("equals the sum of circuit_count over the five classes, k <= N <= 12"
              + (", p = 2/7" if weighted else ""), "exact", _eq41_exact(weighted),
              r"equals the sum of `circuit_count` over the five classes, $k \le N \le 12$"
              + (r", $p = 2/7$" if weighted else "")),
        Check("equals brute-force enumeration, N <= 4" + (", p = 1/3" if weighted else ""),
              "exact", _eq41_brute(weighted), r"equals brute-force enumeration, $N \le 4$"
              + (r", $p = 1/3$" if weighted else "")),
    ]
    paper41 = _paper41()
    if not weighted:
        checks.append(Check(
            "generic branch (k > 2) equals the paper's printed sum, symbolic", "symbolic",
            lambda d: sym_equal(rhs(d).args[0].expr, paper41),
            r"the generic branch ($k > 2$) equals the paper's printed sum, symbolically"))
        checks.append(Check(
            "k = 1 and k = 2 differ from the printed sum (corrected boundaries), N = 2..8",
            "exact", lambda d: all(
                rhs(d).subs({N: n, k: kk}) != paper41.subs({N: n, k: kk})
                for n in range(2, 9) for kk in (1, 2)),
            r"$k = 1$ and $k = 2$ differ from the printed sum (the corrected boundaries), "
            r"$N = 2, \dots, 8$"))
    return dict(result=sp.Eq(sp.Function(name)(k), result), checks=tuple(checks),
                paper=None if weighted else paper41)


@register("41", 8, "Circuits with k distinct impacts in the eq. (41) sample space (five classes, "
          "boundary cases corrected)", r"Circuits with $k$ distinct impacts in the sample space "
          "of eq. (41) (five classes, boundary cases corrected)")
def _d41() -> dict:
    return _eq41(False)


@register("41-weighted", 8, "Weight p^length of the eq. (41) sample space with k distinct "
          "impacts (unnormalised pmf; the default weighting)",
          r"Weight $p^{\text{length}}$ of the eq. (41) sample space with $k$ distinct impacts "
          "(the unnormalised pmf; the default weighting)")
def _d41_weighted() -> dict:
    return _eq41(True)


@register("41-truncation", 8, "Dropped vs kept classes at length k+3: (3,2) and (2,2,2) relative "
          "to (4,) -- both larger for k >= 3 (the (2,2,2) ratio is for k >= 4; 16/15 at k = 3)",
          r"Dropped against kept classes at length $k+3$: $(3,2)$ and $(2,2,2)$ relative to "
          r"$(4)$, both larger for $k \ge 3$ (the $(2,2,2)$ ratio is for $k \ge 4$; "
          r"$16/15$ at $k = 3$)")
def _d41_truncation() -> dict:
    # the classes the truncation drops, compared with the kept "one vertex four times"
    ratios = sp.Tuple(*[sp.factor(sp.gammasimp(
        (pattern_count(r).args[0].expr / pattern_count((4,)).args[0].expr).rewrite(sp.gamma)))
        .subs(k, k + 3) for r in ((3, 2), (2, 2, 2))])

    def ratio_exact(d: Derivation) -> bool:
        e = rhs(d)
        pairs = []
        for n in range(3, 12):
            for kk in range(3, n + 1):
                base = _circuit_count(n, (4,) + (1,) * (kk - 1))
                pairs.append((e[0].subs({k: kk}),
                              Fraction(_circuit_count(n, (3, 2) + (1,) * (kk - 2)), base)))
                if kk >= 4:  # (2,2,2) with no single vertex (k = 3) is a Burnside boundary
                    cnt = _circuit_count(n, (2, 2, 2) + (1,) * (kk - 3))
                    pairs.append((e[1].subs({k: kk}), Fraction(cnt, base)))
        return all_exact(pairs)

    return dict(
        result=sp.Eq(sp.Tuple(sp.Symbol("R_{3,2}"), sp.Symbol("R_{2,2,2}")), ratios),
        checks=(Check("equal ratios of circuit_count, 3 <= k <= N <= 11 (k >= 4 for (2,2,2))",
                      "exact", ratio_exact,
                      r"equal the ratios of `circuit_count`, $3 \le k \le N \le 11$ "
                      r"($k \ge 4$ for $(2,2,2)$)"),),
    )
