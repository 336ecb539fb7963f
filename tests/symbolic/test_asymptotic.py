"""symhx.symbolic.asymptotic (large-N derivations: the p_d series, the expansion of log(N c_k),
the Lambert-W minimiser): every derivation verifies and each of its checks rejects a tampered
result on its own. Their agreement with symhx.asymptotics is tested in tests/test_asymptotics.py
(the numeric side)."""

from __future__ import annotations

from symhx.symbolic import derivation
from tests.harness.derivations import contract_tests, tamper_part

#: every derivation of the module and its number of checks
CHECKS = {"16-series": 2, "log-Nc-expansion": 1, "pc-lambert": 1}


(test_the_table_lists_every_derivation_of_the_module, test_every_derivation_verifies,
 test_each_check_rejects_a_tampered_result) = contract_tests("asymptotic", CHECKS)


def test_both_entries_of_the_lambert_result_are_verified():
    for j in (0, 1):
        assert tamper_part(derivation("pc-lambert"), j).verify() is False
