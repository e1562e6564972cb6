"""Measured surfaces: from height maps, line scans and spectrum files to C(q).

This module turns what an instrument gives (a height map, one or several line scans, or a
tabulated spectrum in a text file) into a :class:`~persson_fast.surfaces.tabulated.TabulatedPSD` in
Persson's isotropic convention, and writes any surface's spectrum back to a CSV file. The
public entry points are the classmethods ``TabulatedPSD.from_topography``,
``TabulatedPSD.from_heights``, ``TabulatedPSD.from_file`` and the method ``Surface.to_csv``;
they delegate here.

Conventions
-----------
Persson's 2-D spectrum of an isotropic surface (THEORY.md §1) is

.. math::

    C(q) = (2\\pi)^{-2} \\int d^2x\\, \\langle h(\\mathbf x) h(\\mathbf 0)\\rangle
           e^{-i\\mathbf q\\cdot\\mathbf x},
    \\qquad h_{rms}^2 = 2\\pi\\int q C\\,dq.                                  [m^4]

For an N_x × N_y map with pixel size Δx × Δy and area A = L_x L_y, the discrete Fourier
transform :math:`\\tilde h(\\mathbf q) = \\Delta x \\Delta y \\sum h_{ij} e^{-i\\mathbf q\\cdot
\\mathbf x_{ij}}` on the grid :math:`\\mathbf q = 2\\pi(m/L_x, n/L_y)` gives the estimate

.. math:: C(\\mathbf q) = \\frac{|\\tilde h(\\mathbf q)|^2}{(2\\pi)^2 A},

so that Parseval's identity reads :math:`\\overline{h^2} = \\sum_{\\mathbf q \\ne 0}
C(\\mathbf q)\\,\\Delta q_x \\Delta q_y` with :math:`\\Delta q_x \\Delta q_y = (2\\pi)^2/A`. The
spectrum ``power_spectrum_from_area`` of SurfaceTopography (Jacobs, Junge, Pastewka, Surf.
Topogr. Metrol. Prop. 5, 013001 (2017)) is :math:`C^{2D} = |\\tilde h|^2/A`: Persson's C is
:math:`C^{2D}/(2\\pi)^2`. A line scan of length L gives Persson's 1-D spectrum
:math:`C_{1D}(q) = |\\tilde h(q)|^2/(2\\pi L)` (:math:`h_{rms}^2 = \\int_{-\\infty}^{\\infty}
C_{1D} dq`), SurfaceTopography's ``power_spectrum_from_profile`` times :math:`1/(2\\pi)`; it is
converted to the isotropic 2-D spectrum by the power-law relation of
``TabulatedPSD.from_line_scan``, :math:`C(q) = C_{1D}(q)\\,\\Gamma(1+H)/(\\sqrt\\pi\\,
\\Gamma(H+\\tfrac12)\\, q)`.

Binning
-------
The raw spectrum of one map scatters by 100 % from mode to mode (each mode's power is an
exponential random variable). It is averaged in logarithmic bins (``bins_per_decade``, default
10) between q0 and q1 and tabulated at the bins' geometric centres (plus the two band ends),
log-log interpolated in between. The node values are then rescaled (a few multiplicative
sweeps) until the table's integral over every bin equals the power of the Fourier modes in
that bin: :math:`2\\pi\\int_{bin} qC\\,dq = \\sum_{\\mathbf q \\in bin} C(\\mathbf q)\\Delta q_x
\\Delta q_y` for maps, :math:`2\\int_{bin} C_{1D}\\,dq = \\sum_{|q| \\in bin} C_{1D}(q)\\,\\Delta q`
for line scans. With the default band the table's h_rms is therefore the map's own rms height
(mean, or plane, removed). Without this step a plain radial average would miss the power of the
few longest modes: the sum over the discrete lattice near q0 = 2π/L holds 27 % (H = 0.3) to
72 % (H = 0.8) more variance than the continuous integral from q0 of the same power law. The
rms slope is not constrained bin by bin; its error is that of the log-log shape inside a bin,
below 1 % at 10 bins per decade (tests/test_topography.py measures it). A table with C ≥ 0
has a non-negative, non-decreasing G(q).
"""
from __future__ import annotations

import math
import warnings

import numpy as np

from .._validation import as_float_array, check_positive, check_whole_number
from .base import write_spectrum_csv

__all__ = [
    "TOPOGRAPHY_EXTRA",
    "Q_UNITS",
    "C_UNITS",
    "mode_spectrum",
    "spectrum_from_heights",
    "write_spectrum_csv",
]

#: the optional extra that brings SurfaceTopography
TOPOGRAPHY_EXTRA = "topography"

#: wavevector units a spectrum file may use, and their factor to 1/m
Q_UNITS = {"1/m": 1.0, "1/mm": 1e3, "1/um": 1e6, "1/µm": 1e6, "1/nm": 1e9, "1/A": 1e10}
#: units of the 2-D spectrum C(q) a file may use, and their factor to m^4
C_UNITS = {"m^4": 1.0, "mm^4": 1e-12, "um^4": 1e-24, "µm^4": 1e-24, "nm^4": 1e-36,
           "A^4": 1e-40}
#: length units of height data (SurfaceTopography's names), and their factor to m
_LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9, "Å": 1e-10,
                 "A": 1e-10, "pm": 1e-12, "km": 1e3}

_WINDOWS = ("hann", "none")
_DETRENDS = ("mean", "plane")

#: most log bins per decade: finer bins hold no mode on any measured scan's lower decades
#: (a line scan's first decade holds 9 modes, a map's ~300) and are merged with their
#: neighbours at a cost that grows with the square of their number (1e6 per decade ran for
#: minutes); 1000 takes ~1 s on a 1024 x 1024 map
MAX_BINS_PER_DECADE = 1000
#: the fewest points of a line scan, and pixels along each side of a map
MIN_POINTS = 4
#: relative tolerance of Parseval's identity in :func:`mode_spectrum`: the mode powers sum
#: to the data's variance up to the FFT's rounding (~1e-15 log N); a larger miss means the
#: spectrum under- or overflowed double precision
PARSEVAL_RTOL = 1e-9


# ----------------------------------------------------------------------------------------------
# argument checks
# ----------------------------------------------------------------------------------------------
def _pixel_sizes(pixel_size, ndim: int) -> tuple:
    arr = as_float_array(pixel_size, "pixel_size", "m", ndim=(0, 1))
    check_positive(arr, "pixel_size", "m")
    if arr.ndim == 0:
        return (float(arr),) * ndim
    if arr.size != ndim:
        raise ValueError(f"pixel_size must hold 1 or {ndim} value(s) for {ndim}-D heights [m]; "
                         f"got {arr.size} values {arr.tolist()!r}")
    return tuple(float(v) for v in arr)


def _check_heights(heights, name: str = "heights") -> np.ndarray:
    """Heights as float64 (masked pixels and NaN refused, with their count)."""
    n_masked = int(np.ma.count_masked(heights)) if np.ma.isMaskedArray(heights) else 0
    data = np.ma.getdata(heights) if np.ma.isMaskedArray(heights) else heights
    arr = as_float_array(data, name, "m")
    if arr.ndim not in (1, 2):
        raise ValueError(f"{name} must be 1-D (a line scan) or 2-D (a map or several line "
                         f"scans) [m]; got shape {arr.shape}")
    bad = ~np.isfinite(arr)
    if n_masked:
        bad = bad | np.ma.getmaskarray(heights)
    n_bad = int(bad.sum())
    if n_bad:
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ValueError(
            f"{name} must be defined and finite at every pixel [m]; got {n_bad} undefined "
            f"pixel(s) out of {arr.size} (the first at index {idx}, value "
            f"{'masked' if n_masked and np.ma.getmaskarray(heights)[idx] else arr[idx]!r}); "
            f"fill them first, e.g. SurfaceTopography's interpolate_undefined_data(), or "
            f"crop the map to a region without them")
    return arr


def _check_size(h: np.ndarray, lines: bool, name: str = "heights") -> None:
    """At least MIN_POINTS points per line scan, or MIN_POINTS x MIN_POINTS pixels for a
    map (before any band limit is derived from the size)."""
    if lines:
        n = h.shape[-1]
        if n < MIN_POINTS or h.size == 0:
            raise ValueError(f"{name}: a line scan must have at least {MIN_POINTS} points [-]; "
                             f"got shape {h.shape}")
    elif min(h.shape) < MIN_POINTS:
        raise ValueError(f"{name}: a map must have at least {MIN_POINTS} x {MIN_POINTS} "
                         f"pixels [-]; got shape {h.shape}"
                         + (" (parallel profiles: pass line_scans=True)"
                            if h.shape[-1] >= MIN_POINTS and min(h.shape) > 0 else ""))


def _check_extent(pixel, shape, lines: bool) -> None:
    """The scan's lengths, area and wavevectors must be normal doubles (a pixel_size off by
    many orders of magnitude, e.g. a unit mistake, makes them 0 or inf)."""
    lengths = [n * d for n, d in zip(shape[-len(pixel):], pixel)]
    area = lengths[0] if lines else lengths[0] * lengths[1]
    numbers = [*lengths, area, (2.0 * math.pi) ** 2 / area if area > 0 else 0.0,
               *(math.pi / d for d in pixel)]
    tiny = np.finfo(float).tiny
    if not all(tiny <= x < math.inf for x in numbers):
        given = pixel[0] if len(set(pixel)) == 1 else pixel
        raise ValueError(
            f"pixel_size must give a scan whose size, area and wavevectors are normal double "
            f"precision numbers [m] (pixel sizes are in metres, e.g. 1e-8 for 10 nm); got "
            f"pixel_size = {given!r} for shape {tuple(shape)}: scan "
            f"{'length' if lines else 'area'} {area!r}, Nyquist wavevector "
            f"{math.pi / min(pixel)!r} 1/m")


def _check_representable(x: np.ndarray, power_sum: float, cell: float, pixel,
                         heights_max: float, lines: bool) -> None:
    """Parseval's identity: the mode powers (sum C * cell, the q = 0 mode left out) equal
    the variance of the transformed data ``x`` (for line scans, the mean of the rows'
    variances); an under- or overflow of the spectrum in double precision breaks it. The
    variance is taken of x divided by its largest value, so it cannot under- or overflow
    itself; the FFT's rounding is allowed relative to that largest value too."""
    scale = float(np.max(np.abs(x))) if x.size else 0.0
    if not math.isfinite(scale):
        rms_direct = math.inf
    elif scale == 0.0:
        rms_direct = 0.0
    else:
        y = x / scale
        mean = y.mean(axis=-1, keepdims=True) if lines else y.mean()
        var = float(np.mean((y - mean) ** 2))
        rms_direct = scale * math.sqrt(var)
    with np.errstate(over="ignore", invalid="ignore"):
        ms = power_sum * cell
    rms_spectrum = math.sqrt(ms) if ms >= 0 else math.nan
    if (math.isfinite(rms_direct) and math.isfinite(rms_spectrum) and abs(
            rms_spectrum - rms_direct) <= PARSEVAL_RTOL * rms_direct + 1e-12 * scale):
        return
    given = pixel[0] if len(set(pixel)) == 1 else pixel
    raise ValueError(
        f"heights and pixel_size give a spectrum C = |h~|^2/((2 pi)^2 A) that is not "
        f"representable in double precision [m^4]: it "
        f"{'underflows' if rms_spectrum < rms_direct else 'overflows'} (the rms height from "
        f"the spectrum is {rms_spectrum!r} m, from the heights {rms_direct!r} m); got "
        f"max |heights| = {heights_max!r}, pixel_size = {given!r} (both are in metres: "
        f"convert them, e.g. nm * 1e-9)")


def user_terms_table(table, q, c, pixel_size, heights_max, **kwargs):
    """``table(q, C, **kwargs)`` of a spectrum measured from heights, its refusal (a moment
    of the spectrum not finite in double precision) said in the terms of the data."""
    try:
        return table(q, c, **kwargs)
    except ValueError as exc:
        raise ValueError(
            f"heights and pixel_size must give a spectrum whose moments are finite in double "
            f"precision [m^4]; got max |heights| = {heights_max!r}, pixel_size = "
            f"{pixel_size!r} (both are in metres: convert them, e.g. nm * 1e-9); the table "
            f"of their spectrum says: {exc}") from None


def _choice(value, name: str, choices) -> str:
    if value not in choices:
        valid = ", ".join(repr(c) for c in choices)
        raise ValueError(f"{name} must be one of {valid}; got {value!r}")
    return value


# ----------------------------------------------------------------------------------------------
# the spectrum of every Fourier mode
def _wavevectors(shape, pixel) -> np.ndarray:
    """|q| on the FFT grid, q = 2π k/L with integer k (so that the lowest mode is exactly
    2π/L as computed elsewhere, not an ulp off)."""
    (ny, nx), (dy, dx) = shape, pixel
    qy = np.fft.fftfreq(ny, 1.0 / ny) * (2.0 * math.pi / (ny * dy))
    qx = np.fft.fftfreq(nx, 1.0 / nx) * (2.0 * math.pi / (nx * dx))
    return np.sqrt(qy[:, None] ** 2 + qx[None, :] ** 2)


# ----------------------------------------------------------------------------------------------
def _window_1d(n: int) -> np.ndarray:
    """Hann window of n points normalised so that the mean of its square is 1."""
    w = np.hanning(n) if n > 2 else np.ones(n)
    return w / math.sqrt(np.mean(w * w))


def _detrend(h: np.ndarray, how: str, axes: int) -> np.ndarray:
    """Remove the mean, or the least-squares plane (line for profiles), along the last
    ``axes`` axes (``axes`` = 1: every row separately)."""
    if how == "mean" or (axes == 2 and min(h.shape) < 2) or h.shape[-1] < 2:
        if axes == 2:
            return h - h.mean()
        return h - h.mean(axis=-1, keepdims=True)
    if axes == 2:
        ny, nx = h.shape
        y, x = np.meshgrid(np.arange(ny) - 0.5 * (ny - 1), np.arange(nx) - 0.5 * (nx - 1),
                           indexing="ij")
        basis = np.stack([np.ones(h.size), x.ravel(), y.ravel()], axis=1)
        coef, *_ = np.linalg.lstsq(basis, h.ravel(), rcond=None)
        return h - (basis @ coef).reshape(h.shape)
    n = h.shape[-1]
    x = np.arange(n) - 0.5 * (n - 1)
    slope = (h * x).sum(axis=-1, keepdims=True) / (x * x).sum()
    return h - h.mean(axis=-1, keepdims=True) - slope * x


def mode_spectrum(heights, pixel_size, *, line_scans=None, window="none", detrend="mean"):
    """Persson-convention spectrum of every Fourier mode of a map or of line scans.

    Parameters
    ----------
    heights : array_like
        Heights on a uniform grid: 1-D (a line scan), or 2-D: a map (rows along y, columns
        along x) or, with ``line_scans=True``, parallel line scans along the last axis. [m]
    pixel_size : float or sequence of float
        Grid spacing, one value or one per axis (Δy, Δx for a map). [m]
    line_scans : bool, optional
        Treat 2-D heights as independent line scans (rows) whose 1-D spectra are averaged.
        Default: False for 2-D heights, True for 1-D.
    window : {'none', 'hann'}, optional
        Hann window (separable for maps), normalised to a mean square of 1. [-]
    detrend : {'mean', 'plane'}, optional
        What is removed before the transform (for line scans: per row; 'plane' = line). [-]

    Returns
    -------
    q : numpy.ndarray
        |q| of every mode with q != 0 (for line scans: every q_k, k != 0, both signs). [1/m]
    C : numpy.ndarray
        For maps, Persson's 2-D C(q) = |h~|²/((2π)² A) of each mode [m^4]; for line scans, the
        1-D spectrum C_1D(q) = |h~|²/(2π L), averaged over the rows. [m^3]
    cell : float
        The q-space measure of one mode: (2π)²/A for maps [1/m^2], 2π/L for line scans
        [1/m]; ``sum(C) * cell`` is the mean-square height of the (windowed) data. [m^2]
    """
    h = _check_heights(heights)
    lines = (h.ndim == 1) if line_scans is None else bool(line_scans)
    _check_size(h, lines)
    if h.ndim == 1:
        lines = True
        h = h[None, :]
    window = _choice("none" if window is None else window, "window", _WINDOWS)
    detrend = _choice(detrend, "detrend", _DETRENDS)
    h_max = float(np.max(np.abs(h)))
    if lines:
        dx = _pixel_sizes(pixel_size, 1)[0] if np.ndim(pixel_size) == 0 else \
            _pixel_sizes(np.asarray(pixel_size, dtype=float).reshape(-1)[-1:], 1)[0]
        n = h.shape[-1]
        _check_extent((dx,), h.shape, True)
        with np.errstate(all="ignore"):        # an under- or overflow is refused below
            hd = _detrend(h, detrend, 1)
            if window == "hann":
                hd = hd * _window_1d(n)[None, :]
            length = n * dx
            f = np.fft.fft(hd, axis=-1) * dx
            c1 = (np.abs(f) ** 2).mean(axis=0) / (2.0 * math.pi * length)
        q = np.abs(np.fft.fftfreq(n, 1.0 / n)) * (2.0 * math.pi / length)
        keep = q > 0
        with np.errstate(over="ignore"):
            power_sum = float(np.sum(c1[keep]))
        _check_representable(hd, power_sum, 2.0 * math.pi / length, (dx,), h_max, True)
        return q[keep], c1[keep], 2.0 * math.pi / length
    dy, dx = _pixel_sizes(pixel_size, 2)
    ny, nx = h.shape
    _check_extent((dy, dx), h.shape, False)
    with np.errstate(all="ignore"):            # an under- or overflow is refused below
        hd = _detrend(h, detrend, 2)
        if window == "hann":
            hd = hd * np.outer(_window_1d(ny), _window_1d(nx))
        area = ny * dy * nx * dx
        f = np.fft.fft2(hd) * (dx * dy)
        c2 = np.abs(f) ** 2 / ((2.0 * math.pi) ** 2 * area)
    q = _wavevectors((ny, nx), (dy, dx))
    keep = q > 0
    with np.errstate(over="ignore"):
        power_sum = float(np.sum(c2[keep]))
    _check_representable(hd, power_sum, (2.0 * math.pi) ** 2 / area, (dy, dx), h_max, False)
    return q[keep], c2[keep], (2.0 * math.pi) ** 2 / area


# ----------------------------------------------------------------------------------------------
# binning into a table
# ----------------------------------------------------------------------------------------------
def _log_edges(q0: float, q1: float, bins_per_decade: int) -> np.ndarray:
    n = max(1, int(math.ceil(bins_per_decade * math.log10(q1 / q0) - 1e-9)))
    edges = q0 * (q1 / q0) ** (np.arange(n + 1) / n)
    edges[0], edges[-1] = q0, q1
    return edges


def _bin_index(edges: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Bin of each q: [e_j, e_j+1), a q within 1e-9 (relative) below an edge counted above it
    (lattice modes and lattice edges agree to rounding only); the last bin is closed."""
    return np.clip(np.searchsorted(edges, q * (1.0 + 1e-9), side="right") - 1, 0,
                   edges.size - 2)


def _merge_empty(edges: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Edges with every bin holding at least one mode: an empty bin joins its neighbour
    above (the last one, its neighbour below)."""
    edges = list(edges)
    counts = list(counts)
    j = 0
    while j < len(counts):
        if counts[j] == 0 and len(counts) > 1:
            if j < len(counts) - 1:
                counts[j + 1] += counts[j]
                del edges[j + 1]
            else:
                counts[j - 1] += counts[j]
                del edges[j]
            del counts[j]
            continue
        j += 1
    return np.asarray(edges)


def _conserving_table(edges, target, k: int, table):
    """Nodes (q, C) of a log-log table whose integral ∫ q^k C dq over each bin equals
    ``target`` (bins given by ``edges``), found by multiplicative sweeps from the bin
    densities; ``table(q, C)`` builds the table model whose exact moments are matched."""
    lo, hi = edges[:-1], edges[1:]
    measure = (hi ** (k + 1) - lo ** (k + 1)) / (k + 1)
    dens = target / measure
    centres = np.sqrt(lo * hi)
    q = np.concatenate(([edges[0]], centres, [edges[-1]]))
    c = np.concatenate(([dens[0]], dens, [dens[-1]]))
    owner = np.concatenate(([0], np.arange(lo.size), [lo.size - 1]))
    positive = target > 0

    def extend(c):
        # the band ends continue the power law of the neighbouring segment (flat if either
        # neighbour is 0, or for a single bin)
        if c.size > 3 and c[1] > 0 and c[2] > 0:
            c[0] = c[1] * (c[2] / c[1]) ** (math.log(q[0] / q[1]) / math.log(q[2] / q[1]))
        else:
            c[0] = c[1]
        if c.size > 3 and c[-2] > 0 and c[-3] > 0:
            c[-1] = c[-2] * (c[-3] / c[-2]) ** (math.log(q[-1] / q[-2]) /
                                                 math.log(q[-3] / q[-2]))
        else:
            c[-1] = c[-2]
        return c

    c = extend(c)
    for _ in range(500):
        got = table(q, c).moment(k, lo, hi)
        ratio = np.ones_like(got)
        ok = positive & (got > 0)
        ratio[ok] = target[ok] / got[ok]
        c = extend(c * ratio[owner])
        if np.all(np.abs(ratio - 1.0) < 1e-13):
            break
    return q, c


def _band(q0, q1, q_lowest, q_nyquist, q_reliable, length_text):
    """Validated band (q0, q1) with defaults 2π/L and the reliable limit."""
    if q0 is None:
        q0 = q_lowest
    else:
        arr = as_float_array(q0, "q0", "1/m", ndim=(0,))
        check_positive(arr, "q0", "1/m")
        q0 = float(arr)
        if q0 < q_lowest * (1.0 - 1e-12):
            raise ValueError(
                f"q0 must be >= 2π/L = {q_lowest!r} [1/m], the longest wavelength a scan of "
                f"size {length_text} holds; got q0 = {q0!r}: the scan is too small for this "
                f"q0 (measure a larger area, or raise q0)")
        q0 = max(q0, q_lowest)
    if q1 is None:
        q1 = q_reliable
    else:
        arr = as_float_array(q1, "q1", "1/m", ndim=(0,))
        check_positive(arr, "q1", "1/m")
        q1 = float(arr)
        if q1 > q_nyquist * (1.0 + 1e-12):
            raise ValueError(
                f"q1 must be <= π/Δx = {q_nyquist!r} [1/m], the largest wavevector the pixel "
                f"size resolves; got q1 = {q1!r}")
        q1 = min(q1, q_nyquist)
        if q1 > q_reliable * (1.0 + 1e-12):
            warnings.warn(
                f"q1 = {q1!r} 1/m lies above the reliability cut-off q = {q_reliable!r} 1/m of "
                f"this measurement: the spectrum above it is instrument artefact, not surface",
                UserWarning, stacklevel=4)
    if not q1 > q0:
        raise ValueError(f"q1 must be > q0 [1/m]; got q1 = {q1!r}, q0 = {q0!r}")
    return q0, q1


def _hurst_from_line_spectrum(q, c1, cell):
    """Least-squares fit of ln C_1D = a - (1 + 2H) ln q over the bins; H clipped to [0, 1]."""
    good = c1 > 1e-10 * np.max(c1)  # bins holding only round-off stay out of the fit
    if good.sum() < 2:
        return 0.5
    slope = np.polyfit(np.log(q[good]), np.log(c1[good]), 1)[0]
    return float(np.clip(-(slope + 1.0) / 2.0, 0.0, 1.0))


def spectrum_from_heights(heights, pixel_size, *, table, q0=None, q1=None, bins_per_decade=10,
                          window=None, periodic=False, detrend=None, line_scans=None,
                          hurst=None, q_reliable=None, source="heights"):
    """Binned Persson spectrum of a map or line scans: the work of ``TabulatedPSD.from_heights``.

    ``table(q, C)`` builds the tabulated model (``TabulatedPSD``) whose exact moments keep
    the power of every bin; the caller passes it, so that this module does not import the
    model layer above it.

    Returns
    -------
    q, C : numpy.ndarray
        Nodes of the isotropic 2-D table. [1/m], [m^4]
    q0, q1 : float
        The band. [1/m]
    info : dict
        What was done and the limits of the data (see ``TabulatedPSD.from_heights``).
    """
    h = _check_heights(heights)
    lines = (h.ndim == 1) if line_scans is None else bool(line_scans)
    if h.ndim == 1:
        lines = True
    _check_size(h, lines)
    periodic = bool(periodic)
    if window is None:
        window = "none" if periodic else "hann"
    window = _choice(window, "window", _WINDOWS)
    if detrend is None:
        detrend = "mean" if periodic else "plane"
    detrend = _choice(detrend, "detrend", _DETRENDS)
    if isinstance(bins_per_decade, float) and not math.isfinite(bins_per_decade):
        raise ValueError(f"bins_per_decade must be a whole number in [1, {MAX_BINS_PER_DECADE}] "
                         f"[-]; got bins_per_decade = {bins_per_decade!r}")
    bins_per_decade = check_whole_number(bins_per_decade, "bins_per_decade")
    if bins_per_decade > MAX_BINS_PER_DECADE:
        raise ValueError(f"bins_per_decade must be a whole number in [1, {MAX_BINS_PER_DECADE}] "
                         f"[-] (finer bins hold no Fourier mode on a scan's lower decades and "
                         f"are merged with their neighbours, at a cost that grows with the "
                         f"square of their number); got bins_per_decade = {bins_per_decade!r}")
    if hurst is not None:
        arr = as_float_array(hurst, "hurst", "-", ndim=(0,))
        H = float(arr)
        if not (math.isfinite(H) and 0.0 <= H <= 1.0):
            raise ValueError(f"hurst must be in [0, 1] [-]; got hurst = {H!r}")
        if not lines:
            raise ValueError(f"hurst applies to line scans only (the 1-D to 2-D conversion of "
                             f"their spectrum) [-]; a 2-D map gives its 2-D spectrum directly: "
                             f"leave hurst out, or pass line_scans=True for rows that are "
                             f"parallel profiles; got hurst = {H!r} with a map of shape "
                             f"{h.shape}")
    if lines:
        dx = _pixel_sizes(pixel_size, 1)[0] if np.ndim(pixel_size) == 0 else \
            _pixel_sizes(np.asarray(pixel_size, dtype=float).reshape(-1)[-1:], 1)[0]
        _check_extent((dx,), h.shape, True)
        n = h.shape[-1]
        length = n * dx
        q_lowest = 2.0 * math.pi / length
        q_nyquist = math.pi / dx
        length_text = f"L = {length!r} m"
    else:
        dy, dx = _pixel_sizes(pixel_size, 2)
        _check_extent((dy, dx), h.shape, False)
        ly, lx = h.shape[0] * dy, h.shape[1] * dx
        q_lowest = 2.0 * math.pi / max(lx, ly)
        q_nyquist = math.pi / max(dx, dy)
        length_text = f"L_y x L_x = {ly!r} m x {lx!r} m"
    reliable = q_nyquist if q_reliable is None else min(float(q_reliable), q_nyquist)
    q0, q1 = _band(q0, q1, q_lowest, q_nyquist, reliable, length_text)

    qm, cm, cell = mode_spectrum(h, dx if lines else (dy, dx), line_scans=lines,
                                 window=window, detrend=detrend)
    h_max = float(np.max(np.abs(h)))
    given_pixel = pixel_size

    def checked_table(q, c):
        return user_terms_table(table, q, c, given_pixel, h_max)

    edges = _log_edges(q0, q1, bins_per_decade)
    if lines:
        # the modes of a line scan sit on the lattice k 2π/L: interior edges half-way between
        # them, so that a bin [k - 1/2, m - 1/2) 2π/L holds exactly the cells of the modes
        # k .. m-1 and its density is their mean (edges anywhere else would make neighbouring
        # bins alternate by up to 2x)
        cell_1d = 2.0 * math.pi / length
        inner = (np.unique(np.round(edges[1:-1] / cell_1d - 0.5)) + 0.5) * cell_1d
        inner = inner[(inner > q0 * (1.0 + 1e-9)) & (inner < q1 * (1.0 - 1e-9))]
        edges = np.concatenate(([q0], inner, [q1]))
    # a mode on a band end belongs to the band (2π/L and fftfreq's k/(n d) differ by an ulp)
    inside = (qm >= q0 * (1.0 - 1e-9)) & (qm <= q1 * (1.0 + 1e-9))
    qi, ci = qm[inside], cm[inside]
    j = _bin_index(edges, qi)
    counts = np.bincount(j, minlength=edges.size - 1)
    edges = _merge_empty(edges, counts)
    if edges.size < 2 or qi.size == 0:
        raise ValueError(f"the band [q0, q1] = [{q0!r}, {q1!r}] [1/m] holds no Fourier mode of "
                         f"the data; widen it")
    j = _bin_index(edges, qi)
    counts = np.bincount(j, minlength=edges.size - 1)
    power = np.bincount(j, weights=ci * cell, minlength=edges.size - 1)  # mean square per bin

    info = {"source": source, "kind": "line scans" if lines else "map",
            "q_lowest": q_lowest, "q_nyquist": q_nyquist, "q_reliable": reliable,
            "window": window, "detrend": detrend, "periodic": periodic,
            "bins_per_decade": bins_per_decade, "bin_edges": edges, "modes_per_bin": counts,
            "h_rms_band": math.sqrt(power.sum()),
            "h_rms_data": math.sqrt(cm.sum() * cell)}
    if lines:
        # 2 ∫_bin C_1D dq = the bin's mean square (q of both signs)
        q1d, c1d = _conserving_table(edges, 0.5 * power, 0, checked_table)
        centres = np.sqrt(edges[:-1] * edges[1:])
        if hurst is None:
            H = _hurst_from_line_spectrum(centres, 0.5 * power / np.diff(edges), cell)
            info["hurst_fitted"] = True
        else:                                   # H checked above
            info["hurst_fitted"] = False
        factor = math.gamma(1.0 + H) / (math.sqrt(math.pi) * math.gamma(H + 0.5))
        info.update(hurst=H, line_factor=factor, psd_1d=(q1d, c1d), n_lines=int(
            1 if h.ndim == 1 else h.shape[0]), scan_length=length)
        c2d = c1d * factor / q1d
        checked_table(q1d, c2d)                # the caller's table of it, refused in these terms
        return q1d, c2d, q0, q1, info
    # 2π ∫_bin q C dq = the bin's mean square
    q2, c2 = _conserving_table(edges, power / (2.0 * math.pi), 1, checked_table)
    checked_table(q2, c2)                      # the caller's table of it, refused in these terms
    info.update(scan_size=(ly, lx), shape=tuple(h.shape))
    return q2, c2, q0, q1, info
