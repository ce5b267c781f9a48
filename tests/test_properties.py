"""Property tests: for random valid devices and small steps, both models converge, keep their
compatibility and symmetry properties, and the batched path equals the one-case path.

Random sampling with fixed seeds (a reproducible stand-in for hypothesis): N_EXAMPLES devices,
symmetric and not, each run under both models."""

import numpy as np
import pytest

from dccss.mechanics import models
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.kinematics import interpenetration

N_EXAMPLES = 40


def random_device(rng, symmetric):
    R1 = rng.uniform(0.8, 3.0)
    alpha1 = rng.uniform(12.0, 30.0)
    p = dict(R1=R1, alpha1=alpha1, alpha21=rng.uniform(0.25, 0.6) * alpha1, hr1=0.02, hmin1=rng.uniform(0.05, 0.15),
             tr1=0.025)
    p["h2"] = rng.uniform(0.05, 0.25) * R1
    if symmetric:
        p.update(R3=R1, alpha3=alpha1, alpha23=p["alpha21"], hr3=0.02, hmin3=p["hmin1"], tr3=0.025)
    else:
        R3 = R1 * rng.uniform(0.7, 1.4)
        alpha3 = rng.uniform(12.0, 30.0)
        p.update(R3=R3, alpha3=alpha3, alpha23=rng.uniform(0.25, 0.6) * alpha3, hr3=0.02,
                 hmin3=rng.uniform(0.05, 0.15), tr3=0.025)
    return Geometry.from_degrees(**p)


def small_motion(rng, geometry, steps=40):
    """A half sine within a third of the device's capacity, steps of at most ~1 % of L."""
    amplitude = rng.uniform(0.1, 0.33) * min(geometry.capacity1, geometry.capacity3)
    return amplitude * np.sin(np.linspace(0.0, np.pi, steps + 1)) * rng.choice([-1.0, 1.0])


@pytest.mark.parametrize("seed", range(N_EXAMPLES))
def test_random_device_small_steps(seed):
    rng = np.random.default_rng(seed)
    symmetric = seed % 2 == 0
    g = random_device(rng, symmetric)
    theta2_0 = np.radians(rng.uniform(-3.0, 3.0))
    Xg = small_motion(rng, g)
    q0 = g.compatible(theta2_0, Xg[0])
    assert np.abs(interpenetration(q0, g)).max() < 1e-12  # the start is compatible
    for model in models.MODELS:
        h = models.run(model, g, Xg, theta2_0)  # raises if Newton does not converge
        q = h["q"]
        assert np.isfinite(q).all() and (h["residual"] <= 1e-12).all()
        # the pendulum relation holds to the tangent error: sin th2 - sin th2_0 = -(Xg - Xg0) / L
        dX = np.abs(np.diff(Xg)).max()
        assert np.abs(np.sin(q[:, 5]) - np.sin(theta2_0) + (Xg - Xg[0]) / g.L).max() < 50 * dX**2 / min(g.R1, g.R3)
        I = interpenetration(q, g)
        assert np.abs(I).max() < 5 * dX**2 / min(g.R1, g.R3)  # corners stay near their circles
        if symmetric:
            assert np.abs(I[:, 0] - I[:, 3]).max() < 1e-9 and np.abs(I[:, 1] - I[:, 2]).max() < 1e-9


@pytest.mark.parametrize("model", models.MODELS)
def test_random_batch_equals_one_case(model):
    """A batch of random devices, start angles and motions equals the one-case path to 1e-12."""
    rng = np.random.default_rng(2021)
    devices = [random_device(rng, k % 2 == 0) for k in range(8)]
    motions = np.stack([small_motion(rng, g) for g in devices], axis=1)
    theta2_0 = np.radians(rng.uniform(-3.0, 3.0, size=8))
    fields = {name: np.array([getattr(g, name) for g in devices]) for name in Geometry.__dataclass_fields__}
    batch = models.run(model, Geometry(**fields), motions, theta2_0)
    for k, g in enumerate(devices):
        one = models.run(model, g, motions[:, k], theta2_0[k])
        assert np.abs(batch["q"][:, k] - one["q"]).max() < 1e-12
