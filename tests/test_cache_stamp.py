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
