"""Higher-order sample spaces (section 8 of the paper): circuits that visit a vertex more than once.

Space syntax (accepted as ``space=`` by every distribution function and by ``critical_point``;
the default everywhere is ``"simple"``, :data:`symhx.validation.DEFAULT_SPACE`):

* ``"simple"`` -- simple circuits only (eqs. 7-8);
* ``"eq41"`` -- the paper's five classes (simple, phi^1, phi^{1,0}, phi^2, phi^{1,0,0}) with the
  correct counts at every length, including the boundary terms eq. (41) leaves out;
* ``"eq41-printed"`` -- the counts as printed: formulas (35), (38)-(40) inside their stated ranges,
  (36) ``phi^1(2) = N``, zero for the other boundary terms (only to reproduce figures 11-13);
* ``"excess<=m"`` (``0 <= m <= MAX_EXCESS``, a documented work limit) -- every visit pattern
  whose length exceeds its number of distinct vertices by at most ``m``: the consistent
  truncation (``"excess<=0"`` is ``"simple"``);
* work limit: every computation over a space other than ``"simple"`` scans ``k = 1..N`` and is
  refused before any work when ``N * (m + 1) > MAX_SPACE_WORK`` (``m`` the largest excess:
  ``N <= 10**6`` for eq41, ``N <= 153846`` for ``excess<=25``; :func:`space_n_limit`);
* suffix ``";distinct"`` (or ``weighting="distinct"`` in this module) weights a circuit by
  ``p**k`` (k distinct vertices) instead of the default ``p**length`` (``";length"``).

>>> from fractions import Fraction
>>> from symhx.spaces import distribution, critical_point
>>> distribution(4, Fraction(1, 2), space="eq41").pmf(1)
Fraction(4, 25)
>>> critical_point(100, space="excess<=3", dps=10).k_after
25
"""

from symhx.spaces._classes import (
    EQ41_SHAPES,
    MAX_EXCESS,
    MAX_SPACE_WORK,
    PRINTED_RANGES,
    Space,
    check_space_work,
    class_count,
    class_ratio,
    eq41_terms,
    paper_label,
    parse_space,
    printed_count,
    shape_excess,
    shapes_up_to,
    space_n_limit,
)
from symhx.spaces._critical import critical_point, root_estimates
from symhx.spaces._dist import (
    ClassDecomposition,
    SpaceDistribution,
    class_decomposition,
    class_probabilities,
    distribution,
    modes,
    space_modes,
)
from symhx.spaces.study import DEFAULT_PS, ConvergenceRow, convergence_study
from symhx.spaces.symbolic import (
    boundary_table,
    class_count_symbolic,
    pattern_count_symbolic,
    printed_formula,
    verify_printed_formulas,
)

__all__ = [
    "DEFAULT_PS",
    "EQ41_SHAPES",
    "MAX_EXCESS",
    "MAX_SPACE_WORK",
    "PRINTED_RANGES",
    "ClassDecomposition",
    "ConvergenceRow",
    "Space",
    "SpaceDistribution",
    "boundary_table",
    "check_space_work",
    "class_count",
    "class_count_symbolic",
    "class_decomposition",
    "class_probabilities",
    "class_ratio",
    "convergence_study",
    "critical_point",
    "distribution",
    "eq41_terms",
    "modes",
    "paper_label",
    "parse_space",
    "pattern_count_symbolic",
    "printed_count",
    "printed_formula",
    "root_estimates",
    "shape_excess",
    "shapes_up_to",
    "space_modes",
    "space_n_limit",
    "verify_printed_formulas",
]
