"""Build the optional C extension of the float64 impact engine (symhx.impact._fast).

All metadata lives in pyproject.toml; setuptools runs this file for ``ext_modules`` only.  The
extension is ``optional``: without a C compiler ``symhx`` still installs and
``symhx.impact.simulate`` falls back to the (slow) pure-Python float64 engine.
"""

from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "symhx.impact._fast",
            sources=["symhx/impact/_fast.c"],
            extra_compile_args=["-O2", "-fno-fast-math", "-ffp-contract=off"],  # = Python floats
            optional=True,
        )
    ]
)
