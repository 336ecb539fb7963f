"""The critical point along a direction of site probabilities, and the critical curve of two
site classes (section 6 generalised to per-site probabilities).

Let the sites' probabilities scale as ``p_v = t w_v`` along a direction ``w`` (a
:class:`symhx.SiteClasses` of positive weights).  Simple circuits weigh
``W_t(k) = t**k V(k)``, ``V(k) = (k-1)! e_k(w)`` (:mod:`symhx.site_weights`), so

``W_t(k) / W_t(1) = (t / c_k)**(k-1)``,  ``c_k = (e_1(w) / ((k-1)! e_k(w)))**(1/(k-1))``,

and the mode of X is 1 exactly for ``t < t_c = min_{k >= 2} c_k``; just above ``t_c`` it is the
largest tied argmin ``k_after``.  One class of weight ``w`` gives ``c_k = c_k(N) / w`` (eq. 11-16:
``symhx.critical``).  With several classes ``c_k`` need not be unimodal in ``k`` (two classes far
apart in weight can give two local minima), so the argmin is proved globally:

* **table** (``N <= symhx.site_weights.BALL_TABLE_N_LIMIT``, any classes): Arb balls of every
  ``log c_k`` at doubling precision, candidates that no ball separates compared exactly in
  integers (the weights are rationals: floats at their binary value), which also finds exact
  ties;
* **perturbative** (one large class of ``n`` sites and at most
  :data:`symhx.site_weights.MAX_SMALL_SITES` other sites, any N, ``10**100`` and beyond): with
  the large class's weight as the unit and ``rho_v`` the others' relative weights,
  ``V(k) = Phi_{n,1}(k) A(k)``, ``A(k) = sum_J e_J(rho) falling(k, J) / rising(n - k + 1, J)``
  (convex and increasing on ``0..n``), and the sign of ``c_{k+1} - c_k`` is that of
  ``E_w(k) = E_n(k) - P(k)``: ``E_n`` the one-class function of :mod:`symhx.critical`
  (decreasing, then increasing) and ``P(k) = (k-1) log A(k+1) - k log A(k) + log A(1)``, with
  ``|P(k)| <= (k-1) [A(k+1) - A(k) - (A(2) - A(1))/A(k+1)]``, a bound increasing in ``k``.  The
  certificate: ``E_w(k*-1) < 0 < E_w(k*)`` (Arb signs), ``E_w < 0`` on ``[2, k*-2]`` and
  ``E_w > 0`` on ``[k*+1, n/2)`` from those bounds over a few ranges, ``c_k`` above ``c_{k*}`` on
  ``[n/2, n]`` from ``c_k >= c_k(n) (A(1)/A(k))**(1/(k-1))`` with ``A <= prod(1 + rho_v n)``,
  and each ``k > n`` by its own ball.  It holds when the small sites perturb the large class
  (``sum rho_v k*/n`` small); otherwise the table decides (``N`` within its limit) or the call
  is refused.

``p_bounds`` is a rigorous enclosure of ``t_c``; ``q = t_c e_1(w) - 1`` (the expected number of
impacting sites per period at the jump, minus one) is computed without cancellation.  ``p_d``
(eq. 16, the discriminant root of the one-class quadratic ``f_{N,p}``) has no counterpart for
several classes (``W(k+1)/W(k)`` is no longer a quadratic in ``k``): it is ``None`` there, and
``p_d / w`` for one class.

>>> from symhx.sites import SiteClasses
>>> cp = direction_critical_point(101, SiteClasses((2, 99), (1, 1)), dps=20)
>>> cp.k_after, mpmath.nstr(cp.p, 20)      # one class: today's p_c
(20, '0.012889115326530578361')
>>> cp = direction_critical_point(101, SiteClasses((2, 99), ("1/2", 1)), dps=20)
>>> cp.k_after, cp.method, cp.p_bounds[0] <= cp.p <= cp.p_bounds[1]
(20, 'table', True)
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import mpmath
from flint import arb, fmpz
from flint import ctx as flint_ctx

from symhx import site_weights as _sw  # its work limits, read when called (raised there)
from symhx._mpctx import export, mp
from symhx.certify import (
    G_arb,
    UndecidedError,
    arb_prec,
    bits_for,
    certified_sign,
    mpf_bounds,
    rel_width_ok,
    to_arb,
)
from symhx.critical import CriticalPoint
from symhx.critical import critical_point as simple_critical_point
from symhx.site_weights import (
    SIMPLE,
    ball_weights,
    elementary_ball,
    elementary_exact,
    exact_table_bits,
    exact_weights,
    short_sum_split,
)
from symhx.sites import SiteClasses, as_site_classes, show_int
from symhx.validation import DEFAULT_DPS, InputError, check_dps, check_int, check_N, check_p

__all__ = [
    "CURVE_DIRECTIONS",
    "PERTURBATIVE_MIN_N",
    "CriticalCurve",
    "DirectionCriticalPoint",
    "critical_curve",
    "direction_critical_point",
]

#: at and above this N a direction with one large class tries the perturbative certificate
#: first (below it, and whenever the certificate does not close, the table decides)
PERTURBATIVE_MIN_N = 2_000
#: the default number of directions of :func:`critical_curve`
CURVE_DIRECTIONS = 17
#: exact integer comparisons of two c_k are attempted up to this many bits
EXACT_COMPARE_BITS = 4_000_000
#: the table's Arb precision doubles from 64 bits up to this before exact comparisons decide
TABLE_MAX_BITS = 2048


@dataclass(frozen=True, repr=False)
class DirectionCriticalPoint(CriticalPoint):
    """Where the mode of X leaves 1 along the direction ``p_v = t w_v`` (``weights``).

    The fields of :class:`symhx.critical.CriticalPoint`, read for the direction: ``p`` is
    ``t_c``, ``p_bounds`` its Arb enclosure, ``p_exact`` its exact value when rational, ``q``
    is ``t_c e_1(w) - 1`` (``sum_v p_v - 1`` at the jump), ``k_before = 1``, ``k_after`` the
    largest tied argmin of ``c_k``, ``argmins`` all of them; ``p_d``/``q_d`` are ``None`` for
    several classes (no discriminant root: see the module docstring).  Extra fields:
    ``weights`` (the direction) and ``method`` (``"one class"``, ``"table"`` or
    ``"perturbative"``).
    """

    weights: Any = None
    method: str = field(default="", compare=False)

    def site_probabilities(self) -> SiteClasses:
        """The site probabilities at the jump, ``t_c w`` (mpf, or Fractions when ``t_c`` is
        exact)."""
        t = self.p_exact if self.p_exact is not None else self.p
        return self.weights.scaled(t)

    def _show(self, x: Any) -> str:
        return "None" if x is None else str(mp().nstr(x, self.dps))

    def __repr__(self) -> str:
        lo, hi = self.p_bounds
        args = ", ".join(str(k) for k in self.argmins)
        return (f"DirectionCriticalPoint(N={self.N}, weights={self.weights!r}, "
                f"t_c={self._show(self.p)}, q=t_c*e_1(w)-1={self._show(self.q)}, "
                f"k_before={self.k_before}, k_after={self.k_after}, "
                f"argmins=({args}{',' if len(self.argmins) == 1 else ''}), "
                f"p_d={self._show(self.p_d)}, p_exact={self.p_exact}, "
                f"p_bounds=({self._show(lo)}, {self._show(hi)}), dps={self.dps}, "
                f"method={self.method!r})")

    def __str__(self) -> str:
        lo, hi = self.p_bounds
        lines = [f"critical point along a direction, N = {show_int(self.N)} ({self.dps} digits)",
                 f"  weights     = {self.weights!r}",
                 f"  t_c         = {self._show(self.p)}"
                 + (f"  (= {self.p_exact})" if self.p_exact is not None else ""),
                 f"  t_c e_1 - 1 = {self._show(self.q)}",
                 f"  t_c in        [{self._show(lo)}, {self._show(hi)}]  (Arb ball)",
                 f"  mode jumps  {self.k_before} -> {self.k_after}"
                 f"  (argmins {', '.join(str(k) for k in self.argmins)}; {self.method})"]
        if self.p_d is not None:
            lines.insert(5, f"  p_d / w     = {self._show(self.p_d)}")
        return "\n".join(lines)

    def as_dict(self) -> dict[str, Any]:
        d = super().as_dict() if self.p_d is not None else {
            "N": self.N, "p_c": self.p, "N_p_c_minus_1": self.q, "k_before": self.k_before,
            "k_after": self.k_after, "argmins": list(self.argmins), "p_d": None,
            "N_p_d_minus_1": None, "p_c_exact": self.p_exact, "p_c_lo": self.p_bounds[0],
            "p_c_hi": self.p_bounds[1], "dps": self.dps}
        d["t_c_e1_minus_1"] = d.pop("N_p_c_minus_1")
        d["sizes"] = list(self.weights.sizes)
        d["weights"] = list(self.weights.values)
        d["names"] = list(self.weights.names) if self.weights.names else None
        d["method"] = self.method
        return d


# --------------------------------------------------------------------------- helpers
def _mid_mpf(x: arb, dps: int) -> Any:
    """The midpoint of a ball rounded once to ``dps`` digits (a global mpf)."""
    man, exp = x.mid().man_exp()
    prec = mpmath.libmp.dps_to_prec(dps)
    return mpmath.mp.make_mpf(mpmath.libmp.from_man_exp(int(man), int(exp), prec, "n"))


def _frac_mpf(x: Fraction, dps: int) -> Any:
    prec = mpmath.libmp.dps_to_prec(dps)
    return mpmath.mp.make_mpf(mpmath.libmp.from_rational(x.numerator, x.denominator, prec, "n"))


def _enclose(sigma_fn: Any, log_e1: Fraction, dps: int, start_bits: int
             ) -> tuple[Any, Any, tuple[Any, Any], tuple[Any, Any]]:
    """From a ball function of ``sigma = log t_c``: ``(t, q, t_bounds, q_bounds)`` with
    ``q = expm1(sigma + log e_1)``, to ``dps`` digits, precision doubled until both balls are
    narrow enough."""
    bits = max(64, start_bits)
    for _ in range(14):
        with arb_prec(bits):
            s = sigma_fn()
            t, q = s.exp(), (s + to_arb(log_e1).log()).expm1()
            ok = rel_width_ok(t, dps) and rel_width_ok(q, dps)
            if ok:
                tb, qb = mpf_bounds(t, dps), mpf_bounds(q, dps)
                tm, qm = _mid_mpf(t, dps), _mid_mpf(q, dps)
        if ok:
            return tm, qm, (min(tb[0], tm), max(tb[1], tm)), (min(qb[0], qm), max(qb[1], qm))
        bits *= 2
    raise UndecidedError(f"could not enclose t_c to {dps} digits")  # pragma: no cover


def _exact_enclosure(a: Fraction, e1: Fraction, dps: int
                     ) -> tuple[Any, Any, tuple[Any, Any], tuple[Any, Any]]:
    q = a * e1 - 1
    bits = int(dps * 3.33) + 64
    with arb_prec(bits):
        tb, qb = mpf_bounds(to_arb(a), dps), mpf_bounds(to_arb(q), dps)
    t, qm = _frac_mpf(a, dps), _frac_mpf(q, dps) if q else mpmath.mpf(0)
    return t, qm, (min(tb[0], t), max(tb[1], t)), (min(qb[0], qm), max(qb[1], qm))


def _rational_root(a: Fraction, n: int) -> Fraction | None:
    """``a**(1/n)`` when it is rational (moderate sizes only), else None."""
    if n == 1:
        return a
    num, den = fmpz(a.numerator), fmpz(a.denominator)
    if max(num.bit_length(), den.bit_length()) > 20_000:
        return None
    rn, rd = num.root(n), den.root(n)
    if rn**n == num and rd**n == den:
        return Fraction(int(rn), int(rd))
    return None


def _classes(sc: SiteClasses) -> list[tuple[int, Fraction]]:
    m = sc.merged()
    return list(zip(m.sizes, m.values, strict=True))


# --------------------------------------------------------------------------- one class
def _one_class(N: int, sc: SiteClasses, dps: int) -> DirectionCriticalPoint:
    """``c_k = c_k(N) / w``: the simple critical point, divided by the weight."""
    cp = simple_critical_point(N, dps=dps)
    w = sc.merged().values[0]
    if w == 1:
        return DirectionCriticalPoint(**{f.name: getattr(cp, f.name)
                                         for f in dataclasses.fields(cp)},
                                      weights=sc, method="one class")
    prec = mpmath.libmp.dps_to_prec(dps)
    wr = mpmath.libmp.from_rational(w.numerator, w.denominator, prec + 64, "n")
    lo_w = mpmath.libmp.from_rational(w.numerator, w.denominator, prec + 64, "c")
    hi_w = mpmath.libmp.from_rational(w.numerator, w.denominator, prec + 64, "f")

    def div(x: Any, by: Any, rnd: str) -> Any:
        return mpmath.mp.make_mpf(mpmath.libmp.mpf_div(x._mpf_, by, prec + 8, rnd))

    p_exact = cp.p_exact / w if cp.p_exact is not None else None
    if p_exact is not None:
        p = _frac_mpf(p_exact, dps)
    else:
        p = mpmath.mp.make_mpf(mpmath.libmp.mpf_div(cp.p._mpf_, wr, prec, "n"))
    pb = (div(cp.p_bounds[0], lo_w, "f"), div(cp.p_bounds[1], hi_w, "c"))
    pb = (min(pb[0], p), max(pb[1], p))
    p_d = mpmath.mp.make_mpf(mpmath.libmp.mpf_div(cp.p_d._mpf_, wr, prec, "n"))
    return DirectionCriticalPoint(
        N=N, p=p, q=cp.q, k_before=1, k_after=cp.k_after, argmins=cp.argmins, p_d=p_d,
        p_exact=p_exact, dps=dps, p_bounds=pb, q_bounds=cp.q_bounds, q_d=cp.q_d,
        sign_evaluations=cp.sign_evaluations, weights=sc, method="one class")


# --------------------------------------------------------------------------- the table
def _exact_V(sc: SiteClasses) -> list[int]:
    exact = SiteClasses(sc.sizes, sc.values)
    if exact_table_bits(exact) > _sw.EXACT_TABLE_BITS_LIMIT:
        raise UndecidedError(
            f"c_k of two candidates agree to {TABLE_MAX_BITS} bits and the exact table of "
            f"N={sc.N} would exceed symhx.site_weights.EXACT_TABLE_BITS_LIMIT: an exact tie is "
            f"likely")
    nums, den = exact_weights(exact)
    del den  # one common denominator: comparisons of c_k need V(k) up to a common factor
    return nums


def _compare_c_exact(V: list[int], j: int, k: int) -> int:
    """Sign of ``c_k - c_j`` (``j < k``) from exact ``V`` (``V[i-1]`` proportional to
    ``V(i)`` with one common factor ``D``): ``c_j <= c_k`` iff
    ``V(1)**(k-j) V(k)**(j-1) <= V(j)**(k-1)`` (the factor cancels: both sides have degree
    ``k - 1``)."""
    v1, vj, vk = V[0], V[j - 1], V[k - 1]
    bits = (k - 1) * max(v1.bit_length(), vj.bit_length(), vk.bit_length())
    if bits > EXACT_COMPARE_BITS:
        raise UndecidedError(f"c_{j} vs c_{k}: balls did not separate and the exact comparison "
                             f"needs ~{bits} bits")
    lhs = fmpz(v1) ** (k - j) * fmpz(vk) ** (j - 1)
    rhs = fmpz(vj) ** (k - 1)
    # c_k^((j-1)(k-1)) = V1^(j-1)/Vk^(j-1), c_j^((j-1)(k-1)) = V1^(k-1)/Vj^(k-1):
    # c_k > c_j  iff  V1^(j-1) Vj^(k-1) > V1^(k-1) Vk^(j-1)  iff  Vj^(k-1) > V1^(k-j) Vk^(j-1)
    return (rhs > lhs) - (rhs < lhs)


def _table_argmins(sc: SiteClasses) -> tuple[tuple[int, ...], int]:
    """Every argmin of ``c_k`` (``2 <= k <= N``) and the number of ball evaluations."""
    N = sc.N
    classes = _classes(sc)
    e1 = sum(n * w for n, w in classes)
    bits = 64
    evals = 0
    cand: list[int] = []
    while bits <= TABLE_MAX_BITS:
        V = ball_weights(sc, SIMPLE, prec=bits)
        evals += 1
        with arb_prec(bits + 64):
            lv1 = to_arb(e1).log()
            logc = [(lv1 - V[k - 1].log()) / (k - 1) for k in range(2, N + 1)]
            best = min(range(len(logc)), key=lambda i: logc[i].mid())
            top = logc[best].upper()
            cand = [i + 2 for i, x in enumerate(logc) if not x.lower() > top]
            # drop candidates another candidate beats for sure
            cand = [k for k in cand
                    if not any(logc[k - 2].lower() > logc[j - 2].upper() for j in cand)]
        if len(cand) == 1:
            return (cand[0],), evals
        bits *= 2
    V_exact = _exact_V(sc)
    best_k = [cand[0]]
    for k in cand[1:]:
        s = _compare_c_exact(V_exact, best_k[0], k)  # sign of c_k - c_best
        if s < 0:
            best_k = [k]
        elif s == 0:
            best_k.append(k)
    return tuple(sorted(best_k)), evals


def _table(sc: SiteClasses, dps: int) -> DirectionCriticalPoint:
    N = sc.N
    classes = _classes(sc)
    e1 = sum((n * w for n, w in classes), Fraction(0))
    argmins, evals = _table_argmins(sc)
    k = argmins[0]
    p_exact = None
    if k == 2:
        p_exact = e1 / elementary_exact(classes, 2)  # c_2 = e_1 / (1! e_2)
    elif k * N.bit_length() < 2_000 and exact_table_bits(SiteClasses(sc.sizes, sc.values)) \
            <= _sw.EXACT_TABLE_BITS_LIMIT // 16:
        ck = e1 / (math.factorial(k - 1) * elementary_exact(classes, k))
        p_exact = _rational_root(ck, k - 1)
    if p_exact is not None:
        p, q, pb, qb = _exact_enclosure(p_exact, e1, dps)
    else:
        def sigma() -> arb:
            ek = elementary_ball(classes, k, _flint_prec())
            return (to_arb(e1).log() - ek.log() - to_arb(k).lgamma()) / (k - 1)

        p, q, pb, qb = _enclose(sigma, e1, dps, int(dps * 3.33) + 64)
    return DirectionCriticalPoint(
        N=N, p=p, q=q, k_before=1, k_after=argmins[-1], argmins=argmins, p_d=None,
        p_exact=p_exact, dps=dps, p_bounds=pb, q_bounds=qb, q_d=None, sign_evaluations=evals,
        weights=sc, method="table")


def _flint_prec() -> int:
    """flint's working precision in force (inside :func:`symhx.certify.arb_prec`)."""
    return int(flint_ctx.prec)


# --------------------------------------------------------------------------- perturbative
class _Perturbed:
    """``V(k) = Phi_{n,1}(k) A(k)`` for a large class of ``n`` sites (weight 1) and small
    sites of relative weights ``rho`` (classes), with the certified signs and bounds of the
    module docstring."""

    def __init__(self, n: int, small: list[tuple[int, Fraction]]) -> None:
        self.n = n
        self.small = small
        self.S = sum(m for m, _ in small)
        self.eJ = [elementary_exact(small, J) for J in range(self.S + 1)]
        self.evaluations = 0
        self.last: dict[int, arb] = {}
        self.memo: dict[tuple[str, int, int], arb] = {}

    def bits(self, k: int, extra: int = 0) -> int:
        """The precision of the lgamma terms (``G(n, k)`` cancels ``log2(n log n)`` bits)."""
        return bits_for(self.n, 3 * max(k, 2).bit_length() + 64 + extra)

    def fine(self) -> Any:
        """A block at the precision of the differences of ``A``: they cancel up to
        ``log2(n k)`` bits (no lgamma to pay for), and ``P`` must resolve ``E_n``'s steps of
        size ``~k/n``: ``2 log2 n`` plus the caller's margin bits."""
        return arb_prec(max(_flint_prec(), 3 * self.n.bit_length() + 128))

    def _memo(self, name: str, k: int, fn: Any) -> Any:
        key = (name, k, _flint_prec())
        got = self.memo.get(key)
        if got is None:
            got = self.memo[key] = fn()
        return got

    def _eJ_arb(self) -> list[arb]:
        return self._memo("eJ", 0, lambda: [to_arb(e) for e in self.eJ])

    def A1(self, k: int) -> arb:
        """``A(k) - 1 = sum_{J>=1} e_J(rho) falling(k, J) / rising(n - k + 1, J)``
        (``0 <= k <= n``), a sum of positive terms."""
        def value() -> arb:
            n = self.n
            eJ = self._eJ_arb()
            total = arb(0)
            x = arb(1)
            for J in range(1, min(self.S, k) + 1):
                x = x * (k - J + 1) / (n - k + J)
                total += eJ[J] * x
            return total

        return self._memo("A1", k, value)

    def B(self, k: int) -> arb:
        return self.A1(k).log1p()

    def P(self, k: int) -> arb:
        with self.fine():
            return (k - 1) * self.B(k + 1) - k * self.B(k) + self.B(1)

    def Pbound(self, k: int) -> arb:
        """An upper bound of ``|P(j)|`` for every ``2 <= j <= k`` (``k + 3 <= n``).

        ``P(j) = sum_{i=1}^{j-1} i D2B(i)`` with ``D2B(i) = log A(i+2) - 2 log A(i+1) +
        log A(i) = log1p(u_i)``, ``u_i = (A(i) D2A(i) - DA(i)**2) / A(i+1)**2``.  ``A >= 1`` has
        non-negative first, second and third differences on ``0..n`` (a sum of products of
        ``falling(k, J)`` and of ``1/(n - k + 1 + i)``, both with that property), so on a piece
        ``lo <= i <= hi``: ``|u_i| <= v = max(A(hi) D2A(hi), DA(hi)**2) / A(lo+1)**2`` and
        ``|D2B(i)| <= v/(1 - v)``; the pieces halve ``[1, k-1]`` from the top until ``A`` is
        within 1/8 of ``A(1)`` (a single piece at huge N)."""
        with self.fine():
            return self._pbound(k)

    def _pbound(self, k: int) -> arb:
        a_one = float(self.A1(1).mid())
        total = arb(0)
        hi = k - 1
        while hi >= 1:
            a_hi = self.A1(hi)
            lo = 1 if hi <= 8 or float(a_hi.mid()) - a_one < 0.125 else hi // 2
            a_hi1, a_hi2 = self.A1(hi + 1), self.A1(hi + 2)
            d1 = a_hi1 - a_hi
            d2 = a_hi2 - 2 * a_hi1 + a_hi
            den = 1 + self.A1(lo + 1)
            v = ((1 + a_hi) * d2).max(d1 * d1) / (den * den)
            weight = (hi * (hi + 1) - (lo - 1) * lo) // 2
            total += weight * v / (1 - v)
            hi = lo - 1
        return total

    def E_n(self, k: int) -> arb:
        """``E(k)`` of :mod:`symhx.critical` for ``n`` sites: the sign of ``c_{k+1} - c_k``."""
        def value() -> arb:
            kk = to_arb(k)
            return ((k - 1) * (1 / kk).log1p() - kk.log() + G_arb(self.n, k - 1)
                    - (k - 1) * (-kk / to_arb(self.n)).log1p())

        return self._memo("E_n", k, value)

    def E_w(self, k: int) -> arb:
        return self.E_n(k) - self.P(k)

    def s_n(self, k: int) -> arb:
        """``log(n c_k(n))`` of the large class alone."""
        return self._memo("s_n", k,
                          lambda: (to_arb(k).log() - G_arb(self.n, k - 1)) / (k - 1))

    def sigma(self, k: int) -> arb:
        """``log(n c_k)`` for ``2 <= k <= n`` (large-class weight 1)."""
        return self.s_n(k) + (self.B(1) - self.B(k)) / (k - 1)

    def D2_n(self, j: int) -> arb:
        jj = to_arb(j)
        return (jj * jj / (jj * jj - 1)).log() + (-1 / to_arb(self.n - j + 1)).log1p()

    def sign(self, fn: Any, k: int) -> int:
        """Certified sign of ``fn(k)``; the last ball is kept in :attr:`last` (for seeding)."""
        self.evaluations += 1
        start = self.bits(k)

        def ball() -> arb:
            x = self.last[k] = fn(k)
            return x

        return certified_sign(ball, start_bits=start, max_bits=16 * start)

    def positive(self, fn: Any, k: int | None = None, bits: int | None = None) -> bool:
        """Whether the ball ``fn()`` is certified > 0 (at the precision for ``k``, or
        ``bits``)."""
        self.evaluations += 1
        with arb_prec(bits or self.bits(k or 2)):
            return bool(fn() > 0)


#: at most this many k next to k* are checked one by one in the perturbative certificate
_MAX_SINGLE = 64


def _seed(n: int) -> int:
    """A guess (decides nothing) of the one-class argmin for ``n`` sites: the Lambert-W
    asymptotics ``k ~ sqrt(n v) - (ln n)/3``, ``v = -W_{-1}(-e**2/n)``, as in
    :mod:`symhx.critical`."""
    with arb_prec(n.bit_length() // 2 + 64):
        v = -(-arb.const_e() ** 2 / to_arb(n)).lambertw(branch=-1)
        z = (to_arb(n) * v).sqrt().mid().floor().unique_fmpz()
    k0 = int(z) if z is not None else 2
    return max(2, min(n // 8, k0 - int(math.log(n) / 3)))


def _reach(pt: _Perturbed, a: int, last: int) -> int:
    """A guess (floats, decides nothing) of the largest ``b <= last`` with
    ``Pbound(b) < E_n(a)``: ``Pbound`` grows about like ``b**2``."""
    with arb_prec(pt.bits(a)):
        e, pb = pt.E_n(a), pt.Pbound(a)
        if not (e > 0 and pb > 0):
            return a
        half_log = float((e / pb).log().mid()) / 2 + math.log(0.7)  # log(b / a)
    if half_log <= 0:
        return a
    if half_log >= math.log(last) - math.log(a):
        return last
    shift = half_log / math.log(2)  # b = a * 2**shift, in integers
    whole = int(shift)
    b = (a * int(2 ** (shift - whole) * 2**30)) << whole >> 30
    return max(a, min(last, b))


def _perturbative_argmin(pt: _Perturbed) -> int | None:
    """The certified argmin ``k*`` of ``c_k`` over ``2..N``, or ``None`` when the certificate
    does not close (the caller falls back to the table or refuses)."""
    n, S = pt.n, pt.S
    if n < 64:
        return None
    k = _seed(n)
    # local search: E_w(k-1) < 0 < E_w(k), secant steps on the ball midpoints
    for _ in range(_MAX_SINGLE):
        below = -1 if k == 2 else pt.sign(pt.E_w, k - 1)
        at = pt.sign(pt.E_w, k)
        if below < 0 < at:
            break
        new = k + 1 if at <= 0 else k - 1
        if k > 2:
            e0, e1 = pt.last[k - 1].mid(), pt.last[k].mid()
            if e1 != e0:
                with arb_prec(64 + 2 * k.bit_length()):
                    step = (arb(k - 1) - e0 / (e1 - e0)).mid().ceil().unique_fmpz()
                if step is not None and int(step) != k:
                    new = int(step)
        if not 2 <= new < n // 4:
            return None
        k = new
    else:
        return None
    K1 = n // 2
    if not k + 2 < K1:
        return None
    # (i) E_w < 0 on [2, k-2]: ranges [2, a] (E_n <= max(E_n(2), E_n(a)), |P| <= Pbound(a)),
    # the few k next to k* where the bound is too coarse by their own signs
    a = k - 2
    for _ in range(_MAX_SINGLE):
        if a < 2:
            break
        if pt.positive(lambda a=a: -(pt.E_n(2).max(pt.E_n(a)) + pt.Pbound(a)), a):
            break
        if pt.sign(pt.E_w, a) >= 0:
            return None
        a -= 1
    else:
        return None
    # (ii) E_n increasing from k+1 on, and E_w > 0 on [k+1, K1-1]: ranges [a, b] with
    # E_n(j) >= E_n(a) and |P(j)| <= Pbound(b), b placed where the bound should still hold
    if not pt.positive(lambda: -pt.D2_n(k + 2), k):
        return None
    a = k + 1
    for _ in range(4 * _MAX_SINGLE):
        if a >= K1 - 1:
            break
        if pt.positive(lambda a=a: pt.E_n(a) - pt.Pbound(K1 - 1), a):
            break
        b = _reach(pt, a, K1 - 1)
        while b > a and not pt.positive(lambda a=a, b=b: pt.E_n(a) - pt.Pbound(b), a):
            b = a + (b - a) // 4
        if b > a:
            a = b
            continue
        if pt.sign(pt.E_w, a) <= 0:
            return None
        a += 1
    else:
        return None
    # (iii) c_k > c_{k*} on [K1, n]:  s_n(K1) - log(prod(1 + rho n)) / (K1 - 1) > sigma(k*)
    def third() -> arb:
        lam = arb(0)
        for m, q in pt.small:
            lam += m * to_arb(1 + q * n).log()
        return pt.s_n(K1) - lam / (K1 - 1) - pt.sigma(k)

    coarse = bits_for(n, 96)  # (iii) and (iv) have margins of order 1
    if not pt.positive(third, bits=coarse):
        return None
    # (iv) each k > n by its own ball: log(n c_j) - sigma(k*) > 0
    e1_rel = 1 + Fraction(sum(m * q for m, q in pt.small), n)  # e_1 / n = A(1)
    for j in range(n + 1, n + S + 1):

        def fourth(j: int = j) -> arb:
            # (j-1)! e_j / w_big**j = (j-1)! sum_J e_J(rho) C(n, j - J), C(n, n - j + J) exact
            total = sum((pt.eJ[J] * math.comb(n, n - j + J) for J in range(j - n, S + 1)),
                        Fraction(0))
            logV = to_arb(j).lgamma() + to_arb(total).log()
            logc = (to_arb(e1_rel * n).log() - logV) / (j - 1)
            return logc + to_arb(n).log() - pt.sigma(k)

        if not pt.positive(fourth, bits=coarse):
            return None
    return k


def _perturbative(sc: SiteClasses, dps: int) -> DirectionCriticalPoint | None:
    split = short_sum_split(sc)
    if split is None:
        return None
    (n, wB), small = split
    rho = [(m, w / wB) for m, w in small]
    pt = _Perturbed(n, rho)
    try:
        k = _perturbative_argmin(pt)
    except UndecidedError:
        return None
    if k is None:
        return None
    e1 = n * wB + sum(m * w for m, w in small)
    N = sc.N
    start = bits_for(n, int(dps * 3.33) + 2 * k.bit_length() + 40)

    def sigma() -> arb:  # log t_c = log(n c_k') - log n - log w_B
        return pt.sigma(k) - to_arb(n).log() - to_arb(wB).log()

    p, q, pb, qb = _enclose(sigma, e1, dps, start)
    return DirectionCriticalPoint(
        N=N, p=p, q=q, k_before=1, k_after=k, argmins=(k,), p_d=None, p_exact=None, dps=dps,
        p_bounds=pb, q_bounds=qb, q_d=None, sign_evaluations=pt.evaluations, weights=sc,
        method="perturbative")


# --------------------------------------------------------------------------- public
def direction_critical_point(N: Any, weights: Any, *, dps: int = DEFAULT_DPS
                             ) -> DirectionCriticalPoint:
    """The critical point along the direction ``p_v = t w_v`` (simple circuits).

    Parameters
    ----------
    N : int
        Number of sites, ``N >= 2``.
    weights : SiteClasses or sequence
        The direction: a :class:`symhx.SiteClasses` of positive weights summing to ``N``
        sites, or a sequence of ``N`` per-site weights (exact, float or mpf; only ratios
        matter).
    dps : int
        Digits of ``t_c``, ``q`` and the width of ``p_bounds``.

    Returns
    -------
    DirectionCriticalPoint
        ``p = t_c = min_{k>=2} (e_1(w) / ((k-1)! e_k(w)))**(1/(k-1))``, ``k_after``, ``argmins``,
        ``p_bounds`` (Arb), ``p_exact`` when rational.

    Raises
    ------
    ValueError
        Bad ``N``, ``weights`` or ``dps``; several large classes with ``N`` above
        :data:`symhx.site_weights.BALL_TABLE_N_LIMIT`.
    UndecidedError
        An exact tie that integers too large to compare would be needed to settle.

    >>> cp = direction_critical_point(5, [1, 1, 1, 1, 1])     # N = 5: c_2 = c_3 = 1/2
    >>> cp.argmins, cp.p_exact, cp.method
    ((2, 3), Fraction(1, 2), 'one class')
    >>> cp = direction_critical_point(4, [1, 1, 2, 2])     # c_2 = 6/13 < c_3 = (1/4)**(1/2)
    >>> cp.argmins, cp.p_exact
    ((2,), Fraction(6, 13))
    """
    N = check_N(N)
    sc = as_site_classes(weights, N, "weights")
    d = check_dps(dps)
    assert d is not None
    if len(sc.merged()) == 1:
        return _one_class(N, sc, d)
    if N >= PERTURBATIVE_MIN_N:
        cp = _perturbative(sc, d)
        if cp is not None:
            return cp
    if N > _sw.BALL_TABLE_N_LIMIT:
        raise InputError(
            f"the critical point along {sc!r} at N={show_int(N)}: several large classes (more than "
            f"symhx.site_weights.MAX_SMALL_SITES = {_sw.MAX_SMALL_SITES} sites outside the largest "
            f"class), or small classes that are not a small perturbation of the large one, "
            f"are decided by a table of every k, limited to N <= "
            f"symhx.site_weights.BALL_TABLE_N_LIMIT = {_sw.BALL_TABLE_N_LIMIT}")
    return _table(sc, d)


# --------------------------------------------------------------------------- the curve
def _direction_pair(x: Any, i: int) -> tuple[Fraction, Fraction]:
    if isinstance(x, (str, bytes)) or not hasattr(x, "__len__") or len(x) != 2:
        raise TypeError(f"directions[{i}] must be a pair (w_1, w_2) of positive weights, got "
                        f"{type(x).__name__} {x!r}")
    out = []
    for j, v in enumerate(x):
        fr, _ = check_p(v, f"directions[{i}][{j}]")
        if fr is None:
            raise TypeError(f"directions[{i}][{j}] must be rational, float or mpf, got {v!r}")
        out.append(fr)
    return out[0], out[1]


@dataclass(frozen=True, repr=False)
class CriticalCurve:
    """The boundary in the plane ``(p_1, p_2)`` of two site classes where the mode of X leaves 1.

    Along each direction ``(w_1, w_2)`` the boundary point is ``t_c (w_1, w_2)``; the mode is 1
    strictly inside (towards the origin) and has jumped to ``k_after`` just outside.

    Attributes
    ----------
    N : int
    sizes : tuple of int
        The two class sizes.
    names : tuple of str or None
    dps : int
    points : tuple of DirectionCriticalPoint
        One per direction, in order.
    """

    N: int
    sizes: tuple[int, int]
    names: tuple[str, str] | None
    dps: int
    points: tuple[DirectionCriticalPoint, ...]
    _cache: dict = field(default_factory=dict, compare=False)

    @property
    def directions(self) -> tuple[tuple[Fraction, Fraction], ...]:
        """The directions ``(w_1, w_2)`` (exact)."""
        return tuple((cp.weights.values[0], cp.weights.values[1]) for cp in self.points)

    @property
    def p1(self) -> tuple[Any, ...]:
        """``t_c w_1`` of each point (mpf to ``dps`` digits)."""
        return tuple(self._coord(cp, 0) for cp in self.points)

    @property
    def p2(self) -> tuple[Any, ...]:
        """``t_c w_2`` of each point."""
        return tuple(self._coord(cp, 1) for cp in self.points)

    @property
    def k_after(self) -> tuple[int, ...]:
        """The mode just outside the curve at each point."""
        return tuple(cp.k_after for cp in self.points)

    def _coord(self, cp: DirectionCriticalPoint, i: int) -> Any:
        ctx = mp()
        w = cp.weights.values[i]
        with ctx.workdps(self.dps + 10):
            v = ctx.mpf(cp.p) * w.numerator / w.denominator
        with ctx.workdps(self.dps):
            return export(+v)

    def at(self, direction: Any) -> DirectionCriticalPoint:
        """The certified boundary point along any direction ``(w_1, w_2)``."""
        w1, w2 = _direction_pair(direction, 0)
        key = w1 / w2
        got = self._cache.get(key)
        if got is None:
            sc = SiteClasses(self.sizes, (w1, w2), self.names)
            got = self._cache[key] = direction_critical_point(self.N, sc, dps=self.dps)
        return got

    def as_rows(self) -> list[dict[str, Any]]:
        """One dict per point: direction, ``t_c``, its bounds, ``p_1``, ``p_2``, ``k_after``."""
        rows = []
        for cp, a, b in zip(self.points, self.p1, self.p2, strict=True):
            w1, w2 = cp.weights.values
            rows.append({"w1": w1, "w2": w2, "t_c": cp.p, "t_c_lo": cp.p_bounds[0],
                         "t_c_hi": cp.p_bounds[1], "p1": a, "p2": b, "k_after": cp.k_after,
                         "method": cp.method})
        return rows

    def __repr__(self) -> str:
        names = f", names={self.names!r}" if self.names else ""
        return (f"CriticalCurve(N={self.N}, sizes={self.sizes}{names}, "
                f"points={len(self.points)}, dps={self.dps})")


def critical_curve(N: Any, sizes: Sequence[Any], *, directions: Any = CURVE_DIRECTIONS,
                   names: Sequence[str] | None = None, dps: int = DEFAULT_DPS
                   ) -> CriticalCurve:
    """The certified critical curve of two site classes: in the plane ``(p_1, p_2)`` of their
    probabilities, where the mode of X leaves 1 (simple circuits).

    Parameters
    ----------
    N : int
        Number of sites, ``N >= 2``.
    sizes : pair of int
        The two class sizes (``(2, N - 2)`` for a row: walls and pipe pairs).
    directions : int or sequence of pairs
        ``m`` (default :data:`CURVE_DIRECTIONS`): the directions ``(m + 1 - j, j)``,
        ``j = 1..m`` (from mostly class 1 to mostly class 2); or explicit pairs
        ``(w_1, w_2)`` of positive weights.
    names : pair of str, optional
        Class names (``("wall", "pipe")``).
    dps : int
        Digits of every point.

    Returns
    -------
    CriticalCurve

    >>> curve = critical_curve(101, (2, 99), directions=3, dps=15)
    >>> curve.k_after                   # mostly walls ... mostly pipes (the middle: one class)
    (19, 20, 20)
    >>> [str(d) for d in curve.directions[0]]
    ['3', '1']
    """
    N = check_N(N)
    d = check_dps(dps)
    assert d is not None
    if isinstance(sizes, (str, bytes)) or not hasattr(sizes, "__len__") or len(sizes) != 2:
        raise TypeError(f"sizes must be a pair of positive ints (two classes), got "
                        f"{type(sizes).__name__} {sizes!r}")
    n1 = check_int(sizes[0], "sizes[0]", minimum=1)
    n2 = check_int(sizes[1], "sizes[1]", minimum=1)
    if n1 + n2 != N:
        raise InputError(f"sizes must add up to N = {show_int(N)}, got sizes=({n1}, {n2})")
    if isinstance(directions, bool):
        raise TypeError(f"directions must be an int or a sequence of pairs, got {directions!r}")
    if isinstance(directions, int):
        m = check_int(directions, "directions", minimum=1, maximum=10_000)
        pairs = [(Fraction(m + 1 - j), Fraction(j)) for j in range(1, m + 1)]
    else:
        if isinstance(directions, (str, bytes)) or not hasattr(directions, "__iter__"):
            raise TypeError(f"directions must be an int or a sequence of pairs, got "
                            f"{type(directions).__name__} {directions!r}")
        pairs = [_direction_pair(x, i) for i, x in enumerate(directions)]
        if not pairs:
            raise InputError("directions must hold at least one pair, got an empty sequence")
    names_t = None
    if names is not None:
        names_t = tuple(SiteClasses((1, 1), (1, 2), names).names or ())
    points = tuple(direction_critical_point(N, SiteClasses((n1, n2), w, names_t), dps=d)
                   for w in pairs)
    return CriticalCurve(N=N, sizes=(n1, n2), names=names_t,  # type: ignore[arg-type]
                         dps=d, points=points)
