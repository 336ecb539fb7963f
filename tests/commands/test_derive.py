"""The derivation sub-commands (:mod:`symhx.commands.derive`): ``derive``, ``asymptotics`` and
their section of ``symhx paper``."""

from __future__ import annotations

import json

from symhx.cli import main


def test_derive_prints_latex_with_the_equation_number(capsys):
    assert main(["derive", "16", "--latex"]) == 0
    out = capsys.readouterr().out
    assert r"\sqrt{N + 1}" in out and "(16)" in out


def test_derive_verify_json_reports_each_label_verified(capsys):
    assert main(["derive", "13", "38", "--verify", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [d["label"] for d in data] == ["13", "38"]
    assert all(d["verified"] for d in data)


def test_derive_lists_labels_and_refuses_an_unknown_one(capsys):
    assert main(["derive", "--list"]) == 0
    assert "crossing" in capsys.readouterr().out
    assert main(["derive", "999"]) == 2
    assert "999" in capsys.readouterr().err


def test_asymptotics_json_agrees_with_the_exact_jump(capsys):
    assert main(["asymptotics", "1e10", "--json", "--exact", "--order", "best"]) == 0
    (row,) = json.loads(capsys.readouterr().out)
    assert row["k"] == row["k_exact"]
    assert main(["asymptotics", "1e6"]) == 0
    assert "corrected" in capsys.readouterr().out


def test_derive_paper_section_verifies_every_derivation(tmp_path):
    from symhx.commands.derive import paper

    lines = paper(tmp_path, False)
    data = json.loads((tmp_path / "derivations.json").read_text())
    assert all(d["verified"] for d in data)
    import csv

    with open(tmp_path / "asymptotic_errors.csv", newline="") as fh:
        header = next(csv.reader(fh))
    assert header == ["N", "formula", "quantity", "rel_error", "k", "k_exact", "decay"]
    assert lines and "verified" in lines[0]
    # "n/m verified (s with a symbolic check)": s counted from the derivations' check kinds
    with_symbolic = sum("symbolic" in d["kinds"] for d in data)
    assert 0 < with_symbolic < len(data)
    assert lines[0].endswith(f"({with_symbolic} with a symbolic check)")


def test_derive_verify_text_ends_with_the_count_verified(capsys):
    assert main(["derive", "13", "38", "--verify"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[-1] == "2/2 derivations verified"
    assert sum("[ok  ]" in line for line in out) >= 2 and not any("FAIL" in x for x in out)


def test_derive_verify_counts_and_names_a_failed_derivation(capsys, monkeypatch):
    # a derivation whose result is tampered with fails its checks: exit 1, the count of those
    # verified and the label of the failed one on the last line
    import symhx.symbolic as symbolic

    real = symbolic.derivation

    def tampered(label):
        d = real(label)
        return d.with_result(d.result.func(d.result.lhs, d.result.rhs + 1)) if label == "38" \
            else d

    monkeypatch.setattr(symbolic, "derivation", tampered)
    assert main(["derive", "13", "38", "--verify"]) == 1
    assert capsys.readouterr().out.splitlines()[-1] == \
        "1/2 derivations verified; failed: 38"
