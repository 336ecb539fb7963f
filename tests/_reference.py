"""Independent reference computations for the tests (direct formulas, no symhx internals)."""

from fractions import Fraction
from math import factorial

import mpmath


def phi_exact(N: int, p: Fraction, k: int) -> Fraction:
    """Phi_{N,p}(k) straight from eq. (8) with factorials."""
    return Fraction(p) ** k * Fraction(factorial(N), k * factorial(N - k))


def pmf_table(N: int, p: Fraction) -> list[Fraction]:
    w = [phi_exact(N, p, k) for k in range(1, N + 1)]
    g = sum(w)
    return [x / g for x in w]


def brute_modes(N: int, p: Fraction) -> tuple[int, ...]:
    w = [phi_exact(N, p, k) for k in range(1, N + 1)]
    m = max(w)
    return tuple(k for k, x in zip(range(1, N + 1), w, strict=True) if x == m)


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
