"""The work cap of the "cn" diffusion solve holds on every path.

A pressure whose start distance to the wall is tiny (adhesion at p = 0: the fixed point's
iterate put the wall at 6e-14 of sigma0) makes the wall recede by ~1e10 start distances over
the schedule's first piece. The steps per profile width travelled were judged by the width
at the piece's start (and floored under the work cap): 2.75e8 steps, 2e10 node-steps, 240 s.
"""
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from persson_fast._kernels import similarity as d
from persson_fast._kernels import status as st

# the saved inputs (/tmp/hang_G.npy, /tmp/hang_x.npy), sigma0 = 0
G_HANG = np.array([0.0, 4.25722714e-09, 4.68294957e-08, 4.72551894e-07, 4.72974709e-06,
                   5.23020242e-03, 1.0])
X_HANG = np.array([5.82029000e-14, 4.15000183e-04, 1.35679549e-03, 4.33914661e-03,
                   1.38464128e-02, 7.45879254e-01, 2.49305036e+00])


def _solve(G, x, sigma0, rtol):
    n = G.shape[0]
    outs = [np.zeros(n) for _ in range(5)]
    counts = np.zeros(3, dtype=np.int64)
    sx, stp, th, ex, wm = d.variant_resolution(d.CN, rtol, np.int64(-1))
    s = d._solve_grid_tol(G, x, sigma0, sx, stp, th, ex, wm, 2, rtol, *outs, counts)
    return s, outs, counts, wm


@pytest.mark.parametrize("rtol", [0.1, 1e-3, 1e-6])
def test_tiny_start_distance_within_work_cap(rtol):
    s, outs, counts, wm = _solve(G_HANG, X_HANG, 0.0, rtol)
    assert s in (st.OK, st.GRID_CAP, st.RTOL_NOT_MET)
    assert counts[2] <= d.WORK_TOTAL * wm
    area, err = outs[0], outs[4]
    assert np.all(np.isfinite(area)) and np.all(area >= 0.0) and np.all(area <= 1.0)
    # converged value (rtol 1e-8): the wall recedes from ~0, the area is ~ y0 b ~ 6e-9
    ref = np.array([1.0, 5.67369718e-09, 5.67114619e-09, 5.66770635e-09, 5.66436243e-09,
                    4.77455957e-09, 3.59940076e-09])
    if s == st.OK:
        assert np.all(np.abs(area - ref) <= rtol * ref + d.RTOL_ATOL)
        assert np.all(err <= rtol * area + d.RTOL_ATOL)


def test_tiny_start_distance_fast_subprocess():
    """The public entry point finishes in seconds (it took 240 s), compile included."""
    code = textwrap.dedent(f"""
        import numpy as np
        from persson_fast._kernels.similarity import solve_one
        G = np.array({G_HANG.tolist()}); x = np.array({X_HANG.tolist()})
        outs = [np.zeros(G.shape[0]) for _ in range(5)]
        print(solve_one(G, x, 0.0, 0.1, 2, *outs))
    """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    assert int(r.stdout.strip().splitlines()[-1]) in (st.OK, st.GRID_CAP, st.RTOL_NOT_MET)


def test_hard_cap_on_fast_wall_schedule():
    """A wall that moves many profile widths per piece, on many pieces: all runs together
    stay within WORK_TOTAL work caps, and the status says when the cap cut resolution."""
    G = np.geomspace(1e-6, 1e2, 400)
    x = 1.0 + 50.0 * np.sin(np.linspace(0.0, 200.0, 400))
    x = np.maximum(x, 1e-3)
    s, outs, counts, wm = _solve(G, x, 1.0, 1e-6)
    assert counts[2] <= d.WORK_TOTAL * wm
    assert s in (st.OK, st.GRID_CAP, st.RTOL_NOT_MET, st.WALL_JUMP, st.FAR_LEAK)
    assert np.all(np.isfinite(outs[0]))
