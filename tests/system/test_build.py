"""The test environment contains what the suite is meant to test: the compiled impact engine.

The C engine (``symhx.impact._fast``) is optional for users, but a test run that silently skips
its twin checks would pass without testing it. A machine without a C compiler can say so with
``SYMHX_NO_C_ENGINE=1``.
"""

import os

import pytest

from symhx.impact import fast


@pytest.mark.skipif(os.environ.get("SYMHX_NO_C_ENGINE") == "1",
                    reason="SYMHX_NO_C_ENGINE=1: this machine has no C compiler")
def test_the_compiled_engine_is_importable_from_the_tested_sources():
    assert fast.available(), (
        "symhx.impact._fast is not built next to the sources under test; install with "
        "pip install -e '.[test]' (README command 2) or set SYMHX_NO_C_ENGINE=1")
