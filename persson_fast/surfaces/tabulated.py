"""Measured spectra: :class:`TabulatedPSD` (a table of C(q), interpolated log-log, with exact
moments) and the surface models built from measured files, 'topography' (a height map or line
scan, through :mod:`persson_fast.surfaces.topography`) and 'psd' (a two-column spectrum file).

Re-exported by :mod:`persson_fast.surfaces`; this module is imported there after
:class:`~persson_fast.surfaces.models.CapillaryWaves` and :class:`~persson_fast.surfaces.models.SelfAffine`,
so that the registry lists the package's models in the order capillary, self-affine,
topography, psd.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from collections.abc import Sequence
    
    from numpy.typing import ArrayLike

import math
import os

import numpy as np

from .._validation import as_float_array, check_nonnegative, check_positive
from .base import Surface, _check_band, _check_hurst, _positive_scalar, _power_law_integral
from .registry import Parameter, SurfaceModel, band_parameters, register_surface_model
from .topography import _LENGTH_UNITS, C_UNITS, Q_UNITS

__all__ = ["TabulatedPSD"]


# ----------------------------------------------------------------------------------------------
# tabulated (measured) spectrum
# ----------------------------------------------------------------------------------------------
class TabulatedPSD(Surface):
    """Measured isotropic spectrum, interpolated log-log between its nodes.

    Parameters
    ----------
    q : array_like
        Node wavevectors, 1-D, strictly increasing, positive and finite, at least 2. [1/m]
    C : array_like
        C at the nodes, same length, >= 0 and finite. [m^4]
    q0, q1 : float, optional
        Band limits inside [q[0], q[-1]], q0 < q1; default the ends of the table. [1/m]

    Attributes
    ----------
    q_table, C_table : numpy.ndarray
        The nodes as given (the whole table, also when q0/q1 restrict it). [1/m], [m^4]

    Raises
    ------
    ValueError
        If the table is not finite, ``q`` not positive and strictly increasing, ``C``
        negative, or the band [q0, q1] not inside the table.

    See Also
    --------
    persson_fast.TabulatedPSD.from_heights : The spectrum of a height map.
    persson_fast.TabulatedPSD.from_file : A spectrum read from a file.
    persson_fast.SelfAffine : A self-affine spectrum in closed form.

    Notes
    -----
    Between nodes j and j+1 with C_j, C_{j+1} > 0 the spectrum is the power law
    C = C_j (q/q_j)^{α_j}, α_j = ln(C_{j+1}/C_j)/ln(q_{j+1}/q_j), so every moment is a sum of
    exact power-law integrals (see :class:`SelfAffine`; the logarithmic case k + α_j = -1 is exact).
    **Zero bands:** a segment with C = 0 at either end is taken as C = 0 on the whole segment
    (log-log interpolation towards 0 is undefined); at a node C is the tabulated value. C is 0
    outside [q0, q1]. Sums over many full segments use a table of block sums (powers of two), so
    a partial moment is a sum of at most ~2 log2(n) positive terms and keeps full relative
    accuracy even far out in a decaying tail.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> q = np.geomspace(1e4, 1e8, 41)
    >>> C = 2.5e-21 * (q / 1e4) ** -3.6
    >>> s = pf.TabulatedPSD(q, C)
    >>> print(f"{s.q0:.0f} {s.q1:.0f} {s.h_rms:.3g}")
    10000 100000000 9.91e-07
    >>> rng = np.random.default_rng(0)
    >>> m = pf.TabulatedPSD.from_heights(1e-9 * rng.standard_normal((64, 64)), 1e-6)
    >>> print(f"{m.q0:.4g} .. {m.q1:.4g} 1/m")
    9.817e+04 .. 3.142e+06 1/m
    """

    def __init__(self, q: ArrayLike, C: ArrayLike, q0: float | None = None,
                 q1: float | None = None):
        qa = as_float_array(q, "q", "1/m", ndim=(1,))
        ca = as_float_array(C, "C", "m^4", ndim=(1,))
        check_positive(qa, "q", "1/m")
        check_nonnegative(ca, "C", "m^4")
        if qa.size != ca.size:
            raise ValueError(
                f"q and C must have the same length [-]; got len(q) = {qa.size}, len(C) = {ca.size}"
            )
        if qa.size < 2:
            raise ValueError(f"q must hold at least 2 nodes [1/m]; got len(q) = {qa.size}")
        steps = np.diff(qa)
        if np.any(steps <= 0):
            i = int(np.argmax(steps <= 0))
            raise ValueError(
                f"q must be strictly increasing [1/m]; got q[{i}] = {float(qa[i])!r} "
                f">= q[{i + 1}] = {float(qa[i + 1])!r}"
            )
        self.q_table = qa.copy()
        self.C_table = ca.copy()
        lo_end, hi_end = float(qa[0]), float(qa[-1])
        self.q0 = lo_end if q0 is None else _positive_scalar(q0, "q0", "1/m")
        self.q1 = hi_end if q1 is None else _positive_scalar(q1, "q1", "1/m")
        for name, val in (("q0", self.q0), ("q1", self.q1)):
            if not lo_end <= val <= hi_end:
                raise ValueError(
                    f"{name} must lie inside the table [q[0], q[-1]] = [{lo_end!r}, {hi_end!r}] [1/m]; "
                    f"got {name} = {val!r}"
                )
        _check_band(self.q0, self.q1)
        positive = (ca[:-1] > 0) & (ca[1:] > 0)
        self._active = positive
        self._coef = np.where(positive, ca[:-1], 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            alpha = np.log(ca[1:] / ca[:-1]) / np.log(qa[1:] / qa[:-1])
        self._alpha = np.where(positive, alpha, 0.0)
        self._block_sums = {}
        self._require_finite_spectrum({"q": f"max(q) = {float(qa.max())!r} [1/m]",
                                       "C": f"max(C) = {float(ca.max())!r} [m^4]"})

    @classmethod
    def from_line_scan(cls, q: ArrayLike, C1d: ArrayLike, hurst: float, q0: float | None = None,
                       q1: float | None = None) -> TabulatedPSD:
        """Isotropic 2-D spectrum from a 1-D (line-scan) spectrum.

        Parameters
        ----------
        q : array_like
            Node wavevectors of the line scan, strictly increasing, > 0. [1/m]
        C1d : array_like
            1-D spectrum at the nodes, >= 0. [m^3]
        hurst : float
            Hurst exponent H in [0, 1] of the power law the conversion assumes. [-]
        q0, q1 : float, optional
            Band limits, as for :class:`TabulatedPSD`. [1/m]

        Returns
        -------
        TabulatedPSD
            Nodes q with C(q) = C_1D(q) Γ(1+H)/(√π Γ(H+½) q).

        Notes
        -----
        Convention: :math:`C_{1D}(q) = (2\\pi)^{-1}\\int dx \\langle h(x)h(0)\\rangle e^{-iqx}`,
        defined for q of both signs, so :math:`h_{rms}^2 = \\int_{-\\infty}^{\\infty} C_{1D} dq =
        2\\int_0^\\infty C_{1D} dq`, and :math:`C_{1D}(q_x) = \\int dq_y\\, C(\\sqrt{q_x^2+q_y^2})`.
        For an isotropic power law C = K q^{-2(1+H)} this integral is
        K q^{-(1+2H)} √π Γ(H+½)/Γ(1+H), hence the factor above (C_1D/(2q) at H = ½, C_1D/(πq) at
        H = 0). Persson, Tribol. Lett. 54, 99 (2014). Spectra normalised per one-sided q
        (h_rms² = ∫_0^∞ C dq) must be halved first; spectra in cycles per length (f = q/2π)
        must be converted to angular q first.
        """
        h = _check_hurst(hurst)
        qa = as_float_array(q, "q", "1/m", ndim=(1,))
        c1 = as_float_array(C1d, "C1d", "m^3", ndim=(1,))
        check_positive(qa, "q", "1/m")
        check_nonnegative(c1, "C1d", "m^3")
        if qa.size != c1.size:
            raise ValueError(
                f"q and C1d must have the same length [-]; got len(q) = {qa.size}, len(C1d) = {c1.size}"
            )
        factor = math.gamma(1.0 + h) / (math.sqrt(math.pi) * math.gamma(h + 0.5))
        return cls(qa, c1 * factor / qa, q0=q0, q1=q1)

    @classmethod
    def from_heights(cls, heights: ArrayLike, pixel_size: float | Sequence[float], *,
                     q0: float | None = None, q1: float | None = None, bins_per_decade: int = 10,
                     window: str | None = None, periodic: bool = False, detrend: str | None = None,
                     line_scans: bool | None = None, hurst: float | None = None) -> TabulatedPSD:
        """Isotropic spectrum of a height map or of line scans given as a numpy array.

        Parameters
        ----------
        heights : array_like
            Heights on a uniform grid, all defined (no NaN): 1-D (one line scan of at least 4
            points), 2-D (a map of at least 4 x 4 pixels, rows along y), or 2-D with
            ``line_scans=True`` (parallel line scans, one per row, whose 1-D spectra are
            averaged). Heights and pixel size must give a spectrum C = abs(h~)²/((2π)² A) and
            moments of it that double precision represents (heights in metres: a map in
            nm given as numbers of nm is off by 1e-36 in C). [m]
        pixel_size : float or sequence of float
            Grid spacing: one value, or (Δy, Δx) for a map; the scan's size, area and
            Nyquist wavevector π/Δx must be normal doubles. [m]
        q0 : float, optional
            Lower band limit, >= 2π/L (L the longer side of the scan); default 2π/L. [1/m]
        q1 : float, optional
            Upper band limit, <= π/Δx (Nyquist); default π/Δx, the reliability cut-off
            ``info['q_reliable']`` of a topography that knows a better one. [1/m]
        bins_per_decade : int, optional
            Logarithmic bins per decade of q in which the raw spectrum is averaged, a whole
            number in [1, 1000] (default 10; finer bins hold no mode on a scan's lower
            decades). [-]
        window : {'hann', 'none'}, optional
            Window against the leakage of non-periodic data; default 'none' for periodic data,
            'hann' otherwise (normalised to a mean square of 1). [-]
        periodic : bool, optional
            Whether the data are periodic (synthetic surfaces); default False. [-]
        detrend : {'mean', 'plane'}, optional
            What is removed first: default the mean for periodic data, the least-squares plane
            (line, for line scans) otherwise. [-]
        line_scans : bool, optional
            Treat 2-D heights as line scans; default False (1-D heights are always one). [-]
        hurst : float, optional
            H in [0, 1] of the 1-D to 2-D conversion of line scans; default fitted to the 1-D
            spectrum over the band (``info['hurst']``). Line scans only: a 2-D map (without
            ``line_scans=True``) refuses it, as it has no conversion to make. [-]

        Returns
        -------
        TabulatedPSD
            With ``info``: a dict holding the band limits of the data (``q_lowest`` = 2π/L,
            ``q_nyquist``, ``q_reliable``), the bins, the window, the data's own rms height
            (``h_rms_data``) and, for line scans, ``hurst``, ``line_factor`` and the 1-D table
            ``psd_1d``. [SI]

        Notes
        -----
        Persson's C(q) = abs(h~(q))²/((2π)² A) for each Fourier mode of a map (h~ = Δx Δy Σ h
        e^{-iq·x}, A the scan area), averaged in log bins so that every bin keeps the power
        of its modes. The result's h_rms is the rms height of the modes inside the band
        [q0, q1] of the windowed data, not the data's own (``info['h_rms_data']``): the two
        agree only for data with little power outside the band and at its lower end. A
        square map's corners (π/Δx < abs(q) <= √2 π/Δx) lie outside the disk abs(q) <= π/Δx
        and hold 21 % of the modes, so white noise comes out 11.8 % low; and the Hann
        window spreads the power of the longest wavelengths (256 x 256 self-affine maps, H =
        0.3 and 0.8, without a roll-off: 17-20 % low with the window, 2-8 % without; with a
        roll-off at 8 q0: 3-4 % and under 0.5 %). Line scans:
        C_1D = abs(h~)²/(2π L), then C = C_1D Γ(1+H)/(√π Γ(H+½) q) (see :meth:`from_line_scan`).
        The module ``persson_fast.surfaces.topography`` gives the derivation and the expected
        errors.
        """
        from .topography import spectrum_from_heights

        q, c, lo, hi, info = spectrum_from_heights(
            heights, pixel_size, table=TabulatedPSD, q0=q0, q1=q1,
            bins_per_decade=bins_per_decade, window=window,
            periodic=periodic, detrend=detrend, line_scans=line_scans, hurst=hurst)
        out = cls(q, c, q0=lo, q1=hi)
        out.info = info
        return out

    @classmethod
    def from_topography(cls, topography: object, *, q0: float | None = None,
                        q1: float | None = None, bins_per_decade: int = 10,
                        window: str | None = None, detrend: str | None = None,
                        line_scans: bool | None = None, hurst: float | None = None) -> TabulatedPSD:
        """Isotropic spectrum of a SurfaceTopography map or uniform line scan.

        Parameters
        ----------
        topography : SurfaceTopography.Topography or SurfaceTopography.UniformLineScan
            Measured (or synthetic) surface with a length unit; every pixel defined. Its
            periodicity sets the default window and detrending, and its short reliability
            cut-off λ_c, where known, the default q1 = 2π/λ_c.
        q0, q1, bins_per_decade, window, detrend, line_scans, hurst
            As for :meth:`from_heights`.

        Returns
        -------
        TabulatedPSD
            As :meth:`from_heights`, ``info`` included.

        Notes
        -----
        Needs the optional extra: ``pip install "persson_fast[topography]"``. The heights are
        converted to m; the spectrum is this package's own (:meth:`from_heights`), equal to
        SurfaceTopography's ``power_spectrum_from_area`` divided by (2π)² mode by mode.
        """
        from .files import spectrum_from_topography

        q, c, lo, hi, info = spectrum_from_topography(
            topography, table=TabulatedPSD, q0=q0, q1=q1,
            bins_per_decade=bins_per_decade, window=window,
            detrend=detrend, line_scans=line_scans, hurst=hurst)
        out = cls(q, c, q0=lo, q1=hi)
        out.info = info
        return out

    @classmethod
    def from_file(cls, path: str | os.PathLike, *, q_unit: str | None = None,
                  C_unit: str | None = None, q0: float | None = None,
                  q1: float | None = None) -> TabulatedPSD:
        """Spectrum from a plain two-column text file (CSV or whitespace-separated).

        Parameters
        ----------
        path : str or os.PathLike
            File with rows ``q, C`` (Persson's isotropic 2-D C); '#' starts a comment; a header
            line may name the units, ``q [1/m], C [m^4]`` (as :meth:`Surface.to_csv` writes).
        q_unit : str, optional
            Unit of q: '1/m', '1/mm', '1/um', '1/nm'; overrides the header. [-]
        C_unit : str, optional
            Unit of C: 'm^4', 'mm^4', 'um^4', 'nm^4'; overrides the header. [-]
        q0, q1 : float, optional
            Band limits inside the table; default its ends. [1/m]

        Returns
        -------
        TabulatedPSD
        """
        from .files import read_spectrum

        q, c = read_spectrum(path, q_unit=q_unit, C_unit=C_unit)
        out = cls(q, c, q0=q0, q1=q1)
        out.info = {"source": os.fspath(path)}
        return out

    def _repr_params(self) -> dict:
        return {"n_nodes": int(self.q_table.size), "q0": self.q0, "q1": self.q1}

    def __repr__(self) -> str:
        return (
            f"TabulatedPSD(<{self.q_table.size} nodes in [{float(self.q_table[0])!r}, "
            f"{float(self.q_table[-1])!r}]>, "
            f"q0={self.q0!r}, q1={self.q1!r}{self._repr_source()})"
        )

    def _repr_source(self) -> str:
        info = getattr(self, "info", None)
        if not info or "q_reliable" not in info:
            return ""
        return (f", from {info.get('kind', 'data')}: reliable up to "
                f"q={info['q_reliable']!r}, Nyquist {info['q_nyquist']!r}")

    def _psd_inside(self, q):
        qt = self.q_table
        seg = np.clip(np.searchsorted(qt, q, side="right") - 1, 0, qt.size - 2)
        out = self._coef[seg] * np.exp(self._alpha[seg] * np.log(q / qt[seg]))
        # at a node, C is the tabulated value (matters only next to a zero band)
        node = np.clip(np.searchsorted(qt, q, side="left"), 0, qt.size - 1)
        at_node = qt[node] == q
        out[at_node] = self.C_table[node[at_node]]
        return out

    def _segment_integral(self, k, seg, a, b):
        """Exact ∫_a^b q^k C dq with [a, b] inside segment ``seg`` (arrays)."""
        qref = self.q_table[seg]
        coef = self._coef[seg] * qref**k
        return _power_law_integral(coef, qref, self._alpha[seg] + k, a, b)

    def _levels(self, k):
        """Block sums of full-segment moments: level l holds sums over 2**l consecutive segments."""
        if k not in self._block_sums:
            nseg = self.q_table.size - 1
            seg = np.arange(nseg)
            full = np.zeros(nseg)
            act = self._active
            if np.any(act):
                full[act] = self._segment_integral(
                    k, seg[act], self.q_table[:-1][act], self.q_table[1:][act]
                )
            levels = [full]
            while 2 ** len(levels) <= nseg:
                prev = levels[-1]
                half = 2 ** (len(levels) - 1)
                levels.append(prev[: prev.size - half] + prev[half:])
            self._block_sums[k] = levels
        return self._block_sums[k]

    def _range_sum(self, k, j1, j2):
        """Sum of full-segment moments over segments j1 .. j2-1 (arrays), positive terms only."""
        levels = self._levels(k)
        total = np.zeros(j1.shape, dtype=np.float64)
        j = j1.copy()
        for lev in range(len(levels) - 1, -1, -1):
            size = 2**lev
            take = j + size <= j2
            if np.any(take):
                total[take] += levels[lev][j[take]]
                j[take] += size
        return total

    def _integral(self, k, a, b):
        qt = self.q_table
        nseg = qt.size - 1
        ja = np.clip(np.searchsorted(qt, a, side="right") - 1, 0, nseg - 1)
        jb = np.clip(np.searchsorted(qt, b, side="left") - 1, 0, nseg - 1)
        out = np.zeros_like(a)
        same = ja == jb
        if np.any(same):
            out[same] = self._segment_integral(k, ja[same], a[same], b[same])
        diff = ~same
        if np.any(diff):
            ja_d, jb_d = ja[diff], jb[diff]
            head = self._segment_integral(k, ja_d, a[diff], qt[ja_d + 1])
            tail = self._segment_integral(k, jb_d, qt[jb_d], b[diff])
            out[diff] = head + self._range_sum(k, ja_d + 1, jb_d) + tail
        return out

    def breakpoints(self) -> np.ndarray:
        inner = self.q_table[(self.q_table > self.q0) & (self.q_table < self.q1)]
        return np.concatenate(([self.q0], inner, [self.q1]))


# the measured spectra: TabulatedPSD from a height map or line scan, or from a spectrum file
_MEASURED_TITLE = "measured surface"
_MEASURED_TEXT = (
    "a height map or line scan in any format SurfaceTopography reads (needs the extra: "
    "pip install \"persson_fast[topography]\"), or a two-column spectrum file q, C "
    "(Persson's isotropic 2-D C; units from its header 'q [1/m], C [m^4]' or the flags)")


def _surface_from_topography_file(file, q0=None, q1=None, hurst=None, bins_per_decade=10,
                                  unit=None, physical_sizes=None) -> TabulatedPSD:
    """The 'topography' model: :meth:`TabulatedPSD.from_topography` of a file read with
    :func:`persson_fast.surfaces.files.read_topography`."""
    from .files import read_topography

    topography = read_topography(file, unit=unit,
                                 physical_sizes=tuple(physical_sizes) if physical_sizes else None)
    return TabulatedPSD.from_topography(topography, q0=q0, q1=q1, hurst=hurst,
                                        bins_per_decade=bins_per_decade)


def _surface_from_spectrum_file(file, q_unit=None, C_unit=None, q0=None, q1=None) -> TabulatedPSD:
    """The 'psd' model: :meth:`TabulatedPSD.from_file`."""
    return TabulatedPSD.from_file(file, q_unit=q_unit, C_unit=C_unit, q0=q0, q1=q1)


def _ascii_names(units) -> str:
    """The unit names of a table as the help lists them: the ASCII spellings (``um`` stands for
    ``µm`` too, ``A`` for ``Å``; both are accepted)."""
    return ", ".join(name for name in units if name.isascii())


register_surface_model(SurfaceModel(
    name="topography",
    parameters={
        "file": Parameter(None, "height map or line scan; q0 defaults to 2 pi/L, q1 to "
                                "pi/pixel (or the file's reliability cut-off)",
                          required=True, metavar="MAP", flag="--topography", type=str,
                          path=True, selects=True),
        **band_parameters(required=False),
        "hurst": Parameter("-", "Hurst exponent of the 1-D to 2-D conversion of line scans "
                                "(default fitted)", metavar="H"),
        "bins_per_decade": Parameter(None, "log bins per decade of the measured spectrum",
                                     metavar="NBINS", type=int),
        "unit": Parameter(None, f"length unit of a topography file that names none "
                                f"({_ascii_names(_LENGTH_UNITS)})", metavar="HUNIT",
                          flag="--height-unit", type=str),
        "physical_sizes": Parameter(None, "scan size of a topography file that gives none, in "
                                          "--height-unit", metavar="SIZE",
                                    flag="--physical-size", nargs="+"),
    },
    build=_surface_from_topography_file, title=_MEASURED_TITLE, description=_MEASURED_TEXT))

register_surface_model(SurfaceModel(
    name="psd",
    parameters={
        "file": Parameter(None, "two-column spectrum file q, C", required=True,
                          metavar="FILE.csv", flag="--psd", type=str, path=True, selects=True),
        "q_unit": Parameter(None, f"unit of q in --psd ({_ascii_names(Q_UNITS)})",
                            metavar="QUNIT", type=str),
        "C_unit": Parameter(None, f"unit of C in --psd ({_ascii_names(C_UNITS)})",
                            metavar="CUNIT", type=str),
        **band_parameters(required=False),
    },
    build=_surface_from_spectrum_file, title=_MEASURED_TITLE, description=_MEASURED_TEXT))
