"""The disk cache of the kernels goes stale with any kernel source, not only the function's own.

numba checks only the source file of a cached function; a cached sweep would keep running an
old solver from another file after an edit or an upgrade. The package stamps its cache
entries with a hash of every kernel file (``persson_fast._jit.kernel_source_stamp``).
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import persson_fast

PACKAGE = Path(persson_fast.__file__).resolve().parent

_CHILD = r"""
import json
from persson_fast._kernels.special import ndtr
ndtr(0.5)
print(json.dumps({"hits": sum(ndtr.stats.cache_hits.values()),
                  "misses": sum(ndtr.stats.cache_misses.values()),
                  "file": __import__("persson_fast").__file__}))
"""


def _run(root, cache):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), PYTHONPATH=str(root))
    env.pop("NUMBA_DISABLE_JIT", None)
    out = subprocess.run([sys.executable, "-c", _CHILD], env=env, cwd=str(root),
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_editing_another_kernel_file_invalidates_the_cache(tmp_path):
    root = tmp_path / "src"
    shutil.copytree(PACKAGE, root / "persson_fast",
                    ignore=shutil.ignore_patterns("__pycache__"))
    cache = tmp_path / "cache"
    first = _run(root, cache)
    assert first["file"].startswith(str(root))
    assert (first["hits"], first["misses"]) == (0, 1)
    assert (_run(root, cache)["hits"], _run(root, cache)["misses"]) == (1, 0)
    # an edit in a file that ndtr does not live in (tridiag.py) must invalidate it too
    with open(root / "persson_fast" / "_kernels" / "tridiag.py", "a") as fh:
        fh.write("\n# an edit\n")
    after = _run(root, cache)
    assert (after["hits"], after["misses"]) == (0, 1)


_LATE_IMPORT_CHILD = r"""
import json, os, time
import persson_fast._kernels.special                 # the kernels imported, then the files
open(os.environ["IMPORTED"], "w").close()            # change on disk (an upgrade) ...
while not os.path.exists(os.environ["GO"]):
    time.sleep(0.05)
from persson_fast import embed                       # ... and a module is imported later
embed._rtol_ok(1e-6)                                 # compiled and saved by this process
print(json.dumps({"misses": sum(embed._rtol_ok.stats.cache_misses.values())}))
"""

_FRESH_CHILD = r"""
import json
from persson_fast import embed
embed._rtol_ok(1e-6)
print(json.dumps({"hits": sum(embed._rtol_ok.stats.cache_hits.values()),
                  "misses": sum(embed._rtol_ok.stats.cache_misses.values())}))
"""


def test_code_compiled_after_an_upgrade_on_disk_keeps_its_import_stamp(tmp_path):
    """A session imports the package; its kernel files then change on disk; the session
    imports a module on demand (``embed``) and compiles from it, against the kernels it
    has in memory. Its cache entries must carry the stamp of the sources it imported: found
    when an embed entry point, compiled that way, kept returning the previous kernel's
    results in every later process (labelled with the new files' hash)."""
    import time

    root = tmp_path / "src"
    shutil.copytree(PACKAGE, root / "persson_fast",
                    ignore=shutil.ignore_patterns("__pycache__"))
    cache = tmp_path / "cache"
    imported, go = tmp_path / "imported", tmp_path / "go"
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), PYTHONPATH=str(root),
               IMPORTED=str(imported), GO=str(go))
    env.pop("NUMBA_DISABLE_JIT", None)
    child = subprocess.Popen([sys.executable, "-c", _LATE_IMPORT_CHILD], env=env,
                             cwd=str(root), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True)
    try:
        t0 = time.monotonic()
        while not imported.exists():
            assert child.poll() is None, child.stderr.read()
            assert time.monotonic() - t0 < 300
            time.sleep(0.05)
        with open(root / "persson_fast" / "_kernels" / "tridiag.py", "a") as fh:
            fh.write("\n# an upgrade\n")
        go.touch()
        out, err = child.communicate(timeout=300)
    finally:
        if child.poll() is None:
            child.kill()
    assert child.returncode == 0, err
    assert json.loads(out.strip().splitlines()[-1])["misses"] == 1
    fresh = subprocess.run([sys.executable, "-c", _FRESH_CHILD], env=env, cwd=str(root),
                           capture_output=True, text=True, timeout=300)
    assert fresh.returncode == 0, fresh.stderr
    after = json.loads(fresh.stdout.strip().splitlines()[-1])
    assert (after["hits"], after["misses"]) == (0, 1)
