"""The theory chain ``sigma -> p -> (mean, mode of X)`` of figure 10."""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from symhx._mpctx import mp as thread_mp
from symhx.forcing.arguments import ForcingParams, float_arg
from symhx.forcing.probability import evaluate
from symhx.validation import InputError, check_dps, check_N, show_exact

__all__ = ["THEORY_MAX_N", "THEORY_P_FLOOR", "TheoryCurve", "theory_curve"]

#: largest ``N`` of :func:`theory_curve`: the mean is a float64 array, so N must stay inside the
#: float range (the simple-space distribution itself is summed up to
#: ``symhx.distribution.MP_SUM_N_LIMIT = 10**1000``); modes beyond int64 come as Python ints
THEORY_MAX_N = 10**300
#: below this ``p`` the graph model is evaluated at ``THEORY_P_FLOOR`` itself: there ``X = 1``
#: with probability ``1 - O(N p)``, so mean and mode are already 1 in float64 (checked at the
#: call); an exact ``p`` with an exponent of millions of bits would make the model's exact
#: conversion of ``p`` run for minutes
THEORY_P_FLOOR = "1e-1000"


class TheoryCurve(NamedTuple):
    """Result of :func:`theory_curve`: arrays over ``sigma`` (mean, mode from the graph model)."""

    sigma: np.ndarray
    p: np.ndarray
    mean: np.ndarray
    mode: np.ndarray
    N: int


def theory_curve(
    sigma: Any,
    *,
    N: int = 101,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    space: str = "simple",
    dps: int = 30,
) -> TheoryCurve:
    """The chain ``sigma -> p -> (mean, mode of X)``: figure 10's theory curve in one call.

    ``p`` is :func:`impact_probability` at ``dps`` digits (mpmath, so ``p`` far below 1e-16 is
    exact), then ``symhx.mean(N, p, space=space, dps=dps)`` and ``symhx.mode(N, p,
    space=space)`` of the graph model (``N = n + 1`` possible impacts for ``n`` pipes; the
    paper's simulation has ``n = 100``, ``N = 101``).

    Parameters
    ----------
    sigma : float or array_like
        Forcing standard deviations.
    N : int
        Number of possible impacts (vertices).
    sigma1, omega, Omega, d
        As in :func:`impact_probability`.
    space : str
        Sample space of the graph model (``"simple"``, ``"eq41"``, ...).
    dps : int
        Digits of the mpmath evaluation.

    Returns
    -------
    TheoryCurve
        ``sigma``, ``p`` (float arrays), ``mean`` (float array), ``mode`` (int array), ``N``.

    >>> tc = theory_curve([0.05, 0.3], N=101)
    >>> int(tc.mode[0]), bool(tc.mode[1] > 50), bool(tc.mean[0] < tc.mean[1])
    (1, True, True)
    """
    import symhx  # lazily: the graph model lives in a higher layer (the API)

    N = check_N(N)
    if N > THEORY_MAX_N:
        shown = f"{N}" if N < 10**30 else f"an integer of {len(str(N))} digits"
        cap = THEORY_MAX_N
        cap_shown = f"10**{len(str(cap)) - 1}" if cap == 10 ** (len(str(cap)) - 1) else \
            show_exact(cap)
        raise InputError(f"N must be <= THEORY_MAX_N = {cap_shown} (the limit "
                         f"symhx.forcing.theory.THEORY_MAX_N), got {shown}")
    dps = check_dps(dps)
    s = np.atleast_1d(float_arg("sigma", sigma))
    fp = ForcingParams.validated(1, sigma1, omega, Omega, d, dps=dps)
    if fp.broadcast_fields():
        raise TypeError("theory_curve: sigma1, omega, Omega and d must be scalars")
    ps, means, modes_ = [], [], []
    for sv in s.ravel():
        # float64 log p first: far below the floor p is not evaluated in mpmath at all
        lp = evaluate(ForcingParams.validated(float(sv), sigma1, omega, Omega, d), None, "logp")
        tiny = float(lp) < -2400.0  # p < exp(-2400) < THEORY_P_FLOOR
        if not tiny:
            pm = evaluate(ForcingParams.validated(float(sv), sigma1, omega, Omega, d, dps=dps),
                          dps, "p")
            with thread_mp().workdps(dps):
                floor = thread_mp().mpf(THEORY_P_FLOOR)
                tiny = pm < floor
        ps.append(0.0 if tiny else float(pm))
        if tiny:  # the limit p -> 0: evaluate at the floor and check it is the limit
            with thread_mp().workdps(dps):
                floor = thread_mp().mpf(THEORY_P_FLOOR)
            m_val = float(symhx.mean(N, floor, space=space, dps=dps))
            mo_val = int(symhx.mode(N, floor, space=space))
            if m_val != 1.0 or mo_val != 1:  # pragma: no cover - N <= THEORY_MAX_N
                raise InputError(f"sigma={sv!r}: p below {THEORY_P_FLOOR} is not in the "
                                 f"p -> 0 limit for N={N}")
            means.append(m_val)
            modes_.append(mo_val)
            continue
        means.append(float(symhx.mean(N, pm, space=space, dps=dps)))
        modes_.append(int(symhx.mode(N, pm, space=space)))
    return TheoryCurve(
        sigma=s,
        p=np.array(ps).reshape(s.shape),
        mean=np.array(means).reshape(s.shape),
        mode=np.array(modes_, dtype=np.int64 if N < 2**63 else object).reshape(s.shape),
        N=N,
    )
