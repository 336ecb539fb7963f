r"""Each class of impact sites gets its own impact probability from its gap and its bodies.

Eq. (27) is the probability that the gap between two *pipes* closes: the gap moves by the
difference of the two pipes' motions (eq. 21), so each frequency component of that difference has
a Rayleigh amplitude of scale ``sqrt(2) sigma_i/|omega**2 - Omega_i**2|`` (eqs. 24-25: the
difference of two independent ``N(0, sigma_i**2)`` coefficients has variance ``2 sigma_i**2``).
A gap between a pipe and a fixed *wall* moves by one pipe's motion: the same components, each
of scale ``sigma_i/|omega**2 - Omega_i**2|``.  Hence

.. math::

    p_{\rm pipe}(g) = P\Bigl(\sum_i R_i > g\Bigr),\qquad
    p_{\rm wall}(g) = P\Bigl(\sum_i R_i/\sqrt2 > g\Bigr) = p_{\rm pipe}(\sqrt2\,g),

with ``R_i`` the Rayleigh amplitudes of eq. (22) and ``g`` the gap. The paper's one ``p`` for every
site contradicts its own eq. (27): at ``sigma = 0.14`` (``d = 1``, the paper's forcing) a wall site
is about 400 times less likely to impact than a pipe-pipe site (see the book's chapter
"Different impacts, different probabilities" and its errata).

The square lattice (:func:`symhx.graph.lattice_sites`). Pipes of diameter ``D`` sit at the nodes
of a square lattice of pitch ``P``; every pipe moves in the plane, each coordinate as in eqs.
(19)-(20) with independent ``N(0, sigma_i**2)`` coefficients (isotropic motion). The projection
of isotropic motion on any unit vector is the 1-D motion of the row, so a contact across a gap
``g`` along the line of centres has the row's probability for that gap:

* orthogonal neighbours (one pitch apart): ``g = P - D``, two bodies;
* diagonal neighbours: ``g = sqrt(2) P - D``, two bodies;
* a wall (a straight line parallel to a side of the lattice): one body, ``g = wall_gap``;
  by default ``P - D``: the wall stands where the near surface of a missing neighbour would be,
  so that with ``D = 0`` the walls sit one pitch from the outer pipes, as in the row of
  :mod:`symhx.impact` (walls at ``0`` and ``(n + 1) d``).

A wall contact is exact (a flat wall is reached exactly when the projected motion covers the
gap). A pipe-pipe contact is *linearised*: two round pipes touch when the centre distance
``|c + Delta u|`` reaches ``D``, which needs an approach ``a >= g + b**2/(2 D) + ...`` along the
line of centres when they also move by ``b`` across it; the projection drops that term, so the
lattice pipe-pipe probabilities are upper bounds, accurate when the gaps are small against ``D``
(the book measures the difference by Monte Carlo).

Precision: float64 (``dps=None``, vectorised over the forcing arguments ``sigma``, ``sigma1``,
``omega``, ``Omega`` as :func:`symhx.impact_probability`) or mpmath correct to ``dps`` digits;
the geometry (``gap``, ``d``, ``pitch``, ``diameter``, ``wall_gap``) is scalar and exact (decimal
strings, Fractions, floats at their binary value). A threshold with a factor ``sqrt(2)`` is
computed with ``symhx.forcing.arguments.IRRATIONAL_EXTRA_DIGITS`` more digits than asked
(float64: rounded once from 113 bits), in the calling thread's own mpmath context; the
probability itself is :func:`symhx.impact_probability`'s, as thread-safe as that route.

>>> probs = row_site_probabilities(100, 0.14)
>>> probs.names, probs.sizes
(('wall', 'pipe-pipe'), (2, 99))
>>> probs["pipe-pipe"] == impact_probability(0.14)        # eq. (27) itself
True
>>> round(probs["pipe-pipe"] / probs["wall"])
416
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from symhx._mpctx import export, mp
from symhx.forcing.arguments import IRRATIONAL_EXTRA_DIGITS, is_array
from symhx.forcing.probability import impact_probability, log_impact_probability
from symhx.graph import SiteLayout, lattice_sites, row_sites
from symhx.validation import InputError, check_dps, check_int, check_real

__all__ = [
    "SiteProbabilities",
    "Threshold",
    "contact_probability",
    "lattice_site_probabilities",
    "row_site_probabilities",
]


@dataclass(frozen=True)
class Threshold:
    r"""The exact threshold ``a + b sqrt(2)`` that the *pipe-pair* amplitudes of eq. (22) must
    exceed for a site to impact.

    A pipe-pipe gap ``g`` is ``(g, 0)``; a wall gap ``g`` is ``(0, g)`` (``p_wall(g) =
    p_pipe(sqrt(2) g)``); a diagonal lattice gap ``sqrt(2) P - D`` is ``(-D, P)``.

    Attributes
    ----------
    a, b : Fraction
        The rational and the ``sqrt(2)`` part.

    Examples
    --------
    >>> t = Threshold(Fraction(-1, 2), Fraction(1))
    >>> round(float(t), 12)
    0.914213562373
    """

    a: Fraction
    b: Fraction

    def __float__(self) -> float:
        return float(self.value(None))

    def value(self, dps: int | None) -> Any:
        """The threshold as a Fraction (``b = 0``), a float (``dps=None``, correctly rounded
        from 113 bits) or an mpf with ``IRRATIONAL_EXTRA_DIGITS`` digits beyond ``dps``.

        >>> Threshold(Fraction(3, 4), Fraction(0)).value(30)
        Fraction(3, 4)
        """
        if self.b == 0:
            return self.a if dps is not None else float(self.a)
        ctx = mp()
        digits = 34 if dps is None else dps + IRRATIONAL_EXTRA_DIGITS
        with ctx.workdps(digits):
            a = ctx.mpf(self.a.numerator) / self.a.denominator
            b = ctx.mpf(self.b.numerator) / self.b.denominator
            x = a + b * ctx.sqrt(2)
        return float(x) if dps is None else export(x)


def _scalar(value: Any, name: str, *, allow_zero: bool = False) -> Fraction:
    """A scalar geometric length, exact, ``> 0`` (or ``>= 0``)."""
    if is_array(value):
        raise TypeError(f"{name} must be a scalar (the geometry is one number; the forcing "
                        f"arguments broadcast), got {type(value).__name__} {value!r}"[:300])
    if value is None:
        raise TypeError(f"{name} must be a real number, got None")
    return check_real(value, name, low=0, low_open=not allow_zero)


def _probability(threshold: Threshold, sigma: Any, sigma1: Any, omega: Any, Omega: Any,
                 dps: int | None, log: bool) -> Any:
    fn = log_impact_probability if log else impact_probability
    return fn(sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=threshold.value(dps), dps=dps)


def contact_probability(
    sigma: Any,
    *,
    bodies: int = 2,
    gap: Any = 1,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    log: bool = False,
    dps: int | None = None,
) -> Any:
    r"""Impact probability of one site whose gap ``gap`` is closed by ``bodies`` moving bodies.

    ``bodies=2`` (a pipe pair) is eq. (27) with ``d = gap``: ``P(sum_i R_i > gap)``, ``R_i``
    Rayleigh of scales ``sqrt(2) sigma_i/|omega**2 - Omega_i**2|`` (eqs. 22-25).
    ``bodies=1`` (a pipe against a fixed wall): scales ``sigma_i/|omega**2 - Omega_i**2|``, so
    the value equals eq. (27) at ``d = sqrt(2) gap``.

    Parameters
    ----------
    sigma, sigma1, omega, Omega
        The forcing, as in :func:`symhx.impact_probability` (broadcasting for ``dps=None``).
    bodies : {1, 2}
        Moving bodies that close the gap.
    gap : real, scalar
        The gap ``> 0`` at rest (decimal strings and Fractions exact).
    log : bool
        Return ``log p`` (also where ``p`` underflows float64).
    dps : int or None
        ``None``: float64; an int: mpmath correct to ``dps`` digits.

    Returns
    -------
    float, ndarray or mpf
        ``p`` (or ``log p``).

    Raises
    ------
    ValueError, TypeError
        Naming the argument: ``bodies`` not 1 or 2, a gap ``<= 0`` or an array gap, bad forcing
        arguments (as :func:`symhx.impact_probability`).

    Examples
    --------
    >>> contact_probability(0.3, bodies=2) == impact_probability(0.3)
    True
    >>> p1 = contact_probability(0.3, bodies=1, dps=30)
    >>> abs(p1 / impact_probability(0.3 / 2**0.5, dps=30) - 1) < 1e-15   # sigma / sqrt(2)
    True
    """
    if isinstance(bodies, (bool, np.bool_)):
        raise TypeError(f"bodies must be 1 (a wall site) or 2 (a pipe pair), got bool {bodies}")
    bodies = check_int(bodies, "bodies", minimum=1, maximum=2)
    if not isinstance(log, (bool, np.bool_)):
        raise TypeError(f"log must be True or False, got {type(log).__name__} {log!r}")
    dps = check_dps(dps, allow_none=True)
    g = _scalar(gap, "gap")
    th = Threshold(g, Fraction(0)) if bodies == 2 else Threshold(Fraction(0), g)
    return _probability(th, sigma, sigma1, omega, Omega, dps, bool(log))


@dataclass(frozen=True)
class SiteProbabilities:
    """The impact probability of every class of sites of a geometry.

    Attributes
    ----------
    layout : SiteLayout
        The classes (:func:`symhx.graph.row_sites`, :func:`symhx.graph.lattice_sites`).
    thresholds : tuple of Threshold
        Per class, the exact threshold of the pipe-pair amplitudes (``a + b sqrt(2)``).
    probabilities : tuple
        Per class, ``p`` (float, ndarray or mpf, as :func:`contact_probability` returns).

    Examples
    --------
    >>> sp = lattice_site_probabilities(3, 0.2, pitch="1.5", diameter=1)
    >>> sp.names
    ('wall', 'orthogonal', 'diagonal')
    >>> sp["orthogonal"] > sp["diagonal"], sp["orthogonal"] > sp["wall"]
    (True, True)
    """

    layout: SiteLayout
    thresholds: tuple[Threshold, ...]
    probabilities: tuple[Any, ...]

    @property
    def names(self) -> tuple[str, ...]:
        """The class names of the layout."""
        return self.layout.names

    @property
    def sizes(self) -> tuple[int, ...]:
        """The class sizes of the layout."""
        return self.layout.sizes

    def __getitem__(self, name: str) -> Any:
        if name not in self.layout.names:
            raise KeyError(f"no site class {name!r}; the classes are {self.layout.names}")
        return self.probabilities[self.layout.names.index(name)]


def _classes(layout: SiteLayout, thresholds: dict[str, Threshold], sigma: Any, sigma1: Any,
             omega: Any, Omega: Any, dps: int | None, log: bool) -> SiteProbabilities:
    ths = tuple(thresholds[name] for name in layout.names)
    probs = tuple(_probability(t, sigma, sigma1, omega, Omega, dps, log) for t in ths)
    return SiteProbabilities(layout, ths, probs)


def _flags(log: Any, dps: Any) -> tuple[bool, int | None]:
    if not isinstance(log, (bool, np.bool_)):
        raise TypeError(f"log must be True or False, got {type(log).__name__} {log!r}")
    return bool(log), check_dps(dps, allow_none=True)


def row_site_probabilities(
    n: int,
    sigma: Any,
    *,
    d: Any = 1,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    log: bool = False,
    dps: int | None = None,
) -> SiteProbabilities:
    """Per-class impact probabilities of a row of ``n`` pipes (the model of section 7).

    Every gap is ``d`` at rest (walls at ``0`` and ``(n + 1) d``, :class:`symhx.impact.PipeRow`):
    the ``n - 1`` pipe-pipe sites have eq. (27)'s ``p``, the 2 wall sites
    ``contact_probability(bodies=1, gap=d)``.

    Parameters
    ----------
    n : int
        Number of pipes ``>= 1``.
    sigma, sigma1, omega, Omega
        The forcing, as in :func:`symhx.impact_probability`.
    d : real, scalar
        The spacing ``> 0``.
    log : bool
        Give ``log p`` per class.
    dps : int or None
        ``None``: float64; an int: mpmath correct to ``dps`` digits.

    Returns
    -------
    SiteProbabilities
        Classes ``("wall", "pipe-pipe")`` (only ``"wall"`` for ``n = 1``).

    Raises
    ------
    ValueError, TypeError
        Naming the argument (``n``, ``d``, the forcing).

    Examples
    --------
    >>> sp = row_site_probabilities(100, "0.2", dps=20)
    >>> sp["wall"]
    mpf('0.0085543477134200301')
    """
    log, dps = _flags(log, dps)
    layout = row_sites(n)
    g = _scalar(d, "d")
    th = {"wall": Threshold(Fraction(0), g), "pipe-pipe": Threshold(g, Fraction(0))}
    return _classes(layout, th, sigma, sigma1, omega, Omega, dps, log)


def lattice_site_probabilities(
    m: int,
    sigma: Any,
    *,
    pitch: Any,
    diameter: Any,
    wall_gap: Any = None,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    log: bool = False,
    dps: int | None = None,
) -> SiteProbabilities:
    """Per-class impact probabilities of an ``m x m`` square lattice (8-neighbour contact).

    Isotropic 2-D motion projected on each line of centres (module docstring): orthogonal
    neighbours across ``pitch - diameter``, diagonal ones across ``sqrt(2) pitch - diameter``
    (both two bodies, linearised contact), walls across ``wall_gap`` (one body, exact).

    Parameters
    ----------
    m : int
        Pipes per side ``>= 1``.
    sigma, sigma1, omega, Omega
        The forcing of each coordinate, as in :func:`symhx.impact_probability`.
    pitch : real, scalar
        Distance ``> 0`` between the centres of orthogonal neighbours.
    diameter : real, scalar
        Pipe diameter, ``0 <= diameter < pitch`` (0: point pipes as in the row model).
    wall_gap : real, scalar or None
        Gap ``> 0`` between a boundary pipe and its wall; ``None``: ``pitch - diameter``.
    log : bool
        Give ``log p`` per class.
    dps : int or None
        ``None``: float64; an int: mpmath correct to ``dps`` digits.

    Returns
    -------
    SiteProbabilities
        Classes ``("wall", "orthogonal", "diagonal")`` (only ``"wall"`` for ``m = 1``).

    Raises
    ------
    ValueError, TypeError
        Naming the argument: ``diameter >= pitch`` (pipes overlap), non-positive lengths, an
        array where a scalar is due, bad forcing arguments.

    Examples
    --------
    >>> sp = lattice_site_probabilities(4, 0.2, pitch="1.25", diameter=1, dps=15)
    >>> [float(p) > 0 for p in sp.probabilities]
    [True, True, True]
    >>> sp.thresholds[2]            # sqrt(2) * 5/4 - 1
    Threshold(a=Fraction(-1, 1), b=Fraction(5, 4))
    """
    log, dps = _flags(log, dps)
    layout = lattice_sites(m)
    P = _scalar(pitch, "pitch")
    D = _scalar(diameter, "diameter", allow_zero=True)
    if D >= P:
        raise InputError(f"diameter must be < pitch = {pitch!r} (neighbouring pipes would "
                         f"overlap), got {diameter!r}")
    W = P - D if wall_gap is None else _scalar(wall_gap, "wall_gap")
    th = {"wall": Threshold(Fraction(0), W), "orthogonal": Threshold(P - D, Fraction(0)),
          "diagonal": Threshold(-D, P)}
    return _classes(layout, th, sigma, sigma1, omega, Omega, dps, log)
