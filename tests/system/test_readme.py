"""The README: its quick tour runs as written and its benchmark table is the rendered results."""

import doctest
import subprocess
import sys
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"


@pytest.fixture
def readme() -> Path:
    if not README.exists():  # installed without the source tree
        pytest.skip("README.md not present")
    return README


def test_readme_examples_run_as_written(readme):
    result = doctest.testfile(str(readme), module_relative=False,
                              optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 5 and result.failed == 0


def test_readme_benchmark_table_is_rendered_from_results(readme):
    script = readme.parent / "scripts" / "bench_table.py"
    table = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                           check=True).stdout.strip()
    assert table in readme.read_text(), "run: python scripts/bench_table.py --readme"
