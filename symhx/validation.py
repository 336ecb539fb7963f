"""The one conversion and validation layer of symhx.

Every public function and every CLI command converts its arguments here, so that one argument
means the same thing everywhere (API and CLI) and bad input always raises a clear error:

* :class:`InputError` (a :class:`ValueError`) for a value of the right kind outside what is
  allowed, and
  :class:`TypeError` for a wrong kind of object; every message names the argument, shows the
  value and says what is allowed.  Arrays report the first bad index.
* ``bool`` is never a number (``True`` is rejected wherever an int or a real is expected).

Input conventions for real numbers (``p``, ``sigma``, ...)
------------------------------------------------------------
* ``int``, numpy integers, :class:`fractions.Fraction`, :class:`decimal.Decimal`, sympy
  ``Rational`` and *decimal strings* (``"0.02"``, ``"2e-2"``, ``"1/50"``) are **exact
  rationals**: ``"0.02"`` is exactly 1/50.  Strings follow Python's literals: an underscore may
  only separate two digits (``"1_000"``, not ``"1__0"`` or ``"_1"``).
* ``float``, numpy floats (any width), ``mpmath.mpf`` and sympy ``Float`` are taken at their
  **exact binary value**: the float ``0.02`` is ``0.0200000000000000004163...``, slightly above
  1/50, so ``symhx.modes(101, 0.02) == (51,)`` while ``symhx.modes(101, "0.02") == (50, 51)``.
* Exact values are capped so that a typo cannot ask for billions of digits: decimal exponents
  beyond :data:`MAX_DECIMAL_EXPONENT` (strings, ``"b**e"`` and ``Decimal``) and binary exponents
  beyond :data:`MAX_BINARY_EXPONENT` (``mpf``, sympy ``Float``) are a ValueError.
* sympy irrationals (``sympy.sqrt(2)/50``) are accepted where documented. They are never read
  at a fixed number of digits: a decision about one (its sign here; modes elsewhere) is taken on
  a rigorous Arb ball of the expression (:func:`symhx.certify.real_ball`), the precision raised
  until it is proved, and a value is evaluated to the working precision of the computation.

Precision
---------
``dps`` is the number of significant decimal digits wanted in an mpmath result:
an int in ``[1, MAX_DPS]``.  ``dps=None`` means float64 for every numeric function that has a
float64 path.  :data:`DEFAULT_DPS` is the one default of the API and the CLI.

>>> to_rational("0.02")
Fraction(1, 50)
>>> to_rational("1/50") == to_rational("2e-2") == to_rational(Fraction(1, 50))
True
>>> check_dps(True, allow_none=True)
Traceback (most recent call last):
    ...
TypeError: dps must be an int between 1 and 5000 (or None for float64), got bool True
"""

from __future__ import annotations

import functools
import math
import numbers
import operator
import re
from collections.abc import Iterable
from decimal import Decimal
from fractions import Fraction
from typing import Any, Literal, overload

import mpmath
import numpy as np
from mpmath import libmp

from symhx._mpctx import is_mpf
from symhx.certify import UndecidedError, real_sign

__all__ = [
    "DEFAULT_DPS",
    "DEFAULT_SPACE",
    "IRRATIONAL_SIGN_BITS",
    "MAX_BINARY_EXPONENT",
    "MAX_DECIMAL_EXPONENT",
    "MAX_DPS",
    "MAX_SAMPLE_SIZE",
    "InputError",
    "as_fraction",
    "brief_repr",
    "check_N",
    "check_array",
    "check_choice",
    "check_dps",
    "check_int",
    "check_p",
    "check_real",
    "check_seed",
    "check_size",
    "exact_work_refusal",
    "float64_refusal",
    "is_exact_type",
    "mpf_to_fraction",
    "safe_repr",
    "short_value",
    "show_exact",
    "to_rational",
]

#: The one default precision (significant decimal digits) of the API and the CLI.
DEFAULT_DPS = 50
#: The largest ``dps`` accepted anywhere (a documented work limit: mpmath beyond this takes minutes
#: to hours per call).  Raise it by editing this constant if you really need more digits.
MAX_DPS = 5000
#: The sign of a sympy irrational ``p`` is proved on Arb balls of up to this many bits (about
#: 20 000 digits); an expression that is 0 in disguise (``pi - pi`` unevaluated) is refused.
IRRATIONAL_SIGN_BITS = 1 << 16
#: The default sample space of every distribution function, ``critical_point`` and the CLI.
DEFAULT_SPACE = "simple"
#: Decimal strings such as ``"1e100000"`` are parsed exactly; the exponent is capped here so that a
#: typo cannot ask for a number with billions of digits (10**100000 has 100001 digits).
MAX_DECIMAL_EXPONENT = 100_000
#: ``mpf`` values are taken at their exact binary value ``man * 2**exp``; beyond this binary
#: exponent that exact value has more than ~10**6 digits, so it is refused (the same guard as
#: :data:`MAX_DECIMAL_EXPONENT`; ``mpf('1e-100000')`` is well inside).
MAX_BINARY_EXPONENT = 3_400_000


class InputError(ValueError):
    """A user input that symhx refuses: a value of the right kind outside what is allowed, or
    beyond a documented work limit.  The message names the argument, shows the value and says
    what is allowed.

    Every refusal of symhx raises this type (a subclass of :class:`ValueError`, so ``except
    ValueError`` still catches it); the command line reports it as a usage error (exit code 2)
    and any other exception as an internal error (exit code 1).  A wrong kind of object is still
    a plain :class:`TypeError`.

    >>> check_int("2.5", "N")
    Traceback (most recent call last):
        ...
    symhx.validation.InputError: N must be an integer, got '2.5'
    >>> issubclass(InputError, ValueError)
    True

    ``cli``: the same refusal worded for the command line, when its remedy is an option there
    rather than an argument of the API (``--float`` instead of "pass p as a float"); the
    command line prints it instead of the message.
    """

    def __init__(self, message: str, *, cli: str | None = None) -> None:
        super().__init__(message)
        self.cli = cli


def float64_refusal(head: str) -> InputError:
    """The refusal of a value float64 cannot carry (``head`` says which and why), with the
    remedy: ``dps=`` (mpmath) in the API, ``--dps`` on the command line.

    >>> e = float64_refusal("sigma = '1e400' is outside the float64 range")
    >>> print(e); print(e.cli)
    sigma = '1e400' is outside the float64 range; use dps= (the mpmath path)
    sigma = '1e400' is outside the float64 range; use --dps (the mpmath path)
    """
    return InputError(f"{head}; use dps= (the mpmath path)",
                      cli=f"{head}; use --dps (the mpmath path)")


def exact_work_refusal(head: str, values: str = "p as a float or mpmath.mpf") -> InputError:
    """The refusal of exact (rational) work beyond a documented limit: ``head`` (what would be
    computed, how large, which limit), then the remedy, for the API (``values`` passed as
    floats or mpf: the mpmath path, or ``dps=None``: float64) and for the command line
    (``--float``).

    >>> e = exact_work_refusal("exact sums of N=10**6 beyond LIMIT")
    >>> str(e).endswith("; pass p as a float or mpmath.mpf for the mpmath path at dps digits, "
    ...                 "or dps=None for float64")
    True
    >>> print(e.cli)
    exact sums of N=10**6 beyond LIMIT; use --float (mpmath at --dps digits)
    """
    return InputError(f"{head}; pass {values} for the mpmath path at dps digits, or dps=None "
                      f"for float64", cli=f"{head}; use --float (mpmath at --dps digits)")


def short_value(fr: Fraction) -> str:
    """An exact value in 5 significant digits for an error message (``1.0e+400``), not the
    hundreds of digits of a huge or tiny Fraction.

    >>> short_value(Fraction(10) ** 400)
    '1.0e+400'
    """
    if fr and abs(fr.numerator.bit_length() - fr.denominator.bit_length()) > 200:
        return _sci5(fr)  # mpmath's to_str takes seconds for a decimal exponent ~10**5
    return str(libmp.to_str(libmp.from_rational(fr.numerator, fr.denominator, 53,
                                                 libmp.round_nearest), 5))


def _sci5(fr: Fraction) -> str:
    """``fr`` (far from 1) as ``d.dddde+NN`` in 5 significant digits (trailing zeros dropped),
    mpmath's ``to_str`` style, with integer arithmetic only."""
    sign, a = ("-", -fr) if fr < 0 else ("", fr)
    e = math.floor(math.log10(a.numerator) - math.log10(a.denominator))
    num, den = a.numerator, a.denominator
    if e >= 0:
        den *= 10**e
    else:
        num *= 10 ** (-e)
    m = round(Fraction(num, den) * 10**4)  # 5 significant digits, if 1 <= num/den < 10
    while m >= 10**5:
        e, num, den = e + 1, num, den * 10
        m = round(Fraction(num, den) * 10**4)
    while m < 10**4:
        e, num = e - 1, num * 10
        m = round(Fraction(num, den) * 10**4)
    digits = str(m)
    frac = digits[1:].rstrip("0") or "0"
    return f"{sign}{digits[0]}.{frac}e{e:+d}"


#: largest number of random draws of one ``rvs`` call (distributions of X, ``RayleighSum``): the
#: draws and their uniforms are int64 / float64 arrays (16 bytes per draw: 10**7 draws ~160 MB,
#: ~1 s).  Checked before any work; draw in chunks, or raise the constant, for more.
MAX_SAMPLE_SIZE = 10**7


def check_size(size: Any, name: str = "size") -> tuple[int, ...] | None:
    """A sample ``size`` of an ``rvs`` method: ``None`` (one draw), a non-negative int or a tuple
    of them (a shape), with at most :data:`MAX_SAMPLE_SIZE` draws in all; returns the shape.

    >>> check_size(3), check_size((2, 3)), check_size(None)
    ((3,), (2, 3), None)
    """
    if size is None:
        return None
    if isinstance(size, (str, bytes)):
        raise TypeError(f"{name} must be None, an int >= 0 or a tuple of them, got {size!r}")
    if isinstance(size, tuple):
        shape = tuple(check_int(s, f"each entry of {name}", minimum=0) for s in size)
    else:
        shape = (check_int(size, name, minimum=0),)
    total = math.prod(shape)
    if total > MAX_SAMPLE_SIZE:
        shown = show_exact(total) if len(shape) == 1 else repr(shape)[:80]
        raise InputError(f"{name}={shown} asks "
                         f"for {show_exact(total)} draws, beyond the documented limit of "
                         f"{MAX_SAMPLE_SIZE:.0e} draws per call ({name} <= MAX_SAMPLE_SIZE, "
                         f"symhx.validation.MAX_SAMPLE_SIZE); draw in chunks or raise that "
                         f"constant")
    return shape


def show_exact(x: int | Fraction) -> str:
    """An exact int or Fraction for an error message: as it is when short (``101``, ``1/50``),
    else in 5 significant digits (``1.0e+400``) -- never thousands of digits, and never Python's
    4300-digit ``str`` limit.

    >>> show_exact(101), show_exact(Fraction(1, 50)), show_exact(Fraction(1, 10**5000))
    ('101', '1/50', '1.0e-5000')
    """
    fr = Fraction(x)
    if fr.numerator.bit_length() + fr.denominator.bit_length() <= 128:
        return str(x)
    return short_value(fr)


def safe_repr(x: Any) -> str:
    """``repr(x)`` in full, except an int or Fraction beyond Python's 4300-digit ``str`` limit,
    which is shown as :func:`brief_repr` does (an object's ``repr`` must never raise).

    >>> safe_repr(10**20), safe_repr(10**5000)
    ('100000000000000000000', '1.0e+5000')
    """
    if isinstance(x, (int, Fraction)) and not isinstance(x, bool):
        fr = Fraction(x)
        if max(fr.numerator.bit_length(), fr.denominator.bit_length()) > 14_000:
            return short_value(fr)
    return repr(x)


def brief_repr(x: Any) -> str:
    """``repr(x)``, but an int or Fraction of more than 200 bits in 5 significant digits
    (:func:`short_value`): a refusal never formats thousands of digits (nor hits Python's
    4300-digit ``str`` limit).

    >>> brief_repr(Fraction(1, 3)), brief_repr(-10**5000)
    ('Fraction(1, 3)', '-1.0e+5000')
    """
    if isinstance(x, (int, Fraction)) and not isinstance(x, bool):
        fr = Fraction(x)
        if fr.numerator.bit_length() + fr.denominator.bit_length() > 200:
            return short_value(fr)
    return repr(x)


def _show(x: Any) -> str:
    """A short description of a bad value for an error message."""
    try:
        r = repr(x)
    except ValueError:  # an int beyond Python's 4300-digit str limit
        r = brief_repr(x)
    except Exception:  # pragma: no cover - exotic objects
        r = object.__repr__(x)
    if len(r) > 60:
        r = r[:57] + "..."
    return f"{type(x).__name__} {r}"


def _sympy_number(x: Any) -> bool:
    return str(type(x).__module__).startswith("sympy")


def _sympy_is(x: Any, flag: str) -> bool:
    """``x`` is a sympy object whose class flag (``is_Rational``, ``is_Float``, ``is_number``) is
    set; objects without the flag (matrices, ...) are not."""
    return _sympy_number(x) and getattr(x, flag, None) is True


# --------------------------------------------------------------------------- strings
_RATIO = re.compile(r"^\s*([+-]?\d+)\s*/\s*([+-]?\d+)\s*$")
_POWER = re.compile(r"^\s*(\d+)\s*\*\*\s*(\d+)\s*$")
_DECIMAL = re.compile(r"^\s*[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\s*$")


@functools.lru_cache(maxsize=4)
def _decimal_limit(max_exponent: int) -> tuple[int, int]:
    """``10**(max_exponent + 1)``: the smallest magnitude refused (its decimal exponent is beyond
    the cap), and its bit length; called with :data:`MAX_DECIMAL_EXPONENT` as it is at the call
    (so a changed cap takes effect), computed once per value."""
    limit = 10 ** (max_exponent + 1)
    return limit, limit.bit_length()


#: an underscore that does not sit between two digits ("_1", "1_", "1__0", "1._5", "1e_5")
_BAD_UNDERSCORE = re.compile(r"(?<![0-9])_|_(?![0-9])")


def _parse_string(text: str, name: str, integer: bool = False) -> Fraction:
    """Exact rational value of ``"0.02"``, ``"2e-2"``, ``"1/50"`` or ``"10**100"``.

    ``integer`` only changes the wording of the errors (the caller checks integrality)."""
    s = text.strip()
    if _BAD_UNDERSCORE.search(s):   # Python's rule: one underscore, between two digits
        kind = "an integer" if integer else "a number"
        raise InputError(f"{name} must be {kind}; an underscore may only separate two digits, "
                         f"got {text!r}")
    s = s.replace("_", "")
    m = _RATIO.match(s)
    if m:
        num, den = int(m.group(1)), int(m.group(2))
        if den == 0:
            kind = "an integer" if integer else "a finite number"
            raise InputError(f"{name} must be {kind}, got {text!r} (division by zero)")
        return Fraction(num, den)
    m = _POWER.match(s)
    if m:
        base, exp = int(m.group(1)), int(m.group(2))
        # base**exp >= 2**(exp * (bit_length - 1)): refused before it is computed when that bound
        # is already >= 2**limit_bits > 10**(MAX_DECIMAL_EXPONENT + 1); otherwise exactly
        limit, limit_bits = _decimal_limit(MAX_DECIMAL_EXPONENT)
        if exp * (base.bit_length() - 1) >= limit_bits or base**exp >= limit:
            raise InputError(_exponent_error(name, text))
        return Fraction(base**exp)
    if _DECIMAL.match(s):
        return _decimal_to_fraction(Decimal(s), name, text)
    kind = ("an integer such as 7, 10**100 or '1e100'" if integer
            else "a number such as 0.02, 2e-2, 1/50 or 10**100")
    raise InputError(f"{name} must be {kind}, got {text!r}")


def _exponent_error(name: str, shown: Any) -> str:
    return (f"{name}={shown!r}: decimal exponent beyond +-{MAX_DECIMAL_EXPONENT} "
            f"(symhx.validation.MAX_DECIMAL_EXPONENT)")


def _decimal_to_fraction(dec: Decimal, name: str, shown: Any) -> Fraction:
    """The exact value of a finite Decimal whose decimal exponent is within the cap."""
    if dec and abs(dec.adjusted()) > MAX_DECIMAL_EXPONENT:
        raise InputError(_exponent_error(name, shown))
    return Fraction(dec)


def _mpf_tuple_to_fraction(t: tuple, name: str, shown: Any) -> Fraction:
    """The exact value of a finite mpf tuple ``(sign, man, exp, bc)`` within the binary cap."""
    sign, man, exp, bc = t
    if man and abs(exp + bc) > MAX_BINARY_EXPONENT:
        raise InputError(f"{name}={shown} is beyond the exact-conversion range "
                         f"2**+-{MAX_BINARY_EXPONENT} (symhx.validation.MAX_BINARY_EXPONENT)")
    return _binary_fraction(sign, man, exp)


def _binary_fraction(sign: int, man: int, exp: int) -> Fraction:
    """``(-1)**sign * man * 2**exp`` exactly (``Fraction(2)**exp`` is exact for any int exp)."""
    fr = Fraction(man) * Fraction(2) ** exp
    return -fr if sign else fr


# --------------------------------------------------------------------------- exact numbers
def to_rational(x: Any, name: str = "p") -> Fraction | None:
    """The exact rational value of ``x``, or ``None`` for a real sympy irrational.

    See the module docstring for the conventions.  Raises ``ValueError`` for NaN and infinities,
    ``TypeError`` for bools, complex numbers and non-numbers.

    >>> to_rational(0.5), to_rational("1e-3"), to_rational(3)
    (Fraction(1, 2), Fraction(1, 1000), Fraction(3, 1))
    """
    if isinstance(x, (bool, np.bool_)):
        raise TypeError(f"{name} must be a real number, got {_show(x)}")
    if isinstance(x, (int, Fraction)):
        return Fraction(x)
    if isinstance(x, str):
        return _parse_string(x, name)
    if isinstance(x, float):
        if not math.isfinite(x):
            raise InputError(f"{name} must be finite, got {x!r}")
        return Fraction(x)
    if isinstance(x, Decimal):
        if not x.is_finite():
            raise InputError(f"{name} must be finite, got {x!r}")
        return _decimal_to_fraction(x, name, x)
    if is_mpf(x):  # an mpf of any context (global, or a thread's private one)
        t = x._mpf_
        if not t[1] and t != libmp.fzero:  # inf, -inf, nan
            raise InputError(f"{name} must be finite, got {x!r}")
        return _mpf_tuple_to_fraction(t, name, libmp.to_str(t, 5))
    if _sympy_number(x):
        if _sympy_is(x, "is_Rational"):
            return Fraction(int(x.p), int(x.q))
        if _sympy_is(x, "is_Float"):  # a binary float: its exact value, like an mpf
            return _mpf_tuple_to_fraction(x._mpf_, name, x)
        if _sympy_is(x, "is_number") and (x.is_infinite or type(x).__name__ == "NaN"):
            # oo, -oo, zoo and nan: the value is the problem, as for a float inf or nan
            raise InputError(f"{name} must be finite, got {x!r}")
        if _sympy_is(x, "is_number") and x.is_real and x.is_finite:
            return None
        raise TypeError(f"{name} must be a finite real number, got sympy object {x!r}")
    if isinstance(x, numbers.Integral):  # numpy ints
        return Fraction(int(x))
    if isinstance(x, np.floating):  # float16 ... longdouble: the exact value, not float(x)
        if not np.isfinite(x):
            raise InputError(f"{name} must be finite, got {x!r}")
        return Fraction(*x.as_integer_ratio())
    if isinstance(x, np.ndarray) and x.ndim == 0:
        return to_rational(x[()], name)
    if isinstance(x, numbers.Complex) or hasattr(x, "_mpc_"):
        raise TypeError(f"{name} must be a real number, got {_show(x)}")
    raise TypeError(f"{name} must be a real number, got {_show(x)}")


def mpf_to_fraction(x: mpmath.mpf) -> Fraction:
    """The exact value ``man * 2**exp`` of a finite mpf (never re-rounded to the global
    precision).  No size cap: :func:`to_rational` caps user inputs; internal values (a cdf far in
    its tail can be ~10**-2000000) come here directly."""
    sign, man, exp, _ = x._mpf_
    return _binary_fraction(sign, man, exp)


def as_fraction(p: Any, name: str = "p") -> Fraction | None:
    """Alias of :func:`to_rational` (the older name)."""
    return to_rational(p, name)


def is_exact_type(p: Any) -> bool:
    """Inputs whose results are returned exactly: ints, Fractions, sympy Rationals, Decimals and
    decimal strings (floats and mpf are rational too, but results for them are mpf at ``dps``).

    >>> is_exact_type("0.3"), is_exact_type(Decimal("0.3")), is_exact_type(0.3)
    (True, True, False)
    """
    if isinstance(p, (bool, np.bool_)):
        return False
    if isinstance(p, (int, Fraction, str, Decimal, numbers.Integral)):
        return True
    return _sympy_is(p, "is_Rational")


def check_p(p: Any, name: str = "p") -> tuple[Fraction | None, Any]:
    """Validate an impact probability ``p > 0``; return ``(exact value or None, original)``.

    ``p > 1`` is accepted (the formulas are defined for any ``p > 0``) but is unphysical.
    A sympy irrational returns ``None`` as its exact value.
    """
    fr = to_rational(p, name)
    if fr is not None:
        if fr <= 0:
            raise InputError(f"{name} must be > 0, got {brief_repr(p)}")
        return fr, p
    # the sign, proved on a rigorous Arb ball of the expression with rising precision (sympy's
    # evalf runs special functions in mpmath's global, process-wide context, and plain evalf
    # shows an unevaluated pi - pi as 0.e-163 > 0). Not p.is_positive: for unevaluated
    # expressions its answer depends on the hash seed (Mul(0, sqrt(2), evaluate=False)
    # .is_positive is True under some seeds, sympy 1.14)
    try:
        sign = real_sign(p, max_bits=IRRATIONAL_SIGN_BITS)
    except UndecidedError:
        raise InputError(f"{name} must be > 0, got {brief_repr(p)} (its sign cannot be decided "
                         f"numerically: simplify it)") from None
    except TypeError as exc:
        raise TypeError(f"{name} must be a real number symhx can enclose rigorously, got "
                        f"sympy object {p!r}: {exc}") from None
    except ValueError as exc:  # not real or not finite (I, oo, a complex power)
        raise InputError(f"{name} must be a finite real number > 0, got {p!r} ({exc})") from None
    if sign <= 0:
        raise InputError(f"{name} must be > 0, got {brief_repr(p)}")
    return None, p


def check_real(x: Any, name: str, *, low: float | None = None, high: float | None = None,
               low_open: bool = False, high_open: bool = False) -> Fraction:
    """A finite real scalar as an exact ``Fraction`` within ``[low, high]`` (bounds optional,
    ``low_open``/``high_open`` exclude them).  sympy irrationals are refused here."""
    fr = to_rational(x, name)
    if fr is None:
        raise TypeError(f"{name} must be a rational or float number, got {_show(x)}")
    if low is not None and (fr < Fraction(low) or (low_open and fr == Fraction(low))):
        rel = ">" if low_open else ">="
        raise InputError(f"{name} must be {rel} {brief_repr(low)}, got {brief_repr(x)}")
    if high is not None and (fr > Fraction(high) or (high_open and fr == Fraction(high))):
        rel = "<" if high_open else "<="
        raise InputError(f"{name} must be {rel} {brief_repr(high)}, got {brief_repr(x)}")
    return fr


# --------------------------------------------------------------------------- integers
def check_int(x: Any, name: str, *, minimum: int | None = None, maximum: int | None = None,
              limit: str | None = None) -> int:
    """An exact integer: ints, numpy ints, integral Fractions / sympy Rationals and integer strings
    (``"101"``, ``"1e100"``, ``"10**100"``).  Floats are refused (above 2**53 they are not exact);
    bools are refused.  A non-integral rational (``"2.5"``, ``Fraction(5, 2)``) is a ValueError.
    ``limit``: the documented constant ``maximum`` comes from, named in the refusal.

    >>> check_int("7", "n", maximum=5, limit="symhx.x.MAX_N")
    Traceback (most recent call last):
        ...
    symhx.validation.InputError: n must be <= 5 (the work limit symhx.x.MAX_N), got 7
    """
    if isinstance(x, (bool, np.bool_)):
        raise TypeError(f"{name} must be an integer, got {_show(x)}")
    if isinstance(x, str):
        fr = _parse_string(x, name, integer=True)
        if fr.denominator != 1:
            raise InputError(f"{name} must be an integer, got {x!r}")
        v = fr.numerator
    elif isinstance(x, Fraction) or _sympy_is(x, "is_Rational"):
        # a non-integral rational is a value of the right kind out of range: ValueError
        fr = Fraction(x)  # sympy's Rational is a numbers.Rational
        if fr.denominator != 1:
            raise InputError(f"{name} must be an integer, got {x!r}")
        v = fr.numerator
    else:
        try:
            v = operator.index(x)
        except TypeError:
            if isinstance(x, (float, np.floating)):
                raise TypeError(
                    f"{name} must be an int, got float {x!r} (floats above 2**53 are not exact: "
                    f"write e.g. 10**100 or the string '1e100')") from None
            raise TypeError(f"{name} must be an integer, got {_show(x)}") from None
    if minimum is not None and v < minimum:
        raise InputError(f"{name} must be >= {brief_repr(minimum)}, got {brief_repr(v)}")
    if maximum is not None and v > maximum:
        why = f" (the work limit {limit})" if limit else ""
        raise InputError(f"{name} must be <= {brief_repr(maximum)}{why}, got {brief_repr(v)}")
    return v


def check_N(N: Any, name: str = "N", minimum: int = 2) -> int:
    """Validate a number of vertices (possible impacts) ``N >= minimum`` (any size)."""
    return check_int(N, name, minimum=minimum)


@overload
def check_dps(dps: Any, *, allow_none: Literal[False] = ..., name: str = ...) -> int: ...
@overload
def check_dps(dps: Any, *, allow_none: bool, name: str = ...) -> int | None: ...
def check_dps(dps: Any, *, allow_none: bool = False, name: str = "dps") -> int | None:
    """Validate a precision: an int in ``[1, MAX_DPS]`` (``None`` too when ``allow_none``,
    meaning float64)."""
    if dps is None and allow_none:
        return None
    allowed = f"an int between 1 and {MAX_DPS}" + (" (or None for float64)" if allow_none else "")
    if isinstance(dps, (bool, np.bool_)):
        raise TypeError(f"{name} must be {allowed}, got {_show(dps)}")
    try:
        d = operator.index(dps)
    except TypeError:
        raise TypeError(f"{name} must be {allowed}, got {_show(dps)}") from None
    if not 1 <= d <= MAX_DPS:
        raise InputError(f"{name} must be {allowed}, got {brief_repr(d)} "
                         f"(the cap is symhx.validation.MAX_DPS)")
    return d


def check_seed(seed: Any, name: str = "seed") -> int | None:
    """A random seed: ``None`` or a non-negative int (not a bool, not a float)."""
    if seed is None:
        return None
    return check_int(seed, name, minimum=0)


def check_choice(x: Any, name: str, allowed: Iterable[Any]) -> Any:
    """``x`` if it is one of ``allowed`` (compared with ``==``), else ValueError listing them."""
    options = list(allowed)
    if isinstance(x, (bool, np.bool_)) and not any(isinstance(o, bool) for o in options):
        raise TypeError(f"{name} must be one of {options}, got {_show(x)}")
    for o in options:
        try:
            if x == o:
                return o
        except Exception:  # pragma: no cover - objects whose == raises
            continue
    raise InputError(f"{name} must be one of {options}, got {x!r}")


# --------------------------------------------------------------------------- float arrays
def check_array(x: Any, name: str, *, positive: bool = False, nonnegative: bool = False,
                finite: bool = True, allow_empty: bool = False) -> np.ndarray:
    """A float64 array from numbers, lists or arrays; errors name the first bad index.

    Bools, strings and non-numeric entries raise TypeError; NaN, infinities (when ``finite``),
    exact values beyond the float64 range (when ``finite``) and values out of range raise
    ValueError.  Object arrays (Fractions, mpf, huge ints) are converted entry by entry at their
    exact value (:func:`to_rational`), then rounded once to float64; sympy irrationals are refused.
    """
    if isinstance(x, (bool, np.bool_, str, bytes)):
        raise TypeError(f"{name} must be a real number or an array of them, got {_show(x)}")
    try:
        arr = np.asarray(x)
    except Exception as exc:  # ragged lists and the like
        raise TypeError(f"{name} must be a real number or an array of them ({exc})") from None

    def at(idx: Any) -> str:
        return f" at index {tuple(int(i) for i in idx)}" if arr.ndim else ""

    def entry(idx: Any, val: Any) -> float:
        # one entry of an object array (Fractions, mpf, huge ints, ...): exact value, then float64
        if isinstance(val, (str, bytes)):
            raise TypeError(f"{name} must hold real numbers, got {_show(val)}{at(idx)}")
        try:
            fr = to_rational(val, name)
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"{exc}{at(idx)}") from None
        if fr is None:
            raise TypeError(f"{name} must be a rational or float number, got {_show(val)}"
                            f"{at(idx)}")
        try:
            return float(fr)
        except OverflowError:
            if finite:
                raise InputError(f"{name} must be within the float64 range (magnitude below "
                                 f"1.8e308), got {_show(val)}{at(idx)}") from None
            return math.inf if fr > 0 else -math.inf

    if arr.dtype == bool or arr.dtype.kind not in ("i", "u", "f"):
        if arr.dtype.kind != "O":
            raise TypeError(f"{name} must hold real numbers, got an array of dtype {arr.dtype}")
        arr = np.fromiter((entry(idx, val) for idx, val in np.ndenumerate(arr)),
                          dtype=np.float64).reshape(arr.shape)
    arr = np.asarray(arr, dtype=np.float64)  # no copy of a float64 array
    if arr.size == 0 and not allow_empty:
        raise InputError(f"{name} is empty: give at least one value")

    def first_bad(mask: np.ndarray) -> str:
        idx = np.argwhere(mask)[0]
        return f"{float(arr[tuple(idx)])!r}{at(idx)}"

    if finite and not np.all(np.isfinite(arr)):
        raise InputError(f"{name} must be finite, got {first_bad(~np.isfinite(arr))}")
    if np.any(np.isnan(arr)):
        raise InputError(f"{name} must not be NaN, got {first_bad(np.isnan(arr))}")
    if positive and not np.all(arr > 0):
        raise InputError(f"{name} must be > 0, got {first_bad(~(arr > 0))}")
    if nonnegative and not np.all(arr >= 0):
        raise InputError(f"{name} must be >= 0, got {first_bad(~(arr >= 0))}")
    return arr
