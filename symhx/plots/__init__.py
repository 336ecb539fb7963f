"""Figures of the paper and beyond, drawn with matplotlib (imported only when this package is).

Every public ``plot_*`` function of the submodules (one per topic) is re-exported here, takes an
optional ``ax`` and returns the matplotlib ``Figure``. Axes carry symbols, titles carry parameters.
"""

from __future__ import annotations

import importlib
import pkgutil

__all__: list[str] = []

for _info in pkgutil.iter_modules(__path__):
    if _info.name.startswith("_"):
        continue
    _mod = importlib.import_module(f"{__name__}.{_info.name}")
    for _name in getattr(_mod, "__all__", []):
        globals()[_name] = getattr(_mod, _name)
        __all__.append(_name)
