"""Integer status codes returned by the kernels, one per pressure, and their meaning."""

OK = 0
NONFINITE = 1          # a non-finite value appeared; the result is not usable
FAR_LEAK = 2           # mass reached the far end of the grid (domain too small)
START_UNRESOLVED = 3   # the exact start profile is narrower than the grid can resolve
GRID_CAP = 4           # the resolution needed (drift/Peclet or tolerance) exceeded the node cap
BAD_INPUT = 5          # inconsistent arrays reached the kernel (a bug in the calling layer)
NOT_CONVERGED = 6      # a fixed point (adhesion) did not reach its tolerance
NEGATIVE_DENSITY = 7   # the stress distribution became markedly negative (ringing)
WALL_JUMP = 8          # the wall jumped (flat G): accuracy after a jump is below the scheme's order
LOST_CONTACT = 9       # adhesion, tension: separated, although pull_off finds contact there
# argument checks of the compiled entry points in persson_fast.embed (area NaN, nothing solved)
BAD_PRESSURE = 10      # the pressure (sigma0) is not finite
BAD_RTOL = 11          # rtol is not finite or outside [1e-12, 0.1]
BAD_G = 12             # G is empty, not finite, negative at G[0] or decreasing
BAD_SIGMA_A = 13       # sigma_a is not finite or not of the length of G
BAD_SCENE = 14         # the adhesive scene tuple is not one adhesive_scene builds
RTOL_NOT_MET = 15      # the error estimate of the result exceeds rtol after refining to the work cap
WALL_THINNED = 16      # bnr: more G points than its node cap allows; solved on a subset of them
BELOW_RESOLVED = 17    # separation: pressure below the resolved range of the quadrature near q0
BAD_SEPARATION = 18    # contact law: the separation is not finite or not > 0
LAW_EXTRAPOLATED = 19  # contact law: separation below the table (pressure above it), continued
BAD_SIGMA_Y = 20       # embed.elastoplastic_area: sigma_y not finite, not of G's length, jumping
                       # or not above -sigma_a
BAD_LAW = 21           # contact law: the table is not one contact_law can have built
SEPARATION_UNDERFLOW = 22  # separation: u (or Q = p/K) near or below the smallest normal double

STATUS_MESSAGES = {
    OK: "ok",
    NONFINITE: "non-finite value in the stress distribution",
    FAR_LEAK: "stress distribution reached the far end of the grid",
    START_UNRESOLVED: "exact start profile narrower than the grid resolves; accuracy not guaranteed",
    GRID_CAP: "required resolution exceeds the node cap; accuracy not guaranteed",
    BAD_INPUT: "inconsistent kernel input",
    NOT_CONVERGED: "adhesion fixed point did not converge",
    NEGATIVE_DENSITY: ("stress distribution became markedly negative, with a negative mass "
                       "above the area's tolerance (ringing)"),
    WALL_JUMP: ("the wall jumped over a flat stretch of G: the error after a jump converges at "
                "first to second order, not fourth; rtol is not guaranteed (compare a smaller rtol)"),
    LOST_CONTACT: ("separated, although pull_off finds contact down to this tension (or cannot "
                   "exclude it within its error estimate): the fixed point on this zeta grid "
                   "lost the end of the contact branch (use a smaller rtol, or pull_off for the "
                   "pull-off stress)"),
    BAD_PRESSURE: ("pressure (sigma0) must be finite [Pa; in diffusion_area and diffusion_solve "
                   "the stress unit of sqrt(G)]; nothing solved"),
    BAD_RTOL: "rtol must be finite and lie in [1e-12, 0.1] [-]; nothing solved",
    BAD_G: ("G must hold at least one finite diffusion time, G[0] >= 0, non-decreasing "
            "[stress^2]; nothing solved"),
    BAD_SIGMA_A: "sigma_a must be finite and have the length of G [stress]; nothing solved",
    BAD_SCENE: ("scene must be the tuple embed.adhesive_scene returns: G of at least 2 finite "
                "non-decreasing times from G[0] >= 0, c of G's length and wa, wb one shorter, "
                "all finite and >= 0, energy correction finite and <= 1, stress scale finite "
                "and > 0 (build it again with adhesive_scene); nothing solved"),
    RTOL_NOT_MET: ("the error estimate exceeds rtol after refining up to the work cap: the "
                   "result is less accurate than asked (error_estimate says by how much; a "
                   "kinked or fast wall converges slowly)"),
    BAD_SEPARATION: "separation must be finite and > 0 [m]; p and K are NaN",
    BAD_SIGMA_Y: ("sigma_y must be finite, have the length of G, keep -sigma_a < sigma_y at every "
                  "G and not jump (a repeated G with different values) [stress]; nothing "
                  "solved"),
    BAD_LAW: ("the contact law's table must be the five arrays of ContactLaw.table (ln u, ln p, "
              "d ln p/d ln u, ln K, d ln K/d ln u), all of one length >= 2 and finite, ln u "
              "strictly increasing and ln p strictly decreasing within [-746, 710] (logarithms "
              "of doubles), d ln p/d ln u < 0, ln K = ln p - ln u + ln(-d ln p/d ln u) (K = "
              "-dp/du) and every interval monotone (Fritsch-Carlson: "
              "(s_i^2 + s_(i+1)^2) <= 9 secant^2); p, K and u are NaN (build it with "
              "contact_law, or read its to_csv columns back unchanged)"),
    SEPARATION_UNDERFLOW: ("the separation underflows double precision at this pressure (u or "
                           "Q = p/K below 1e-292 m, where terms of their sums fall below the "
                           "smallest normal double): the surfaces are in full contact to "
                           "rounding; u may be 0 or have lost digits and K may be inf (u ~ "
                           "exp(-p^2/(4 G1)): a pressure far above sqrt(G1)); "
                           "pressure_at_separation cannot invert u = 0"),
    LAW_EXTRAPOLATED: ("separation below the contact law's table (a pressure above its range): p "
                       "and K are a continuation with the last slope, not a result (build the "
                       "law with a larger pressure_max)"),
    BELOW_RESOLVED: ("pressure below the resolved range of the separation quadrature (its nodes "
                     "near q0 end before the stress distribution leaves them); u and K are not "
                     "guaranteed there"),
    WALL_THINNED: ("more G points than the node cap of the bnr solver allows: the result is that "
                   "of a wall through a subset of them (every m-th sample of a smooth stretch, "
                   "kinks kept, the other points interpolated); error_estimate includes the "
                   "estimated thinning error (use fewer G points, or another method)"),
}
