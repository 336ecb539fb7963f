"""Event-driven impact engine over exact (closed-form) flight: one algorithm, two arithmetics.

This module is the *reference* engine (mpmath at any precision); the same code also runs in plain
Python floats (the fallback of the fast engine, and an independent check of the C port in
``_fast.c``, which follows this file line by line).

Representation
--------------
Every pipe ``j = 0..n+1`` (``0`` and ``n + 1`` are the walls) moves as a trigonometric polynomial

    x_j(t) = c0 + sum_m a_m cos(F_m t) + b_m sin(F_m t),   F = (omega, Omega_1, ..., Omega_K),

stored as the vector ``[c0, a_0, b_0, a_1, b_1, ...]`` in absolute time (eq. 21 for a free pipe).
A gap ``Delta_i = x_{i+1} - x_i`` is the difference of two such vectors.

Certified first-root search (:meth:`Engine.search`)
---------------------------------------------------
For ``g(t) = c0 + sum_m (a_m cos + b_m sin)`` put ``c_m = |(a_m, b_m)|`` and
``M_k = sum_m c_m F_m**k`` so that ``|g^(k)| <= M_k``.

* If ``c0 - sum c_m > 0`` the gap can never close: it is not searched at all.
* From a point where ``g = D > 0`` and ``g' = V``, ``g(t + s) >= D + V s - M_2 s^2 / 2`` (and, for
  ``s <= H``, ``>= D + V s + (g'' - M_3 H / 3) s^2 / 2``), so a step to the first root of either
  lower bound can never jump over a root of ``g``.  Every quantity carries its rounding bound.
* If ``V < 0`` and ``2 M_2 D < V^2``, ``g`` is strictly decreasing on ``[t, t + 2 D / |V|]`` and
  negative at its end: exactly one root there, refined by safeguarded Newton to full precision.
* If ``g`` comes within rounding of zero without a certified crossing, the local minimum is
  located (Newton on ``g'``): a true dip below rounding is a (small-velocity) impact, otherwise a
  **graze** (tangential contact, relative velocity zero within rounding) which is reported as an
  event of its own and changes no velocity.
* A gap within rounding of zero that is closing (``V < 0``) has its root at the first root of
  ``D + V s + A s^2 / 2`` (a small ``|V|`` under a closing curvature makes ``D / |V|`` far too
  late).
* Each (re)search stops at the first certified point beyond the next scheduled event of the other
  sites (an event there may change this gap: then it is searched again from scratch; if not, the
  search resumes where it stopped, so no step is repeated).
* At a contact (``g = 0`` after an impact, graze or release) the search starts one-sidedly from
  the Taylor bound ``V s + g'' s^2/2 - M_3 s^3/6`` (or the next non-vanishing derivative), so it
  never rediscovers the same root.  A gap that starts overlapping by more than rounding while
  opening is such a contact too; a *contact force* that starts below ``-tolD`` is tensile, so
  its contact releases at once, however fast the force is rising.

Events
------
``IMPACT``: Newton restitution ``u -> -r u`` between the two bodies (a body is a pipe or a stuck
cluster; masses count pipes, walls are infinitely heavy).  ``GRAZE``: see above.  ``STICK``: chatter
ends -- when the relative velocity at a contact is below ``v_stick`` (after an impact: while the
free relative acceleration pushes the pair together), the two bodies merge (momentum kept) and
move as one in closed form; the event's ``aux`` is the estimated accumulation time of the skipped
impacts ``t + 2 r |u| / (|Delta''| (1 - r))``.  ``RELEASE``: a stuck contact opens when its
contact force (itself a trigonometric polynomial with the forcing frequencies only) crosses zero.

Plastic and slow contacts: an impact slower than ``v_stick``, and every impact with ``r = 0``,
merges the two bodies (``STICK``); the merged body's contact force then decides (``RELEASE`` as
soon as it is tensile, possibly at the same instant), so an ``r = 0`` cascade through a chain of
touching pipes is resolved in one merge per contact instead of a velocity halved forever.  A
stuck contact is therefore compressive (or within rounding of zero) at every time: a merge
under tension is released at its own instant, even while the tension still grows.

Simultaneous events are processed in increasing time; at one instant the free gaps (impacts)
before the stuck ones (releases), then in increasing site order, each pairwise; a contact left
approaching by an earlier one fires at the same instant (sequential pairwise rule -- for ``r = 1``
and equal masses it reproduces Newton's cradle).

Every cluster ends (bounds on the number of events)
---------------------------------------------------
* At one instant: after :func:`cascade_bound` ``= 20 (n + 1) + 100`` events every further impact
  of that instant is plastic (merges two bodies: at most ``n + 1`` more, and a release leaves both
  sides with the same velocity, so it creates no approaching pair); a touch (graze) repeated at
  one site within one :meth:`Engine.touch_step` (the same instant, or a restart that found the
  touch again a rounding step later) merges the pair once, and a further repetition resumes the
  search a touch step later.  Twice the bound raises :class:`SimulationError` (never reached on
  the 1050-row sweep of the tests).
* Between instants, one site: after an impact the pair separates at ``|u'| > v_stick`` (slower
  ones stick), and ``|Delta''| <= M2`` (the site's bound), so the same gap cannot close again
  within ``2 v_stick / M2`` unless a neighbour's event changes it; by the rule above a site has
  at most five events (touch, touch again, merge, release, touch) per touch step
  ``(6 tolD / M3)**(1/3)``; a search that crawls ``_CRAWL`` steps just above zero is taken as
  a touch.  Hence an undisturbed site has at most
  ``1 + T max(M2 / (2 v_stick), 5 / touch_step)`` events in a time ``T``; events forced by
  neighbours are counted at the neighbours (a chain of them at one instant is the first case).
  This is an argument, not a machine-checked proof, for the interplay of several sites.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum
from typing import Any

import mpmath
import numpy as np

from symhx._mpctx import export, is_mpf, mp
from symhx.impact.model import PipeRow, SimulationError, exact_to_mpf
from symhx.validation import check_dps

__all__ = ["EVENT_DTYPE", "GRAZE", "IMPACT", "KIND_NAMES", "RELEASE", "STICK", "V_STICK_FLOAT64",
           "Engine", "EventKind", "EventLog", "FloatContext", "MPContext", "Outcome", "RowArrays",
           "default_v_stick", "row_arrays", "work_dps"]


class EventKind(IntEnum):
    """Kinds of recorded events (the values are those stored in :attr:`History.kinds`)."""

    IMPACT = 0    #: Newton restitution at a closing contact
    GRAZE = 1     #: tangential touch: zero relative velocity, nothing changes
    STICK = 2     #: the two bodies merge (chatter ended, or a plastic impact)
    RELEASE = 3   #: a stuck contact opens (its contact force turned tensile)


IMPACT, GRAZE, STICK, RELEASE = (EventKind.IMPACT, EventKind.GRAZE, EventKind.STICK,
                                 EventKind.RELEASE)
KIND_NAMES = ("impact", "graze", "stick", "release")


class Outcome(IntEnum):
    """Outcome of the certified search of one site (:meth:`Engine.search`)."""

    NONE = 0    #: never closes (time is inf)
    CONT = 1    #: no root before the returned time (certified up to it): resume there
    ROOT = 2    #: a crossing (impact) at the returned time
    GRAZE = 3   #: a tangential touch at the returned time
    NOW = 4     #: at contact and approaching at the start time


# short aliases of the outcomes for this module's search and run loop
_NONE, _CONT, _ROOT, _GRAZE, _NOW = (Outcome.NONE, Outcome.CONT, Outcome.ROOT, Outcome.GRAZE,
                                     Outcome.NOW)
_TOL = 64  # rounding bound = _TOL * eps * (scale of the evaluated quantity)
_MAXIT = 1_000_000
_CRAWL = 100_000   # search steps after which a gap hovering above zero is taken as a touch


def work_dps(dps: int) -> int:
    """Working precision of the reference engine for ``dps`` wanted digits: ``2 dps + 10``.

    Doubling makes grazing-type contacts (whose velocity is the square root of the gap's
    rounding) accurate to ``dps`` digits too.

    >>> work_dps(30)
    70
    """
    return 2 * check_dps(dps) + 10


#: the factor of ``omega d`` in the float64 chatter threshold (:func:`default_v_stick`)
V_STICK_FLOAT64 = 10.0 ** (-10 / 2 - 1)


def default_v_stick(row: PipeRow, dps: int | None) -> float | mpmath.mpf:
    """Relative speed below which a contact sticks (chatter ends): ``omega d 10**(-dps/2 - 1)``.

    The position error of sticking at speed ``u`` instead of completing the chatter is
    ``u**2 / |Delta''| ~ 10**-dps``.  Float64 uses ``dps = 10`` (``1e-6 omega d``): slower
    bounces last ``2u/|Delta''|`` and their roots are below the rounding of the gap, so float64
    cannot resolve them anyway.  For an int ``dps`` the value is an mpf (``10**-2501`` at
    ``dps = MAX_DPS`` is below the float64 range).

    >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[0.0])
    >>> default_v_stick(row, None), float(default_v_stick(row, 20))
    (1e-06, 1e-11)
    """
    if not isinstance(row, PipeRow):
        raise TypeError(f"row must be a PipeRow, got {type(row).__name__} {row!r:.60}")
    dps = check_dps(dps, allow_none=True)
    if dps is None:
        return row.omega * row.d * V_STICK_FLOAT64
    ctx = mp()   # this thread's context: nothing depends on mpmath's global precision
    with ctx.workdps(20):
        v = ctx.mpf(row.omega) * row.d * ctx.power(10, -ctx.mpf(dps) / 2 - 1)
    return export(v)


def _cos_sin(x: float) -> tuple[float, float]:
    """``(cos x, sin x)`` in float64, absolute error below ``2**-52`` (tests: against mpmath):
    Cody-Waite reduction to the nearest multiple of pi/2 (three 33-bit parts: exact products
    for ``|x| < 2**19 pi/2``; the two small ones summed first) and the fdlibm minimax
    polynomials on ``[-pi/4, pi/4]`` (their tails by Estrin's scheme: shorter dependency
    chains, same accuracy).  The C engine (``_fast.c``) runs the same IEEE
    operations in the same order, so both float64 engines see identical values; larger ``|x|``
    use libm in both.
    """
    if not abs(x) < 823549.6:
        return math.cos(x), math.sin(x)
    # nearest integer to x 2/pi by the 1.5 * 2**52 shift (exact for |x 2/pi| < 2**19)
    fn = (x * 6.36619772367581382433e-01 + 6755399441055744.0) - 6755399441055744.0
    y = ((x - fn * 1.57079632673412561417e+00)
         - (fn * 6.07710050630396597660e-11 + fn * 2.02226624871116645580e-21))
    z = y * y
    z2 = z * z   # Estrin's scheme: shorter dependency chains than Horner, the same accuracy
    z4 = z2 * z2
    sr = ((8.33333333332248946124e-03 + z * -1.98412698298579493134e-04)
          + (z2 * (2.75573137070700676789e-06 + z * -2.50507602534068634195e-08)
             + z4 * 1.58969099521155010221e-10))
    sv = y + (z * y * -1.66666666666666324348e-01 + z2 * y * sr)
    cp = ((4.16666666666666019037e-02 + z * -1.38888888888741095749e-03)
          + (z2 * (2.48015872894767294178e-05 + z * -2.75573143513906633035e-07)
             + z4 * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))
    hz = 0.5 * z
    w = 1.0 - hz
    cv = w + (((1.0 - w) - hz) + z2 * cp)
    q = int(fn) & 3
    if q == 0:
        return cv, sv
    if q == 1:
        return -sv, cv
    if q == 2:
        return -cv, -sv
    return sv, -cv


class FloatContext:
    """Float64 arithmetic for :class:`Engine` (``num`` rounds an exact value to float64)."""

    is_mp = False
    eps = 2.0**-52
    inf = math.inf

    @staticmethod
    def num(x: Any) -> float:
        return float(x)

    cos = staticmethod(math.cos)
    sin = staticmethod(math.sin)
    sqrt = staticmethod(math.sqrt)

    cos_sin = staticmethod(_cos_sin)


class MPContext:
    """mpmath arithmetic in the calling thread's own context (``symhx._mpctx.mp()``), never in
    mpmath's global one: threads with different precisions do not see each other's.

    Create it in the thread that uses it and compute inside its :meth:`workdps` (the working
    precision of everything it makes, :attr:`eps` included); ``num`` rounds an exact value
    (``Fraction``, :data:`~symhx.impact.SQRT2`, ...) correctly at that precision.  Its numbers
    belong to this thread: pass them through ``symhx._mpctx.export`` before they leave it
    (:func:`symhx.impact.simulate` does).

    >>> from symhx.impact import SQRT2
    >>> mc = MPContext()
    >>> with mc.workdps(30):
    ...     print(mc.num(SQRT2), mc.eps == mc.num(2) ** -mc.mp.prec)
    1.41421356237309504880168872421 True
    """

    is_mp = True

    def __init__(self) -> None:
        ctx = self.mp = mp()
        self.inf = ctx.inf
        self.cos = ctx.cos
        self.sin = ctx.sin
        self.sqrt = ctx.sqrt
        self.cos_sin = ctx.cos_sin
        self.workdps = ctx.workdps
        self.workprec = ctx.workprec

    @property
    def eps(self) -> Any:
        """``2**-prec`` at the context's current precision."""
        return self.mp.ldexp(self.mp.mpf(1), -self.mp.prec)

    def num(self, x: Any) -> Any:
        return exact_to_mpf(x, self.mp)



@dataclass
class RowArrays:
    """The closed-form data of a row in one arithmetic (the only row-to-arrays conversion).

    ``F``: frequencies ``(omega, Omega_1, ...)``; ``coef``, ``forced``, ``raw``: arrays of shape
    ``(n + 2, L)`` (``L = 3 + 2 K``, rows ``0`` and ``n + 1`` are the walls) holding each pipe's
    motion ``[c0, a_0, b_0, a_1, b_1, ...]`` at ``t = 0`` (eq. 21), its forced particular solution
    and the raw force amplitudes ``alpha_ij, beta_ij`` (eq. 20); ``chunk``: search horizon.
    """

    F: np.ndarray
    coef: np.ndarray
    forced: np.ndarray
    raw: np.ndarray
    chunk: Any


def row_arrays(row: PipeRow, ctx: Any) -> RowArrays:
    """Closed-form arrays of ``row`` in the arithmetic ``ctx`` (float64 arrays for
    :class:`FloatContext`; object arrays of mpf from the row's *exact* inputs for
    :class:`MPContext`, inside its ``workdps``).

    Both engines use it: the float64 arrays are bit-identical whatever engine asks.

    >>> row = PipeRow.random(3, 0.1, seed=3, Omega=(0.37, 2.1), d=1.7)
    >>> ra = row_arrays(row, FloatContext())
    >>> ra.coef.shape, float(ra.coef[4, 0]) == 4 * 1.7
    ((5, 7), True)
    """
    n, K = row.n, len(row.Omega)
    if ctx.is_mp:
        num = ctx.num
        om, d = num(row.exact("omega")), num(row.exact("d"))
        F = np.array([om] + [num(w) for w in row.exact("Omega")], dtype=object)
        alpha = np.vectorize(num, otypes=[object])(row.exact("alpha"))
        beta = np.vectorize(num, otypes=[object])(row.exact("beta"))
        x0 = np.vectorize(num, otypes=[object])(row.exact("x0"))
        v0 = np.vectorize(num, otypes=[object])(row.exact("v0"))
        zero = num(0)
    else:
        om, d = float(row.omega), float(row.d)
        F = np.array([om] + [float(w) for w in row.Omega])
        alpha, beta = row.alpha, row.beta
        x0, v0 = row.x0, row.v0
        zero = 0.0
    L = 3 + 2 * K
    om2 = om * om
    # float64 arrays, or object arrays of mpf: the dtype follows the fill value
    forced = np.full((n + 2, L), zero)
    raw = np.full((n + 2, L), zero)
    coef = np.full((n + 2, L), zero)
    fx: Any = zero   # the forced part's position and velocity at t = 0, summed over m
    fv: Any = zero
    for m in range(K):
        a = alpha[:, m]
        b = beta[:, m]
        den = om2 - F[m + 1] * F[m + 1]
        fa = a / den
        fb = b / den
        forced[1:n + 1, 3 + 2 * m] = fa
        forced[1:n + 1, 4 + 2 * m] = fb
        raw[1:n + 1, 3 + 2 * m] = a
        raw[1:n + 1, 4 + 2 * m] = b
        fx = fx + fa
        fv = fv + fb * F[m + 1]
    jd = np.arange(1, n + 1) * d
    coef[1:n + 1] = forced[1:n + 1]
    coef[1:n + 1, 0] = jd
    coef[1:n + 1, 1] = x0 - jd - fx
    coef[1:n + 1, 2] = (v0 - fv) / om
    coef[n + 1, 0] = (n + 1) * d
    return RowArrays(F=F, coef=coef, forced=forced, raw=raw, chunk=2 / om)


#: one event record of the C engine (48 bytes: ``_fast.c`` writes this layout)
EVENT_DTYPE = np.dtype({"names": ["t", "site", "kind", "u0", "u1", "aux"],
                        "formats": ["f8", "i8", "i1", "f8", "f8", "f8"],
                        "offsets": [0, 8, 16, 24, 32, 40], "itemsize": 48})


class EventLog:
    """The typed record of one run, filled by either engine: through :meth:`add_event` and
    :meth:`add_update` (one at a time, the Python engines) or built by :meth:`from_buffers` (the
    buffers of the C engine, kept as they are: no per-event Python work).

    :meth:`event_arrays` gives ``times, sites, kinds, u_before, u_after, aux`` (one entry per
    event; ``kinds`` are :class:`EventKind` values); :meth:`updates` gives, per pipe ``j``, the
    times from which it follows each closed-form coefficient vector (the first is ``t = 0``).
    """

    def __init__(self, coef0: Any) -> None:
        self._coef0 = coef0
        self._events: list[tuple[Any, ...]] = []
        self._upd_t: list[list[Any]] | None = None   # per-pipe lists: built on first use
        self._upd_c: list[list[Any]] | None = None
        self._ev_arr: np.ndarray | None = None
        self._up_arr: np.ndarray | None = None
        self._width = 0

    @classmethod
    def from_buffers(cls, coef0: bytes, events: bytes, updates: bytes, width: int) -> EventLog:
        """The C engine's record as it comes: buffers of ``coef0`` (float64, ``(n + 2) x width``,
        the coefficients at ``t = 0``), ``events`` (records of :data:`EVENT_DTYPE`) and
        ``updates`` (float64 rows ``j, t, coef...``).  The events become an array at once, the
        updates only when :meth:`updates` is first called (a run that is never asked for states
        does not pay for them)."""
        log = cls(coef0)
        log._width = width
        log._ev_arr = np.frombuffer(events, dtype=EVENT_DTYPE)
        log._up_arr = updates   # type: ignore[assignment]
        return log

    def _coef0_rows(self) -> Any:
        c = self._coef0
        if isinstance(c, bytes):
            c = self._coef0 = np.frombuffer(c, dtype=np.float64).reshape(-1, self._width)
        return c

    def __len__(self) -> int:
        return len(self._events) if self._ev_arr is None else len(self._ev_arr)

    def _lists(self) -> tuple[list[list[Any]], list[list[Any]]]:
        if self._upd_t is None or self._upd_c is None:   # built together, on first use
            coef0 = self._coef0_rows()
            zero = coef0[0][0] * 0
            self._upd_t = [[zero] for _ in range(len(coef0))]
            self._upd_c = [[list(c)] for c in coef0]
        return self._upd_t, self._upd_c

    def add_event(self, t: Any, site: int, kind: EventKind, u_before: Any, u_after: Any,
                  aux: Any) -> None:
        """Append one event."""
        self._events.append((t, site, EventKind(kind), u_before, u_after, aux))

    def add_update(self, j: int, t: Any, coef: Any) -> None:
        """Pipe ``j`` follows the coefficient vector ``coef`` from time ``t`` on."""
        upd_t, upd_c = self._lists()
        upd_t[j].append(t)
        upd_c[j].append(coef)

    def event_arrays(self, dtype: Any = float) -> tuple[np.ndarray, ...]:
        """``(times, sites, kinds, u_before, u_after, aux)`` as arrays (``dtype`` for the real
        columns: ``float`` or ``object`` for mpf; sites int64, kinds int8)."""
        ev = self._ev_arr
        if ev is not None:   # the C engine's records: the fields as they are (no copies)
            return (ev["t"], ev["site"], ev["kind"], ev["u0"], ev["u1"], ev["aux"])
        cols = list(zip(*self._events, strict=True)) if self._events else [()] * 6
        return (np.array(cols[0], dtype=dtype), np.array(cols[1], dtype=np.int64),
                np.array(cols[2], dtype=np.int8), np.array(cols[3], dtype=dtype),
                np.array(cols[4], dtype=dtype), np.array(cols[5], dtype=dtype))

    def exported(self) -> EventLog:
        """This log with every mpf turned into mpmath's global type, bit for bit
        (``symhx._mpctx.export``): the record of a run of the mpmath engine, made in one thread's
        own context, safe to keep and to read in any thread.  Float logs come back as they are.
        """
        if self._ev_arr is not None or not is_mpf(self._coef0_rows()[0][0]):
            return self   # a float log (the C or the Python float64 engine)
        out = EventLog(export([list(c) for c in self._coef0_rows()]))
        out._events = [export(e) for e in self._events]
        if self._upd_t is not None:
            out._upd_t, out._upd_c = export(self._upd_t), export(self._upd_c)
        return out

    def updates(self) -> tuple[list[list[Any]], list[Any]]:
        """``(upd_t, upd_c)``: per pipe ``j = 0..n+1`` the start times and coefficient vectors
        of its closed-form pieces (C logs: built on first use, then cached)."""
        up: Any = self._up_arr
        if up is not None:
            coef0 = np.asarray(self._coef0_rows(), dtype=float)
            if isinstance(up, bytes):
                up = np.frombuffer(up, dtype=np.float64).reshape(-1, 2 + coef0.shape[1])
            j = up[:, 0].astype(np.int64)
            order = np.argsort(j, kind="stable")
            cuts = np.searchsorted(j[order], np.arange(len(coef0) + 1))
            upd_t: list[list[Any]] = []
            upd_c: list[Any] = []
            for k in range(len(coef0)):
                sel = order[cuts[k]:cuts[k + 1]]
                upd_t.append([0.0, *up[sel, 1].tolist()])
                upd_c.append(np.vstack((coef0[k:k + 1], up[sel, 2:])))
            self._upd_t, self._upd_c = upd_t, upd_c
            self._up_arr = None
        return self._lists()


def cascade_bound(n: int) -> int:
    """Events at one instant after which the rest of the instant is resolved plastically
    (``20 (n + 1) + 100``; twice as many raise :class:`SimulationError`)."""
    return 20 * (n + 1) + 100


class Engine:
    """The event-driven engine in the arithmetic ``ctx`` (:class:`FloatContext` or
    :class:`MPContext`); :meth:`run` fills :attr:`log` (an :class:`EventLog`)."""

    def __init__(self, row: PipeRow, ctx: Any, *, v_stick: Any, chunk: float | None = None):
        self.row = row
        self.ctx = ctx
        num = ctx.num
        n = row.n
        self.n = n
        self.r = num(row.exact("restitution")) if ctx.is_mp else float(row.restitution)
        ra = row_arrays(row, ctx)
        self.om = ra.F[0]
        self.d = num(row.exact("d")) if ctx.is_mp else float(row.d)
        self.F = ra.F.tolist()
        L = 3 + 2 * len(row.Omega)
        self.L = L
        zero = num(0)
        self.zero = zero
        self.forced = ra.forced.tolist()
        self.raw = ra.raw.tolist()
        self.coef: list[list[Any]] = ra.coef.tolist()
        self.stuck = [False] * (n + 1)
        self.v_stick = num(v_stick)
        # search horizon per (re)search: a gap is mostly re-searched (a neighbour's impact) about
        # every 1/omega to 3/omega at sigma = 0.3, so certifying further ahead is mostly wasted
        # (benchmarks/bench_impact.py: 2/omega is ~1.7x faster than 2 pi/omega)
        self.chunk = num(chunk) if chunk is not None else ra.chunk
        self.log = EventLog(ra.coef.tolist())   # its own copy: self.coef changes in the run
        self.plastic_at: Any = None   # instant at which the cascade backstop is active

    # ---------------------------------------------------------------- trig polynomials
    def derivs(self, g: Any, t: Any) -> tuple[Any, Any, Any, Any]:
        """g, g', g'', g''' at t."""
        D = g[0]
        V = A = J = self.zero
        for m, f in enumerate(self.F):
            a = g[1 + 2 * m]
            b = g[2 + 2 * m]
            if not a and not b:
                continue
            c, s = self.ctx.cos_sin(f * t)
            p = a * c + b * s          # value part
            q = b * c - a * s          # derivative / f
            D += p
            V += f * q
            f2 = f * f
            A -= f2 * p
            J -= f2 * f * q
        return D, V, A, J

    def bounds(self, g: list[Any]) -> tuple[Any, Any, Any, Any, Any, Any]:
        """``(c0, S, M1..M4)``: constant part (zero frequencies folded in) and the bounds."""
        sq = self.ctx.sqrt
        c0 = g[0]
        S = M1 = M2 = M3 = M4 = self.zero
        for m, f in enumerate(self.F):
            if not f:
                c0 += g[1 + 2 * m]
                continue
            c = sq(g[1 + 2 * m] ** 2 + g[2 + 2 * m] ** 2)
            S += c
            M1 += c * f
            M2 += c * f * f
            M3 += c * f * f * f
            M4 += c * f * f * f * f
        return c0, S, M1, M2, M3, M4

    # ---------------------------------------------------------------- certified search
    def search(self, g: list[Any], t0: Any, t_hi: Any, *, is_gap: bool = True,
               graze_restart: bool = False) -> tuple[Any, int]:
        """First event of ``g`` in ``[t0, t_hi]`` (see the module docstring).

        Returns ``(t, code)`` with code ``_NONE`` (never closes: ``t`` is inf), ``_CONT`` (no root
        before ``t``, the first certified point ``>= t_hi``), ``_ROOT``, ``_GRAZE`` or ``_NOW`` (at
        contact and approaching at ``t0``).
        """
        ctx = self.ctx
        eps = ctx.eps
        c0, S, M1, M2, M3, M4 = self.bounds(g)
        scale0 = abs(c0) + S
        if M2 == 0:  # constant
            return (ctx.inf, _NONE) if c0 > _TOL * eps * abs(c0) else (t0, _NOW)
        if c0 - S > _TOL * eps * scale0:  # amplitude bound: can never reach zero
            return ctx.inf, _NONE
        t = t0
        iM2 = 1 / M2       # per search: multiplications in the step loop, not divisions
        M3_3 = M3 / 3
        first = True
        for _it in range(_MAXIT):
            if t >= t_hi:   # certified up to t (>= t_hi): resume there, nothing is redone
                return t, _CONT
            D, V, A, J = self.derivs(g, t)
            at = abs(t)
            tolD = _TOL * eps * (scale0 + M1 * at)
            tolV = _TOL * eps * (M1 + M2 * at)
            tolA = _TOL * eps * (M2 + M3 * at)
            tolJ = _TOL * eps * (M3 + M4 * at)
            if first:
                first = False
                # a gap overlapping (by rounding) and not opening, or a contact force clearly
                # tensile, rising or not: contact now (a release at once for a stuck contact)
                if D < -tolD and not (is_gap and V > tolV):
                    return t, _NOW
                if D <= tolD:  # at contact: one-sided start
                    if graze_restart and V < 0:
                        V = self.zero
                    if V < -tolV:
                        return t, _NOW
                    if V > tolV:
                        if is_gap and V <= self.v_stick and A < -tolA:
                            return t, _NOW
                        Vl = V - tolV
                        Al = A - tolA
                        h = (Al / 2 + ctx.sqrt(Al * Al / 4 + 2 * Vl * M3 / 3)) / (M3 / 3)
                    elif A < -tolA:
                        return t, _NOW
                    elif A > tolA:
                        h = 3 * (A - tolA) / M3
                    elif J < -tolJ:
                        return t, _NOW
                    elif J > tolJ:
                        h = 4 * (J - tolJ) / M4
                    else:
                        raise SimulationError(
                            f"degenerate contact at t={t}: value and three derivatives vanish")
                    t = t + h * 3 / 4
                    continue
            elif D <= tolD or _it == _CRAWL:
                # came within rounding of zero from above (all earlier steps were certified), or
                # crawled _CRAWL steps along a gap that stays just above it: a touch there
                if V < -tolV and (A <= 0 or V * V > 8 * M2 * tolD):
                    # first root of D + V s + A s^2/2 (not D / -V: with a small |V| and a
                    # closing curvature that is far too late, and the gap overlaps meanwhile)
                    Dz = max(D, self.zero)
                    return t + 2 * Dz / (-V + ctx.sqrt(V * V - 2 * A * Dz)), _ROOT
                if A < -tolA and V <= tolV:   # compressed at zero speed: contact now
                    return t, _NOW
                return self._graze(g, t, t0, tolD)
            # D > tolD here
            Dl = D - tolD
            if V < 0:
                Vm = -V - tolV
                Dp = D + tolD
                if Vm > 0 and 2 * M2 * Dp < Vm * Vm:
                    return self.refine(g, t, t + 2 * Dp / Vm), _ROOT
            Vl = V - tolV
            h = (Vl + ctx.sqrt(Vl * Vl + 2 * M2 * Dl)) * iM2
            # cubic-improved step: on [0, H], g >= Dl + Vl s + (A - tolA - M3 H/3) s^2/2
            Al = A - tolA
            H = 2 * h
            for _k in range(5):
                c = (Al - M3_3 * H) / 2
                if Dl + Vl * H + c * H * H <= 0:
                    break
                # the bound's minimum (at s = -Vl / (2 c) inside [0, H]) is <= 0
                if c > 0 and Vl < 0 and -Vl < 2 * c * H and 4 * c * Dl <= Vl * Vl:
                    break
                h = H
                H = 2 * H
            t = t + h
        raise SimulationError(f"root search did not finish after {_MAXIT} steps (t={t})")

    def _graze(self, g: list[Any], t: Any, t0: Any, tolD: Any) -> tuple[Any, int]:
        eps = self.ctx.eps
        tg = t
        for _ in range(100):
            _, V, A, _ = self.derivs(g, tg)
            if A <= 0:
                break
            step = V / A
            tg = tg - step
            if abs(step) <= 4 * eps * (abs(tg) + 1):
                break
        if tg < t0:
            tg = t
        Dg = self.derivs(g, tg)[0]
        if Dg < -tolD and tg > t:
            return self.refine(g, t, tg), _ROOT
        return tg, _GRAZE

    def touch_step(self, g: Any, t: Any) -> Any:
        """``(6 tolD / M3)**(1/3)``: at a contact whose value, slope and curvature are all within
        rounding, ``|g| <= tolD + M3 s**3 / 6 <= 2 tolD`` on ``[t, t + s]``: nothing there can be
        told from the touch itself, so the search resumes after it."""
        eps = self.ctx.eps
        c0, S, M1, _, M3, _ = self.bounds(g)
        tolD = _TOL * eps * (abs(c0) + S + M1 * abs(t))
        return (6 * tolD / M3) ** (self.ctx.num(1) / 3) if M3 else self.chunk

    def refine(self, g: list[Any], lo: Any, hi: Any) -> Any:
        """Root of ``g`` in ``[lo, hi]`` where ``g(lo) > 0 > g(hi)`` and ``g`` is monotone.

        Safeguarded Householder iteration of order 3 (``g'', g'''`` come free with ``g, g'``:
        quartic convergence, one evaluation fewer than Halley on most roots of the benchmark
        rows), Halley or Newton where its denominator has the wrong sign, bisection where a step
        leaves the bracket; stops when ``|g|`` is within its rounding bound (then a last Newton
        step) or the step is below the resolution of ``t``.
        """
        eps = self.ctx.eps
        c0, S, M1, _, _, _ = self.bounds(g)
        x = lo
        for _ in range(400):
            D, V, A, J = self.derivs(g, x)
            if abs(D) <= _TOL * eps * (abs(c0) + S + M1 * abs(x)) and V < 0:
                return x - D / V
            if D > 0:
                lo = x
            elif D < 0:
                hi = x
            else:
                return x
            if V < 0:   # Householder of order 3 (J comes free too), else Halley, else Newton
                den3 = 6 * V * V * V - 6 * D * V * A + D * D * J
                if den3 < 0:
                    xn = x - D * (6 * V * V - 3 * D * A) / den3
                else:
                    den = 2 * V * V - D * A
                    xn = x - 2 * D * V / den if den > 0 else x - D / V
            else:
                xn = (lo + hi) / 2
            if not lo < xn < hi:
                xn = (lo + hi) / 2
            if abs(xn - x) <= 2 * eps * abs(xn) or hi - lo <= 4 * eps * abs(hi):
                return xn
            x = xn
        return x

    # ---------------------------------------------------------------- bodies
    def body(self, j: int) -> tuple[int, int]:
        lo = j
        while lo > 0 and self.stuck[lo - 1]:
            lo -= 1
        hi = j
        while hi < self.n + 1 and self.stuck[hi]:
            hi += 1
        return lo, hi

    def _is_wall(self, lo: int, hi: int) -> bool:
        return lo == 0 or hi == self.n + 1

    def _mass(self, lo: int, hi: int) -> Any:
        return None if self._is_wall(lo, hi) else hi - lo + 1

    def _pos_vel(self, j: int, t: Any) -> tuple[Any, Any]:
        D, V, _, _ = self.derivs(self.coef[j], t)
        return D, V

    def set_motion(self, lo: int, hi: int, t: Any, X: Any, Vel: Any) -> None:
        """Give the body ``lo..hi`` position ``X`` and velocity ``Vel`` at ``t`` (closed form)."""
        n = self.n
        if lo == 0:
            c = [self.zero] * self.L
        elif hi == n + 1:
            c = [self.zero] * self.L
            c[0] = (n + 1) * self.d
        else:
            m = hi - lo + 1
            c = [sum(self.forced[j][k] for j in range(lo, hi + 1)) / m for k in range(self.L)]
            c[0] = (lo + hi) * self.d / 2
            fx, fv, _, _ = self.derivs(c, t)      # constant + forced part
            y = X - fx
            yv = (Vel - fv) / self.om
            cs, sn = self.ctx.cos_sin(self.om * t)
            c[1] = y * cs - yv * sn
            c[2] = y * sn + yv * cs
        for j in range(max(lo, 1), min(hi, n) + 1):
            self.coef[j] = list(c)
            self.log.add_update(j, t, self.coef[j])

    def kick(self, lo: int, hi: int, t: Any, dv: Any) -> None:
        cs, sn = self.ctx.cos_sin(self.om * t)
        for j in range(max(lo, 1), min(hi, self.n) + 1):
            c = list(self.coef[j])
            c[1] -= dv * sn / self.om
            c[2] += dv * cs / self.om
            self.coef[j] = c
            self.log.add_update(j, t, c)

    def contact_force(self, k: int) -> list[Any]:
        """Contact force at stuck gap ``k`` as a trig polynomial (per unit mass of one pipe)."""
        lo, hi = self.body(k)
        n, L = self.n, self.L
        om2d = self.om * self.om * self.d
        out = [self.zero] * L
        if lo == 0:      # left wall body: lambda_k = -sum_{j>k} (om^2 j d + F_j)
            for j in range(k + 1, hi + 1):
                out[0] -= om2d * j
                for q in range(3, L):
                    out[q] -= self.raw[j][q]
        elif hi == n + 1:  # right wall body: lambda_k = sum_{j<=k} (-om^2 (n+1-j) d + F_j)
            for j in range(lo, k + 1):
                out[0] -= om2d * (n + 1 - j)
                for q in range(3, L):
                    out[q] += self.raw[j][q]
        else:             # free body: lambda_k = sum_{j<=k} (om^2 d (j - jbar) + F_j - Fbar)
            m = hi - lo + 1
            jbar2 = lo + hi   # 2 * jbar
            fbar = [sum(self.raw[j][q] for j in range(lo, hi + 1)) / m for q in range(L)]
            for j in range(lo, k + 1):
                out[0] += om2d * (2 * j - jbar2) / 2
                for q in range(3, L):
                    out[q] += self.raw[j][q] - fbar[q]
        return out

    def gap_poly(self, i: int) -> list[Any]:
        a, b = self.coef[i], self.coef[i + 1]
        return [b[q] - a[q] for q in range(self.L)]

    # ---------------------------------------------------------------- event loop
    def run(self, t_end: Any, max_events: int | None = None) -> None:
        n = self.n
        ctx = self.ctx
        t_end = ctx.num(t_end)
        nt: list[Any] = [ctx.inf] * (n + 1)
        nk: list[int] = [_NONE] * (n + 1)

        def schedule(i: int, t: Any, graze_restart: bool = False) -> None:
            t_hi = min(t + self.chunk, t_end)
            # no further than the next event of the other sites: it may well change this gap
            # (then the search restarts from scratch), and a search stopped there resumes
            # where it stopped (certified up to that point), so nothing is lost either way
            t_next = min((nt[k] for k in range(n + 1) if k != i), default=ctx.inf)
            if t < t_next < t_hi:
                t_hi = t_next
            if self.stuck[i]:
                te, code = self.search(self.contact_force(i), t, t_hi, is_gap=False,
                                       graze_restart=graze_restart)
            else:
                te, code = self.search(self.gap_poly(i), t, t_hi, graze_restart=graze_restart)
            if code == _CONT and te >= t_end:
                te, code = ctx.inf, _NONE
            nt[i] = te
            nk[i] = code

        t = self.zero
        for i in range(n + 1):
            schedule(i, t)
        last_t = None
        same = 0
        count = 0
        bound = cascade_bound(n)
        last_graze: tuple[Any, int] | None = None
        last_merge: tuple[Any, int] | None = None
        stuck = self.stuck
        while True:
            # earliest event; at one instant the free gaps (impacts) before the stuck ones
            # (releases), then the smallest site
            i = min(range(n + 1), key=lambda k: (nt[k], stuck[k], k))
            te = nt[i]
            if te > t_end:
                break
            code = nk[i]
            if te == last_t:
                same += 1
                if same == bound:
                    self.plastic_at = te      # backstop: the rest of this instant is plastic
                elif same > 2 * bound:
                    raise SimulationError(
                        f"more than {same} events at t={te} even with plastic impacts: "
                        "degenerate contact configuration")
            else:
                same = 0
                last_t = te
            t = te
            if code == _CONT:
                schedule(i, t)
                continue
            count += 1
            if max_events is not None and count > max_events:
                raise SimulationError(f"more than max_events={max_events} events before t_end")
            if self.stuck[i]:
                if code == _GRAZE:           # contact force touches zero: stays stuck
                    schedule(i, t, graze_restart=True)
                    continue
                lo, hi = self.body(i)
                X, Vel = self._body_state(lo, t)
                self.stuck[i] = False
                self.set_motion(lo, i, t, X, Vel)
                self.set_motion(i + 1, hi, t, X, Vel)
                self._record(t, i, RELEASE, self.zero, self.zero, t)
                self._reschedule(lo, hi, t, schedule)
                continue
            if code == _GRAZE:
                g = self.gap_poly(i)
                D, V, A, _ = self.derivs(g, t)
                self._record(t, i, GRAZE, V, V, D)
                # "the same touch": the same site within one touch step (the rounding time
                # scale, where nothing can be told from the touch itself; a curvature just above
                # rounding restarts the search ~1e-13 later, at a different instant)
                touch = self.touch_step(g, t)
                # (events come in time order, so t >= the time of either record)
                if last_merge is not None and last_merge[1] == i and t < last_merge[0] + touch:
                    # merged and released there already: step past the touch
                    schedule(i, t + touch, graze_restart=True)
                    continue
                if last_graze is not None and last_graze[1] == i and t < last_graze[0] + touch:
                    # the same touch again: value, slope and curvature
                    last_merge = (t, i)
                    lo, _ = self.body(i)   # are all rounding; the pair moves together
                    _, hi = self.body(i + 1)
                    self._stick(i, lo, hi, t, self.zero, A, self._mass(lo, i),
                                self._mass(i + 1, hi))
                    self._reschedule(lo, hi, t, schedule)
                    continue
                last_graze = (t, i)
                schedule(i, t, graze_restart=True)
                continue
            lo, hi = self._impact(i, t)
            self._reschedule(lo, hi, t, schedule)

    def _body_state(self, lo: int, t: Any) -> tuple[Any, Any]:
        if lo == 0:
            return self.zero, self.zero
        return self._pos_vel(lo, t)

    def _reschedule(self, lo: int, hi: int, t: Any, schedule: Any) -> None:
        for g in range(max(lo - 1, 0), min(hi, self.n) + 1):
            schedule(g, t)

    def _record(self, t: Any, site: int, kind: EventKind, u0: Any, u1: Any, aux: Any) -> None:
        self.log.add_event(t, site, kind, u0, u1, aux)

    def _impact(self, i: int, t: Any) -> tuple[int, int]:
        eps = self.ctx.eps
        lo, _ = self.body(i)
        _, hi = self.body(i + 1)
        g = self.gap_poly(i)
        _, u, A, J = self.derivs(g, t)
        _, _, _M1, M2, M3, _ = self.bounds(g)
        tolA = _TOL * eps * (M2 + M3 * abs(t))
        compressive = A < -tolA or (abs(A) <= tolA and J < 0)
        mL = self._mass(lo, i)
        mR = self._mass(i + 1, hi)
        r = self.r
        plastic = not r or (self.plastic_at is not None and t == self.plastic_at)
        if abs(u) <= self.v_stick:   # below the chatter threshold: the bodies move together
            self._stick(i, lo, hi, t, r * abs(u), A, mL, mR)
            return lo, hi
        if u >= 0:   # numerically zero relative velocity without compression: a touch
            self._record(t, i, GRAZE, u, u, self.zero)
            return lo, hi
        u1 = -r * u
        # Newton's law between the bodies: u -> -r u, momentum kept
        if mL is None:
            dvL, dvR = self.zero, -(1 + r) * u
        elif mR is None:
            dvL, dvR = (1 + r) * u, self.zero
        else:
            dvL = (1 + r) * u * mR / (mL + mR)
            dvR = -(1 + r) * u * mL / (mL + mR)
        if mL is not None:
            self.kick(lo, i, t, dvL)
        if mR is not None:
            self.kick(i + 1, hi, t, dvR)
        self._record(t, i, IMPACT, u, u1, self.zero)
        if plastic or (u1 <= self.v_stick and compressive):
            self._stick(i, lo, hi, t, abs(u1), A, mL, mR)
        return lo, hi

    def _stick(self, i: int, lo: int, hi: int, t: Any, u: Any, A: Any, mL: Any, mR: Any) -> None:
        """Merge the bodies at gap ``i``; ``u`` = speed of the next (skipped) bounce."""
        r = self.r
        if r < 1 and A < 0:
            aux = t + 2 * u / ((-A) * (1 - r))
        else:
            aux = t
        if self._is_wall(lo, hi):   # a wall body does not move: set_motion places it
            X = Vel = self.zero
        else:
            xL, vL = self._pos_vel(i, t)
            xR, vR = self._pos_vel(i + 1, t)
            X = (mL * xL + mR * xR) / (mL + mR)
            Vel = (mL * vL + mR * vR) / (mL + mR)
        self.stuck[i] = True
        self.set_motion(lo, hi, t, X, Vel)
        self._record(t, i, STICK, -u, self.zero, aux)


