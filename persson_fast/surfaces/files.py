"""Measured surfaces from files: SurfaceTopography maps and line scans, and two-column spectrum files (q, C) with their units."""
from __future__ import annotations

import math
import os
import re

import numpy as np

from .._validation import optional_import
from .topography import (C_UNITS, Q_UNITS, TOPOGRAPHY_EXTRA, _LENGTH_UNITS, spectrum_from_heights)

__all__ = ["spectrum_from_topography", "read_topography", "read_spectrum"]


# ----------------------------------------------------------------------------------------------
# SurfaceTopography objects and files
# ----------------------------------------------------------------------------------------------
def _require_surface_topography(what: str):
    return optional_import("SurfaceTopography", TOPOGRAPHY_EXTRA, what)


def _unit_factor(unit) -> float:
    if unit is None:
        raise ValueError(
            "the topography has no length unit [-]; give one when reading it (SurfaceTopography:"
            " read_topography(path, unit='um')) or use TabulatedPSD.from_heights with heights "
            "in m")
    if unit not in _LENGTH_UNITS:
        raise ValueError(f"the topography's unit must be one of {', '.join(_LENGTH_UNITS)}; "
                         f"got {unit!r}")
    return _LENGTH_UNITS[unit]


def spectrum_from_topography(topography, **kwargs):
    """``spectrum_from_heights`` for a SurfaceTopography map or uniform line scan (heights
    and pixel size converted to m, periodicity and reliability cut-off taken from it);
    ``kwargs`` as for ``spectrum_from_heights``, ``table`` included."""
    if isinstance(topography, np.ndarray) or not hasattr(topography, "heights"):
        raise ValueError(
            f"topography must be a SurfaceTopography Topography or UniformLineScan; got "
            f"{type(topography).__name__}: for a plain height array use "
            f"TabulatedPSD.from_heights(heights, pixel_size)")
    if not getattr(topography, "is_uniform", True):
        raise ValueError("topography must be on a uniform grid; a nonuniform line scan is not "
                         "supported (resample it onto a uniform grid first)")
    scale = _unit_factor(getattr(topography, "unit", None))
    heights = topography.heights()
    n_undefined = int(np.ma.count_masked(heights)) if np.ma.isMaskedArray(heights) else 0
    if n_undefined or getattr(topography, "has_undefined_data", False):
        n_bad = n_undefined or int((~np.isfinite(np.ma.getdata(heights))).sum())
        raise ValueError(
            f"topography must have data at every pixel [-]; got {n_bad} undefined pixel(s) out "
            f"of {np.size(heights)}: fill them first (topography.interpolate_undefined_data()) "
            f"or crop the map to a region without them")
    heights = np.asarray(heights, dtype=np.float64) * scale
    pixel = np.atleast_1d(np.asarray(topography.pixel_size, dtype=np.float64)) * scale
    if heights.ndim == 2:
        # SurfaceTopography stores maps as heights[ix, iy]: x along the first axis
        heights = heights.T
        pixel = pixel[::-1]
    kwargs.setdefault("periodic", bool(getattr(topography, "is_periodic", False)))
    q_reliable = None
    cutoff = getattr(topography, "short_reliability_cutoff", None)
    if callable(cutoff):
        try:
            lam = cutoff()
        except Exception:  # noqa: BLE001 - a reader without the metadata
            lam = None
        if lam is not None and np.isfinite(lam) and lam > 0:
            q_reliable = 2.0 * math.pi / (float(lam) * scale)
    return spectrum_from_heights(heights, pixel if pixel.size > 1 else float(pixel[0]),
                                 q_reliable=q_reliable,
                                 source=f"{type(topography).__name__}", **kwargs)


def read_topography(path, *, unit=None, physical_sizes=None, periodic=None):
    """Read an instrument file with SurfaceTopography (any of its formats).

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    unit : str, optional
        Length unit of files that carry none ('m', 'mm', 'um', 'nm'). [-]
    physical_sizes : float or sequence of float, optional
        Scan size of files that carry none, in ``unit``. [-]
    periodic : bool, optional
        Whether the data are periodic (synthetic surfaces); default the reader's.

    Returns
    -------
    SurfaceTopography.Topography or SurfaceTopography.UniformLineScan
    """
    st = _require_surface_topography("reading a topography file")
    kwargs = {}
    if unit is not None:
        kwargs["unit"] = unit
    if physical_sizes is not None:
        kwargs["physical_sizes"] = physical_sizes
    if periodic is not None:
        kwargs["periodic"] = bool(periodic)
    try:
        return st.read_topography(os.fspath(path), **kwargs)
    except FileNotFoundError:
        raise
    except Exception as exc:  # the readers raise their own exception types
        if isinstance(exc, OSError):
            raise
        raise ValueError(f"cannot read the topography file {os.fspath(path)!r}: "
                         f"{type(exc).__name__}: {exc}") from None


# ----------------------------------------------------------------------------------------------
# plain two-column spectrum files
# ----------------------------------------------------------------------------------------------
_SPLIT = re.compile(r"[,;\t ]+")
_UNIT_IN_NAME = re.compile(r"\[([^\]]+)\]|\(([^)]+)\)")


def _normalise_unit(text: str) -> str:
    u = text.strip().replace(" ", "").replace("**", "^").replace("μ", "µ")
    u = u.replace("m-1", "1/m").replace("m^-1", "1/m")
    return u


def _units_from_header(line: str):
    found = [m.group(1) or m.group(2) for m in _UNIT_IN_NAME.finditer(line)]
    if len(found) >= 2:
        return _normalise_unit(found[0]), _normalise_unit(found[1])
    # names such as q_1/m, C_m^4
    parts = [p for p in _SPLIT.split(line.lstrip("#").strip()) if p]
    if len(parts) >= 2 and all("_" in p for p in parts[:2]):
        return tuple(_normalise_unit(p.split("_", 1)[1]) for p in parts[:2])
    return None


def _unit(value, table: dict, name: str) -> float:
    u = _normalise_unit(value)
    if u not in table:
        raise ValueError(f"{name} must be one of {', '.join(table)}; got {value!r}")
    return table[u]


def read_spectrum(path, *, q_unit=None, C_unit=None):
    """Read a two-column spectrum (q, C) from a CSV or whitespace-separated text file.

    Parameters
    ----------
    path : str or os.PathLike
        The file. Lines starting with '#' are comments; the first line that is not numbers is
        a header that may give the units in brackets, ``q [1/m], C [m^4]`` (or
        ``q_1/um,C_um^4``). Columns are separated by commas, semicolons, tabs or spaces.
    q_unit : str, optional
        Unit of the first column, one of :data:`Q_UNITS`; overrides the header's. [-]
    C_unit : str, optional
        Unit of the second column (Persson's isotropic 2-D spectrum), one of
        :data:`C_UNITS`; overrides the header's. [-]

    Returns
    -------
    q, C : numpy.ndarray
        In 1/m and m^4; q strictly increasing, C finite and >= 0.
    """
    path = os.fspath(path)
    header_units = None
    rows = []
    with open(path, encoding="utf-8-sig") as fh:
        for lineno, raw in enumerate(fh, start=1):
            line = raw.strip()
            if not line:
                continue
            if line.startswith("#"):
                if header_units is None and not rows:
                    header_units = _units_from_header(line) or None
                continue
            parts = [p for p in _SPLIT.split(line) if p]
            try:
                values = [float(p) for p in parts[:2]]
            except ValueError:
                if rows:
                    raise ValueError(f"{path!r} line {lineno}: expected two numbers q, C; "
                                     f"got {line!r}") from None
                header_units = _units_from_header(line) or header_units
                continue
            if len(values) < 2:
                raise ValueError(f"{path!r} line {lineno}: expected two columns q, C; "
                                 f"got {line!r}")
            rows.append((lineno, values[0], values[1]))
    if len(rows) < 2:
        raise ValueError(f"{path!r} must hold at least 2 rows of q, C [-]; got {len(rows)}")
    if q_unit is None or C_unit is None:
        if header_units is None:
            raise ValueError(
                f"{path!r} names no units: give q_unit= (one of {', '.join(Q_UNITS)}) and "
                f"C_unit= (one of {', '.join(C_UNITS)}), or a header line such as "
                f"'q [1/m], C [m^4]'")
        q_unit = header_units[0] if q_unit is None else q_unit
        C_unit = header_units[1] if C_unit is None else C_unit
    fq = _unit(q_unit, Q_UNITS, "q_unit")
    fc = _unit(C_unit, C_UNITS, "C_unit")
    lines = np.array([r[0] for r in rows])
    q = np.array([r[1] for r in rows]) * fq
    c = np.array([r[2] for r in rows]) * fc
    for name, arr, unit in (("q", q, "1/m"), ("C", c, "m^4")):
        bad = ~np.isfinite(arr)
        if np.any(bad):
            i = int(np.argmax(bad))
            raise ValueError(f"{name} must be finite [{unit}]; got {name} = {float(arr[i])!r} on line "
                             f"{lines[i]} of {path!r}")
    if np.any(q <= 0):
        i = int(np.argmax(q <= 0))
        raise ValueError(f"q must be > 0 [1/m]; got q = {float(q[i])!r} on line {lines[i]} of {path!r}")
    if np.any(c < 0):
        i = int(np.argmax(c < 0))
        raise ValueError(f"C must be >= 0 [m^4]; got C = {float(c[i])!r} on line {lines[i]} of "
                         f"{path!r}")
    step = np.diff(q)
    if np.any(step <= 0):
        i = int(np.argmax(step <= 0))
        raise ValueError(f"q must be strictly increasing [1/m]; got q = {float(q[i])!r} on line "
                         f"{lines[i]} and q = {float(q[i + 1])!r} on line {lines[i + 1]} of {path!r}")
    return q, c
