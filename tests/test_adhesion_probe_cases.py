"""Adhesive scenes found by random probing (``python -m benchmarks.adhesion_probe``).

Weak adhesion: gamma_eff changes sign in the last cells before zeta1.

There sigma_a = c sqrt(gamma_eff) starts with an infinite slope and races into the
distribution just before the end; the fixed point amplifies the diffusion solves' errors
(the onset moves with them). Two scenes found by random probing that came back with status 0
and end-area errors of 4.7 and 4.1 rtol, the error estimate 0.17-0.2x the error. Such rows now
solve their diffusions to rtol / CROSSING_INNER_DIV with a margin on the inner estimate
(:data:`persson_fast.adhesion.CROSSING_LATE`). Oracles: the same scene at 100x and 1000x
tighter rtol, agreeing with each other to 5e-8 and 4e-7 relative (far below the tolerance
tested).
"""
import numpy as np
import pytest

import persson_fast as pf

SCENES = {
    "onset in the last cell": dict(
        hurst=0.45044310542364746, decades=1.8399840200468982, q0=962437.1802274695,
        h_rms=8.971173966106342e-08, e_star=2965871853.443321,
        work_of_adhesion=0.001407509561907074, pressure=29332833.67918106, rtol=6.8e-5),
    "onset two cells before zeta1": dict(
        hurst=0.6126085204513996, decades=2.500354888253453, q0=534893.0053184172,
        h_rms=8.39912061035827e-08, e_star=4430726672.433928,
        work_of_adhesion=0.0012567777565314407, pressure=56210437.50886578, rtol=1.5e-4),
}


@pytest.mark.parametrize("name", sorted(SCENES))
def test_onset_before_zeta1_within_rtol(name):
    c = SCENES[name]
    s = pf.SelfAffine(hurst=c["hurst"], q0=c["q0"], q1=c["q0"] * 10 ** c["decades"],
                      h_rms=c["h_rms"])
    kw = dict(e_star=c["e_star"], work_of_adhesion=c["work_of_adhesion"])
    p = np.array([c["pressure"]])
    refs = [pf.solve_contact(s, p, rtol=c["rtol"] * f, **kw).area[0] for f in (1e-2, 1e-3)]
    assert abs(refs[0] - refs[1]) <= 0.01 * c["rtol"] * refs[1]      # the oracle has converged
    res = pf.solve_contact(s, p, rtol=c["rtol"], **kw)
    g = res.gamma_eff[0]
    cells = np.flatnonzero((g[:-1] > 0) != (g[1:] > 0))
    assert cells.size == 1 and cells[0] >= g.size - 3               # the onset just before zeta1
    err = abs(res.area[0] - refs[1])
    assert res.status[0] == 0, res.message
    assert err <= c["rtol"] * refs[1]
    assert err <= res.error_estimate[0] <= 10 * err


@pytest.mark.xfail(strict=True, reason=(
    "known: in tension with moderate adhesion, random probing (benchmarks/adhesion_probe.py) "
    "finds about 1 % of unflagged rows up to 1.4 rtol off; here the solutions at rtol "
    "4e-6 and 4e-7 differ by 5x the looser one's tolerance: the two solves use zeta grids "
    "of different bases (97 and 203 points), the ladders converge erratically (differences "
    "shrinking by 3.5, 6.9, 5.9 on the first), and the tighter one's three-level "
    "extrapolation overshoots by 1.1e-5 with an estimate of 2e-7"))
def test_tension_results_agree_across_tolerances():
    s = pf.SelfAffine(hurst=0.5572021812003338, q0=160327.29244919273,
                      q1=160327.29244919273 * 10 ** 3.4231316182156704,
                      h_rms=9.541910010634932e-09)
    kw = dict(e_star=309221691.3732101, work_of_adhesion=0.011796651584371015)
    p = np.array([-81579.70296864415])
    loose = pf.solve_contact(s, p, rtol=3.96e-6, **kw)
    tight = pf.solve_contact(s, p, rtol=3.96e-7, **kw)
    assert loose.status[0] == 0 and tight.status[0] == 0
    assert abs(loose.area[0] - tight.area[0]) <= 3.96e-6 * tight.area[0]
