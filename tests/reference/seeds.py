"""The ensemble's documented seed formulas, written out here through numpy (not through the
package), for the tests that rebuild a run or a bootstrap from its seed."""

from __future__ import annotations

import numpy as np


def sigma_bits(sigma: float) -> int:
    """The float64 bit pattern of ``sigma`` (-0.0 read as 0.0)."""
    return int(np.array(float(sigma) + 0.0, dtype=np.float64).view(np.uint64))


def run_seed_ref(seed: int, sigma: float, k: int) -> np.random.SeedSequence:
    """Run ``k`` at forcing ``sigma``: ``SeedSequence([seed, 0, bits(sigma), k])``."""
    return np.random.SeedSequence([seed, 0, sigma_bits(sigma), k])


def boot_seed_ref(seed: int, sigma: float) -> np.random.SeedSequence:
    """The bootstrap stream at ``sigma``: ``SeedSequence([seed, 1, bits(sigma)])``."""
    return np.random.SeedSequence([seed, 1, sigma_bits(sigma)])
