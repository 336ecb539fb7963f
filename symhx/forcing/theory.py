"""The theory chain ``sigma -> p -> (mean, mode of X)`` of figure 10."""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from symhx.forcing.arguments import ForcingParams, float_arg
from symhx.forcing.probability import evaluate
from symhx.validation import check_dps, check_N

__all__ = ["TheoryCurve", "theory_curve"]


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
    dps = check_dps(dps)
    s = np.atleast_1d(float_arg("sigma", sigma))
    fp = ForcingParams.validated(1, sigma1, omega, Omega, d, dps=dps)
    if fp.broadcast_fields():
        raise TypeError("theory_curve: sigma1, omega, Omega and d must be scalars")
    ps, means, modes_ = [], [], []
    for sv in s.ravel():
        pm = evaluate(ForcingParams.validated(float(sv), sigma1, omega, Omega, d, dps=dps),
                      dps, "p")
        ps.append(float(pm))
        means.append(float(symhx.mean(N, pm, space=space, dps=dps)))
        modes_.append(int(symhx.mode(N, pm, space=space)))
    return TheoryCurve(
        sigma=s,
        p=np.array(ps).reshape(s.shape),
        mean=np.array(means).reshape(s.shape),
        mode=np.array(modes_, dtype=np.int64).reshape(s.shape),
        N=N,
    )
