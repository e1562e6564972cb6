"""Surfaces: the roughness power spectra C(q) in Persson's isotropic convention.

``base`` (the :class:`~persson_fast.surfaces.base.Surface` base class, constants and shared
checks), ``models`` (:class:`CapillaryWaves`, :class:`SelfAffine`, the seed scene),
``registry`` (declared model parameters, as the command line and scans see them),
``tabulated`` (:class:`TabulatedPSD`, measured spectra), ``topography`` (height maps and line
scans to C(q)), ``files`` (SurfaceTopography maps and spectrum files), ``synthetic`` (random
heights with a given spectrum). The public names are ``persson_fast.*``.
"""
