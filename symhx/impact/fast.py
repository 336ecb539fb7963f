"""The float64 engine: C extension ``symhx.impact._fast`` (placeholder until built)."""

from __future__ import annotations


def available() -> bool:
    """True when the C extension is importable."""
    try:
        from symhx.impact import _fast  # noqa: F401
    except ImportError:
        return False
    return True
