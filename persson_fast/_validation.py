"""Argument checks shared by the public layer.

Every message names the argument, the rule, the unit and the offending value, e.g.
``pressure must be finite [Pa]; got pressure[3] = nan``.
"""
from __future__ import annotations

import numpy as np

__all__ = [
    "as_float_array",
    "check_not_bool",
    "check_finite",
    "check_positive",
    "check_nonnegative",
    "check_nondecreasing",
    "check_choice",
]


def _where(name: str, arr: np.ndarray, mask: np.ndarray) -> str:
    if arr.ndim == 0:
        return f"{name} = {arr.item()!r}"
    idx = tuple(int(i) for i in np.argwhere(mask)[0])
    label = ",".join(str(i) for i in idx)
    return f"{name}[{label}] = {arr[idx].item()!r}"


def _bool_in(value, name: str):
    """Where ``value`` holds a bool (Python's or NumPy's), as the words of an error message
    (``"x = True"``, ``"x[1][0] = False"``, ``"x (an array of dtype bool, shape (3,))"``);
    None where it holds none.

    Array-likes (arrays, Series, anything with a ``dtype``) are judged by their dtype, an
    object array element by element; lists and tuples, whose conversion loops over their
    elements anyway, element by element, so that a bool among floats (``[1e5, True]``,
    which NumPy converts to ``[1e5, 1.0]``) is found too."""
    if isinstance(value, (bool, np.bool_)):
        return f"{name} = {value!r}"
    dtype = getattr(value, "dtype", None)
    if dtype is not None:
        kind = getattr(dtype, "kind", None)
        if kind == "b":
            return f"{name} (an array of dtype {dtype}, shape {np.shape(value)})"
        if kind == "O" and isinstance(value, np.ndarray):
            for idx, v in np.ndenumerate(value):
                if isinstance(v, (bool, np.bool_)):
                    return f"{name}[{','.join(str(i) for i in idx)}] = {v!r}"
        return None
    if isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            found = _bool_in(v, f"{name}[{i}]")
            if found is not None:
                return found
    return None


def check_not_bool(value, name: str, unit: str) -> None:
    """Refuse a bool where a number is expected: ``True`` would otherwise be read as 1 (a
    1 Pa hardness, a 1 m pixel) and ``False`` as 0. Python's and NumPy's bools, boolean
    arrays and lists or tuples holding a bool are a ValueError naming ``name``."""
    found = _bool_in(value, name)
    if found is not None:
        raise ValueError(f"{name} must be a real number or array of them [{unit}], not a "
                         f"bool (True/False is not read as 1/0); got {found}")


def as_float_array(value, name: str, unit: str, *, ndim: tuple[int, ...] | None = None) -> np.ndarray:
    """Convert to a float64 array, rejecting non-numeric input (bools included, see
    :func:`check_not_bool`) with a clear message."""
    check_not_bool(value, name, unit)
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a real number or array of them [{unit}]; got {value!r}") from exc
    if ndim is not None and arr.ndim not in ndim:
        raise ValueError(
            f"{name} must have {' or '.join(str(n) for n in ndim)} dimension(s) [{unit}]; "
            f"got shape {arr.shape}"
        )
    return arr


def _all_true(mask) -> bool:
    """``mask.all()`` as a bool; a numpy bool scalar (what a ufunc returns for a 0-d input)
    directly, since its ``.all()`` costs ~1 us, as much as a whole scalar check."""
    return bool(mask.all()) if np.ndim(mask) else bool(mask)


def check_finite(arr: np.ndarray, name: str, unit: str) -> None:
    finite = np.isfinite(arr)
    if not _all_true(finite):
        raise ValueError(f"{name} must be finite [{unit}]; got {_where(name, arr, ~finite)}")


def check_positive(arr: np.ndarray, name: str, unit: str) -> None:
    check_finite(arr, name, unit)
    good = arr > 0
    if not _all_true(good):
        raise ValueError(f"{name} must be > 0 [{unit}]; got {_where(name, arr, ~good)}")


def check_nonnegative(arr: np.ndarray, name: str, unit: str) -> None:
    check_finite(arr, name, unit)
    good = arr >= 0
    if not _all_true(good):
        raise ValueError(f"{name} must be >= 0 [{unit}]; got {_where(name, arr, ~good)}")


def check_nondecreasing(arr: np.ndarray, name: str, unit: str) -> None:
    check_finite(arr, name, unit)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional [{unit}]; got shape {arr.shape}")
    d = np.diff(arr)
    bad = d < 0
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(
            f"{name} must be non-decreasing [{unit}]; got {name}[{i}] = {arr[i].item()!r} > "
            f"{name}[{i + 1}] = {arr[i + 1].item()!r}"
        )


def check_choice(value, name: str, choices) -> None:
    if isinstance(value, (bool, np.bool_)) or value not in choices:
        valid = ", ".join(repr(c) for c in choices)
        raise ValueError(f"{name} must be one of {valid}; got {value!r}")


def optional_import(module: str, extra: str, what: str):
    """Import an optional dependency, or raise a ModuleNotFoundError naming the extra.

    ``what`` says what needs it, e.g. ``"pf.scan"``; the message gives the install command.
    """
    import importlib

    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        raise ModuleNotFoundError(
            f"{what} needs the optional package {module!r}, which is not installed; install the "
            f"{extra!r} extra: python -m pip install \"persson_fast[{extra}]\" (in a checkout: "
            f"python -m pip install -e \".[{extra}]\")", name=module) from exc


def wall_rows(arr: np.ndarray, name: str, n_p: int, n_t: int) -> np.ndarray:
    """A wall given as a scalar, (n_t,) or (n_p, n_t) samples (a validated float array), as a
    fresh (n_p, n_t) array of rows, one per pressure."""
    if arr.ndim == 0:
        return np.full((n_p, n_t), float(arr))
    if arr.ndim == 1:
        if arr.size != n_t:
            raise ValueError(f"{name} must have the length of G ({n_t}) [Pa]; got shape "
                             f"{arr.shape}")
        return np.broadcast_to(arr, (n_p, n_t)).copy()
    if arr.shape != (n_p, n_t):
        raise ValueError(f"{name} must have shape (n_p, n_t) = ({n_p}, {n_t}) [Pa]; got shape "
                         f"{arr.shape}")
    return arr.copy()


def check_n_damp(n_damp, default: int) -> int:
    """Damped (implicit-Euler) step pairs: an integer >= 0; None gives ``default``."""
    if n_damp is None:
        return default
    if isinstance(n_damp, (bool, np.bool_)) or not isinstance(n_damp, (int, np.integer)) \
            or n_damp < 0:
        raise ValueError(f"n_damp must be an integer >= 0 [-]; got n_damp = {n_damp!r}")
    return int(n_damp)


def check_level(level) -> None:
    """An explicit resolution level of a grid method: None or an integer in [0, 10]."""
    if level is not None and (isinstance(level, bool) or not isinstance(level, (int, np.integer))
                              or not 0 <= level <= 10):
        raise ValueError(f"level must be an integer in [0, 10] [-] or None; got level = {level!r}")


def check_whole_number(value, name: str, minimum: int = 1) -> int:
    """A whole number >= ``minimum`` (an int, or a float with an integral value); a bool is
    refused as such (:func:`check_not_bool`)."""
    check_not_bool(value, name, "-")
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, float)) or \
            value != int(value) or int(value) < minimum:
        raise ValueError(f"{name} must be a whole number >= {minimum} [-]; got {name} = {value!r}")
    return int(value)
