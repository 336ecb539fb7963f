"""Build the optional C extension of the float64 impact engine (symhx.impact._fast).

All metadata lives in pyproject.toml; setuptools runs this file for ``ext_modules`` only.  The
extension is ``optional``: without a C compiler ``symhx`` still installs and
``symhx.impact.simulate`` falls back to the (slow) pure-Python float64 engine.

The SHA-256 of ``_fast.c`` is compiled into the module (``symhx.impact._fast.source_sha256``,
read by ``symhx.impact.fast.source_sha256()``): a test compares it with the file on disk, and
``build_ext`` rebuilds an extension whose embedded hash is not the source's, whatever the file
times say (setuptools compares whole-second modification times, so an edit within a second of
the last build used to be skipped).
"""

import hashlib
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = "symhx/impact/_fast.c"
SHA256 = hashlib.sha256((Path(__file__).resolve().parent / SOURCE).read_bytes()).hexdigest()


class BuildExtByHash(build_ext):
    """``build_ext`` that also rebuilds when the built module does not embed the source's hash."""

    def build_extension(self, ext):  # type: ignore[no-untyped-def]
        target = Path(self.get_ext_fullpath(ext.name))
        if not self.force and target.exists() and SHA256.encode() not in target.read_bytes():
            self.force = True   # stale: built from another _fast.c
            try:
                super().build_extension(ext)
            finally:
                self.force = False
            return
        super().build_extension(ext)


setup(
    ext_modules=[
        Extension(
            "symhx.impact._fast",
            sources=[SOURCE],
            extra_compile_args=["-O2", "-fno-fast-math", "-ffp-contract=off"],  # = Python floats
            define_macros=[("SYMHX_FAST_SOURCE_SHA256", f'"{SHA256}"')],
            optional=True,
        )
    ],
    cmdclass={"build_ext": BuildExtByHash},
)
