"""CLI: symhx derive / symhx asymptotics, the paper hook and the asymptotic-error figure."""

from __future__ import annotations

import json

import pytest

from symhx.cli import main


def test_derive_latex(capsys):
    assert main(["derive", "16", "--latex"]) == 0
    out = capsys.readouterr().out
    assert r"\sqrt{N + 1}" in out and "(16)" in out


def test_derive_verify_json(capsys):
    assert main(["derive", "13", "38", "--verify", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [d["label"] for d in data] == ["13", "38"]
    assert all(d["verified"] for d in data)


def test_derive_list_and_unknown(capsys):
    assert main(["derive", "--list"]) == 0
    assert "crossing" in capsys.readouterr().out
    assert main(["derive", "999"]) == 2


def test_asymptotics_cli(capsys):
    assert main(["asymptotics", "1e10", "--json", "--exact", "--order", "best"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    assert row["k"] == row["k_exact"]
    assert main(["asymptotics", "1e6"]) == 0
    assert "corrected" in capsys.readouterr().out


def test_paper_hook(tmp_path):
    from symhx.commands.derive import paper

    lines = paper(tmp_path, False)
    data = json.loads((tmp_path / "derivations.json").read_text())
    assert all(d["verified"] for d in data)
    assert (tmp_path / "asymptotic_errors.csv").exists()
    assert lines and "verified" in lines[0]


def test_plot_asymptotic_errors():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    from symhx.asymptotics import error_table
    from symhx.plots.asymptotics import plot_asymptotic_errors

    fig = plot_asymptotic_errors(error_table((10**3, 10**6, 10**10), dps=40))
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert len(ax.get_lines()) >= 7
