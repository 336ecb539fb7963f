"""Circuit weights with per-site probabilities: symmetric polynomials of the site probabilities.

Sites ``v = 1..N`` have probabilities ``p_v``; a circuit weighs the product over its impacts of
``p_(site)`` (``p_v**m`` for a site visited ``m`` times; ``p_v`` under the ``;distinct``
weighting).  ``W(k)`` is the total weight of the circuits of a sample space with ``k`` distinct
sites, so that ``P(X = k) = W(k) / sum_j W(j)`` generalises eqs. (7)-(8).

Simple circuits.  On a set ``S`` of ``k`` distinct sites there are ``(k-1)!`` simple circuits
(the cyclic orders of ``S``; ``k = 1`` is the loop), each of weight ``prod_{v in S} p_v``, so

``W(k) = (k-1)! e_k(p_1, ..., p_N)``  (``e_k`` the elementary symmetric polynomial).

One class (all ``p_v = p``) gives ``(k-1)! C(N, k) p**k = Phi_{N,p}(k)``, eq. (8).  With classes
(sizes ``n_i``, probabilities ``q_i``), ``e_k = [z**k] prod_i (1 + q_i z)**n_i``.

Higher-order spaces (section 8).  A circuit's visit pattern ``lambda = (m_1 >= ... >= m_r)``
(``r`` distinct sites, length ``L = sum m_j``).  On a fixed assignment of the multiplicities to
sites there are ``necklaces(lambda)`` circuits (:func:`symhx.circuits.necklaces_with_content`);
summing ``prod_v p_v**(m_v)`` over the assignments gives the monomial symmetric polynomial
``m_lambda(p)``, so ``W(k) = sum_{lambda in space, r = k} necklaces(lambda) m_lambda(p)`` (with
``prod_{v} p_v`` over the ``r`` sites, times the number of arrangements of the multiset, under
``;distinct``).  For a class ``s`` of the space (the parts ``> 1``, ``r_s`` of them, excess
``e_s``) and ``k > r_s``, ``necklaces = (k + e_s - 1)!/S_s`` (``S_s = prod s_i!``), and the parts
of ``s`` are distributed among the site classes: ``sigma = (sigma_1, ..., sigma_c)``, class ``i``
receiving ``r_i`` repeated parts of total ``d_i``, so::

    W(k) = sum_s (k + e_s - 1)!/S_s sum_sigma prod_i [falling(n_i, r_i) q_i**(d_i) / C(sigma_i)]
              e_{k - r_s}(sites with r_i removed from class i),

with ``C(sigma_i) = prod_j (number of parts j in sigma_i)!``.  At ``k = r_s`` (no site visited once)
the necklace count is taken from the space itself (Burnside, or the paper's printed value for
``eq41-printed``).  With ``R`` the largest ``r_s`` of the space and ``R_i = min(n_i, R)``, all of
this is ``W(k) = sum_e (k + e - 1)! [z**k] B(z) N_e(z)`` for ``k > R``, with the *base*
``B = prod_i (1 + q_i z)**(n_i - R_i)`` and short polynomials ``N_e`` of degree ``<= c R``.

Arithmetic of the weight tables
-------------------------------
* **exact** (rational ``q_i``): integer polynomials (python-flint ``fmpz_poly``), weights as
  ints over one common denominator; the table holds about ``N**2 (bits of q + log2 N) / 2``
  bits and is refused beyond :data:`EXACT_TABLE_BITS_LIMIT`.
* **balls** (any ``q_i``, certified relative accuracy ``2**-prec`` on every weight): the
  coefficients of the base are those of a Poisson-binomial law tilted by ``x``,
  ``e_t x**t = prod_i (1 + q_i x)**m_i * P(K = t)``, ``K = sum_i Bin(m_i, q_i x/(1 + q_i x))``;
  each tilt is an exact product of fixed-point integer binomial laws (``fmpz_poly``) with a
  rigorous bound on the fixed-point error, and tilts are added until every coefficient is
  within a band where that bound is below ``2**-prec`` relative (about ``sqrt(N / prec)``
  tilts).  ``N`` is capped by :data:`BALL_TABLE_N_LIMIT`.
* **short sums** (one large class and at most :data:`MAX_SMALL_SITES` other sites, any N):
  ``e_k = sum_J e_J(small) C(n_big, k - J) q_big**(k - J)``, a few terms per ``k``.

>>> from fractions import Fraction
>>> from symhx.sites import SiteClasses
>>> nums, den = exact_weights(SiteClasses((1, 2), ("1/2", "1/3")))
>>> [Fraction(x, den) for x in nums]          # (k-1)! e_k of (1/2, 1/3, 1/3)
[Fraction(7, 6), Fraction(4, 9), Fraction(1, 9)]
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterator, Sequence
from fractions import Fraction
from functools import lru_cache
from typing import Any

from flint import arb, fmpz, fmpz_poly

from symhx.certify import arb_prec, to_arb
from symhx.sites import SiteClasses, show_int
from symhx.validation import InputError, exact_work_refusal

__all__ = [
    "BALL_TABLE_N_LIMIT",
    "EXACT_TABLE_BITS_LIMIT",
    "MAX_SMALL_SITES",
    "SIMPLE",
    "SITE_PATTERN_LIMIT",
    "PatternSpace",
    "ball_weights",
    "binomial_product_balls",
    "check_pattern_work",
    "elementary_ball",
    "elementary_exact",
    "exact_table_bits",
    "exact_weights",
    "pattern_terms",
    "pattern_work",
    "short_sum_split",
]

#: exact weight tables are refused when they would hold more than this many bits in all
#: (:func:`exact_table_bits`: about ``N**2 (bits of q + log2 N) / 2``; ``N = 2000`` with
#: ``q = 1/100`` is 3.6e7 bits, 0.4 s).  Pass float / mpf probabilities for the ball path.
EXACT_TABLE_BITS_LIMIT = 200_000_000
#: the ball path tabulates every ``k = 1..N`` (a few ``sqrt(N)`` fixed-point products of
#: length ``~sqrt(N)``): 1e4 sites take ~0.1 s, 1e5 a few seconds.
BALL_TABLE_N_LIMIT = 100_000
#: a higher-order space with several site classes enumerates every (class of the space,
#: distribution of its parts among the site classes) pair once: refused beyond this many
#: (``excess<=16`` with 3 site classes is 146095 pairs, ~10 s; ``excess<=25`` with 2 is 456286)
SITE_PATTERN_LIMIT = 200_000
#: the short-sum representation (any N) needs all classes but the largest to hold at most this
#: many sites in all: ``e_k`` is then a sum of at most ``MAX_SMALL_SITES + 1`` binomial terms.
MAX_SMALL_SITES = 64

Classes = list[tuple[int, Fraction]]


# --------------------------------------------------------------------------- sample spaces
class PatternSpace:
    """The part of a sample space the weights need (duck-typed, so this layer does not import
    :mod:`symhx.spaces`): ``shapes`` (the classes: parts ``> 1`` of a visit pattern),
    ``ratio(shape, k)`` (circuits of the class with ``k`` distinct vertices per simple circuit,
    N-independent), ``weighting`` (``"length"`` or ``"distinct"``), ``max_parts``, ``name``.
    :class:`symhx.spaces.Space` has all of them; :data:`SIMPLE` is the simple space."""

    def __init__(self, name: str, shapes: tuple[tuple[int, ...], ...], weighting: str) -> None:
        self.name = name
        self.shapes = shapes
        self.weighting = weighting

    @property
    def max_parts(self) -> int:
        return max(len(s) for s in self.shapes)

    def ratio(self, shape: tuple[int, ...], k: int) -> Fraction:
        return Fraction(1) if shape == () and k >= 1 else Fraction(0)


#: the simple space: simple circuits only, ``W(k) = (k-1)! e_k``
SIMPLE = PatternSpace("simple", ((),), "length")


def _multiset_factorials(parts: Sequence[int]) -> int:
    out = 1
    for c in Counter(parts).values():
        out *= math.factorial(c)
    return out


def _compositions(n: int, c: int) -> Iterator[tuple[int, ...]]:
    """All ``(x_1, ..., x_c)`` of non-negative ints summing to ``n``."""
    if c == 1:
        yield (n,)
        return
    for first in range(n + 1):
        for rest in _compositions(n - first, c - 1):
            yield (first, *rest)


def distributions(shape: tuple[int, ...], c: int) -> Iterator[tuple[tuple[int, ...], ...]]:
    """Every way to distribute the parts of ``shape`` (a multiset) among ``c`` classes, each
    once: tuples of ``c`` sub-multisets (decreasing tuples) whose union is ``shape``.

    >>> sorted(distributions((2, 2), 2))
    [((), (2, 2)), ((2,), (2,)), ((2, 2), ())]
    """
    values = sorted(Counter(shape).items(), reverse=True)
    splits = [list(_compositions(cnt, c)) for _, cnt in values]

    def rec(i: int, acc: list[list[int]]) -> Iterator[tuple[tuple[int, ...], ...]]:
        if i == len(values):
            yield tuple(tuple(sorted(a, reverse=True)) for a in acc)
            return
        v = values[i][0]
        for comp in splits[i]:
            yield from rec(i + 1, [a + [v] * x for a, x in zip(acc, comp, strict=True)])

    yield from rec(0, [[] for _ in range(c)])


@lru_cache(maxsize=64)
def _pattern_terms_cached(name: str, shapes: tuple[tuple[int, ...], ...], weighting: str,
                          c: int) -> dict[int, dict[tuple[tuple[int, ...], tuple[int, ...]],
                                                 Fraction]]:
    out: dict[int, dict[tuple[tuple[int, ...], tuple[int, ...]], Fraction]] = {}
    for s in shapes:
        e = sum(x - 1 for x in s)
        S = 1
        for x in s:
            S *= math.factorial(x)
        level = out.setdefault(e, {})
        for sig in distributions(s, c):
            r = tuple(len(part) for part in sig)
            d = tuple(sum(part) for part in sig) if weighting == "length" else r
            C = 1
            for part in sig:
                C *= _multiset_factorials(part)
            key = (r, d)
            level[key] = level.get(key, Fraction(0)) + Fraction(1, S * C)
    return out


def pattern_work(space: Any, c: int) -> int:
    """The number of (class of the space, distribution of its parts among ``c`` site classes)
    pairs that :func:`pattern_terms` enumerates, counted without enumerating them.

    >>> pattern_work(SIMPLE, 3)
    1
    """
    return sum(math.prod(math.comb(m + c - 1, c - 1) for m in Counter(s).values())
               for s in space.shapes)


def check_pattern_work(space: Any, c: int) -> None:
    """Refuse ``space`` with ``c`` site classes when :func:`pattern_work` exceeds
    :data:`SITE_PATTERN_LIMIT` (before any enumeration).

    >>> check_pattern_work(SIMPLE, 5)
    """
    work = pattern_work(space, c)
    if work > SITE_PATTERN_LIMIT:
        raise InputError(
            f"space {space.name!r} with {c} site classes: its classes and their distributions "
            f"among the site classes make {work} pairs, more than the documented work limit "
            f"symhx.site_weights.SITE_PATTERN_LIMIT = {SITE_PATTERN_LIMIT} (a smaller excess "
            f"or fewer site classes fit)")


def pattern_terms(space: Any, c: int) -> dict[int, dict[tuple[tuple[int, ...], tuple[int, ...]],
                                                        Fraction]]:
    """For ``k > max_parts``: ``{e: {(r, w): coefficient}}`` with ``W(k) = sum_e (k+e-1)!
    sum_{(r, w)} coefficient * prod_i falling(n_i, r_i) q_i**(w_i) e_{k - |r|}(r removed)``;
    ``r_i`` repeated sites and ``w_i`` the exponent of ``q_i`` (the visits of the repeated
    sites of class ``i``, or ``r_i`` under ``;distinct``), summed over the classes ``s`` of
    the space and the distributions of their parts among ``c`` site classes (see the module
    docstring).

    >>> pattern_terms(SIMPLE, 2)
    {0: {((0, 0), (0, 0)): Fraction(1, 1)}}
    """
    check_pattern_work(space, c)
    return _pattern_terms_cached(space.name, tuple(space.shapes), space.weighting, c)


# --------------------------------------------------------------------------- small exact sums
def elementary_exact(classes: Classes, t: int) -> Fraction:
    """``e_t`` of the multiset of sites exactly (truncated product of the class polynomials;
    for small ``t``).

    >>> elementary_exact([(2, Fraction(1, 2)), (1, Fraction(1, 3))], 2)
    Fraction(7, 12)
    """
    if t < 0:
        return Fraction(0)
    poly = [Fraction(1)] + [Fraction(0)] * t
    for n, q in classes:
        new = [Fraction(0)] * (t + 1)
        coef = Fraction(1)
        binom = []
        for j in range(min(n, t) + 1):
            binom.append(coef)
            coef = coef * q * (n - j) / (j + 1)
        for i, a in enumerate(poly):
            if a:
                for j, b in enumerate(binom):
                    if i + j > t:
                        break
                    new[i + j] += a * b
        poly = new
    return poly[t]


def _falling(n: int, r: int) -> int:
    out = 1
    for i in range(r):
        out *= n - i
    return out


def _class_list(sc: SiteClasses) -> Classes:
    m = sc.merged()
    return list(zip(m.sizes, m.values, strict=True))


def _boundary_corrections(space: Any, classes: Classes) -> dict[int, Fraction]:
    """``{k: W(k) - generic(k)}`` for ``k <= max_parts``: the generic formula counts
    ``(L - 1)!/prod s_i!`` circuits per assignment for every class ``s`` (words / L); at
    ``k = r_s`` (no site visited once) the space's own count differs (Burnside's necklace count
    when the parts share a divisor, or the paper's printed value), and only those classes are
    summed, each over the distributions of its parts among the site classes."""
    c = len(classes)
    out: dict[int, Fraction] = {}
    for s in space.shapes:
        r_s = len(s)
        if r_s == 0:
            continue
        C_s = _multiset_factorials(s)
        S_s = math.prod(math.factorial(x) for x in s)
        L = sum(s)
        delta = space.ratio(s, r_s) * Fraction(C_s, r_s) - Fraction(math.factorial(L - 1), S_s)
        if not delta:
            continue
        total = Fraction(0)
        for sig in distributions(s, c):
            w = Fraction(1)
            for (n, q), part in zip(classes, sig, strict=True):
                if len(part) > n:
                    w = Fraction(0)
                    break
                expo = sum(part) if space.weighting == "length" else len(part)
                w *= Fraction(_falling(n, len(part)), _multiset_factorials(part)) * q**expo
            total += w
        if total:
            out[r_s] = out.get(r_s, Fraction(0)) + delta * total
    return out


def _short_polys(space: Any, classes: Classes) -> tuple[list[int], dict[int, list[Fraction]]]:
    """``(R_i, {e: coefficients of N_e})`` exactly (see the module docstring): the scalar
    coefficients are gathered per ``(e, r)`` first, so each ``prod_i (1 + q_i z)**(R_i - r_i)``
    is built once per ``r``."""
    c = len(classes)
    R = space.max_parts
    Rs = [min(n, R) for n, _ in classes]
    scal: dict[int, dict[tuple[int, ...], Fraction]] = {}
    for e, level in pattern_terms(space, c).items():
        acc = scal.setdefault(e, {})
        for (r, w), coef in level.items():
            if any(ri > n for ri, (n, _) in zip(r, classes, strict=True)):
                continue
            factor = coef
            for (n, q), ri, wi in zip(classes, r, w, strict=True):
                factor *= _falling(n, ri) * q**wi
            acc[r] = acc.get(r, Fraction(0)) + factor
    powers: list[list[list[Fraction]]] = []  # powers[i][j] = coefficients of (1 + q_i z)**j
    for (_, q), Ri in zip(classes, Rs, strict=True):
        row = [[Fraction(1)]]
        for _ in range(Ri):
            prev = row[-1]
            row.append([a + (q * prev[i - 1] if i else 0) for i, a in
                        enumerate([*prev, Fraction(0)])])
        powers.append(row)
    products: dict[tuple[int, ...], list[Fraction]] = {}
    out: dict[int, list[Fraction]] = {}
    for e, acc in scal.items():
        poly = [Fraction(0)] * (sum(Rs) + 1)
        for r, factor in acc.items():
            part = products.get(r)
            if part is None:
                part = [Fraction(1)]
                for i, (ri, Ri) in enumerate(zip(r, Rs, strict=True)):
                    f = powers[i][Ri - ri]
                    new = [Fraction(0)] * (len(part) + len(f) - 1)
                    for a_i, a in enumerate(part):
                        if a:
                            for b_i, b in enumerate(f):
                                new[a_i + b_i] += a * b
                    part = new
                products[r] = part
            shift = sum(r)
            for i, a in enumerate(part):
                poly[shift + i] += factor * a
        while len(poly) > 1 and poly[-1] == 0:
            poly.pop()
        out[e] = poly
    return Rs, out


# --------------------------------------------------------------------------- exact tables
def exact_table_bits(sc: SiteClasses) -> int:
    """An upper estimate of the bits of the exact weight table of ``sc`` (checked against
    :data:`EXACT_TABLE_BITS_LIMIT` before any work)."""
    N = sc.N
    qbits = sum(max(v.numerator.bit_length(), v.denominator.bit_length()) for v in sc.values)
    return N * N * (qbits + N.bit_length() + 2) // 2


def exact_weights(sc: SiteClasses, space: Any = SIMPLE) -> tuple[list[int], int]:
    """``(nums, den)`` with ``W(k) = nums[k-1] / den`` exactly, ``k = 1..N`` (rational
    probabilities; the table is refused beyond :data:`EXACT_TABLE_BITS_LIMIT`).

    >>> exact_weights(SiteClasses((2,), ("1/2",)))      # Phi_{2,1/2}(k) = 1, 1/4
    ([4, 1], 4)
    """
    bits = exact_table_bits(sc)
    if bits > EXACT_TABLE_BITS_LIMIT:
        raise exact_work_refusal(
            f"exact weights with site classes would hold ~{bits:.2g} bits for N={sc.N} "
            f"(documented work limit symhx.site_weights.EXACT_TABLE_BITS_LIMIT = "
            f"{EXACT_TABLE_BITS_LIMIT:.2g})", values="the probabilities as floats or mpf")
    classes = _class_list(sc)
    N = sc.N
    Rs, npolys = _short_polys(space, classes)
    # base B(z) = prod (b + a z)**m / prod b**m, m = n - R_i
    base = fmpz_poly([1])
    den_b = 1
    for (n, q), Ri in zip(classes, Rs, strict=True):
        m = n - Ri
        a, b = q.numerator, q.denominator
        coeffs = []
        x = b**m
        for j in range(m + 1):
            coeffs.append(x)
            if j < m:
                x = x * (m - j) * a // ((j + 1) * b)
        base *= fmpz_poly(coeffs)
        den_b *= b**m
    B = [int(x) for x in base.coeffs()]
    den_n = 1
    for fpoly in npolys.values():
        for fx in fpoly:
            den_n = math.lcm(den_n, fx.denominator)
    nint: dict[int, list[int]] = {e: [int(x * den_n) for x in poly]
                                  for e, poly in npolys.items()}
    den = den_n * den_b
    nums: list[int] = []
    corr = _boundary_corrections(space, classes)
    for w in corr.values():
        den = math.lcm(den, w.denominator)
    scale = den // (den_n * den_b)
    fact = 1  # (k - 1)!
    for k in range(1, N + 1):
        if k > 1:
            fact *= k - 1
        total = 0
        for e, ipoly in nint.items():
            rise = fact
            for i in range(e):
                rise *= k + i
            s = 0
            for j, cj in enumerate(ipoly):
                if cj and 0 <= k - j < len(B):
                    s += cj * B[k - j]
            total += rise * s
        wk = corr.get(k)
        nums.append(total * scale + (wk.numerator * (den // wk.denominator) if wk else 0))
    return nums, den


# --------------------------------------------------------------------------- ball tables
def _bits(x: int) -> int:
    return max(1, int(x).bit_length())


def _tilt_pmf(m: int, rho: Fraction, F: int) -> tuple[int, list[int]]:
    """``(j_lo, B)`` with ``B[j - j_lo] = 2**F C(m, j) pi**j (1 - pi)**(m - j)`` rounded, error
    below 1 for every ``j`` (entries outside ``[j_lo, j_lo + len(B))`` are below 1), where
    ``pi = rho / (1 + rho)``: fixed-point ratio recurrences outward from the mode (the ratios
    are at most 1 there, so the floor errors add up, one unit of ``2**-(F+g)`` per step)."""
    g = _bits(m + 2) + 3
    rn, rd = rho.numerator, rho.denominator
    j0 = ((m + 1) * rn) // (rn + rd)  # floor((m + 1) pi)
    j0 = min(max(j0, 0), m)
    scale = F + g
    wp = scale + 2 * _bits(m) + 80
    while True:
        with arb_prec(wp):
            lb = (to_arb(m + 1).lgamma() - to_arb(j0 + 1).lgamma() - to_arb(m - j0 + 1).lgamma()
                  + j0 * to_arb(rho).log() - m * to_arb(1 + rho).log())
            x = lb.exp() * arb(2) ** scale
            ok = x.rad() < arb(1) / 4
            z = x.mid().floor().unique_fmpz() if ok else None
            v0 = int(z) if z is not None else 0
        if ok:
            break
        wp *= 2  # pragma: no cover - the working precision above is ample
    half = 1 << (g - 1)
    up = []
    v = v0
    j = j0
    while v >= half:
        up.append(v)
        if j == m:
            break
        v = v * (m - j) * rn // ((j + 1) * rd)
        j += 1
    down = []
    v = v0
    j = j0
    while j > 0:
        v = v * j * rd // ((m - j + 1) * rn)
        j -= 1
        if v < half:
            break
        down.append(v)
    vals = down[::-1] + up
    j_lo = j0 - len(down)
    return j_lo, [(x + half) >> g for x in vals]


def _tilt_for_mean(parts: Classes, target: float) -> tuple[int, int]:
    """A dyadic tilt ``x = xn * 2**xe`` whose Poisson-binomial mean is ``target`` (float
    bisection on ``log x``; any x is valid, this only places the band)."""
    logq = [math.log(q.numerator) - math.log(q.denominator) for _, q in parts]

    def mean(lx: float) -> float:
        tot = 0.0
        for (m, _), lq in zip(parts, logq, strict=True):
            u = lq + lx
            pi = 1.0 / (1.0 + math.exp(-u)) if u > -700 else math.exp(u)
            tot += m * pi
        return tot

    lo, hi = -60.0 - max(logq), 60.0 - min(logq)
    while mean(lo) > target:
        lo -= 60.0
    while mean(hi) < target:
        hi += 60.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mean(mid) < target:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-12 * max(1.0, abs(mid)):
            break
    lx = 0.5 * (lo + hi)
    e2 = lx / math.log(2)
    xe = math.floor(e2) - 30
    xn = max(1, round(2 ** (e2 - xe)))
    return xn, xe


def _sigma(parts: Classes, xn: int, xe: int) -> float:
    tot = 0.0
    for m, q in parts:
        lr = math.log(q.numerator) - math.log(q.denominator) + math.log(xn) + xe * math.log(2)
        pi = 1.0 / (1.0 + math.exp(-lr)) if lr > -700 else math.exp(lr)
        tot += m * pi * (1 - pi)
    return math.sqrt(max(tot, 1.0))


def binomial_product_balls(parts: Sequence[tuple[int, Fraction]], prec: int) -> list[arb]:
    """The coefficients ``e_t``, ``t = 0..M``, of ``prod_i (1 + q_i z)**m_i`` as Arb balls of
    relative radius below ``2**-prec`` (``q_i`` exact positive rationals).

    >>> from flint import ctx
    >>> e = binomial_product_balls([(3, Fraction(1, 2)), (2, Fraction(1, 3))], 60)
    >>> [x.mid().str(5, radius=False) for x in e]   # 1, 13/6, 67/36, 19/24, 1/6, 1/72
    ['1.0000', '2.1667', '1.8611', '0.79167', '0.16667', '0.013889']
    """
    parts = [(int(m), Fraction(q)) for m, q in parts if m > 0]
    M = sum(m for m, _ in parts)
    wp = prec + 2 * _bits(M) + 30
    if not parts:
        with arb_prec(wp):
            return [arb(1)]
    if len(parts) == 1:
        (m, q), = parts
        out = []
        with arb_prec(wp):
            qa = to_arb(q)
            x = arb(1)
            for j in range(m + 1):
                out.append(x)
                x = x * qa * (m - j) / (j + 1)
        return out
    c = len(parts)
    G = max(64, prec)
    F = prec + G + _bits(c) + _bits(M) + 8
    out_: list[arb | None] = [None] * (M + 1)
    err = c << ((c - 1) * F + 1)
    need = err << (prec + 2)
    t_next = 0
    while t_next <= M:
        xn, xe = _tilt_for_mean(parts, max(0.5, min(M - 0.5, t_next)))
        sig = _sigma(parts, xn, xe)
        target = t_next + 0.7 * math.sqrt(2 * math.log(2) * G) * sig
        if target < M - 0.5 and t_next > 0:
            xn, xe = _tilt_for_mean(parts, target)
        covered = _tilt_apply(parts, xn, xe, F, err, need, out_, wp)
        if out_[t_next] is None:  # the band missed t_next: a tilt centred on it cannot
            xn, xe = _tilt_for_mean(parts, max(0.5, min(M - 0.5, t_next)))
            covered = _tilt_apply(parts, xn, xe, F, err, need, out_, wp)
            if out_[t_next] is None:  # pragma: no cover - the central term is >= 2**-G
                raise ArithmeticError(f"tilted product did not reach e_{t_next}")
        del covered
        while t_next <= M and out_[t_next] is not None:
            t_next += 1
    return [x for x in out_ if x is not None]


def _tilt_apply(parts: Classes, xn: int, xe: int, F: int, err: int, need: int,
                out: list[arb | None], wp: int, only: int | None = None) -> int:
    """One tilt: fill every ``out[t]`` (or only ``out[only]``) whose fixed-point product is
    accurate enough."""
    x = Fraction(xn) * Fraction(2) ** xe
    prod = fmpz_poly([1])
    lo = 0
    for m, q in parts:
        j_lo, B = _tilt_pmf(m, q * x, F)
        prod *= fmpz_poly(B)
        lo += j_lo
    coeffs = prod.coeffs()
    c = len(parts)
    done = 0
    with arb_prec(wp):
        logZ = sum((m * to_arb(1 + q * x).log() for m, q in parts), arb(0))
        logx = to_arb(xn).log() + xe * arb(2).log()
        two = arb(2) ** (-c * F)
        inv_x = (-logx).exp()
        scale = None
        for i, R in enumerate(coeffs):
            t = lo + i
            if out[t] is not None or R <= need or (only is not None and t != only):
                continue
            if scale is None or scale[0] != t - 1:
                fac = (logZ - t * logx).exp() * two
            else:
                fac = scale[1] * inv_x
            scale = (t, fac)
            out[t] = arb(fmpz(R), fmpz(err)) * fac
            done += 1
    return done


def elementary_ball(parts: Sequence[tuple[int, Fraction]], t: int, prec: int) -> arb:
    """``e_t = [z**t] prod_i (1 + q_i z)**m_i`` as one Arb ball of relative radius below
    ``2**-prec``: a single tilt centred on ``t`` (the whole table only if that misses).

    >>> x = elementary_ball([(3, Fraction(1, 2)), (2, Fraction(1, 3))], 2, 60)
    >>> x.mid().str(5, radius=False)      # 67/36
    '1.8611'
    """
    parts = [(int(m), Fraction(q)) for m, q in parts if m > 0]
    M = sum(m for m, _ in parts)
    if t < 0 or t > M:
        return arb(0)
    if len(parts) <= 1 or t == 0:
        if not parts or t == 0:
            return arb(1)
        (m, q), = parts
        wp = prec + 2 * _bits(m) + 30
        with arb_prec(wp):
            return (to_arb(m + 1).lgamma() - to_arb(t + 1).lgamma() - to_arb(m - t + 1).lgamma()
                    + t * to_arb(q).log()).exp()
    c = len(parts)
    G = max(64, prec)
    F = prec + G + _bits(c) + _bits(M) + 8
    err = c << ((c - 1) * F + 1)
    need = err << (prec + 2)
    wp = prec + 2 * _bits(M) + 30
    xn, xe = _tilt_for_mean(parts, max(0.5, min(M - 0.5, t)))
    out: list[arb | None] = [None] * (M + 1)
    _tilt_apply(parts, xn, xe, F, err, need, out, wp, only=t)
    x = out[t]
    if x is None:  # pragma: no cover - the central term of a tilt is far above 2**-G
        return binomial_product_balls(parts, prec)[t]
    return x


def short_sum_split(sc: SiteClasses) -> tuple[tuple[int, Fraction], Classes] | None:
    """``((n_big, q_big), small)`` when all classes but the largest hold at most
    :data:`MAX_SMALL_SITES` sites, else ``None``."""
    classes = _class_list(sc)
    i = max(range(len(classes)), key=lambda j: classes[j][0])
    small = [cl for j, cl in enumerate(classes) if j != i]
    if sum(n for n, _ in small) > MAX_SMALL_SITES:
        return None
    return classes[i], small


def ball_weights(sc: SiteClasses, space: Any = SIMPLE, prec: int = 128) -> list[arb]:
    """``W(k)``, ``k = 1..N``, as Arb balls of relative radius below ``2**-prec`` (any
    rational or binary probabilities; ``N <= BALL_TABLE_N_LIMIT``).

    >>> w = ball_weights(SiteClasses((1, 2), ("1/2", "1/3")), prec=60)
    >>> [x.mid().str(6, radius=False) for x in w]   # 7/6, 4/9, 1/9
    ['1.16667', '0.444444', '0.111111']
    """
    N = sc.N
    if N > BALL_TABLE_N_LIMIT:
        raise InputError(
            f"weights with site classes tabulate every k; N={show_int(N)} is above the "
            f"documented work limit symhx.site_weights.BALL_TABLE_N_LIMIT = {BALL_TABLE_N_LIMIT}")
    classes = _class_list(sc)
    Rs, npolys = _short_polys(space, classes)
    deg = max(len(p) for p in npolys.values())
    inner = prec + 2 * _bits(N) + 2 * _bits(deg) + 16
    base = binomial_product_balls([(n - Ri, q) for (n, q), Ri in zip(classes, Rs, strict=True)],
                                  inner)
    wp = inner + 20
    out: list[arb] = []
    with arb_prec(wp):
        polys = {e: [to_arb(x) for x in poly] for e, poly in npolys.items()}
        corr = _boundary_corrections(space, classes)
        fact = arb(1)
        for k in range(1, N + 1):
            if k > 1:
                fact = fact * (k - 1)
            total = to_arb(corr[k]) if k in corr else arb(0)
            for e, poly in polys.items():
                s = arb(0)
                for j, cj in enumerate(poly):
                    if 0 <= k - j < len(base) and npolys[e][j]:
                        s += cj * base[k - j]
                rise = fact
                for i in range(e):
                    rise = rise * (k + i)
                total += rise * s
            out.append(total)
    return out
