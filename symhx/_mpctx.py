"""Thread-owned mpmath arithmetic: every symhx computation runs in a context of its own thread.

``mpmath.workdps`` changes mpmath's *process-wide* context (``mpmath.mp``), so two threads that
both raise and restore it run at each other's precision.  symhx never uses that context for its
own work.  Instead each thread gets a private :class:`mpmath.MPContext` (created on first use),
and symhx code computes with it exactly as it would with ``mpmath``::

    ctx = mp()
    with ctx.workdps(dps + guard):
        y = ctx.log(ctx.mpf(x))
    return export(y)

Rules that keep this safe:

* an ``mpf`` computes at the precision of *its own* context (``x + y`` uses ``x``'s), so a value
  that leaves the call (a return value, a cached attribute of an object that another thread may
  read) is passed through :func:`export` (for the user: global ``mpmath.mpf``, bit for bit) and
  a value that enters (a user's ``mpf``, a cached attribute) through :func:`local` (this
  thread's type, bit for bit) before any arithmetic;
* values of the thread's context are used only in that thread;
* ``isinstance(x, mpmath.mpf)`` is False for a private-context ``mpf``: use :func:`is_mpf`.

The global ``mpmath.mp`` is neither read nor changed: a user's ``mp.dps`` has no effect on symhx,
and symhx's precision has none on the user's code.

>>> import mpmath
>>> ctx = mp()
>>> with ctx.workdps(30):
...     third = export(ctx.mpf(1) / 3)
>>> isinstance(third, mpmath.mpf), mpmath.mp.dps
(True, 15)
>>> mpmath.nstr(third, 30)
'0.333333333333333333333333333333'
"""

from __future__ import annotations

import threading
from typing import Any

import mpmath

__all__ = ["export", "is_mpf", "local", "mp"]

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
    """True for a real mpmath number of *any* context (global or private)."""
    return hasattr(x, "_mpf_")


def export(x: Any) -> Any:
    """``x`` as the global ``mpmath`` type with the same bits (``mpf``/``mpc`` of any context);
    tuples and lists are exported element-wise; anything else is returned unchanged."""
    if hasattr(x, "_mpf_"):
        return mpmath.mp.make_mpf(x._mpf_)
    if hasattr(x, "_mpc_"):
        return mpmath.mp.make_mpc(x._mpc_)
    if isinstance(x, tuple):
        return tuple(export(v) for v in x)
    if isinstance(x, list):
        return [export(v) for v in x]
    return x


def local(x: Any) -> Any:
    """``x`` as this thread's type with the same bits (an ``mpf``/``mpc`` of any context);
    anything else is returned unchanged (convert it with ``mp().mpf`` where a number is due)."""
    ctx = mp()
    if hasattr(x, "_mpf_"):
        return ctx.make_mpf(x._mpf_)
    if hasattr(x, "_mpc_"):
        return ctx.make_mpc(x._mpc_)
    return x
