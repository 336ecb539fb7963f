"""``symhx paper`` writes every figure of the paper, 1-13, and reports its phases in order
(issue 29: figures 1-2 were missing, figure 11 lacked its panel (b))."""

from __future__ import annotations

import json
import re

from symhx.cli import main
from symhx.plots.paper import PAPER_FIGURES


def test_paper_job_writes_figures_1_to_13_and_times_each_phase(tmp_path, capsys):
    assert main(["paper", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    written = {int(m.group(1)) for p in tmp_path.glob("fig*.png")
               if (m := re.match(r"fig(\d+)_", p.name))}
    assert written == set(PAPER_FIGURES) == set(range(1, 14))
    for p in tmp_path.glob("fig*.png"):
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        width = int.from_bytes(p.read_bytes()[16:20], "big")
        assert width >= 700, (p.name, width)  # 200 dpi: sharp stand-alone files (were ~600 px)
    # the phases are printed in the modules' order, each with its time, then the total
    heads = re.findall(r"^\[symhx paper\] (\w+) \((\d+\.\d) s\)$", out, re.M)
    assert [h[0] for h in heads] == ["core", "derive", "forcing", "impact", "spaces"]
    assert re.search(r"^\[symhx paper\] 5/5 sections in \d+\.\d s; results in ", out, re.M)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert list(summary) == [h[0] for h in heads]
