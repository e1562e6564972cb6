"""What follows from the contact without adhesion: separation, stiffness, gaps.

``elastic`` (the mean interfacial separation, the contact stiffness and the stored elastic
energy), ``contact_law`` (a tabulated p(u), K(u) for other codes), ``gaps`` (the distribution
of interfacial gaps).
"""
