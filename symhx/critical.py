"""The jump of the mode (section 6): the discriminant root p_d, the critical point p_c, and the
whole mode path k*(p), for any N (simple sample space).

Definitions (simple sample space, eq. 8): ``Phi_{N,p}(k) = p**k N! / (k (N-k)!)``. Then

* ``Phi(k+1) - Phi(k)`` has the sign of ``f_{N,p}(k) = -p k**2 + (N p - 1) k - 1`` (eqs. 9-10);
* ``Phi(k) / Phi(1) = (p / c_k)**(k-1)`` with ``c_k = (k (N-k)! / (N-1)!)**(1/(k-1))``, so the
  mode leaves 1 at ``p_c = min_{k >= 2} c_k`` and lands on the argmin (the largest one if two
  tie, since ``(p/p_c)**(k-1)`` then grows fastest for the larger k);
* ``p_d`` (eq. 16) is where ``f`` first gets real roots: an interior local maximum of ``Phi``
  appears there, but it is not yet global: ``p_c > p_d`` for ``N >= 4``.

Unimodality. ``s(k) = log(N c_k) = h(k)/(k-1)`` with ``h(k) = log k - G(k-1)``,
``G(K) = lgamma(N) - lgamma(N-K) - K log N``, ``h(1) = 0``: the slope of the chord of ``h`` from 1
to k. ``h''(k) = psi'(N-k+1) - 1/k**2`` is strictly increasing, so ``h`` is concave then convex;
the chord slope from the left end of such a function strictly decreases, then strictly increases.
Hence ``c_k`` is strictly unimodal in real k, and the integer argmin is the first ``k`` with
``c_{k+1} >= c_k``, i.e. with ``E(k) >= 0`` where

``E(k) = k (k-1) (s(k+1) - s(k)) = (k-1) log1p(1/k) - log k + G(k-1) - (k-1) log1p(-k/N)``

(no cancellation between the ``k log k`` terms). ``E`` changes sign once on the reals.

Certification (seed, then verify). The real zero of ``E`` is seeded by the Lambert-W asymptotics
(``k ~ sqrt(N v)``, ``v = -W_{-1}(-e**2/N)``) and refined by a few secant steps on the ball
midpoints; the integer ``k*`` is then *proved* by two signs, ``E(k*-1) < 0 <= E(k*)``, each an
Arb ball (python-flint) that excludes 0, the precision doubled until it does. A ball that still
contains 0 is settled exactly in integers
(``c_{k+1} > c_k  <=>  (k+1)**(k-1) (N-1)!/(N-k)! > k**k (N-k)**(k-1)``), which also detects exact
ties (e.g. ``N = 5``: ``c_2 = c_3 = 1/2``). No float guess is ever rounded into an answer, and k
is never scanned. ``p_c`` is returned with a rigorous Arb enclosure ``p_bounds`` of relative
width at most ``10**-dps``.

Degenerate small N: ``N = 2`` has ``p_c = 2`` (no jump for ``p`` in (0, 1]); ``N = 3`` has
``p_c = p_d = 1``; ``N = 5`` ties ``Phi(1) = Phi(2) = Phi(3)`` at ``p = 1/2``; for ``N <= 7`` the
jump lands on 2 or 3.

Limits. N may be any int (10**10000 takes about a second: the balls need ``~log2(N)`` bits
because ``lgamma(N)`` cancels); ``dps <= symhx.validation.MAX_DPS``; :func:`mode_path` lists at
most :data:`MAX_BREAKPOINTS` breakpoints (choose ``p_max`` accordingly for huge N).

>>> cp = critical_point(101, dps=20)
>>> cp.k_before, cp.k_after
(1, 20)
>>> mpmath.nstr(cp.p, 20)
'0.012889115326530578361'
>>> cp.p_bounds[0] <= cp.p <= cp.p_bounds[1]
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import mpmath
from flint import arb, fmpz
from mpmath import libmp

from symhx._mpctx import export, make_mpf, mp, prec_of_dps
from symhx.certify import (
    G_arb,
    UndecidedError,
    arb_prec,
    bits_for,
    certified_sign,
    mpf_bounds,
    rel_width_ok,
    to_arb,
)
from symhx.validation import (
    DEFAULT_DPS,
    InputError,
    as_fraction,
    check_dps,
    check_int,
    check_N,
    show_exact,
)

__all__ = [
    "MAX_BREAKPOINTS",
    "CriticalPoint",
    "ModePath",
    "argmin_certificate",
    "certified_argmin",
    "critical_point",
    "discriminant_root",
    "discriminant_root_q",
    "log_c",
    "mode_path",
]

#: exact integer fall-back is used only while the integers have at most this many bits
EXACT_BITS_LIMIT = 4_000_000

#: :func:`mode_path` refuses to list more breakpoints than this (lower ``p_max`` for huge N);
#: counted exactly by bisection before any is built. 10**5 take ~0.2 s, 10**6 ~3.5 s.
MAX_BREAKPOINTS = 100_000


def _dps(dps: Any) -> int:
    d = check_dps(dps)
    assert d is not None
    return d


def discriminant_root(N: int, *, dps: int = DEFAULT_DPS) -> mpmath.mpf:
    """``p_d = ((1 + sqrt(N + 1)) / N)**2`` (eq. 16): where ``f_{N,p}`` gets a double root.

    The other root of the discriminant, ``((1 - sqrt(N+1))/N)**2``, gives the double root at
    ``k < 0`` and is irrelevant. Computed to ``dps`` significant digits for any N.

    >>> discriminant_root(3)
    mpf('1.0')
    >>> mpmath.nstr(discriminant_root(100, dps=15), 15)
    '0.0122099751242242'
    """
    return _pd_qd(check_N(N), _dps(dps))[0]


def _pd_qd(N: int, dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(p_d, N p_d - 1)`` to ``dps`` digits: ``q_d = 2 (1 + sqrt(N+1)) / N`` (no cancellation)
    and ``p_d = (1 + q_d) / N``, as Arb balls rounded to nearest."""
    with arb_prec(int(dps * 3.33) + 40):
        q = 2 * (1 + to_arb(N + 1).sqrt()) / to_arb(N)
        p = (1 + q) / to_arb(N)
        return _mid_mpf(p, dps), _mid_mpf(q, dps)


def discriminant_root_q(N: int, *, dps: int = DEFAULT_DPS) -> mpmath.mpf:
    """``N p_d - 1 = (N + 2 + 2 sqrt(N + 1)) / N - 1 = 2 (1 + sqrt(N + 1)) / N`` to ``dps``
    digits (no cancellation).

    >>> mpmath.nstr(discriminant_root_q(10**100, dps=10), 10)
    '2.0e-50'
    """
    return _pd_qd(check_N(N), _dps(dps))[1]


def _s_arb(N: int, k: int) -> arb:
    """Ball of ``s(k) = log(N c_k) = (log k - G(k-1)) / (k-1)`` at the current precision."""
    return (to_arb(k).log() - G_arb(N, k - 1)) / (k - 1)


def log_c(N: int, k: int, *, dps: int = DEFAULT_DPS) -> mpmath.mpf:
    """``log(N c_k) = [log k - G(k-1)] / (k-1)`` with ``G(K) = lgamma(N) - lgamma(N-K) - K log N``.

    ``c_k = (k (N-k)!/(N-1)!)**(1/(k-1))`` is the p at which ``Phi(k) = Phi(1)``. Evaluated as an
    Arb ball whose precision is raised until it is correct to ``dps`` digits.

    >>> mpmath.nstr(log_c(5, 2, dps=10), 10), mpmath.nstr(mpmath.log(mpmath.mpf(5) / 2), 10)
    ('0.9162907319', '0.9162907319')
    """
    N = check_N(N)
    dps = _dps(dps)
    k = check_int(k, "k", minimum=2, maximum=N)
    bits = bits_for(N, int(dps * 3.33) + 20)
    while True:
        with arb_prec(bits):
            s = _s_arb(N, k)
        if rel_width_ok(s, dps + 2) or bits > 40 * bits_for(N, int(dps * 3.33) + 20):
            break
        bits *= 2
    return _mid_mpf(s, dps)


def _mid_mpf(x: arb, dps: int) -> mpmath.mpf:
    """The ball's midpoint rounded to ``dps`` digits (nearest), as a global mpf (libmp only:
    no mpmath context and no Arb rounding involved)."""
    man, exp = x.mid().man_exp()
    return make_mpf(libmp.from_man_exp(int(man), int(exp), prec_of_dps(dps), "n"))


# --------------------------------------------------------------------------- certified signs
def _E_arb(N: int, k: int) -> arb:
    """Ball of ``E(k) = k (k-1) (s(k+1) - s(k))`` (``2 <= k <= N-1``), same sign as
    ``c_{k+1} - c_k``."""
    kk = to_arb(k)
    return ((k - 1) * (1 / kk).log1p() - kk.log() + G_arb(N, k - 1)
            - (k - 1) * (-kk / to_arb(N)).log1p())


class _SignOracle:
    """Certified signs of ``c_{k+1} - c_k`` for one N (Arb balls, exact integers on a tie)."""

    def __init__(self, N: int) -> None:
        self.N = N
        self.evaluations = 0
        self.cache: dict[int, int] = {}
        self.values: dict[int, arb] = {}  # the last ball of E(k) (seeding only)

    def bits(self, k: int) -> int:
        return bits_for(self.N, 2 * k.bit_length() + 40)

    def _exact(self, k: int) -> int:
        N = self.N
        bits = k * (max(N, k + 1).bit_length() + 1)
        if bits > EXACT_BITS_LIMIT:
            raise UndecidedError(
                f"c_{k + 1} vs c_{k} for N={_fmt_int(N)}: balls did not separate and the "
                f"exact comparison needs ~{bits} bits"
            )
        lhs = fmpz(k + 1) ** (k - 1) * _perm(N - 1, k - 1)
        rhs = fmpz(k) ** k * fmpz(N - k) ** (k - 1)
        return (lhs > rhs) - (lhs < rhs)

    def sign(self, k: int) -> int:
        """Sign of ``c_{k+1} - c_k`` for ``2 <= k <= N - 1`` (``+1`` for ``k >= N``)."""
        if k >= self.N:
            return 1
        if k not in self.cache:
            self.evaluations += 1
            start = self.bits(k)

            def ball() -> arb:
                x = self.values[k] = _E_arb(self.N, k)
                return x

            self.cache[k] = certified_sign(ball, start_bits=start, max_bits=16 * start,
                                           exact_fn=lambda: self._exact(k))
        return self.cache[k]


def _perm(n: int, r: int) -> fmpz:
    """``n! / (n - r)!`` as an fmpz."""
    return fmpz(math.perm(n, r))


def _seed(N: int) -> int:
    """Approximate first argmin from the Lambert-W asymptotics: ``k ~ sqrt(N v) - (ln N)/3``
    with ``v = -W_{-1}(-e**2/N)`` (the ``-(ln N)/3`` shift was fitted on N = 10**2 .. 10**30;
    it only saves verification steps)."""
    if N < 25:
        return 2
    L = math.log(N)  # exact-enough for an int of any size (no float(N))
    if N.bit_length() <= 60:  # v in float64 is enough to place k ~ 2**32 within < 1
        v = L
        for _ in range(60):
            w, v = v, L - 2 + math.log(v)
            if abs(v - w) < 1e-12:
                break
        k0 = math.isqrt(N * int(v * 2**40)) >> 20
    else:
        with arb_prec(N.bit_length() // 2 + 64):
            vb = -(-arb.const_e() ** 2 / to_arb(N)).lambertw(branch=-1)
            k0 = _exact_int((to_arb(N) * vb).sqrt().mid().floor())
    return max(2, min(N, k0 - int(L / 3)))


def _exact_int(x: arb) -> int:
    """The integer value of an exact integer ball (a floor/ceil of a midpoint)."""
    z = x.unique_fmpz()
    assert z is not None
    return int(z)


def _frac(x: Any) -> Fraction:
    """An mpf / float as its exact binary Fraction."""
    fr = as_fraction(x)
    assert fr is not None
    return fr


def _argmin_c(N: int, seed: int | None = None) -> tuple[int, bool, int]:
    """(first integer argmin k* of c_k over 2..N, whether c_{k*+1} ties, sign evaluations)."""
    if N == 2:
        return 2, False, 0
    oracle = _SignOracle(N)
    k = _seed(N) if seed is None else max(2, min(N, seed))
    # verify E(k-1) < 0 <= E(k); a failed check moves k by a secant step on the ball midpoints
    for _ in range(6):
        below = -1 if k == 2 else oracle.sign(k - 1)
        at = oracle.sign(k)
        if below < 0 <= at:
            return k, at == 0, oracle.evaluations
        if k == 2 or k >= N - 1:
            break
        with arb_prec(64 + 2 * k.bit_length()):
            e0, e1 = oracle.values[k - 1].mid(), oracle.values[k].mid()
            new = k if e1 == e0 else _exact_int((to_arb(k - 1) - e0 / (e1 - e0)).mid().ceil())
        if new == k:
            new = k + 1 if at < 0 else k - 1
        k = max(2, min(N - 1, new))
    # fall back: gallop from k in the direction shown, then bisect (certified signs only)
    lo, hi = 2, N  # invariant: the answer lies in [lo, hi]
    if k > 2 and oracle.sign(k - 1) >= 0:  # the answer is below k
        hi, step = k - 1, 1
        while lo < hi:
            cand = max(lo, hi - step)
            if cand == lo or oracle.sign(cand - 1) < 0:
                lo = cand
                break
            hi, step = cand - 1, 2 * step
    elif oracle.sign(k) >= 0:  # proved: E(k-1) < 0 <= E(k)
        lo = hi = k
    else:  # the answer is above k
        lo, step = k + 1, 1
        while lo < hi:
            cand = min(hi, lo + step)
            if oracle.sign(cand) >= 0:
                hi = cand
                break
            lo, step = cand + 1, 2 * step
    while lo < hi:
        mid = (lo + hi) // 2
        if oracle.sign(mid) >= 0:
            hi = mid
        else:
            lo = mid + 1
    kstar = lo
    tie = kstar < N and oracle.sign(kstar) == 0
    return kstar, tie, oracle.evaluations


def certified_argmin(N: int, seed: int | None = None) -> tuple[int, ...]:
    """Every integer argmin of ``c_k`` over ``2 <= k <= N`` (two only at an exact tie), proved
    by Arb balls (exact integers on a tie), starting the verification at ``seed`` (a guess of
    the first argmin; a wrong guess only costs a few more certified signs).

    >>> certified_argmin(101, seed=25), certified_argmin(5)
    ((20,), (2, 3))
    """
    N = check_N(N)
    if seed is not None:
        seed = check_int(seed, "seed", minimum=2)
    kstar, tie, _ = _argmin_c(N, seed)
    return (kstar, kstar + 1) if tie else (kstar,)


def argmin_certificate(N: int, k: int) -> bool:
    """Whether ``k`` is *proved* (Arb balls, exact integers on ties) to be the first integer
    argmin of ``c_j`` over ``2 <= j <= N``: ``c_{k-1} > c_k <= c_{k+1}``. Used by the tests
    to show that a perturbed answer fails the certificate.

    >>> argmin_certificate(101, 20), argmin_certificate(101, 19), argmin_certificate(101, 21)
    (True, False, False)
    """
    N = check_N(N)
    k = check_int(k, "k", minimum=2, maximum=N)
    oracle = _SignOracle(N)
    return (k == 2 or oracle.sign(k - 1) < 0) and oracle.sign(k) >= 0


def _vp_factorial(n: int, p: int) -> int:
    """The exponent of the prime ``p`` in ``n!`` (Legendre: ``(n - digit sum_p(n)) / (p-1)``)."""
    total, m = 0, n
    while m:
        m //= p
        total += m
    return total


def _root_possible(N: int, k: int) -> bool:
    """Necessary condition for ``c_k = (k / perm(N-1, k-1))**(1/(k-1))`` to be rational: the
    exponents of 2, 3, 5 and 7 in ``k / perm(N-1, k-1)`` are multiples of ``k - 1``."""
    for p in (2, 3, 5, 7):
        vk, m = 0, k
        while m % p == 0:
            m //= p
            vk += 1
        vperm = _vp_factorial(N - 1, p) - _vp_factorial(N - k, p)
        if (vk - vperm) % (k - 1):
            return False
    return True


def _exact_root(a: Fraction, n: int) -> Fraction | None:
    """``a**(1/n)`` if it is rational, else None (only for moderately sized a)."""
    if n == 1:
        return a
    num, den = fmpz(a.numerator), fmpz(a.denominator)
    if max(num.bit_length(), den.bit_length()) > 20_000:  # pragma: no cover - gated by caller
        return None
    rn, rd = num.root(n), den.root(n)
    if rn**n == num and rd**n == den:
        return Fraction(int(rn), int(rd))
    return None


def _fmt_int(N: int) -> str:
    """``N`` for messages and reprs (no str() of ints beyond Python's digit limit): exact up to
    160 bits, else ``~d.dddde+E``, ``N`` correctly rounded to 15 significant digits (integer
    arithmetic: one rounding, half to even).

    >>> _fmt_int(95676649905087550000000000000004549377870619113110)
    '~9.56766499050876e+49'
    """
    if N.bit_length() <= 160:
        return str(N)
    e = int((N.bit_length() - 1) * 0.30102999566398120)  # floor(log10 N) or one below
    if N >= 10 ** (e + 1):
        e += 1
    scale = 10 ** (e - 14)
    q, r = divmod(N, scale)  # 10**14 <= q < 10**15
    if 2 * r > scale or (2 * r == scale and q % 2):
        q += 1
    if q == 10**15:
        q, e = 10**14, e + 1
    digits = str(q).rstrip("0")
    return f"~{digits[0]}.{digits[1:] or '0'}e+{e}"


@dataclass(frozen=True, repr=False)
class CriticalPoint:
    """Where the mode of X leaves 1 (simple sample space, or a higher-order space).

    Attributes
    ----------
    N : int
        Number of vertices (possible impacts), ``N = n_pipes + 1``.
    p : mpf
        ``p_c = min_{k>=2} c_k`` to ``dps`` digits (may exceed 1: ``N = 2`` gives 2).
    q : mpf
        ``N p_c - 1`` to ``dps`` digits, computed without cancellation (distinguishes ``p_c``
        from ``p_d`` at huge N, where both round to ``1/N``).
    k_before, k_after : int
        The mode just below ``p_c`` (always 1) and just above it (the largest tied argmin).
    argmins : tuple of int
        Every k with ``c_k = p_c`` (two only at an exact tie, e.g. ``N = 5``).
    p_d : mpf
        The simple space's discriminant root (eq. 16), for comparison; ``p_d <= p_c``.
    p_exact : Fraction or None
        ``p_c`` exactly when it is rational (e.g. whenever the argmin is 2: ``2/(N-1)``).
    dps : int
        Digits requested.
    p_bounds : tuple of mpf
        ``(lo, hi)``, a rigorous (Arb ball) enclosure of ``p_c``, ``(hi - lo) / p_c <= 10**-dps``.
    q_bounds : tuple of mpf
        The same for ``q``.
    q_d : mpf
        ``N p_d - 1`` to ``dps`` digits.
    """

    N: int
    p: mpmath.mpf
    q: mpmath.mpf
    k_before: int
    k_after: int
    argmins: tuple[int, ...]
    p_d: mpmath.mpf
    p_exact: Fraction | None
    dps: int
    p_bounds: tuple[mpmath.mpf, mpmath.mpf]
    q_bounds: tuple[mpmath.mpf, mpmath.mpf]
    q_d: mpmath.mpf
    sign_evaluations: int = field(default=0, compare=False)

    @property
    def jump(self) -> int:
        """Size of the jump of the mode, ``k_after - k_before``."""
        return self.k_after - self.k_before

    def _s(self, x: mpmath.mpf) -> str:
        return str(mp().nstr(x, self.dps))

    def __repr__(self) -> str:
        lo, hi = self.p_bounds
        args = ", ".join(_fmt_int(k) for k in self.argmins)
        return (f"CriticalPoint(N={_fmt_int(self.N)}, p_c={self._s(self.p)}, "
                f"q=N*p_c-1={self._s(self.q)}, k_before={self.k_before}, "
                f"k_after={_fmt_int(self.k_after)}, "
                f"argmins=({args}{',' if len(self.argmins) == 1 else ''}), "
                f"p_d={self._s(self.p_d)}, "
                f"q_d=N*p_d-1={self._s(self.q_d)}, p_exact={self.p_exact}, "
                f"p_bounds=({self._s(lo)}, {self._s(hi)}), dps={self.dps})")

    def __str__(self) -> str:
        lo, hi = self.p_bounds
        lines = [f"critical point, N = {_fmt_int(self.N)} ({self.dps} digits)",
                 f"  p_c         = {self._s(self.p)}"
                 + (f"  (= {self.p_exact})" if self.p_exact is not None else ""),
                 f"  N p_c - 1   = {self._s(self.q)}",
                 f"  p_c in        [{self._s(lo)}, {self._s(hi)}]  (Arb ball)",
                 f"  p_d         = {self._s(self.p_d)}",
                 f"  N p_d - 1   = {self._s(self.q_d)}",
                 f"  mode jumps  {self.k_before} -> {_fmt_int(self.k_after)}"
                 f"  (argmins {', '.join(_fmt_int(k) for k in self.argmins)})"]
        return "\n".join(lines)

    def as_dict(self) -> dict[str, Any]:
        """Plain dict (mpf values; ``p_c_lo``/``p_c_hi`` the certified enclosure)."""
        return {
            "N": self.N,
            "p_c": self.p,
            "N_p_c_minus_1": self.q,
            "k_before": self.k_before,
            "k_after": self.k_after,
            "argmins": list(self.argmins),
            "p_d": self.p_d,
            "N_p_d_minus_1": self.q_d,
            "p_c_exact": self.p_exact,
            "p_c_lo": self.p_bounds[0],
            "p_c_hi": self.p_bounds[1],
            "dps": self.dps,
        }


def enclose_from_s(N: int, s_fn: Any, dps: int, start_bits: int
                   ) -> tuple[mpmath.mpf, mpmath.mpf, tuple[Any, Any], tuple[Any, Any]]:
    """From a ball function ``s_fn()`` of ``s = log(N p)``: ``(p, q, p_bounds, q_bounds)`` with
    ``p = e**s / N`` and ``q = expm1(s)`` to ``dps`` digits, the precision doubled until both
    balls have relative width below ``10**-dps / 4``."""
    bits = max(64, start_bits)
    for _ in range(12):
        with arb_prec(bits):
            s = s_fn()
            p, q = s.exp() / to_arb(N), s.expm1()
        if rel_width_ok(p, dps) and rel_width_ok(q, dps):
            break
        bits *= 2
    else:  # pragma: no cover - q = 0 cannot happen for N >= 2
        raise UndecidedError(f"could not enclose p_c to {dps} digits (N={_fmt_int(N)})")
    pm, qm = _mid_mpf(p, dps), _mid_mpf(q, dps)
    return pm, qm, _hull(mpf_bounds(p, dps), pm), _hull(mpf_bounds(q, dps), qm)


def _hull(b: tuple[Any, Any], x: mpmath.mpf) -> tuple[Any, Any]:
    """The enclosure ``b`` widened to contain the rounded value ``x`` (so ``lo <= x <= hi``)."""
    return (min(b[0], x), max(b[1], x))


def exact_enclosure(N: int, a: Fraction, dps: int
                    ) -> tuple[mpmath.mpf, mpmath.mpf, tuple[Any, Any], tuple[Any, Any]]:
    """``(p, q, p_bounds, q_bounds)`` for an exact rational ``p_c = a``."""
    ctx = mp()
    with ctx.workdps(dps):
        p = export(ctx.mpf(a.numerator) / a.denominator)
        q = export(ctx.mpf(N * a.numerator - a.denominator) / a.denominator)
    bits = int(dps * 3.33) + 64
    with arb_prec(bits):
        pb = mpf_bounds(to_arb(a), dps)
        qb = mpf_bounds(to_arb(N * a - 1), dps)
    return p, q, _hull(pb, p), _hull(qb, q)


def critical_point(N: int, *, dps: int = DEFAULT_DPS) -> CriticalPoint:
    """The critical probability ``p_c`` at which the mode of X (simple space) jumps away from 1.

    For the higher-order sample spaces see :func:`symhx.spaces.critical_point`.

    Parameters
    ----------
    N : int
        Number of vertices (``N = n + 1`` for ``n`` pipes), any ``N >= 2`` (tested to
        10**10000; the cost is a handful of Arb evaluations at ``~log2(N) + 2 log2(k)`` bits).
    dps : int
        Significant decimal digits of ``p``, ``q``, ``p_d`` and the width of ``p_bounds``
        (``1 <= dps <= MAX_DPS``).

    Returns
    -------
    CriticalPoint

    >>> cp = critical_point(5)
    >>> cp.argmins, cp.k_after, cp.p_exact
    ((2, 3), 3, Fraction(1, 2))
    >>> critical_point(2).p
    mpf('2.0')
    """
    N = check_N(N)
    dps = _dps(dps)
    kstar, tie, evals = _argmin_c(N)
    argmins = (kstar, kstar + 1) if tie else (kstar,)
    p_d, q_d = _pd_qd(N, dps)
    a = None
    if kstar == 2 or (kstar * N.bit_length() < 20_000 and _root_possible(N, kstar)):
        a = _exact_root(Fraction(kstar, int(_perm(N - 1, kstar - 1))), kstar - 1)
    if a is not None:
        p, q, pb, qb = exact_enclosure(N, a, dps)
    else:
        start = bits_for(N, int(dps * 3.33) + 2 * kstar.bit_length() + 20) - kstar.bit_length()
        p, q, pb, qb = enclose_from_s(N, lambda: _s_arb(N, kstar), dps, start)
    return CriticalPoint(
        N=N, p=p, q=q, k_before=1, k_after=argmins[-1], argmins=argmins,
        p_d=p_d, p_exact=a, dps=dps, p_bounds=pb, q_bounds=qb, q_d=q_d,
        sign_evaluations=evals,
    )


def compare_with_critical(cp: CriticalPoint, fr: Fraction) -> int:
    """Certified sign of ``fr - p_c`` for a rational ``fr`` (simple space): Arb balls of
    ``(k-1) log(N fr) - (k-1) s(k)``, exact integers on a tie."""
    if cp.p_exact is not None:
        return (fr > cp.p_exact) - (fr < cp.p_exact)
    lo, hi = cp.p_bounds
    if fr < _frac(lo):
        return -1
    if fr > _frac(hi):
        return 1
    N, k = cp.N, cp.argmins[0]

    def ball() -> arb:
        # (k-1) log(N fr) - (log k - G(k-1)) = log(fr**(k-1) perm(N-1, k-1) / k)
        return (k - 1) * (to_arb(fr) * to_arb(N)).log() - to_arb(k).log() + G_arb(N, k - 1)

    def exact() -> int:
        if k * (N.bit_length() + fr.numerator.bit_length() + fr.denominator.bit_length()) \
                > EXACT_BITS_LIMIT:
            raise UndecidedError(f"p={show_exact(fr)} vs p_c for N={_fmt_int(N)}: exact "
                                 f"comparison too big")
        lhs = fmpz(fr.numerator) ** (k - 1) * _perm(N - 1, k - 1)
        rhs = k * fmpz(fr.denominator) ** (k - 1)
        return (lhs > rhs) - (lhs < rhs)

    start = bits_for(N, int(cp.dps * 3.33) + 2 * k.bit_length() + 40)
    return certified_sign(ball, start_bits=start, max_bits=16 * start, exact_fn=exact)


# --------------------------------------------------------------------------- the mode path
@dataclass(frozen=True)
class ModePath:
    """The mode ``k*(p)`` (smallest maximiser) of the simple-space X as a step function of p.

    ``breakpoints[i] = (p_i, k_left, k_right)``: the mode is ``k_left`` on ``(p_{i-1}, p_i]`` and
    ``k_right`` just above ``p_i`` (at ``p_i`` itself both maximise and the smaller is the mode).
    The first breakpoint is the jump ``p_c`` (an mpf unless rational, enclosed by
    ``critical.p_bounds``); the others are ``p = (k+1) / (k (N-k))`` (where ``f_{N,p}(k) = 0``,
    i.e. ``Phi(k+1) = Phi(k)``), exact Fractions.
    """

    N: int
    critical: CriticalPoint
    breakpoints: tuple[tuple[Any, int, int], ...]
    p_max: Fraction

    @property
    def bounds(self) -> tuple[tuple[Any, Any], ...]:
        """A rigorous enclosure ``(lo, hi)`` of every breakpoint (``lo == hi`` when exact)."""
        out = []
        for i, (bp, _, _) in enumerate(self.breakpoints):
            if i == 0 and not isinstance(bp, Fraction):
                out.append(self.critical.p_bounds)
            else:
                out.append((bp, bp))
        return tuple(out)

    def mode_at(self, p: Any) -> int:
        """The mode at ``p`` read off the path (for ``0 < p <= p_max``); the comparison with the
        irrational jump point is certified by Arb balls."""
        fr = as_fraction(p)
        if fr is None or fr <= 0:
            raise InputError(f"p must be a positive rational, float or mpf, got {p!r}")
        if fr > self.p_max:
            raise InputError(f"p must be <= p_max = {self.p_max} of this path, got {p!r}")
        k = 1
        for i, (bp, _, right) in enumerate(self.breakpoints):
            above = (compare_with_critical(self.critical, fr) > 0 if i == 0
                     else fr > bp)
            if above:
                k = right
            else:
                break
        return k

    def as_rows(self) -> list[dict[str, Any]]:
        return [{"p": bp, "k_left": kl, "k_right": kr, "p_lo": lo, "p_hi": hi}
                for (bp, kl, kr), (lo, hi) in zip(self.breakpoints, self.bounds, strict=True)]


def _breakpoints_below(N: int, k0: int, pm: Fraction) -> int:
    """Largest ``k`` in ``[k0 - 1, N - 1]`` with ``(k+1)/(k(N-k)) <= pm`` (increasing in k
    beyond the jump), by bisection in exact integers."""
    def ok(k: int) -> bool:
        return (k + 1) * pm.denominator <= pm.numerator * k * (N - k)

    lo, hi = k0 - 1, N - 1
    if not ok(k0):
        return k0 - 1
    lo = k0
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if ok(mid):
            lo = mid
        else:
            hi = mid - 1
    return lo


def mode_path(N: int, *, p_max: Any = 1, dps: int = DEFAULT_DPS) -> ModePath:
    """Every exact breakpoint of the mode ``k*(p)`` for ``0 < p <= p_max`` (simple space).

    After the jump the mode climbs one step at a time: it moves from ``k`` to ``k + 1`` exactly
    where ``Phi(k+1) = Phi(k)``, ``p = (k + 1)/(k (N - k))`` (eq. 10 with ``f = 0``). These are
    increasing in ``k`` beyond the jump and all exceed ``p_c`` (checked as they are built).

    Parameters
    ----------
    N : int
        Vertices, ``2 <= N`` (any size).
    p_max : number
        Upper end of the p range (default 1), a positive exact rational / float / mpf. The path
        has one breakpoint per integer step of the mode below ``p_max``; more than
        :data:`MAX_BREAKPOINTS` is refused (for huge N choose ``p_max`` just above ``p_c``).
    dps : int
        Digits of the (irrational) jump point.

    >>> path = mode_path(6)
    >>> [(a, b) for _, a, b in path.breakpoints]
    [(1, 3), (3, 4), (4, 5)]
    >>> [str(p) for p, _, _ in path.breakpoints[1:]]
    ['4/9', '5/8']
    >>> [(a, b) for _, a, b in mode_path(101).breakpoints][:3]
    [(1, 20), (20, 21), (21, 22)]
    """
    N = check_N(N)
    dps = _dps(dps)
    pm = as_fraction(p_max, "p_max")
    if pm is None or pm <= 0:
        raise InputError(f"p_max must be a positive number, got {p_max!r}")
    cp = critical_point(N, dps=dps)
    if compare_with_critical(cp, pm) < 0:
        return ModePath(N, cp, (), pm)
    pc = cp.p_exact if cp.p_exact is not None else cp.p
    last = _breakpoints_below(N, cp.k_after, pm) if cp.k_after < N else cp.k_after - 1
    count = last - cp.k_after + 2
    if count > MAX_BREAKPOINTS:
        raise InputError(
            f"mode_path(N={_fmt_int(N)}, p_max={p_max!r}) would list {count} breakpoints "
            f"(more than symhx.critical.MAX_BREAKPOINTS = {MAX_BREAKPOINTS}, a work limit); "
            f"choose a smaller p_max")
    bps: list[tuple[Any, int, int]] = [(pc, 1, cp.k_after)]
    prev = cp.p_exact if cp.p_exact is not None else _frac(cp.p_bounds[0])
    for k in range(cp.k_after, last + 1):
        pk = Fraction(k + 1, k * (N - k))
        if pk <= prev:
            raise AssertionError(f"mode path not monotone at N={N}, k={k}")  # pragma: no cover
        bps.append((pk, k, k + 1))
        prev = pk
    return ModePath(N, cp, tuple(bps), pm)
