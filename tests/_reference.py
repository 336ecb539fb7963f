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


def eq27_xy(sigma, sigma1, omega, Omega, d) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``x = d**2/(4 sigma**2)``, ``y = (d (omega**2 - Omega**2))**2/(4 sigma1**2)`` of one
    component (``sigma1 = None``: sigma; ``Omega = None``: sqrt 2), at the current precision."""
    s0, om, dd = mpmath.mpf(sigma), mpmath.mpf(omega), mpmath.mpf(d)
    s1 = s0 if sigma1 is None else mpmath.mpf(sigma1)
    om2 = 2 if Omega is None else mpmath.mpf(Omega) ** 2
    return dd * dd / (4 * s0 * s0), (dd * (om * om - om2)) ** 2 / (4 * s1 * s1)


def eq27_p(sigma, sigma1, omega, Omega, d) -> mpmath.mpf:
    """``p = P(R0 + R1 > d)`` of one component from the closed form of eq. (27), at the current
    mpmath precision."""
    return eq27_p_xy(*eq27_xy(sigma, sigma1, omega, Omega, d))


def eq27_p_xy(x, y) -> mpmath.mpf:
    """The closed form of eq. (27) from ``x`` and ``y``, written out (``r = sqrt(x + y)``,
    ``u = x/r``, ``v = y/r``), at the current mpmath precision."""
    r = mpmath.sqrt(x + y)
    u, v = x / r, y / r
    b = v * mpmath.exp(-u * u) + u * mpmath.exp(-v * v)
    b += mpmath.sqrt(mpmath.pi) * u * v * (mpmath.erf(u) + mpmath.erf(v))
    return mpmath.exp(-u * v) * b / r
