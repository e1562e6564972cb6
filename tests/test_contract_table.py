"""The contract table (benchmarks/contract_table.py): its verdicts say what they claim, and its
rows and references are right on cheap cases."""
import numpy as np

import persson_fast as pf
from benchmarks.contract_table import (SCENES, jump_reference, judge, row, scene, verdict,
                                       wall_methods)


def test_verdict_logic_on_fabricated_results():
    ref = np.array([1.0, 0.5, 0.2])
    rtol = 1e-4
    inside = ref * (1 + 0.5 * rtol)
    outside = ref * (1 + 10 * rtol)
    e, _, v, nan = judge(inside, np.full(3, 1e-5), 0, ref, rtol)
    assert v == "ok" and e <= 1.0 and not nan
    e, _, v, _ = judge(outside, np.full(3, 1e-5), 0, ref, rtol)
    assert v == "MISS" and 9.0 < e < 11.0          # outside rtol with status 0: broken
    assert judge(outside, np.full(3, 1e-5), 15, ref, rtol)[2] == "flagged"
    # a NaN area: a MISS with status 0, flagged otherwise, and reported as NaN
    bad = inside.copy()
    bad[1] = np.nan
    e, ratio, v, nan = judge(bad, np.full(3, 1e-5), 0, ref, rtol)
    assert v == "MISS" and nan and not np.isfinite(e) and ratio is None
    assert judge(bad, np.full(3, 1e-5), 1, ref, rtol)[2] == "flagged"
    assert verdict(0.99, 0) == "ok" and verdict(1.01, 0) == "MISS"
    assert verdict(0.5, 8) == "flagged" and verdict(1.5, 15) == "flagged"


def test_est_over_actual_is_left_out_at_rounding_and_reference_level():
    ref = np.array([1.0, 0.5])
    # actual error 1e-15 relative: rounding, no ratio
    assert judge(ref * (1 + 1e-15), [0, 1e-14], 0, ref, 1e-6)[1] is None
    # actual error 1e-9, below 3x a reference uncertainty of 1e-9: no ratio
    assert judge(ref + 1e-9, [0, 1e-9], 0, ref, 1e-6, ref_unc=1e-9)[1] is None
    r = judge(ref + 1e-8, [0, 2e-8], 0, ref, 1e-6)[1]
    assert abs(r - 2.0) < 1e-6


def test_the_table_covers_the_wall_solvers():
    assert set(wall_methods()) == {"cn", "cn-plain", "implicit-euler", "fixed-grid", "bnr"}
    assert len(SCENES) == 8


def test_cheap_rows():
    res = row("cn", scene("images"), 1e-4, repeats=1)
    assert res["verdict"] == "ok" and res["status"] == 0 and res["error_over_rtol"] <= 1.0
    assert res["seconds"] > 0
    jump = scene("jump 0.2 -> 0.35 at G = 0.6")
    res = row("cn", jump, 1e-3, repeats=1)
    # within rtol of the exact reference; cn flags a jump (WALL_JUMP) whatever the error
    assert res["error_over_rtol"] <= 1.0 and res["verdict"] in ("ok", "flagged")
    assert res["verdict"] == ("ok" if res["status"] == 0 else "flagged")
    # methods that cannot serve a jump are n/a, not a verdict
    assert row("bnr", jump, 1e-3, repeats=1)["verdict"] == "n/a"
    # a wrong reference is caught (the row can fail)
    wrong = scene("images")
    wrong.ref = wrong.ref * (1 + 1e-2)
    assert row("cn", wrong, 1e-4, repeats=1)["verdict"] == "MISS"


def test_jump_reference_is_the_images_before_and_continuous_at_the_jump():
    G = np.array([0.1, 0.6, 0.6 + 1e-12, 1.0])
    a = jump_reference(G)
    assert abs(a[0] - pf.images_area(0.7, 0.1)) < 1e-15
    assert abs(a[2] - a[1]) < 1e-9
    # the wall moved away at the jump: more survives than with the wall kept at 0.2
    assert a[3] > pf.images_area(0.7, 1.0)
    assert abs(jump_reference(G, n=400)[3] - a[3]) < 1e-13


def test_random_wall_stats_on_two_walls():
    """The random-wall table's counts add up; a result outside rtol with status 0 is a MISS
    (checked with a reference made wrong on purpose)."""
    from benchmarks import contract_table as ct
    from benchmarks import random_walls

    stats, misses = ct.random_wall_stats(2, (1e-4,), ("cn",))
    s = stats[("cn", 1e-4)]
    assert s["n"] == 4 and s["refused"] == 0 and s["nan"] == 0     # 2 walls x 2 forms
    assert s["miss"] == 0 and not misses and s["flagged_within"] <= s["flagged"]
    assert s["est_min"] is None or s["est_min"] > 0
    real = random_walls.with_reference

    def wrong(wall):
        wall = real(wall)
        wall.ref = wall.ref * (1 + 1e-2)
        return wall

    random_walls.with_reference = wrong
    try:
        stats, misses = ct.random_wall_stats(1, (1e-4,), ("cn",))
    finally:
        random_walls.with_reference = real
    assert stats[("cn", 1e-4)]["miss"] == 2 and len(misses) == 2
