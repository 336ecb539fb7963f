"""symhx.symbolic.asymptotic (large-N derivations: the p_d series, the expansion of log(N c_k),
the Lambert-W minimiser): every derivation verifies and each of its checks rejects a tampered
result on its own. Their agreement with symhx.asymptotics is tested in tests/test_asymptotics.py
(the numeric side)."""

from __future__ import annotations

import sympy as sp

from symhx.symbolic import N, derivation, k
from symhx.symbolic.asymptotic import log_Nc_expansion
from tests.harness.derivations import contract_tests, tamper_part

#: every derivation of the module and its number of checks
CHECKS = {"16-series": 2, "log-Nc-expansion": 1, "pc-lambert": 1}


(test_the_table_lists_every_derivation_of_the_module, test_every_derivation_verifies,
 test_each_check_rejects_a_tampered_result) = contract_tests("asymptotic", CHECKS)


def test_both_entries_of_the_lambert_result_are_verified():
    for j in (0, 1):
        assert tamper_part(derivation("pc-lambert"), j).verify() is False


def test_log_Nc_expansion_has_exactly_the_terms_of_its_order():
    # log(N c_k) = log k/(k-1) + sum_{m <= order} S_m(k-1) / (m (k-1) N**m), S_m(K) the power
    # sums, here summed term by term
    for order in (1, 2, 3, 4):
        e = log_Nc_expansion(order)
        for kk in (2, 3, 5):
            K = kk - 1
            ref = sp.log(kk) / K + sum(sp.Rational(sum(i**m for i in range(1, K + 1)), m * K)
                                       / N**m for m in range(1, order + 1))
            assert sp.cancel(e.subs(k, kk) - ref) == 0, (order, kk)


def test_the_expansion_check_rejects_an_expansion_of_another_order():
    # the check pins the order: a result one order short (error too large) or one order
    # beyond (error far below the next term) fails as the tampered one does
    from dataclasses import replace

    d = derivation("log-Nc-expansion")
    (check,) = d.checks
    for order in (2, 4):
        other = replace(d, result=sp.Eq(d.result.lhs, log_Nc_expansion(order)))
        assert check.fn(other) is False, order
    assert check.fn(d) is True


def test_the_expansion_is_stated_for_log_of_n_times_c_k():
    # the derivation's left side, as the book prints it: log(N c_k)
    d = derivation("log-Nc-expansion")
    assert sp.simplify(d.result.lhs - sp.log(N * sp.Symbol("c_k"))) == 0
