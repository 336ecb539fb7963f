"""``symhx spaces`` with ``--sites`` (issue 30): a higher-order space with site classes."""

from __future__ import annotations

import json
from fractions import Fraction

import symhx
from symhx.cli import main
from symhx.sites import SiteClasses


def test_spaces_with_sites_matches_the_api(capsys):
    rc = main(["spaces", "40", "--sites", "4:1/50,36:1/40", "--space", "eq41", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert rc == 0
    sc = SiteClasses((4, 36), ("1/50", "1/40"))
    d = symhx.distribution_of(40, sc, space="eq41")
    assert Fraction(data["mean"]) == d.mean() and data["modes"] == list(d.modes())
    assert "critical" not in data  # the jump along a direction is `symhx critical --sites`
    # the text output states the same mean and modes
    assert main(["spaces", "40", "--sites", "4:1/50,36:1/40", "--space", "eq41"]) == 0
    text = dict(line.split("=", 1) for line in capsys.readouterr().out.splitlines()[1:])
    assert [int(m) for m in text["  modes  "].split(",")] == list(d.modes())
    assert abs(float(text["  E[X]   "].split()[0]) - float(d.mean())) <= 1e-12 * float(d.mean())


def test_spaces_with_sites_refuses_classes_and_p(capsys):
    for argv in (["spaces", "40", "--sites", "4:1/50,36:1/40", "--classes"],
                 ["spaces", "40", "0.02", "--sites", "4:1/50,36:1/40"]):
        rc = main(argv)
        err = capsys.readouterr().err
        assert rc == 2 and "--sites" in err and len(err.strip().splitlines()) == 1
