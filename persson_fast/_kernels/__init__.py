"""Compiled (numba ``@njit``) kernels: dimensionless float64 loops only.

Conventions: inputs first, then scalars, then scratch, outputs last; no allocation inside
time loops; an integer status per pressure (see :mod:`persson_fast._kernels.status`).
Every function here is callable from a user's own ``@numba.njit`` code.
"""
from .status import STATUS_MESSAGES

__all__ = ["STATUS_MESSAGES"]
