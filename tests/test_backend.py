"""Backend selection (DCCSS_BACKEND, dccss.mechanics.backend) and the dispatch of models.run,
summaries.summarize and simulate to the kernels, compiled or interpreted.

The fast tests stand in the numpy reference (tests/oracle.py) for the kernels' module (or block
numba's import); the tests marked slow run the compiled kernels and check that they give the
numpy reference's datasets through ``simulate``, failures and capacity policies included, and
that interpreted and compiled kernels give the same bytes."""

import os
import sys
import warnings

import numpy as np
import oracle
import pytest

from dccss.cli import main
from dccss.excitation import Sine, step_times
from dccss.mechanics import backend, models, summaries
from dccss.mechanics.capacity import CapacityError
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.newton import ConvergenceError
from dccss.paper.prototypes import DFP1, TABLE1
from dccss.simulation import simulate

TOL = 1e-10
#: far beyond DFP1's capacity: the pad passes RB1's ring at 0.04 s, sticking fails at 0.15 s
BEYOND = Sine(0.9, 10.0, 1.0)
#: plate 3 steeper than plate 1: RB3's ring is reached first
STEEP_TOP = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha3": 19.0})
#: a wide, flat pad whose sticking phase cannot follow the ground at dt = 0.01 s
WIDE_FLAT = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": 12.0, "alpha23": 12.0, "h2": 0.10})


@pytest.fixture(autouse=True)
def clean(monkeypatch):
    monkeypatch.delenv(backend.ENV, raising=False)
    monkeypatch.setattr(backend, "_warned", False)


# --- DCCSS_BACKEND ---------------------------------------------------------------------------
@pytest.mark.parametrize("value, expected", [(None, "auto"), ("", "auto"), ("auto", "auto"), ("numba", "numba"),
                                             (" Python ", "python"), ("NUMBA", "numba")])
def test_values(monkeypatch, value, expected):
    if value is not None:
        monkeypatch.setenv(backend.ENV, value)
    assert backend.requested() == expected


@pytest.mark.parametrize("value", ["cuda", "numpy", "numba,python", "1"])
def test_unknown_value_names_the_variable_and_the_values(monkeypatch, value):
    monkeypatch.setenv(backend.ENV, value)
    with pytest.raises(ValueError) as err:
        backend.choose(10)
    assert "DCCSS_BACKEND" in str(err.value) and repr(value) in str(err.value)
    assert all(name in str(err.value) for name in backend.BACKENDS)
    with pytest.raises(ValueError, match="DCCSS_BACKEND"):
        simulate(DFP1, Sine(0.27, 30.0, 0.05), dt=0.01)


def test_cli_reports_a_bad_value(monkeypatch, tmp_path, capsys):
    case = tmp_path / "case.yaml"
    case.write_text("prototype: DFP1\nexcitation: {kind: sine, amplitude: 0.27, omega: 30.0, duration: 0.05}\n"
                    "dt: 0.01\nmodel: compliant\n")
    monkeypatch.setenv(backend.ENV, "fast")
    assert main(["run", str(case), "-o", str(tmp_path / "out.nc")]) == 2
    err = capsys.readouterr().err
    assert "DCCSS_BACKEND='fast'" in err and "auto, numba, python" in err and not (tmp_path / "out.nc").exists()
    monkeypatch.setenv(backend.ENV, "python")
    assert main(["run", str(case), "-o", str(tmp_path / "out.nc")]) == 0
    assert "(backend python)" in capsys.readouterr().out


def test_auto_rule(monkeypatch):
    monkeypatch.setattr(backend, "numba_installed", lambda: True)
    assert backend.choose(1000) == "python"  # a paper history
    assert backend.choose(1, 212) == "python"  # a breakaway sweep
    assert backend.choose(30000) == "numba"  # a long history
    assert backend.choose(1000, 10000) == "numba"  # a sweep
    assert backend.work(1000, 1) < backend.AUTO_THRESHOLD <= backend.work(1000, 20)
    monkeypatch.setenv(backend.ENV, "python")
    assert backend.choose(30000, 10000) == "python"
    monkeypatch.setenv(backend.ENV, "numba")
    assert backend.choose(1) == "numba"


def test_size_of_a_run():
    g = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": np.array([8.0, 10.0, 12.0])})
    assert backend.size(g, np.zeros((11, 3))) == (10, 3)
    assert backend.size(DFP1, np.zeros(101), np.zeros((2, 4))) == (100, 8)
    assert backend.size(DFP1, np.zeros(6)) == (5, 1)


# --- without numba ---------------------------------------------------------------------------
@pytest.fixture
def no_numba(monkeypatch):
    """numba cannot be imported (None in sys.modules), nor the compiled module."""
    monkeypatch.setitem(sys.modules, "numba", None)
    monkeypatch.delitem(sys.modules, "dccss.mechanics.compiled", raising=False)
    assert not backend.numba_installed()


def test_numba_requested_without_numba_is_an_error(monkeypatch, no_numba, tmp_path, capsys):
    monkeypatch.setenv(backend.ENV, "numba")
    with pytest.raises(backend.BackendError) as err:
        simulate(DFP1, Sine(0.27, 30.0, 0.05), dt=0.01)
    assert "pip install numba" in str(err.value) and "compiled" in str(err.value)
    assert isinstance(err.value, ImportError)
    case = tmp_path / "case.yaml"
    case.write_text("prototype: DFP1\nexcitation: {kind: sine, amplitude: 0.27, omega: 30.0, duration: 0.05}\n"
                    "dt: 0.01\nmodel: compliant\n")
    assert main(["run", str(case), "-o", str(tmp_path / "out.nc")]) == 2
    assert "pip install numba" in capsys.readouterr().err


def test_auto_without_numba_warns_once_and_runs_interpreted(monkeypatch, no_numba):
    excitation = Sine(0.27, 30.0, 0.2)
    monkeypatch.setenv(backend.ENV, "python")
    reference = simulate(DFP1, excitation, model="stick_slip", dt=0.01)
    monkeypatch.delenv(backend.ENV)
    monkeypatch.setattr(backend, "AUTO_THRESHOLD", 0)  # every run is large
    with pytest.warns(backend.BackendWarning, match="pip install numba"):
        ds = simulate(DFP1, excitation, model="stick_slip", dt=0.01)
    assert ds.identical(reference) and backend.last == "python"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # once per process
        simulate(DFP1, excitation, model="compliant", dt=0.01)
        summaries.summarize("compliant", DFP1, np.zeros((3, 2)))


def test_auto_where_numba_fails_to_import_warns_and_runs_interpreted(monkeypatch, no_numba):
    monkeypatch.setattr(backend, "numba_installed", lambda: True)  # found, but its import fails
    monkeypatch.setattr(backend, "AUTO_THRESHOLD", 0)
    with pytest.warns(backend.BackendWarning):
        module, compiled = backend.kernels("compliant", 10)
    assert not compiled and backend.last == "python"


def test_interpreted_runs_do_not_import_numba():
    """A paper history and a breakaway sweep run interpreted without importing numba (0.3 s a process)."""
    import subprocess

    code = ("import sys; import numpy as np; from dccss.simulation import simulate, breakaway; "
            "from dccss.excitation import Sine; from dccss.paper.prototypes import DFP1; "
            "simulate(DFP1, Sine(0.27, 30.0, 1.0), model='stick_slip', dt=0.001); "
            "breakaway(DFP1, theta2_0_deg=np.arange(-10.5, 0.05, 0.1), dXg=[0.05, 0.1]); "
            "from dccss.mechanics import backend; print(backend.last, 'numba' in sys.modules)")
    env = {k: v for k, v in os.environ.items() if k != backend.ENV}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    assert out.stdout.split() == ["python", "False"]


def test_small_runs_do_not_warn(no_numba):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        simulate(DFP1, Sine(0.27, 30.0, 0.1), model="compliant", dt=0.01)


# --- dispatch, with a stand-in for the compiled module ---------------------------------------
class Fake:
    """The kernels' entry points, computed by the numpy reference (tests/oracle.py); records its calls."""

    def __init__(self):
        self.calls = []

    def run(self, model, geometry, Xg, theta2_0=0.0, **kw):
        self.calls.append(("run", model, kw.get("stop_at_ring", False)))
        assert kw["compiled"]
        return oracle.run(model, geometry, Xg, theta2_0, **kw)

    def summarize(self, model, geometry, Xg, theta2_0=0.0, **kw):
        self.calls.append(("summarize", model, kw.get("capacity")))
        assert kw["compiled"]
        return oracle.summarize(model, geometry, Xg, theta2_0, **kw)


KERNELS = backend._load  # the real kernels' module


@pytest.fixture
def fake(monkeypatch):
    """Every run is large and numba 'installed': the dispatch goes to a Fake."""
    module = Fake()
    monkeypatch.setattr(backend, "numba_installed", lambda: True)
    monkeypatch.setattr(backend, "AUTO_THRESHOLD", 0)
    monkeypatch.setattr(backend, "_load", lambda: module)
    return module


def interpreted(call):
    """call() on the real kernels, interpreted (inside a test that stands a Fake in for them); backend.last
    stays as the test's dispatch set it."""
    last = backend.last
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(backend, "_load", KERNELS)
        mp.setenv(backend.ENV, "python")
        try:
            return call()
        finally:
            backend.last = last


def reference(**kw):
    return interpreted(lambda: simulate(**kw))


@pytest.mark.parametrize("kw", [
    dict(geometry=DFP1, excitation=Sine(0.27, 30.0, 0.3), model="compliant", dt=0.01),
    dict(geometry=DFP1, excitation=Sine(0.27, 30.0, 0.3), model="stick_slip", dt=0.01, theta2_0=0.03),
    dict(geometry=STEEP_TOP, excitation=Sine(0.40, 10.0, 1.0), model="stick_slip", dt=0.01, capacity="stop"),
    dict(geometry=STEEP_TOP, excitation=Sine(0.40, 10.0, 1.0), model="compliant", dt=0.01, capacity="stop"),
    dict(geometry=DFP1, excitation=BEYOND, model="stick_slip", dt=0.01, on_failure="mark"),
    dict(geometry=DFP1, excitation=BEYOND, model="stick_slip", dt=0.01, on_failure="mark", capacity="stop"),
], ids=["compliant", "stick_slip", "stop", "stop compliant", "mark", "mark stop"])
def test_simulate_dispatch(fake, kw):
    """simulate sends a run to the kernels' module (here the numpy reference: one case rounds as the
    kernels do, so the datasets are identical)."""
    calls = []
    ds = simulate(**kw, progress=lambda n, N: calls.append((n, N)))
    assert backend.last == "numba" and ds.identical(reference(**kw))
    assert fake.calls == [("run", kw["model"], kw.get("capacity", "continue") != "continue")]
    assert calls == [(ds.sizes["t"] - 1, len(step_times(kw["excitation"], kw["dt"])) - 1)]  # once, at the end


@pytest.mark.parametrize("kw", [
    dict(geometry=DFP1, excitation=BEYOND, model="stick_slip", dt=0.01),
    dict(geometry=WIDE_FLAT, excitation=Sine(0.27, 30.0, 1.0), model="stick_slip", dt=0.01),
    dict(geometry=STEEP_TOP, excitation=Sine(0.40, 10.0, 1.0), model="compliant", dt=0.01, capacity="error"),
], ids=["after the ring", "reduce dt", "capacity error"])
def test_simulate_dispatch_errors(fake, kw):
    with pytest.raises((ConvergenceError, CapacityError)) as ref:
        reference(**kw)
    with pytest.raises(type(ref.value)) as ours:
        simulate(**kw)
    assert str(ours.value) == str(ref.value)


def test_models_run_and_summarize_dispatch(fake):
    Xg = 0.1 * np.sin(np.linspace(0.0, np.pi, 11))
    expected = oracle.run("stick_slip", DFP1, Xg)
    reference = oracle.summarize("compliant", DFP1, np.stack([Xg, -Xg], axis=1), capacity="stop")
    history = models.run("stick_slip", DFP1, Xg)
    assert history.keys() == expected.keys() and all(np.array_equal(history[k], expected[k], equal_nan=True)
                                                      for k in history)
    out = summaries.summarize("compliant", DFP1, np.stack([Xg, -Xg], axis=1), capacity="stop")
    assert all(np.array_equal(out[k], reference[k], equal_nan=True) for k in out)
    assert fake.calls == [("run", "stick_slip", False), ("summarize", "compliant", "stop")]


def test_small_runs_run_interpreted(monkeypatch):
    """A paper history runs the kernels interpreted: no compiler, and the bytes of the compiled kernels."""
    compiled = backend._load()  # the module the dispatch uses
    calls = []
    original = compiled._Batch.run

    def spy(self, *args, **kw):
        calls.append(kw.get("compiled", args[-1] if len(args) > 5 else True))
        return original(self, *args, **kw)

    monkeypatch.setattr(compiled._Batch, "run", spy)
    kw = dict(geometry=DFP1, excitation=Sine(0.27, 30.0, 1.0), model="stick_slip", dt=0.001, theta2_0=0.02)
    ds = simulate(**kw)  # a paper history: 1000 steps
    assert backend.last == "python" and calls == [False]
    monkeypatch.setenv(backend.ENV, "numba")
    assert simulate(**kw).identical(ds) and backend.last == "numba" and calls == [False, True]


# --- the real kernels ------------------------------------------------------------------------
def assert_same_dataset(ours, ref):
    assert ours.attrs.keys() == ref.attrs.keys()
    for key, value in ref.attrs.items():
        if isinstance(value, float):
            assert ours.attrs[key] == pytest.approx(value, rel=TOL, abs=TOL), key
        else:
            assert ours.attrs[key] == value, key
    assert list(ours.variables) == list(ref.variables) and ours.sizes == ref.sizes
    for name, variable in ref.variables.items():
        a, b = ours[name].values, variable.values
        assert a.dtype == b.dtype and ours[name].attrs.keys() == variable.attrs.keys(), name
        assert all(np.array_equal(ours[name].attrs[k], v) for k, v in variable.attrs.items()), name
        if a.dtype.kind == "f":
            assert np.array_equal(np.isnan(a), np.isnan(b)), name
            assert np.allclose(a, b, rtol=0, atol=TOL, equal_nan=True), (name, np.nanmax(np.abs(a - b)))
        else:
            assert np.array_equal(a, b), name


def both(monkeypatch, call):
    """call() on the compiled kernels and on the numpy reference in their place: the results, or the
    errors raised."""
    monkeypatch.setenv(backend.ENV, "numba")
    out = []
    for module in (KERNELS(), Fake()):
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(backend, "_load", lambda module=module: module)
            try:
                out.append(call())
            except (ConvergenceError, CapacityError) as err:
                out.append(err)
        assert backend.last == "numba"
    return out


@pytest.mark.slow
@pytest.mark.parametrize("kw", [
    dict(geometry=DFP1, excitation=Sine(0.27, 30.0, 1.0), model="compliant", dt=0.01),
    dict(geometry=DFP1, excitation=Sine(0.27, 30.0, 1.0), model="stick_slip", dt=0.001, theta2_0=0.03),
    dict(geometry=TABLE1["DFP2"], excitation=Sine(0.27, 30.0, 1.0), model="compliant", dt=0.001,
         normals="unsigned"),
    dict(geometry=STEEP_TOP, excitation=Sine(0.40, 10.0, 1.0), model="stick_slip", dt=0.01, capacity="stop"),
    dict(geometry=STEEP_TOP, excitation=Sine(0.40, 10.0, 1.0), model="compliant", dt=0.01, capacity="stop"),
    dict(geometry=STEEP_TOP, excitation=Sine(0.40, 10.0, 1.0), model="stick_slip", dt=0.01, capacity="error"),
    dict(geometry=DFP1, excitation=BEYOND, model="stick_slip", dt=0.01, on_failure="mark"),
    dict(geometry=DFP1, excitation=BEYOND, model="stick_slip", dt=0.01, on_failure="mark", capacity="stop"),
    dict(geometry=DFP1, excitation=BEYOND, model="stick_slip", dt=0.01),
    dict(geometry=WIDE_FLAT, excitation=Sine(0.27, 30.0, 1.0), model="stick_slip", dt=0.01),
    dict(geometry=WIDE_FLAT, excitation=Sine(0.27, 30.0, 1.0), model="stick_slip", dt=0.01, on_failure="mark"),
], ids=["compliant", "stick_slip", "unsigned", "stop", "stop compliant", "capacity error", "mark", "mark stop",
        "raise after the ring", "raise", "mark reduce dt"])
def test_simulate_compiled_equals_the_numpy_reference(monkeypatch, kw):
    if isinstance(kw["geometry"], dict):
        kw = {**kw, "geometry": Geometry.from_degrees(**kw["geometry"])}
    ours, ref = both(monkeypatch, lambda: simulate(**kw))
    if isinstance(ref, Exception):
        assert type(ours) is type(ref) and str(ours) == str(ref)
    else:
        assert_same_dataset(ours, ref)


@pytest.mark.slow
def test_random_devices_through_simulate(monkeypatch):
    from test_properties import random_device

    rng = np.random.default_rng(11)
    for k in range(4):
        g = random_device(rng, k % 2 == 0)
        excitation = Sine(0.3 * min(g.capacity1, g.capacity3), 20.0, 0.5)
        for model in models.MODELS:
            ours, ref = both(monkeypatch, lambda g=g, e=excitation, m=model: simulate(g, e, model=m, dt=0.005))
            assert_same_dataset(ours, ref)


@pytest.mark.slow
def test_models_run_and_summarize_compiled_equal_the_numpy_reference(monkeypatch):
    g = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": np.linspace(6.0, 12.0, 5),
                                 "alpha23": np.linspace(6.0, 12.0, 5)})
    Xg = 0.2 * np.sin(np.linspace(0.0, 2 * np.pi, 51))
    for model in models.MODELS:
        ours, ref = both(monkeypatch, lambda m=model: models.run(m, g, Xg))
        assert all(np.allclose(ours[k], ref[k], rtol=0, atol=TOL, equal_nan=True) for k in ref)
        ours, ref = both(monkeypatch, lambda m=model: summaries.summarize(m, g, Xg, capacity="stop"))
        assert all(np.allclose(ours[k], ref[k], rtol=0, atol=TOL, equal_nan=True) for k in ref)
