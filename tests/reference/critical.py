"""Independent references for c_k and the critical point (section 6): the definition with
loggamma at generous precision, and an exhaustive scan over k."""

import mpmath


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
