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

STATUS_MESSAGES = {
    OK: "ok",
    NONFINITE: "non-finite value in the stress distribution",
    FAR_LEAK: "stress distribution reached the far end of the grid",
    START_UNRESOLVED: "exact start profile narrower than the grid resolves; accuracy not guaranteed",
    GRID_CAP: "required resolution exceeds the node cap; accuracy not guaranteed",
    BAD_INPUT: "inconsistent kernel input",
    NOT_CONVERGED: "adhesion fixed point did not converge",
    NEGATIVE_DENSITY: "stress distribution became negative beyond rounding",
    WALL_JUMP: ("the wall jumped over a flat stretch of G: the error after a jump converges at "
                "first to second order, not fourth; rtol is not guaranteed (compare a smaller rtol)"),
    LOST_CONTACT: ("separated, although pull_off finds contact down to this tension (or cannot "
                   "exclude it within its error estimate): the fixed point on this zeta grid "
                   "lost the end of the contact branch (use a smaller rtol, or pull_off for the "
                   "pull-off stress)"),
}
