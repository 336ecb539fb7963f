"""``python -m symhx`` (:mod:`symhx.__main__`): the same command line as ``symhx``."""

import json
import subprocess
import sys


def test_python_dash_m_symhx_runs_the_cli_and_its_exit_codes():
    proc = subprocess.run([sys.executable, "-m", "symhx", "critical", "5", "--json"],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["argmins"] == [2, 3]
    proc = subprocess.run([sys.executable, "-m", "symhx", "critical", "1e-3"],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
