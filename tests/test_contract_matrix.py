"""The contract matrix's verdicts (benchmarks/contract_matrix.py) say what they claim."""
import numpy as np

import persson_fast as pf
from benchmarks.contract_matrix import row, verdict


def test_verdict_logic():
    assert verdict(0.5, 0) == "ok"
    assert verdict(1.5, 0) == "MISS"          # outside rtol, status 0: the contract broken
    assert verdict(1.5, 15) == "flagged"
    assert verdict(0.5, 8) == "flagged"
    assert verdict(np.inf, 0) == "MISS"       # a NaN area with status 0
    assert verdict(np.inf, 1) == "flagged"


def test_rows_against_a_closed_form():
    G = np.concatenate([[0.0], np.geomspace(1e-3, 10.0, 12)])
    ref = pf.images_area(1.0, G)
    e, ratio, s, v, sec = row("cn", G, 1.0, np.zeros_like(G), ref, 1e-4, repeats=1)
    assert v == "ok" and e <= 1.0 and s == 0 and sec > 0
    # a wrong reference is caught as a miss (the check can fail)
    e, _, s, v, _ = row("cn", G, 1.0, np.zeros_like(G), ref * (1 + 1e-2), 1e-4, repeats=1)
    assert s == 0 and v == "MISS" and e > 1.0
    # a method that refuses the scene is n/a (None), not a verdict
    Gj = np.array([0.0, 0.5, 0.5, 1.0])
    assert row("bnr", Gj, 1.0, np.array([0.1, 0.1, 0.3, 0.3]), np.ones(4), 1e-3) is None
