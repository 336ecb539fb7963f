"""Independent references for the tests: the one home of every value a test compares symhx with.

Each module computes its quantities by a route that is *not* the one symhx takes (brute force,
another formula, another quadrature, exact Fractions, a higher precision), from the paper's
definitions, without importing symhx internals.  A test that needs a reference imports it from
here; it never writes one of its own.

Modules: :mod:`tests.reference.mp` (``assert_mp_close``, log-spaced argument grids, relative
errors) and one module per topic of the package (combinatorics, distribution, critical, spaces,
forcing, impact, seeds).
"""
