"""pytest configuration of the whole suite: hypothesis draws the same examples on every run.

Deterministic by default, everywhere (locally and in CI): the ``deterministic`` profile sets
``derandomize=True`` (each test's examples come from a seed derived from the test itself, so a
run does not depend on the clock or on earlier runs) and ``database=None`` (no failing example is
stored and replayed, so pass or fail never depends on the history of the machine).  Hypothesis'
own caches go to a folder under the system temp dir, never to ``.hypothesis/`` in the work tree
(``HYPOTHESIS_STORAGE_DIRECTORY`` overrides that folder).

Fresh draws are an opt-in for exploring: ``SYMHX_HYPOTHESIS_FRESH=1 python -m pytest ...`` loads
the ``fresh`` profile (random examples on each run, still no database); hypothesis prints the seed
of a failing run, and ``python -m pytest --hypothesis-seed=SEED ...`` (with the variable set)
replays it.  A failure found that way becomes a deterministic test (an ``@example`` or a plain
test), never a stored database entry.
"""

import os
import tempfile
from pathlib import Path

from hypothesis import settings
from hypothesis.configuration import set_hypothesis_home_dir

#: environment variable that switches hypothesis to fresh random draws (see the module docstring)
FRESH_ENV = "SYMHX_HYPOTHESIS_FRESH"

if not os.environ.get("HYPOTHESIS_STORAGE_DIRECTORY"):
    set_hypothesis_home_dir(Path(tempfile.gettempdir()) / "symhx-hypothesis")

settings.register_profile("deterministic", max_examples=60, deadline=None, derandomize=True,
                          database=None)
settings.register_profile("fresh", max_examples=60, deadline=None, derandomize=False,
                          database=None, print_blob=True)
settings.load_profile("fresh" if os.environ.get(FRESH_ENV, "") not in ("", "0") else
                      "deterministic")


def pytest_sessionstart(session):
    """A session that tests a mutant (``MUTANT_UNDER_TEST``, set by mutmut in a process forked
    after its clean run) starts from empty caches: see :mod:`tests.harness.caches`."""
    if os.environ.get("MUTANT_UNDER_TEST", "") not in ("", "stats", "fail"):
        from tests.harness.caches import clear_caches

        clear_caches()


def pytest_runtest_setup(item):
    """While mutmut records which tests run which function (``MUTANT_UNDER_TEST=stats``), every
    test starts from empty caches: otherwise only the first test to build a cached value (a
    derivation, a Gauss-Legendre rule) is recorded as running its builder, and a mutant of the
    builder is tested by that test alone."""
    if os.environ.get("MUTANT_UNDER_TEST", "") == "stats":
        from tests.harness.caches import clear_caches

        clear_caches()
