"""Helpers shared by the CLI sub-commands: argument types (through :mod:`symhx.validation`),
strict JSON output, and the display of exact and mpmath values.

* Every numeric CLI argument is parsed by the same functions as the API (:mod:`symhx.validation`),
  so ``"0.02"`` means exactly 1/50 on the command line too; a bad value becomes argparse's one-line
  ``symhx CMD: error: argument ...`` message (exit code 2).
* JSON is strict (``allow_nan=False``): exact integers beyond 2**53 and mpf values are decimal
  strings (no digit lost), Fractions are ``"a/b"``, a float NaN is ``null`` and float infinities
  are the strings ``"inf"`` / ``"-inf"``.
* CSV cells hold floats with 17 significant digits (enough to round-trip a float64); the full
  precision goes to a JSON file next to each CSV.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
from collections.abc import Callable
from fractions import Fraction
from pathlib import Path
from typing import Any

import mpmath
from mpmath import libmp

from symhx import validation as V
from symhx._mpctx import export, is_mpf, local, mp

#: help texts of the options shared by the sub-commands
N_HELP = "number of vertices N = pipes + 1 (exact integer: 101, 1e100 or 10**100)"
P_HELP = "impact probability p > 0, exact: 0.02, 2e-2 and 1/50 are all exactly 1/50"
DPS_HELP = "significant decimal digits of the results"

#: integers with more digits than this are shown as ``d.ddd...e+NN (D digits)`` in text output
MAX_INT_DIGITS_SHOWN = 60


# --------------------------------------------------------------------------- argument types
def _arg_type(fn: Callable[[str], Any], what: str) -> Callable[[str], Any]:
    def convert(text: str) -> Any:
        try:
            return fn(text)
        except V.InputError as exc:  # anything else is a bug: argparse reports it as invalid
            raise argparse.ArgumentTypeError(str(exc)) from None

    convert.__name__ = what  # argparse names the type in some messages
    return convert


def int_arg(name: str, minimum: int | None = None, maximum: int | None = None,
            limit: str | None = None) -> Callable[[str], int]:
    """argparse ``type=``: an exact integer such as ``101``, ``1e100`` or ``10**100``
    (:func:`symhx.validation.check_int`); ``limit`` names the documented constant ``maximum``
    comes from (shown in the refusal)."""
    def conv(text: str) -> int:
        v = V.check_int(text, name)
        if minimum is not None and v < minimum:
            raise V.InputError(f"{name} must be >= {int_show(minimum)}, got {int_show(v)}")
        if maximum is not None and v > maximum:
            why = f" (the work limit {limit})" if limit else ""
            raise V.InputError(f"{name} must be <= {int_show(maximum)}{why}, got {int_show(v)}")
        return v

    return _arg_type(conv, name)


def rational_arg(name: str, positive: bool = True) -> Callable[[str], Fraction]:
    """argparse ``type=``: an exact rational such as ``0.02``, ``2e-2`` or ``1/50``
    (:func:`symhx.validation.to_rational`); ``> 0`` when ``positive``."""
    def conv(text: str) -> Fraction:
        fr = V.to_rational(text, name)
        assert fr is not None  # strings are always rational
        if positive and fr <= 0:
            raise V.InputError(f"{name} must be > 0, got {text!r}")
        return fr

    return _arg_type(conv, name)


def sites_arg(text: str) -> str:
    """argparse ``type=`` for ``--sites``: the text, read against ``N`` by :func:`sites_for`
    (a size may be ``rest``, N minus the others, so it is parsed once N is known)."""
    return text


#: the ``--sites`` option's help (``symhx distribution``, ``spaces``, ``critical``)
SITES_HELP = ("per-class impact probabilities instead of p: size:probability pairs separated "
              "by commas, optionally named, e.g. wall=2:0.01,pipe=99:0.02 (sizes add up to N; "
              "one size may be 'rest', N minus the others: 2:0.01,rest:0.02; probabilities "
              "exact as p)")


def sites_for(sc: Any, N: int, dps: int | None = None) -> Any:
    """``--sites`` (its text, or classes) read against ``N`` (the sizes must add up to it); with
    ``dps``, every probability as an mpf of ``dps + 10`` digits (``--float``)."""
    from symhx.sites import SiteClasses, as_site_classes

    if isinstance(sc, str):
        sc = SiteClasses.parse(sc, "--sites", N=N)
    sc = as_site_classes(sc, N, "--sites")
    if dps is None:
        return sc
    ctx = mp()
    with ctx.workdps(dps + 10):
        probs = [export(ctx.mpf(v.numerator) / v.denominator) for v in sc.values]
    return SiteClasses(sc.sizes, probs, sc.names)


def sites_show(sc: Any) -> str:
    """``--sites`` as it reads on the command line (``wall=2:0.01,pipe=99:0.02``)."""
    from symhx.sites import show_int

    names = sc.names or ("",) * len(sc.sizes)
    return ",".join(f"{name + '=' if name else ''}{show_int(n)}:{p}"
                    for name, n, p in zip(names, sc.sizes, sc.probabilities, strict=True))


def sites_json(sc: Any) -> dict[str, Any]:
    """``--sites`` for JSON output: sizes, exact probabilities, names (or ``None``)."""
    return {"sizes": list(sc.sizes), "probabilities": list(sc.values),
            "names": list(sc.names) if sc.names else None}


def dps_arg(text: str) -> int:
    """argparse ``type=`` for ``--dps`` (:func:`symhx.validation.check_dps`)."""
    try:
        return V.check_dps(V.check_int(text, "dps"))
    except V.InputError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def add_dps(parser: Any, default: int | None = V.DEFAULT_DPS, help_text: str = DPS_HELP) -> None:
    """The ``--dps`` option (validated by :func:`symhx.validation.check_dps`)."""
    parser.add_argument("--dps", type=dps_arg, default=default, metavar="DPS", help=help_text)


def add_json(parser: Any) -> None:
    parser.add_argument("--json", action="store_true",
                        help="print strict JSON instead of text (no NaN/Infinity; big numbers "
                        "as decimal strings)")


def rational_show(fr: Fraction) -> str:
    """A rational argument as the user would type it: a plain decimal when it has one of at most
    30 digits, else ``a/b``.

    >>> rational_show(Fraction(1, 200)), rational_show(Fraction(3)), rational_show(Fraction(1, 3))
    ('0.005', '3', '1/3')
    """
    d = fr.denominator
    twos, fives = (d & -d).bit_length() - 1, 0
    while d % 5 ** (fives + 1) == 0:
        fives += 1
    if d != 2**twos * 5**fives or max(twos, fives) > 30:
        return f"{fr.numerator}/{fr.denominator}"
    places = max(twos, fives)
    digits = str(abs(fr.numerator) * 10**places // fr.denominator).rjust(places + 1, "0")
    whole, frac = digits[:len(digits) - places], digits[len(digits) - places:]
    return ("-" if fr < 0 else "") + whole + ("." + frac if places else "")


# --------------------------------------------------------------------------- JSON
def jsonable(obj: Any, digits: int | None = None) -> Any:
    """Convert ints, Fractions, mpf and containers into strict-JSON values (see module doc).

    ``digits``: the significant digits promised (a command's ``--dps``): an mpf or float is
    printed with at most that many (never the 15+ digits of a value rounded to fewer bits);
    exact ints and Fractions stay exact.

    >>> jsonable({"a": Fraction(1, 3), "b": 2**60, "c": float("nan"), "d": float("-inf")})
    {'a': '1/3', 'b': '1152921504606846976', 'c': None, 'd': '-inf'}
    >>> jsonable([mpmath.mpf(1) / 3, 2 / 3], digits=3)
    ['0.333', 0.667]
    """
    if isinstance(obj, bool) or obj is None:
        return obj
    if isinstance(obj, int):
        return obj if abs(obj) < 2**53 else int_str(obj)
    if isinstance(obj, Fraction):
        if obj.denominator == 1:
            return jsonable(obj.numerator)
        return f"{int_str(obj.numerator)}/{int_str(obj.denominator)}"
    if is_mpf(obj):  # any mpmath context
        if not _finite(obj):
            return None if obj._mpf_ == libmp.fnan else ("inf" if obj > 0 else "-inf")
        shown = mpf_digits(obj) if digits is None else min(digits, mpf_digits(obj))
        return _tidy(str(mp().nstr(obj, shown, strip_zeros=False)))
    if isinstance(obj, float):
        if not math.isfinite(obj):
            return None if math.isnan(obj) else ("inf" if obj > 0 else "-inf")
        return obj if digits is None or digits >= 17 else float(f"{obj:.{digits}g}")
    if isinstance(obj, dict):
        return {str(k): _directed(v, digits, str(k)) if digits is not None and is_mpf(v)
                and _finite(v) and str(k).endswith(("_lo", "_hi")) else jsonable(v, digits)
                for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v, digits) for v in obj]
    if hasattr(obj, "as_dict"):
        return jsonable(obj.as_dict(), digits)
    if hasattr(obj, "item") and callable(obj.item):  # numpy scalars
        return jsonable(obj.item(), digits)
    return str(obj)


def _directed(x: mpmath.mpf, digits: int, key: str) -> str:
    """A bound (a key ending in ``_lo`` / ``_hi``) in ``digits`` significant digits, rounded
    outward (down for ``_lo``, up for ``_hi``) so that the printed decimal still encloses.

    >>> _directed(mpmath.mpf(2) / 3, 2, "p_lo"), _directed(mpmath.mpf(2) / 3, 2, "p_hi")
    ('0.66', '0.67')
    """
    from decimal import Decimal

    shown = min(digits, mpf_digits(x))
    text = _tidy(str(mp().nstr(x, shown, strip_zeros=False)))
    exact = V.mpf_to_fraction(x)
    dec = Decimal(text)
    step = Decimal(1).scaleb(dec.adjusted() - shown + 1)
    if key.endswith("_lo") and Fraction(dec) > exact:
        dec -= step
    elif key.endswith("_hi") and Fraction(dec) < exact:
        dec += step
    else:
        return text
    return str(mp().nstr(mp().mpf(str(dec)), shown + 1, strip_zeros=True)) \
        if dec.is_zero() else _dec_str(dec, shown)


def _dec_str(dec: Any, digits: int) -> str:
    """A Decimal in ``digits`` significant digits, in mpmath's ``nstr`` style."""
    ctx = mp()
    with ctx.workdps(digits + 5):
        return _tidy(str(ctx.nstr(ctx.mpf(str(dec)), digits, strip_zeros=False)))


def _tidy(text: str) -> str:
    """mpmath's one-digit forms ``"2."`` and ``"1.e+30"`` as ``"2"`` and ``"1e+30"``.

    >>> _tidy("2."), _tidy("1.e+30"), _tidy("0.25")
    ('2', '1e+30', '0.25')
    """
    return text.replace(".e", "e").removesuffix(".")


def _finite(x: mpmath.mpf) -> bool:
    """Whether an mpf (of any context) is finite (not inf, -inf or nan)."""
    t = x._mpf_
    return bool(t[1]) or t == libmp.fzero


def mpf_digits(x: mpmath.mpf) -> int:
    """Decimal digits carried by the mantissa of ``x`` (at least 15)."""
    bits = x._mpf_[3] if x._mpf_[1] else 53
    return max(15, mpmath.libmp.prec_to_dps(max(bits, 53)))


def dump_json(obj: Any, digits: int | None = None) -> str:
    """Strict JSON text of ``obj`` (never ``NaN`` or ``Infinity``); inexact numbers with at most
    ``digits`` significant digits (see :func:`jsonable`)."""
    return json.dumps(jsonable(obj, digits), indent=2, allow_nan=False)


# --------------------------------------------------------------------------- text and CSV
def int_str(n: int) -> str:
    """All digits of an int of any size (Python's 4300-digit ``str`` limit does not apply)."""
    if abs(n) < 10**4000:
        return str(n)
    chunks = []  # exact digits, 1000 at a time
    sign, n = ("-", -n) if n < 0 else ("", n)
    base = 10**1000
    while n:
        n, r = divmod(n, base)
        chunks.append(r)
    return sign + str(chunks[-1]) + "".join(f"{c:01000d}" for c in reversed(chunks[:-1]))


def int_show(n: int) -> str:
    """An int for text output: in full up to :data:`MAX_INT_DIGITS_SHOWN` digits, else as
    ``10**e`` (exact powers of ten) or ``d.dddd...e+NN (exact integer, D digits)``.

    >>> int_show(101), int_show(10**100), int_show(3 * 10**80 + 1)
    ('101', '10**100', '3.0000000000000000e+80 (exact integer, 81 digits)')
    """
    a = abs(n)
    if a < 10**MAX_INT_DIGITS_SHOWN:
        return str(n)
    digits = len(int_str(a))
    if a == 10 ** (digits - 1):
        return ("-" if n < 0 else "") + f"10**{digits - 1}"
    ctx = mp()
    with ctx.workdps(20):
        lead = ctx.nstr(ctx.mpf(n), 17, strip_zeros=False)
    return f"{lead} (exact integer, {digits} digits)"


def mpstr(x: Any, digits: int) -> str:
    """Decimal string of ``x`` with ``digits`` significant digits.

    mpf values are printed from their own mantissa (never re-rounded to the global precision);
    Fractions are printed as decimals followed by ``(exact a/b)`` (or ``(rounded from an exact
    rational)`` when ``a/b`` is long); ints are exact (:func:`int_show`).

    >>> mpstr(Fraction(1, 3), 5), mpstr(Fraction(1, 4), 5)
    ('0.33333  (exact 1/3)', '0.25  (exact 1/4)')
    """
    if isinstance(x, bool):
        return str(x)
    if isinstance(x, int):
        return int_show(x)
    if isinstance(x, Fraction):
        if x.denominator == 1:
            return int_show(x.numerator)
        ctx = mp()
        with ctx.workdps(digits + 10):
            dec = ctx.nstr(ctx.mpf(x.numerator) / x.denominator, digits)
        if x.numerator.bit_length() + x.denominator.bit_length() < 190:
            return f"{dec}  (exact {x.numerator}/{x.denominator})"
        return f"{dec}  (rounded from an exact rational)"
    if is_mpf(x):
        digits = min(digits, mpf_digits(x))
        return _tidy(str(mp().nstr(x, digits, strip_zeros=False, min_fixed=-5,
                                   max_fixed=12)))
    if isinstance(x, float):
        return repr(x)
    return str(x)


def csv_num(x: Any) -> Any:
    """A CSV cell: ints up to 17 digits as they are, every other number as a float with 17
    significant digits (the full precision is in the JSON file written alongside).

    >>> csv_num(Fraction(1, 3)), csv_num(10**100), csv_num(7)
    ('0.33333333333333331', '1e+100', 7)
    """
    if x is None or isinstance(x, (bool, str)):
        return x
    if isinstance(x, int) and abs(x) < 10**17:
        return x
    if isinstance(x, (int, Fraction)):
        ctx = mp()
        with ctx.workdps(30):
            v = ctx.mpf(x.numerator) / x.denominator if isinstance(x, Fraction) \
                else ctx.mpf(x)
            if abs(v) < 1e300 and (v == 0 or abs(v) > 1e-300):
                return f"{float(v):.17g}"
            return str(ctx.nstr(v, 17, strip_zeros=False))
    if is_mpf(x):
        if not _finite(x) or (x != 0 and not 1e-300 < abs(local(x)) < 1e300):
            return str(mp().nstr(x, 17, strip_zeros=False))
        return f"{float(x):.17g}"
    if isinstance(x, float):
        return f"{x:.17g}"
    return x


def write_csv(path: Path, header: list[str], rows: list[list[Any]]) -> None:
    """A CSV with a header; numbers as 17-significant-digit floats (:func:`csv_num`)."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for row in rows:
            w.writerow([csv_num(v) for v in row])
