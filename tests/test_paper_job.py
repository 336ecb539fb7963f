"""The main job, ``symhx paper``, end to end (the README's first command)."""

import json

from symhx.cli import main


def test_symhx_paper_writes_every_section(tmp_path, capsys):
    rc = main(["paper", "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert rc == 0, out
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert set(summary) >= {"core", "derive", "forcing", "impact", "spaces"}
    assert not any(line.startswith("FAILED") for lines in summary.values() for line in lines)
    for fig in (3, 4, 5, 6, 7, 8, 9, 13):
        assert list(tmp_path.glob(f"fig{fig}_*.png")), f"figure {fig} missing"
    assert list(tmp_path.glob("fig11_*.png")) and list(tmp_path.glob("fig12_*.png"))
    crit = json.loads((tmp_path / "critical_N101.json").read_text())
    assert crit["k_after"] == 20 and crit["p_c"].startswith("0.0128891153265305783")
