"""symhx's process-wide caches, and a way to empty them.

mutmut (``scripts/mutation.py``) runs the clean tests in its own process and then forks one
child per mutant: without this, a child starts with every cache the clean run filled (the
Gauss-Legendre rules, Stirling coefficients, shared summation engines, built derivations), so a
mutant of the code that fills a cache is never executed and survives.  ``tests/conftest.py``
empties them at the start of a session that tests a mutant.  ``tests/system/test_mutation.py``
checks that every module-level cache of the package is listed here.
"""

from __future__ import annotations

import sys

#: module -> its module-level caches (dicts and lists filled on demand, thread-local stores);
#: functools caches (anything with ``cache_clear``) are found without a list
CACHES: dict[str, tuple[str, ...]] = {
    "symhx._numeric": ("_STIRLING_EXACT",),
    "symhx.distribution": ("_ENGINES",),
    "symhx.forcing.kernels_float": ("_GL_CACHE",),
    "symhx.forcing.rawmp": ("_SQRT_PI_CACHE",),
    "symhx.simple_sums": ("_STIRLING",),
    "symhx.spaces._dist": ("_LOGU",),
    "symhx.summation": ("_NODES",),
    "symhx.symbolic": ("_BUILT",),
}


def clear_caches() -> int:
    """Empty every cache of the imported symhx modules; returns how many were emptied."""
    count = 0
    for name, mod in list(sys.modules.items()):
        if mod is None or not (name == "symhx" or name.startswith("symhx.")):
            continue
        for val in list(vars(mod).values()):
            if callable(getattr(val, "cache_clear", None)):
                val.cache_clear()
                count += 1
        for attr in CACHES.get(name, ()):
            val = vars(mod).get(attr)
            if isinstance(val, (dict, list)):
                val.clear()
            elif val is not None:  # a threading.local: this (the only) thread's store
                val.__dict__.clear()
            count += val is not None
    return count
