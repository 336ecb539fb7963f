"""The pipe-row model of section 7 of the paper (eqs. 17–21).

Pipe ``j = 1..n`` has equilibrium position ``j d`` and obeys (eqs. 19, 20)

    x_j'' + omega^2 (x_j - j d) = sum_i alpha_ij cos(Omega_i t) + beta_ij sin(Omega_i t)

between impacts.  The walls are "pipes" ``0`` and ``n + 1`` fixed at ``0`` and ``(n + 1) d``.  Site
(gap) ``i = 0..n`` is ``Delta_i = x_{i+1} - x_i`` (eq. 21); sites ``0`` and ``n`` are the walls.
A contact is ``Delta_i = 0``; at a contact Newton's restitution law with coefficient ``r`` acts
(equal masses: momentum kept, relative velocity multiplied by ``-r``).

Between impacts every pipe moves in closed form,

    x_j(t) = j d + A_j cos(omega t) + B_j sin(omega t)
             + sum_i (alpha_ij cos(Omega_i t) + beta_ij sin(Omega_i t)) / (omega^2 - Omega_i^2),

so every gap is a trigonometric polynomial in ``t`` with the frequencies ``omega, Omega_1, ...``
(eq. 21: ``A_j, B_j`` are the paper's free-oscillation coefficients ``alpha_0j, beta_0j``).
"""

from __future__ import annotations

import math
import operator
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np

__all__ = ["SQRT2", "PipeRow"]


class _Sqrt2:
    """The number sqrt(2), exact at whatever precision it is used (float or mpmath).

    >>> float(SQRT2) == math.sqrt(2)
    True
    >>> with mpmath.workdps(40):
    ...     print(mpmath.mpf(SQRT2))
    1.41421356237309504880168872420969807857
    """

    def __float__(self) -> float:
        return math.sqrt(2.0)

    def _mpmath_(self, prec: int, rounding: str) -> mpmath.mpf:
        with mpmath.workprec(prec + 10):
            v = mpmath.sqrt(2)
        return +v

    def __repr__(self) -> str:
        return "sqrt(2)"

    def __reduce__(self) -> str:  # pickles as the module-level singleton
        return "SQRT2"


SQRT2 = _Sqrt2()


def _finite_float(value: Any, name: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def _matrix(value: Any, name: str, n: int, k: int) -> np.ndarray:
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of real numbers") from None
    if arr.ndim == 1 and k == 1 and arr.shape[0] == n:
        arr = arr.reshape(n, 1)
    if arr.shape != (n, k):
        raise ValueError(f"{name} must have shape (n, len(Omega)) = ({n}, {k}), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite")
    return arr


def _vector(value: Any, name: str, n: int) -> np.ndarray:
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of real numbers") from None
    if arr.shape != (n,):
        raise ValueError(f"{name} must have length n = {n}, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite")
    return arr


@dataclass(frozen=True, eq=False)
class PipeRow:
    """A row of ``n`` pipes between two walls (eqs. 17–21), with its initial state.

    Parameters
    ----------
    n : int
        Number of pipes (``>= 1``); there are ``n + 1`` impact sites (gaps) ``0..n``.
    omega : float
        Natural frequency ``omega > 0`` (eq. 19).
    d : float
        Equilibrium spacing ``d > 0``; the walls sit at ``0`` and ``(n + 1) d``.
    restitution : float
        Newton's coefficient of restitution ``r`` in ``[0, 1]`` (``1``: elastic).
    Omega : sequence
        Forcing frequencies ``Omega_i >= 0`` (eq. 20), none equal to ``omega`` (resonance).
        Entries may be floats or exact numbers such as :data:`SQRT2` (the paper's choice), which
        the mpmath engine evaluates at its working precision.
    alpha, beta : array_like, shape ``(n, len(Omega))``
        ``alpha[j][i]``, ``beta[j][i]``: the cosine and sine amplitudes of component ``i`` of the
        force on pipe ``j + 1`` (eq. 20).
    x0, v0 : array_like, shape ``(n,)``
        Positions and velocities at ``t = 0`` (strictly inside ``(0, (n + 1) d)`` and strictly
        increasing: pipes may not overlap).

    Raises
    ------
    ValueError
        naming the argument for resonance, ``r`` outside ``[0, 1]``, ``n < 1``, overlapping initial
        positions, non-finite or wrongly shaped values.

    Examples
    --------
    >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[0.5], v0=[0.0])
    >>> row.gap0()
    array([0.5, 1.5])
    >>> PipeRow(1, restitution=1, Omega=(1.0,), alpha=[[0.0]], beta=[[0.0]], x0=[1], v0=[0])
    Traceback (most recent call last):
    ...
    ValueError: Omega[0] = 1.0 equals omega = 1.0 (resonance): the forced response is unbounded
    """

    n: int
    restitution: float
    alpha: np.ndarray
    beta: np.ndarray
    x0: np.ndarray
    v0: np.ndarray
    omega: float = 1.0
    d: float = 1.0
    Omega: tuple = (SQRT2,)

    def __init__(
        self,
        n: int,
        *,
        omega: float = 1.0,
        d: float = 1.0,
        restitution: float,
        Omega: Sequence[Any] = (SQRT2,),
        alpha: Any,
        beta: Any,
        x0: Any,
        v0: Any,
    ) -> None:
        try:
            n = operator.index(n)
        except TypeError:
            raise ValueError(f"n must be an integer, got {n!r}") from None
        if n < 1:
            raise ValueError(f"n must be >= 1, got {n}")
        omega_f = _finite_float(omega, "omega")
        if omega_f <= 0:
            raise ValueError(f"omega must be > 0, got {omega!r}")
        d_f = _finite_float(d, "d")
        if d_f <= 0:
            raise ValueError(f"d must be > 0, got {d!r}")
        r = _finite_float(restitution, "restitution")
        if not 0.0 <= r <= 1.0:
            raise ValueError(f"restitution must lie in [0, 1], got {restitution!r}")
        if isinstance(Omega, (str, bytes)) or not isinstance(Omega, Sequence):
            Omega = (Omega,)
        Omega = tuple(Omega)
        if len(Omega) < 1:
            raise ValueError("Omega must hold at least one forcing frequency")
        for i, w in enumerate(Omega):
            wf = _finite_float(w, f"Omega[{i}]")
            if wf < 0:
                raise ValueError(f"Omega[{i}] must be >= 0, got {w!r}")
            if abs(wf * wf - omega_f * omega_f) <= 1e-12 * omega_f * omega_f:
                raise ValueError(
                    f"Omega[{i}] = {wf!r} equals omega = {omega_f!r} (resonance): the forced "
                    "response is unbounded"
                )
        k = len(Omega)
        a = _matrix(alpha, "alpha", n, k)
        b = _matrix(beta, "beta", n, k)
        x = _vector(x0, "x0", n)
        v = _vector(v0, "v0", n)
        walls = np.concatenate(([0.0], x, [(n + 1) * d_f]))
        if not np.all(np.diff(walls) > 0):
            bad = int(np.argmin(np.diff(walls)))
            raise ValueError(
                f"x0 must be strictly increasing inside (0, {(n + 1) * d_f!r}): pipes overlap at "
                f"site {bad}"
            )
        for name, val in (("n", n), ("omega", omega_f), ("d", d_f), ("restitution", r),
                          ("Omega", Omega), ("alpha", a), ("beta", b), ("x0", x), ("v0", v)):
            object.__setattr__(self, name, val)
        for arr in (a, b, x, v):
            arr.setflags(write=False)

    # ------------------------------------------------------------------ constructors
    @classmethod
    def random(
        cls,
        n: int,
        sigma: float,
        *,
        seed: Any = None,
        restitution: float = 0.8,
        omega: float = 1.0,
        d: float = 1.0,
        Omega: Sequence[Any] = (SQRT2,),
        sigma0: float | None = None,
        max_redraws: int = 10_000,
    ) -> PipeRow:
        """A random row as in section 7: ``alpha_ij, beta_ij ~ N(0, sigma**2)`` independent.

        The free-oscillation coefficients ``alpha_0j, beta_0j`` (eq. 21) are ``N(0, sigma0**2)``
        (``sigma0 = sigma`` unless given) and define the start: ``x_j(0) = j d + alpha_0j +
        forced_j(0)``, ``v_j(0) = omega beta_0j + forced_j'(0)``.

        Non-overlap rule (documented choice; the paper does not say): the forcing is drawn once;
        then pipe by pipe from the left, pipe ``j``'s ``(alpha_0j, beta_0j)`` are redrawn until
        ``x_{j-1}(0) < x_j(0) < (n + 1) d`` (the last pipe also needs room before the right wall).
        The draw is a pure function of ``seed`` (anything ``numpy.random.default_rng`` accepts).

        Parameters
        ----------
        n, sigma : number of pipes, standard deviation of the forcing amplitudes.
        seed : seed of the generator.  restitution : ``r`` (default 0.8, an assumption: the
        paper's value is not given).  omega, d, Omega : as for :class:`PipeRow`.
        sigma0 : standard deviation of the free-oscillation coefficients (default ``sigma``).

        Returns
        -------
        PipeRow

        >>> row = PipeRow.random(5, 0.2, seed=1)
        >>> row.n, row.alpha.shape, bool(np.all(row.gap0() > 0))
        (5, (5, 1), True)
        """
        sig = _finite_float(sigma, "sigma")
        if sig < 0:
            raise ValueError(f"sigma must be >= 0, got {sigma!r}")
        sig0 = sig if sigma0 is None else _finite_float(sigma0, "sigma0")
        if sig0 < 0:
            raise ValueError(f"sigma0 must be >= 0, got {sigma0!r}")
        if isinstance(Omega, (str, bytes)) or not isinstance(Omega, Sequence):
            Omega = (Omega,)
        n = operator.index(n)
        if n < 1:
            raise ValueError(f"n must be >= 1, got {n}")
        rng = np.random.default_rng(seed)
        k = len(Omega)
        alpha = rng.normal(0.0, sig, size=(n, k)) if sig > 0 else np.zeros((n, k))
        beta = rng.normal(0.0, sig, size=(n, k)) if sig > 0 else np.zeros((n, k))
        om = float(omega)
        Om = np.array([float(w) for w in Omega])
        den = om * om - Om * Om
        if np.any(np.abs(den) <= 1e-12 * om * om):
            raise ValueError("Omega equals omega (resonance)")
        f0 = (alpha / den).sum(axis=1)            # forced part at t = 0
        fv0 = (beta * Om / den).sum(axis=1)       # its velocity at t = 0
        x0 = np.empty(n)
        v0 = np.empty(n)
        right = (n + 1) * float(d)
        for _attempt in range(100):
            prev = 0.0
            ok = True
            for j in range(n):
                for _ in range(max_redraws):
                    a0, b0 = (rng.normal(0.0, sig0, size=2) if sig0 > 0 else (0.0, 0.0))
                    xj = (j + 1) * float(d) + a0 + f0[j]
                    if prev < xj < right:
                        break
                else:
                    ok = False
                    break
                x0[j] = xj
                v0[j] = om * b0 + fv0[j]
                prev = xj
            if ok:
                break
        else:  # pragma: no cover - needs absurd sigma
            raise ValueError(f"could not draw non-overlapping initial positions for sigma={sigma}")
        return cls(n, omega=omega, d=d, restitution=restitution, Omega=Omega, alpha=alpha,
                   beta=beta, x0=x0, v0=v0)

    # ------------------------------------------------------------------ helpers
    def gap0(self) -> np.ndarray:
        """Initial gaps ``Delta_i(0)``, ``i = 0..n`` (float64)."""
        walls = np.concatenate(([0.0], self.x0, [(self.n + 1) * self.d]))
        return np.diff(walls)

    def omega_float(self) -> np.ndarray:
        """Forcing frequencies as float64."""
        return np.array([float(w) for w in self.Omega])

    def energy0(self) -> float:
        """Mechanical energy at ``t = 0`` of an unforced row (float64; used by tests)."""
        j = np.arange(1, self.n + 1) * self.d
        return float(0.5 * np.sum(self.v0**2) + 0.5 * self.omega**2 * np.sum((self.x0 - j) ** 2))
