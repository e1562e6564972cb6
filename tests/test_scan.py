"""Tests of persson_fast.scan: labels and values against direct solve_contact calls, input
validation, the distributed path (bitwise equal to the local one), interrupts, progress."""
import dataclasses
import importlib
import threading
import time
import warnings

import numpy as np
import pytest

import persson_fast as pf

xr = pytest.importorskip("xarray")
distributed = pytest.importorskip("distributed")

from persson_fast.scan.api import scan  # noqa: E402  (after the optional-dependency skips)

# the module itself (``persson_fast.scan`` may be shadowed by the function in the package)
scan_module = importlib.import_module("persson_fast.scan.run")
#: where a scan's scenes are solved (the names a test patches: solve_contact, _pull_off,
#: _stderr_is_terminal are looked up there)
scan_run = importlib.import_module("persson_fast.scan.run")

E_STAR = 2.9e9 / (1.0 - 0.3**2)             # seed PMMA [Pa]
SEED = pf.seed_scene()
SEED_KW = {"surface_tension": 0.04, "q_c": 1.7e9, "q0": SEED.q0, "q1": 7e9}
P_PLAIN = np.linspace(0.0, 4e7, 9)                        # [Pa]
P_ADH = np.array([-0.3e6, 0.0, 1e6, 1e7, 5e7])            # tension included [Pa]
SA_PARAMS = {"hurst": [0.6, 0.8], "h_rms": [1e-7, 3e-7, 1e-6], "q0": 1e4, "q1": 1e9}


@pytest.fixture(scope="module", autouse=True)
def _warm_kernels():
    """Load only the serial kernels (disk-cached, about 1 s).

    Replaces the suite-wide warm-up for this module: scans run the serial kernels (threads
    over scenes, or one chunk after another on a worker), and compiling the parallel ones,
    which are not cached on disk, would cost 5-15 s per process without being used here.
    """
    pf.warmup(False)


def _bitwise_equal(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def _assert_datasets_bitwise_equal(a, b):
    assert a.sizes == b.sizes
    assert set(a.data_vars) == set(b.data_vars)
    for name in a.variables:
        va, vb = a[name].values, b[name].values
        if va.dtype.kind in "fiub":
            assert _bitwise_equal(va, vb), name
        else:
            assert np.array_equal(va, vb), name


@pytest.fixture(scope="module")
def adhesive_scan():
    """Seed-like capillary waves at two temperatures, with and without adhesion."""
    return scan(pf.CapillaryWaves, {"temperature": [350.0, 370.0], "work_of_adhesion": [0.0, 0.06],
                                    **SEED_KW},
                P_ADH, e_star=E_STAR, rtol=1e-3, profiles=True, pull_off=True, progress=False)


# ---------------------------------------------------------------------------------------------
# labels, shapes and values against direct calls
# ---------------------------------------------------------------------------------------------
def test_closed_form_scan_equals_direct_calls():
    ds = scan(pf.SelfAffine, SA_PARAMS, P_PLAIN, e_star=1e9, progress=False)
    assert ds.area.dims == ("hurst", "h_rms", "pressure")
    assert ds.area.shape == (2, 3, P_PLAIN.size)
    assert ds.success.dims == ("hurst", "h_rms")
    np.testing.assert_array_equal(ds.hurst.values, [0.6, 0.8])
    np.testing.assert_array_equal(ds.h_rms.values, [1e-7, 3e-7, 1e-6])
    np.testing.assert_array_equal(ds.pressure.values, P_PLAIN)
    assert float(ds.q0) == 1e4 and float(ds.q1) == 1e9            # fixed: scalar coordinates
    assert ds.h_rms.attrs["units"] == "m" and ds.area.attrs["units"] == "-"
    for i, h in enumerate(SA_PARAMS["hurst"]):
        for j, hr in enumerate(SA_PARAMS["h_rms"]):
            r = pf.solve_contact(pf.SelfAffine(hurst=h, h_rms=hr, q0=1e4, q1=1e9), P_PLAIN,
                                 e_star=1e9)
            assert _bitwise_equal(ds.area.values[i, j], r.area)
            assert _bitwise_equal(ds.status.values[i, j], r.status)
            np.testing.assert_array_equal(ds.mean_contact_pressure.values[i, j],
                                          r.mean_contact_pressure)
            assert bool(ds.success.values[i, j]) and ds.message.values[i, j] == r.message
    assert len(ds.to_dataframe()) == 2 * 3 * P_PLAIN.size          # tidy: a row per point


def test_cn_scan_on_threads_equals_direct_calls_and_sequential():
    params = {"hurst": [0.6, 0.7, 0.8], "h_rms": 1e-6, "q0": 1e4, "q1": 1e8}
    ds = scan(pf.SelfAffine, params, P_PLAIN[1:], e_star=1e9, method="cn", rtol=1e-4,
              workers=2, progress=False)
    assert ds.attrs["execution"].startswith("local, 2 threads")
    for i, h in enumerate(params["hurst"]):
        r = pf.solve_contact(pf.SelfAffine(hurst=h, h_rms=1e-6, q0=1e4, q1=1e8), P_PLAIN[1:],
                             e_star=1e9, method="cn", rtol=1e-4)
        assert _bitwise_equal(ds.area.values[i], r.area)
        assert ds.method.values[i] == "cn"
    seq = scan(pf.SelfAffine, params, P_PLAIN[1:], e_star=1e9, method="cn", rtol=1e-4,
               workers=1, progress=False)
    assert seq.attrs["execution"] == "local, sequential"
    _assert_datasets_bitwise_equal(ds, seq)


def test_adhesive_scan_equals_direct_calls(adhesive_scan):
    ds = adhesive_scan
    assert ds.area.dims == ("temperature", "work_of_adhesion", "pressure")
    assert ds.area_zeta.dims == ("temperature", "work_of_adhesion", "pressure", "zeta")
    assert ds.pull_off.dims == ("temperature", "work_of_adhesion")
    for i, temp in enumerate([350.0, 370.0]):
        surface = pf.CapillaryWaves(temperature=temp, **SEED_KW)
        # without adhesion: tension separates the surfaces (A = 0, no solve)
        plain = ds.isel(temperature=i, work_of_adhesion=0)
        r0 = pf.solve_contact(surface, P_ADH[1:], e_star=E_STAR, rtol=1e-3,
                              zeta=ds.zeta.values)
        assert plain.area.values[0] == 0.0 and np.isnan(plain.mean_contact_pressure.values[0])
        assert _bitwise_equal(plain.area.values[1:], r0.area)
        assert _bitwise_equal(plain.area_zeta.values[1:], r0.area_zeta)
        assert float(plain.pull_off) == 0.0 and float(plain.pull_off_error) == 0.0
        assert bool(plain.success) and plain.message.values == "ok"   # no adhesion: no pull-off
        # with adhesion: all pressures, the default zeta grid, pull-off
        adh = ds.isel(temperature=i, work_of_adhesion=1)
        r1 = pf.solve_contact(surface, P_ADH, e_star=E_STAR, work_of_adhesion=0.06, rtol=1e-3)
        assert _bitwise_equal(adh.area.values, r1.area)
        assert _bitwise_equal(adh.status.values, r1.status)
        assert _bitwise_equal(adh.sigma_a.values, r1.sigma_a)
        assert _bitwise_equal(adh.gamma_eff.values, r1.gamma_eff)
        np.testing.assert_array_equal(ds.zeta.values, r1.zeta)
        sigma_c = pf.pull_off(surface, e_star=E_STAR, work_of_adhesion=0.06, rtol=1e-3)
        assert float(adh.pull_off) == sigma_c > 0
        assert adh.area.values[0] > 0                # -0.3 MPa is above -sigma_c: contact


def test_surface_instance_scans_solve_parameters():
    ds = scan(SEED, {"e_star": [1e9, 3e9]}, [1e6, 1e7], progress=False)
    for k, e in enumerate([1e9, 3e9]):
        r = pf.solve_contact(SEED, [1e6, 1e7], e_star=e)
        assert _bitwise_equal(ds.area.values[k], r.area)
    assert ds.attrs["surface_model"] == "CapillaryWaves"


def test_no_scanned_parameter_gives_pressure_axis_only():
    ds = scan(SEED, {}, 5e6, e_star=E_STAR, progress=False)
    assert ds.area.dims == ("pressure",)
    assert ds.area.values[0] == pf.solve_contact(SEED, [5e6], e_star=E_STAR).area[0]


# ---------------------------------------------------------------------------------------------
# validation: argument, rule and offending value
# ---------------------------------------------------------------------------------------------
def _sa(**extra):
    return {"hurst": [0.7], "h_rms": 1e-6, "q0": 1e4, "q1": 1e9, **extra}


@pytest.mark.parametrize("kwargs, match", [
    ({"params": [("hurst", [0.5])]}, r"params must be a dict"),
    ({"params": _sa(hurts=[0.1])}, r"params key 'hurts' is neither a parameter of SelfAffine"),
    ({"params": _sa(pressure=[1.0])}, r"params cannot hold 'pressure'"),
    ({"params": {**_sa(), "hurst": []}}, r"params\['hurst'\] must hold at least one value"),
    ({"params": {**_sa(), "hurst": [0.5, 0.5]}}, r"must hold distinct values.*0\.5"),
    ({"params": {**_sa(), "hurst": [0.5, np.nan]}},
     r"params\['hurst'\] must be finite.*\[1\] = nan"),
    ({"params": {**_sa(), "hurst": [[0.5, 0.6]]}}, r"1-D sequence.*shape \(1, 2\)"),
    ({"params": {**_sa(), "hurst": [0.5, 1.5]}},
     r"scene \(hurst=1\.5\).*hurst must be in \[0, 1\]"),
    ({"params": _sa(e_star=[1e9, -1.0]), "e_star": None},
     r"params\['e_star'\]\[1\] must be > 0 \[Pa\].*-1\.0"),
    ({"params": _sa(work_of_adhesion=[0.1]), "work_of_adhesion": 0.2},
     r"work_of_adhesion is given twice"),
    ({"params": _sa(energy_correction=[0.5, 2.0])},
     r"energy_correction.*must lie in \[0, 1\].*2\.0"),
    ({"e_star": None}, r"e_star must be given"),
    ({"work_of_adhesion": -0.1},
     r"work_of_adhesion must be >= 0 \[J/m\^2\]; got work_of_adhesion = -0\.1"),
    ({"pressure": [1e6, np.nan]}, r"pressure must be finite \[Pa\]; got pressure\[1\] = nan"),
    ({"pressure": []}, r"pressure must hold at least one"),
    ({"rtol": 1.0}, r"rtol must lie in \[1e-12, 0\.1\].*1\.0"),
    ({"method": "rk4"}, r"method must be one of .*'cn'.*got method = 'rk4'"),
    ({"method": "analytic", "work_of_adhesion": 0.05},
     r"'analytic' has no closed form with adhesion"),
    ({"chunks": 0}, r"chunks must be a positive integer.*0"),
    ({"workers": -1}, r"workers must be a positive integer.*-1"),
    ({"progress": "yes"}, r"progress must be None, True, False or a callable"),
    ({"profiles": "yes"}, r"profiles must be True or False"),
    ({"zeta": [1.0, 1e6]}, r"zeta must lie in \[1, q1/q0\].*1000000\.0"),
    ({"zeta": [2.0, 3.0]}, r"zeta must start at 1"),
    ({"zeta": [1.0, 1e3]}, r"zeta must end at q1/q0.*\(hurst=0\.7\).*100000\.0.*1000\.0"),
    ({"client": 42}, r"client must be None, 'local', a scheduler address or a dask"),
    ({"surface": SEED, "params": {"hurst": [0.5]}}, r"params\['hurst'\] is a surface parameter"),
    ({"params": {"hurst": 0.8, "h_rms": 1e-6, "q0": 1e4, "q1": [1e8, 1e9]}, "profiles": True},
     r"profiles=True needs one zeta grid for all scenes.*pass zeta="),
])
def test_validation_errors(kwargs, match):
    call = {"surface": pf.SelfAffine, "params": _sa(), "pressure": [1e6], "e_star": 1e9,
            "progress": False}
    call.update(kwargs)
    with pytest.raises(ValueError, match=match):
        scan(call.pop("surface"), call.pop("params"), call.pop("pressure"), **call)


# ---------------------------------------------------------------------------------------------
# progress
# ---------------------------------------------------------------------------------------------
def test_progress_bar_on_off_and_callback(capsys, monkeypatch):
    params = {"hurst": np.linspace(0.5, 0.9, 60), "h_rms": 1e-6, "q0": 1e4, "q1": 1e9}
    scan(pf.SelfAffine, params, [1e6], e_star=1e9, progress=True)
    assert "scene" in capsys.readouterr().err
    scan(pf.SelfAffine, params, [1e6], e_star=1e9, progress=False)
    assert capsys.readouterr().err == ""
    scan(pf.SelfAffine, params, [1e6], e_star=1e9)           # None, stderr not a terminal
    assert capsys.readouterr().err == ""
    monkeypatch.setattr(scan_run, "_stderr_is_terminal", lambda: True)
    scan(pf.SelfAffine, params, [1e6], e_star=1e9)           # None, terminal, > 50 scenes
    assert "60/60" in capsys.readouterr().err
    scan(pf.SelfAffine, {**params, "hurst": [0.5, 0.6]}, [1e6], e_star=1e9)  # short scan
    assert capsys.readouterr().err == ""
    seen = []
    scan(pf.SelfAffine, {**params, "hurst": [0.5, 0.6, 0.7]}, [1e6], e_star=1e9,
         progress=lambda done, total: seen.append((done, total)))
    assert seen == [(1, 3), (2, 3), (3, 3)]


def test_keyboard_interrupt_local_leaves_no_threads():
    params = {"hurst": np.linspace(0.5, 0.9, 8), "h_rms": 1e-6, "q0": 1e4, "q1": 1e8}

    def interrupt(done, total):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        scan(pf.SelfAffine, params, P_PLAIN[1:], e_star=1e9, method="cn", rtol=1e-3,
             workers=2, progress=interrupt)
    assert not [t for t in threading.enumerate() if t.name.startswith("persson-scan")]


# ---------------------------------------------------------------------------------------------
# failures: recorded per scene, never "ok ...", one warning per scan
# ---------------------------------------------------------------------------------------------
SA_CN = {"hurst": [0.6, 0.7, 0.8], "h_rms": 1e-6, "q0": 1e4, "q1": 1e8}


def _scan_warnings(record):
    return [w for w in record if w.category.__name__ == "ScanWarning"]


def _fail_at(monkeypatch, name, hursts, exc):
    """Make scan's ``name`` (``solve_contact`` or ``_pull_off``) raise ``exc`` for the scenes
    whose surface has one of the Hurst exponents ``hursts``."""
    real = getattr(scan_run, name)

    def fake(surface, *args, **kwargs):
        if getattr(surface, "hurst", None) in hursts:
            raise exc
        return real(surface, *args, **kwargs)

    monkeypatch.setattr(scan_run, name, fake)


@pytest.mark.parametrize("workers", [1, 2])
def test_scene_that_raises_is_recorded_and_the_scan_goes_on(monkeypatch, workers):
    _fail_at(monkeypatch, "solve_contact", (0.7,), ValueError("boom in scene 0.7"))
    filters = list(warnings.filters)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        ds = scan(pf.SelfAffine, SA_CN, P_PLAIN[1:], e_star=1e9, method="cn", rtol=1e-3,
                  workers=workers, progress=False)
    assert ds.attrs["execution"] == ("local, sequential" if workers == 1
                                     else "local, 2 threads over scenes")
    np.testing.assert_array_equal(ds.success.values, [True, False, True])
    bad = ds.sel(hurst=0.7)
    assert np.all(np.isnan(bad.area.values)) and np.all(np.isnan(bad.error_estimate.values))
    assert np.all(bad.status.values == scan_module.SCENE_ERROR)
    assert bad.message.values == "solve_contact raised ValueError: boom in scene 0.7"
    for h in (0.6, 0.8):                                   # the other scenes: as direct calls
        r = pf.solve_contact(pf.SelfAffine(hurst=h, h_rms=1e-6, q0=1e4, q1=1e8), P_PLAIN[1:],
                             e_star=1e9, method="cn", rtol=1e-3)
        assert _bitwise_equal(ds.area.sel(hurst=h).values, r.area)
        assert ds.message.sel(hurst=h).values == r.message == "ok"
    (w,) = _scan_warnings(record)
    text = str(w.message)
    assert "1 of 3 scenes failed" in text
    assert "(hurst=0.7): solve_contact raised ValueError: boom in scene 0.7" in text
    assert list(warnings.filters) == filters               # no filter leaks from the threads


def test_failed_message_never_starts_with_ok(monkeypatch):
    # solve_contact succeeds with a note ("ok; ...", as when it cannot check separated
    # tensions against the pull-off stress), then the scene's pull-off fails
    real_solve = scan_run.solve_contact

    def noted(surface, *args, **kwargs):
        r = real_solve(surface, *args, **kwargs)
        return dataclasses.replace(r, message=r.message + "; a note")

    monkeypatch.setattr(scan_run, "solve_contact", noted)
    _fail_at(monkeypatch, "_pull_off", (0.7,),
             RuntimeError("pull_off: the contact branch could not be followed"))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        ds = scan(pf.SelfAffine, SA_CN, P_PLAIN, e_star=1e9, pull_off=True, progress=False)
    np.testing.assert_array_equal(ds.success.values, [True, False, True])
    assert ds.message.sel(hurst=0.6).values == "ok; a note"    # a success keeps its message
    failed = str(ds.message.sel(hurst=0.7).values)
    assert not failed.lower().startswith("ok")
    assert failed == ("pull_off raised RuntimeError: the contact branch could not be followed; "
                      "solve_contact: ok; a note")
    assert np.isnan(ds.pull_off.sel(hurst=0.7)) and float(ds.pull_off.sel(hurst=0.6)) == 0.0
    assert np.all(np.isfinite(ds.area.sel(hurst=0.7).values))  # the solve itself succeeded
    assert len(_scan_warnings(record)) == 1


def test_failures_warn_once_with_count_and_worst_scenes(monkeypatch):
    hursts = [0.5, 0.6, 0.7, 0.8, 0.9]
    _fail_at(monkeypatch, "_pull_off", (0.5, 0.6), RuntimeError("pull_off: no branch"))
    _fail_at(monkeypatch, "solve_contact", (0.8, 0.9), FloatingPointError("overflow"))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        ds = scan(pf.SelfAffine, {**SA_CN, "hurst": hursts}, P_PLAIN, e_star=1e9,
                  pull_off=True, progress=False)
    np.testing.assert_array_equal(ds.success.values, [False, False, True, False, False])
    assert all(not m.startswith("ok") for m in ds.message.values[[0, 1, 3, 4]])
    assert [w.category.__name__ for w in record] == ["ScanWarning"]       # one warning only
    assert issubclass(record[0].category, UserWarning)
    text = str(record[0].message)
    n_points = 2 * P_PLAIN.size                # the raised solves: every pressure flagged
    assert "4 of 5 scenes failed" in text and f"{n_points} of {5 * P_PLAIN.size}" in text
    # the worst first: no numbers at all (a raised solve), then a failed pull-off
    named = [line.split(":")[0].strip() for line in text.splitlines()[1:]]
    assert named == ["(hurst=0.8)", "(hurst=0.9)", "(hurst=0.5)", "... and 1 more"]
    assert "FloatingPointError: overflow" in text and "pull_off raised RuntimeError" in text
    assert record[0].filename == __file__                # points at the caller of scan


def test_unconverged_pull_off_is_flagged_and_kept(monkeypatch):
    def unconverged(surface, **kwargs):
        warnings.warn("pull_off: estimated error exceeds rtol", RuntimeWarning)
        info = {"converged": False, "error_estimate": 2.5e3}
        return (1.5e5, info) if kwargs.get("full_output") else 1.5e5

    monkeypatch.setattr(scan_run, "_pull_off", unconverged)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        ds = scan(SEED, {"e_star": [1e9, 2e9]}, [1e6], pull_off=True, progress=False)
    assert not ds.success.values.any()
    np.testing.assert_array_equal(ds.pull_off.values, [1.5e5, 1.5e5])   # the value is kept
    np.testing.assert_array_equal(ds.pull_off_error.values, [2.5e3, 2.5e3])
    assert all(m.startswith("pull_off did not converge: estimated error 2.5e+03 Pa")
               for m in ds.message.values)
    # pull_off's own RuntimeWarning per scene is replaced by the scan's one warning
    assert [w.category.__name__ for w in record] == ["ScanWarning"]
    assert "2 of 2 scenes failed" in str(record[0].message)


def test_scan_without_failures_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = scan(pf.SelfAffine, SA_PARAMS, P_PLAIN, e_star=1e9, pull_off=True, progress=False)
    assert bool(ds.success.all())


# ---------------------------------------------------------------------------------------------
# distributed
# ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=":0")
    cl = distributed.Client(cluster)
    # both workers registered before any test reads the set of workers (on a loaded machine
    # the first test could start while they were still joining, and took an empty set for
    # the workers it must find again)
    cl.wait_for_workers(2, timeout=120)
    yield cl
    cl.close()
    cluster.close()


def _scan_tasks(cl, wait_s=10.0):
    """Keys of scan tasks still on the scheduler, after up to ``wait_s`` for releases."""
    deadline = time.monotonic() + wait_s
    while True:
        keys = cl.run_on_scheduler(lambda dask_scheduler: [
            str(k) for k in dask_scheduler.tasks if "persson-scan" in str(k)])
        if not keys or time.monotonic() > deadline:
            return keys
        time.sleep(0.05)


def test_distributed_equals_local_bitwise(client, adhesive_scan):
    kw = dict(e_star=E_STAR, rtol=1e-3, profiles=True, pull_off=True, progress=False)
    params = {"temperature": [350.0, 370.0], "work_of_adhesion": [0.0, 0.06], **SEED_KW}
    ds = scan(pf.CapillaryWaves, params, P_ADH, client=client, chunks=1, **kw)
    assert ds.attrs["execution"] == "distributed, 4 tasks of <= 1 scenes"
    _assert_datasets_bitwise_equal(ds, adhesive_scan)
    plain = scan(pf.SelfAffine, SA_PARAMS, P_PLAIN[1:], e_star=1e9, method="cn", rtol=1e-4,
                 progress=False)
    dist = scan(pf.SelfAffine, SA_PARAMS, P_PLAIN[1:], e_star=1e9, method="cn", rtol=1e-4,
                progress=False, client=client, chunks=4)      # chunks of 4 and 2 scenes
    assert dist.attrs["execution"] == "distributed, 2 tasks of <= 4 scenes"
    _assert_datasets_bitwise_equal(dist, plain)
    assert not _scan_tasks(client)


def test_keyboard_interrupt_cancels_distributed_tasks(client):
    workers_before = set(client.scheduler_info()["workers"])
    params = {"temperature": np.linspace(340.0, 400.0, 8), "work_of_adhesion": 0.06, **SEED_KW}
    calls = []

    def interrupt(done, total):
        calls.append(done)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        scan(pf.CapillaryWaves, params, P_ADH, e_star=E_STAR, rtol=1e-3, client=client,
             chunks=1, progress=interrupt)
    assert calls == [1]
    assert not _scan_tasks(client)                          # nothing left on the scheduler
    assert not [k for k in client.futures if "persson-scan" in str(k)]
    assert set(client.scheduler_info()["workers"]) == workers_before
    assert client.status == "running"                       # the user's client stays theirs


@pytest.mark.slow
def test_own_local_cluster_is_closed_after_interrupt(monkeypatch):
    created = []

    class RecordingCluster(distributed.LocalCluster):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            created.append(self)

    monkeypatch.setattr(distributed, "LocalCluster", RecordingCluster)
    params = {"hurst": [0.6, 0.7, 0.8], "h_rms": 1e-6, "q0": 1e4, "q1": 1e8}
    local = scan(pf.SelfAffine, params, P_PLAIN[1:], e_star=1e9, method="cn", progress=False)
    ds = scan(pf.SelfAffine, params, P_PLAIN[1:], e_star=1e9, method="cn", client="local",
              progress=False)
    _assert_datasets_bitwise_equal(ds, local)

    def interrupt(done, total):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        scan(pf.SelfAffine, params, P_PLAIN[1:], e_star=1e9, method="cn", client="local",
             chunks=1, progress=interrupt)
    assert len(created) == 2
    assert all(str(c.status.name) == "closed" for c in created)


def test_missing_extra_names_the_extra(monkeypatch):
    """Without xarray, pf.scan says which extra to install instead of a bare import error."""
    import sys

    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(ModuleNotFoundError, match=r"persson_fast\[scan\]"):
        pf.scan(pf.SelfAffine, {"hurst": [0.7, 0.8], "h_rms": 1e-6, "q0": 1e4, "q1": 1e9},
                np.array([1e6]), e_star=1e9)


# --- the area theory, held fixed over a scan ------------------------------------------------

def test_scan_theory_matches_solve_contact():
    ds = pf.scan(pf.SelfAffine, {"hurst": [0.5, 0.8], "q0": 1e4, "q1": 1e9, "h_rms": 1e-6},
                 [1e5, 1e6], e_star=1e9, theory="wm17", workers=1)
    assert ds.attrs["theory"] == "wm17" and ds.attrs["theory_gamma"] == pytest.approx(5 / 9)
    for h in (0.5, 0.8):
        s = pf.SelfAffine(hurst=h, q0=1e4, q1=1e9, h_rms=1e-6)
        ref = pf.solve_contact(s, [1e5, 1e6], e_star=1e9, theory="wm17")
        base = pf.solve_contact(s, [1e5, 1e6], e_star=1e9)
        got = ds.area.sel(hurst=h).values
        assert np.array_equal(got, ref.area) and np.all(got > base.area)


def test_scan_theory_with_adhesion_is_refused():
    with pytest.raises(ValueError, match="defined only at full magnification without walls"):
        pf.scan(pf.SelfAffine, {"hurst": 0.8, "q0": 1e4, "q1": 1e9, "h_rms": 1e-6,
                                "work_of_adhesion": [0.0, 0.05]}, [1e6], e_star=1e9,
                theory="xu24")
    with pytest.raises(ValueError, match="theory must be one of"):
        pf.scan(pf.SelfAffine, {"hurst": 0.8, "q0": 1e4, "q1": 1e9, "h_rms": 1e-6}, [1e6],
                e_star=1e9, theory="yp09")


# --- the area theory as an axis --------------------------------------------------------------

THEORY_AXIS = ["persson01", "yp08", "wm17", "xu24"]
SA_ONE = {"hurst": [0.5, 0.8], "q0": 1e4, "q1": 1e9, "h_rms": 1e-6}
P_THEORY = np.array([-1e5, 0.0, 1e5, 1e6, 1e7])                  # tension included [Pa]


def test_scan_theory_axis_equals_fixed_scans():
    """Each entry of a theory axis is bitwise the scan with that theory held fixed."""
    ds = scan(pf.SelfAffine, SA_ONE, P_THEORY, e_star=1e9, theory=THEORY_AXIS, profiles=True,
              pull_off=True, workers=2)
    assert ds.area.dims == ("hurst", "theory", "pressure")
    assert ds.area_zeta.dims == ("hurst", "theory", "pressure", "zeta")
    assert list(ds.theory.values) == THEORY_AXIS
    assert ds.theory_gamma.dims == ("theory",)
    np.testing.assert_array_equal(ds.theory_gamma.values, [np.nan, 0.42, 5 / 9, 0.42])
    assert ds.attrs["theory"] == "" and ds.attrs["theory_gamma"] == ""
    for t in THEORY_AXIS:
        fixed = scan(pf.SelfAffine, SA_ONE, P_THEORY, e_star=1e9, theory=t, profiles=True,
                     pull_off=True, workers=2)
        got = ds.sel(theory=t, drop=True)
        _assert_datasets_bitwise_equal(got, fixed)
        assert all(got[name].dims == fixed[name].dims for name in fixed.data_vars)
        if t != "persson01":
            assert float(ds.theory_gamma.sel(theory=t)) == fixed.attrs["theory_gamma"]
    assert np.all(ds.area.sel(theory="yp08").values[:, 2:]
                  > ds.area.sel(theory="persson01").values[:, 2:])


def test_scan_theory_axis_matches_solve_contact():
    """A theory axis with one theory_gamma: it goes to the corrected theories only."""
    p = [1e5, 1e6]
    ds = scan(pf.SelfAffine, SA_ONE, p, e_star=1e9, theory=("xu24", "persson01", "wm17"),
              theory_gamma=0.6)
    np.testing.assert_array_equal(ds.theory_gamma.values, [0.6, np.nan, 0.6])
    for h, t in [(0.5, "xu24"), (0.8, "persson01"), (0.8, "wm17")]:
        s = pf.SelfAffine(hurst=h, q0=1e4, q1=1e9, h_rms=1e-6)
        ref = pf.solve_contact(s, p, e_star=1e9, theory=t,
                               theory_gamma=None if t == "persson01" else 0.6)
        assert ref.theory == t
        np.testing.assert_array_equal(ds.area.sel(hurst=h, theory=t).values, ref.area)


def test_distributed_theory_axis_equals_local_bitwise(client):
    kw = dict(e_star=1e9, theory=THEORY_AXIS, theory_gamma=0.7, progress=False)
    local = scan(pf.SelfAffine, SA_ONE, P_THEORY, **kw)
    dist = scan(pf.SelfAffine, SA_ONE, P_THEORY, client=client, chunks=3, **kw)
    assert dist.attrs["execution"] == "distributed, 3 tasks of <= 3 scenes"
    _assert_datasets_bitwise_equal(dist, local)
    assert not _scan_tasks(client)


@pytest.mark.parametrize("kwargs, match", [
    ({"theory": []}, r"theory must hold at least one theory .*empty"),
    ({"theory": ["yp08", "wm17", "yp08"]},
     r"theory must hold distinct theories .*theory\[0\] = theory\[2\] = 'yp08'"),
    ({"theory": ["persson01", "yp09"]}, r"theory\[1\] must be one of .*got theory\[1\] = 'yp09'"),
    ({"theory": ["persson01", None]}, r"theory\[1\] must be one of"),
    ({"theory": [["yp08"], ["wm17"]]}, r"1-D sequence of theories .*shape \(2, 1\)"),
    ({"theory": ["persson01"], "theory_gamma": 0.5}, r"theory_gamma must be None for "),
    ({"theory": ["yp08", "wm17"], "theory_gamma": 0.005},
     r"theory_gamma must lie in .*theory='wm17'.*0\.005"),
    ({"theory": ["persson01", "wm17"], "separation": True},
     r"separation=True needs .*theory = 'wm17'"),
])
def test_scan_theory_axis_refusals(kwargs, match):
    with pytest.raises(ValueError, match=match):
        scan(pf.SelfAffine, SA_ONE, [1e6], e_star=1e9, **kwargs)


def test_scan_theory_axis_keeps_the_per_theory_refusals():
    """Adhesion and hardness with a corrected theory of the axis: the ValueErrors of a
    fixed-theory scan (xu24 anywhere on the axis, also after a theory that serves)."""
    adhesive = {**SA_ONE, "work_of_adhesion": [0.0, 0.05]}
    with pytest.raises(ValueError) as fixed:
        scan(pf.SelfAffine, adhesive, [1e6], e_star=1e9, theory="xu24")
    with pytest.raises(ValueError) as axis:
        scan(pf.SelfAffine, adhesive, [1e6], e_star=1e9, theory=["persson01", "yp08", "xu24"])
    assert str(axis.value) == str(fixed.value)
    with pytest.raises(ValueError, match=r"theory='xu24' is defined only at full magnification"
                                         r".*hardness \(the yield wall\)"):
        scan(pf.SelfAffine, SA_ONE, [1e6], e_star=1e9, hardness=3e8,
             theory=["persson01", "wm17", "xu24"])
    with pytest.raises(ValueError, match=r"params cannot hold 'theory'"):
        scan(pf.SelfAffine, {**SA_ONE, "theory": ["yp08", "wm17"]}, [1e6], e_star=1e9)
    ds = scan(pf.SelfAffine, adhesive, [1e6], e_star=1e9, rtol=1e-3, theory=["persson01"])
    assert ds.area.dims == ("hurst", "work_of_adhesion", "theory", "pressure")
