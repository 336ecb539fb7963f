"""Sub-commands of the ``symhx`` CLI (one module per topic; see :mod:`symhx.cli`)."""
