"""``python -m symhx``: the same command line as ``symhx`` (see :mod:`symhx.cli`)."""

import sys

from symhx.cli import main

if __name__ == "__main__":
    sys.exit(main())
