"""Pickles written by 0.1.x (before the modules moved into subpackages) still load, and the
objects they hold work: the surfaces give their spectra, the results their fields."""
import importlib.util
import pathlib
import pickle

import numpy as np
import pytest

import persson_fast as pf

DATA = pathlib.Path(__file__).parent / "data" / "pickles_0.1.0"
NAMES = sorted(p.stem for p in DATA.glob("*.pkl"))
#: the stored pickles were written under NumPy 2, whose arrays pickle as numpy._core objects:
#: NumPy 1.x reads them only from 1.26 on (it has numpy._core for that); with NumPy 1.24/1.25
#: (supported, tested in CI's lowest-versions run) such a pickle cannot load, whatever the
#: package does -- NumPy's rule, said in docs/developer.md
NUMPY2_PICKLES_LOAD = importlib.util.find_spec("numpy._core") is not None
NEEDS_NUMPY_CORE = "NumPy < 1.26 cannot read arrays pickled under NumPy 2 (no numpy._core)"


def _read(name):
    data = (DATA / f"{name}.pkl").read_bytes()
    if b"numpy._core" in data and not NUMPY2_PICKLES_LOAD:
        pytest.skip(NEEDS_NUMPY_CORE)
    return data


def test_the_stored_pickles_are_there():
    assert {"surface_seed", "surface_affine", "surface_tab", "scene", "contact_result",
            "diffusion_result", "separation_result"} <= set(NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_old_pickle_loads(name):
    obj = pickle.loads(_read(name))
    assert type(obj).__module__.startswith("persson_fast.")


def test_old_surfaces_and_results_work():
    load = lambda n: pickle.loads(_read(n))  # noqa: E731
    seed = load("surface_seed")
    assert isinstance(seed, pf.CapillaryWaves)
    assert seed.h_rms() == pf.seed_scene().h_rms()
    tab = load("surface_tab")
    assert isinstance(tab, pf.TabulatedPSD)
    q = np.geomspace(tab.q0, tab.q1, 7)
    assert np.all(np.isfinite(tab.psd(q)))
    scene = load("scene")
    assert isinstance(scene, pf.Scene)
    again = pf.solve_contact(scene.surface, [1e6], e_star=scene.e_star, hardness=scene.hardness)
    assert again.success
    res = load("contact_result")
    fresh = pf.solve_contact(pf.seed_scene(), [1e5, 1e6], e_star=pf.seed_e_star(),
                             work_of_adhesion=pf.SEED_WORK_OF_ADHESION, rtol=1e-4)
    assert isinstance(res, pf.ContactResult)
    np.testing.assert_allclose(res.area, fresh.area, rtol=1e-3)
    assert isinstance(load("separation_result"), pf.SeparationResult)


def test_old_paths_resolve_to_the_new_modules():
    import importlib

    assert importlib.import_module("persson_fast.tabulated").TabulatedPSD is pf.TabulatedPSD
    from persson_fast import surfaces

    assert surfaces.SelfAffine is pf.SelfAffine
    with pytest.raises(AttributeError):
        surfaces.no_such_name
