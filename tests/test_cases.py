"""The benchmark scenes (benchmarks/cases.py) are test scenes too: what the benchmarks time is
checked here against the closed form, so a speed figure always refers to a correct answer."""
import numpy as np
import pytest

import persson_fast as pf
from benchmarks.cases import CASES


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
@pytest.mark.parametrize("rtol", [1e-4, 1e-6])
def test_benchmark_case_cn_within_rtol(case, rtol):
    inp = case.setup()
    r = pf.solve_contact(pf.Scene(inp.surface, e_star=inp.e_star), inp.pressure, method="cn",
                         rtol=rtol)
    exact = pf.solve_contact(inp.surface, inp.pressure, e_star=inp.e_star, method="analytic")
    assert np.all(r.status == 0), r.message
    assert np.all(np.abs(r.area - exact.area) <= rtol * exact.area + 1e-12)
    assert np.array_equal(r.zeta, inp.zeta) and np.array_equal(r.G, inp.G)
