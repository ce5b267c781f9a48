"""The kernels (mechanics.compiled, mechanics.models) against the numpy reference (tests/oracle.py).

Same keys, dtypes and shapes; lengths (m) and angles (rad; degrees in summaries) to 1e-10;
Newton iteration counts, flags, failures and capacity times identical; the same errors. On the
devices of the property tests (symmetric and not), both models, both normal conventions, one
case and batches, histories and summaries.

In the quick loop (``-m "not slow"``) so that a broken kernel is caught there: a few seconds with
the kernel cache warm; the first run on a machine compiles the kernels (about 30 s, once)."""

import inspect
import re
from functools import partial

import numpy as np
import oracle
import pytest
from test_properties import random_device, small_motion

from dccss.mechanics import compiled, models, newton, summaries
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.kinematics import all_corners, frames, local
from dccss.paper.prototypes import TABLE1

TOL = 1e-10



MARK = newton.NewtonOptions(on_failure="mark")
NORMALS = ("signed", "unsigned")


def stack(devices):
    return Geometry(**{name: np.array([getattr(g, name) for g in devices]) for name in Geometry.__dataclass_fields__})


@pytest.fixture(scope="module")
def devices():
    """Eight random devices (even: symmetric), their start angles and motions."""
    rng = np.random.default_rng(2021)
    devices = [random_device(rng, k % 2 == 0) for k in range(8)]
    motions = np.stack([small_motion(rng, g) for g in devices], axis=1)
    theta2_0 = np.radians(rng.uniform(-3.0, 3.0, size=8))
    return devices, motions, theta2_0


#: a batch with cases that pass a retaining ring and (stick-slip) cases the solver fails on:
#: flat and wide pads (R1 = 1 m, alpha21 = 18, 20 deg) at large steps
GRID = Geometry.from_degrees(**{**TABLE1["DFP1"], "R1": np.array([[1.0], [3.0]]), "R3": np.array([[1.0], [3.0]]),
                                "alpha21": np.array([8.0, 14.0, 18.0, 20.0]),
                                "alpha23": np.array([8.0, 14.0, 18.0, 20.0])})
GRID_XG = 0.3 * np.sin(np.linspace(0.0, np.pi, 9))
GRID_T = np.linspace(0.0, 0.8, 9)
WIDE = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": 18.0, "alpha23": 18.0})


def reference_local(history, geometry):
    """The plate-frame corner positions of a history, as ``compliant_steps`` yields them."""
    F = frames(history["q"])
    return np.stack([local(F, c) for c in all_corners(geometry)], axis=-1)


def failed_steps(ref):
    """Where a Newton solve of the reference did not converge (its residual is the last iterate's of a
    divergent iteration: compared relatively)."""
    its = ref["newton_iterations"]
    return (its == its.max()) & (ref["residual"] > 1e-12)


def assert_same(ours, ref, geometry=None):
    """Same keys, types, dtypes and shapes; NaN at the same places; floats to TOL; the rest equal."""
    ref = dict(ref)
    if "local" in ref and geometry is not None:
        ref["local"] = reference_local(ref, geometry)
    assert set(ours) == set(ref)
    for key in ref:
        a, b = ours[key], ref[key]
        assert type(a) is type(b), key
        a, b = np.asarray(a), np.asarray(b)
        assert a.dtype == b.dtype and a.shape == b.shape, (key, a.dtype, b.dtype, a.shape, b.shape)
        if a.dtype.kind in "biu":
            assert np.array_equal(a, b), key
            continue
        assert np.array_equal(np.isnan(a), np.isnan(b)), key
        ok = ~np.isnan(b)
        if key.startswith("residual") and "newton_iterations" in ref:
            its = ref["newton_iterations" + key[len("residual"):]]
            diverged = (its == its.max()) & (np.abs(b) > 1e-12) & ok
            assert np.allclose(a[diverged], b[diverged], rtol=1e-3), key
            ok &= ~diverged
        assert np.all(np.abs(a[ok] - b[ok]) <= TOL), (key, np.abs(a[ok] - b[ok]).max())


@pytest.mark.parametrize("model", models.MODELS)
@pytest.mark.parametrize("normals", NORMALS)
def test_batch_histories_and_summaries(devices, model, normals):
    devices, motions, theta2_0 = devices
    batch = stack(devices)
    assert_same(compiled.run(model, batch, motions, theta2_0, normals=normals),
                oracle.run(model, batch, motions, theta2_0, normals=normals), batch)
    assert_same(compiled.summarize(model, batch, motions, theta2_0, normals=normals),
                oracle.summarize(model, batch, motions, theta2_0, normals=normals))


@pytest.mark.parametrize("model", models.MODELS)
@pytest.mark.parametrize("normals", NORMALS)
@pytest.mark.parametrize("k", [0, 1, 2, 5])
def test_one_case_histories_and_summaries(devices, model, normals, k):
    devices, motions, theta2_0 = devices
    g, Xg, t0 = devices[k], motions[:, k], theta2_0[k]
    times = np.linspace(0.0, 0.4, len(Xg))
    assert_same(compiled.run(model, g, Xg, t0, normals=normals, times=times),
                oracle.run(model, g, Xg, t0, normals=normals, times=times), g)
    assert_same(compiled.summarize(model, g, Xg, t0, normals=normals, times=times),
                oracle.summarize(model, g, Xg, t0, normals=normals, times=times))


@pytest.mark.parametrize("model", models.MODELS)
@pytest.mark.parametrize("normals", NORMALS)
def test_one_case_histories_round_as_the_reference_bit_for_bit(devices, model, normals):
    """One case, the reference evaluates the rows on Python scalars and both take the same
    written-out solve (``linear.solve4``): every configuration, residual and contact point of
    the history is the reference's to the last bit (no tolerance), on all eight devices."""
    devices, motions, theta2_0 = devices
    for k, g in enumerate(devices):
        ours = compiled.run(model, g, motions[:, k], theta2_0[k], normals=normals)
        ref = oracle.run(model, g, motions[:, k], theta2_0[k], normals=normals)
        for key in ("q", "q_stick", "residual", "point", "normal"):
            if key in ref:
                assert np.array_equal(ours[key], ref[key], equal_nan=True), (k, key)


def test_batch_of_one_and_shared_motion(devices):
    """A batch of one takes the reference's one-case path; a (T,) motion is shared by a batch."""
    devices, motions, theta2_0 = devices
    one = stack(devices[1:2])
    for model in models.MODELS:
        assert_same(compiled.summarize(model, one, motions[:, 1:2], theta2_0[1:2]),
                    oracle.summarize(model, one, motions[:, 1:2], theta2_0[1:2]))
        batch = stack(devices[:3])
        assert_same(compiled.run(model, batch, motions[:, 0]), oracle.run(model, batch, motions[:, 0]), batch)


@pytest.mark.filterwarnings("ignore:invalid value:RuntimeWarning")  # the reference's NaN of failed cases
@pytest.mark.parametrize("model", models.MODELS)
def test_failures_and_capacity_marked_alike(model):
    """Cases past a retaining ring and (stick-slip) cases the solver fails on, with
    on_failure="mark": the same NaN from the failing step on, the same flags and times."""
    ours = compiled.summarize(model, GRID, GRID_XG, options=MARK, times=GRID_T)
    ref = oracle.summarize(model, GRID, GRID_XG, options=MARK, times=GRID_T)
    assert_same(ours, ref)
    assert ref["capacity_exceeded"].any()
    if model == "stick_slip":
        assert ref["failed"].any() and not ref["failed"].all()
    assert_same(compiled.run(model, GRID, GRID_XG, options=MARK), oracle.run(model, GRID, GRID_XG, options=MARK),
                GRID)
    # the one-case path: a failed case iterates NaN to the cap afterwards
    assert_same(compiled.run(model, WIDE, GRID_XG, options=MARK), oracle.run(model, WIDE, GRID_XG, options=MARK),
                WIDE)
    assert_same(compiled.summarize(model, WIDE, GRID_XG, options=MARK),
                oracle.summarize(model, WIDE, GRID_XG, options=MARK))


def error_of(call):
    with pytest.raises(newton.ConvergenceError) as err:
        call()
    return err.value


@pytest.mark.parametrize("geometry", [GRID, WIDE], ids=["batch", "one case"])
def test_convergence_error_same_message(geometry):
    mine = error_of(lambda: compiled.run("stick_slip", geometry, GRID_XG, times=GRID_T))
    ref = error_of(lambda: oracle.run("stick_slip", geometry, GRID_XG, times=GRID_T))
    assert type(mine) is type(ref) and str(mine) == str(ref)
    mine = error_of(lambda: compiled.summarize("stick_slip", geometry, GRID_XG, times=GRID_T))
    assert str(mine) == str(ref)


def test_convergence_error_keeps_history_of_one_case():
    err = error_of(lambda: compiled.run("stick_slip", WIDE, GRID_XG, times=GRID_T))
    n = int(str(err).split("step ")[1].split(",")[0])
    assert err.history["q"].shape == (n, 9) and np.isfinite(err.history["q"]).all()


def test_tolerance_below_round_off_fails_alike():
    """The same error where it fails; the residuals are round-off (1e-17 m), not reproducible."""
    t = np.linspace(0.0, 1.0, 11)
    Xg = 0.27 * np.sin(30.0 * t)
    options = newton.NewtonOptions(tol=1e-30, max_iter=3)
    mine = error_of(lambda: compiled.run("compliant", GRID, Xg, options=options, times=t))
    ref = error_of(lambda: oracle.run("compliant", GRID, Xg, options=options, times=t))

    def masked(err):
        return re.sub(r"-?\d\.\d+e[-+]\d+", "#", str(err))

    assert type(mine) is type(ref) and masked(mine) == masked(ref)


def singular_start():
    """A stick-slip start whose jammed diagonal A-D is exactly horizontal: the sticking Jacobian
    of the first step is singular (two rows differ only in a column whose entries are equal)."""
    return Geometry.from_degrees(**{**TABLE1["DFP1"], "h2": 0.125}), -0.34548755058401825


@pytest.mark.parametrize("options", [newton.NewtonOptions(), MARK], ids=["raise", "mark"])
def test_singular_jacobian_one_case(options):
    """The one-case reference raises SingularJacobianError under both failure policies."""
    g, theta2_0 = singular_start()
    Xg = np.array([0.0, 0.001, 0.002])
    mine = error_of(lambda: compiled.run("stick_slip", g, Xg, theta2_0, options=options, times=Xg))
    ref = error_of(lambda: oracle.run("stick_slip", g, Xg, theta2_0, options=options, times=Xg))
    assert isinstance(ref, newton.SingularJacobianError)
    assert type(mine) is type(ref) and str(mine) == str(ref)


def test_singular_jacobian_batch():
    """In a batch the singular case is marked failed (0 updates, NaN) or named by its index. (The
    reference's batch path evaluates e^{i theta} with numpy's complex exp, which differs from
    libm's in the last bit, so it misses this exact singularity and fails by non-convergence.)"""
    g, theta2_0 = singular_start()
    Xg = np.array([0.0, 0.001, 0.002])[:, None] * np.array([1.0, 1.0, -1.0])
    start = np.array([0.0, theta2_0, theta2_0])
    h = compiled.run("stick_slip", g, Xg, start, options=MARK)
    assert np.isnan(h["q"][1:, 1, 3:6]).all() and np.isfinite(h["q"][:, [0, 2]]).all()  # the pad of case 1
    assert h["newton_iterations_stick"][1, 1] == 0 and np.isnan(h["residual_stick"][1, 1])
    err = error_of(lambda: compiled.run("stick_slip", g, Xg, start))
    assert isinstance(err, newton.SingularJacobianError) and "batch index (1,), step 1" in str(err)


def test_stop_at_ring_ends_where_simulate_stops():
    t = np.linspace(0.0, 1.0, 101)
    Xg = 0.35 * np.sin(30.0 * t)
    g = Geometry.from_degrees(**TABLE1["DFP1"])
    for model in models.MODELS:
        full = compiled.run(model, g, Xg)
        gap = g.ring_inner_x - np.stack([np.abs(full["local"][..., :2].real).max(-1),
                                         np.abs(full["local"][..., 2:].real).max(-1)], -1) \
            if model == "compliant" else None
        h = compiled.run(model, g, Xg, stop_at_ring=True)
        assert 1 < len(h["q"]) < len(Xg)
        assert np.array_equal(h["q"], full["q"][:len(h["q"])])
        if gap is not None:
            assert (gap[len(h["q"]) - 1] < 0).any() and not (gap[:len(h["q"]) - 1] < 0).any()


@pytest.mark.skipif("capacity" not in inspect.signature(summaries.summarize).parameters,
                    reason="the reference summaries have no capacity policies")
@pytest.mark.parametrize("model", models.MODELS)
@pytest.mark.parametrize("capacity", ["stop", "error"])
def test_capacity_policies(model, capacity):
    kw = dict(options=MARK, times=GRID_T, capacity=capacity)
    assert_same(compiled.summarize(model, GRID, GRID_XG, **kw), oracle.summarize(model, GRID, GRID_XG, **kw))
    from dccss.mechanics.capacity import CapacityError

    if capacity == "error":
        with pytest.raises(CapacityError) as mine:
            compiled.summarize(model, GRID, GRID_XG, times=GRID_T, capacity=capacity)
        with pytest.raises(CapacityError) as ref:
            oracle.summarize(model, GRID, GRID_XG, times=GRID_T, capacity=capacity)
        assert str(mine.value) == str(ref.value)
        # the case's (R1, alpha21) in GRID, by which a study names the sweep point
        assert mine.value.index == ref.value.index and len(mine.value.index) == 2


@pytest.mark.parametrize("model", models.MODELS)
@pytest.mark.parametrize("capacity", ["stop", "error"])
@pytest.mark.parametrize("kernels", [True, False], ids=["compiled", "interpreted"])
def test_a_case_stopped_at_its_ring_is_not_stepped_on(model, capacity, kernels):
    """Without "mark", a case that reached its ring under capacity "stop" or "error" is no longer stepped: a
    solver failure it would meet later is not raised (stop) and does not come before the ring's error (error);
    its summaries are those marked runs give. Case 0 passes a ring at 0.04 s and (stick-slip) the solver fails
    on it at 0.15 s; case 1 stays inside. A batch of one runs the one-case path."""
    from dccss.excitation import Sine, step_times

    beyond = Sine(0.9, 10.0, 1.0)  # far beyond DFP1's capacity
    t = step_times(beyond, 0.01)
    Xg = beyond.displacement(t)[:, None] * np.array([1.0, 0.1])
    g = Geometry.from_degrees(**TABLE1["DFP1"])
    for motion in (Xg, Xg[:, :1]):
        marked = compiled.summarize(model, g, motion, capacity=capacity, options=MARK, times=t, compiled=kernels)
        if capacity == "stop":
            assert_same(compiled.summarize(model, g, motion, capacity=capacity, times=t, compiled=kernels), marked)
            assert not marked["failed"].any() and marked["capacity_time"][0] == pytest.approx(0.04)
            continue
        from dccss.mechanics.capacity import CapacityError

        with pytest.raises(CapacityError, match=r"t = 0\.04 s in the case at batch index"):
            compiled.summarize(model, g, motion, capacity=capacity, times=t, compiled=kernels)
        assert marked["failed"][0] and marked["failure_time"][0] == pytest.approx(0.04)


def test_bad_input_rejected_alike():
    g = Geometry.from_degrees(**TABLE1["DFP1"])
    for call in (partial(compiled.run, "compliant"), partial(oracle.run, "compliant")):
        with pytest.raises(ValueError, match="normals must be one of"):
            call(g, np.array([0.0, 0.01]), normals="mirrored")
        with pytest.raises(ValueError, match="at least two step values"):
            call(g, np.array([0.0]))
    with pytest.raises(ValueError, match="model must be one of"):
        compiled.summarize("rocking", g, np.array([0.0, 0.01]))


def test_a_record_per_case_read_only_runs_the_kernel_the_warm_up_compiles():
    """A batch whose cases each have their own record, read-only (a view of a study's records), compiled the
    batch kernel a second time, for read-only arrays: the warm-up (``python -m dccss.mechanics``) did not
    cover it. The batch copies such a record: one signature."""
    from dccss.mechanics import registry, scalar, warmup

    warmup.warm_part("planar compliant")
    Xg = np.linspace(0.0, 1e-3, 3)[:, None] * np.array([1.0, 2.0])
    Xg.flags.writeable = False
    compiled.summarize("compliant", warmup._device(), Xg)
    compiled.run("compliant", warmup._device(), Xg)
    assert len(scalar._KERNELS[registry.model("compliant").planar.batch].signatures) == 1


def test_the_warm_up_has_a_part_per_kernel_and_knows_which_the_cache_lacks(tmp_path, monkeypatch):
    """``warmup.parts``: one part per kernel a run compiles (every registered model's planar batch and
    spatial history, the structure's four kernels); ``cold``: those without numba's index in the cache."""
    from dccss.mechanics import registry, scalar, warmup
    from dccss.mechanics.structure import articulated, circular, exact, series

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    kernels = {part: function for part, (function, _) in warmup.parts().items()}
    assert set(kernels.values()) == ({registry.model(n).planar.batch for n in registry.names()}
                                     | {registry.model(n).spatial for n in registry.names(lambda e: e.spatial)}
                                     | {circular.plane, exact.line, articulated.articulated, series.series_line})
    assert warmup.cold() == list(kernels)
    name = kernels["structure plane"].__qualname__
    index = scalar.cache_folder(str(tmp_path)) / "mechanics_x" / f"models.{name}-1.nbi"
    index.parent.mkdir(parents=True)
    index.touch()
    assert warmup.cold() == [part for part in kernels if part != "structure plane"]


def test_the_warm_up_command_refuses_no_processes():
    import subprocess
    import sys

    run = subprocess.run([sys.executable, "-m", "dccss.mechanics", "--jobs", "0"], capture_output=True, text=True)
    assert run.returncode == 2 and "--jobs: at least 1, got 0" in run.stderr
