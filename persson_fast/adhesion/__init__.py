"""Adhesion: the detachment stress sigma_a(zeta), self-consistent with seed Eqs. 8-9.

``zeta_grid`` (the magnification grids and the kernels' scaled inputs), ``runner`` (the
compiled fixed point called on one grid: rows, controls, compile), ``ladder`` (the error
control on nested grids), ``fixed_point`` (the entry point ``solve_adhesive_contact``),
``pulloff`` and ``branch`` (the contact branch followed to the pull-off stress). A new
adhesive solver enters here, as a route of :mod:`persson_fast.plan`.
"""
