"""Arguments of the forcing functions: conversion, validation and the forcing value object.

Every public forcing function converts its arguments here once, through the package's one
validation layer (:mod:`symhx.validation`):

* scalars: ints, Fractions, sympy Rationals and decimal strings (``"0.05"``) are exact rationals;
  floats and mpf are taken at their exact binary value; bools, NaN, infinities and values
  ``<= 0`` raise ``ValueError``/``TypeError`` naming the argument;
* arrays (lists, tuples, numpy arrays) are float64 arrays (object arrays of decimal strings too);
  errors name the first bad index; an *empty* array gives an empty result of the same shape
  (as numpy/scipy ufuncs do).

>>> fp = ForcingParams.validated("0.05", dps=30)
>>> fp.sigma, fp.omega, fp.components
(Fraction(1, 20), Fraction(1, 1), False)
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

from symhx._mpctx import export, is_mpf
from symhx._mpctx import mp as thread_mp
from symhx.validation import (
    InputError,
    brief_repr,
    check_array,
    check_dps,
    float64_refusal,
    to_rational,
)

__all__ = [
    "IRRATIONAL_EXTRA_DIGITS",
    "MAX_SCALES",
    "ForcingParams",
    "bad_index",
    "elementwise",
    "export_result",
    "exported",
    "float_arg",
    "is_array",
    "is_components",
    "mp_arg",
    "mpf_of",
    "rational_arg",
]


def is_array(value: Any) -> bool:
    """Lists, tuples and numpy arrays (of any dimension) are arrays; everything else a scalar."""
    return isinstance(value, (list, tuple, np.ndarray))


def is_components(Omega: Any) -> bool:
    """A list/tuple ``Omega`` means several forcing components (eq. 22); arrays broadcast."""
    return isinstance(Omega, (list, tuple))


def bad_index(arr: np.ndarray, bad: np.ndarray) -> str:
    """`` at index i`` (or a tuple for n-D arrays) of the first True of ``bad``; ``""`` for 0-D."""
    if arr.ndim == 0:
        return ""
    idx = np.unravel_index(int(np.argmax(bad)), arr.shape)
    return f" at index {idx[0] if len(idx) == 1 else tuple(int(i) for i in idx)}"


def export_result(x: Any) -> Any:
    """A public result as the global ``mpmath`` type, bit for bit (mpf/mpc, and inside
    tuples, named tuples, lists and object arrays): the forcing layer computes in the calling
    thread's context (:mod:`symhx._mpctx`), its users compute with ``mpmath``."""
    if hasattr(x, "_mpf_") or hasattr(x, "_mpc_"):
        return export(x)
    if isinstance(x, np.ndarray):
        if x.dtype != object:
            return x
        out = np.empty(x.shape, dtype=object)
        for idx in np.ndindex(x.shape):
            out[idx] = export_result(x[idx])
        return out
    if isinstance(x, tuple):
        vals = [export_result(v) for v in x]
        return type(x)(*vals) if hasattr(x, "_fields") else tuple(vals)
    if isinstance(x, list):
        return [export_result(v) for v in x]
    return x


def exported(fn: Callable[..., Any]) -> Callable[..., Any]:
    """Decorator of the public functions and methods: results through :func:`export_result`."""
    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        return export_result(fn(*args, **kwargs))
    return wrapper


#: most Rayleigh scales of a sum (``RayleighSum``; eq. 22 with ``M + 1`` amplitudes, so at most
#: ``MAX_SCALES - 1`` forcing components): checked before any conversion or evaluation, for the
#: float64 and the mpmath paths alike (the float64 path takes under 50 ms a threshold at this
#: size, the mpmath path is bounded by ``rayleigh.MAX_MP_SUM_WORK`` too)
MAX_SCALES = 64


#: extra digits of a sympy irrational input over the requested ``dps``: ``p = exp(-E)`` turns a
#: relative error ``eps`` of sigma, omega, Omega or d into ``~2 E eps`` in ``p``, and ``E`` may
#: reach ``MAX_EXPONENT`` (~1.8e308) in the mpmath evaluation
IRRATIONAL_EXTRA_DIGITS = 330


def rational_arg(name: str, value: Any, digits: int = 40) -> Fraction:
    """A scalar ``> 0`` as an exact Fraction (a sympy irrational rounded to ``digits``)."""
    if isinstance(value, Fraction) and value > 0:
        return value
    fr = to_rational(value, name)
    if fr is None:  # a real sympy irrational such as sqrt(2)
        fr = Fraction(str(value.evalf(digits)))
    if not fr > 0:
        raise InputError(f"{name} must be > 0, got {brief_repr(value)}")
    return fr


def float_arg(name: str, value: Any, *, positive: bool = True) -> np.ndarray:
    """A finite (``> 0`` if ``positive``) float64 array; scalars give 0-d arrays.

    Scalars go through the exact conversion (decimal strings allowed); a value outside the
    float64 range is refused with a pointer to ``dps=``.
    """
    if isinstance(value, np.ndarray) and value.dtype.kind == "f" and value.ndim:
        arr = value.astype(np.float64, copy=False)
        fin = np.isfinite(arr)
        if not fin.all():
            raise InputError(f"{name} must be finite, got {float(arr[~fin].flat[0])!r}"
                             f"{bad_index(arr, ~fin)}")
        if positive and not (arr > 0).all():
            bad = ~(arr > 0)
            raise InputError(f"{name} must be > 0, got {float(arr[bad].flat[0])!r}"
                             f"{bad_index(arr, bad)}")
        return arr
    if is_array(value):
        return check_array(value, name, positive=positive, allow_empty=True)
    fr = rational_arg(name, value) if positive else to_rational(value, name)
    if fr is None:
        fr = Fraction(str(value.evalf(40)))
    try:
        x = float(fr)
    except OverflowError:
        raise float64_refusal(f"{name} = {brief_repr(value)} is outside the float64 "
                              "range") from None
    if fr != 0 and x == 0.0:
        raise float64_refusal(f"{name} = {brief_repr(value)} underflows float64")
    return np.asarray(x)


def mpf_of(fr: Fraction) -> mpmath.mpf:
    """``fr`` as an mpf rounded at the current precision (exact for dyadic fractions)."""
    num, den = fr.numerator, fr.denominator
    if den & (den - 1) == 0:  # a power of two: exact
        return thread_mp().ldexp(thread_mp().mpf(num), -(den.bit_length() - 1))
    return thread_mp().mpf(num) / den


def mp_arg(name: str, value: Any) -> mpmath.mpf:
    """A scalar ``> 0`` as an mpf at the current precision (floats and mpf exactly)."""
    if is_mpf(value) and thread_mp().isfinite(value) and value > 0:
        return thread_mp().mpf(value)  # any context's mpf, at this thread's precision
    return mpf_of(rational_arg(name, value))


def _object_rationals(name: str, value: Any, digits: int = 40) -> np.ndarray:
    """An object array of exact positive Fractions (first bad index in errors)."""
    arr = np.asarray(value, dtype=object)
    out = np.empty(arr.shape, dtype=object)
    for idx in np.ndindex(arr.shape):
        where = f" at index {idx[0] if len(idx) == 1 else idx}" if arr.ndim else ""
        try:
            out[idx] = rational_arg(name, arr[idx], digits)
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"{exc}{where}") from None
    return out


@dataclass(frozen=True)
class ForcingParams:
    """The validated forcing ``(sigma, sigma1, omega, Omega, d)`` of eqs. (19)-(27).

    For ``dps=None`` every field is a float64 array (0-d for scalars); otherwise an exact
    :class:`~fractions.Fraction` or an object array of them. ``sigma1=None`` means ``sigma_1 =
    sigma`` and ``Omega=None`` the paper's ``sqrt(2)``; several forcing components (eq. 22) have
    tuples ``Omega`` (and ``sigma1``, or ``None``/a scalar for all).
    """

    sigma: Any
    sigma1: Any = None
    omega: Any = Fraction(1)
    Omega: Any = None
    d: Any = Fraction(1)
    exact: bool = True

    @classmethod
    def validated(cls, sigma: Any, sigma1: Any = None, omega: Any = 1, Omega: Any = None,
                  d: Any = 1, *, dps: int | None = None) -> ForcingParams:
        """Convert and check every argument once (see the module docstring); ``dps`` (checked
        here too) only decides exact Fractions (an int) or float64 arrays (``None``)."""
        dps = check_dps(dps, allow_none=True)
        if is_components(Omega) and len(Omega) == 1:  # one component given as a list
            Omega = Omega[0]
            if is_components(sigma1):
                if len(sigma1) != 1:
                    raise InputError(
                        f"sigma1: {len(sigma1)} values for 1 forcing component (Omega)")
                sigma1 = sigma1[0]
        exact = dps is not None

        for name, v in (("sigma", sigma), ("omega", omega), ("d", d)):
            if v is None:
                raise TypeError(f"{name} must be a real number, got None")
        if isinstance(Omega, np.ndarray) and Omega.size == 0:
            raise InputError("Omega: an empty array of forcing frequencies (give a scalar, a "
                             "list of components or None for the paper's sqrt(2))")

        digits = (dps or 0) + IRRATIONAL_EXTRA_DIGITS  # for sympy irrational inputs

        def conv(name: str, v: Any) -> Any:
            if v is None:
                return None
            if exact:
                return (_object_rationals(name, v, digits) if is_array(v)
                        else rational_arg(name, v, digits))
            return float_arg(name, v)

        if is_components(Omega):
            if not Omega:
                raise InputError("Omega: an empty list of forcing components")
            if len(Omega) + 1 > MAX_SCALES:
                raise InputError(f"Omega: {len(Omega)} forcing components, more than "
                                 f"MAX_SCALES - 1 = {MAX_SCALES - 1} (a sum of at most "
                                 f"symhx.forcing.arguments.MAX_SCALES = {MAX_SCALES} Rayleigh "
                                 f"amplitudes, eq. 22)")
            if any(is_array(o) for o in Omega):
                raise TypeError("Omega: each forcing component must be a scalar")
            om_t = tuple(conv(f"Omega[{i}]", o) for i, o in enumerate(Omega))
            if is_components(sigma1):
                if len(sigma1) != len(Omega):
                    raise InputError(f"sigma1: {len(sigma1)} values for {len(Omega)} forcing "
                                     "components (Omega)")
                s1 = tuple(conv(f"sigma1[{i}]", s) for i, s in enumerate(sigma1))
            else:
                s1 = conv("sigma1", sigma1)
            return cls(conv("sigma", sigma), s1, conv("omega", omega), om_t, conv("d", d), exact)
        return cls(conv("sigma", sigma), conv("sigma1", sigma1), conv("omega", omega),
                   conv("Omega", Omega), conv("d", d), exact)

    @property
    def components(self) -> bool:
        """Several forcing components (eq. 22 with ``M >= 2``)."""
        return isinstance(self.Omega, tuple)

    def broadcast_fields(self) -> list[str]:
        """Names of the fields that are arrays (the others are scalars or component tuples)."""
        return [k for k in ("sigma", "sigma1", "omega", "Omega", "d")
                if isinstance(getattr(self, k), np.ndarray) and getattr(self, k).ndim]

    def scalars(self) -> tuple[tuple[int, ...] | None, Iterator[tuple[tuple[int, ...],
                                                                     ForcingParams]]]:
        """``(shape, iterator of (index, scalar ForcingParams))``; shape None for scalars."""
        keys = self.broadcast_fields()
        if not keys:
            return None, iter([((), self)])
        arrs = np.broadcast_arrays(*(getattr(self, k) for k in keys))
        shape = arrs[0].shape

        def gen() -> Iterator[tuple[tuple[int, ...], ForcingParams]]:
            for idx in np.ndindex(shape):
                kw = {k: a[idx] for k, a in zip(keys, arrs, strict=True)}
                if not self.exact:
                    kw = {k: np.asarray(v) for k, v in kw.items()}
                yield idx, _replace(self, kw)

        return shape, gen()


def _replace(fp: ForcingParams, kw: dict[str, Any]) -> ForcingParams:
    vals = {k: getattr(fp, k) for k in ("sigma", "sigma1", "omega", "Omega", "d", "exact")}
    vals.update(kw)
    return ForcingParams(**vals)


def elementwise(fp: ForcingParams, fn: Callable[[ForcingParams], Any], dtype: Any = object
                ) -> Any:
    """``fn`` applied to each scalar forcing of ``fp`` (a scalar result for scalar input, else
    an array of ``dtype``); a ValueError names the index where it happened."""
    shape, items = fp.scalars()
    if shape is None:
        return fn(fp)
    out = np.empty(shape, dtype=dtype)
    for idx, one in items:
        try:
            out[idx] = fn(one)
        except ValueError as exc:
            raise type(exc)(f"{exc} at index {idx if len(idx) > 1 else idx[0]}") from None
    return out
