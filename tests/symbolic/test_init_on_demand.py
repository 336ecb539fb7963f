"""symhx.symbolic builds derivations on demand and carries its own typeset texts."""

from __future__ import annotations

import re
import subprocess
import sys

import mpmath
import pytest
import sympy as sp

from symhx.symbolic import catalogue, derivation, derivations, labels, latex


def _run(code: str) -> str:
    return subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                          text=True).stdout.strip()


def test_reading_one_label_builds_only_that_derivation():
    out = _run("from symhx.symbolic import derivations\n"
               "D = derivations()\n"
               "n, has = len(D), '16' in D and 'crossing' in D\n"
               "before = repr(D)\n"
               "D['16']\n"
               "print(n, has, before, repr(D), sep='|')")
    n, has, before, after = out.split("|")
    assert int(n) == len(labels()) >= 36 and has == "True"
    assert before.endswith(" 0 built>") and after.endswith(" 1 built>")


def test_listing_builds_nothing():
    out = _run("import symhx.symbolic as S\n"
               "cat = S.catalogue(); S.labels()\n"
               "print(len(cat), repr(S.derivations()))")
    assert out.endswith(" 0 built>")


def test_mapping_and_function_agree_and_cache():
    D = derivations()
    assert list(D) == labels() == list(catalogue())
    assert D["16"] is derivation("16") is derivation(16)
    assert "nonsense" not in D and 16 not in D
    with pytest.raises(KeyError):
        D["nonsense"]
    with pytest.raises(ValueError, match="unknown derivation 'nonsense'; known: 4, 5"):
        derivation("nonsense")


def test_catalogue_matches_the_built_derivations():
    for lab, (section, description, text) in catalogue().items():
        d = derivation(lab)
        assert (d.section, d.description, d.text) == (section, description, text)


# Markdown texts: plain words with every piece of maths inside $...$ (what the book shows)
_MATH = re.compile(r"\$[^$]+\$")
_CODE = re.compile(r"`[^`]+`")
_ASCII_MATHS = re.compile(r"_\{|\^\(|<=|>=|->|\bsqrt\(|\boo\b|\bPhi\b|\bphi\(|\bgamma_|\*\*")


def _prose(text: str) -> str:
    return _CODE.sub("", _MATH.sub("", text))


@pytest.mark.parametrize("label", labels())
def test_every_text_keeps_its_maths_in_latex(label):
    d = derivation(label)
    texts = [d.text] + [c.text for c in d.checks] + [s.tex for s in d.steps if s.text]
    assert all(texts), f"{label}: a derivation, check or step without a Markdown text"
    for t in texts:
        assert t.count("$") % 2 == 0, t
        assert not _ASCII_MATHS.search(_prose(t)), f"{label}: ASCII maths outside $...$: {t!r}"
    for r in d.report():
        assert r.text and r.markdown == r.text


def test_latex_keeps_the_order_of_eq_9_and_prints_psi():
    tex = derivation("9").latex()
    assert tex.startswith(r"\Phi_{N,p}{\left(k + 1 \right)} - \Phi_{N,p}{\left(k \right)} = ")
    stationary = latex(derivation("crossing-relaxed").extra["stationary"])
    assert r"\psi\left(" in stationary and "polygamma" not in stationary
    assert r"\log\Gamma" in latex(sp.loggamma(sp.Symbol("x")))


def test_numeric_checks_ignore_the_global_mpmath_precision():
    old = mpmath.mp.dps
    try:
        mpmath.mp.dps = 5  # a user's setting must not leak into the 50-80 digit checks
        for lab in ("16-series", "log-Nc-expansion", "pc-lambert", "crossing-relaxed"):
            assert derivation(lab).verify(), lab
        assert mpmath.mp.dps == 5
    finally:
        mpmath.mp.dps = old


def test_numeric_checks_hold_in_concurrent_threads():
    """Each thread computes in its own mpmath context (80, 50 and 40 digits side by side)."""
    from concurrent.futures import ThreadPoolExecutor

    labels_ = ["16-series", "log-Nc-expansion", "pc-lambert", "crossing-relaxed"] * 2
    with ThreadPoolExecutor(4) as pool:
        assert all(pool.map(lambda lab: derivation(lab).verify(), labels_))
