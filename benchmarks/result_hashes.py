"""sha256 of every result field over the package's methods, walls and combinations.

A change that should not move any number (a re-organisation of the modules, a refactoring)
is checked by running this script before and after it and comparing the two JSON files::

    python -m benchmarks.result_hashes --out before.json
    ... change ...
    python -m benchmarks.result_hashes --out after.json --compare before.json

Only public names are called (``persson_fast.*``, ``persson_fast.embed.*`` and the command
line), so the script runs unchanged on both sides of a move. Each case hashes the names,
dtypes, shapes and bytes of every array of its result, and the repr of every other field
(timings, which depend on the machine, are left out). ``--pickles DIR`` also writes a pickle
of a surface, a scene and each kind of result, for a test that later versions load them.
"""
from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import os
import pickle
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

import persson_fast as pf

#: fields that hold measured times, not results
SKIP = {"timings", "timing", "time", "elapsed", "wall_time"}


def _feed(h, name, value):
    h.update(name.encode())
    if isinstance(value, np.ndarray):
        h.update(f"{value.dtype}{value.shape}".encode())
        h.update(np.ascontiguousarray(value).tobytes())
    elif isinstance(value, dict):
        for k in sorted(value, key=str):
            if str(k) not in SKIP:
                _feed(h, f"{name}.{k}", value[k])
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            _feed(h, f"{name}[{i}]", v)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        for f in dataclasses.fields(value):
            if f.name not in SKIP:
                _feed(h, f"{name}.{f.name}", getattr(value, f.name))
    elif isinstance(value, (float, np.floating)):
        h.update(float(value).hex().encode())
    elif callable(value):
        h.update(type(value).__name__.encode())
    elif hasattr(value, "__dict__") and not isinstance(value, type):
        h.update(type(value).__name__.encode())
        _feed(h, name, {k: v for k, v in vars(value).items()})
    else:                                 # object addresses differ from run to run
        h.update(re.sub(r" at 0x[0-9a-f]+", " at 0x", repr(value)).encode())


def digest(value, extra=()):
    """sha256 of a result (and of the named derived attributes in ``extra``)."""
    h = hashlib.sha256()
    _feed(h, "result", value)
    for name in extra:
        try:
            v = getattr(value, name)
        except Exception as exc:          # a derived field a result refuses: hash the refusal
            v = f"{type(exc).__name__}: {exc}"
        _feed(h, name, v)
    return h.hexdigest()


CONTACT_EXTRA = ("separation", "stiffness", "elastic_energy", "success", "message")


def cases():
    """(name, thunk) pairs; each thunk returns the object to hash."""
    seed = pf.seed_scene()
    es = pf.seed_e_star()
    wa = pf.SEED_WORK_OF_ADHESION
    affine = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    hard = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e9, h_rms=1e-7)
    q = np.geomspace(1e4, 1e8, 60)
    tab = pf.TabulatedPSD(q, 1e-28 * (q / 1e4) ** -2.6)
    p_seed = np.array([-2e5, -5e4, 0.0, 1e4, 1e5, 3e5, 1e6, 3e6])
    p_pos = np.array([1e4, 1e5, 1e6, 1e7])
    p_aff = np.array([1e5, 1e6, 1e7, 1e8])

    G = np.linspace(0.0, 4.0, 41)
    walls = {
        "flat": 0.0,
        "const": 0.3,
        "linear": 0.1 + 0.2 * G,
        "kinked": np.where(G < 1.5, 0.2, 0.2 - 0.15 * (G - 1.5)).clip(0.0),
        "callable": lambda g: 0.15 + 0.05 * np.sqrt(g),
    }
    out = []
    for m in ["cn", "cn-plain", "implicit-euler", "fixed-grid", "bnr", "analytic"]:
        for wname, wall in walls.items():
            if m == "analytic" and wname not in ("flat", "const", "linear"):
                continue
            for rtol in (1e-4, 1e-6):
                out.append((f"diffusion/{m}/{wname}/{rtol:g}",
                            lambda m=m, wall=wall, rtol=rtol: pf.solve_diffusion(
                                G, [0.05, 0.4, 1.0, 2.5], wall, method=m, rtol=rtol)))
    for wname in ("const", "kinked", "callable"):
        out.append((f"diffusion/strip/{wname}", lambda wall=walls[wname]: pf.solve_diffusion(
            G, [0.05, 0.4, 1.0, 2.5], wall, sigma_y=3.0, rtol=1e-5)))
    out.append(("diffusion/yield-auto", lambda: pf.solve_diffusion(
        G, [0.05, 0.4, 1.0, 2.5], 0.0, sigma_y=3.2, rtol=1e-6)))
    out.append(("diffusion/yield-callable", lambda: pf.solve_diffusion(
        G, [0.05, 0.4, 1.0, 2.5], 0.1, sigma_y=lambda g: 3.0 + 0.3 * g, rtol=1e-5)))
    for par in (False, "threads", "prange"):
        out.append((f"diffusion/cn/parallel={par}", lambda par=par: pf.solve_diffusion(
            G, np.linspace(0.01, 3.0, 37), walls["linear"], method="cn", rtol=1e-6,
            parallel=par)))

    # contact without adhesion
    for m in ("auto", "analytic", "cn", "bnr", "fixed-grid"):
        out.append((f"contact/seed/{m}", lambda m=m: pf.solve_contact(
            seed, p_pos, e_star=es, method=m, rtol=1e-6)))
    out.append(("contact/affine/auto", lambda: pf.solve_contact(affine, p_aff, e_star=1e9)))
    out.append(("contact/tab/auto", lambda: pf.solve_contact(tab, p_aff, e_star=1e9)))
    out.append(("contact/affine/S", lambda: pf.solve_contact(
        affine, p_aff, e_star=1e9, energy_correction=0.45)))
    for th in ("persson01", "yp08", "wm17", "xu24"):
        out.append((f"contact/affine/{th}", lambda th=th: pf.solve_contact(
            affine, p_aff, e_star=1e9, theory=th, rtol=1e-5)))
    # yield
    hards = {
        "const": 3e7,
        "power": pf.hardness_power_law(2e7, 0.1),
        "nixgao": pf.hardness_nix_gao(2e7, 1e-6, 1e4),
        "table": pf.hardness_table([1.0, 10.0, 1e3, 1e5], [2e7, 3e7, 5e7, 8e7]),
        "callable": lambda z: 2e7 * (1 + 0.1 * np.log(z)),
    }
    for hname, hd in hards.items():
        out.append((f"contact/affine/hardness-{hname}", lambda hd=hd: pf.solve_contact(
            affine, p_aff[:3], e_star=1e9, hardness=hd, rtol=1e-5)))
    # adhesion
    for rtol in (1e-4, 1e-5):
        out.append((f"contact/seed/adhesive/{rtol:g}", lambda rtol=rtol: pf.solve_contact(
            seed, p_seed, e_star=es, work_of_adhesion=wa, rtol=rtol)))
    for par in (False, "threads", "prange"):
        out.append((f"contact/seed/adhesive/parallel={par}", lambda par=par: pf.solve_contact(
            seed, p_seed, e_star=es, work_of_adhesion=wa, rtol=1e-4, parallel=par)))
    out.append(("contact/seed/adhesive/S", lambda: pf.solve_contact(
        seed, p_seed, e_star=es, work_of_adhesion=wa, energy_correction=0.45, rtol=1e-4)))
    out.append(("contact/seed/adhesive/beta", lambda: pf.solve_contact(
        seed, p_seed, e_star=es, work_of_adhesion=wa, detachment_prefactor=0.9, rtol=1e-4)))
    for th in ("yp08", "wm17"):
        out.append((f"contact/seed/adhesive/{th}", lambda th=th: pf.solve_contact(
            seed, p_seed, e_star=es, work_of_adhesion=wa, theory=th, rtol=1e-4)))
    out.append(("contact/seed/adhesive/hardness", lambda: pf.solve_contact(
        seed, p_seed, e_star=es, work_of_adhesion=wa, hardness=3e8, rtol=1e-4)))
    out.append(("contact/hard/adhesive", lambda: pf.solve_contact(
        hard, [1e6, 5e6], e_star=1e9, work_of_adhesion=0.05, rtol=1e-4)))
    out.append(("contact/tab/adhesive", lambda: pf.solve_contact(
        tab, [0.0, 1e5, 1e6], e_star=1e9, work_of_adhesion=0.02, rtol=1e-4)))
    out.append(("contact/scene-form", lambda: pf.solve_contact(
        pf.Scene(seed, e_star=es, work_of_adhesion=wa), [1e5, 1e6], rtol=1e-4)))
    out.append(("contact/zeta-given", lambda: pf.solve_contact(
        seed, p_pos, e_star=es, zeta=np.geomspace(1, seed.q1 / seed.q0, 20))))

    # pull-off
    out.append(("pull_off/seed/1e-3", lambda: pf.pull_off(
        seed, e_star=es, work_of_adhesion=wa, rtol=1e-3, full_output=True)))
    out.append(("pull_off/seed/1e-4", lambda: pf.pull_off(
        seed, e_star=es, work_of_adhesion=wa, rtol=1e-4)))
    for th in ("yp08", "wm17"):
        out.append((f"pull_off/seed/{th}", lambda th=th: pf.pull_off(
            seed, e_star=es, work_of_adhesion=wa, theory=th, rtol=1e-3)))
    out.append(("pull_off/seed/hardness", lambda: pf.pull_off(
        seed, e_star=es, work_of_adhesion=wa, hardness=3e8, rtol=1e-3)))

    # separation, gaps, analytic
    out.append(("separation/seed", lambda: pf.solve_separation(seed, p_pos, e_star=es)))
    out.append(("separation/affine/S", lambda: pf.solve_separation(
        affine, p_aff, e_star=1e9, energy_correction=0.42)))
    out.append(("separation/inverse", lambda: pf.pressure_at_separation(
        seed, [1e-9, 3e-9, 1e-8], e_star=es)))
    out.append(("separation/decay", lambda: pf.decay_length(seed, e_star=es)))
    for shape in ("truncated", "folded"):
        out.append((f"gaps/seed/{shape}", lambda shape=shape: pf.gap_distribution(
            seed, p_pos, e_star=es, shape=shape, rtol=1e-3)))
    out.append(("gaps/affine/given", lambda: pf.gap_distribution(
        affine, [1e6, 1e7], e_star=1e9, gaps=np.geomspace(1e-10, 1e-6, 50), rtol=1e-3)))
    out.append(("analytic", lambda: [
        pf.contact_area_no_adhesion(seed, p_pos, e_star=es) if _accepts_surface() else None,
        pf.images_area(np.array([0.5, 1.0]), np.array([0.1, 1.0, 4.0]), 0.2)
        if _try(lambda: pf.images_area(np.array([0.5, 1.0]), np.array([0.1, 1.0, 4.0]), 0.2))
        else None,
    ]))
    out.append(("zeta/adhesion", lambda: pf.adhesion_zeta(seed, rtol=1e-5)))
    out.append(("zeta/default", lambda: pf.default_zeta(affine)))
    out.append(("surface/tab-from-heights", lambda: _from_heights()))

    # scan
    out.append(("scan/affine", lambda: _scan(pf.scan(
        pf.SelfAffine, {"hurst": [0.7, 0.8], "q0": [1e4], "q1": [1e9], "h_rms": [1e-6]},
        p_aff, e_star=1e9, separation=True, workers=1))))
    out.append(("scan/seed-adhesive", lambda: _scan(pf.scan(
        seed, {}, p_seed, e_star=es, work_of_adhesion=wa, rtol=1e-4, pull_off=True,
        pull_off_rtol=1e-3, profiles=True, workers=1))))

    # embed
    out.append(("embed", _embed))
    # command line
    out.append(("cli/contact", _cli))
    return out


def _try(f):
    try:
        f()
        return True
    except Exception:
        return False


def _accepts_surface():
    return _try(lambda: pf.contact_area_no_adhesion(pf.seed_scene(), [1e5], e_star=pf.seed_e_star()))


def _from_heights():
    rng = np.random.default_rng(3)
    h = rng.standard_normal((64, 64)) * 1e-7
    s = pf.TabulatedPSD.from_heights(h, 1e-6)
    return vars(s)


def _scan(ds):
    return {name: np.asarray(ds[name].values) for name in sorted(ds.data_vars)
            if ds[name].dtype.kind in "fiub"}


def _embed():
    from persson_fast import embed
    G = np.linspace(0.0, 4.0, 41)
    wall = 0.1 + 0.05 * G
    res = [embed.diffusion_area(G, wall, 0.7, 1e-6),
           embed.elastoplastic_area(G, wall, np.full_like(G, 1.5), 0.7, 1e-5)]
    outs = [np.zeros(41) for _ in range(5)]
    res.append((embed.diffusion_solve(G, wall, 0.7, 1e-6, 0, *outs), outs))
    scene = embed.adhesive_scene(pf.seed_scene(), e_star=pf.seed_e_star(),
                                 work_of_adhesion=pf.SEED_WORK_OF_ADHESION, rtol=1e-4)
    res.append(scene)
    res.append([embed.adhesive_area(scene, p, 1e-4) for p in (-1e5, 0.0, 1e5, 1e6)])
    law = embed.contact_law(pf.seed_scene(), e_star=pf.seed_e_star(), rtol=1e-6)
    res.append(law)
    u = np.geomspace(1e-10, 1e-7, 30)
    res.append([embed.law_pressure(law.table, x) for x in u])
    res.append([embed.law_stiffness(law.table, x) for x in u])
    res.append([embed.law_pressure_stiffness(law.table, x) for x in u])
    res.append([embed.law_separation(law.table, p) for p in (1e4, 1e5, 1e6)])
    res.append(embed.law_status(law.table))
    op, ok, st = np.zeros(30), np.zeros(30), np.zeros(30, dtype=np.int64)
    embed.law_sweep(law.table, u, op, ok, st)
    res.append((op, ok, st))
    return res


def _cli():
    with tempfile.TemporaryDirectory() as d:
        csv = os.path.join(d, "out.csv")
        gaps = os.path.join(d, "gaps.csv")
        aff = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e7", "--h-rms", "1e-8", "--e-star", "1e9"]
        cmds = [
            ["contact", *aff, "--work-of-adhesion", "0.01", "--pressure-range", "-1e3", "1e6",
             "7", "--rtol", "1e-4", "--pull-off", "--csv", csv, "--quiet"],
            ["contact", *aff, "--hardness", "3e7", "--pressure-range", "1e4", "1e6", "5",
             "--csv", csv, "--quiet"],
            ["contact", *aff, "--pressure-range", "1e4", "1e6", "4", "--separation",
             "--csv", csv, "--gaps", gaps, "--quiet"],
            ["figure2", "--no-plot", "--rtol", "1e-4", "--quiet"],
        ]
        out = []
        for c in cmds:
            r = subprocess.run([sys.executable, "-m", "persson_fast.cli", *c],
                               capture_output=True, text=True, cwd=d)
            if r.returncode:
                print(r.stderr[-2000:], file=sys.stderr)
            files = []
            for f in (csv, gaps, os.path.join(d, "figure2.csv")):
                if os.path.exists(f):
                    files.append(open(f, "rb").read())
                    os.remove(f)
            out.append((r.returncode, files))
        return out


def write_pickles(directory):
    os.makedirs(directory, exist_ok=True)
    seed = pf.seed_scene()
    es = pf.seed_e_star()
    objs = {
        "surface_seed": seed,
        "surface_affine": pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6),
        "surface_tab": pf.TabulatedPSD(np.geomspace(1e4, 1e8, 20),
                                       1e-28 * np.geomspace(1, 1e4, 20) ** -2.6),
        "scene": pf.Scene(seed, e_star=es, work_of_adhesion=pf.SEED_WORK_OF_ADHESION,
                          hardness=pf.hardness_power_law(2e8, 0.1)),
        "contact_result": pf.solve_contact(seed, [1e5, 1e6], e_star=es,
                                           work_of_adhesion=pf.SEED_WORK_OF_ADHESION,
                                           rtol=1e-4),
        "contact_result_yield": pf.solve_contact(seed, [1e5, 1e6], e_star=es, hardness=3e8),
        "diffusion_result": pf.solve_diffusion(np.linspace(0, 1, 11), [0.5, 1.0], 0.1),
        "separation_result": pf.solve_separation(seed, [1e5, 1e6], e_star=es),
        "gap_distribution": pf.gap_distribution(seed, [1e5, 1e6], e_star=es, rtol=1e-2),
    }
    for name, obj in objs.items():
        with open(os.path.join(directory, name + ".pkl"), "wb") as f:
            pickle.dump(obj, f, protocol=4)
        with open(os.path.join(directory, name + ".sha256"), "w") as f:
            f.write(digest(obj) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, help="JSON file to write {case: sha256}")
    ap.add_argument("--compare", help="JSON file of an earlier run to compare against")
    ap.add_argument("--only", help="run only the cases whose name contains this text")
    ap.add_argument("--pickles", help="folder to write pickles of each kind of object into")
    args = ap.parse_args(argv)
    if args.pickles:
        write_pickles(args.pickles)
    result = {}
    t0 = time.perf_counter()
    for name, thunk in cases():
        if args.only and args.only not in name:
            continue
        t = time.perf_counter()
        try:
            value = thunk()
            extra = CONTACT_EXTRA if isinstance(value, pf.ContactResult) else ()
            result[name] = digest(value, extra)
        except Exception as exc:
            result[name] = f"raised {type(exc).__name__}: {exc}"
        print(f"{name:45s} {time.perf_counter() - t:7.2f} s  {result[name][:16]}",
              flush=True)
    print(f"total {time.perf_counter() - t0:.1f} s")
    with open(args.out, "w") as f:
        json.dump(result, f, indent=1, sort_keys=True)
    if args.compare:
        with open(args.compare) as f:
            old = json.load(f)
        if args.only:                     # compare the cases that ran
            old = {k: v for k, v in old.items() if args.only in k}
        diff = [k for k in sorted(set(old) | set(result)) if old.get(k) != result.get(k)]
        for k in diff:
            print(f"DIFFERS {k}: {old.get(k, '-')[:40]} -> {result.get(k, '-')[:40]}")
        print(f"{len(result) - len(diff)} of {len(result)} equal")
        return 1 if diff else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
