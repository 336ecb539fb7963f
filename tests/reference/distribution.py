"""Independent references for the simple distribution (eqs. 7-8): exact Fractions straight from
the factorials."""

from fractions import Fraction
from math import factorial


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
