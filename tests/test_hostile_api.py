"""Hostile input to the Python API (issue 42, items 6-8): bools where numbers are meant,
empty and extreme arguments, contradictory options, and the gap distribution's adhesion
keyword. Each test is one reproducer (or a family): a ValueError that names the argument,
or a clean result.
"""
import re

import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed
from tolerances import IDENTITY

AFFINE = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e7, h_rms=1e-8)
E_STAR = 1e9
G = np.array([0.0, 1.0, 2.0, 4.0]) * 1e10
HEIGHTS = np.random.default_rng(42).standard_normal((16, 16)) * 1e-9
LINE = (np.array([1e4, 1e5, 1e6]), np.array([1e-30, 1e-33, 1e-36]))


def _refuses_bool(call, name):
    """``call()`` raises a ValueError that names ``name`` and says it got a bool."""
    n = re.escape(name)
    with pytest.raises(ValueError, match=rf"(?s)^{n}(?!\w).*not a bool.*got {n}(?!\w)") as info:
        call()
    return str(info.value)


# every public numeric argument, given a bool: (label, call, the argument's name)
BOOL_CASES = [
    # solve_contact and pull_off: the reproducers first
    ("solve_contact hardness", lambda: pf.solve_contact(AFFINE, [1e5], e_star=E_STAR,
                                                        hardness=True), "hardness"),
    ("pull_off hardness", lambda: pf.pull_off(AFFINE, e_star=E_STAR, work_of_adhesion=0.05,
                                              hardness=True), "hardness"),
    ("solve_contact pressure", lambda: pf.solve_contact(AFFINE, True, e_star=E_STAR),
     "pressure"),
    ("solve_contact pressure list", lambda: pf.solve_contact(AFFINE, [1e5, True],
                                                             e_star=E_STAR), "pressure"),
    ("solve_contact pressure array", lambda: pf.solve_contact(
        AFFINE, np.array([True, False]), e_star=E_STAR), "pressure"),
    ("solve_contact e_star", lambda: pf.solve_contact(AFFINE, [1e5], e_star=True), "e_star"),
    ("solve_contact work_of_adhesion", lambda: pf.solve_contact(
        AFFINE, [1e5], e_star=E_STAR, work_of_adhesion=True), "work_of_adhesion"),
    ("solve_contact work_of_adhesion False", lambda: pf.solve_contact(
        AFFINE, [1e5], e_star=E_STAR, work_of_adhesion=np.False_), "work_of_adhesion"),
    ("solve_contact energy_correction", lambda: pf.solve_contact(
        AFFINE, [1e5], e_star=E_STAR, energy_correction=True), "energy_correction"),
    ("solve_contact detachment_prefactor", lambda: pf.solve_contact(
        AFFINE, [1e5], e_star=E_STAR, work_of_adhesion=0.05, detachment_prefactor=True),
     "detachment_prefactor"),
    ("solve_contact rtol", lambda: pf.solve_contact(AFFINE, [1e5], e_star=E_STAR, rtol=True),
     "rtol"),
    ("solve_contact zeta", lambda: pf.solve_contact(AFFINE, [1e5], e_star=E_STAR,
                                                    zeta=[True, 1000.0]), "zeta"),
    ("solve_contact theory_gamma", lambda: pf.solve_contact(
        AFFINE, [1e5], e_star=E_STAR, theory="xu24", theory_gamma=True), "theory_gamma"),
    ("solve_contact hardness table", lambda: pf.solve_contact(
        AFFINE, [1e5], e_star=E_STAR, hardness=([1.0, 1000.0], [True, True])), "sigma_y"),
    ("pull_off e_star", lambda: pf.pull_off(AFFINE, e_star=True, work_of_adhesion=0.05),
     "e_star"),
    ("pull_off work_of_adhesion", lambda: pf.pull_off(AFFINE, e_star=E_STAR,
                                                      work_of_adhesion=True),
     "work_of_adhesion"),
    ("pull_off rtol", lambda: pf.pull_off(AFFINE, e_star=E_STAR, work_of_adhesion=0.05,
                                          rtol=True), "rtol"),
    ("Scene hardness", lambda: pf.Scene(AFFINE, E_STAR, hardness=True), "hardness"),
    ("Scene e_star", lambda: pf.Scene(AFFINE, np.True_), "e_star"),
    # solve_diffusion and the closed forms
    ("solve_diffusion G", lambda: pf.solve_diffusion(G > 0, [1e5]), "G"),
    ("solve_diffusion pressure", lambda: pf.solve_diffusion(G, True), "pressure"),
    ("solve_diffusion sigma_a", lambda: pf.solve_diffusion(G, [1e5], True), "sigma_a"),
    ("solve_diffusion sigma_y", lambda: pf.solve_diffusion(G, [1e5], sigma_y=True),
     "sigma_y"),
    ("solve_diffusion rtol", lambda: pf.solve_diffusion(G, [1e5], rtol=True), "rtol"),
    ("contact_area_no_adhesion e_star", lambda: pf.contact_area_no_adhesion(
        AFFINE, [1e5], True), "e_star"),
    ("images_area pressure", lambda: pf.images_area(True, 1e10), "pressure"),
    ("images_area G", lambda: pf.images_area(1e5, True), "G"),
    ("images_density sigma", lambda: pf.images_density(True, 1e5, 1e10), "sigma"),
    ("linear_boundary_area a", lambda: pf.linear_boundary_area(1e5, 1e10, True, 1e-6), "a"),
    ("linear_boundary_area b", lambda: pf.linear_boundary_area(1e5, 1e10, 1e3, True), "b"),
    ("plastic_area yield_stress", lambda: pf.plastic_area(1e5, 1e10, True), "yield_stress"),
    # hardness helpers
    ("hardness_power_law sigma_y0", lambda: pf.hardness_power_law(True, 0.5), "sigma_y0"),
    ("hardness_power_law exponent", lambda: pf.hardness_power_law(1e9, True), "exponent"),
    ("hardness_nix_gao h0", lambda: pf.hardness_nix_gao(True, 1e-6, 1e4), "h0"),
    ("hardness_nix_gao length", lambda: pf.hardness_nix_gao(1e9, True, 1e4), "length"),
    ("hardness_nix_gao q0", lambda: pf.hardness_nix_gao(1e9, 1e-6, True), "q0"),
    ("hardness_table zeta", lambda: pf.hardness_table([1.0, True], [1e9, 1e9]), "zeta"),
    ("hardness_table sigma_y", lambda: pf.hardness_table([1.0, 2.0], [1e9, True]),
     "sigma_y"),
    # surfaces
    ("SelfAffine hurst", lambda: pf.SelfAffine(hurst=True, q0=1e4, q1=1e7, h_rms=1e-8),
     "hurst"),
    ("SelfAffine q0", lambda: pf.SelfAffine(hurst=0.8, q0=True, q1=1e7, h_rms=1e-8), "q0"),
    ("SelfAffine h_rms", lambda: pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e7, h_rms=True),
     "h_rms"),
    ("CapillaryWaves temperature", lambda: pf.CapillaryWaves(True, 0.04, 1e9, 1e4, 1e9),
     "temperature"),
    ("CapillaryWaves density", lambda: pf.CapillaryWaves(370.0, 0.04, 1e9, 1e4, 1e9,
                                                         density=True), "density"),
    ("TabulatedPSD C", lambda: pf.TabulatedPSD(LINE[0], LINE[1] > 0), "C"),
    ("from_heights heights", lambda: pf.TabulatedPSD.from_heights(HEIGHTS > 0, 1e-6),
     "heights"),
    ("from_heights heights list", lambda: pf.TabulatedPSD.from_heights(
        [[True] * 8] * 8, 1e-6), "heights"),
    ("from_heights pixel_size", lambda: pf.TabulatedPSD.from_heights(HEIGHTS, True),
     "pixel_size"),
    ("from_heights pixel_size pair", lambda: pf.TabulatedPSD.from_heights(
        HEIGHTS, (1e-6, True)), "pixel_size"),
    ("from_heights q0", lambda: pf.TabulatedPSD.from_heights(HEIGHTS, 1e-6, q0=True), "q0"),
    ("from_heights hurst", lambda: pf.TabulatedPSD.from_heights(HEIGHTS[0], 1e-6,
                                                                hurst=True), "hurst"),
    ("from_line_scan C1d", lambda: pf.TabulatedPSD.from_line_scan(LINE[0], LINE[1] > 0, 0.8),
     "C1d"),
    ("from_line_scan hurst", lambda: pf.TabulatedPSD.from_line_scan(*LINE, True), "hurst"),
    ("diffusion_time e_star", lambda: AFFINE.diffusion_time(1e5, True), "e_star"),
    ("psd q", lambda: AFFINE.psd(True), "q"),
    ("moment q_hi", lambda: AFFINE.moment(2, 1e4, True), "q_hi"),
    ("seed_e_star poisson", lambda: pf.seed_e_star(True), "poisson"),
    ("default_zeta per_decade", lambda: pf.default_zeta(AFFINE, True), "per_decade"),
    ("adhesion_zeta rtol", lambda: pf.adhesion_zeta(AFFINE, True), "rtol"),
    ("adhesion_zeta per_decade", lambda: pf.adhesion_zeta(AFFINE, per_decade=True),
     "per_decade"),
    ("adhesion_zeta near_one_min", lambda: pf.adhesion_zeta(AFFINE, near_one_min=True),
     "near_one_min"),
    # separation, gaps, embed
    ("solve_separation pressure", lambda: pf.solve_separation(AFFINE, True, e_star=E_STAR),
     "pressure"),
    ("solve_separation energy_correction", lambda: pf.solve_separation(
        AFFINE, 1e5, e_star=E_STAR, energy_correction=True), "energy_correction"),
    ("pressure_at_separation separation", lambda: pf.pressure_at_separation(
        AFFINE, True, e_star=E_STAR), "separation"),
    ("pressure_at_separation rtol", lambda: pf.pressure_at_separation(
        AFFINE, 1e-8, e_star=E_STAR, rtol=True), "rtol"),
    ("decay_length e_star", lambda: pf.decay_length(AFFINE, e_star=True), "e_star"),
    ("gap_distribution pressure", lambda: pf.gap_distribution(AFFINE, True, e_star=E_STAR),
     "pressure"),
    ("gap_distribution gaps", lambda: pf.gap_distribution(AFFINE, 1e5, e_star=E_STAR,
                                                          gaps=[False, True]), "gaps"),
    ("gap_distribution rtol", lambda: pf.gap_distribution(AFFINE, 1e5, e_star=E_STAR,
                                                          rtol=True), "rtol"),
    ("gap_distribution work_of_adhesion", lambda: pf.gap_distribution(
        AFFINE, 1e5, e_star=E_STAR, work_of_adhesion=True), "work_of_adhesion"),
    ("contact_law pressure_max", lambda: embed.contact_law(AFFINE, e_star=E_STAR,
                                                           pressure_max=True),
     "pressure_max"),
    ("contact_law rtol", lambda: embed.contact_law(AFFINE, e_star=E_STAR, rtol=True), "rtol"),
    ("adhesive_scene work_of_adhesion", lambda: embed.adhesive_scene(
        AFFINE, e_star=E_STAR, work_of_adhesion=True), "work_of_adhesion"),
    ("adhesive_scene rtol", lambda: embed.adhesive_scene(
        AFFINE, e_star=E_STAR, work_of_adhesion=0.05, rtol=True), "rtol"),
]


@pytest.mark.parametrize("call, name", [c[1:] for c in BOOL_CASES],
                         ids=[c[0] for c in BOOL_CASES])
def test_bool_refused_naming_the_argument(call, name):
    _refuses_bool(call, name)


MORE_BOOL_CASES = [
    ("to_csv points_per_decade", lambda: AFFINE.to_csv("unused.csv", points_per_decade=True),
     "points_per_decade"),
    ("solve_diffusion kinks (callable wall)", lambda: pf.solve_diffusion(
        G, [1e5], sigma_a=lambda g: 0.0 * g, kinks=[True]), "kinks"),
    ("scan params solve value", lambda: pf.scan(AFFINE, {"hardness": [3e7, True]}, [1e5],
                                                e_star=E_STAR), "params['hardness'][1]"),
    ("scan pressure", lambda: pf.scan(AFFINE, {}, [True], e_star=E_STAR), "pressure"),
    ("scan hardness", lambda: pf.scan(AFFINE, {}, [1e5], e_star=E_STAR, hardness=True),
     "hardness"),
    ("scan gaps_rtol", lambda: pf.scan(AFFINE, {}, [1e5], e_star=E_STAR, gaps=True,
                                       gaps_rtol=True), "gaps_rtol"),
    ("GapDistribution.cumulative gaps", lambda: pf.gap_distribution(
        AFFINE, 1e5, e_star=E_STAR).cumulative(np.array([True])), "gaps"),
]


@pytest.mark.parametrize("call, name", [c[1:] for c in MORE_BOOL_CASES],
                         ids=[c[0] for c in MORE_BOOL_CASES])
def test_bool_refused_more(call, name):
    _refuses_bool(call, name)


def test_scan_surface_parameter_bool_among_numbers_refused():
    """[0.8, True] is not [0.8, 1.0]: the bool reaches the model, which refuses it."""
    with pytest.raises(ValueError, match=r"^SelfAffine\(\.\.\.\) failed for the scene "
                                         r"\(hurst=True\): hurst must be a real number or array "
                                         r"of them \[-\], not a bool"):
        pf.scan(pf.SelfAffine, {"hurst": [0.8, True], "q0": 1e4, "q1": 1e7, "h_rms": 1e-8},
                [1e5], e_star=E_STAR)


def test_counts_refuse_bool():
    """Counts and choices that are integers refuse a bool too (True == 1 in Python)."""
    with pytest.raises(ValueError, match=r"^k must be one of 0, 1, 2, 3; got True"):
        AFFINE.moment(True)
    with pytest.raises(ValueError, match=r"^n_damp must be an integer >= 0 \[-\]; got "
                                         r"n_damp = True"):
        pf.solve_diffusion(G, [1e5], n_damp=True)


@pytest.mark.parametrize("wall", ["sigma_a", "sigma_y"])
def test_callable_wall_returning_bools_refused(wall):
    """A callable wall that returns bools would be a 1 Pa wall: refused, naming it."""
    kwargs = {wall: lambda g: g >= 0.0}
    with pytest.raises(ValueError, match=rf"^{wall}\(G\) must return real numbers \[Pa\], not "
                                         rf"bools.*got {wall}\(G\) \(an array of dtype bool"):
        pf.solve_diffusion(G, [1e5], **kwargs)


def test_hardness_callable_returning_bools_refused():
    with pytest.raises(ValueError, match=r"^hardness\(zeta\) must return real numbers \[Pa\], "
                                         r"not bools.*dtype bool"):
        pf.solve_contact(AFFINE, [1e5], e_star=E_STAR, hardness=lambda z: z > 0)


def test_bool_array_refused_names_shape_and_dtype():
    msg = _refuses_bool(lambda: pf.TabulatedPSD.from_heights(HEIGHTS > 0, 1e-6), "heights")
    assert "(an array of dtype bool, shape (16, 16))" in msg
    assert "[m]" in msg


def test_bool_in_list_names_the_element():
    msg = _refuses_bool(lambda: pf.solve_contact(AFFINE, [1e5, 2e5, np.True_],
                                                 e_star=E_STAR), "pressure")
    assert msg.endswith("got pressure[2] = np.True_") or msg.endswith("got pressure[2] = True")
    assert "[Pa]" in msg


def test_numbers_still_accepted_where_bools_are_refused():
    """The refusal looks at bools only: ints, floats, float arrays and NumPy numbers pass."""
    r = pf.solve_contact(AFFINE, [np.float32(1e5), 2e5, np.int64(300000)], e_star=int(E_STAR),
                         hardness=np.float64(3e7))
    assert r.success and r.pressure.tolist() == [1e5, 2e5, 3e5]
    pf.TabulatedPSD.from_heights(HEIGHTS.astype(np.float32), 1e-6)
    assert pf.seed_e_star(0) == pf.SEED_YOUNG_MODULUS


# ---------------------------------------------------------------------------------------------
# gap_distribution(work_of_adhesion=...) (item 8)
# ---------------------------------------------------------------------------------------------
GAPS_WHY = (r"^gap_distribution: work_of_adhesion must be 0 \[J/m\^2\]: the gap distribution is "
            r"defined here for scenes without adhesion only; got work_of_adhesion = 0\.03\. ")


def test_gap_distribution_refuses_positive_work_of_adhesion_saying_why():
    with pytest.raises(ValueError, match=GAPS_WHY + r".*derived without adhesion"):
        pf.gap_distribution(AFFINE, 1e5, e_star=E_STAR, work_of_adhesion=0.03)


def test_gap_distribution_refuses_adhesive_scene_with_the_same_words():
    with pytest.raises(ValueError, match=GAPS_WHY):
        pf.gap_distribution(pf.Scene(AFFINE, E_STAR, work_of_adhesion=0.03), 1e5)
    # a Scene and the keyword: the adhesion is the reason, not the clash of two records
    with pytest.raises(ValueError, match=GAPS_WHY):
        pf.gap_distribution(pf.Scene(AFFINE, E_STAR), 1e5, work_of_adhesion=0.03)


@pytest.mark.parametrize("bad, rule", [(-0.03, r"must be >= 0 \[J/m\^2\]; got "
                                                r"work_of_adhesion = -0\.03"),
                                       (np.nan, r"must be finite \[J/m\^2\]"),
                                       ("abc", r"must be a real number")])
def test_gap_distribution_work_of_adhesion_bad_values(bad, rule):
    with pytest.raises(ValueError, match=r"^work_of_adhesion " + rule):
        pf.gap_distribution(AFFINE, 1e5, e_star=E_STAR, work_of_adhesion=bad)


def test_gap_distribution_accepts_zero_work_of_adhesion_bitwise():
    ref = pf.gap_distribution(AFFINE, [1e5, 1e6], e_star=E_STAR)
    for zero in (0, 0.0, np.float64(0.0)):
        g = pf.gap_distribution(AFFINE, [1e5, 1e6], e_star=E_STAR, work_of_adhesion=zero)
        assert g.success
        np.testing.assert_array_equal(g.gaps, ref.gaps)
        np.testing.assert_array_equal(g.density, ref.density)
        np.testing.assert_array_equal(g.mean, ref.mean)


# ---------------------------------------------------------------------------------------------
# empty and extreme arguments, contradictory options (item 7, the API's parts)
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("gaps", [None, [0.0, 1e-9, 2e-9]])
def test_gap_distribution_of_no_pressure_is_an_empty_result(gaps):
    """As solve_contact(S, []) and solve_separation(S, []): an empty result, not a NumPy
    reduction error."""
    g = pf.gap_distribution(AFFINE, [], e_star=E_STAR, gaps=gaps)
    n = 0 if gaps is None else len(gaps)
    assert g.success and g.message == "ok"
    assert g.pressure.shape == (0,) and g.gaps.shape == (n,) and g.density.shape == (0, n)
    for field in ("contact_fraction", "mean", "separation", "weight_error", "mean_error",
                  "error_estimate", "status"):
        assert getattr(g, field).shape == (0,), field
    assert g.cumulative([0.0, 1e-9]).shape == (0, 2)
    assert "pressure          0 values" in repr(g)
    assert pf.solve_contact(AFFINE, [], e_star=E_STAR).area.shape == (0,)


def test_gap_distribution_of_no_pressure_still_checks_its_arguments():
    with pytest.raises(ValueError, match=r"^gaps must hold at least 2 values"):
        pf.gap_distribution(AFFINE, [], e_star=E_STAR, gaps=[1e-9])
    with pytest.raises(ValueError, match=r"^rtol must lie in"):
        pf.gap_distribution(AFFINE, [], e_star=E_STAR, rtol=1.0)


@pytest.mark.parametrize("p", [1e11, 1e154, 1e300, np.finfo(float).max])
def test_gap_distribution_far_above_sqrt_g1_is_flagged_cleanly(p):
    """1e300 Pa overflowed p * p in the lower end of the magnification cells ("cannot convert
    float NaN to integer"); now it is what 1e11 was: full contact, flagged as an underflow
    of the separation."""
    from persson_fast._kernels.status import SEPARATION_UNDERFLOW

    g = pf.gap_distribution(AFFINE, [1e5, p], e_star=E_STAR)
    assert g.status.tolist() == [0, SEPARATION_UNDERFLOW]
    assert not g.success and "underflows double precision" in g.message
    assert g.contact_fraction[1] == 1.0 and g.mean[1] == 0.0
    assert np.all(g.density[1] == 0.0)
    assert np.all(np.isfinite(g.density))


def test_gap_distribution_valid_pressure_unchanged_beside_a_huge_one():
    """The fallback for p * p overflow touches only the pressures that overflow."""
    alone = pf.gap_distribution(AFFINE, [1e5, 1e11], e_star=E_STAR)
    huge = pf.gap_distribution(AFFINE, [1e5, 1e300], e_star=E_STAR)
    np.testing.assert_array_equal(alone.gaps, huge.gaps)
    np.testing.assert_array_equal(alone.density[0], huge.density[0])
    assert alone.mean[0] == huge.mean[0]


@pytest.mark.parametrize("pressure_max", [1e8, 1e20, 1e300])
def test_contact_law_pressure_max_where_u_underflows_is_refused_with_the_limit(pressure_max):
    from persson_fast.separation.elastic import nodes_for

    with pytest.raises(ValueError, match=r"^pressure_max must be at most \S+ for this scene "
                                         r"\[Pa\]: .*underflows double precision.*got "
                                         rf"pressure_max = {re.escape(repr(pressure_max))}$"
                       ) as info:
        embed.contact_law(AFFINE, e_star=E_STAR, pressure_max=pressure_max)
    limit = float(re.search(r"at most (\S+) for", str(info.value)).group(1))
    # the limit it gives is one a table can be built to, and just above it u underflows
    root_g1 = 0.5 / nodes_for(AFFINE, E_STAR).s_scale[0]
    assert 10.0 * root_g1 < limit < 100.0 * root_g1
    law = embed.contact_law(AFFINE, e_star=E_STAR, pressure_max=limit)
    assert law.pressure_max == pytest.approx(limit, rel=IDENTITY)     # exp(ln p): rounding
    assert np.all(law.separation > 0.0)
    with pytest.raises(ValueError, match=r"^pressure_max must be at most"):
        embed.contact_law(AFFINE, e_star=E_STAR, pressure_max=limit * 1.001)
    assert "a bug" not in str(info.value)


@pytest.mark.parametrize("pixel, got", [((1e-6,), "a sequence of 1 value: pixel_size = [1e-06]"),
                                        ((1e-6, 1e-6, 1e-6), "a sequence of 3 values")])
def test_from_heights_pixel_size_length_message_is_consistent(pixel, got):
    """The message said 'must hold 1 or 2 value(s) ... got 1 values': now the rule it
    states is the one the value breaks."""
    with pytest.raises(ValueError, match=r"^pixel_size must be a number \(the same spacing "
                                         r"along every axis\) or a sequence of 2 \(one per "
                                         r"axis: \(dy, dx\)\) for 2-D heights \[m\]; got "
                                         + re.escape(got)):
        pf.TabulatedPSD.from_heights(HEIGHTS, pixel_size=pixel)
    # the forms it names are accepted, and a scalar is the pair of equal spacings
    a = pf.TabulatedPSD.from_heights(HEIGHTS, pixel_size=1e-6)
    b = pf.TabulatedPSD.from_heights(HEIGHTS, pixel_size=(1e-6, 1e-6))
    np.testing.assert_array_equal(a.C_table, b.C_table)


SCAN_PARAMS = {"hurst": [0.8], "q0": 1e4, "q1": 1e7, "h_rms": 1e-8}


@pytest.mark.parametrize("gaps", [False, np.False_])
def test_scan_gaps_rtol_without_gaps_is_refused(gaps):
    with pytest.raises(ValueError, match=r"^gaps_rtol is the tolerance of the gap "
                                         r"distributions and needs gaps \(True or an array of "
                                         r"gaps\) \[-\]; got gaps_rtol = 0\.0001 with gaps = "
                                         r"(np\.)?False"):
        pf.scan(pf.SelfAffine, SCAN_PARAMS, [1e5], e_star=E_STAR, gaps=gaps, gaps_rtol=1e-4)


def test_scan_pull_off_rtol_without_pull_off_is_refused():
    with pytest.raises(ValueError, match=r"^pull_off_rtol is the accuracy of the pull-off "
                                         r"stress and needs pull_off=True \[-\]; got "
                                         r"pull_off_rtol = 0\.001 with pull_off = False"):
        pf.scan(pf.SelfAffine, SCAN_PARAMS, [1e5], e_star=E_STAR, pull_off_rtol=1e-3)


def test_scan_gaps_rtol_with_gaps_is_taken():
    ds = pf.scan(pf.SelfAffine, SCAN_PARAMS, [1e5], e_star=E_STAR, gaps=True, gaps_rtol=1e-2,
                 workers=1)
    assert ds.attrs["gaps_rtol"] == 1e-2


@pytest.mark.parametrize("call, rule", [
    (lambda: pf.adhesion_zeta(AFFINE, rtol=2.0), r"^rtol must lie in \(0, 1\) \[-\]; got rtol = 2\.0"),
    (lambda: pf.adhesion_zeta(AFFINE, rtol=0.0), r"^rtol must lie in \(0, 1\) \[-\]; got rtol = 0\.0"),
    (lambda: pf.adhesion_zeta(AFFINE, rtol=np.nan), r"^rtol must be finite"),
    (lambda: pf.adhesion_zeta(AFFINE, per_decade=0),
     r"^per_decade must be a whole number >= 1 \[-\]; got per_decade = 0"),
    (lambda: pf.adhesion_zeta(AFFINE, per_decade=2.5),
     r"^per_decade must be a whole number >= 1 \[-\]; got per_decade = 2\.5"),
    (lambda: pf.adhesion_zeta(AFFINE, near_one_min=1.5),
     r"^near_one_min must lie in \(0, 1\) \[-\]; got near_one_min = 1\.5"),
    (lambda: pf.default_zeta(AFFINE, per_decade=0),
     r"^per_decade must be a whole number >= 1 \[-\]; got per_decade = 0"),
    (lambda: pf.default_zeta(AFFINE, per_decade=-3),
     r"^per_decade must be a whole number >= 1 \[-\]; got per_decade = -3"),
], ids=["adhesion rtol 2", "adhesion rtol 0", "adhesion rtol nan", "adhesion per_decade 0",
        "adhesion per_decade 2.5", "adhesion near_one_min 1.5", "default per_decade 0",
        "default per_decade -3"])
def test_zeta_grids_refuse_values_outside_their_rules(call, rule):
    """adhesion_zeta(rtol=2.0) and default_zeta(per_decade=0) made a grid; now each names the
    argument and its rule."""
    with pytest.raises(ValueError, match=rule):
        call()


def test_zeta_grids_unchanged_for_valid_arguments():
    """A float with a whole value is the same per_decade as the int (the grid is identical)."""
    np.testing.assert_array_equal(pf.adhesion_zeta(AFFINE, per_decade=12.0),
                                  pf.adhesion_zeta(AFFINE, per_decade=12))
    np.testing.assert_array_equal(pf.default_zeta(AFFINE, per_decade=np.int64(5)),
                                  pf.default_zeta(AFFINE, per_decade=5))


SEPARATION_ENTRIES = [
    ("solve_separation", lambda **kw: pf.solve_separation(AFFINE, [1e5, 1e6], e_star=E_STAR,
                                                          **kw).separation),
    ("pressure_at_separation", lambda **kw: pf.pressure_at_separation(
        AFFINE, [1e-6, 2e-6], e_star=E_STAR, **kw)),
    ("decay_length", lambda **kw: pf.decay_length(AFFINE, e_star=E_STAR, **kw)),
    ("contact_law", lambda **kw: embed.contact_law(AFFINE, e_star=E_STAR, rtol=1e-4,
                                                   **kw).table),
]


@pytest.mark.parametrize("where, call", SEPARATION_ENTRIES, ids=[e[0] for e in SEPARATION_ENTRIES])
def test_separation_entries_take_work_of_adhesion_and_refuse_it_saying_why(where, call):
    """As gap_distribution: the keyword exists (it was "unexpected keyword argument"), 0 is
    the scene without adhesion (bitwise), > 0 is refused with the reason, < 0 by its rule."""
    ref = call()
    np.testing.assert_array_equal(call(work_of_adhesion=0.0), ref)
    with pytest.raises(ValueError, match=rf"^{where}: the mean separation and the contact "
                                         r"stiffness are derived here for scenes without "
                                         r"adhesion only \(work_of_adhesion = 0\); got "
                                         r"work_of_adhesion = 0\.03 \[J/m\^2\]"):
        call(work_of_adhesion=0.03)
    with pytest.raises(ValueError, match=r"^work_of_adhesion must be >= 0 \[J/m\^2\]"):
        call(work_of_adhesion=-1.0)
    _refuses_bool(lambda: call(work_of_adhesion=True), "work_of_adhesion")
