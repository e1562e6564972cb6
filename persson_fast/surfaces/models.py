"""Surface roughness power spectra C(q) in Persson's isotropic convention.

Every model here describes a randomly rough, isotropic surface through its 2-D power
spectral density

.. math::

    C(q) = (2\\pi)^{-2} \\int d^2x \\, \\langle h(\\mathbf{x}) h(\\mathbf{0}) \\rangle
           e^{-i \\mathbf{q}\\cdot\\mathbf{x}}                                   [m^4]

cut off outside the band :math:`[q_0, q_1]` (Persson, J. Chem. Phys. 115, 3840 (2001);
Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)). With this convention

.. math::

    h_{rms}^2 = 2\\pi \\int q C dq, \\qquad
    \\langle |\\nabla h|^2 \\rangle = 2\\pi \\int q^3 C dq,

and the contact theory sees the surface only through the diffusion time

.. math::

    G(q) = \\frac{\\pi}{4} E^{*2} \\int_{q_0}^{q} q'^3 C(q') dq'            [Pa^2]

(seed paper Eqs. 4-5 integrated over ζ; Persson 2001).

The public classes are :class:`CapillaryWaves` (seed Eq. 1), :class:`SelfAffine` (power law
with roll-off) and :class:`TabulatedPSD` (measured spectra, log-log interpolated). All three
share :class:`Surface`, whose :meth:`Surface.moment` returns the partial moments
:math:`\\int q^k C dq` (k = 0..3) in closed form wherever one exists. SI units, float64.

Surface models declare their parameters once: a subclass that sets ``MODEL`` (its name on the
command line and in TOML files) and ``PARAMETERS`` (name -> :class:`Parameter`: unit, help,
whether required) enters :data:`SURFACE_MODELS` when its class is created, in whatever module
that happens. The ``persson-fast contact`` command builds its flags and TOML keys from that
registry, and :func:`persson_fast.scan` reads the units of a declared class's parameters from
it; neither keeps its own list.

This module holds the two analytic models and the seed paper's constants; the rest lives in
:mod:`persson_fast.surfaces.base` (:class:`Surface`, constants, shared numerics),
:mod:`persson_fast.surfaces.registry` (the registry) and :mod:`persson_fast.surfaces.tabulated`
(:class:`TabulatedPSD`, the measured-file models). Every name is re-exported here, so
``persson_fast.surfaces.<name>`` keeps working (and pickles of earlier versions load).
"""
from __future__ import annotations

import math

import numpy as np

from .._validation import check_not_bool
# the names of __all__ that live elsewhere, re-exported (persson_fast.surfaces.<name>)
from .base import (BOLTZMANN, E_STAR_WARN_BELOW, RmsValue, Surface, _atan_ratio,
                           _check_band, _check_hurst, _gauss_legendre_log, _log1p_ratio,
                           _nonnegative_scalar, _positive_scalar, _power_law_integral,
                           _x_minus_atan, _x_minus_log1p, check_e_star)
from .registry import (BAND, SURFACE_MODELS, Parameter, SurfaceModel, band_parameters,
                             register_surface_model)

__all__ = [
    "BOLTZMANN",
    "E_STAR_WARN_BELOW",
    "check_e_star",
    "RmsValue",
    "Parameter",
    "SurfaceModel",
    "SURFACE_MODELS",
    "BAND",
    "band_parameters",
    "register_surface_model",
    "Surface",
    "CapillaryWaves",
    "SelfAffine",
    "TabulatedPSD",
    "seed_scene",
]



# ----------------------------------------------------------------------------------------------
# frozen capillary waves (seed Eq. 1)
# ----------------------------------------------------------------------------------------------
class CapillaryWaves(Surface):
    """Roughness of frozen capillary waves (seed paper Eq. 1).

    Parameters
    ----------
    temperature : float
        Temperature at which the waves freeze (the glass transition T_g), > 0. [K]
    surface_tension : float
        Surface tension γ of the melt, > 0. [J/m^2]
    q_c : float
        Cross-over wavevector q_c = (γ/κ)^{1/2}, > 0; sets the bending stiffness. [1/m]
    q0, q1 : float
        Band limits, 0 < q0 < q1, finite. [1/m]
    density : float, optional
        Mass density ρ of the melt, >= 0; 0 (default) neglects gravity. [kg/m^3]
    gravity : float, optional
        Gravitational acceleration g, >= 0 (default 9.81). [m/s^2]

    Attributes
    ----------
    bending_stiffness : float
        κ = γ/q_c². [J]

    Raises
    ------
    ValueError
        If a parameter is not finite or out of range (temperature, surface tension,
        q_c and 0 < q0 < q1 positive; density and gravity >= 0).

    See Also
    --------
    persson_fast.seed_scene : The seed paper's PMMA surface, a CapillaryWaves.
    persson_fast.SelfAffine : A self-affine fractal surface.

    Notes
    -----
    The spectrum is (B.N.J. Persson, "Influence of frozen capillary waves on contact mechanics",
    arXiv:cond-mat/0512604, Eq. 1; also Surf. Sci. Rep. 61, 201 (2006) §2.2)

    .. math:: C(q) = \\frac{1}{(2\\pi)^2} \\frac{k_B T}{\\rho g + \\gamma q^2 + \\kappa q^4}.

    Write A = k_B T/(2π)². Without gravity (ρg = 0), for q0 <= a < b <= q1 and w = q_c(b-a)/(ab+q_c²):

    .. math::

        \\int_a^b C dq &= \\frac{A}{\\kappa}\\frac{b-a}{ab(ab+q_c^2)}
                          + \\frac{A}{\\gamma q_c}(w - \\arctan w) \\\\
        \\int_a^b q C dq &= \\frac{A}{2\\gamma}
                  \\ln\\left[1 + \\frac{q_c^2 (b^2-a^2)}{a^2 (b^2+q_c^2)}\\right] \\\\
        \\int_a^b q^2 C dq &= \\frac{A}{\\kappa q_c} \\arctan\\frac{q_c (b-a)}{q_c^2 + ab} \\\\
        \\int_a^b q^3 C dq &= \\frac{A}{2\\kappa} \\ln\\left[1 + \\frac{b^2-a^2}{q_c^2+a^2}\\right]

    (partial fractions of 1/(q²(γ+κq²)) and the arctan/log addition theorems, arranged as sums
    of positive terms). With a = q0, b = q1 the second line is Eq. 2,
    h_rms² = (k_B T/2πγ) ln[(q1/q0)((q0²+q_c²)/(q1²+q_c²))^{1/2}], and the last gives
    G(q) = (E*² k_B T/(32πκ)) ln[(γ+κq²)/(γ+κq0²)] (from Eq. 6).

    With gravity, u = q² turns the k = 1, 3 moments into ½∫du/P and ½∫u du/P with
    P(u) = κu² + γu + ρg = κ(u+p)(u+s), Δ = γ² - 4κρg, s = (γ+√Δ)/(2κ), p = 2ρg/(γ+√Δ)
    (the cancellation-free small root). For Δ >= 0, with δ = u_b - u_a,

    .. math:: \\int \\frac{du}{P} = \\frac{\\delta}{\\kappa (u_a+p)(u_b+s)}
              \\frac{\\ln(1+x)}{x}, \\qquad x = \\frac{\\delta (s-p)}{(u_a+p)(u_b+s)},

    and for Δ < 0 (m = γ/2κ, n = √-Δ/2κ) the same with arctan(y)/y,
    y = nδ/(n² + (u_a+m)(u_b+m)), in place of ln(1+x)/x. For k = 3 and s >= 3p,

    .. math:: \\int \\frac{u\\,du}{P} = \\frac{g(p) - g(s)}{\\kappa (s-p)},\\quad
              g(t) = \\int \\frac{u\\,du}{u+t} = \\frac{\\delta u_a}{u_a+t}
              + t\\,\\psi\\!\\left(\\frac{\\delta}{u_a+t}\\right),\\ \\psi(x) = x - \\ln(1+x)

    on u <= s, and :math:`\\frac{1}{2\\kappa}[\\ln(P(u_b)/P(u_a)) - \\gamma\\int du/P]` on u >= s;
    each loses at most a factor 3 to cancellation. The k = 0, 2 moments with gravity (and k = 3
    when s < 3p, which needs q_c² < 16ρg/3γ, far outside physical ranges) use 20-point
    Gauss-Legendre panels of unit width in ln q: the poles of C lie at least π/4 off the real
    ln q axis, which gives a relative error below 1e-13.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.CapillaryWaves(temperature=370.0, surface_tension=0.04, q_c=1.7e9,
    ...                       q0=2 * np.pi / 1e-4, q1=7e9)
    >>> print(f"h_rms {s.h_rms:.3g} m, slope rms {s.slope_rms:.3g}")
    h_rms 4.55e-10 m, slope rms 0.291
    """

    MODEL = "capillary"
    MODEL_TITLE = "capillary-wave surface"
    PARAMETERS = {
        "temperature": Parameter("K", "temperature", required=True, metavar="T"),
        "surface_tension": Parameter("J/m^2", "surface tension", required=True, metavar="GAMMA"),
        "q_c": Parameter("1/m", "crossover wavevector", required=True, metavar="QC"),
        **band_parameters(),
        "density": Parameter("kg/m^3", "mass density", metavar="RHO"),
        "gravity": Parameter("m/s^2", "gravity", metavar="G"),
    }

    def __init__(self, temperature: float, surface_tension: float, q_c: float, q0: float,
                 q1: float, density: float = 0.0, gravity: float = 9.81):
        self.temperature = _positive_scalar(temperature, "temperature", "K")
        self.surface_tension = _positive_scalar(surface_tension, "surface_tension", "J/m^2")
        self.q_c = _positive_scalar(q_c, "q_c", "1/m")
        self.q0 = _positive_scalar(q0, "q0", "1/m")
        self.q1 = _positive_scalar(q1, "q1", "1/m")
        _check_band(self.q0, self.q1)
        self.density = _nonnegative_scalar(density, "density", "kg/m^3")
        self.gravity = _nonnegative_scalar(gravity, "gravity", "m/s^2")
        self.bending_stiffness = self.surface_tension / (self.q_c * self.q_c)
        # C = A/(rho g + gamma q^2 + kappa q^4) with A = k_B T/(2 pi)^2 [J]
        self._amp = BOLTZMANN * self.temperature / (4.0 * math.pi * math.pi)
        self._rho_g = self.density * self.gravity
        if self._rho_g > 0.0:
            gam, kap, c = self.surface_tension, self.bending_stiffness, self._rho_g
            disc = gam * gam - 4.0 * kap * c
            self._disc = disc
            if disc >= 0.0:
                root = math.sqrt(disc)
                self._s = (gam + root) / (2.0 * kap)
                self._p = 2.0 * c / (gam + root)
            else:
                self._m = gam / (2.0 * kap)
                self._n = math.sqrt(-disc) / (2.0 * kap)
        self._require_finite_spectrum({
            "temperature": f"temperature = {self.temperature!r} [K]",
            "surface_tension": f"surface_tension = {self.surface_tension!r} [J/m^2]",
            "q_c": f"q_c = {self.q_c!r} [1/m]",
        })

    def _repr_params(self) -> dict:
        return {
            "temperature": self.temperature,
            "surface_tension": self.surface_tension,
            "q_c": self.q_c,
            "q0": self.q0,
            "q1": self.q1,
            "density": self.density,
            "gravity": self.gravity,
        }

    def _psd_inside(self, q):
        q2 = q * q
        return self._amp / (self._rho_g + q2 * (self.surface_tension + self.bending_stiffness * q2))

    # --- moments -------------------------------------------------------------------------------
    def _integral(self, k, a, b):
        if self._rho_g == 0.0:
            return self._integral_no_gravity(k, a, b)
        # u = q^2; u_b - u_a = (b - a)(b + a) keeps narrow intervals exact
        if k == 1:
            return 0.5 * self._amp * self._inv_quadratic(a * a, b * b, (b - a) * (b + a))
        if k == 3 and self._disc >= 0.0 and self._s >= 3.0 * self._p:
            return 0.5 * self._amp * self._u_over_quadratic(a * a, b * b, (b - a) * (b + a))
        return _gauss_legendre_log(lambda q: q ** (k + 1) * self._psd_inside(q), a, b)

    def _integral_no_gravity(self, k, a, b):
        amp, gam, kap, qc = self._amp, self.surface_tension, self.bending_stiffness, self.q_c
        qc2 = qc * qc
        diff = b - a
        if k == 0:
            ab = a * b
            w = qc * diff / (ab + qc2)
            return (amp / kap) * diff / (ab * (ab + qc2)) + (amp / (gam * qc)) * _x_minus_atan(w)
        if k == 1:
            return (0.5 * amp / gam) * np.log1p(qc2 * diff * (b + a) / (a * a * (b * b + qc2)))
        if k == 2:
            return (amp / (kap * qc)) * np.arctan(qc * diff / (qc2 + a * b))
        return (0.5 * amp / kap) * np.log1p(diff * (b + a) / (qc2 + a * a))

    def _inv_quadratic(self, ua, ub, delta):
        """∫_{ua}^{ub} du/(κu² + γu + ρg), exact for every sign of the discriminant.

        ``delta`` is ub - ua, passed in so that the caller can compute it without cancellation.
        """
        kap = self.bending_stiffness
        if self._disc >= 0.0:
            p, s = self._p, self._s
            den = (ua + p) * (ub + s)
            return delta / (kap * den) * _log1p_ratio(delta * (s - p) / den)
        m, n = self._m, self._n
        den = n * n + (ua + m) * (ub + m)
        return delta / (kap * den) * _atan_ratio(n * delta / den)

    def _u_over_quadratic(self, ua, ub, delta):
        """∫_{ua}^{ub} u du/(κu² + γu + ρg) for real roots with s >= 3p (see class Notes).

        ``delta`` is ub - ua, computed by the caller without cancellation.
        """
        kap, gam, p, s = self.bending_stiffness, self.surface_tension, self._p, self._s
        out = np.zeros_like(ua)
        # part below s: divided difference of g(t) = ∫ u/(u+t) du
        lo_hi = np.minimum(ub, s)
        m1 = lo_hi > ua
        if np.any(m1):
            x0 = ua[m1]
            d = np.where(ub[m1] <= s, delta[m1], s - x0)

            def g(t):
                return d * x0 / (x0 + t) + t * _x_minus_log1p(d / (x0 + t))

            out[m1] += (g(p) - g(s)) / (kap * (s - p))
        # part above s: (1/2κ)[ln P(ub)/P(ua) - γ ∫ du/P]
        hi_lo = np.maximum(ua, s)
        m2 = ub > hi_lo
        if np.any(m2):
            x0, x1 = hi_lo[m2], ub[m2]
            d = np.where(ua[m2] >= s, delta[m2], x1 - s)
            p_x0 = x0 * (kap * x0 + gam) + self._rho_g
            log_term = np.log1p(d * (kap * (x0 + x1) + gam) / p_x0)
            out[m2] += (log_term - gam * self._inv_quadratic(x0, x1, d)) / (2.0 * kap)
        return out


# ----------------------------------------------------------------------------------------------
# self-affine fractal with roll-off
# ----------------------------------------------------------------------------------------------
class SelfAffine(Surface):
    """Self-affine fractal spectrum with an optional roll-off.

    Parameters
    ----------
    hurst : float
        Hurst exponent H in [0, 1] (fractal dimension D_f = 3 - H). [-]
    q0, q1 : float
        Band limits, 0 < q0 < q1, finite. [1/m]
    q_r : float, optional
        Roll-off wavevector, q0 <= q_r <= q1; None (default) means q_r = q0, no roll-off. [1/m]
    h_rms : float, optional
        Root-mean-square height, > 0. [m]
    slope_rms : float, optional
        Root-mean-square slope, > 0. [-]
    C0 : float, optional
        Plateau value of C, > 0. [m^4]

    Attributes
    ----------
    hurst : float
        H. [-]
    q_r : float
        Roll-off wavevector. [1/m]
    C0 : float
        Plateau value C(q0 <= q < q_r). [m^4]

    Raises
    ------
    ValueError
        If the parameters are not finite, out of range (``hurst`` in [0, 1], 0 < q0 <
        q1) or do not fix the spectrum's level exactly once (one of ``h_rms``,
        ``slope_rms``, ``C0``).

    See Also
    --------
    persson_fast.CapillaryWaves : Frozen capillary waves (the seed paper's surface).
    persson_fast.TabulatedPSD : A measured or tabulated spectrum.
    persson_fast.solve_contact : The contact area of a surface.

    Notes
    -----
    Exactly one of ``h_rms``, ``slope_rms`` and ``C0`` must be given; the others follow. It
    must leave C0 and the moments of C finite in float64 (``slope_rms=1e200`` would give
    C0 = inf): otherwise a ValueError names it.

    .. math::

        C(q) = C_0 \\ (q_0 \\le q < q_r), \\qquad
        C(q) = C_0 (q/q_r)^{-2(1+H)} \\ (q_r \\le q \\le q_1)

    (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)). Every moment is a sum of power-law
    integrals, evaluated exactly as

    .. math:: \\int_a^b c (q/q_r)^{e} dq = c\\, q_r\\, t_a^{\\sigma} L \\frac{e^{\\sigma L} - 1}{\\sigma L},
              \\quad \\sigma = e + 1,\\ t_a = a/q_r,\\ L = \\ln(b/a),

    with (e^x - 1)/x from ``expm1``: the logarithmic cases σ = k - 1 - 2H = 0 (k=1, H=0; k=2,
    H=½; k=3, H=1) come out exactly and σ near 0 keeps full precision. The normalisations are
    C0 = h_rms²/(2π m1) and C0 = slope_rms²/(2π m3), m_k being the k-th moment at C0 = 1.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> print(f"{s.C0:.4g} m^4, slope rms {s.slope_rms:.4g}")
    2.546e-21 m^4, slope rms 0.199
    >>> print(f"{s.h_rms:.3g} m")
    1e-06 m
    """

    MODEL = "self-affine"
    PARAMETERS = {
        "hurst": Parameter("-", "Hurst exponent", required=True, metavar="H"),
        **band_parameters(),
        "q_r": Parameter("1/m", "roll-off wavevector", metavar="QR"),
        "h_rms": Parameter("m", "rms height", metavar="HRMS"),
        "slope_rms": Parameter("-", "rms slope", metavar="S"),
        "C0": Parameter("m^4", "plateau of the spectrum"),
    }

    def __init__(self, hurst: float, q0: float, q1: float, q_r: float | None = None,
                 h_rms: float | None = None, slope_rms: float | None = None,
                 C0: float | None = None):
        self.hurst = _check_hurst(hurst)
        self.q0 = _positive_scalar(q0, "q0", "1/m")
        self.q1 = _positive_scalar(q1, "q1", "1/m")
        _check_band(self.q0, self.q1)
        if q_r is None:
            self.q_r = self.q0
        else:
            self.q_r = _positive_scalar(q_r, "q_r", "1/m")
            if not self.q0 <= self.q_r <= self.q1:
                raise ValueError(
                    f"q_r must lie in [q0, q1] [1/m]; got q_r = {self.q_r!r}, "
                    f"q0 = {self.q0!r}, q1 = {self.q1!r}"
                )
        given = {"h_rms": h_rms, "slope_rms": slope_rms, "C0": C0}
        chosen = [name for name, value in given.items() if value is not None]
        if len(chosen) != 1:
            got = ", ".join(f"{name} = {given[name]!r}" for name in chosen) or "none"
            raise ValueError(
                "exactly one of h_rms [m], slope_rms [-], C0 [m^4] must be given; got " + got
            )
        self.C0 = 1.0
        if C0 is not None:
            self.C0 = _positive_scalar(C0, "C0", "m^4")
            given = {"C0": f"C0 = {self.C0!r} [m^4]"}
        elif h_rms is not None:
            h = _positive_scalar(h_rms, "h_rms", "m")
            with np.errstate(all="ignore"):
                self.C0 = h * h / (2.0 * math.pi * self.moment(1))
            given = {"h_rms": f"h_rms = {h!r} [m]"}
        else:
            g = _positive_scalar(slope_rms, "slope_rms", "-")
            with np.errstate(all="ignore"):
                self.C0 = g * g / (2.0 * math.pi * self.moment(3))
            given = {"slope_rms": f"slope_rms = {g!r} [-]"}
        finite_c0 = math.isfinite(self.C0)
        self._require_finite_spectrum(given, "" if finite_c0 else f"C0 = {self.C0!r} [m^4]")

    def _repr_params(self) -> dict:
        return {"hurst": self.hurst, "q0": self.q0, "q1": self.q1, "q_r": self.q_r, "C0": self.C0}

    def _psd_inside(self, q):
        out = np.full_like(q, self.C0)
        tail = q >= self.q_r
        out[tail] = self.C0 * np.exp(-2.0 * (1.0 + self.hurst) * np.log(q[tail] / self.q_r))
        return out

    def _integral(self, k, a, b):
        out = np.zeros_like(a)
        qr = self.q_r
        # plateau [q0, q_r): C0 q^k = C0 qr^k (q/qr)^k
        lo, hi = a, np.minimum(b, qr)
        m = hi > lo
        if np.any(m):
            out[m] += _power_law_integral(self.C0 * qr**k, qr, float(k), lo[m], hi[m])
        # power-law tail [q_r, q1]
        lo, hi = np.maximum(a, qr), b
        m = hi > lo
        if np.any(m):
            expo = k - 2.0 * (1.0 + self.hurst)
            out[m] += _power_law_integral(self.C0 * qr**k, qr, expo, lo[m], hi[m])
        return out

    def breakpoints(self) -> np.ndarray:
        return np.unique(np.array([self.q0, self.q_r, self.q1], dtype=np.float64))


# the measured spectra, imported after CapillaryWaves and SelfAffine so that the registry lists
# capillary, self-affine, topography, psd in that order (the CLI's --surface choices)
from .tabulated import TabulatedPSD  # noqa: E402


#: Young's modulus of the seed's PMMA. [Pa]
SEED_YOUNG_MODULUS = 2.9e9
#: Poisson ratio assumed for PMMA (the seed paper gives none). [-]
SEED_POISSON = 0.3
#: work of adhesion of the seed's adhesive curve (Fig. 2). [J/m^2]
SEED_WORK_OF_ADHESION = 0.06


def seed_e_star(poisson: float = SEED_POISSON) -> float:
    """Effective modulus E* = E / (1 - nu^2) of the seed's PMMA (E = 2.9 GPa). [Pa]

    Parameters
    ----------
    poisson : float
        Poisson ratio nu in [0, 0.5]; the seed paper gives none, 0.3 (default) is
        assumed. [-]

    Returns
    -------
    float
        E* = 2.9e9 / (1 - nu^2). [Pa]

    Raises
    ------
    ValueError
        If ``poisson`` is not in [0, 0.5].

    See Also
    --------
    persson_fast.seed_scene : The seed paper's surface.
    persson_fast.SEED_YOUNG_MODULUS : E of the seed paper's PMMA.
    persson_fast.SEED_POISSON : Its Poisson ratio.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> print(f"{pf.seed_e_star():.4g} Pa")
    3.187e+09 Pa
    >>> print(f"{pf.seed_e_star(0.5):.4g} Pa")
    3.867e+09 Pa
    """
    check_not_bool(poisson, "poisson", "-")
    nu = float(poisson)
    if not (math.isfinite(nu) and 0.0 <= nu <= 0.5):
        raise ValueError(f"poisson must lie in [0, 0.5] [-]; got poisson = {poisson!r}")
    return SEED_YOUNG_MODULUS / (1.0 - nu * nu)


def seed_scene() -> CapillaryWaves:
    """The seed paper's PMMA surface: frozen capillary waves at T_g.

    Returns
    -------
    CapillaryWaves
        T = 370 K, γ = 0.04 J/m², q_c = 1.7e9 1/m, q0 = 2π/(0.1 mm), q1 = 7e9 1/m, no gravity;
        its h_rms is 0.455 nm (the paper quotes ≈ 0.5 nm, Eq. 2).

    See Also
    --------
    persson_fast.seed_e_star : The seed paper's effective modulus.
    persson_fast.CapillaryWaves : The surface model.
    persson_fast.pull_off : Its pull-off stress.

    Notes
    -----
    Persson, arXiv:cond-mat/0512604.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.seed_scene()
    >>> print(type(s).__name__, f"{s.q0:.4g} {s.q1:.4g}")
    CapillaryWaves 6.283e+04 7e+09
    """
    return CapillaryWaves(
        temperature=370.0, surface_tension=0.04, q_c=1.7e9, q0=2.0 * np.pi / 1e-4, q1=7e9
    )
