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


def test_convergence_text_table_has_a_header_and_the_api_values(capsys):
    import symhx

    assert main(["convergence", "20", "--max-m", "1", "--p", "0.05"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].split() == ["space", "p_c", "k", "0.05"]
    row = lines[2].split()
    assert row[0] == "excess<=0"
    mean = symhx.mean(20, "0.05", space="excess<=0", dps=20)
    assert abs(float(row[3]) - float(mean)) <= 5e-5 * float(mean)
    # the p_c column is the space's critical point
    pc = symhx.critical_point(20, space="excess<=0", dps=20).p
    assert abs(float(row[1]) - float(pc)) <= 5e-5 * float(pc)


def test_spaces_paper_section_against_the_api(tmp_path):
    """``symhx paper``'s section 8: the critical points it summarises (simple, eq41 and
    excess<=6 at N = 100, 101; eq41 at N = 10**6) are the API's, and figures 11-13 and their
    data are written."""
    import mpmath

    import symhx
    from symhx.commands.spaces import paper

    lines = paper(tmp_path, False)
    for N, line in ((100, lines[0]), (101, lines[1])):
        for space, label in (("excess<=0", "simple"), ("eq41", "eq41"),
                             ("excess<=6", "excess<=6")):
            cp = symhx.critical_point(N, space=space, dps=20)
            assert f"{label} {mpmath.nstr(cp.p, 8)}" in line, (N, space, line)
            if label != "simple":
                assert f"(jump to {cp.k_after})" in line
    cp6 = symhx.critical_point(10**6, space="eq41", dps=20)
    assert f"p_c = {mpmath.nstr(cp6.p, 15)}, jump 1 -> {cp6.k_after}" in lines[2]
    for name in ("fig11_classes.png", "fig12_simple_vs_higher.png", "fig13_theory.png",
                 "convergence_N101.json", "section8_boundary.json"):
        assert (tmp_path / name).stat().st_size > 0
    # figure 11's data: per k the class decomposition, as in the API
    f11 = json.loads((tmp_path / "fig11_classes_eq41_p0.05.json").read_text())
    assert f11["columns"][0] == "k" and len(f11["rows"]) == 101
    assert [r[0] for r in f11["rows"]] == list(range(1, 102))
    rows = json.loads((tmp_path / "convergence_N101.json").read_text())
    assert rows[0]["space"] == "excess<=0" and rows[0]["k_after"] == 20
    with mpmath.workdps(30):
        assert abs(mpmath.mpf(rows[0]["means"]["0.05"]) - symhx.mean(101, "0.05", dps=25)) \
            < mpmath.mpf(10) ** -18
