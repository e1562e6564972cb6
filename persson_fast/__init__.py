"""persson_fast: Persson's contact-mechanics theory, fast and error-controlled.

The stress distribution P(sigma, zeta) obeys a diffusion equation in magnification with an
absorbing wall at -sigma_a(zeta); the real contact area is A(zeta1)/A0. The closed form is
returned where one exists; otherwise a compiled solver estimates its error and refines until
the estimate is below ``rtol``, or flags the result; the estimates are measured, not proven
(the documentation's validation page lists the few cases found outside ``rtol`` with status
0, at most 1.5 rtol). Units are SI throughout and the spectrum C(q) follows
Persson's isotropic convention (h_rms^2 = 2 pi int q C(q) dq): see "Units and conventions"
in the documentation's user guide (docs/user-guide/contact-area.md) and the API reference
(docs/api/index.rst).
"""
from .analytic.images import contact_area_no_adhesion, images_area, images_density, images_moments
from .analytic.linear import (linear_boundary_area, linear_boundary_density,
                              linear_boundary_detachment_rate, linear_boundary_load)
from .analytic.plastic import plastic_area
from .adhesion.zeta_grid import adhesion_zeta
from .adhesion.pulloff import pull_off
from ._version import __version__
from .api import default_zeta, solve_contact, solve_diffusion, warmup
from .methods import AUTO_POLICY, METHODS
from .results import ContactResult, DiffusionResult
from .surfaces.models import (
    BOLTZMANN,
    SEED_POISSON,
    SEED_WORK_OF_ADHESION,
    SEED_YOUNG_MODULUS,
    CapillaryWaves,
    SelfAffine,
    Surface,
    TabulatedPSD,
    seed_e_star,
    seed_scene,
)
from .plasticity.hardness import hardness_nix_gao, hardness_power_law, hardness_table
from .scan.api import ScanWarning, scan
from .scene import Scene
from .separation.elastic import (SeparationResult, decay_length, pressure_at_separation,
                         solve_separation)
from .separation.gaps import GapDistribution, gap_distribution


__all__ = [
    "AUTO_POLICY",
    "BOLTZMANN",
    "SEED_POISSON",
    "SEED_WORK_OF_ADHESION",
    "SEED_YOUNG_MODULUS",
    "CapillaryWaves",
    "ContactResult",
    "DiffusionResult",
    "METHODS",
    "ScanWarning",
    "SelfAffine",
    "Surface",
    "TabulatedPSD",
    "adhesion_zeta",
    "contact_area_no_adhesion",
    "default_zeta",
    "hardness_nix_gao",
    "hardness_power_law",
    "hardness_table",
    "images_area",
    "images_density",
    "images_moments",
    "linear_boundary_area",
    "linear_boundary_density",
    "linear_boundary_detachment_rate",
    "linear_boundary_load",
    "plastic_area",
    "pull_off",
    "scan",
    "seed_e_star",
    "seed_scene",
    "solve_contact",
    "solve_diffusion",
    "warmup",
    "Scene",
    "SeparationResult",
    "decay_length",
    "pressure_at_separation",
    "solve_separation",
    "GapDistribution",
    "gap_distribution",
    "__version__",
]

from . import _compat

_compat.install()      # old module paths of pickles from 0.1.x
del _compat
