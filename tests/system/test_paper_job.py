"""The main job, ``symhx paper``, end to end (the README's first command)."""

import csv
import json

from symhx.cli import main


def test_symhx_paper_writes_every_section(tmp_path, capsys):
    rc = main(["paper", "--out", str(tmp_path)])
    captured = capsys.readouterr()
    out = captured.out
    assert "\r" not in captured.err  # no progress frames when stderr is not a terminal
    assert rc == 0, out
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert set(summary) >= {"core", "derive", "forcing", "impact", "spaces"}
    assert not any(line.startswith("FAILED") for lines in summary.values() for line in lines)
    for fig in (3, 4, 5, 6, 7, 8, 9, 13):
        assert list(tmp_path.glob(f"fig{fig}_*.png")), f"figure {fig} missing"
    assert list(tmp_path.glob("fig11_*.png")) and list(tmp_path.glob("fig12_*.png"))
    crit = json.loads((tmp_path / "critical_N101.json").read_text())
    assert crit["k_after"] == 20 and crit["p_c"].startswith("0.0128891153265305783")
    # every section's time is printed once (the job's own header line), nowhere else
    heads = [line for line in out.splitlines() if line.startswith("[symhx paper] ")]
    assert len(heads) == len(summary) + 1, heads
    assert not any("section:" in line for line in out.splitlines())
    # CSVs hold 17-digit floats (the full precision is in the JSON next to them)
    mine = ["critical_table.csv", "mode_path_N101.csv", "asymptotic_errors.csv",
            *[p.name for p in tmp_path.glob("fig11_*.csv")]]
    for name in mine:
        with open(tmp_path / name) as fh:
            rows = list(csv.reader(fh))
        for row in rows[1:]:
            for cell in row:
                try:
                    float(cell)
                except ValueError:
                    continue
                assert len(cell) <= 25, (name, cell)
        json_twin = (tmp_path / name).with_suffix(".json")
        assert json_twin.exists(), name
    table = json.loads((tmp_path / "critical_table.json").read_text())
    assert len(table[-1]["p_c"].replace(".", "").split("e")[0]) >= 50  # full precision in JSON
