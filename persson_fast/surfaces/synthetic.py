"""Synthetic measured surfaces: periodic random heights and line scans with a prescribed spectrum, by Fourier filtering (tests, examples, and where SurfaceTopography is not installed)."""
from __future__ import annotations

import math

import numpy as np

from .topography import (_pixel_sizes, _wavevectors)

__all__ = ["synthesize_heights", "synthesize_line_scans"]


# ----------------------------------------------------------------------------------------------
# synthetic surfaces (tests, examples, and where SurfaceTopography is not installed)
# ----------------------------------------------------------------------------------------------
def synthesize_heights(psd, shape, pixel_size, *, rng=None, random_amplitudes=False):
    """Periodic random heights with a prescribed spectrum, by Fourier filtering.

    Parameters
    ----------
    psd : callable
        q [1/m] -> spectrum, vectorised: for a map (2-tuple ``shape``) Persson's 2-D C(q)
        [m^4], e.g. ``surface.psd``; for line scans (``shape`` = n or (n_lines, n)) the 1-D
        C_1D(q) [m^3]. Zero where no roughness is wanted.
    shape : int or tuple of int
        n (one line scan, ``psd`` 1-D) or (ny, nx) (a map, ``psd`` 2-D); several line scans:
        :func:`synthesize_line_scans`.
    pixel_size : float
        Grid spacing. [m]
    rng : numpy.random.Generator or int, optional
        Random phases (and amplitudes) source.
    random_amplitudes : bool, optional
        False (default): every mode has exactly the prescribed power and a random phase, so
        the data's spectrum is the input mode by mode; True: Rayleigh amplitudes (Gaussian
        heights), as a real surface.

    Returns
    -------
    numpy.ndarray
        Heights, mean zero. [m]

    Notes
    -----
    h(x) = Σ_q Z_q e^{iq·x} with |Z_q|² = C(|q|) Δq_x Δq_y (maps, Δq_x Δq_y = (2π)²/A) or
    C_1D(|q|) Δq (lines, Δq = 2π/L), and Hermitian phases taken from the transform of real
    white noise; so the mean square is Σ C Δq_x Δq_y exactly (Parseval).
    """
    return _synthesize(psd, shape, pixel_size, rng=rng, random_amplitudes=random_amplitudes,
                       line_scans=None)


def synthesize_line_scans(psd_1d, n_points, pixel_size, *, n_lines=1, rng=None,
                          random_amplitudes=False):
    """Independent periodic line scans of n_points with the 1-D spectrum ``psd_1d`` [m^3];
    shape (n_lines, n_points) [m]. See :func:`synthesize_heights`."""
    return _synthesize(psd_1d, (int(n_lines), int(n_points)), pixel_size, rng=rng,
                       random_amplitudes=random_amplitudes, line_scans=True)


def _synthesize(psd, shape, pixel_size, *, rng, random_amplitudes, line_scans):
    rng = np.random.default_rng(rng)
    dx = _pixel_sizes(pixel_size, 1)[0]
    shape = (int(shape),) if np.ndim(shape) == 0 else tuple(int(n) for n in shape)
    if line_scans or len(shape) == 1:
        n = shape[-1]
        cell = 2.0 * math.pi / (n * dx)
        q = np.abs(np.fft.fftfreq(n, 1.0 / n)) * cell
        power = np.zeros(n)
        power[q > 0] = np.asarray(psd(q[q > 0]), dtype=np.float64) * cell
        noise = rng.standard_normal(shape if len(shape) == 2 else (1, n))
        w = np.fft.fft(noise, axis=-1)
        amp = np.abs(w) / math.sqrt(n) if random_amplitudes else 1.0
        with np.errstate(invalid="ignore", divide="ignore"):
            z = np.where(np.abs(w) > 0, w / np.abs(w), 1.0) * amp * np.sqrt(power)[None, :]
        h = np.fft.ifft(z, axis=-1).real * n
        return h[0] if len(shape) == 1 else h
    ny, nx = shape
    q = _wavevectors((ny, nx), (dx, dx))
    cell = (2.0 * math.pi) ** 2 / (ny * nx * dx * dx)
    power = np.zeros_like(q)
    power[q > 0] = np.asarray(psd(q[q > 0]), dtype=np.float64) * cell
    w = np.fft.fft2(rng.standard_normal(shape))
    amp = np.abs(w) / math.sqrt(ny * nx) if random_amplitudes else 1.0
    with np.errstate(invalid="ignore", divide="ignore"):
        z = np.where(np.abs(w) > 0, w / np.abs(w), 1.0) * amp * np.sqrt(power)
    return np.fft.ifft2(z).real * (ny * nx)
