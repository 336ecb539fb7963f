"""Type stub of the C extension ``symhx.impact._fast`` (``_fast.c``).

See :mod:`symhx.impact.fast`."""

from collections.abc import Sequence

import numpy as np

#: SHA-256 (hex) of the _fast.c this module was built from ("unknown" without setup.py's macro)
source_sha256: str

def run(n: int, omega: float, d: float, restitution: float, v_stick: float, t_end: float,
        t_from: float, record: bool, max_events: int, freqs: Sequence[float],
        alpha: np.ndarray | bytes, beta: np.ndarray | bytes, x0: np.ndarray | bytes,
        v0: np.ndarray | bytes, /) -> tuple[bytes, bytes | None, bytes | None, int, object]:
    """One run (C-contiguous float64 buffers in): ``(counts, events, updates, n_events,
    coef0)``, raw buffers read by :mod:`symhx.impact.fast`."""
