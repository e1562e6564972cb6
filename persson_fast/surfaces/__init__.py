"""Surfaces: the roughness power spectra C(q)."""
