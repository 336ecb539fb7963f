"""Large-N asymptotics of the jump: ``p_d`` as a series, ``p_c`` and ``k_jump`` at several orders.

Everything here is mpmath only (no sympy; the symbolic side of the same results lives in
:mod:`symhx.symbolic.asymptotic`, and the tests check that the two agree).

Notation. ``L = ln N``; ``q = N p - 1``. The jump happens at ``p_c = min_{k>=2} c_k`` and lands on
the minimiser ``k_jump`` (see :mod:`symhx.critical`), where

``log(N c_k) = h(k) = (log k - G(k-1)) / (k-1)``,  ``G(K) = lgamma(N) - lgamma(N-K) - K ln N``.

For ``1 << k << N``, ``-G(K)/K = (K+1)/(2N) + (K+1)(2K+1)/(12 N**2) + ...`` (key
``"log-Nc-expansion"`` of :func:`symhx.symbolic.derivations`), so
``h(k) = log k/k + k/(2N) + O(1/N)`` near the minimiser.

Orders of :func:`asymptotic_critical_point` (relative error of ``q``, measured by
:func:`error_table` against the certified solver :func:`symhx.critical_point`):

``"leading"``
    ``k = sqrt(N L)``, ``q = sqrt(L / N)``. Error ``~ (ln L - 1) / (2 L)``: *very* slow (still
    1.2 % at ``N = 10**100``).
``"next"``
    ``v = lam + ln lam`` with ``lam = L - 2`` (two terms of ``-W_{-1}(-e**2/N)``),
    ``k = sqrt(N v)``, ``q = 1/k + k/N = (v + 1)/sqrt(N v)``. Error ``~ ln(lam) / (2 lam**2)``
    (the omitted ``ln(lam)/lam`` of ``v``).
``"lambert"``
    the exact minimiser of the leading part ``log k/k + k/(2N)``: ``v = -W_{-1}(-e**2/N)``,
    ``k = sqrt(N v)`` (key ``"pc-lambert"``), ``q = expm1(1/k + k/N)``.
    Error ``O(sqrt(L / N))``.
``"corrected"``
    the Lambert point with first-order corrections: ``q = expm1(h_2(k_0))`` where
    ``h_2 = log k/(k-1) + k/(2N) + k(2k-1)/(12 N**2)`` (by the envelope theorem the shift of the
    minimiser only enters at second order) and one Newton step for ``k``. Error ``O(L / N)``.
``"relaxed"``
    the minimum over *real* ``k`` of the continuous relaxation of ``h`` (``Gamma`` for the
    factorials; key ``"crossing-relaxed"``), found with mpmath. Error ``O(1 / (N L))`` (the
    integer minimum lies at most half a step away, and ``h'' ~ L/k**3``).
``"best"`` (default)
    the relaxation evaluated at the two integers around its real minimiser, the smaller kept
    (``c_k`` is unimodal in ``k``, so this is the integer minimum): the error is limited only by
    the working precision. ``k`` is then an ``int``, *proved* to be the integer argmin (the
    relaxation only seeds :func:`symhx.critical.certified_argmin`: Arb-certified signs of
    ``c_{k+1} - c_k``, the larger k on an exact tie); ``q`` is not an enclosure (use
    :func:`symhx.critical_point` for ``p_bounds``).

``p_d`` (eq. 16) has the convergent series in ``eps = N**(-1/2)``
``p_d = eps**2 + 2 eps**3 + 2 eps**4 + 2 sum_{j>=1} binom(1/2, j) eps**(3+2j)``; :func:`pd_series`
returns a partial sum with a rigorous error bound.

>>> import symhx
>>> a, exact = asymptotic_critical_point(10**6), symhx.critical_point(10**6)
>>> a.order, a.k == exact.k_after, float(abs(a.q / exact.q - 1)) < 1e-40
('best', True, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import mpmath

from symhx._mpctx import export, local, mp
from symhx._numeric import digits_of, log1m_series, stirling_ok, stirling_series
from symhx.validation import InputError, check_choice, check_dps, check_int, check_N, show_exact

__all__ = [
    "MAX_FORMULA_DIGITS",
    "MAX_PD_TERMS",
    "MAX_RELAXED_DIGITS",
    "ORDERS",
    "AsymptoticCriticalPoint",
    "PdSeries",
    "asymptotic_critical_point",
    "error_table",
    "format_error_table",
    "pd_series",
    "pd_series_coefficients",
]

#: the available orders, from the crudest to the sharpest
ORDERS: tuple[str, ...] = ("leading", "next", "lambert", "corrected", "relaxed", "best")

#: smallest N for which the formulas are defined (W_{-1}(-e**2/N) is real for N >= e**3)
MIN_N = 21

#: how the relative error of q decays, per order (stated in the book and the error table)
DECAY: dict[str, str] = {
    "leading": "~ (ln ln N - 1) / (2 ln N)",
    "next": "~ ln(ln N - 2) / (2 (ln N - 2)^2)",
    "lambert": "O(sqrt(ln N / N))",
    "corrected": "O(ln N / N)",
    "relaxed": "O(1 / (N ln N))",
    "best": "exact to the working precision",
    "pd-series-5": "O(N^(-7/2)) relative (first omitted term N^(-9/2)/8)",
}


#: Work limits of :func:`asymptotic_critical_point`: the working precision carries every digit of
#: N (``k_int`` has ``log10(N)/2`` digits), and mpmath's cost grows faster than linearly with
#: it.  The closed-form orders (``"leading"``, ``"next"``, ``"lambert"``, ``"corrected"``) are
#: refused for ``N >= 10**MAX_FORMULA_DIGITS`` (measured on 2 shared cores: 10**20000 takes
#: 1-9 s, 10**100000 over 30 s); the relaxation (``"relaxed"``, ``"best"``, a root search) for
#: ``N >= 10**MAX_RELAXED_DIGITS`` (10**5000 takes 9 s, 10**10000 30 s).  Checked before any work.
MAX_FORMULA_DIGITS = 20_000
MAX_RELAXED_DIGITS = 5_000


def _check_N(N: Any) -> int:
    N = check_int(N, "N", minimum=2)
    if N < MIN_N:
        raise InputError(f"the asymptotic formulas need N >= {MIN_N}, got N={N}; "
                         "use symhx.critical_point for small N")
    return N


def _check_work(N: int, order: str) -> None:
    """Refuse, before any work, an ``N`` beyond the order's documented digit limit."""
    relaxed = order in ("relaxed", "best")
    limit, name = ((MAX_RELAXED_DIGITS, "MAX_RELAXED_DIGITS") if relaxed
                   else (MAX_FORMULA_DIGITS, "MAX_FORMULA_DIGITS"))
    if N >= 10**limit:
        raise InputError(
            f"N={show_exact(N)} is beyond the documented work limit of order={order!r}: "
            f"N < 10**{limit} (symhx.asymptotics.{name}; the working precision carries every "
            f"digit of N); raise that constant to allow it")


def _dps(dps: Any) -> int:
    d = check_dps(dps)
    assert d is not None
    return d


#: largest number of terms :func:`pd_series` accepts (the coefficients are exact Fractions)
MAX_PD_TERMS = 10_000


# ----------------------------------------------------------------------------- p_d series
def pd_series_coefficients(n_terms: int = 5) -> tuple[tuple[int, Fraction], ...]:
    """Exact coefficients of ``p_d = sum c * N**(-power/2)``: ``((power, c), ...)``.

    From ``p_d = (N + 2 + 2 sqrt(N+1)) / N**2`` and the binomial series of ``sqrt(1 + 1/N)``.

    >>> [(pw, str(c)) for pw, c in pd_series_coefficients(6)]
    [(2, '1'), (3, '2'), (4, '2'), (5, '1'), (7, '-1/4'), (9, '1/8')]
    """
    n_terms = check_int(n_terms, "n_terms", minimum=1, maximum=MAX_PD_TERMS,
                        limit="symhx.asymptotics.MAX_PD_TERMS")
    out: list[tuple[int, Fraction]] = [(2, Fraction(1)), (3, Fraction(2)), (4, Fraction(2))]
    j = 1
    while len(out) < n_terms:
        out.append((3 + 2 * j, 2 * _binom_half(j)))
        j += 1
    return tuple(out[:n_terms])


def _binom_half(j: int) -> Fraction:
    c = Fraction(1)
    for i in range(j):
        c *= (Fraction(1, 2) - i) / (i + 1)
    return c


@dataclass(frozen=True)
class PdSeries:
    """A partial sum of the ``p_d`` series with its rigorous error bound."""

    N: int
    n_terms: int
    value: mpmath.mpf
    bound: mpmath.mpf  #: ``|p_d - value| <= bound`` (for every ``N >= 1``)
    coefficients: tuple[tuple[int, Fraction], ...]


def pd_series(N: int, n_terms: int = 5, *, dps: int = 50) -> PdSeries:
    """``p_d`` (eq. 16) from the first ``n_terms`` terms of its series in ``N**(-1/2)``.

    The bound: the omitted terms of power ``>= 5`` form an alternating series with decreasing
    terms for ``N >= 1`` (binomial series of ``sqrt(1 + 1/N)``), so they are bounded by the
    first of them; omitted terms of power ``<= 4`` are added in full; the rounding of ``value``
    to ``dps`` digits is added too (it dominates when ``dps`` is small for the terms kept).

    Parameters
    ----------
    N : int
        Number of vertices, ``N >= 2`` (any size).
    n_terms : int
        Number of non-zero terms, ``1 <= n_terms <= MAX_PD_TERMS`` (5 gives error
        ``<= N**(-9/2)/8``).
    dps : int
        Working digits (``1 <= dps <= MAX_DPS``).

    Returns
    -------
    PdSeries

    >>> from symhx.critical import discriminant_root
    >>> s = pd_series(10**6)
    >>> mpmath.nstr(s.bound, 3), abs(s.value - discriminant_root(10**6)) <= s.bound
    ('1.25e-28', True)
    """
    N = check_N(N)
    n_terms = check_int(n_terms, "n_terms", minimum=1, maximum=MAX_PD_TERMS,
                        limit="symhx.asymptotics.MAX_PD_TERMS")
    dps = _dps(dps)
    coeffs = pd_series_coefficients(n_terms + 3)
    used, omitted = coeffs[:n_terms], coeffs[n_terms:]
    ctx = mp()
    with ctx.workdps(dps + 10):
        eps = 1 / ctx.sqrt(N)
        value = ctx.fsum(ctx.mpf(c.numerator) / c.denominator * eps**pw for pw, c in used)
        bound = ctx.mpf(0)
        for pw, c in omitted:
            bound += abs(ctx.mpf(c.numerator) / c.denominator) * eps**pw
            if pw >= 5:
                break
    with ctx.workdps(dps):
        rounded = +value
    with ctx.workdps(dps + 10):
        # the returned value is rounded to dps digits: that rounding (and a generous allowance
        # for the (dps+10)-digit sum) is part of |p_d - value|; the factor covers the rounding
        # of the bound itself to dps digits
        bound = (bound + abs(rounded - value) + abs(value) * ctx.mpf(10) ** -(dps + 5)) * (
            1 + ctx.mpf(10) ** (1 - dps))
    return PdSeries(N, n_terms, export(rounded), export(bound, dps), used)


# ------------------------------------------------------------------- the relaxation of h
class _Relaxation:
    """``h(kappa) = (log kappa - G(kappa - 1)) / (kappa - 1)`` for real ``kappa`` and its
    derivative, with ``G`` rewritten as ``N B(K/N) + log1p(-K/N)/2 + Stirling`` for large ``N``
    (no cancellation) and by ``loggamma`` with guard digits for small ``N``; in the calling
    thread's context at its working precision."""

    def __init__(self, N: int) -> None:
        self.N = N
        self.ctx = mp()

    def _series(self, K: mpmath.mpf) -> bool:
        # Stirling's series (400 terms) only where it reaches the working digits at N - K
        return stirling_ok(int(self.N - K), self.ctx.dps)

    def G(self, K: mpmath.mpf) -> mpmath.mpf:
        N, ctx = self.N, self.ctx
        if self._series(K):
            u = K / N
            return (N * log1m_series(u) + ctx.log1p(-u) / 2
                    + stirling_series(ctx.mpf(N)) - stirling_series(N - K))
        with ctx.extradps(digits_of(N) + 10):
            return ctx.loggamma(N) - ctx.loggamma(N - K) - K * ctx.log(N)

    def dG(self, K: mpmath.mpf) -> mpmath.mpf:
        N, ctx = self.N, self.ctx
        if self._series(K):  # psi(N-K) - log N with psi's asymptotic series
            x = N - K
            return ctx.log1p(-K / N) - 1 / (2 * x) + stirling_series(x, derivative=True)
        with ctx.extradps(digits_of(N) + 10):
            return ctx.digamma(N - K) - ctx.log(N)

    def h(self, kappa: mpmath.mpf) -> mpmath.mpf:
        K = kappa - 1
        return (self.ctx.log(kappa) - self.G(K)) / K

    def F(self, K: mpmath.mpf) -> mpmath.mpf:
        """``K**2 h'(K + 1)``: negative left of the minimiser, positive right of it."""
        kappa = K + 1
        return K * (1 / kappa - self.dG(K)) - (self.ctx.log(kappa) - self.G(K))


def _lambert_v(N: int) -> mpmath.mpf:
    ctx = mp()
    return -ctx.lambertw(-ctx.e**2 / N, -1).real


# -------------------------------------------------------------------------- public result
@dataclass(frozen=True)
class AsymptoticCriticalPoint:
    """Large-N approximation of the jump (see the module docstring for the orders).

    Attributes
    ----------
    N : int
    order : str
    p : mpf
        Approximate ``p_c``.
    q : mpf
        Approximate ``N p_c - 1`` (computed directly, no cancellation).
    k : mpf or int
        Approximate ``k_jump`` (real for the formula orders, an int for ``"best"``).
    k_int : int
        The integer nearest to ``k`` before ``k`` is rounded to ``dps`` digits (``k`` has about
        ``log10(N)/2`` integer digits, more than ``dps`` for large N); ``k`` itself for
        ``"best"``.
    dps : int
    decay : str
        How the relative error of ``q`` decays with N.
    """

    N: int
    order: str
    p: mpmath.mpf
    q: mpmath.mpf
    k: Any
    k_int: int
    dps: int
    decay: str

    def as_dict(self) -> dict[str, Any]:
        return {"N": self.N, "order": self.order, "p": self.p, "q": self.q, "k": self.k,
                "k_int": self.k_int, "dps": self.dps, "decay": self.decay}


def asymptotic_critical_point(N: int, *, order: str = "best",
                              dps: int = 50) -> AsymptoticCriticalPoint:
    """Large-N approximation of the critical point ``p_c`` and the jump target ``k_jump``.

    Parameters
    ----------
    N : int
        Number of vertices, ``N >= 21``; the work is done at ``dps + 15 + log10(N)`` digits, so
        the cost grows with the digits of N: ``N < 10**MAX_FORMULA_DIGITS`` (20000) for the
        closed-form orders, ``N < 10**MAX_RELAXED_DIGITS`` (5000) for ``"relaxed"`` and
        ``"best"`` (documented work limits, checked before any work).
    order : str
        One of ``"leading"``, ``"next"``, ``"lambert"``, ``"corrected"``, ``"relaxed"``,
        ``"best"`` (see the module docstring for the formulas and their errors).
    dps : int
        Working decimal digits.

    Returns
    -------
    AsymptoticCriticalPoint
        ``.p``, ``.q`` (= ``N p - 1``), ``.k``, ``.k_int``, ``.order``, ``.decay``.

    Raises
    ------
    ValueError
        ``N < 21``, an unknown ``order``, a bad ``dps``, or ``N`` beyond the work limit of the
        order (:data:`MAX_FORMULA_DIGITS`, :data:`MAX_RELAXED_DIGITS`).

    >>> a = asymptotic_critical_point(10**10, order="leading")
    >>> mpmath.nstr(a.q, 3), a.k_int
    ('4.8e-5', 479853)
    >>> b = asymptotic_critical_point(10**10, order="corrected")
    >>> mpmath.nstr(b.q, 8), b.k_int
    ('5.1240457e-5', 492057)
    """
    N = _check_N(N)
    order = check_choice(order, "order", ORDERS)
    dps = _dps(dps)
    _check_work(N, order)
    # k ~ sqrt(N ln N) has about log10(N)/2 integer digits: k_int (its nearest integer) and the
    # relaxation (which resolves k to well below one unit) need them all, hence log10(N) digits
    wdps = dps + 15 + digits_of(N)
    ctx = mp()
    with ctx.workdps(wdps):
        Nm = ctx.mpf(N)
        L = ctx.log(Nm)
        if order == "leading":
            k = ctx.sqrt(Nm * L)
            q = ctx.sqrt(L / Nm)
        elif order == "next":
            lam = L - 2
            v = lam + ctx.log(lam)
            k = ctx.sqrt(Nm * v)
            q = (v + 1) / k
        elif order in ("lambert", "corrected"):
            k = ctx.sqrt(Nm * _lambert_v(N))
            if order == "lambert":
                q = ctx.expm1(1 / k + k / Nm)
            else:
                h2 = ctx.log(k) / (k - 1) + k / (2 * Nm) + k * (2 * k - 1) / (12 * Nm**2)
                q = ctx.expm1(h2)
                lk = ctx.log(k)
                dh = ((k - 1) - (2 * k - 1) * lk) / (k**2 * (k - 1) ** 2) + (4 * k - 1) / (
                    12 * Nm**2)
                k = k - dh / ((2 * lk - 3) / k**3)
        else:
            rel = _Relaxation(N)
            K0 = ctx.sqrt(Nm * _lambert_v(N)) - 1
            lo, hi = K0 / 2, min(2 * K0, Nm - 2)
            while rel.F(lo) > 0:
                lo /= 2
            while rel.F(hi) < 0 and hi < N - 2:
                hi = min(2 * hi, Nm - 2)
            Kstar = ctx.findroot(rel.F, (lo, hi), solver="anderson")
            kappa = Kstar + 1
            if order == "relaxed":
                k = kappa
                q = ctx.expm1(rel.h(kappa))
            else:
                # c_k is unimodal in real k, so the integer argmin is floor(kappa) or the next
                # integer. The relaxation only seeds: the integer (an exact tie -> the larger)
                # is proved by the Arb-certified signs of c_{k+1} - c_k of the exact solver
                # (a value comparison at dps digits cannot resolve it: the two values agree
                # to ~2 log10(k) digits).
                from symhx.critical import certified_argmin

                kbest = certified_argmin(N, seed=max(2, int(ctx.ceil(kappa))))[-1]
                k = kbest
                q = ctx.expm1(rel.h(ctx.mpf(kbest)))
        p = (1 + q) / Nm
        k_int = k if isinstance(k, int) else int(ctx.nint(k))  # before k is cut to dps
    k_out = k if isinstance(k, int) else export(k, dps)
    return AsymptoticCriticalPoint(N=N, order=order, p=export(p, dps), q=export(q, dps),
                                   k=k_out, k_int=k_int, dps=dps, decay=DECAY[order])


# ----------------------------------------------------------------------------- error table
def _sequence(x: Any, name: str) -> tuple[Any, ...]:
    """The items of a list / tuple / array argument (a string is not a sequence of values)."""
    if hasattr(x, "ndim") and hasattr(x, "tolist"):  # a numpy array
        x = x.tolist() if x.ndim == 1 else None
    if not isinstance(x, (list, tuple, range)):
        raise TypeError(f"{name} must be a list or tuple, got {x!r:.60}")
    return tuple(x)


DEFAULT_NS: tuple[int, ...] = (10**3, 10**6, 10**10, 10**30, 10**100)


def error_table(Ns: tuple[int, ...] = DEFAULT_NS, *, dps: int = 120,
                orders: tuple[str, ...] = ORDERS, pd_terms: int = 5) -> list[dict[str, Any]]:
    """Relative errors of every formula against the exact (certified) solver.

    For each ``N`` and each order: the approximate ``q = N p_c - 1`` and ``k_jump``, the exact
    ones from :func:`symhx.critical_point`, and the relative errors; plus one row per ``N`` for
    the ``pd_terms``-term series of ``p_d`` against :func:`symhx.discriminant_root` (with its
    rigorous bound).

    Parameters
    ----------
    Ns : tuple of int
        Sizes (each ``>= 21``).
    dps : int
        Digits for both the approximations and the exact solver (errors below ``10**-dps`` are
        reported as that floor).
    orders : tuple of str
    pd_terms : int

    Returns
    -------
    list of dict
        Keys ``N``, ``formula``, ``quantity`` (``"q"`` or ``"p_d"``), ``approx``, ``exact``,
        ``rel_error``, ``k``, ``k_exact``, ``k_rel_error``, ``decay``, ``bound`` (p_d only).

    >>> rows = error_table((10**3,), dps=30, orders=("leading", "best"))
    >>> [(r["formula"], r["rel_error"] < 0.5) for r in rows]
    [('leading', True), ('best', True), ('pd-series-5', True)]
    """
    from symhx.critical import critical_point, discriminant_root

    dps = check_dps(dps)
    Ns = tuple(check_N(N, "each N of Ns") for N in _sequence(Ns, "Ns"))
    orders = tuple(check_choice(o, "each order of orders", ORDERS)
                   for o in _sequence(orders, "orders"))
    pd_terms = check_int(pd_terms, "pd_terms", minimum=1)
    rows: list[dict[str, Any]] = []
    ctx = mp()
    with ctx.workprec(53):  # errors below 10**-dps are reported as this float-sized floor
        floor = export(ctx.mpf(10) ** (-dps))
    for N in Ns:
        cp = critical_point(N, dps=dps)
        for order in orders:
            a = asymptotic_critical_point(N, order=order, dps=dps)
            with ctx.workdps(dps):
                err = max(abs(local(a.q) / local(cp.q) - 1), floor)
                kerr = abs(ctx.mpf(local(a.k)) / cp.k_after - 1)
            rows.append({"N": N, "formula": order, "quantity": "q", "approx": a.q,
                         "exact": cp.q, "rel_error": export(err), "k": a.k,
                         "k_exact": cp.k_after, "k_rel_error": export(kerr),
                         "decay": DECAY[order], "bound": None})
        s = pd_series(N, pd_terms, dps=dps)
        pdx = discriminant_root(N, dps=dps)
        with ctx.workdps(dps):
            err = max(abs(local(s.value) / local(pdx) - 1), floor)
            bound = local(s.bound) / local(pdx)
        rows.append({"N": N, "formula": f"pd-series-{pd_terms}", "quantity": "p_d",
                     "approx": s.value, "exact": pdx, "rel_error": export(err), "k": None,
                     "k_exact": None, "k_rel_error": None,
                     "decay": DECAY.get(f"pd-series-{pd_terms}", ""),
                     "bound": export(bound)})
    return rows


def format_error_table(rows: list[dict[str, Any]], *, digits: int = 3) -> str:
    """A Markdown table (``N`` down, formulas across) of the relative errors of ``q``/``p_d``.

    >>> print(format_error_table([{"N": 1000, "formula": "best", "rel_error": mpmath.mpf(0)}]))
    | N | best |
    |---|---|
    | 1e3 | 0 |
    """
    formulas = list(dict.fromkeys(r["formula"] for r in rows))
    Ns = list(dict.fromkeys(r["N"] for r in rows))
    cell = {(r["N"], r["formula"]): r["rel_error"] for r in rows}
    out = ["| N | " + " | ".join(formulas) + " |", "|---|" + "---|" * len(formulas)]
    for N in Ns:
        e = round(math.log10(N)) if N > 0 and 10 ** round(math.log10(N)) == N else None
        name = f"1e{e}" if e is not None else str(N)
        vals = []
        for f in formulas:
            v = cell.get((N, f))
            vals.append("" if v is None else (
                "0" if v == 0 else mp().nstr(v, digits)))
        out.append(f"| {name} | " + " | ".join(vals) + " |")
    return "\n".join(out)
