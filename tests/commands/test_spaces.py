"""The section-8 sub-commands (:mod:`symhx.commands.spaces`): ``spaces`` and ``convergence``."""

from __future__ import annotations

import json
import time

from symhx.cli import main


def test_spaces_json_has_the_critical_point_and_one_row_per_class(capsys):
    assert main(["spaces", "20", "1/20", "--space", "excess<=2", "--classes", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["critical"]["k_before"] == 1 and len(out["classes"]) == 4


def test_convergence_json_lists_the_spaces_in_order(capsys):
    assert main(["convergence", "20", "--max-m", "1", "--p", "0.05", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert [r["space"] for r in rows] == ["excess<=0", "excess<=1", "eq41", "eq41-printed"]


def test_spaces_unknown_space_is_exit_2(capsys):
    assert main(["spaces", "20", "--space", "bogus"]) == 2
    assert "bogus" in capsys.readouterr().err


def test_convergence_caps_refused_up_front(capsys):
    t = time.monotonic()
    for argv in (["convergence", "1e6", "--max-m", "1"], ["convergence", "12", "--max-m", "1e6"],
                 ["convergence", "12", "--max-m", "10**1000"]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("error:") == 1 and "<=" in err
    assert time.monotonic() - t < 1
