"""Compile time of the kernels, measured in fresh processes.

Usage::

    python -m benchmarks.compile_time [--cached-runs N] [--cache-dir DIR]

Each measurement starts a new Python process with ``NUMBA_CACHE_DIR`` pointing at one folder
(a new temporary one unless ``--cache-dir`` is given) and times, inside that process,

* ``import persson_fast``,
* ``persson_fast.warmup()`` (the sweep kernels and the adhesive kernel), and
* the first ``solve_contact(method="cn")`` call afterwards (the seed scene, 128 pressures,
  default ``parallel``: threads over the serial kernels),

and then, as whole commands in fresh processes, ``persson-fast figure2`` (the README's main
job) and ``persson-fast info``, each cold (an empty cache folder of its own) and cached.

The first process compiles from scratch ("cold"); the following ones reuse that cache
("cached"). Only the ``prange`` sweeps (``parallel="prange"``) are not cached on disk (see
``persson_fast/_jit.py``); nothing here uses them.
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent

_CHILD = r"""
import json, time
t0 = time.perf_counter()
import persson_fast as pf
t_import = time.perf_counter() - t0
import numba
import numpy as np
warm = pf.warmup()
surface = pf.seed_scene()
p = np.linspace(0.0, 100e6, 128)
t0 = time.perf_counter()
res = pf.solve_contact(surface, p, e_star=pf.seed_e_star(), method="cn")
t_first = time.perf_counter() - t0
print(json.dumps({
    "import": t_import,
    "warmup_serial": warm.get("serial", float("nan")),
    "warmup_adhesion": warm.get("adhesion", float("nan")),
    "first_cn": t_first,
    "first_cn_compile": res.timings.get("compile", 0.0),
    "success": bool(res.success),
    "threads": numba.config.NUMBA_NUM_THREADS,
    "numba": numba.__version__,
}))
"""


def measure(cache_dir: str) -> dict:
    """Run one fresh process with NUMBA_CACHE_DIR=cache_dir; return its timings (seconds)."""
    env = dict(os.environ)
    env["NUMBA_CACHE_DIR"] = cache_dir
    env.pop("NUMBA_DISABLE_JIT", None)
    paths = [str(REPO_ROOT), env.get("PYTHONPATH", "")]
    env["PYTHONPATH"] = os.pathsep.join(p for p in paths if p)
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", _CHILD], env=env, cwd=str(REPO_ROOT),
                          capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"child process failed (exit {proc.returncode}):\n{proc.stderr}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    out["process"] = wall
    return out


def command_seconds(args, cache_dir: str) -> float:
    """Wall seconds of ``python -m persson_fast.cli ARGS`` in a fresh process."""
    env = dict(os.environ)
    env["NUMBA_CACHE_DIR"] = cache_dir
    env.pop("NUMBA_DISABLE_JIT", None)
    paths = [str(REPO_ROOT), env.get("PYTHONPATH", "")]
    env["PYTHONPATH"] = os.pathsep.join(p for p in paths if p)
    with tempfile.TemporaryDirectory() as out:
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "persson_fast.cli", *args]
                              + (["--out", out] if args[0] == "figure2" else []),
                              env=env, cwd=out, capture_output=True, text=True)
        wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"persson-fast {' '.join(args)} failed (exit {proc.returncode}):\n"
                           f"{proc.stderr}")
    return wall


def commands() -> dict:
    """Cold and cached wall seconds of ``persson-fast figure2`` and ``persson-fast info``."""
    out = {}
    for name in ("figure2", "info"):
        cache_dir = tempfile.mkdtemp(prefix="persson_fast_numba_cache_")
        try:
            out[name] = {"cold": command_seconds([name], cache_dir),
                         "cached": command_seconds([name], cache_dir)}
        finally:
            shutil.rmtree(cache_dir, ignore_errors=True)
    return out


def _table(rows) -> str:
    cols = [("import", "import"), ("warmup_serial", "warmup serial"),
            ("warmup_adhesion", "warmup adhesion"), ("first_cn", "first cn call"),
            ("process", "whole process")]
    head = f"{'run':<10}" + "".join(f"{label:>17}" for _, label in cols)
    lines = [head, "-" * len(head)]
    for name, r in rows:
        lines.append(f"{name:<10}" + "".join(f"{r[key]:17.3f}" for key, _ in cols))
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.compile_time",
                                     description="Kernel compile time in fresh processes.")
    parser.add_argument("--cached-runs", type=int, default=1, metavar="N",
                        help="processes run after the cold one, reusing its cache (default 1)")
    parser.add_argument("--cache-dir", metavar="DIR",
                        help="use (and keep) this cache folder; it should be empty for a cold run")
    parser.add_argument("--commands", action="store_true",
                        help="also time `persson-fast figure2` and `persson-fast info`, cold "
                             "and cached")
    args = parser.parse_args(argv)

    own_dir = args.cache_dir is None
    cache_dir = tempfile.mkdtemp(prefix="persson_fast_numba_cache_") if own_dir else args.cache_dir
    try:
        rows = [("cold", measure(cache_dir))]
        for i in range(max(0, args.cached_runs)):
            name = "cached" if args.cached_runs == 1 else f"cached {i + 1}"
            rows.append((name, measure(cache_dir)))
    finally:
        if own_dir:
            shutil.rmtree(cache_dir, ignore_errors=True)

    first = rows[0][1]
    print("Kernel compile time, seconds (each row a fresh process; NUMBA_CACHE_DIR shared)")
    print(_table(rows))
    if args.commands:
        print()
        for name, t in commands().items():
            print(f"persson-fast {name}: {t['cold']:.1f} s cold, {t['cached']:.1f} s cached "
                  "(whole process, wall)")
    print()
    print("first cn call: solve_contact(seed_scene(), 128 pressures, method='cn') after warmup")
    print(f"machine: {platform.platform()}, {platform.machine()}, {os.cpu_count()} CPUs, "
          f"numba threads {first['threads']}")
    print(f"python {platform.python_version()}, numba {first['numba']}")
    print(f"date: {datetime.datetime.now().astimezone().isoformat(timespec='seconds')}")
    if not all(r["success"] for _, r in rows):
        print("warning: a solve did not succeed")
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
