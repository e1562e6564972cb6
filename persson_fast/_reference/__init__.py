"""Slow twins."""
