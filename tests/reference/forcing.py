"""Independent references for the forcing layer: the closed form of eq. (27) written out in
mpmath (one component)."""

import mpmath


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
