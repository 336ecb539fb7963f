"""The suite draws the same hypothesis examples on every run and keeps no example database
(tests/conftest.py); fresh draws are an explicit opt-in."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import settings
from hypothesis.configuration import storage_directory

ROOT = Path(__file__).resolve().parents[2]
FRESH_ENV = "SYMHX_HYPOTHESIS_FRESH"


@pytest.mark.skipif(os.environ.get(FRESH_ENV, "") not in ("", "0"), reason="fresh draws asked")
def test_default_profile_is_derandomized_without_a_database():
    assert settings.default.derandomize is True
    assert settings.default.database is None


@pytest.mark.skipif(bool(os.environ.get("HYPOTHESIS_STORAGE_DIRECTORY")),
                    reason="storage folder chosen by the user")
def test_hypothesis_writes_nothing_into_the_work_tree():
    path = storage_directory(intent_to_write=False).path.resolve()
    assert ROOT not in path.parents and path != ROOT, path


@pytest.mark.parametrize("value, derandomize", [("1", False), ("0", True), ("", True)])
def test_fresh_draws_are_an_opt_in_by_environment_variable(value, derandomize):
    code = ("import tests.conftest\nfrom hypothesis import settings\n"
            "print(settings.default.derandomize, settings.default.database)")
    env = {**os.environ, FRESH_ENV: value, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True,
                         text=True, check=True).stdout.split()
    assert out == [str(derandomize), "None"]
