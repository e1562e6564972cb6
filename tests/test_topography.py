"""Measured surfaces: height maps, line scans and spectrum files to Persson's C(q).

The numpy path (persson_fast.surfaces.topography) needs nothing optional; the tests that use
SurfaceTopography skip cleanly when it is not installed.

Expected errors, and why (the tolerances below):

* h_rms of a map's table equals the map's own rms height to rounding: the log bins are made to
  keep the power of their Fourier modes (2π∫_bin qC dq = Σ_bin C Δq_x Δq_y).
* slope_rms of the table differs from the map's own rms gradient (computed spectrally) only
  through the log-log shape of C inside a bin: below 1.5 % at 10 bins per decade for 64² and
  larger maps (1.3e-2 worst seen at H = 0.8, 64²).
* Against the *continuous* input spectrum over [2π/L, π/Δx], the map itself differs: its modes
  sit on a lattice, and the lattice sum of q³C exceeds the integral by up to 2.6 % (H = 0.8,
  64²; 1.3 % at 256²); the sum of qC, the variance, by 27 % (H = 0.3) to 72 % (H = 0.8) — that
  is why h_rms is compared with the map, not with the input. A(p) follows slope_rms
  (A ≈ p/√(πG1) ∝ 1/slope_rms at small p): within the same few percent of the input's
  closed form.
* Line scans: the same for the 1-D spectrum, then the power-law factor of from_line_scan.
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

import persson_fast as pf
from persson_fast.surfaces import topography as topo
from persson_fast.surfaces import files, synthetic

#: rounding of an FFT and a few sums over up to 1e6 modes, relative
ROUNDING = 1e-10
#: table slope_rms vs the data's own rms gradient: log-log shape inside a bin (10 per decade)
BIN_SHAPE = 1.5e-2
#: data (on the Fourier lattice) vs the continuous input spectrum, slope and A(p): lattice sum
#: of q^3 C vs its integral (2.6 % at H = 0.8, 64²) plus BIN_SHAPE
LATTICE = 4e-2
#: the tables of a 256² map with exact mode amplitudes (and of its rows, converted by the
#: power-law factor) vs the input C(q), pointwise in [8 q0, q1/8]: the number of lattice modes
#: in a log bin's annulus differs from its area/(Δq_x Δq_y) by up to 3 % (the Gauss circle
#: problem), and the rows' sum over q_y misses the |q| > π/Δx tail near the top (2 % at q1/8 for
#: H = 0.3)
ROWS_VS_MAP = 0.04

E_STAR = 1e9
PRESSURES = np.geomspace(1e4, 3e7, 7)


def _factor(hurst):
    return math.gamma(1.0 + hurst) / (math.sqrt(math.pi) * math.gamma(hurst + 0.5))


def _input(hurst, n, dx):
    """The continuous input: a self-affine spectrum on [2π/(n dx), π/dx], slope_rms 0.1."""
    return pf.SelfAffine(hurst=hurst, q0=2 * math.pi / (n * dx), q1=math.pi / dx, slope_rms=0.1)


def _spectral_gradient(h, dx):
    """rms |∇h| of a periodic map, by Fourier differentiation (finite differences would lose
    up to 36 % of each mode near π/Δx: 2 sin(qΔx/2)/Δx instead of q)."""
    f = np.fft.fft2(h - h.mean())
    ky = 2 * math.pi * np.fft.fftfreq(h.shape[0], dx)
    kx = 2 * math.pi * np.fft.fftfreq(h.shape[1], dx)
    gx = np.fft.ifft2(1j * kx[None, :] * f).real
    gy = np.fft.ifft2(1j * ky[:, None] * f).real
    return math.sqrt(np.mean(gx**2 + gy**2))


def _spectral_slope_1d(h, dx):
    f = np.fft.fft(h - h.mean(axis=-1, keepdims=True), axis=-1)
    k = 2 * math.pi * np.fft.fftfreq(h.shape[-1], dx)
    return math.sqrt(np.mean(np.fft.ifft(1j * k * f, axis=-1).real ** 2))


# ----------------------------------------------------------------------------------------------
# the conversion factor, on cases where every factor is known
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("shape", [(32, 32), (24, 40)])
def test_single_cosine_map_has_the_exact_persson_spectrum(shape):
    """h = a cos(q_m x): two modes ±q_m, each C = a²/(4 Δq_x Δq_y); h_rms² = a²/2."""
    ny, nx = shape
    dx = 2e-9
    a, m = 3e-9, 3
    x = np.arange(nx) * dx
    h = np.broadcast_to(a * np.cos(2 * math.pi * m * x / (nx * dx)), shape)
    q, c, cell = topo.mode_spectrum(h, dx)
    assert cell == pytest.approx((2 * math.pi) ** 2 / (ny * nx * dx * dx), rel=ROUNDING)
    q_m = 2 * math.pi * m / (nx * dx)
    peak = np.isclose(q, q_m, rtol=1e-12) & (c > 1e-6 * c.max())
    assert peak.sum() == 2
    np.testing.assert_allclose(c[peak], a * a / (4 * cell), rtol=ROUNDING)
    assert c[~peak].max() < 1e-20 * c.max()
    s = pf.TabulatedPSD.from_heights(h, dx, periodic=True)
    assert s.h_rms == pytest.approx(a / math.sqrt(2), rel=ROUNDING)
    # the power sits in the bin holding q_m (and nowhere else)
    edges = s.info["bin_edges"]
    j = np.searchsorted(edges, q_m, side="right") - 1
    in_bin = 2 * math.pi * s.moment(1, edges[j], edges[j + 1])
    assert in_bin == pytest.approx(a * a / 2, rel=ROUNDING)


@pytest.mark.parametrize("hurst", [0.0, 0.5, 0.8])
def test_single_cosine_line_scan_factor(hurst):
    """1-D: 2∫C_1D dq = a²/2; the 2-D table is C_1D Γ(1+H)/(√π Γ(H+½) q), so its h_rms² is
    2π Γ(1+H)/(√π Γ(H+½)) ∫C_1D dq = π factor a²/2 (π/2 · a²/2 at H = ½)."""
    n, dx, a, m = 128, 1e-8, 2e-9, 5
    x = np.arange(n) * dx
    h = a * np.cos(2 * math.pi * m * x / (n * dx))
    s = pf.TabulatedPSD.from_heights(h, dx, periodic=True, hurst=hurst)
    q1d, c1d = s.info["psd_1d"]
    assert 2 * pf.TabulatedPSD(q1d, c1d).moment(0) == pytest.approx(a * a / 2, rel=ROUNDING)
    assert s.info["line_factor"] == pytest.approx(_factor(hurst), rel=1e-15)
    assert s.h_rms**2 == pytest.approx(math.pi * _factor(hurst) * a * a / 2, rel=ROUNDING)
    if hurst == 0.5:
        np.testing.assert_allclose(s.C_table, c1d / (2 * q1d), rtol=1e-14)


def test_gaussian_white_noise_level():
    """White noise of variance σ² on an n×n grid: every mode has <C> = σ² Δx²/(2π)², so the
    table is flat at that level (within the scatter of the ~n²/10 modes per top bin)."""
    n, dx, sigma = 256, 1e-8, 1e-9
    h = np.random.default_rng(7).normal(0.0, sigma, (n, n))
    s = pf.TabulatedPSD.from_heights(h, dx, periodic=True)
    level = sigma**2 * dx**2 / (2 * math.pi) ** 2
    # the power between 0.3 q1 and q1 (~15000 modes: scatter < 1 %) over that annulus
    lo = s.info["bin_edges"][np.searchsorted(s.info["bin_edges"], 0.3 * s.q1)]
    mean_c = s.moment(1, lo, s.q1) / (0.5 * (s.q1**2 - lo**2))
    assert mean_c == pytest.approx(level, rel=0.02)
    # the default band is the disc |q| <= π/Δx: the corners of the square grid (21 % of the
    # modes, all of white noise's power there) stay out
    q, c, cell = topo.mode_spectrum(h, dx)
    assert s.h_rms**2 == pytest.approx(c[q <= math.pi / dx * (1 + 1e-9)].sum() * cell,
                                       rel=ROUNDING)
    assert s.h_rms**2 == pytest.approx(math.pi / 4 * np.var(h), rel=0.02)


def test_convention_equals_surfacetopography_over_two_pi_squared():
    st = pytest.importorskip("SurfaceTopography")
    from SurfaceTopography.Generation import fourier_synthesis

    n, size = 64, 1e-6
    t = fourier_synthesis((n, n), (size, size), hurst=0.8, rms_height=1e-9, unit="m",
                          rng=np.random.default_rng(3))
    _, _, c_map = t.power_spectrum_from_area(return_map=True)
    h = np.asarray(t.heights()).T          # SurfaceTopography stores heights[ix, iy]
    _, c, _ = topo.mode_spectrum(h, size / n)
    ours = np.zeros(n * n)
    ours[1:] = c                           # mode_spectrum leaves out q = 0 (the first entry)
    theirs = np.asarray(c_map).T.reshape(-1) / (2 * math.pi) ** 2
    np.testing.assert_allclose(ours[1:], theirs[1:], rtol=1e-9, atol=1e-12 * theirs.max())
    # line scans: their C^1D = |h~|²/L; Persson's C_1D is that over 2π
    line = st.UniformLineScan(h[0], size, periodic=True, unit="m")
    q_st, c_st = line.power_spectrum_from_profile(resampling_method=None)
    q1, c1, _ = topo.mode_spectrum(h[0], size / n)
    for qq, cc in zip(q_st[1:], c_st[1:]):
        np.testing.assert_allclose(c1[np.isclose(q1, qq, rtol=1e-12)], cc / (2 * math.pi),
                                   rtol=1e-9)


# ----------------------------------------------------------------------------------------------
# round trips on synthetic surfaces
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("hurst", [0.3, 0.8])
@pytest.mark.parametrize("n", [64, 256])
def test_map_round_trip(hurst, n):
    dx = 1e-6 / n
    surface = _input(hurst, n, dx)
    h = synthetic.synthesize_heights(surface.psd, (n, n), dx, rng=n)
    s = pf.TabulatedPSD.from_heights(h, dx, periodic=True)
    assert s.q0 == surface.q0 and s.q1 == surface.q1
    # the map's own rms height (mean removed), exactly
    assert s.h_rms == pytest.approx(np.std(h), rel=ROUNDING)
    own_slope = _spectral_gradient(h, dx)
    assert abs(s.slope_rms / own_slope - 1) < BIN_SHAPE
    assert abs(s.slope_rms / surface.slope_rms - 1) < LATTICE
    # G is non-negative and non-decreasing
    g = s.diffusion_time(np.geomspace(s.q0, s.q1, 200), E_STAR)
    assert g[0] == 0.0 and np.all(np.diff(g) >= 0)
    # A(p) against the closed form for the input spectrum, A = erf(p / (2 sqrt(G1)))
    a = pf.solve_contact(s, PRESSURES, e_star=E_STAR).area
    g1 = surface.diffusion_time(surface.q1, E_STAR)
    from scipy.special import erf
    exact = erf(PRESSURES / (2 * math.sqrt(g1)))
    assert np.max(np.abs(a / exact - 1)) < LATTICE


@pytest.mark.parametrize("hurst", [0.3, 0.8])
@pytest.mark.parametrize("n, n_lines", [(256, 1), (1024, 8)])
def test_line_scan_round_trip(hurst, n, n_lines):
    """Line scans with the 1-D spectrum of the isotropic input (C_1D = C q / factor): the
    table's slope and A(p) match the input; its h_rms is √(π factor) times the scans' own rms
    (the 1-D variance kept bin by bin, then the factor)."""
    dx = 1e-6 / n
    surface = _input(hurst, n, dx)
    f = _factor(hurst)
    h = synthetic.synthesize_line_scans(lambda q: surface.psd(q) * q / f, n, dx, n_lines=n_lines,
                                   rng=n + n_lines)
    s = pf.TabulatedPSD.from_heights(h, dx, line_scans=True, periodic=True, hurst=hurst)
    own = math.sqrt(np.mean(h**2))
    assert s.h_rms == pytest.approx(math.sqrt(math.pi * f) * own, rel=ROUNDING)
    own_slope = _spectral_slope_1d(h, dx)
    assert abs(s.slope_rms / (math.sqrt(math.pi * f) * own_slope) - 1) < BIN_SHAPE
    assert abs(s.slope_rms / surface.slope_rms - 1) < LATTICE
    a = pf.solve_contact(s, PRESSURES, e_star=E_STAR).area
    a_in = pf.solve_contact(surface, PRESSURES, e_star=E_STAR).area
    assert np.max(np.abs(a / a_in - 1)) < LATTICE
    # the fitted H is close to the input's
    fitted = pf.TabulatedPSD.from_heights(h, dx, line_scans=True, periodic=True)
    assert abs(fitted.info["hurst"] - hurst) < 0.1 and fitted.info["hurst_fitted"]


@pytest.mark.parametrize("hurst", [0.3, 0.8])
def test_rows_of_an_isotropic_map_convert_to_its_2d_spectrum(hurst):
    """The factor Γ(1+H)/(√π Γ(H+½) q) is the projection C_1D(q_x) = ∫dq_y C(|q|): the rows of
    an isotropic map, converted, give the map's 2-D spectrum (the input, mode by mode)."""
    n = 256
    dx = 1e-6 / n
    surface = _input(hurst, n, dx)
    h = synthetic.synthesize_heights(surface.psd, (n, n), dx, rng=11)
    s2 = pf.TabulatedPSD.from_heights(h, dx, periodic=True)
    rows = pf.TabulatedPSD.from_heights(h, dx, line_scans=True, periodic=True, hurst=hurst)
    q = np.geomspace(8 * s2.q0, s2.q1 / 8, 25)
    np.testing.assert_allclose(rows.psd(q), surface.psd(q), rtol=ROWS_VS_MAP)
    np.testing.assert_allclose(s2.psd(q), surface.psd(q), rtol=ROWS_VS_MAP)


def test_non_periodic_map_with_window_and_tilt():
    """A tilted, non-periodic cut of a larger surface: the plane is removed and the Hann window
    keeps leakage out; slope_rms within a few percent of the surface's."""
    n, dx = 512, 1e-6 / 512
    surface = _input(0.8, n, dx)
    big = synthetic.synthesize_heights(surface.psd, (n, n), dx, rng=5)
    cut = big[:256, :256] + 0.05 * np.arange(256)[None, :] * dx
    s = pf.TabulatedPSD.from_heights(cut, dx)
    assert s.info["window"] == "hann" and s.info["detrend"] == "plane"
    assert abs(s.slope_rms / _spectral_gradient(big, dx) - 1) < 0.05


# ----------------------------------------------------------------------------------------------
# SurfaceTopography objects
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("hurst", [0.3, 0.8])
def test_from_topography_map_and_line_scan(hurst):
    st = pytest.importorskip("SurfaceTopography")
    from SurfaceTopography.Generation import fourier_synthesis

    n, size = 128, 2.0   # in um
    t = fourier_synthesis((n, n), (size, size), hurst=hurst, rms_slope=0.1, unit="um",
                          rng=np.random.default_rng(9))
    s = pf.TabulatedPSD.from_topography(t)
    assert s.info["periodic"] and s.info["window"] == "none"
    assert s.q0 == pytest.approx(2 * math.pi / (size * 1e-6), rel=1e-12)
    assert s.q1 == pytest.approx(math.pi / (size * 1e-6 / n), rel=1e-12)
    assert s.h_rms == pytest.approx(t.rms_height_from_area() * 1e-6, rel=ROUNDING)
    h = np.asarray(t.heights()) * 1e-6
    assert abs(s.slope_rms / _spectral_gradient(h, size * 1e-6 / n) - 1) < BIN_SHAPE
    same = pf.TabulatedPSD.from_heights(h.T, size * 1e-6 / n, periodic=True)
    np.testing.assert_allclose(s.C_table, same.C_table, rtol=1e-9)
    # a uniform line scan
    line = st.UniformLineScan(h[:, 0] * 1e9, size * 1e3, periodic=True, unit="nm")
    sl = pf.TabulatedPSD.from_topography(line, hurst=hurst)
    assert sl.h_rms == pytest.approx(math.sqrt(math.pi * _factor(hurst)) * np.std(h[:, 0]),
                                     rel=ROUNDING)


def test_from_topography_refuses_undefined_data_and_arrays():
    st = pytest.importorskip("SurfaceTopography")
    h = np.ma.masked_array(np.random.default_rng(0).normal(size=(16, 16)), mask=False)
    h.mask[2, 3] = h.mask[5, 5] = h.mask[7, 1] = True
    t = st.Topography(h, (1.0, 1.0), unit="um")
    with pytest.raises(ValueError, match=r"3 undefined pixel\(s\) out of 256"):
        pf.TabulatedPSD.from_topography(t)
    with pytest.raises(ValueError, match="from_heights"):
        pf.TabulatedPSD.from_topography(np.zeros((8, 8)))


def test_reliability_cut_off_is_visible():
    n, dx = 64, 1e-8
    h = synthetic.synthesize_heights(_input(0.8, n, dx).psd, (n, n), dx, rng=1)
    s = pf.TabulatedPSD.from_heights(h, dx, periodic=True)
    assert s.info["q_nyquist"] == pytest.approx(math.pi / dx)
    assert s.info["q_reliable"] == s.q1
    assert "reliable up to" in repr(s)


# ----------------------------------------------------------------------------------------------
# errors
# ----------------------------------------------------------------------------------------------
def test_nan_heights_are_counted():
    h = np.zeros((16, 16))
    h[1, 2] = h[3, 4] = np.nan
    with pytest.raises(ValueError, match=r"heights must be defined.*2 undefined pixel\(s\) "
                                         r"out of 256.*index \(1, 2\)"):
        pf.TabulatedPSD.from_heights(h, 1e-9)


def test_scan_too_small_for_q0_and_q1_above_nyquist():
    h = np.random.default_rng(1).normal(size=(32, 32)) * 1e-9
    with pytest.raises(ValueError, match=r"q0 must be >= 2π/L = .*\[1/m\].*too small"):
        pf.TabulatedPSD.from_heights(h, 1e-8, q0=1e5)
    with pytest.raises(ValueError, match=r"q1 must be <= π/Δx"):
        pf.TabulatedPSD.from_heights(h, 1e-8, q1=1e9)
    with pytest.raises(ValueError, match=r"q1 must be > q0"):
        pf.TabulatedPSD.from_heights(h, 1e-8, q0=1e8, q1=5e7)
    with pytest.raises(ValueError, match=r"pixel_size must be > 0 \[m\]"):
        pf.TabulatedPSD.from_heights(h, -1e-8)
    with pytest.raises(ValueError, match=r"window must be one of"):
        pf.TabulatedPSD.from_heights(h, 1e-8, window="kaiser")
    with pytest.raises(ValueError, match=r"bins_per_decade must be a whole number"):
        pf.TabulatedPSD.from_heights(h, 1e-8, bins_per_decade=0)


def test_user_band_keeps_only_its_modes():
    n, dx = 128, 1e-8
    h = synthetic.synthesize_heights(_input(0.3, n, dx).psd, (n, n), dx, rng=2)
    q0 = 4 * 2 * math.pi / (n * dx)
    s = pf.TabulatedPSD.from_heights(h, dx, periodic=True, q0=q0, q1=math.pi / dx / 2)
    q, c, cell = topo.mode_spectrum(h, dx)
    band = (q >= q0 * (1 - 1e-9)) & (q <= math.pi / dx / 2 * (1 + 1e-9))
    assert s.h_rms**2 == pytest.approx(c[band].sum() * cell, rel=ROUNDING)


def test_missing_extra_names_the_install_command(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)
    with pytest.raises(ModuleNotFoundError, match=r'pip install "persson_fast\[topography\]"'):
        files.read_topography(tmp_path / "x.x3p")


# ----------------------------------------------------------------------------------------------
# spectrum files
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("surface", [
    pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e9, q_r=1e6, h_rms=1e-8),
    pf.seed_scene(),
], ids=["self-affine", "capillary"])
def test_to_csv_from_file_round_trip(surface, tmp_path):
    path = tmp_path / "psd.csv"
    assert surface.to_csv(path) == os.fspath(path)
    back = pf.TabulatedPSD.from_file(path)
    assert back.q0 == surface.q0 and back.q1 == surface.q1
    np.testing.assert_array_equal(back.psd(back.q_table), surface.psd(back.q_table))
    # 20 points per decade: the log-log interpolation error of the moments is small
    assert back.slope_rms == pytest.approx(surface.slope_rms, rel=2e-3)
    # a table writes its own nodes and reads back bit for bit
    back.to_csv(tmp_path / "again.csv")
    again = pf.TabulatedPSD.from_file(tmp_path / "again.csv")
    np.testing.assert_array_equal(again.q_table, back.q_table)
    np.testing.assert_array_equal(again.C_table, back.C_table)
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def test_to_csv_is_atomic(tmp_path, monkeypatch):
    path = tmp_path / "psd.csv"
    path.write_text("old\n")

    def broken(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", broken)
    with pytest.raises(OSError, match="disk full"):
        pf.seed_scene().to_csv(path)
    assert path.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["psd.csv"]


@pytest.mark.parametrize("text, kwargs", [
    ("q [1/um], C [um^4]\n1, 2e-3\n10, 3e-5\n", {}),
    ("# from an instrument\nq_1/um\tC_um^4\n1\t2e-3\n10\t3e-5\n", {}),
    ("1 2e-3\n10 3e-5\n", {"q_unit": "1/um", "C_unit": "um^4"}),
    ("q [1/m], C [m^4]\n1; 2e-3\n10; 3e-5\n", {"q_unit": "1/um", "C_unit": "um^4"}),
])
def test_from_file_units(text, kwargs, tmp_path):
    path = tmp_path / "spectrum.txt"
    path.write_text(text)
    s = pf.TabulatedPSD.from_file(path, **kwargs)
    np.testing.assert_allclose(s.q_table, [1e6, 1e7], rtol=1e-15)
    np.testing.assert_allclose(s.C_table, [2e-27, 3e-29], rtol=1e-15)


@pytest.mark.parametrize("text, message", [
    ("1 2\n10 3\n", r"names no units: give q_unit="),
    ("q [1/m], C [m^4]\n1, 2\n10, -3\n", r"C must be >= 0 \[m\^4\]; got C = -3.0 on line 3"),
    ("q [1/m], C [m^4]\n1, 2\n10, nan\n", r"C must be finite \[m\^4\]; got C = nan on line 3"),
    ("q [1/m], C [m^4]\n1, 2\n1, 3\n", r"q must be strictly increasing \[1/m\]; got q = 1.0 on "
                                       r"line 2 and q = 1.0 on line 3"),
    ("q [1/m], C [m^4]\n1, 2\n", r"at least 2 rows"),
    ("q [1/ft], C [m^4]\n1, 2\n2, 3\n", r"q_unit must be one of"),
    ("q [1/m], C [m^4]\n1, 2\n2, x\n", r"line 3: expected two numbers"),
])
def test_from_file_errors(text, message, tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=message):
        pf.TabulatedPSD.from_file(path)
