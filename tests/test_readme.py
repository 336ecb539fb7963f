"""The README's quick tour runs as written."""

import doctest
from pathlib import Path

README = Path(__file__).resolve().parent.parent / "README.md"


def test_readme_examples():
    if not README.exists():  # installed without the source tree
        import pytest

        pytest.skip("README.md not present")
    result = doctest.testfile(str(README), module_relative=False,
                              optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 5 and result.failed == 0


def test_readme_benchmark_table_is_rendered_from_results():
    import subprocess
    import sys

    if not README.exists():
        import pytest

        pytest.skip("README.md not present")
    script = README.parent / "scripts" / "bench_table.py"
    table = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                           check=True).stdout.strip()
    assert table in README.read_text(), "run: python scripts/bench_table.py --readme"
