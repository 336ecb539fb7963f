"""EnsembleResult's repr is one short line (it printed every histogram: thousands of numbers)."""

from __future__ import annotations

from symhx.impact import ensemble


def test_repr_is_one_short_line_with_the_grid_and_the_runs():
    res = ensemble([0.1, 0.3], 3, n=5, seed=0, t_transient=1.0, t_window=2.0)
    text = repr(res)
    assert "\n" not in text and len(text) < 200, text
    assert text.startswith("EnsembleResult(2 sigmas in [0.1, 0.3], 6 runs, 0 failed; n=5")
    assert "t_window=2.0" in text
