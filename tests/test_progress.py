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


# --------------------------------------------------------------------------------------------
# every scene kind through the progress path (issue 42, item 1: a yield wall without adhesion
# crashed there, its blocks' sticky/iterations being None)
# --------------------------------------------------------------------------------------------

#: the scene of issue 42's report, with each kind of physics the contact command solves
KIND_SCENE = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e7",
              "--h-rms", "1e-8", "--e-star", "1e9", "--rtol", "1e-3"]
KINDS = {
    "elastic": [],
    "adhesive": ["--work-of-adhesion", "0.005"],
    "yield": ["--hardness", "3e7"],
    "yield+adhesion": ["--hardness", "3e7", "--work-of-adhesion", "0.005"],
    "theory": ["--theory", "wm17"],
    "theory+yield": ["--theory", "wm17", "--hardness", "3e7"],
    "theory+adhesion": ["--theory", "yp08", "--work-of-adhesion", "0.005"],
}
KIND_KWARGS = {
    "elastic": {},
    "adhesive": dict(work_of_adhesion=0.005),
    "yield": dict(hardness=3e7),
    "yield+adhesion": dict(hardness=3e7, work_of_adhesion=0.005),
    "theory": dict(theory="wm17"),
    "theory+yield": dict(theory="wm17", hardness=3e7),
    "theory+adhesion": dict(theory="yp08", work_of_adhesion=0.005),
}
#: the command's slow scenes (a progress bar): adhesion or a yield wall
SLOW_KINDS = {"adhesive", "yield", "yield+adhesion", "theory+yield", "theory+adhesion"}


@pytest.mark.parametrize("kind", list(KIND_KWARGS))
def test_every_scene_kind_in_blocks_is_one_call(kind):
    """Blocks of pressures joined give every field the command reads as one call does, None
    where the scene has no such field."""
    s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e7, h_rms=1e-8)
    kw = dict(e_star=1e9, rtol=1e-3, **KIND_KWARGS[kind])
    p = np.linspace(1e4, 1e6, 7)
    whole = pf.solve_contact(s, p, **kw)
    cli.PROGRESS_UPDATES, keep = 4, cli.PROGRESS_UPDATES
    try:
        joined = cli._solve_with_progress(pf, s, p, False, True, **kw)
    finally:
        cli.PROGRESS_UPDATES = keep
    assert isinstance(joined, cli._Joined)
    for name in cli._Joined.ROWS:
        want = getattr(whole, name)
        if want is None:
            assert getattr(joined, name) is None, name
        else:
            assert np.array_equal(getattr(joined, name), want), name
    assert (joined.method, joined.theory, joined.theory_gamma) == (
        whole.method, whole.theory, whole.theory_gamma)
    assert joined.success == whole.success


def test_joined_blocks_that_disagree_are_reported():
    s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e7, h_rms=1e-8)
    parts = [pf.solve_contact(s, [1e5], e_star=1e9, rtol=1e-3, work_of_adhesion=0.05),
             pf.solve_contact(s, [2e5], e_star=1e9, rtol=1e-3)]
    with pytest.raises(RuntimeError, match="disagree on whether the result has 'sticky'"):
        cli._Joined(parts)


def _run_on_a_terminal(argv, timeout=240):
    """(exit code, stdout, what reached the terminal) of ``persson-fast`` run with its stderr
    on a pseudo-terminal (stdout piped), the progress bar shown at once, one numba thread (so
    that 5 pressures are 3 blocks)."""
    import fcntl
    import pty
    import select
    import struct
    import termios
    import time

    code = ("import sys; from persson_fast.cli import main as m; m.PROGRESS_DELAY = 0.0; "
            "assert sys.stderr.isatty(); sys.argv = ['persson-fast', *sys.argv[1:]]; m.run()")
    env = {**os.environ, "NUMBA_NUM_THREADS": "1", "COLUMNS": "100"}
    master, slave = pty.openpty()
    # a terminal of 24 x 100 characters (a new one has 0 columns, where tqdm draws nothing)
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    try:
        proc = subprocess.Popen([sys.executable, "-c", code, *argv], stdin=subprocess.DEVNULL,
                                stdout=subprocess.PIPE, stderr=slave, env=env)
    finally:
        os.close(slave)
    terminal = b""
    deadline = time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            ready, _, _ = select.select([master], [], [], 0.5)
            if ready:
                try:
                    chunk = os.read(master, 65536)
                except OSError:          # EIO: the child closed its end, all read
                    break
                if not chunk:
                    break
                terminal += chunk
            elif proc.poll() is not None:
                break                    # exited, and nothing left to read
        out = proc.communicate(timeout=max(1.0, deadline - time.monotonic()))[0]
    finally:
        os.close(master)
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    return proc.returncode, out.decode(), terminal.decode(errors="replace")


def _table(text):
    """The printed table's lines (from its head to the last row)."""
    lines = text.splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.lstrip().startswith("pressure [Pa]"))
    end = start + 1
    while end < len(lines) and lines[end][:14].strip().replace(".", "").replace("e+", "") \
            .replace("e-", "").isdigit():
        end += 1
    return lines[start:end]


@pytest.mark.parametrize("kind", list(KINDS))
def test_every_scene_kind_on_a_terminal(kind, capsys):
    """With stderr on a pseudo-terminal the command solves slow scenes in blocks behind a
    progress bar: every kind of scene runs there, exits 0 and prints the table that a piped
    run (one call) prints."""
    if os.environ.get("NUMBA_DISABLE_JIT") == "1":
        pytest.skip("compiled code only (a subprocess per scene)")
    argv = ["contact", *KIND_SCENE, *KINDS[kind], "--pressure-range", "1e4", "1e6", "5"]
    code, out, terminal = _run_on_a_terminal(argv)
    assert code == 0, (out, terminal)
    assert "error" not in terminal and "Traceback" not in terminal, terminal
    if kind in SLOW_KINDS:
        assert "pressure" in terminal, terminal           # the bar was drawn
    assert cli.main(argv) == 0                            # piped (capsys): one call
    piped = capsys.readouterr().out
    table = _table(out)
    assert len(table) == 6
    assert table == _table(piped)
