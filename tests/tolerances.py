"""Every tolerance the tests use, with its reason."""

#: requested accuracy of the solver in the accuracy tests (the package default)
RTOL = 1e-6
#: absolute floor of the area check |A - A_exact| <= RTOL*A_exact + ATOL (issue contract)
ATOL = 1e-12
#: A + detached = 1 and the load identity are exact in the scheme: rounding only
IDENTITY = 1e-12
#: ... accumulated over a solve: at most a few units of rounding (eps = 2.2e-16) per step taken
#: by all the runs of the ladder (counts[:, 1]); the larger of the two bounds applies
IDENTITY_PER_STEP = 8 * 2.2e-16
#: load conservation without adhesion, relative to sigma0 (contract: 1e-8; the scheme gives rounding)
LOAD_CONSERVATION = 1e-8
#: compiled building blocks vs their NumPy twins: rounding of O(n) operations
TWIN = 1e-12
#: areas may overshoot [0, 1] by rounding of the extrapolation
BOUNDS = 1e-12
