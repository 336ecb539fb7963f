"""Rigorous ball arithmetic (python-flint ``arb``) for every integer decision of symhx.

An ``arb`` is a ball ``[m +/- r]`` guaranteed to contain the exact real value of the expression
that produced it (FLINT/Arb propagates rounding and truncation errors of every operation,
including ``log``, ``lgamma`` and ``digamma``). A sign is *certified* when the ball excludes 0.

Precision and threads. Every Arb operation rounds at ``flint.ctx.prec``, one process-wide
setting (python-flint has no per-thread context). :func:`arb_prec` is the only place symhx sets
it: it holds a process-wide re-entrant lock (:data:`ARB_LOCK`) while it sets the precision *and
while the block runs*, and restores the precision on exit, so Arb sections of different threads
are serialized and never see each other's precision. Every arb operation of symhx runs inside
such a block (a finished ball may be compared or read outside: comparisons, ``mid``, ``rad``
and ``man_exp`` are exact). Neither ``flint.ctx.prec`` as seen by the user's code between calls
nor ``mpmath.mp.dps`` changes.

Irrational inputs. :func:`real_ball` encloses a sympy real expression (integers, rationals,
binary floats, ``pi``, ``E``, ``EulerGamma``, ``Catalan``, ``GoldenRatio``, sums, products,
integer and rational powers and roots, real powers of positive bases, ``exp``, ``log``,
trigonometric, hyperbolic and their inverses, ``gamma``, ``loggamma``, ``erf``, ``erfc``,
``Abs``, ``floor``, ``ceiling``, ``Min``, ``Max``) at any precision, walking the expression tree
with Arb (no sympy ``evalf``: its special functions run in mpmath's global context); anything
else is a clear ``TypeError``. Decisions about an irrational are taken on its ball, the
precision doubled until the decision is proved (at most :data:`MAX_IRRATIONAL_BITS` bits); a
decision that no precision settles (a true tie, e.g. ``p`` equal to a rational breakpoint
written irrationally) raises :class:`UndecidedError` saying how to get it decided.

>>> with arb_prec(bits_for(10**100, 100)):  # lgamma(N) cancels ~log2(N log N) bits
...     x = G_arb(10**100, 10**40)          # sum_{j<=K} log(1 - j/N): about -K**2/(2N) = -5e-21
>>> x < 0, round(float(x.mid()) * 1e21, 9), bool(x.rad() < arb('1e-30'))
(True, -5.0, True)
>>> certified_sign(lambda: arb(2).sqrt() - arb('1.4142135623730950488'), start_bits=64,
...                max_bits=256)
1
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from fractions import Fraction
from typing import Any, TypeVar

import mpmath
from flint import arb, ctx, fmpq, fmpz
from mpmath import libmp

from symhx._mpctx import make_mpf

__all__ = [
    "ARB_LOCK",
    "MAX_IRRATIONAL_BITS",
    "G_arb",
    "UndecidedError",
    "arb_prec",
    "bits_for",
    "certified_sign",
    "decide_with_rising_precision",
    "mpf_bounds",
    "rational_bracket",
    "real_ball",
    "real_sign",
    "rel_width_ok",
    "space_candidates",
    "space_candidates_ball",
    "space_q_ball",
    "to_arb",
]

T = TypeVar("T")

#: The process-wide lock held by :func:`arb_prec` (re-entrant: blocks may nest in one thread).
ARB_LOCK = threading.RLock()

#: Largest precision (bits, ~39 000 digits) at which a decision about an irrational input is
#: attempted: an irrational closer than ~2**-MAX_IRRATIONAL_BITS (relative) to the boundary of
#: a decision, or exactly on it (a true tie), raises :class:`UndecidedError`.
MAX_IRRATIONAL_BITS = 1 << 17


class UndecidedError(ArithmeticError):
    """A sign could not be certified within the precision budget (an exact tie is likely)."""


@contextmanager
def arb_prec(bits: int, cap: int | None = None) -> Iterator[None]:
    """Set flint's working precision to ``bits`` (and, given ``cap``, the length to which
    power series are truncated: flint's default is 10 terms) for the block (restored on exit),
    holding :data:`ARB_LOCK` (process-wide, re-entrant) until the block ends: Arb sections of
    different threads are serialized, so none runs at another's precision."""
    with ARB_LOCK:
        old, old_cap = ctx.prec, ctx.cap
        ctx.prec = int(bits)
        if cap is not None:
            ctx.cap = int(cap)
        try:
            yield
        finally:
            ctx.prec, ctx.cap = old, old_cap


def _mpf_tuple_to_arb(t: tuple) -> arb:
    sign, man, exp, bc = t
    if not man:
        if bc == 0 and exp == 0:
            return arb(0)
        raise ValueError(f"cannot convert {libmp.to_str(t, 5)} to arb: not a finite number")
    return arb((-int(man) if sign else int(man), int(exp)))


def to_arb(x: Any) -> arb:
    """An int / Fraction / mpf (of any context) / float as an exact ``arb`` where the value is
    exactly representable (ints, mpf, floats, dyadic fractions), else a ball containing the
    exact value at the current precision; a sympy real number goes through :func:`real_ball`;
    an ``arb`` is returned as it is (radius included). Call it inside :func:`arb_prec`."""
    if isinstance(x, arb):  # a ball already: kept whole (its ``_mpf_`` is the midpoint alone)
        return x
    if isinstance(x, int) and not isinstance(x, bool):
        return arb(fmpz(x))
    if hasattr(x, "_mpf_"):
        return _mpf_tuple_to_arb(x._mpf_)
    if isinstance(x, float):
        return _mpf_tuple_to_arb(libmp.from_float(x))
    if _is_sympy(x):
        return real_ball(x)
    num, den = getattr(x, "numerator", None), getattr(x, "denominator", None)
    if num is not None and den is not None:
        num, den = int(num), int(den)
        if den & (den - 1) == 0:  # a power of two: exact
            return arb((num, -(den.bit_length() - 1)))
        return arb(fmpq(num, den))
    raise TypeError(f"cannot convert {type(x).__name__} to arb")


# --------------------------------------------------------------------------- sympy reals
def _is_sympy(x: Any) -> bool:
    return str(type(x).__module__).startswith("sympy")


def _fn_name(x: Any) -> str:
    """The sympy head of ``x`` (``sin`` for ``sin(1)``): its class's name (``x.func`` is the
    class for every sympy function application)."""
    return type(x).__name__


def _unary(name: str) -> Callable[[arb], arb] | None:
    table: dict[str, Callable[[arb], arb]] = {
        "exp": arb.exp, "log": arb.log, "sin": arb.sin, "cos": arb.cos, "tan": arb.tan,
        "cot": arb.cot, "sec": arb.sec, "csc": arb.csc, "asin": arb.asin, "acos": arb.acos,
        "atan": arb.atan, "sinh": arb.sinh, "cosh": arb.cosh, "tanh": arb.tanh,
        "coth": arb.coth, "asinh": arb.asinh, "acosh": arb.acosh, "atanh": arb.atanh,
        "gamma": arb.gamma, "loggamma": arb.lgamma, "erf": arb.erf, "erfc": arb.erfc,
        "Abs": abs, "floor": arb.floor, "ceiling": arb.ceil, "LambertW": arb.lambertw,
        "zeta": arb.zeta, "digamma": arb.digamma,
    }
    return table.get(name)


_CONSTANTS: dict[str, Callable[[], arb]] = {
    "Pi": arb.pi,
    "Exp1": arb.const_e,
    "EulerGamma": arb.const_euler,
    "Catalan": arb.const_catalan,
    "GoldenRatio": lambda: (1 + arb(5).sqrt()) / 2,
}


def _pow_ball(base: arb, expo: Any, shown: Any) -> arb:
    """``base**expo`` for a sympy exponent: integers exactly, rationals ``a/q`` by a q-th root,
    other reals by ``exp(expo log base)``. As in sympy, a negative base with a non-integer
    exponent is the principal *complex* power (``(-8)**(1/3) = 1 + sqrt(3) I``): ValueError. A
    base ball that still holds 0 gives a ``nan`` ball (the caller raises the precision), and
    so does a zero base whose irrational exponent's ball still holds 0."""
    if getattr(expo, "is_Integer", False):
        e = int(expo)
        return base**e if e >= 0 else 1 / base**(-e)
    if base < 0:
        raise ValueError(f"{str(shown)[:60]} is not a real number (a negative base to a "
                         f"non-integer power is complex in sympy; write real_root or -x**(1/q))")
    if base.is_zero():
        if getattr(expo, "is_Rational", False):
            positive = expo > 0
        else:
            x = real_ball(expo)
            if not (x > 0 or x <= 0):  # the exponent's sign is not proved at this precision
                return arb.nan()
            positive = x > 0
        if positive:
            return arb(0)
        raise ValueError(f"{str(shown)[:60]} is not a finite real number")
    if not base > 0:
        return arb.nan()
    if getattr(expo, "is_Rational", False):
        a, q = int(expo.p), int(expo.q)
        r = base.root(q)
        return r**a if a >= 0 else 1 / r**(-a)
    return (base.log() * real_ball(expo)).exp()


def real_ball(x: Any) -> arb:
    """Rigorous ball of a real number at the current precision (call inside
    :func:`arb_prec`): ints, Fractions, floats and mpf exactly; a sympy real expression by
    walking its tree (see the module docstring for what it knows).

    A ball may be wide or ``nan`` at a low precision (``log`` of a ball holding 0, heavy
    cancellation): callers raise the precision. Raises ``TypeError`` (naming the part it cannot
    evaluate) for anything else, ``ValueError`` for a non-real (``I``, ``oo``, ``nan``).

    >>> import sympy
    >>> with arb_prec(300):  # 1/50 + sqrt(2)/10**70 is above 1/50: 300 bits prove it
    ...     b = real_ball(sympy.Rational(1, 50) + sympy.sqrt(2) / 10**70)
    ...     above = b > to_arb(Fraction(1, 50))
    >>> above
    True
    """
    if not _is_sympy(x):
        return to_arb(x)
    if getattr(x, "is_Rational", False):
        return to_arb(Fraction(int(x.p), int(x.q)))
    if getattr(x, "is_Float", False):
        return _mpf_tuple_to_arb(x._mpf_)
    name = _fn_name(x)
    if name in _CONSTANTS:
        return _CONSTANTS[name]()
    if name in ("ImaginaryUnit", "Infinity", "NegativeInfinity", "ComplexInfinity", "NaN"):
        raise ValueError(f"{x} is not a finite real number")
    if getattr(x, "is_Add", False):
        total = arb(0)
        for a in x.args:
            total += real_ball(a)
        return total
    if getattr(x, "is_Mul", False):
        prod = arb(1)
        for a in x.args:
            prod *= real_ball(a)
        return prod
    if getattr(x, "is_Pow", False):
        base, expo = x.args
        if _fn_name(base) == "Exp1":
            return real_ball(expo).exp()
        return _pow_ball(real_ball(base), expo, x)
    if name in ("Min", "Max"):
        balls = [real_ball(a) for a in x.args]
        out = balls[0]
        for b in balls[1:]:
            out = out.min(b) if name == "Min" else out.max(b)
        return out
    fn = _unary(name)
    if fn is not None and len(x.args) == 1:
        return fn(real_ball(x.args[0]))
    if name == "atan2" and len(x.args) == 2:
        return arb.atan2(real_ball(x.args[0]), real_ball(x.args[1]))
    raise TypeError(f"cannot evaluate {name} (in {str(x)[:60]}) as a rigorous real ball; "
                    "pass the number as an exact rational or a float instead")


def decide_with_rising_precision(fn: Callable[[int], T | None], *, start_bits: int,
                                 max_bits: int | None = None,
                                 undecided: Callable[[int], str]) -> T:
    """``fn(bits)`` at ``start_bits``, doubled until it returns a decision (not ``None``);
    ``UndecidedError(undecided(bits))`` past ``max_bits`` (default: :data:`MAX_IRRATIONAL_BITS`
    as it is at the call, so raising that constant reaches every caller). ``fn`` opens its own
    :func:`arb_prec` blocks (the lock is not held between attempts)."""
    if max_bits is None:
        max_bits = MAX_IRRATIONAL_BITS
    bits = max(64, int(start_bits))
    while True:
        got = fn(bits)
        if got is not None:
            return got
        if bits >= max_bits:
            raise UndecidedError(undecided(bits))
        bits = min(2 * bits, int(max_bits))


def real_sign(x: Any, *, start_bits: int = 64, max_bits: int | None = None) -> int:
    """Sign (-1, 0, +1) of a real number (a sympy expression too), proved on its Arb ball with
    rising precision: 0 only when the ball is exactly 0 (an exact zero such as an unevaluated
    ``0 * sqrt(2)``); :class:`UndecidedError` when no precision up to ``max_bits`` (default
    :data:`MAX_IRRATIONAL_BITS`) separates
    it from 0 (``pi - pi`` written unevaluated); ``TypeError`` for what :func:`real_ball` cannot
    evaluate.

    >>> import sympy
    >>> real_sign(sympy.sqrt(2) - sympy.Rational(14142135623730950488, 10**19))
    1
    """
    def attempt(bits: int) -> int | None:
        with arb_prec(bits):
            b = real_ball(x)
            if b.is_zero():
                return 0
            return 1 if b > 0 else -1 if b < 0 else None

    return decide_with_rising_precision(
        attempt, start_bits=start_bits, max_bits=max_bits,
        undecided=lambda bits: f"the sign of {str(x)[:60]} is not decided at {bits} bits")


def rational_bracket(ball: arb) -> tuple[Fraction, Fraction] | None:
    """Exact binary rationals ``lo <= every point of ball <= hi`` (None for a non-finite
    ball); call inside :func:`arb_prec` (the ends are rounded outward at its precision)."""
    if not ball.is_finite():
        return None
    lo, hi = ball.lower(), ball.upper()  # exact floating-point ends (rounded outward)
    return _arb_fraction(lo), _arb_fraction(hi)


def _arb_fraction(x: arb) -> Fraction:
    m, e = x.man_exp()
    man, exp = int(m), int(e)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2 ** (-exp))


def bits_for(N: int, extra_bits: int) -> int:
    """Starting precision for quantities built from ``lgamma(N)``: the ``log2(N log N)`` bits
    that cancel, plus ``extra_bits``."""
    return N.bit_length() + max(N.bit_length(), 2).bit_length() + int(extra_bits) + 16


def G_arb(N: int, K: int) -> arb:
    """Ball enclosing ``G(N, K) = lgamma(N) - lgamma(N - K) - K log N
    = sum_{j=1}^{K} log(1 - j/N)`` (``0 <= K < N``) at the current precision.

    The definition cancels about ``log2(N log N)`` bits; choose the precision with
    :func:`bits_for`. The ball is rigorous whatever the precision.
    """
    if K == 0:
        return arb(0)
    n = to_arb(N)
    return n.lgamma() - to_arb(N - K).lgamma() - to_arb(K) * n.log()


def certified_sign(
    fn: Callable[[], arb],
    *,
    start_bits: int,
    max_bits: int,
    exact_fn: Callable[[], int] | None = None,
) -> int:
    """Sign (-1, 0, +1) of a real quantity, certified by Arb ball arithmetic.

    ``fn()`` evaluates the quantity as an ``arb`` at the precision in force (it runs inside
    :func:`arb_prec`). The precision doubles from ``start_bits`` until the ball excludes 0. If it
    still contains 0 at ``max_bits``, ``exact_fn()`` (exact rational/integer arithmetic, which
    also detects exact ties and returns 0) decides; without one, :class:`UndecidedError` is
    raised.
    """
    bits = max(64, int(start_bits))
    while True:
        with arb_prec(bits):
            x = fn()
            sign = 1 if x > 0 else -1 if x < 0 else 0
            shown = x.str(5, radius=True) if sign == 0 else ""
        if sign:
            return sign
        if bits >= max_bits:
            break
        bits = min(2 * bits, int(max_bits))
    if exact_fn is not None:
        return exact_fn()
    raise UndecidedError(
        f"sign not certified at {bits} bits (ball {shown}); an exact tie is "
        "likely and the integers involved are too large to compare exactly"
    )


def _exact_mpf(x: arb) -> mpmath.mpf:
    """The exact float ``x`` (an arb with radius 0) as a global mpf, bit for bit (pure libmp:
    no context involved)."""
    man, exp = x.man_exp()
    return make_mpf(libmp.from_man_exp(int(man), int(exp)))


def mpf_bounds(x: arb, dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(lo, hi)`` global mpf with ``lo <= every point of x <= hi`` (rounded outward to
    ``dps + 5`` digits)."""
    prec = int((dps + 5) * 3.3219280948873626) + 8
    with arb_prec(prec):  # lower/upper round outward at ctx.prec: the ends to prec bits
        lo, hi = x.lower(), x.upper()
    return _exact_mpf(lo), _exact_mpf(hi)


def rel_width_ok(x: arb, dps: int) -> bool:
    """Whether the ball's relative width (``radius / |midpoint|``) is below ``10**-dps / 4``
    (decided exactly, from the exact radius and midpoint: no Arb rounding involved)."""
    with arb_prec(64):
        if x.is_exact():
            return True
        if x.contains(0):
            return False
        rm, re = (int(v) for v in x.rad().man_exp())
        mm, me = (int(v) for v in x.mid().man_exp())
    # rm 2**re * 4 * 10**dps < |mm| 2**me, in integers
    lhs, rhs = rm * 4 * 10 ** int(dps), abs(mm)
    e = min(re, me)
    return (lhs << (re - e)) < (rhs << (me - e))


def _scan_candidates(space: Any, N: int, pa: arb, q_ball: Callable[[int], arb],
                     p_hi: Fraction, top: int) -> list[int]:
    """The scan of :func:`space_candidates` with ``p`` a ball ``pa`` (``p <= p_hi``) and
    ``q_ball(k)`` a ball of ``Q*(k)`` up to a factor common to every k; inside
    :func:`arb_prec`."""
    m, R = space.max_excess, space.max_parts
    qprev = q_ball(1)
    ratios = [arb(1)]  # ratios[k - 1] = W(k) / W(1)
    for k in range(1, top):
        qk1 = q_ball(k + 1)
        ratios.append(ratios[-1] * pa * ((N - k) * k) / (k + 1) * qk1 / qprev)
        qprev = qk1
    wtop = ratios[top - 1]
    out = [k for k in range(1, top) if not ratios[k - 1] < wtop]
    ratio = wtop
    for k in range(top, N):
        qk1 = q_ball(k + 1)
        ratio = ratio * pa * ((N - k) * k) / (k + 1) * qk1 / qprev
        qprev = qk1
        kk = k + 1
        below = ratio < wtop
        if not below:
            out.append(kk)
        elif kk > R and p_hi * (N - kk) * max(kk + m, kk + 1 - R) < kk + 1 - R:
            break
    return sorted({top, *out})


def space_candidates(space: Any, N: int, fr: Any, top: int) -> list[int]:
    """Every ``k`` that may maximise ``W(k) = Phi_{N,p}(k) Q*(k)`` at the rational ``p = fr``
    over a sample space (``space.Qnum``, ``.max_parts``, ``.max_excess`` as in
    :class:`symhx.spaces.Space`), given a guess ``top`` (e.g. a float64 argmax): ``top`` plus
    each ``k`` that an Arb ball cannot prove to have ``W(k) < W(top)``.

    ``W(k)/W(1)`` is a running product of the exact ratios
    ``W(k+1)/W(k) = p (N-k) k/(k+1) Q*(k+1)/Q*(k)``; it stops at the first ``k > max(top, r)``
    with ``W(k) < W(top)`` and ``rho(k) = p (N-k) max((k+m)/(k+1-r), 1) < 1``
    (``r = max_parts``, ``m = max_excess``): each later ratio ``W(j+1)/W(j)`` is at most
    ``p (N-j) (j+m)/(j+1-r)`` (mediant inequality on the non-negative polynomial coefficients of
    ``Q*``), and ``(j+m)/(j+1-r)`` is monotone in ``j`` with limit 1, so ``rho(k)`` bounds every
    later ratio and W decreases after it. (Without the ``max(., 1)``, for ``m = r = 0``, the
    excess<=0 space, ``k/(k+1)`` *increases* and a dip of W after ``top`` used to stop the scan
    before a larger maximum.)
    """
    a, b = fr.numerator, fr.denominator
    bits = 96 + 2 * N.bit_length() + a.bit_length() + b.bit_length()
    with arb_prec(bits):
        return _scan_candidates(space, N, to_arb(fr), lambda k: to_arb(space.Qnum(k, a, b)),
                                Fraction(fr), top)


def space_q_ball(space: Any, k: int, pa: arb) -> arb:
    """Ball of ``D Q*(k) = sum_e U_e(k) p**e`` (``sum_e U_e(k)`` for the distinct weighting)
    for ``p`` in the ball ``pa``; inside :func:`arb_prec`."""
    U = space.U(k)
    if space.weighting == "distinct":
        return to_arb(sum(U))
    total, pe = arb(0), arb(1)
    for u in U:
        if u:
            total += pe * to_arb(u)
        pe *= pa
    return total


def space_candidates_ball(space: Any, N: int, pa: arb, p_hi: Fraction, top: int) -> list[int]:
    """:func:`space_candidates` for a ``p`` known only as a ball ``pa`` (an irrational), with
    ``p <= p_hi``; runs at the precision in force (call inside :func:`arb_prec`). Every ``k``
    that may maximise ``W`` for *some* point of the ball is kept."""
    return _scan_candidates(space, N, pa, lambda k: space_q_ball(space, k, pa), p_hi, top)
