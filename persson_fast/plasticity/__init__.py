"""The yield wall sigma_Y(zeta): elastoplastic contact.

``hardness`` (the hardness laws and their checks), ``yield_wall`` (``solve_diffusion(sigma_y=...)``
and ``solve_contact(hardness=...)`` without adhesion), ``strip`` (the two-wall solver's Python
side).
"""
