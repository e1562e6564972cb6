"""Closed-form solutions of the stress diffusion.

Persson's stress distribution obeys the heat equation ``dP/dG = d2P/dsigma2`` in the
"diffusion time" ``G`` [Pa^2] (free variance ``2 G``), starting from ``P = delta(sigma - sigma0)``
at ``G = 0`` and absorbed at the wall ``sigma = -sigma_a(G)``.  Three boundaries have closed forms:

* ``sigma_a = 0`` (no adhesion): the method of images -- :func:`images_area`,
  :func:`images_density`, :func:`images_moments`, :func:`contact_area_no_adhesion`;
* ``sigma_a(G) = a + b G`` (a wall moving linearly in ``G``): Brownian motion with drift absorbed
  at a fixed point (Girsanov + images) -- :func:`linear_boundary_area`,
  :func:`linear_boundary_density`, :func:`linear_boundary_detachment_rate`,
  :func:`linear_boundary_load`;
* ``sigma_a = 0`` plus a second absorbing wall at a constant yield stress (Persson 2001) --
  :func:`plastic_area`.

They are the exact oracles for the numerical solvers, so they are written for full relative
accuracy (about 1e-13) also where the textbook form cancels catastrophically or overflows: tiny
areas (``sigma0 << sqrt(G)``), both normal cdfs close to 1, ``exp(-b y0)`` beyond the float range.
All functions are vectorised with numpy broadcasting; all arguments are SI; results are float64
(a numpy scalar for scalar input).  ``G = 0`` returns the ``G -> 0+`` limit.

The closed forms live in :mod:`persson_fast.analytic.images` (no adhesion),
:mod:`persson_fast.analytic.linear` (the linearly moving wall) and
:mod:`persson_fast.analytic.plastic` (the plastic strip), on the shared numerics of
:mod:`persson_fast.analytic.base`. The public
names are ``persson_fast.<name>``.
"""
