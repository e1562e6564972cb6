"""scipy.special's error functions and exponential integral, imported on their first use.

Importing ``scipy.special`` takes about 0.17 s (it loads scipy's array-API layer, and with it
``numpy.testing`` and ``numpy.f2py``), a third of ``import persson_fast``. The functions
here take one array (or number) and return scipy's ufunc of it; the first call imports
scipy.special (thread-safe: Python's import lock), later calls cost a dictionary lookup.
"""
from __future__ import annotations

__all__ = ["erf", "erfc", "erfcx", "exp1"]

_module = None


def _special():
    global _module
    if _module is None:
        import scipy.special        # blocks until another thread's import of it is done

        _module = scipy.special
    return _module


def erf(x):
    """scipy.special.erf(x)."""
    return _special().erf(x)


def erfc(x):
    """scipy.special.erfc(x)."""
    return _special().erfc(x)


def erfcx(x):
    """scipy.special.erfcx(x) = exp(x^2) erfc(x)."""
    return _special().erfcx(x)


def exp1(x):
    """scipy.special.exp1(x), the exponential integral E1."""
    return _special().exp1(x)
