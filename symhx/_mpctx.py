"""Thread-owned mpmath arithmetic: every symhx computation runs in a context of its own thread.

``mpmath.workdps`` changes mpmath's *process-wide* context (``mpmath.mp``), so two threads that
both raise and restore it run at each other's precision.  symhx never uses that context for its
own work.  Instead each thread gets a private :class:`mpmath.MPContext` (created on first use),
and symhx code computes with it exactly as it would with ``mpmath``::

    ctx = mp()
    with ctx.workdps(dps + guard):
        y = ctx.log(ctx.mpf(x))
    return export(y, dps)         # rounded once to dps digits, as the global mpmath.mpf type

Rules that keep this safe
-------------------------
* An ``mpf`` computes at the precision of *its own* context: ``x + y``, ``2 * x`` and ``+x``
  round at the context of ``x`` (the left operand, or the mpf one), whatever context is "in
  force".  ``ctx.<function>`` (``ctx.log``, ``ctx.fsum``, ``ctx.mpf``, ...) accepts an mpf of
  any context and computes at ``ctx``'s precision.
* A value that *leaves* a call (a return value, a cached attribute of an object that another
  thread may read, a value handed to another module's hook) is passed through :func:`export`:
  the global ``mpmath.mpf`` type, bit for bit, so users compute with it in their own context.
* A value that *enters* (a user's ``mpf``, a cached attribute, another module's return value)
  goes through :func:`local` (this thread's type, bit for bit) before any operator arithmetic.
* Values of the thread's context are used only in that thread (never stored where another
  thread can reach them); ``isinstance(x, mpmath.mpf)`` is False for them: use :func:`is_mpf`.
* Caches shared by threads hold exported values (or plain ints / ``_mpf_`` tuples).

Conventions between modules
---------------------------
* Helpers that take no precision argument (``symhx._numeric.G_mp``, ``mp_value``,
  ``stirling_series``, ``log1m_series``) compute in the calling thread's context :func:`mp` at
  its current precision (the caller sets it with ``mp().workdps``), accept mpf of any context
  and return values of that thread's context, ready for the caller's arithmetic.
* Public functions, frozen results, cached attributes and the hooks a subclass hands its base
  class (``SpaceDistribution._mp_moments``, ``_mp_terms``, ``_pmf1``, ``_logpmf1`` for
  :class:`symhx.distribution.Distribution`) return exported values; the receiver localises
  them before operator arithmetic.

The global ``mpmath.mp`` is neither read nor changed: a user's ``mp.dps`` has no effect on symhx,
and symhx's precision has none on the user's code.  ``mpmath.libmp`` functions that take an
explicit ``prec`` are thread-safe and may be called directly.

python-flint's precision (``flint.ctx.prec``) is process-wide as well; symhx sets it only through
:func:`symhx.certify.arb_prec`, which holds a process-wide lock while the block runs (Arb
sections are serialized across threads).

>>> import mpmath
>>> ctx = mp()
>>> with ctx.workdps(30):
...     third = export(ctx.mpf(1) / 3)
>>> isinstance(third, mpmath.mpf), mpmath.mp.dps
(True, 15)
>>> mpmath.nstr(third, 30)
'0.333333333333333333333333333333'
>>> export(third, 5)            # rounded once, to 5 digits (20 bits)
mpf('0.33333349227905273')
"""

from __future__ import annotations

import threading
from typing import Any

import mpmath
from mpmath import libmp
from mpmath.ctx_mp_python import _mpf  # the base class of every context's mpf

__all__ = ["export", "is_mpf", "local", "make_mpf", "mp", "prec_of_dps"]

_tls = threading.local()


def mp() -> Any:
    """This thread's private :class:`mpmath.MPContext` (53 bits until the caller's
    ``workdps``/``workprec`` raises it; every use sets its own precision)."""
    try:
        return _tls.ctx
    except AttributeError:
        ctx = _tls.ctx = mpmath.MPContext()
        return ctx


def is_mpf(x: Any) -> bool:
    """True for a real mpmath number of *any* context (global or private); False for other
    objects that merely carry an ``_mpf_`` (a sympy ``Float``)."""
    return isinstance(x, _mpf)


def prec_of_dps(dps: int) -> int:
    """The binary precision that ``workdps(dps)`` sets (mpmath's ``dps_to_prec``)."""
    return int(libmp.dps_to_prec(int(dps)))


def make_mpf(raw: tuple) -> Any:
    """A global ``mpmath.mpf`` holding the raw libmp value ``raw`` (``(sign, man, exp, bc)``,
    e.g. from ``libmp.from_man_exp(man, exp, prec, rnd)``), bit for bit."""
    return mpmath.mp.make_mpf(raw)


def export(x: Any, dps: int | None = None) -> Any:
    """``x`` as the global ``mpmath`` type (``mpf``/``mpc`` of any context), bit for bit, or,
    with ``dps``, rounded once to ``dps`` significant digits (to nearest: the value that
    ``+x`` inside ``workdps(dps)`` gives); tuples, lists and dict values are exported
    element-wise; anything else is returned unchanged."""
    if hasattr(x, "_mpf_"):
        v = x._mpf_
        if dps is not None:
            v = libmp.mpf_pos(v, prec_of_dps(dps), libmp.round_nearest)
        return make_mpf(v)
    if hasattr(x, "_mpc_"):
        re, im = x._mpc_
        if dps is not None:
            prec = prec_of_dps(dps)
            re = libmp.mpf_pos(re, prec, libmp.round_nearest)
            im = libmp.mpf_pos(im, prec, libmp.round_nearest)
        return mpmath.mp.make_mpc((re, im))
    if isinstance(x, tuple):
        return tuple(export(v, dps) for v in x)
    if isinstance(x, list):
        return [export(v, dps) for v in x]
    if isinstance(x, dict):
        return {k: export(v, dps) for k, v in x.items()}
    return x


def local(x: Any) -> Any:
    """``x`` as this thread's type with the same bits (an ``mpf``/``mpc`` of any context);
    tuples, lists and dict values element-wise; anything else is returned unchanged (convert
    it with ``mp().mpf`` where a number is due)."""
    ctx = mp()
    if hasattr(x, "_mpf_"):
        return ctx.make_mpf(x._mpf_)
    if hasattr(x, "_mpc_"):
        return ctx.make_mpc(x._mpc_)
    if isinstance(x, tuple):
        return tuple(local(v) for v in x)
    if isinstance(x, list):
        return [local(v) for v in x]
    if isinstance(x, dict):
        return {k: local(v) for k, v in x.items()}
    return x
