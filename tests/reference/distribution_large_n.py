"""Independent references for the simple distribution at large N (not symhx.simple_sums):

* :func:`direct_sums` adds every term with mpmath (loggamma at twice the digits of N, then the
  exact ratio recurrence): any p, N up to ~1e5;
* :func:`poisson_side_sums` sums from the top, ``j = N - k``: ``Phi(N - j) / Phi(N)
  = (1/p)**j / j! * N / (N - j)`` (a Poisson weight), exact for every N when ``1/p`` is moderate
  (the terms beyond ``jmax`` are below the working precision);
* :func:`head_sums` sums the log-series head ``k = 1..K`` directly (any N, ``N p`` well below 1).

Each returns ``(S0, mean, var)`` of the whole distribution at ``dps`` digits (global mpmath).
"""

from __future__ import annotations

from fractions import Fraction

import mpmath


def critical_p(N: int) -> Fraction:
    """``p_c`` of N as the exact rational of its 80-digit value (the scale of the test grids
    ``p = r p_c``; symhx's certified critical point, not a reference value)."""
    import symhx
    from symhx.validation import mpf_to_fraction

    return mpf_to_fraction(symhx.critical_point(N, dps=80).p)


def _mp(p: Fraction) -> mpmath.mpf:
    return mpmath.mpf(p.numerator) / p.denominator


def direct_sums(N: int, p: Fraction, dps: int) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
    with mpmath.workdps(dps + 2 * len(str(N)) + 10):
        pm = _mp(p)
        return _term_by_term(N, pm, N * pm, N)  # from Phi(1) itself


def poisson_side_sums(N: int, p: Fraction, dps: int, jmax: int
                      ) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
    """``S0 = sum_j w_j`` with ``w_j = lam**j/j! * N/(N-j)``, ``lam = 1/p`` (relative to Phi(N))."""
    with mpmath.workdps(dps + 20):
        lam = 1 / _mp(p)
        ws = []
        t = mpmath.mpf(1)  # lam**j / j!
        for j in range(0, min(jmax, N - 1) + 1):
            ws.append(t * N / (N - j))
            t = t * lam / (j + 1)
        s0 = mpmath.fsum(ws)
        mj = mpmath.fsum(j * w for j, w in enumerate(ws)) / s0  # E[N - X]
        var = mpmath.fsum((j - mj) ** 2 * w for j, w in enumerate(ws)) / s0
        with mpmath.workdps(dps + 20 + len(str(N))):
            mean = N - mj
        return s0, mean, var


def head_sums(N: int, p: Fraction, dps: int, K: int) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
    """The first K terms from k = 1 (relative to Phi(1)), for N p well below 1."""
    with mpmath.workdps(dps + 20):
        return _term_by_term(N, _mp(p), mpmath.mpf(1), K)


def _term_by_term(N: int, pm: mpmath.mpf, f: mpmath.mpf, K: int
                  ) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
    """``(S0, mean, var)`` of the terms k = 1..K walked one by one from ``f`` (the k = 1 term)
    with the ratio Phi(k+1)/Phi(k) = p (N - k) k/(k + 1), at the caller's precision."""
    s0 = s1 = s2 = mpmath.mpf(0)
    for k in range(1, K + 1):
        s0 += f
        s1 += k * f
        s2 += k * k * f
        f = f * pm * (N - k) * k / (k + 1)
    mean = s1 / s0
    return s0, mean, s2 / s0 - mean * mean


def log_phi(N: int, p: Fraction, k: int, dps: int) -> mpmath.mpf:
    """``log Phi(k) = k log p + lgamma(N + 1) - lgamma(N - k + 1) - log k`` at ``dps`` digits
    *absolute* (mpmath's loggamma with the digits of ``N log N`` on top; not the Stirling
    series around a reference that :mod:`symhx.simple_sums` uses)."""
    extra = 2 * len(str(N)) + 20
    with mpmath.workdps(dps + extra):
        lp = mpmath.log(p.numerator) - mpmath.log(p.denominator)
        return k * lp + mpmath.loggamma(N + 1) - mpmath.loggamma(N - k + 1) - mpmath.log(k)


def log_phi_ratio(N: int, p: Fraction | float, x: mpmath.mpf | int, c: int,
                 digits: int | None = None) -> mpmath.mpf:
    """``log Phi(x) - log Phi(c)`` for a real ``x`` (``0 < x < N + 1``) from mpmath's loggamma
    at ``digits`` (default ``2 digits(N) + 80``) digits: the direct form, whose parts of size
    ``N log N`` cancel (not the saddle-point or Stirling forms of symhx)."""
    with mpmath.workdps(digits or 2 * len(str(N)) + 80):
        pm = _mp(p) if isinstance(p, Fraction) else mpmath.mpf(p)
        return (x - c) * mpmath.log(pm) + mpmath.loggamma(N + 1 - c) \
            - mpmath.loggamma(N + 1 - x) - mpmath.log(mpmath.mpf(x) / c)


def log_lower_sum_geometric(N: int, p: Fraction, k: int, dps: int) -> mpmath.mpf:
    """``log sum_{j <= k} Phi(j)`` for a ``k`` on the increasing stretch where the ratio
    ``Phi(j+1)/Phi(j) = p (N - j) j/(j + 1)`` stays well above 1 (``N p >= 2``, ``k`` far
    below the hump): the terms walked *down* from ``k`` by the exact ratio until they drop
    below ``10**-(dps+10)`` of the sum."""
    with mpmath.workdps(dps + 20):
        pm = mpmath.mpf(p.numerator) / p.denominator
        total, t, j = mpmath.mpf(1), mpmath.mpf(1), k  # relative to Phi(k)
        eps = mpmath.mpf(10) ** -(dps + 10)
        while j > 1:
            t = t / (pm * (N - (j - 1)) * (j - 1) / j)  # Phi(j-1)/Phi(k)
            total += t
            j -= 1
            if t < eps * total:
                break
    return log_phi(N, p, k, dps) + mpmath.log(total)


def log_upper_sum_walk(N: int, p: Fraction, k: int, dps: int) -> mpmath.mpf:
    """``log sum_{j > k} Phi(j)`` for a ``k`` beyond the hump where the terms fall fast
    (ratio ``p (N - j) j/(j + 1)`` well below 1): walked *up* from ``k + 1`` by the exact ratio
    until they drop below ``10**-(dps+10)`` of the sum (and :func:`log_phi` for the first)."""
    with mpmath.workdps(dps + 20):
        pm = mpmath.mpf(p.numerator) / p.denominator
        total, t, j = mpmath.mpf(1), mpmath.mpf(1), k + 1  # relative to Phi(k + 1)
        eps = mpmath.mpf(10) ** -(dps + 10)
        while j < N:
            t = t * pm * (N - j) * j / (j + 1)  # Phi(j+1)/Phi(k+1)
            total += t
            j += 1
            if t < eps * total:
                break
    return log_phi(N, p, k + 1, dps) + mpmath.log(total)


def log_series_tails(N: int, p: Fraction, k: int, dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(log P(X <= k), log P(X > k))`` from the log-series law ``P(X = j) ~ x**j / j``,
    ``x = N p < 1``: ``Phi(j) = x**j/j prod_{i<j} (1 - i/N)``, and the product is 1 to
    ``j**2/N``, below ``10**-dps`` for every term that matters when ``N >= 10**(dps + 14)`` and
    ``k <= 10**6`` (the terms past ``j ~ 10**6`` are below ``x**j``).  The upper tail is
    ``x**(k+1) lerchphi(x, 1, k + 1)``, the whole sum ``-log(1 - x)``."""
    with mpmath.workdps(dps + 20):
        x = mpmath.mpf(p.numerator) * N / p.denominator
        total = -mpmath.log1p(-x)
        log_up = (k + 1) * mpmath.log(x) + mpmath.log(mpmath.lerchphi(x, 1, k + 1))
        up = mpmath.exp(log_up)
        log_lo = mpmath.log(total - up) if up < total / 2 else \
            mpmath.log(mpmath.fsum(x**j / j for j in range(1, k + 1)))
        return log_lo - mpmath.log(total), log_up - mpmath.log(total)


def log_poisson_side_tails(N: int, p: Fraction, k: int, dps: int, jmax: int
                           ) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(log P(X <= k), log P(X > k))`` summed from the top, ``j = N - i``:
    ``Phi(N - j)/Phi(N) = lam**j/j! N/(N - j)``, ``lam = 1/p`` (exact for every N; the
    terms beyond ``jmax`` must be negligible), for ``N - jmax <= k < N``."""
    with mpmath.workdps(dps + 20):
        lam = 1 / (mpmath.mpf(p.numerator) / p.denominator)
        ws, t = [], mpmath.mpf(1)
        for j in range(0, min(jmax, N - 1) + 1):
            ws.append(t * N / (N - j))
            t = t * lam / (j + 1)
        J = N - k  # X > k  <=>  j < J
        up, lo = mpmath.fsum(ws[:J]), mpmath.fsum(ws[J:])
        tot = up + lo
        return mpmath.log(lo / tot), mpmath.log(up / tot)
