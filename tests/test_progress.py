"""Long runs say what they are doing: the progress bar of ``persson-fast contact`` (solved in
blocks of pressures, bitwise as one call) and the note that kernels are being compiled (once
per machine, on the ``persson_fast`` logger, printed by the command line)."""
import dataclasses
import os
import subprocess
import sys

import numpy as np
import pytest

import persson_fast as pf
from persson_fast.cli import main as cli


def _scene():
    s = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e7, h_rms=1e-8)
    return s, dict(e_star=1e9, work_of_adhesion=0.05, rtol=1e-4)


def test_blocks_of_pressures_are_bitwise_one_call():
    s, kw = _scene()
    p = np.linspace(-1e5, 3e6, 7)
    whole = pf.solve_contact(s, p, **kw)
    cli.PROGRESS_UPDATES, keep = 4, cli.PROGRESS_UPDATES
    try:
        joined = cli._solve_with_progress(pf, s, p, False, True, **kw)
    finally:
        cli.PROGRESS_UPDATES = keep
    assert isinstance(joined, cli._Joined)
    for name in cli._Joined.ROWS:
        assert np.array_equal(getattr(joined, name), getattr(whole, name)), name
    assert joined.success == whole.success


def test_quiet_or_fast_scenes_are_one_call():
    s, kw = _scene()
    res = cli._solve_with_progress(pf, s, [1e6, 2e6], True, True, **kw)
    assert isinstance(res, pf.ContactResult)
    kw.pop("work_of_adhesion")
    res = cli._solve_with_progress(pf, s, [1e6, 2e6], False, False, **kw)
    assert isinstance(res, pf.ContactResult)


def test_joined_message_names_the_flagged_block():
    s, kw = _scene()
    parts = [pf.solve_contact(s, [1e6], **kw), pf.solve_contact(s, [2e6], **kw)]
    parts[1] = dataclasses.replace(parts[1], status=np.array([15]), success=False,
                                   message="flagged here")
    joined = cli._Joined(parts)
    assert not joined.success
    assert "pressures 1-1: flagged here" in joined.message
    assert "index 1" in joined.message


def test_compile_note_on_a_cold_cache(tmp_path):
    """On an empty disk cache the first adhesive solve says it compiles (nothing is compiled
    by the check itself), once; a second check in the same process says nothing."""
    code = ("import logging, sys\n"
            "logging.basicConfig(level=logging.INFO, stream=sys.stdout, format='%(message)s')\n"
            "from persson_fast._jit import announce_compile\n"
            "from persson_fast._kernels.adhesion import fixed_point, FIXED_POINT_SIGNATURE\n"
            "jobs = [(fixed_point, FIXED_POINT_SIGNATURE)]\n"
            "print(announce_compile('adhesion', jobs), announce_compile('adhesion', jobs))\n")
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    if os.environ.get("NUMBA_DISABLE_JIT") == "1":
        pytest.skip("compiled code only")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                         timeout=120, check=True).stdout
    assert ("compiling kernels for adhesion, once per machine: tens of seconds of CPU "
            "(`persson-fast info` measures it on this machine)") in out
    assert out.strip().endswith("True False")


def test_no_compile_note_on_a_warm_cache():
    """The session's kernels are compiled and cached: nothing is announced."""
    from persson_fast._jit import _announced, announce_compile
    from persson_fast._kernels.adhesion import FIXED_POINT_SIGNATURE, fixed_point
    from persson_fast._kernels.similarity import GRID_SIGNATURE, _solve_grid_tol

    pf.solve_contact(*_scene()[:1], [1e6], e_star=1e9, work_of_adhesion=0.05, rtol=1e-3)
    _announced.discard("warm check")
    assert not announce_compile("warm check", [(fixed_point, FIXED_POINT_SIGNATURE),
                                               (_solve_grid_tol, GRID_SIGNATURE)])


def test_quiet_flag_parses():
    args = cli.build_parser().parse_args(["contact", "--quiet"])
    assert args.quiet
    args = cli.build_parser().parse_args(["figure2", "--quiet"])
    assert args.quiet
