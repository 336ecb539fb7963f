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
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np
from mpmath import libmp

from symhx._mpctx import is_mpf
from symhx.validation import InputError, check_int, check_real, check_seed, to_rational

__all__ = ["MAX_EVENTS", "MAX_HORIZON", "MAX_PIPES", "MAX_SCALE", "SQRT2", "PipeRow",
           "SimulationError", "check_horizon", "check_pipes", "exact_to_mpf"]

#: documented work cap: rows of more than this many pipes are refused (every event scans the
#: ``n + 1`` sites: a row of 10**4 pipes already takes minutes per unit of time at sigma = 0.3).
MAX_PIPES = 10_000
#: documented work cap on a simulated time span ``t``: ``omega * t <= MAX_HORIZON`` (radians,
#: about 16,000 periods; a row of 3 pipes at sigma = 3 makes ~3.5 events per unit of time and a
#: row of 100 pipes ~100 times more, a million events take about a second in the C engine and
#: ``symhx simulate`` prints each one).  Longer spans are refused up front.
MAX_HORIZON = 10**5
#: the largest ``max_events`` of :func:`symhx.impact.simulate`, and its value when ``None`` (a
#: recorded history of 10**8 events needs about 5 GB).
MAX_EVENTS = 10**8
#: the float64 engine squares and multiplies amplitudes and frequencies: every input of a
#: :class:`PipeRow` must have ``|value| <= MAX_SCALE`` and the scales ``omega, d >= 1 / MAX_SCALE``
#: (a row scaled by 1e160 or 1e-200 silently lost all its impacts before this check).
MAX_SCALE = 1e100
#: draws of free-oscillation coefficients :meth:`PipeRow.random` may spend per pipe (in total,
#: over all redraws of the forcing) before it gives up with a ``ValueError``; each forcing gets
#: an equal share of them (``_DRAWS_PER_PIPE n / _FORCINGS``).
_DRAWS_PER_PIPE = 4_000
#: forcings :meth:`PipeRow.random` draws at most (the first one and up to 9 redraws).
_FORCINGS = 10


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
        # correctly rounded at ``prec`` bits by libmp with an explicit precision (thread-safe:
        # no context's precision is read or set; a square root at more bits rounded again to
        # ``prec`` would be a double rounding: wrong in the last bit at 1401 bits, for instance)
        return mpmath.mp.make_mpf(libmp.mpf_sqrt(libmp.from_int(2), prec, rounding))

    def __repr__(self) -> str:
        return "sqrt(2)"

    def __reduce__(self) -> str:  # pickles as the module-level singleton
        return "SQRT2"


SQRT2 = _Sqrt2()


class SimulationError(RuntimeError):
    """A run of the impact engines could not proceed; the message says why (and at which time).

    Raised instead of a bare ``RuntimeError`` so that ensembles can record the run as failed and
    go on.  ``max_events`` overruns raise it too.
    """


def check_horizon(t: Any, name: str, omega: float = 1.0, *, allow_zero: bool = False
                  ) -> Fraction:
    """A time span ``t`` (``> 0``, or ``>= 0`` with ``allow_zero``) as an exact ``Fraction``,
    refused up front when ``omega * t > MAX_HORIZON``.

    >>> check_horizon("2.5", "t_end")
    Fraction(5, 2)
    >>> check_horizon(1e7, "t_end")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    symhx.validation.InputError: t_end = 10000000.0 is too long: omega * t_end must be <= 100000 ...
    """
    fr = check_real(t, name, low=0, low_open=not allow_zero)
    if fr * Fraction(omega) > MAX_HORIZON:
        raise InputError(
            f"{name} = {t!r} is too long: omega * {name} must be <= {MAX_HORIZON} (about "
            f"{MAX_HORIZON // 6:,} periods; the work cap symhx.impact.model.MAX_HORIZON), got "
            f"omega = {omega!r}")
    return fr


def check_pipes(n: Any, name: str = "n") -> int:
    """A number of pipes: an int in ``[1, MAX_PIPES]``.

    >>> check_pipes(5)
    5
    """
    n = check_int(n, name, minimum=1)
    if n > MAX_PIPES:
        raise InputError(f"{name} must be <= {MAX_PIPES} pipes (the work cap "
                         f"symhx.impact.model.MAX_PIPES), got {n}")
    return n


def _check_scale(value: float, name: str, positive: bool = False) -> None:
    """``|value| <= MAX_SCALE`` (and ``>= 1 / MAX_SCALE`` for the positive scales)."""
    if abs(value) > MAX_SCALE or (positive and abs(value) < 1 / MAX_SCALE):
        rng = f"[{1 / MAX_SCALE:g}, {MAX_SCALE:g}]" if positive else f"<= {MAX_SCALE:g} in size"
        raise InputError(f"{name} = {value!r} is outside the range {rng} that the engines "
                         "resolve (symhx.impact.model.MAX_SCALE); rescale the units")


def _scalar(value: Any, name: str) -> tuple[float, Any]:
    """``(float64 value, exact value)`` of a scalar input: the exact value is a ``Fraction``
    (ints, decimal strings, Fractions, floats and mpf at their binary value, sympy Rationals) or
    the object itself for :data:`SQRT2` and sympy irrationals."""
    if isinstance(value, _Sqrt2):
        return float(value), value
    fr = to_rational(value, name)
    if fr is None:   # sympy irrational: its own evaluation (duck-typed; sympy is not imported)
        f = float(value)
        if not math.isfinite(f):
            raise InputError(f"{name} must be finite, got {value!r}")
        return f, value
    try:
        f = float(fr)
    except OverflowError:
        f = math.inf
    if not math.isfinite(f):
        raise InputError(f"{name} = {value!r} is beyond the float64 range")
    return f, fr


def exact_to_mpf(x: Any, ctx: Any = None) -> mpmath.mpf:
    """An exact value (``Fraction``, float, int, mpf, :data:`SQRT2`, sympy number) as an mpf of
    the mpmath context ``ctx``, correctly rounded at that context's current precision.

    symhx passes its thread's own context (``symhx._mpctx.mp()``, inside its ``workdps``), so
    the engines never read mpmath's global precision; ``ctx=None`` means mpmath's global
    context ``mpmath.mp``, for interactive use.

    >>> from fractions import Fraction
    >>> with mpmath.workdps(30):
    ...     print(exact_to_mpf(Fraction(1, 3)))
    0.333333333333333333333333333333
    """
    if ctx is None:
        ctx = mpmath.mp
    if isinstance(x, Fraction):   # one rounding (numerator and denominator may be huge)
        return ctx.make_mpf(libmp.from_rational(x.numerator, x.denominator, ctx.prec,
                                                libmp.round_nearest))
    if isinstance(x, (float, int)) or is_mpf(x) or hasattr(x, "_mpmath_"):
        return ctx.mpf(x)
    if hasattr(x, "evalf"):   # a sympy number (kept as the user gave it)
        return +ctx.mpf(x.evalf(ctx.dps + 10))
    return ctx.mpf(x)


def _array(value: Any, name: str, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray | None]:
    """``(float64 array, exact object array or None)``; ``None`` when the float64 array is the
    exact input (a float or int numpy array: the common, fast path)."""
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise TypeError(f"{name} must be an array of real numbers, got {value!r}")
    if isinstance(value, np.ndarray) and value.dtype.kind in "fiu":
        arr = np.array(value, dtype=np.float64)
        if arr.ndim == 1 and len(shape) == 2 and shape[1] == 1 and arr.shape == (shape[0],):
            arr = arr.reshape(shape)
        if arr.shape != shape:
            raise InputError(f"{name} must have shape {shape}, got {arr.shape}")
        if not np.all(np.isfinite(arr)):
            idx = tuple(int(i) for i in np.argwhere(~np.isfinite(arr))[0])
            raise InputError(f"{name} must be finite, got {arr[idx]!r} at index {idx}")
        if value.dtype.kind in "iu" and np.any(np.abs(value) > 2**53):
            return arr, np.vectorize(Fraction, otypes=[object])(value)
        return arr, None
    try:
        obj = np.empty(shape, dtype=object)
        src = np.array(value, dtype=object)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be an array of real numbers ({exc})") from None
    if src.ndim == 1 and len(shape) == 2 and shape[1] == 1 and src.shape == (shape[0],):
        src = src.reshape(shape)
    if src.shape != shape:
        raise InputError(f"{name} must have shape {shape}, got {src.shape}")
    arr = np.empty(shape, dtype=np.float64)
    for idx in np.ndindex(*shape):
        label = name + "".join(f"[{i}]" for i in idx)
        arr[idx], obj[idx] = _scalar(src[idx], label)
    return arr, obj


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
    ... # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    symhx.validation.InputError: Omega[0] = 1.0 equals omega = 1.0 (resonance): ... != omega
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
    _exact: dict = None  # type: ignore[assignment]

    def __init__(
        self,
        n: int,
        *,
        omega: Any = 1.0,
        d: Any = 1.0,
        restitution: Any,
        Omega: Sequence[Any] = (SQRT2,),
        alpha: Any,
        beta: Any,
        x0: Any,
        v0: Any,
    ) -> None:
        n = check_pipes(n)
        omega_f, omega_x = _scalar(omega, "omega")
        if not omega_f > 0:
            raise InputError(f"omega must be > 0, got {omega!r}")
        d_f, d_x = _scalar(d, "d")
        if not d_f > 0:
            raise InputError(f"d must be > 0, got {d!r}")
        r, r_x = _scalar(restitution, "restitution")
        if (isinstance(r_x, Fraction) and not 0 <= r_x <= 1) or not 0.0 <= r <= 1.0:
            raise InputError(f"restitution must lie in [0, 1], got {restitution!r}")
        if isinstance(Omega, (str, bytes)) or not isinstance(Omega, (Sequence, np.ndarray)):
            Omega = (Omega,)
        Omega = tuple(Omega)
        if len(Omega) < 1:
            raise InputError("Omega must hold at least one forcing frequency")
        Omega_x, Omega_f = [], []
        for i, w in enumerate(Omega):
            wf, wx = _scalar(w, f"Omega[{i}]")
            Omega_f.append(wf)
            if wf < 0:
                raise InputError(f"Omega[{i}] must be >= 0, got {w!r}")
            if wx == omega_x or abs(wf * wf - omega_f * omega_f) <= 1e-12 * omega_f * omega_f:
                raise InputError(
                    f"Omega[{i}] = {wf!r} equals omega = {omega_f!r} (resonance): the forced "
                    "response is unbounded; choose Omega[i] != omega"
                )
            Omega_x.append(wx)
        k = len(Omega)
        a, a_x = _array(alpha, "alpha", (n, k))
        b, b_x = _array(beta, "beta", (n, k))
        x, x_x = _array(x0, "x0", (n,))
        v, v_x = _array(v0, "v0", (n,))
        _check_scale(omega_f, "omega", positive=True)
        _check_scale(d_f, "d", positive=True)
        for name, arr in (("Omega", np.array(Omega_f)), ("alpha", a),
                          ("beta", b), ("v0", v)):
            if arr.size and np.max(np.abs(arr)) > MAX_SCALE:
                idx = tuple(int(i) for i in np.unravel_index(np.argmax(np.abs(arr)), arr.shape))
                _check_scale(float(arr[idx]), f"{name}{list(idx)}")
        # the right wall (n + 1) d <= (MAX_PIPES + 1) MAX_SCALE is finite in float64
        walls = np.concatenate(([0.0], x, [(n + 1) * d_f]))
        if not np.all(np.diff(walls) > 0):
            bad = int(np.argmin(np.diff(walls)))
            raise InputError(
                f"x0 must be strictly increasing inside (0, (n + 1) d) = (0, {(n + 1) * d_f!r}): "
                f"pipes overlap at site {bad}"
            )
        # Omega keeps the user's numbers (SQRT2 stays SQRT2); strings become their Fraction
        Omega = tuple(wx if isinstance(w, (str, bytes)) else w
                      for w, wx in zip(Omega, Omega_x, strict=True))
        for name, val in (("n", n), ("omega", omega_f), ("d", d_f), ("restitution", r),
                          ("Omega", Omega), ("alpha", a), ("beta", b), ("x0", x), ("v0", v)):
            object.__setattr__(self, name, val)
        for arr in (a, b, x, v):
            arr.setflags(write=False)
        object.__setattr__(self, "_exact", {
            "omega": omega_x, "d": d_x, "restitution": r_x, "Omega": tuple(Omega_x),
            "alpha": a_x, "beta": b_x, "x0": x_x, "v0": v_x})

    def exact(self, name: str) -> Any:
        """The exact value of parameter ``name`` as the user gave it: a ``Fraction`` (ints,
        decimal strings, floats and mpf at their binary value), :data:`SQRT2` or a sympy
        irrational; arrays come back as object arrays (the float64 arrays when those are exact).

        >>> row = PipeRow(1, restitution="0.5", alpha=[["0.1"]], beta=[[0]], x0=["0.3"], v0=[0])
        >>> row.exact("restitution"), row.exact("x0")[0], row.restitution
        (Fraction(1, 2), Fraction(3, 10), 0.5)
        """
        if name not in self._exact:
            raise InputError(f"name must be one of {sorted(self._exact)}, got {name!r}")
        val = self._exact[name]
        if val is None:
            return getattr(self, name)
        return val

    # ------------------------------------------------------------------ constructors
    @classmethod
    def random(
        cls,
        n: int,
        sigma: Any,
        *,
        seed: Any = None,
        restitution: Any = 0.8,
        omega: Any = 1.0,
        d: Any = 1.0,
        Omega: Sequence[Any] = (SQRT2,),
        sigma0: Any = None,
        max_redraws: int = 10_000,
    ) -> PipeRow:
        """A random row as in section 7: ``alpha_ij, beta_ij ~ N(0, sigma**2)`` independent.

        The free-oscillation coefficients ``alpha_0j, beta_0j`` (eq. 21) are ``N(0, sigma0**2)``
        (``sigma0 = sigma`` unless given) and define the start: ``x_j(0) = j d + alpha_0j +
        forced_j(0)``, ``v_j(0) = omega beta_0j + forced_j'(0)``.

        Non-overlap rule (documented choice; the paper does not say): the forcing is drawn once;
        then, in passes over the pipes from the left, pipe ``j``'s ``(alpha_0j, beta_0j)`` are
        redrawn (at most ``max_redraws`` times per pass) until ``x_{j-1}(0) < x_j(0) < (n + 1) d``
        (the last pipe also needs room before the right wall); a pipe that gets no place ends
        the pass and the next pass starts again from the left.  A forcing is given up after 100
        passes or ``min(20 max_redraws, 400 n)`` draws (its equal share of the ``4000 n`` draws
        in all; e.g. the forced displacements alone overlap near resonance), and the forcing is
        then drawn again: at most 10 forcings, then a ``ValueError`` says so (bounded work:
        about a second at worst).
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

        Raises
        ------
        ValueError
            for bad parameters, or when no non-overlapping row could be drawn (the message gives
            the displacement scale against ``d``).

        >>> row = PipeRow.random(5, 0.2, seed=1)
        >>> row.n, row.alpha.shape, bool(np.all(row.gap0() > 0))
        (5, (5, 1), True)
        """
        n = check_pipes(n)
        check_real(sigma, "sigma", low=0)   # range and type; the message names the input
        sig, _ = _scalar(sigma, "sigma")
        if sigma0 is not None:
            check_real(sigma0, "sigma0", low=0)
        sig0 = sig if sigma0 is None else _scalar(sigma0, "sigma0")[0]
        max_redraws = check_int(max_redraws, "max_redraws", minimum=1)
        if not isinstance(seed, (np.random.SeedSequence, np.random.Generator,
                                 np.random.BitGenerator)):
            seed = check_seed(seed)
        if isinstance(Omega, (str, bytes)) or not isinstance(Omega, (Sequence, np.ndarray)):
            Omega = (Omega,)
        Omega = tuple(Omega)
        om, _ = _scalar(omega, "omega")
        d_f, _ = _scalar(d, "d")
        if not om > 0:
            raise InputError(f"omega must be > 0, got {omega!r}")
        if not d_f > 0:
            raise InputError(f"d must be > 0, got {d!r}")
        _check_scale(om, "omega", positive=True)
        _check_scale(d_f, "d", positive=True)
        right = (n + 1) * d_f   # finite: d <= MAX_SCALE and n <= MAX_PIPES
        _scalar(restitution, "restitution")   # range checked by the constructor
        if len(Omega) < 1:
            raise InputError("Omega must hold at least one forcing frequency")
        Om = np.array([_scalar(w, f"Omega[{i}]")[0] for i, w in enumerate(Omega)])
        den = om * om - Om * Om
        if np.any(np.abs(den) <= 1e-12 * om * om):
            i = int(np.argmin(np.abs(den)))
            raise InputError(f"Omega[{i}] = {float(Om[i])!r} equals omega = {om!r} (resonance): "
                             "the forced response is unbounded; choose Omega[i] != omega")

        def too_large(scale: float) -> InputError:
            return InputError(
                f"could not draw non-overlapping initial positions: with sigma={sigma!r}, "
                f"sigma0={sigma0!r}, omega={omega!r}, Omega={Omega!r} the random displacements "
                f"(scale ~{scale:.3g}) are too large for the spacing d={d!r}; use a smaller "
                "sigma/sigma0, a larger d, or Omega further from omega")

        scale = sig * float(np.sum(1 / np.abs(den))) + sig0
        # refused up front: a pipe's start x_j(0) ~ N(j d + forced, sig0**2) must land in an
        # interval of width < (n + 1) d, which has probability < (n + 1) d / (sig0 sqrt(2 pi))
        # per draw; below 1e-3 the bounded redraws below would all but surely fail
        if sig0 > 0 and right / (sig0 * math.sqrt(2 * math.pi)) < 1e-3:
            raise too_large(scale)
        rng = np.random.default_rng(seed)
        k = len(Omega)
        x0 = np.empty(n)
        v0 = np.empty(n)
        # every forcing gets an equal share of the 4000 n draws: the redraws of the forcing that
        # the docstring promises do happen (a first forcing used to spend them all)
        share = min(20 * max_redraws, _DRAWS_PER_PIPE * n // _FORCINGS)
        ok = False
        for _forcing in range(_FORCINGS):
            alpha = rng.normal(0.0, sig, size=(n, k)) if sig > 0 else np.zeros((n, k))
            beta = rng.normal(0.0, sig, size=(n, k)) if sig > 0 else np.zeros((n, k))
            f0 = (alpha / den).sum(axis=1)            # forced part at t = 0
            fv0 = (beta * Om / den).sum(axis=1)       # its velocity at t = 0
            if not (np.all(np.isfinite(f0)) and np.all(np.isfinite(fv0))):
                raise too_large(scale)
            ok = False
            budget = share   # draws of this forcing: bounded work (~0.1 s) on failure
            for _attempt in range(100):
                prev = 0.0
                ok = True
                for j in range(n):
                    tries = min(max_redraws if sig0 > 0 else 1, budget)
                    for _ in range(tries):
                        budget -= 1
                        a0, b0 = (rng.normal(0.0, sig0, size=2) if sig0 > 0 else (0.0, 0.0))
                        xj = (j + 1) * d_f + a0 + f0[j]
                        if prev < xj < right:
                            break
                    else:
                        ok = False
                        break
                    x0[j] = xj
                    v0[j] = om * b0 + fv0[j]
                    prev = xj
                if ok or budget <= 0:
                    break
            if ok:
                break
        if not ok:
            raise too_large(scale)
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
