"""symhx.symbolic (the package's registry: derivations, derivation, labels, verify_all): every
paper equation is there, described and checked; the derivations of each module are tested in
``test_<module>.py`` of this folder, which together cover every label."""

from __future__ import annotations

import pytest

from symhx.symbolic import derivation, derivations, labels
from tests.harness.derivations import module_of

PAPER_LABELS = [str(i) for i in range(4, 17)] + [str(i) for i in range(29, 42)]


def test_registry_has_every_paper_equation():
    reg = derivations()
    for lab in PAPER_LABELS:
        assert lab in reg, lab
    for d in reg.values():
        assert d.description and "\n" not in d.description
        assert isinstance(d.latex(), str) and d.latex()
        assert d.checks, d.label
        assert set(d.verification_kinds) <= {"symbolic", "exact", "numeric"}


def test_labels_are_in_equation_order_and_unique():
    labs = labels()
    assert len(labs) == len(set(labs)) == len(derivations())
    assert labs[:5] == ["4", "5", "6", "7", "8"]
    numeric = [int(lab.split("-")[0]) for lab in labs if lab.split("-")[0].isdigit()]
    assert numeric == sorted(numeric)
    assert list(derivations()) == labs


def test_every_derivation_comes_from_one_of_the_four_modules():
    # each module's test file checks that its table of labels is exactly that module's
    assert {module_of(d) for d in derivations().values()} == {
        "simple", "jump", "higher", "asymptotic"}


def test_unknown_label_is_refused_with_the_known_ones():
    with pytest.raises(ValueError) as info:
        derivation("99")
    msg = str(info.value)
    assert "'99'" in msg and "16-spurious" in msg and "pc-lambert" in msg
    assert derivation(16) is derivation("16")  # the label is read as a string


def test_the_mapping_of_derivations_names_an_unknown_label_and_counts_built_ones():
    from tests.harness.caches import clear_caches

    clear_caches()  # no derivation built yet
    ds = derivations()
    with pytest.raises(KeyError) as info:
        ds["no-such-label"]
    assert info.value.args == ("no-such-label",)
    n = len(ds)
    assert repr(ds) == f"<Derivations: {n} labels, 0 built>"
    ds["12"]
    assert repr(ds) == f"<Derivations: {n} labels, 1 built>"


def test_verify_all_reports_the_checks_of_each_label(monkeypatch):
    # on three cheap labels (all of them take about 10 s); a derivation whose result is
    # tampered with is reported as failed under its own label
    import symhx.symbolic as symbolic
    from tests.harness.derivations import tamper_result

    monkeypatch.setattr(symbolic, "labels", lambda: ["4", "13", "15"])
    assert symbolic.verify_all() == {"4": True, "13": True, "15": True}
    monkeypatch.setitem(symbolic._BUILT, "13", tamper_result(derivation("13")))
    assert symbolic.verify_all() == {"4": True, "13": False, "15": True}
