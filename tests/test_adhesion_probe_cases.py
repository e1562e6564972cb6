"""Adhesive scenes found by random probing (``python -m benchmarks.adhesion_probe``).

Weak adhesion: gamma_eff changes sign in the last cells before zeta1. There
sigma_a = c sqrt(gamma_eff) starts with an infinite slope and races into the distribution
just before the end; the fixed point amplifies the diffusion solves' errors (the onset moves
with them). Two scenes found by random probing that came back with status 0 and end-area
errors of 4.7 and 4.1 rtol, the error estimate 0.17-0.2x the error. Such rows now solve their
diffusions to rtol / CROSSING_INNER_DIV with a margin on the inner estimate
(:data:`persson_fast.adhesion.fixed_point.CROSSING_LATE`).

The fixed point's stop: at zero load on a sticky surface and in tension the map is nearly
singular in the direction the area is most sensitive to, and a small residual left the area
off (``STOP_SCENES``; :data:`persson_fast._kernels.adhesion.FIXED_POINT_STOP`).

Oracles: the same scene at 100x and 1000x tighter rtol, agreeing with each other far below
the tolerance tested (checked in each test).
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


def _scene(c):
    s = pf.SelfAffine(hurst=c["hurst"], q0=c["q0"], q1=c["q0"] * 10 ** c["decades"],
                      h_rms=c["h_rms"])
    return s, dict(e_star=c["e_star"], work_of_adhesion=c["work_of_adhesion"])


def _solve_and_oracle(c, factors=(1e-2, 1e-3), agree=0.02, oracle_status=True):
    """The scene's result at its rtol and the oracle: the solve at rtol times the last of
    ``factors``, checked against the one at the first (within ``agree`` rtol, and with
    status 0 unless ``oracle_status`` is False)."""
    s, kw = _scene(c)
    p = np.array([c["pressure"]])
    refs = [pf.solve_contact(s, p, rtol=c["rtol"] * f, **kw) for f in factors]
    assert not oracle_status or all(r.status[0] == 0 for r in refs)
    ref = refs[-1].area[0]
    assert abs(refs[0].area[0] - ref) <= agree * c["rtol"] * ref    # the oracle has converged
    return pf.solve_contact(s, p, rtol=c["rtol"], **kw), ref


@pytest.mark.parametrize("name", sorted(SCENES))
def test_onset_before_zeta1_within_rtol(name):
    c = SCENES[name]
    # the oracles of these late onsets are flagged RTOL_NOT_MET (their error estimates at
    # rtol/100 and rtol/1000 exceed those tolerances), but agree with each other to 0.01 rtol
    res, ref = _solve_and_oracle(c, agree=0.01, oracle_status=False)
    g = res.gamma_eff[0]
    cells = np.flatnonzero((g[:-1] > 0) != (g[1:] > 0))
    assert cells.size == 1 and cells[0] >= g.size - 3               # the onset just before zeta1
    err = abs(res.area[0] - ref)
    assert res.status[0] == 0, res.message
    assert err <= c["rtol"] * ref
    assert err <= res.error_estimate[0] <= 10 * err


#: scenes whose fixed point stopped on a small residual with the area still off (zero load on
#: a sticky surface, small tensions): 1.0-2.8 rtol off with status 0 and estimates
#: 0.26-0.66x the error before the stop also required 0.01 rtol and a settled area
#: (:data:`persson_fast._kernels.adhesion.FIXED_POINT_STOP`); now 0.04-0.24 rtol
STOP_SCENES = {
    "zero load, H 0.53": dict(
        hurst=0.5330449353904594, decades=3.9032137113069956, q0=67463.03793714973,
        h_rms=1.9640006802783903e-07, e_star=1628816.2806910549,
        work_of_adhesion=0.010929812965173874, rtol=4.580854432649984e-05, pressure=0.0),
    "zero load, H 0.69": dict(
        hurst=0.68707790499246, decades=3.7913059458548455, q0=204094.22633654936,
        h_rms=6.356356867953165e-09, e_star=166394008.6840512,
        work_of_adhesion=0.0015723698261139974, rtol=0.000130811293077087, pressure=0.0),
    "small tension, H 0.79": dict(
        hurst=0.7896916334645145, decades=1.6772981630079968, q0=12869.851628011455,
        h_rms=1.385133623374262e-07, e_star=24880225.6444868,
        work_of_adhesion=0.005195748907531678, rtol=4.9151271894067574e-05,
        pressure=-218.2159072009384),
    "tension, H 0.56": dict(
        hurst=0.5572021812003338, decades=3.4231316182156704, q0=160327.29244919273,
        h_rms=9.541910010634932e-09, e_star=309221691.3732101,
        work_of_adhesion=0.011796651584371015, rtol=3.96e-6, pressure=-81579.70296864415),
    "tension, H 0.90": dict(
        hurst=0.9027846438496626, decades=4.123442974760945, q0=39573.413562054,
        h_rms=6.28784325720153e-08, e_star=15732358.628873209,
        work_of_adhesion=0.0032497286892947145, rtol=7.493566412222187e-05,
        pressure=-3056.1809275408527),
}


@pytest.mark.parametrize("name", sorted(STOP_SCENES))
def test_fixed_point_stop_within_rtol(name):
    c = STOP_SCENES[name]
    res, ref = _solve_and_oracle(c)
    err = abs(res.area[0] - ref)
    assert res.status[0] == 0, res.message
    assert err <= c["rtol"] * ref
    assert 0.5 * err <= res.error_estimate[0] <= c["rtol"] * ref


def test_tension_results_agree_across_tolerances():
    # the solutions at rtol 4e-6 and 4e-7 differed by 5x the looser one's tolerance (the
    # tighter one's three-level extrapolation 1.1e-5 off with an estimate of 2e-7)
    c = STOP_SCENES["tension, H 0.56"]
    s, kw = _scene(c)
    p = np.array([c["pressure"]])
    loose = pf.solve_contact(s, p, rtol=3.96e-6, **kw)
    tight = pf.solve_contact(s, p, rtol=3.96e-7, **kw)
    assert loose.status[0] == 0 and tight.status[0] == 0
    assert abs(loose.area[0] - tight.area[0]) <= 3.96e-6 * tight.area[0]


#: scenes found by random probing (benchmarks/adhesion_probe.py) 1.0-1.5 rtol off with status
#: 0: the fixed point amplifying the errors of its diffusion solves alike on every zeta level,
#: so that the ladder could not see it (now measured at level 0 and charged:
#: ``_ZetaLadder._probe_inner``), and (the late onsets) the diffusion error on a wall that
#: recedes fast just before zeta1. Per scene: the parameters, the oracle's rtol factors and,
#: for a miss still known, the reason of its strict xfail
LATE_ONSET_REASON = (
    "known: weak adhesion at a large pressure, gamma_eff changing sign in the last cells "
    "before zeta1 (random probing, seeds 23 and 25): 1.39 and 1.45 rtol off with status 0, "
    "estimates 0.53x and 0.36x the error. The diffusion error on the wall receding fast "
    "after the onset is first order in the node spacing (the sub-grid flux through the wall "
    "face), 4.7x the diffusions' own estimate; the probe of the fixed point's amplification "
    "(level 0 solved 4x looser) underrates it, since a first-order error moves by "
    "4^(1/4) - 1 = 0.41 of itself there, not 3x. Tried: a third probe 4x tighter (at level "
    "0 or at the finest level) fixed both but put the estimates of two other late-onset "
    "scenes 30-55x over their errors (one flagged within rtol); the sub-grid term in the "
    "fixed point's inner estimates made them 16-30x over and adhesion 5-7x slower")
PROBE_MISS_SCENES = {
    "strong adhesion, compression": (dict(
        hurst=0.8017880918070945, decades=1.4646249671845748, q0=207392.2073337302,
        h_rms=1.5759564780661478e-07, e_star=108318607.20923069,
        work_of_adhesion=0.41865480617164014, rtol=0.0008736754705484193,
        pressure=188425.48943503003), (1e-2, 1e-3), None),
    "onset in the last cell at a large pressure": (dict(
        hurst=0.531161966809038, decades=1.698543846049879, q0=404993.66796160623,
        h_rms=2.3608289836876854e-07, e_star=3449903158.786992,
        work_of_adhesion=0.0013618066270709342, rtol=0.0001937245614110028,
        pressure=5558724.611461243), (1.0 / 30, 1e-2), LATE_ONSET_REASON),
    "late onset at a large pressure, A = 0.3": (dict(
        hurst=0.8697038427174335, decades=1.3467292268026538, q0=142674.75358994355,
        h_rms=2.521662456445143e-07, e_star=1747370750.4979184,
        work_of_adhesion=0.0014104534269785438, rtol=0.0006373554515046465,
        pressure=34641808.455012806), (1e-2, 1e-3), LATE_ONSET_REASON),
}


@pytest.mark.parametrize("name", [
    pytest.param(name, marks=() if reason is None
                 else pytest.mark.xfail(strict=True, reason=reason))
    for name, (_, _, reason) in sorted(PROBE_MISS_SCENES.items())])
def test_probe_miss_within_rtol(name):
    """Each scene was 1.4-1.5 rtol off with status 0 (estimates 0.36-0.53x the error). With
    the amplification measured and charged, the strong-adhesion scene is within rtol with
    status 0, its estimate at least half the error; the late onsets are still known misses."""
    c, factors, _ = PROBE_MISS_SCENES[name]
    res, ref = _solve_and_oracle(c, factors)
    err = abs(res.area[0] - ref)
    assert res.status[0] == 0, res.message
    assert err <= c["rtol"] * ref
    assert res.error_estimate[0] >= 0.5 * err


@pytest.mark.parametrize("theory, hardness", [
    pytest.param("persson01", False, marks=pytest.mark.slow),     # 12 s
    pytest.param("yp08", False, marks=pytest.mark.slow),          # 23 s
    ("persson01", True)])
def test_probe_tool_runs_each_fixed_point(theory, hardness, capsys):
    from benchmarks.adhesion_probe import probe
    checked, misses, flagged, worst = probe(1, 120.0, scenes=2, theory=theory,
                                            hardness=hardness)
    assert checked >= 2 and misses == 0 and worst <= 1.0
    assert "2 scenes: checked" in capsys.readouterr().out
