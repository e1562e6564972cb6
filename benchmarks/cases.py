"""The one table of benchmark cases.

Every benchmark (``bench_core.py``) and any speed/accuracy report reads its scenes from
:data:`CASES`, so the numbers quoted anywhere refer to the same inputs. A case builds its inputs
in :meth:`Case.setup`, which is never called inside a timed callable.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

import persson_fast as pf

__all__ = ["Case", "CaseInputs", "CASES", "CASE_BY_NAME", "get_case", "sqrt_g1"]

def sqrt_g1(surface, e_star: float) -> float:
    """sqrt(G1) = E* slope_rms / (2 sqrt 2), the stress scale of a full band. [Pa]"""
    return e_star * surface.slope_rms() / (2.0 * math.sqrt(2.0))


def _self_affine_5dec():
    """Self-affine, H = 0.8, five decades 1e4 ... 1e9 1/m, h_rms = 1 um."""
    return pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)


def _log_pressures(n: int, lo: float = 1e-3, hi: float = 3.0):
    """n pressures log-spaced so that p / sqrt(G1) spans lo ... hi."""
    def make(surface, e_star):
        return np.geomspace(lo, hi, n) * sqrt_g1(surface, e_star)
    return make


def _linear_pressures(n: int, p_max: float):
    def make(surface, e_star):
        return np.linspace(0.0, p_max, n)
    return make


@dataclass(frozen=True)
class CaseInputs:
    """What a case hands to the code under test (all arrays are fresh copies)."""

    surface: pf.Surface
    pressure: np.ndarray  # (n_p,) nominal pressures [Pa]
    e_star: float         # effective modulus [Pa]
    zeta: np.ndarray      # (n_z,) default magnification grid [-]
    G: np.ndarray         # (n_z,) diffusion time on zeta, G[0] = 0 [Pa^2]
    sigma_a: np.ndarray   # (n_p, n_z) zeros: the wall of the non-adhesive problem [Pa]

    @property
    def n_p(self) -> int:
        return int(self.pressure.size)

    @property
    def n_z(self) -> int:
        return int(self.zeta.size)


@dataclass(frozen=True)
class Case:
    """One benchmark scene: a surface, an effective modulus and a set of pressures."""

    name: str
    description: str
    make_surface: Callable[[], pf.Surface]
    e_star: float
    make_pressures: Callable[[pf.Surface, float], np.ndarray]

    def setup(self) -> CaseInputs:
        """Build the inputs (surface, pressures, zeta grid, G, zero wall) outside any timing."""
        surface = self.make_surface()
        pressure = np.ascontiguousarray(self.make_pressures(surface, self.e_star), dtype=float)
        zeta = pf.default_zeta(surface)
        G = np.asarray(surface.diffusion_time(zeta * surface.q0, self.e_star), dtype=float)
        G[0] = 0.0  # as solve_contact does
        sigma_a = np.zeros((pressure.size, zeta.size))
        return CaseInputs(surface=surface, pressure=pressure, e_star=float(self.e_star),
                          zeta=zeta, G=G, sigma_a=sigma_a)


CASES: list[Case] = [
    Case(
        name="selfaffine-5dec",
        description="SelfAffine(H=0.8, q0=1e4, q1=1e9, h_rms=1 um), E*=1 GPa, "
                    "64 pressures, p/sqrt(G1) log-spaced 1e-3..3",
        make_surface=_self_affine_5dec,
        e_star=1e9,
        make_pressures=_log_pressures(64),
    ),
    Case(
        name="seed-noadh",
        description="seed PMMA scene (capillary waves), E*=2.9 GPa/(1-0.3^2), "
                    "128 pressures 0..100 MPa, no adhesion",
        make_surface=pf.seed_scene,
        e_star=pf.seed_e_star(),
        make_pressures=_linear_pressures(128, 100e6),
    ),
    Case(
        name="sweep-1000",
        description="the selfaffine-5dec scene with 1000 pressures, p/sqrt(G1) log-spaced 1e-3..3",
        make_surface=_self_affine_5dec,
        e_star=1e9,
        make_pressures=_log_pressures(1000),
    ),
]

CASE_BY_NAME: dict[str, Case] = {case.name: case for case in CASES}


def get_case(name: str) -> Case:
    """The case called ``name`` (KeyError listing the names otherwise)."""
    try:
        return CASE_BY_NAME[name]
    except KeyError:
        raise KeyError(f"no benchmark case {name!r}; cases: {', '.join(CASE_BY_NAME)}") from None
