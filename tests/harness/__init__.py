"""Conformance checks that every object of a kind must pass (frozen discrete distributions,
continuous distributions, twin implementations, refusals of bad input)."""
