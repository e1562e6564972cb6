"""Adhesion."""
