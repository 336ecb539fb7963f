"""Independent references for c_k and the critical point (section 6): the definition with
loggamma at generous precision, an exhaustive scan over k, exact integer comparisons of c_k for
small N, the discriminant root in closed form, G(N, K) and Stirling's series by other routes,
and the large-N formulas and relaxation written out from their definitions."""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import mpmath

from tests.reference.combinatorics import bernoulli_numbers


def log_c_direct(N: int, k: int, dps: int) -> mpmath.mpf:
    """log(N c_k) from the definition with loggamma and generous guard digits."""
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        v = (mpmath.log(k) + mpmath.loggamma(N - k + 1) - mpmath.loggamma(N)) / (k - 1)
        return v + mpmath.log(N)


def critical_by_scan(N: int, dps: int) -> tuple[list[int], mpmath.mpf]:
    """Exhaustive scan over k = 2..N of c_k (definition), returning (argmins, p_c)."""
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        vals = [(log_c_direct(N, k, dps), k) for k in range(2, N + 1)]
        best = min(v for v, _ in vals)
        tol = mpmath.mpf(10) ** -(dps + 5)
        argmins = [k for v, k in vals if abs(v - best) <= tol * max(1, abs(best))]
        return argmins, mpmath.exp(best) / N


# ------------------------------------------------------------------ exact integers (small N)
def ck_power(N: int, k: int) -> Fraction:
    """``c_k**(k-1) = k (N-k)! / (N-1)!`` exactly (``2 <= k <= N``)."""
    return Fraction(k * math.factorial(N - k), math.factorial(N - 1))


def compare_c(N: int, j: int, k: int) -> int:
    """The exact sign of ``c_j - c_k``: both powers raised to the common exponent
    ``(j-1)(k-1)``, integers only (no logs, no balls)."""
    a, b = ck_power(N, j), ck_power(N, k)
    lhs = a.numerator ** (k - 1) * b.denominator ** (j - 1)
    rhs = b.numerator ** (j - 1) * a.denominator ** (k - 1)
    return (lhs > rhs) - (lhs < rhs)


def exact_argmins(N: int) -> list[int]:
    """Every argmin of ``c_k`` over ``2 <= k <= N`` by exact integer comparisons (a tie gives
    two; about a second at N = 400, so small N only)."""
    best = [2]
    for k in range(3, N + 1):
        s = compare_c(N, k, best[0])
        if s < 0:
            best = [k]
        elif s == 0:
            best.append(k)
    return best


#: :func:`is_first_argmin` decides exhaustively in integers up to this N
EXACT_ARGMIN_N = 200


def is_first_argmin(N: int, k: int) -> bool:
    """Whether ``k`` is the first integer argmin of ``c_j`` over ``2 <= j <= N``: exhaustively
    in exact integers for ``N <= EXACT_ARGMIN_N``, else ``c_{k-1} > c_k < c_{k+1}`` from the
    loggamma definition at digits that resolve the ``~1/k**2`` relative gaps (with the proved
    unimodality of ``c_k`` a strict local minimum is the argmin; beyond ``EXACT_ARGMIN_N`` the
    argmin is far from both ends, ``k ~ sqrt(N ln N)``, and an exact tie is not expected)."""
    if N <= EXACT_ARGMIN_N:
        return k == exact_argmins(N)[0]
    if not 2 < k < N:
        return False
    dps = 40 + 2 * len(str(k))
    a, b, c = (log_c_direct(N, j, dps) for j in (k - 1, k, k + 1))
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        return bool(a > b < c)


# ------------------------------------------------------------------ p_c, p_d at high precision
def p_c_direct(N: int, k: int, dps: int) -> mpmath.mpf:
    """``p_c = c_k`` at the argmin ``k`` from the loggamma definition at ``3 dps`` digits plus
    ``2 log10(N)`` guard digits (good to ~``10**-(3 dps)``)."""
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        return mpmath.exp(log_c_direct(N, k, 3 * dps)) / N


def p_d_closed(N: int, dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(p_d, N p_d - 1)`` of eq. (16), ``((1 + sqrt(N+1))/N)**2`` and ``2 (1 + sqrt(N+1))/N``,
    at ``dps`` digits plus ``2 log10(N)`` guard digits."""
    with mpmath.workdps(dps + 2 * len(str(N)) + 30):
        s = mpmath.sqrt(N + 1)
        return ((1 + s) / N) ** 2, 2 * (1 + s) / N


def last_breakpoint_k(N: int, k0: int, p_max: Fraction) -> int:
    """The last ``k >= k0`` whose mode-path breakpoint ``(k+1)/(k (N-k))`` is ``<= p_max``
    (``k0 - 1`` if none), by walking every k."""
    last = k0 - 1
    for k in range(k0, N):
        if Fraction(k + 1, k * (N - k)) <= p_max:
            last = k
    return last


# ------------------------------------------------------------------ G(N, K) and Stirling
def G_log1p_sum(N: int, K: int, dps: int) -> mpmath.mpf:
    """``G(N, K) = sum_{j=1}^{K} log1p(-j/N)`` term by term at ``dps`` digits (no loggamma)."""
    with mpmath.workdps(dps):
        return mpmath.fsum(mpmath.log1p(-mpmath.mpf(j) / N) for j in range(1, K + 1))


def G_exact_ratio(N: int, K: int, dps: int) -> mpmath.mpf:
    """``G(N, K)`` as the log of the exact rational ``(N-1)! / ((N-1-K)! N**K)`` at ``dps``
    digits (the integers are exact; only the final division and log round)."""
    num = math.perm(N - 1, K)
    with mpmath.workdps(dps):
        return mpmath.log(mpmath.mpf(num) / mpmath.mpf(N) ** K)


def G_loggamma(N: int, K: Any, dps: int) -> mpmath.mpf:
    """``G(N, K) = lgamma(N) - lgamma(N-K) - K log N`` for real ``K`` at ``dps`` digits plus
    ``2 log10(N)`` guard digits for the cancellation."""
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        K = mpmath.mpf(K)
        return mpmath.loggamma(N) - mpmath.loggamma(N - K) - K * mpmath.log(N)


def dG_digamma(N: int, K: Any, dps: int) -> mpmath.mpf:
    """``dG/dK = psi(N-K) - log N`` at ``dps`` digits plus guard digits."""
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        return mpmath.digamma(N - mpmath.mpf(K)) - mpmath.log(N)


def stirling_remainder(x: Any, *, derivative: bool = False) -> mpmath.mpf:
    """``S(x) = lgamma(x) - (x - 1/2) log x + x - log(2 pi)/2`` (or ``S'(x) = psi(x) - log x +
    1/(2x)``) at the current mpmath precision."""
    x = mpmath.mpf(x)
    if derivative:
        return mpmath.digamma(x) - mpmath.log(x) + 1 / (2 * x)
    return mpmath.loggamma(x) - (x - mpmath.mpf(1) / 2) * mpmath.log(x) + x \
        - mpmath.log(2 * mpmath.pi) / 2


def stirling_terms(x: Fraction, n: int, derivative: bool = False) -> list[Fraction]:
    """The first ``n`` terms of Stirling's series ``B_2r / (2r (2r-1) x**(2r-1))`` (or of its
    derivative, ``-B_2r / (2r x**(2r))``) exactly, from exact Bernoulli numbers."""
    B = bernoulli_numbers(2 * n)
    if derivative:
        return [-B[2 * m] / (2 * m) / x ** (2 * m) for m in range(1, n + 1)]
    return [B[2 * m] / (2 * m * (2 * m - 1)) / x ** (2 * m - 1) for m in range(1, n + 1)]


# ------------------------------------------------------------------ large-N asymptotics
def binom_half(j: int) -> Fraction:
    """``binom(1/2, j) = (-1)**(j+1) C(2j, j) / ((2j - 1) 4**j)`` (Catalan form)."""
    return Fraction((-1) ** (j + 1) * math.comb(2 * j, j), (2 * j - 1) * 4**j)


def relaxed_minimum(N: int, dps: int) -> tuple[mpmath.mpf, mpmath.mpf, Callable[[Any], Any]]:
    """``(kappa, q, h)``: the real minimiser ``kappa`` of the relaxation ``h(kappa) = (log kappa
    - G(kappa - 1)) / (kappa - 1)`` (loggamma / digamma at ``3 dps`` digits, ``findroot`` on
    ``K**2 h'``), ``q = expm1(h(kappa))`` and ``h`` itself (evaluate it inside a ``workdps`` of
    at least ``3 dps + 2 log10(N)`` digits)."""
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        Nm = mpmath.mpf(N)

        def G(K: Any) -> Any:
            return mpmath.loggamma(Nm) - mpmath.loggamma(Nm - K) - K * mpmath.log(Nm)

        def h(kap: Any) -> Any:
            K = kap - 1
            return (mpmath.log(kap) - G(K)) / K

        def dh(kap: Any) -> Any:  # K**2 h'(kappa)
            K = kap - 1
            dG = mpmath.digamma(Nm - K) - mpmath.log(Nm)
            return K * (1 / kap - dG) - (mpmath.log(kap) - G(K))

        k0 = mpmath.sqrt(Nm * mpmath.log(Nm))
        kap = mpmath.findroot(dh, (k0 / 3, 2 * k0), solver="anderson")
        return kap, mpmath.expm1(h(kap)), h


def asymptotic_formula(N: int, order: str, dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(k, q)`` of the formula orders ``"leading"``, ``"next"``, ``"lambert"``,
    ``"corrected"`` straight from their definitions at ``3 dps`` digits: the Lambert value from
    its defining equation ``v - ln v = ln N - 2`` (root above 1) solved by Newton, not
    ``lambertw``; the corrected k by a Newton step with a numerical derivative of
    ``h_2 = log k/(k-1) + k/(2N) + k(2k-1)/(12 N**2)``."""
    with mpmath.workdps(3 * dps + 20):
        Nm = mpmath.mpf(N)
        L = mpmath.log(Nm)
        lam = L - 2
        if order == "leading":
            return mpmath.sqrt(Nm * L), mpmath.sqrt(L / Nm)
        if order == "next":
            v = lam + mpmath.log(lam)
            return mpmath.sqrt(Nm * v), (v + 1) / mpmath.sqrt(Nm * v)
        w = L
        for _ in range(200):
            w = w - (w - mpmath.log(w) - lam) / (1 - 1 / w)
        k0 = mpmath.sqrt(Nm * w)
        if order == "lambert":
            return k0, mpmath.expm1(1 / k0 + k0 / Nm)
        if order != "corrected":
            raise ValueError(f"no formula reference for order {order!r}")

        def h2(k: Any) -> Any:
            return mpmath.log(k) / (k - 1) + k / (2 * Nm) + k * (2 * k - 1) / (12 * Nm**2)

        k1 = k0 - mpmath.diff(h2, k0) / ((2 * mpmath.log(k0) - 3) / k0**3)
        return k1, mpmath.expm1(h2(k0))


def asymptotic_k(N: int, order: str, dps: int) -> mpmath.mpf:
    """The real ``k`` of an order: the formula orders from :func:`asymptotic_formula`, the
    ``"relaxed"`` one the minimiser of :func:`relaxed_minimum`."""
    if order == "relaxed":
        return relaxed_minimum(N, dps)[0]
    return asymptotic_formula(N, order, dps)[0]
