"""Sums over the simple-space distribution (eqs. 7-8) at any N without walking its terms.

``Phi(k) = p**k N! / (k (N-k)!)``; all work is relative to a reference index ``c`` (the larger of
``Phi(1)`` and the hump's top), through ``f(x) = Phi(x)/Phi(c) = exp(D(x))`` for *real* ``x`` in
``(0, N + 1)``:

    D(x) = d log(p u) + u B(d/u) + log1p(-d/u)/2 + S(u) - S(u - d) - log(x/c),
    d = x - c,  u = N + 1 - c,  B(t) = -(1 - t) log1p(-t) - t,

``S`` Stirling's series (``lgamma`` directly below ``Y = 10**4``).  ``p u - 1`` is formed in
exact integers (``p = a/b``), so the working precision is ``dps`` plus a few guard digits for
every N: nothing of size ``N log N`` is ever subtracted.  Two facts carry every bound below:

* ``g(x) = x f(x) = p**x N!/Gamma(N+1-x) / Phi(c)`` is log-concave (``(log g)'' = -psi'(N+1-x)``)
  with its peak at ``x_g ~ N + 1/2 - 1/p``; so ``max g`` on an interval is ``g`` at ``x_g``
  clamped into it;
* off the real axis (product formula of Gamma) ``|f(x + iy)| <= f(x) exp(y**2 psi'(N+1-x)/2)``
  for ``0 < x < N + 1``, and ``psi'(u) <= 1/u + 1/u**2``.

Algorithm (one pass, for ``sum_{k=A}^{B} f(k) w(k)`` with ``w`` in ``1, k - c, (k - c)**2, D(k)``):

1. *Significant runs.*  ``Phi`` decreases on ``[1, m]``, increases to the top ``t`` of the hump,
   then decreases (:func:`symhx.distribution.simple_modes` finds ``t`` in integers).  The head
   run ``[1, e1]`` and the hump run ``[s2, e2]`` are cut where ``D`` falls below
   ``-(dps + guard) ln 10 - ln N - 10`` (safeguarded Newton on ``D``); each dropped term is then
   below ``10**-(dps+guard) / N`` of the largest, so all of them together are below
   ``10**-(dps+guard)`` of the sum.  A whole monotone stretch is dropped without a cut when its
   length times its largest term (times the weight, against the weight's scale) is already
   below ``10**-(dps+guard) e**-10`` of the largest term: near ``p_c`` at ``N = 10**100`` the
   head holds ``10**50`` terms of ``e**-358`` of the hump's top.  Runs that touch are merged.
2. *Short runs* (at most ``direct_terms`` terms) are summed term by term with the exact ratio
   ``Phi(k+1)/Phi(k) = p (N-k) k/(k+1)``, in fixed-point integers (the largest term of the run
   at ``2**P``, ``P`` the working bits plus twice those of the run's length).
3. *Long runs* ``[A, B]``: the first ``K0 - A`` terms (``K0 = 16 (dps + guard)``) directly, then
   Euler-Maclaurin on ``[K0, B]``: the integral by Gauss-Legendre panels (in ``s = log x`` near
   the pole of ``f`` at 0, in ``x`` elsewhere), each panel's node count chosen from its
   Bernstein-ellipse bound ``(64/15) l M rho**(-2n)/(rho**2 - 1)`` with ``M`` from the two facts
   above (panels that need more than 512 nodes are halved), and the endpoint corrections
   from the Taylor coefficients of ``D`` (``psi`` and its derivatives from Arb's power series
   of ``lgamma``, each to the working precision relative to itself, and ``1/x**n``); an end
   whose terms are provably negligible by Cauchy's estimate on a disc around it (a run cut at
   a level) gets none.  The remainder is bounded by Cauchy's estimate on discs of radius
   ``r`` (``r = x/2`` near 0, about ``sqrt(2) sigma`` in the hump): ``|R_M| <= sum_panels
   2 zeta(2M) (2M)!/(2 pi r)**(2M) max|F| (B - A)``; ``M`` is the smallest that makes it
   negligible.
4. *Arithmetic.*  The integrand at the quadrature nodes and ``log g`` in the panel bounds are
   evaluated in Arb ball arithmetic (``lgamma``/``digamma`` of python-flint, C speed) at the
   working precision plus the bits of ``N log N`` (the parts of ``log Phi`` that cancel); the
   integral's ball radius is checked against ``2**-prec`` of the sum of the ``|terms|`` and the
   panels are redone with 64 more bits if it is not met.  ``log Phi`` is accurate in *absolute*
   terms to one unit of the working precision times its size, so a range whose terms are
   ``exp(-1e20)`` below the reference needs 20 more digits: :meth:`SimpleSums.log_max` gives
   that size and the caller (:class:`symhx.distribution.SimpleDistribution`) picks an engine
   with ``extra`` working digits (``W = R + extra``), whose cuts, panels and remainders still
   aim at its relative digits ``R = dps + guard``; level cuts and bounds add
   :meth:`SimpleSums.abs_bits` bits.
5. Every error term (dropped tails, quadrature, remainder) is held below ``10**-(dps+guard)`` of a
   proved lower bound of the sum (``2 delta min(f(x* - delta), f(x* + delta))`` around its
   largest term ``x*``), so the result is correct to ``dps`` digits with ``guard`` digits to spare
   for rounding.

>>> from fractions import Fraction
>>> import symhx
>>> N, p = 10**100, Fraction(2, 10**100)
>>> s = SimpleSums(N, p, 30, top=symhx.mode(N, p))  # terms relative to the hump's top
>>> s.reference == N // 2 - 1
True
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from mpmath.libmp import from_int

from symhx._mpctx import mp
from symhx._numeric import stirling_coefficients
from symhx.certify import arb_prec, to_arb
from symhx.summation import (
    GL_SIZES,
    em_correction,
    em_remainder_factor,
    exp_series,
    gauss_legendre_raw,
    gl_error_factor,
    series_mul,
)

__all__ = ["STIRLING_MIN", "SimpleSums"]

#: Stirling's series is used for ``lgamma(y)`` at ``y >= STIRLING_MIN`` (``lgamma`` directly
#: below, where nothing large cancels)
STIRLING_MIN = 10**4
_LN10 = math.log(10)
#: weights: 0 -> 1, 1 -> (k - c), 2 -> (k - c)**2, 3 -> D(k) = log(Phi(k)/Phi(c))
_ALL = (0, 1, 2, 3)
_STIRLING: dict[int, tuple[Any, ...]] = {}
#: ellipse parameters tried per panel: small panels of a high-precision sum need a large rho
#: (256 nodes at rho = 16 give only ~1400 nats), so the list goes on geometrically to 2**40
#: (``MAX_DPS`` digits); the search stops once a larger rho needs more nodes again
_RHOS = (1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0,
         *(2.0**e for e in range(5, 41)))


def _to_mpf(ctx: Any, num: int, den: int) -> Any:
    """``num/den`` at the context precision, cutting huge integers to ``prec + 64`` bits first."""
    keep = ctx.prec + 64
    sa = max(0, abs(num).bit_length() - keep)
    sb = max(0, den.bit_length() - keep)
    n = num >> sa if num >= 0 else -((-num) >> sa)
    return ctx.ldexp(ctx.mpf(n) / (den >> sb), sa - sb)


def _log_ratio(ctx: Any, num: int, den: int) -> Any:
    """``log(num/den)`` to full relative accuracy of the result: ``log1p`` of the exact
    ``(num - den)/den`` near 1 (``p u - 1`` may be ``1e-49``), else the log of the ratio."""
    if 2 * abs(num - den) < den:
        return ctx.log1p(_to_mpf(ctx, num - den, den))
    return ctx.log(_to_mpf(ctx, num, den))


def _log64(ctx: Any, x: Any) -> Any:
    """``log x`` to 64 bits (bounds only: a log at the bounds' precision of thousands of bits
    costs an AGM)."""
    with ctx.workprec(64):
        return ctx.log(x)


def _exp64(ctx: Any, x: Any) -> Any:
    """``exp x`` to 64 bits (bounds only)."""
    with ctx.workprec(64):
        return ctx.exp(x)


def _from_ball(ctx: Any, ball: Any) -> Any:
    """The midpoint of an Arb ball as an mpf of ``ctx`` (exactly: it is dyadic)."""
    man, exp = ball.mid().man_exp()
    return ctx.ldexp(ctx.mpf(int(man)), int(exp))


def _exact(ctx: Any, n: int) -> Any:
    """The int ``n`` as an mpf of ``ctx`` with every bit (no rounding to the precision)."""
    return ctx.make_mpf(from_int(n))


class SimpleSums:
    """Sums of ``Phi_{N,p}(k)`` and its moments at ``dps`` digits for any ``N`` (see the module
    docstring for the algorithm and its error bound).

    Parameters
    ----------
    N : int
        Number of vertices, ``N >= 1``.
    fr : Fraction
        ``p``, exactly (``p > 0``).
    dps : int
        Digits wanted; the work runs at ``dps + guard``.
    top : int or None
        The top of the hump (the local maximum of ``Phi`` after its increasing stretch, from
        :func:`symhx.distribution.simple_modes`' integer analysis), ``None`` when ``Phi`` is
        decreasing on ``[1, N]``.
    """

    def __init__(self, N: int, fr: Fraction, dps: int, top: int | None = None,
                 extra: int = 0) -> None:
        self.N = N
        self.fr = Fraction(fr)
        self.a, self.b = self.fr.numerator, self.fr.denominator
        self.dps = dps
        self.guard = 12 + 2 * len(str(len(str(N))))
        #: the digits every sum is correct to, relative to itself (cuts, panels, remainders)
        self.R = dps + self.guard
        #: the working precision: ``R`` plus ``extra`` digits for the *absolute* accuracy of
        #: ``log Phi`` where it is large (a range far in a tail: ``|D| ~ 1e20`` needs 20 more)
        self.W = self.R + extra
        self.top = top
        ctx = mp()
        with ctx.workdps(self.W):
            self._p = _to_mpf(ctx, self.a, self.b)
            c = 1
            if top is not None and top > 1:
                # the reference is the larger of Phi(1) and Phi(top) (any choice is exact;
                # the larger keeps every significant D near 0)
                self.c = top
                self._setup_ref()
                if self.D(ctx.mpf(1)) <= 0:
                    c = top
            self.c = c
            self._setup_ref()
        self.reference = self.c

    # ------------------------------------------------------------------ the summand
    def _setup_ref(self) -> None:
        ctx = mp()
        N, c = self.N, self.c
        self.u = N + 1 - c
        self._L1 = _log_ratio(ctx, self.a * self.u, self.b)  # log(p u)
        with ctx.extraprec(128):
            self._logc = ctx.log(c)
            self._logu_hi = ctx.log(self.u)
        self._logu = ctx.log(self.u)
        self._um = _exact(ctx, self.u)
        self._cm = _exact(ctx, c)
        self._magc = ctx.mag(self._cm)
        self._half = ctx.mpf(0.5)
        self._Ymp = ctx.mpf(STIRLING_MIN)
        # the peak of g, N + 1/2 - 1/p, as an offset from c (exact rational first: near the
        # hump its distance to c is ~1/p - (N - c), far below the precision of N itself)
        self._xg_off = _to_mpf(ctx, (2 * (N - c) + 1) * self.a - 2 * self.b, 2 * self.a)
        self._xg = self._cm + self._xg_off
        with ctx.extraprec(64 + self.u.bit_length()):
            self._l2pi = ctx.log(2 * ctx.pi) / 2
        self._Su = self._S(self._um)

    def _S(self, y: Any) -> Any:
        """``S(y) = lgamma(y) - (y - 1/2) log y + y - log(2 pi)/2`` to absolute accuracy:
        Stirling's series for ``y >= Y``, below it ``loggamma`` with ``mag(y log y)`` extra
        bits (the terms cancel to ``~ 1/(12 y)``)."""
        ctx = mp()
        if y < self._Ymp:
            prec = ctx.prec
            my = max(0, ctx.mag(y))
            ctx.prec = prec + my + my.bit_length() + 10
            try:
                return ctx.loggamma(y) - (y - self._half) * ctx.log(y) + y - self._l2pi
            finally:
                ctx.prec = prec
        coef = self._stirling_coef()
        yi2 = 1 / (y * y)
        power = 1 / y
        total = ctx.mpf(0)
        eps = ctx.eps
        for cr in coef:
            term = cr * power
            total += term
            if abs(term) <= eps:
                break
            power *= yi2
        return total

    def _stirling_coef(self) -> list[Any]:
        """``B_2r / (2r (2r-1))``, r = 1..400, at the working precision (cached)."""
        ctx = mp()
        key = ctx.prec
        cache: dict[int, list[Any]] = self.__dict__.setdefault("_coef", {})
        got = cache.get(key)
        if got is None:
            raw = _STIRLING.get(key)  # raw mpf tuples, shared by every thread and engine
            if raw is None:
                r_max = 30 + ctx.dps // 3
                raw = _STIRLING[key] = tuple(
                    (ctx.mpf(num) / den)._mpf_ for num, den in stirling_coefficients(r_max - 1))
            got = cache[key] = [ctx.make_mpf(t) for t in raw]
        return got

    def _lg(self, y: Any) -> Any:
        ctx = mp()
        if y >= self._Ymp:
            return (y - 0.5) * ctx.log(y) - y + ctx.log(2 * ctx.pi) / 2 + self._S(y)
        return ctx.loggamma(y)

    @staticmethod
    def _B(t: Any) -> Any:
        """``-(1 - t) log1p(-t) - t`` without cancellation (``t < 1``)."""
        ctx = mp()
        if abs(t) < 0.05:
            total = ctx.mpf(0)
            power = t * t
            m = 2
            eps = ctx.eps
            while True:
                term = power / (m * (m - 1))
                total += term
                if abs(term) <= eps * abs(total):
                    return -total
                power *= t
                m += 1
        return -(1 - t) * ctx.log1p(-t) - t

    def D(self, x: Any, d: Any = None) -> Any:
        """``log(Phi(x)/Phi(c))`` at the current precision, for real ``0 < x < N + 1``.

        ``x`` an int is exact; for a real point give also its offset ``d = x - c`` (each accurate
        to the working precision *relative to itself*: near ``N`` the position is carried by
        ``d``, near 0 by ``x``)."""
        ctx = mp()
        if d is None:
            d = x - self.c  # exact for an int x
            dm = _exact(ctx, d)
            vm = _exact(ctx, self.u - d)
            xm = _exact(ctx, x)
        else:
            dm = d
            vm = ctx.fsub(self._um, d, exact=True)  # consistent with d to the last bit
            xm = x
        lf = self.Dg(dm, vm)
        # log(x/c): a series for |d| << c, else log x - log c (both with a few extra bits:
        # mpmath's log near 1 takes a slow path)
        mc = ctx.mag(dm) - self._magc
        if mc < -12:
            r = dm / self._cm
            lx, power, m = r, r, 2
            eps = ctx.eps
            while True:
                power *= -r
                term = power / m
                lx += term
                if abs(term) <= eps * abs(lx):
                    break
                m += 1
        else:
            prec = ctx.prec
            ctx.prec = prec + 20 + max(0, self._magc).bit_length()
            try:
                lx = ctx.log(self._cm + dm if mc < 0 else xm) - self._logc
            finally:
                ctx.prec = prec
        return lf - lx

    def Dg(self, dm: Any, vm: Any) -> Any:
        """``log(g(x)/g(c))`` with ``g(x) = x Phi(x)`` (entire in x), from the offset
        ``d = x - c`` and ``v = N + 1 - x`` (``v > 0``; ``x`` may be negative)."""
        return dm * self._L1 + self._lgamma_diff(dm, vm) + self._Su - self._S(vm)

    def _lgamma_diff(self, dm: Any, vm: Any) -> Any:
        """``u B(d/u) + log1p(-d/u)/2 = -(v - 1/2) log(v/u) - d`` (``v = u - d``) to absolute
        accuracy: a series in ``t = d/u`` when ``|t| < 1e-4``, else ``log(1 - t)`` with
        ``2 log10(1/|t|) + 3`` extra digits (the two terms cancel to ``~ d t/2``)."""
        ctx = mp()
        if not dm:
            return ctx.mpf(0)
        t = dm / self._um
        mt = ctx.mag(t)
        if mt < -13:
            # -t/2 - sum_{m>=2} (d t**(m-1)/(m (m-1)) + t**m/(2m))
            total = -t / 2
            dp = dm * t  # d t**(m-1)
            tp = t * t   # t**m
            eps = ctx.eps
            m = 2
            while True:
                term = dp / (m * (m - 1)) + tp / (2 * m)
                total -= term
                if abs(term) <= eps:
                    return total
                dp *= t
                tp *= t
                m += 1
        # (v - 1/2) log(v/u) cancels against d down to ~ d t/2: log v needs mag(v log v)
        # bits beyond the absolute accuracy wanted (one unit of the larger of 1, d t)
        mv = max(0, ctx.mag(vm))
        extra = max(12, mv + mv.bit_length() + 12 - ctx.mag(dm * t))
        prec = ctx.prec
        ctx.prec = prec + extra
        try:
            L = ctx.log(vm) - self._logu_hi  # log(v/u), absolute error 2**-(prec+extra-...)
            return -(vm - self._half) * L - dm
        finally:
            ctx.prec = prec

    def dD(self, x: Any, d: Any = None) -> Any:
        """``D'(x) = log p + psi(N + 1 - x) - 1/x``."""
        ctx = mp()
        if d is None:
            d = x - self.c
        v = self.u - d
        if v >= STIRLING_MIN:
            vm = ctx.mpf(v)
            vi2 = 1 / (vm * vm)
            s = -1 / (2 * vm)
            power = vi2
            for r in range(1, 400):
                term = ctx.bernoulli(2 * r) / (2 * r) * power
                s -= term
                if abs(term) <= ctx.eps * 1e-3:
                    break
                power *= vi2
            psi_minus_log = s
        else:
            psi_minus_log = ctx.digamma(v) - ctx.log(v)
        if 2 * v >= self.u:
            lvu = ctx.log1p(-ctx.mpf(d) / self.u)
        else:  # v/u small (x near N at huge N): d/u would round to 1
            lvu = ctx.log(v) - ctx.log(self.u)
        return self._L1 + psi_minus_log + lvu - 1 / ctx.mpf(x)

    def taylor(self, x0: Any, order: int, d0: Any = None) -> list[Any]:
        """Taylor coefficients ``D(x0), D'(x0), D''(x0)/2, ...`` up to ``order``."""
        ctx = mp()
        if d0 is None:
            d0 = x0 - self.c
        out = [self.D(x0, d0), self.dD(x0, d0)]
        if order < 2:
            return out
        lg = self._lgamma_series(self.u - d0, order)  # an int, or an mpf for a real x0
        x0 = ctx.mpf(x0)
        xp = x0
        for n in range(2, order + 1):
            xp *= x0
            sign = 1 if n % 2 == 0 else -1
            out.append(lg[n - 2] + sign / (n * xp))
        return out

    def _lgamma_series(self, v: Any, order: int) -> list[Any]:
        """The coefficients ``n = 2..order`` of the power series of ``-lgamma(v - t)``
        (``-psi^(n-1)(v)/n!`` up to sign), each to the working precision *relative to
        itself*: Arb's power series of ``lgamma`` carry absolute errors of the size of
        ``lgamma(v)``, so the precision is raised by the bits that cost until every ball is
        narrow enough (``~ n log2 v`` bits for the last one)."""
        from flint import arb_series

        ctx = mp()
        bits = ctx.prec + 20
        for _ in range(8):
            with arb_prec(bits, cap=order + 1):
                coeffs = (-arb_series([to_arb(v), -1], prec=order + 1).lgamma()).coeffs()
                lost = 0
                for b in coeffs[2:order + 1]:
                    if b.rad() > 0:  # bits short of a radius below 2**-(prec + 8) of the value
                        mid, rad = _from_ball(ctx, b.mid()), _from_ball(ctx, b.rad())
                        lost = max(lost, ctx.mag(rad) - ctx.mag(mid) + ctx.prec + 8
                                   if mid else bits)
                if lost <= 0:
                    return [_from_ball(ctx, b) for b in coeffs[2:order + 1]]
            bits += lost + 32
        raise ArithmeticError("the power series of lgamma did not reach the working "
                              "precision")  # pragma: no cover - safety net

    def log_phi_ref(self) -> Any:
        """``log Phi(c)`` at the current precision (``c`` the reference index)."""
        ctx = mp()
        N, c = self.N, self.c
        # log Phi(c) = c log(p (N+1)) + [lgamma(N+1) - lgamma(N+1-c) - c log(N+1)] - log c
        lpn = _log_ratio(ctx, self.a * (N + 1), self.b)
        U = N + 1
        if U >= STIRLING_MIN and U - c >= STIRLING_MIN:
            t = ctx.mpf(c) / U
            lf = U * self._B(t) + ctx.log1p(-t) / 2 + self._S(ctx.mpf(U)) - self._S(
                ctx.mpf(U - c))
        else:
            lf = self._lg(ctx.mpf(U)) - self._lg(ctx.mpf(U - c)) - c * ctx.log(U)
        return c * lpn + lf - self._logc

    # ------------------------------------------------------------------ structure
    def abs_bits(self, A: int, B: int) -> int:
        """Bits to add to a precision so that ``D`` on ``[A, B]`` is accurate to one unit of it
        in *absolute* terms: ``D``'s largest parts (``d log(p u)`` and the lgamma difference,
        which cancel to ``D``) are at most ``|d| (|log p| + 2 log(N+1) + 2)``, ``d = x - c``;
        far from the reference (a tail range at huge N) ``|D|`` reaches ``~N``, so the level
        cuts and bounds there need ``log2 N`` bits beyond their nominal 64-128."""
        d = max(abs(A - self.c), abs(B - self.c), 1)
        lp = abs(self.b.bit_length() - self.a.bit_length()) + 2 * self.N.bit_length() + 4
        return d.bit_length() + lp.bit_length() + 8

    def log_max(self, A: int, B: int) -> Any:
        """``max D`` over ``[A, B]`` (``log`` of the largest term relative to ``Phi(c)``), to
        64 bits *absolute* (an mpf of the thread's context with as many bits as that needs):
        the magnitude that decides the digits a sum over the range needs (cached per range: a
        quantile step asks for it to choose a side and again to choose the engine)."""
        cache: dict[tuple[int, int], Any] = self.__dict__.setdefault("_log_max", {})
        got = cache.get((A, B))
        if got is None:
            ctx = mp()
            top = self.top if (self.top is not None and self.top > 1) else None
            cands = {A, B}
            if top is not None and A <= top <= B:
                cands.add(top)
            with ctx.workprec(64 + self.abs_bits(A, B)):
                got = cache[(A, B)] = max(self.D(k) for k in cands)
        return got

    def _fb(self, k: int) -> int:
        """``b (Phi(k+1)/Phi(k) - 1) (k+1)``-sign: ``Phi(k+1) >= Phi(k)`` iff ``>= 0``."""
        a, b = self.a, self.b
        return -a * k * k + (self.N * a - b) * k - b

    def valley(self) -> int:
        """The local minimum ``m`` of ``Phi`` before the hump (1 without a hump)."""
        if self.top is None or self.top <= 1:
            return 1
        a, b, N = self.a, self.b, self.N
        A = N * a - b
        disc = A * A - 4 * a * b
        m = max(1, (A - math.isqrt(max(disc, 0))) // (2 * a) - 2)
        while m < self.top - 1 and self._fb(m) < 0:
            m += 1
        while m > 1 and self._fb(m - 1) >= 0:
            m -= 1
        return m

    def _level_cut(self, lo: int, hi: int, level: Any, increasing: bool, guess: int) -> int:
        """On ``[lo, hi]`` where ``D`` is monotone: the first ``k`` with ``D(k) >= level``
        (increasing) or the last one (decreasing); the caller ensures ``D(hi)`` (increasing) or
        ``D(lo)`` (decreasing) is ``>= level``.  Newton steps from either end of the bracket
        (whichever lands inside; convex and concave stretches are both monotone from one side),
        else a geometric or arithmetic bisection: a few dozen evaluations at any N."""
        ctx = mp()
        good, bad = (hi, lo) if increasing else (lo, hi)
        if self.D(bad) >= level:
            return bad
        dgood = self.D(good) - level
        x = guess
        if min(good, bad) < x < max(good, bad):
            dx = self.D(x) - level
            if dx >= 0:
                good, dgood = x, dx
            else:
                bad = x
        dbad = self.D(bad) - level
        steps = 0
        while abs(good - bad) > 1:
            steps += 1
            lo_, hi_ = min(good, bad), max(good, bad)
            cand = None
            # Newton for the first 100 steps; bisection after that (it always finishes: each
            # step at least halves the bracket, geometrically or arithmetically)
            for x0, f0, other in ((good, dgood, bad), (bad, dbad, good)) if steps <= 100 else ():
                with ctx.workprec(64):  # a slope for a Newton step: 64 bits (psi at the
                    s = self.dD(x0)     # level cut's thousands of bits costs seconds)
                if s:
                    step = -f0 / s
                    if abs(step) < hi_ - lo_:
                        c1 = x0 + int(ctx.nint(step))
                        if c1 == x0:
                            if abs(f0) > abs(s):  # a steep end far from the root: no step
                                continue
                            c1 = x0 + (1 if other > x0 else -1)  # within one of the root
                        if lo_ < c1 < hi_:
                            cand = c1
                            break
            if cand is None:
                if hi_ > 4 * max(lo_, 1):
                    cand = math.isqrt(max(lo_, 1) * hi_)  # geometric bisection
                else:
                    cand = (lo_ + hi_) // 2
                cand = min(max(cand, lo_ + 1), hi_ - 1)
            dx = self.D(cand) - level
            if abs(dx) < 1e-3:  # on the level to a thousandth of a nat: a cut only needs that
                return cand
            if dx >= 0:
                good, dgood = cand, dx
            else:
                bad, dbad = cand, dx
        return good

    def runs(self, A: int = 1, B: int | None = None) -> list[tuple[int, int]]:
        """The significant runs of ``k`` in ``[A, B]`` (step 1 of the module docstring): every
        ``k`` whose term is within ``10**-(dps+guard)`` / (length of the range) of the largest
        term *of the range*, so a sum over a far tail keeps its relative accuracy."""
        N = self.N
        B = N if B is None else B
        key = (A, B)
        cache = self.__dict__.setdefault("_runs_cache", {})
        if key in cache:
            return cache[key]
        ctx = mp()
        with ctx.workprec(128 + self.abs_bits(A, B)):
            top = self.top if (self.top is not None and self.top > 1) else None
            m = self.valley() if top else N
            # monotone stretches of Phi: [1, m] down, [m, top] up, [top, N] down
            stretches = [(1, m, False)] + ([(m, top, True), (top, N, False)] if top else [])
            pieces = []
            for lo, hi, inc in stretches:
                lo, hi = max(lo, A), min(hi, B)
                if lo <= hi:
                    pieces.append((lo, hi, inc, self.D(hi if inc else lo)))
            dmax = max(p[3] for p in pieces)
            level = dmax - (self.R * _LN10 + math.log(B - A + 1) + 10)
            out: list[tuple[int, int]] = []
            for lo, hi, inc, dtop in pieces:
                if dtop < level or self._negligible(lo, hi, dtop, dmax):
                    continue
                lev = level
                if not inc and top is None and lo == A and self.a * N < self.b:
                    # no hump, N p < 1: each ratio is below N p, so the dropped tail is at
                    # most f(e1)/(1 - N p) (not N f(e1))
                    lev = dmax - (self.R * _LN10 + 10) + _log_ratio(ctx, self.b - self.a * N,
                                                                     self.b)  # log(1 - N p)
                if inc:
                    guess = lo
                    if top is not None:  # the hump's rising side (clipped at hi <= top too)
                        span = int(ctx.nint(self._sigma_at(top) * ctx.sqrt(2 * (dtop - lev))
                                            * 1.05)) + 2
                        guess = max(lo, hi - span)
                    out.append((self._level_cut(lo, hi, lev, True, guess), hi))
                else:
                    guess = hi
                    if top is not None and lo >= top:  # the hump's decreasing side
                        span = int(ctx.nint(self._sigma_at(top) * ctx.sqrt(2 * (dtop - lev))
                                            * 1.05)) + 2
                        guess = min(hi, lo + span)
                    else:
                        guess = lo
                    out.append((lo, self._level_cut(lo, hi, lev, False, guess)))
            out.sort()
            merged: list[tuple[int, int]] = []
            for lo, hi in out:
                if merged and lo <= merged[-1][1] + 1:
                    merged[-1] = (merged[-1][0], max(hi, merged[-1][1]))
                else:
                    merged.append((lo, hi))
        cache[key] = merged
        return merged

    def _negligible(self, lo: int, hi: int, dtop: Any, dmax: Any) -> bool:
        """Whether a whole monotone stretch ``[lo, hi]`` (largest term ``exp(dtop)``) is below
        ``10**-(dps+guard) e**-10`` of the largest term ``exp(dmax)`` of the range for every
        weight: its ``hi - lo + 1`` terms times ``|k - c|**j`` (``j <= 2``, against the
        weights' scale ``sigma**j`` of :meth:`_scales`) or ``|D|`` (``f |log f|`` grows with
        ``f`` below ``1/e``).  Such a stretch (the head near ``p_c`` at huge N: ``e**-358``
        of the hump, over 10**50 terms) needs no level cut and no sum."""
        if dtop >= dmax or dtop > -2:
            return False
        ctx = mp()
        top = self.top if (self.top is not None and self.top > 1) else None
        lsig = float(_log64(ctx, self._sigma_at(top))) if top is not None else 0.0
        far = max(abs(lo - self.c), abs(hi - self.c)) + 1
        excess = max(0.0, 2 * (math.log(far) - lsig), math.log(abs(float(dtop)) + 1))
        bound = math.log(hi - lo + 1) + float(dtop - dmax) + excess
        return bound < -(self.R * _LN10 + 10)

    def _sigma_at(self, k: int) -> Any:
        """``1/sqrt(-D''(k))`` (a width of the hump at its top) at 64 bits (cached per k on the
        engine: the planner asks for the top's width a dozen times per pass)."""
        ctx = mp()
        cache: dict[int, Any] = self.__dict__.setdefault("_sigmas", {})
        got = cache.get(k)
        if got is None:
            with ctx.workprec(64):
                c2 = self.taylor(k, 2)[2]
                got = cache[k] = 1 / ctx.sqrt(-2 * c2) if c2 < 0 else ctx.mpf(1)
        return got

    # ------------------------------------------------------------------ bounds
    def _lgamma_bits(self) -> int:
        """Bits of the parts of ``log Phi`` that cancel (``~ N log N`` and ``N |log p|``): what
        an Arb evaluation of ``log g`` adds to the absolute accuracy it wants."""
        lp_bits = abs(self.b.bit_length() - self.a.bit_length()).bit_length()
        return self.N.bit_length() + self.N.bit_length().bit_length() + lp_bits

    def _ball_consts(self, bits: int) -> tuple[Any, Any, Any, Any]:
        """``(log p, c, N + 1, lgamma(N + 1 - c))`` as Arb balls at ``bits`` (cached per
        precision; call inside :func:`~symhx.certify.arb_prec` of at least ``bits``)."""
        cache: dict[int, tuple[Any, Any, Any, Any]] = self.__dict__.setdefault("_bconsts", {})
        got = cache.get(bits)
        if got is None:
            from flint import arb, fmpz

            with arb_prec(bits):
                lp = arb(fmpz(self.a)).log() - arb(fmpz(self.b)).log()
                ca, n1 = arb(fmpz(self.c)), arb(fmpz(self.N + 1))
                got = cache[bits] = (lp, ca, n1, (n1 - ca).lgamma())
        return got

    @property
    def _bound_bits(self) -> int:
        """The Arb precision of the bounds: ``log g`` absolutely accurate to ``2**-40``."""
        return 80 + self._lgamma_bits()

    def _dg_off(self, d: Any) -> Any:
        """``log(g(x)/g(c))`` at the offset ``d = x - c`` for bounds (Arb, ~40 bits absolute)."""
        bits = self._bound_bits
        lp, ca, n1, lgc = self._ball_consts(bits)
        with arb_prec(bits):
            da = to_arb(d)
            return _from_ball(mp(), da * lp + lgc - (n1 - ca - da).lgamma())

    def _max_dg(self, dlo: Any, dhi: Any) -> Any:
        """``max log(g/g(c))`` for offsets ``x - c`` in ``[dlo, dhi]`` (``g`` log-concave, peak
        near ``x_g = N + 1/2 - 1/p``)."""
        return self._dg_off(min(max(self._xg_off, dlo), dhi))

    def _log_bound(self, kind: str, mid: Any, ell: Any, a: Any, b: Any,
                   kinds: tuple[int, ...]) -> list[Any] | None:
        """Upper bounds of ``log |integrand_j|`` on the Bernstein ellipse (semi-axes ``a ell``,
        ``b ell``) around the panel ``mid +/- ell``: in ``x`` (``kind = "x"``, offsets from
        ``c``; integrand ``f w_j``) or in ``s = log x`` (integrand ``x f w_j = c g/g(c) w_j``,
        ``g`` entire: the image of the ellipse lies in the disc ``|x| <= R = exp(mid + a
        ell)``, and for ``b ell < 1.5`` in the sector ``|arg x| <= b ell`` of it, whose
        bounding rectangle right of 0 is used then).  ``None``
        if the region reaches ``Re x <= 0`` (x panels) or ``Re x >= N + 1``."""
        ctx = mp()
        if kind == "x":
            dlo, dhi = mid - a * ell, mid + a * ell
            xlo = self._cm + dlo
            xhi = self._cm + dhi
            y = b * ell
            if xlo <= 0:
                return None
            R = max(abs(dlo), abs(dhi)) + y
            base_lo = xlo
        else:
            R = _exp64(ctx, mid + a * ell)
            xlo, xhi = -R, R
            y = R
            th = b * ell
            if th < 1.5:  # x = exp(s) maps the ellipse into the sector |arg x| <= th, r <= R:
                # a rectangle right of 0 (the disc would take g at x = -R, which grows like
                # exp(R |log(N p)|) below the jump)
                with ctx.workprec(64):
                    xlo = _exp64(ctx, mid - a * ell) * ctx.cos(th) * (1 - ctx.mpf(2) ** -50)
                    y = R * ctx.sin(th) * (1 + ctx.mpf(2) ** -50)
            dlo, dhi = xlo - self._cm, xhi - self._cm
            base_lo = None
        vlo = self._um - dhi
        if vlo <= 1:
            return None
        lg = self._max_dg(dlo, dhi)
        psi1 = 1 / vlo + 1 / (vlo * vlo)
        vert = y * y * psi1 / 2
        if kind == "x":
            lf = lg + vert - _log64(ctx, base_lo / self._cm)
        else:
            lf = lg + vert + self._logc
        out = []
        for j in kinds:
            if j == 0:
                out.append(lf)
            elif j == 1:
                out.append(lf + _log64(ctx, R + 1 + (self._cm if kind == "s" else 0)))
            elif j == 2:
                out.append(lf + 2 * _log64(ctx, R + 1 + (self._cm if kind == "s" else 0)))
            else:  # |D| <= |Dg| + |log(z/c)|; |Dg(x+iy)| <= max|Dg| + y max|Dg'| + y**2 psi'/2
                dgs = [abs(self._dg_off(dlo)), abs(self._dg_off(dhi)), abs(lg)]
                slopes = [abs(self._dgd(dlo)), abs(self._dgd(dhi))]
                bd = max(dgs) + y * max(slopes) + vert
                if kind == "x":
                    bd += abs(_log64(ctx, xhi / self._cm)) + abs(_log64(ctx, xlo / self._cm))
                    bd += 2
                else:
                    bd += abs(mid) + (a + b) * ell + abs(self._logc) + 4
                out.append(lf + _log64(ctx, bd + 1))
        return out

    def _dgd(self, d: Any) -> Any:
        """``(log g)'(x) = log p + psi(N + 1 - x)`` at the offset ``d = x - c`` (bounds only)."""
        bits = self._bound_bits
        lp, ca, n1, _ = self._ball_consts(bits)
        with arb_prec(bits):
            return _from_ball(mp(), lp + (n1 - ca - to_arb(d)).digamma())

    def _plan_panel(self, kind: str, lo: Any, hi: Any, log_target: list[Any],
                    kinds: tuple[int, ...]) -> int | None:
        """The smallest Gauss-Legendre size in :data:`GL_SIZES` whose ellipse bound meets every
        ``log_target[j]`` on this panel (``None``: halve the panel).  ``kind`` is ``"x"``
        (offsets ``lo, hi`` from ``c``) or ``"s"`` (``x = exp(s)``)."""
        ctx = mp()
        ell = (hi - lo) / 2
        mid = (hi + lo) / 2
        best = None
        lell = float(_log64(ctx, ell))
        for rho in _RHOS:
            a = (rho + 1 / rho) / 2
            b = (rho - 1 / rho) / 2
            bounds = self._log_bound(kind, mid, ell, ctx.mpf(a), ctx.mpf(b), kinds)
            if bounds is None:
                if best is not None:  # the ellipses only grow from here
                    break
                continue
            lr = math.log(rho)
            improved = False
            for n in GL_SIZES:
                if best is not None and n >= best:
                    break
                fac = gl_error_factor(n, lr) + lell
                # the difference first: far in a tail both logs are ~ -1e20 (a float of
                # either alone has lost every unit that matters)
                if all(fac + float(bv - t) <= 0 for bv, t in zip(bounds, log_target,
                                                                 strict=True)):
                    best, improved = n, True
                    break
            if best is not None and not improved:  # past the best rho (the bound now grows
                break  # faster than the nodes' gain): a cost cut, any n found is valid
        return best

    # ------------------------------------------------------------------ sums
    def _direct(self, A: int, B: int, kinds: tuple[int, ...], limit: int | None = None
                ) -> list[Any]:
        """``sum_{k=A}^{B} f(k) w_j(k)`` term by term (exact ratio recurrence); with ``limit``,
        the sum goes on past ``B`` (up to ``limit``) while a weighted term still counts at the
        working precision against its own sum (a point mass at ``k = 1`` has its variance in
        the terms the plain cut drops).  Without the weight ``D`` the terms are walked in
        integers (:meth:`_direct_fixed`)."""
        if 3 not in kinds:
            return self._direct_fixed(A, B, kinds, limit)
        return self._direct_mpf(A, B, kinds, limit)

    def _direct_mpf(self, A: int, B: int, kinds: tuple[int, ...], limit: int | None = None
                    ) -> list[Any]:
        """:meth:`_direct` in mpf arithmetic (every term to the working precision relative to
        itself)."""
        ctx = mp()
        N, c = self.N, self.c
        sums = [ctx.mpf(0) for _ in kinds]
        f = ctx.exp(self.D(A))
        p = self._p
        eps = ctx.eps
        k = A
        while True:
            if k > B:
                if limit is None or k > limit or f == 0:
                    break
                d = k - c
                big = False
                for i, j in enumerate(kinds):
                    w = (1, d, d * d, 1)[j] if j < 3 else abs(ctx.log(f)) + 1
                    if abs(f * w) > eps * abs(sums[i]):
                        big = True
                if not big:
                    break
            d = k - c
            for i, j in enumerate(kinds):
                if j == 0:
                    sums[i] += f
                elif j == 1:
                    sums[i] += f * d
                elif j == 2:
                    sums[i] += f * d * d
                elif f > 0:
                    sums[i] += f * ctx.log(f)
            f = f * p * (N - k) * k / (k + 1)
            k += 1
        return sums

    def _direct_fixed(self, A: int, B: int, kinds: tuple[int, ...], limit: int | None = None
                      ) -> list[Any]:
        """:meth:`_direct` for the weights ``1, k - c, (k - c)**2`` in fixed point: the terms as
        integers, the largest of ``[A, B]`` at about ``2**P``, each the last one times
        ``a (N - k) k`` floor-divided by ``b (k + 1)`` (``p = a/b``), the sums in integers.
        ``P`` is the working bits, plus the bits by which the terms grow from ``A`` to their
        largest (so the first term has the working bits too: floor errors grow with the
        terms), plus twice the bits of the number of terms, plus 20; each floor loses one unit
        and carries it on in proportion, so a sum errs by at most ``n**2`` units times its
        largest weight.  A weighted sum whose value is not far above that (a point mass at
        ``k = c``, whose spread lives in terms ``1e-300`` of it) is redone in mpf."""
        ctx = mp()
        N, c, a, b = self.N, self.c, self.a, self.b
        span = (B if limit is None else max(B, limit)) - A + 1
        lfA = self.D(A)
        P = ctx.prec + 2 * max(span, 1).bit_length() + 20
        with ctx.workprec(64 + self.abs_bits(A, B)):
            lmax = self.log_max(A, B)
            P += max(0, int(ctx.ceil((lmax - lfA) / ctx.ln2)))  # the terms' growth from A
            shift = P - int(ctx.floor(lmax / ctx.ln2))
        F = int(ctx.ldexp(ctx.exp(lfA), shift))
        sums = [0 for _ in kinds]
        k = A
        dmax = 0
        while True:
            if k > B:
                if limit is None or k > limit or F == 0:
                    break
                d = k - c
                ws = (1, abs(d), d * d)
                if not any(F * ws[j] > abs(sums[i]) >> ctx.prec for i, j in enumerate(kinds)):
                    break
            d = k - c
            dmax = max(dmax, abs(d))
            for i, j in enumerate(kinds):
                if j == 0:
                    sums[i] += F
                elif j == 1:
                    sums[i] += F * d
                else:
                    sums[i] += F * d * d
            F = F * (a * (N - k) * k) // (b * (k + 1))
            k += 1
        n = k - A + 1
        for i, j in enumerate(kinds):
            if (n * n * max(dmax, 1) ** j) << ctx.prec > abs(sums[i]):
                return self._direct_mpf(A, B, kinds, limit)
        return [ctx.ldexp(ctx.mpf(v), -shift) for v in sums]

    def _log_radius(self, x: int) -> float:
        """``log min(x/2, 2/|D'(x)|)`` (64 bits): the radius of the Cauchy discs around ``x`` on
        which ``max|f|`` stays within ``e**2`` of ``f(x)`` (``f`` decays at most like
        ``exp(D'(x) t)`` there, and has a pole at 0)."""
        ctx = mp()
        with ctx.workprec(64):
            lr = float(ctx.log(ctx.mpf(x) / 2))
            s = abs(self.dD(x))
            return min(lr, -float(ctx.log(s / 2))) if s else lr

    def _negligible_end(self, x0: int, lr: float, M: int, kinds: tuple[int, ...],
                        targets: list[Any]) -> bool:
        """Whether the Euler-Maclaurin terms at the end ``x0``, ``F(x0)/2 + sum_{m<=M}
        B_2m/(2m)! F^(2m-1)(x0)`` with ``F = f w_j``, are below ``exp(targets[j])``: by
        Cauchy's estimate on the disc of radius ``r = exp(lr)`` they are at most ``max|F|``
        there times ``1/2 + sum_m r 2 zeta(2m) (2m)!/((2 pi r)**(2m) 2m)``, and ``max|F|``
        is :meth:`_log_bound` of the square around the disc.  An end at a level cut
        (``e**-171`` of the top at ``N = 10**6``) needs no Taylor series."""
        if lr < 0:
            return False
        ctx = mp()
        with ctx.workprec(64 + self.abs_bits(x0, x0)):
            r = ctx.exp(lr)
            bounds = self._log_bound("x", ctx.mpf(x0 - self.c), r, ctx.mpf(1), ctx.mpf(1),
                                     kinds)
            if bounds is None:
                return False
            fac = math.log(0.5 + sum(math.exp(lr + em_remainder_factor(m, lr)) / (2 * m)
                                     for m in range(1, M + 1)))
            return all(float(bv - t) + fac < 0 for bv, t in zip(bounds, targets, strict=True))

    def _lower(self, A: int, B: int) -> Any:
        """A proved lower bound of ``log sum_{k=A}^{B} f(k)`` (``A <= B``)."""
        ctx = mp()
        top = self.top if self.top is not None else 1
        x = min(max(top, A), B)
        lf = self.D(x)
        if B - A < 4:
            return lf
        # f >= min(f(x - delta), f(x + delta)) on [x - delta, x + delta] inside one monotone or
        # log-concave stretch: at least 2 delta of those terms
        sig = self._sigma_at(top) if top > 1 else 1.0
        best = lf
        for delta in {max(1, int(sig)), max(1, int(sig) // 4), 1}:
            lo, hi = max(A, x - delta), min(B, x + delta)
            if top > 1 and lo < top <= hi and lo < self.valley():
                continue
            val = min(self.D(lo), self.D(hi)) + ctx.log(hi - lo)
            best = max(best, val)
        return best

    def sums(self, A: int, B: int, kinds: tuple[int, ...] = (0,)) -> list[Any]:
        """``sum_{k=A}^{B} f(k) w_j(k)`` for the weights ``kinds`` (0: 1, 1: ``k - c``,
        2: ``(k - c)**2``, 3: ``D(k)``), each correct to ``dps + guard`` digits relative to
        the sum of ``f`` over ``[A, B]`` times the weight's scale."""
        ctx = mp()
        total = [ctx.mpf(0) for _ in kinds]
        if A > B:
            return total
        with ctx.workdps(self.W):
            runs = self.runs(A, B)
            for i, (lo, hi) in enumerate(runs):
                nxt = runs[i + 1][0] - 1 if i + 1 < len(runs) else B
                part = self._run_sum(lo, hi, kinds, min(nxt, hi + 4 * self.direct_terms)
                                     if kinds != (0,) else None)
                total = [t + v for t, v in zip(total, part, strict=True)]
        return total

    @property
    def direct_terms(self) -> int:
        """Runs up to this many terms are summed term by term."""
        return max(1500, 16 * self.R)

    def _run_sum(self, A: int, B: int, kinds: tuple[int, ...], limit: int | None = None
                 ) -> list[Any]:
        if B - A + 1 <= self.direct_terms:
            return self._direct(A, B, kinds, limit)
        K0 = max(A, 16 * self.R)
        # Euler-Maclaurin needs f smooth on a disc of radius >= rmin at both ends, rmin the
        # Cauchy radius for e**(-2 pi r) below 10**-(dps+guard)
        lrmin = math.log(0.45 * self.R + 3)
        while K0 < B and self._log_radius(K0) < lrmin and K0 < 64 * self.R:
            K0 = min(B, 2 * K0)
        smooth = self._log_radius(K0) >= lrmin and self._log_radius(B) >= lrmin
        if B - K0 + 1 <= self.direct_terms or K0 >= B or not smooth:
            return self._direct(A, B, kinds)
        head = self._direct(A, K0 - 1, kinds) if K0 > A else [mp().mpf(0) for _ in kinds]
        tail = self._em(K0, B, kinds)
        return [h + t for h, t in zip(head, tail, strict=True)]

    def _integral(self, panels: list[tuple[str, Any, Any, int]], kinds: tuple[int, ...]
                  ) -> list[Any]:
        """``int f w_j`` over the planned Gauss-Legendre panels, the integrand at every node in
        Arb ball arithmetic (``log Phi`` through ``lgamma``): C speed, and a rigorous radius.
        The precision is the working one plus the bits of the largest part of ``log Phi``
        (``~ N log N``, which cancels); if a total's radius is still above ``2**-prec`` of it
        (a cancellation the estimate missed), the panels are redone with 64 more bits.
        Returns numbers of the calling thread's context (ball midpoints)."""
        from flint import arb, fmpz

        ctx = mp()
        wbits = ctx.prec
        raw = {n: gauss_legendre_raw(n, wbits) for _, _, _, n in panels}
        P = wbits + self._lgamma_bits() + 24
        for _ in range(4):
            lp, ca, n1, lgc = self._ball_consts(P)
            with arb_prec(P):
                const = lgc + ca.log()
                totals = [arb(0) for _ in kinds]
                sizes = [arb(0) for _ in kinds]  # sums of |f w_j|: what the error is held to
                for kind, plo, phi_, n in panels:
                    lo_a, hi_a = to_arb(plo), to_arb(phi_)
                    ell = (hi_a - lo_a) / 2
                    mid = (hi_a + lo_a) / 2
                    for (xm, xe), (wm, we) in raw[n]:
                        t = mid + ell * arb((fmpz(xm), xe))
                        wt = ell * arb((fmpz(wm), we))
                        if kind == "x":
                            d = t
                            x = ca + d
                        else:
                            x = t.exp()
                            d = x - ca
                            wt = wt * x
                        Dv = d * lp + const - (n1 - x).lgamma() - x.log()
                        fv = Dv.exp() * wt
                        for i, j in enumerate(kinds):
                            term = fv if j == 0 else fv * d if j == 1 else \
                                fv * d * d if j == 2 else fv * Dv
                            totals[i] += term
                            sizes[i] += abs(term.mid())
                tol = arb(2) ** (8 - wbits)
                ok = all(tv.rad() <= sz * tol for tv, sz in zip(totals, sizes, strict=True))
                if ok:
                    return [_from_ball(ctx, tv) for tv in totals]
            P += 64
        raise ArithmeticError("the quadrature's ball arithmetic did not reach the working "
                              "precision")  # pragma: no cover - safety net

    def _scales(self, A: int, B: int, kinds: tuple[int, ...]) -> list[float]:
        """The size of each weight that its sum's error is measured against (``log``)."""
        top = self.top if self.top is not None else 1
        ctx = mp()
        sig = self._sigma_at(top) if top > 1 else ctx.mpf(1)
        T = self.R * _LN10
        width = max(sig, ctx.mpf(B - A) / (4 * T), ctx.mpf(1))
        out = []
        for j in kinds:
            if j == 0 or j == 3:
                out.append(0.0)
            elif j == 1:
                out.append(float(ctx.log(max(self._cm, width))))
            else:
                out.append(float(2 * ctx.log(width)))
        return out

    def _em(self, A: int, B: int, kinds: tuple[int, ...]) -> list[Any]:
        """Euler-Maclaurin on ``[A, B]`` (``A >= 16 (dps + guard)``, f smooth on the scale of A)."""
        ctx = mp()
        eps_log = -(self.R * _LN10) - 3
        lowprec = 128 + self.abs_bits(A, B)  # bounds need D to absolute accuracy
        with ctx.workprec(lowprec):
            low = self._lower(A, B)
            scales = self._scales(A, B, kinds)
        top = self.top if self.top is not None else 0
        c = self.c
        xg = self._xg  # N + 1/2 - 1/p
        # s-region [A, Xs] near the pole at 0, x-region [Xs, B]
        if top and A <= top and xg / 4 > A:  # (a range that stops short of the top too)
            Xs = min(B, int(xg / 4))  # int() of an mpf is exact
        elif top and A >= xg / 4:
            Xs = A
        else:
            Xs = B
        if Xs < 2 * A:  # s = log x pays only over a factor 2 in x; on a short stretch at large
            Xs = A      # x its panels are ~1e-36 wide and a 64-bit sector bound moves x by 1e25
        panels: list[tuple[str, Any, Any, int]] = []
        pieces = []  # exact ends at the working precision; the plan runs at low precision
        if Xs > A:
            pieces.append(("s", ctx.log(A), ctx.log(Xs)))
        if B > Xs:
            pieces.append(("x", ctx.mpf(Xs - c), ctx.mpf(B - c)))
        for kind, lo, hi in pieces:
            span = hi - lo
            stack = [(lo, hi)]
            while stack:
                plo, phi_ = stack.pop()
                with ctx.workprec(lowprec):
                    frac = _log64(ctx, (phi_ - plo) / span) + math.log(
                        0.5 if len(pieces) > 1 else 1)
                    targ = [eps_log + low + sc + frac for sc in scales]
                    n = self._plan_panel(kind, plo, phi_, targ, kinds)
                if n is None:
                    if len(panels) + len(stack) > 4000:  # pragma: no cover - safety net
                        raise ArithmeticError("quadrature panels do not converge")
                    mid = (plo + phi_) / 2
                    stack.append((mid, phi_))
                    stack.append((plo, mid))
                else:
                    panels.append((kind, plo, phi_, n))
        self.last_panels = panels
        total = self._integral(panels, kinds)
        # endpoint terms: (F(A) + F(B))/2 + sum_m B_2m/(2m)! (F^(2m-1)(B) - F^(2m-1)(A))
        # on Cauchy discs of radius r around [A, B] (in the hump r ~ sigma)
        lrA = self._log_radius(A)
        M = 1
        while em_remainder_factor(M, lrA) + 2 > eps_log - 5 and M < 200:
            M += 1
        corr = [ctx.mpf(0) for _ in kinds]
        for x0, sign in ((A, -1), (B, 1)):
            # the Cauchy radius at this end, as for M above (a radius of sigma alone let a
            # steep end take one term), and at most the hump's width
            lr0 = self._log_radius(x0)
            if top:
                with ctx.workprec(64):
                    lr0 = min(lr0, float(ctx.log(max(1, self._sigma_at(top)))))
            Mx = 1
            while em_remainder_factor(Mx, lr0) > eps_log - 5 and Mx < M:
                Mx += 1
            if self._negligible_end(x0, lr0 - math.log(4), Mx, kinds,
                                    [eps_log + low + sc - math.log(4) for sc in scales]):
                continue
            order = 2 * Mx
            tc = self.taylor(x0, order)
            f0 = ctx.exp(tc[0])
            fser = [f0 * e for e in exp_series(ctx, tc, order)]
            d0 = x0 - c
            for i, j in enumerate(kinds):
                if j == 0:
                    ser = fser
                elif j == 1:
                    ser = series_mul(ctx, fser, [ctx.mpf(d0), ctx.mpf(1)], order)
                elif j == 2:
                    ser = series_mul(ctx, fser, [ctx.mpf(d0) ** 2, 2 * ctx.mpf(d0),
                                                 ctx.mpf(1)], order)
                else:
                    ser = series_mul(ctx, fser, tc, order)
                corr[i] += ser[0] / 2 + sign * em_correction(ctx, ser, Mx)
        return [t + k for t, k in zip(total, corr, strict=True)]
