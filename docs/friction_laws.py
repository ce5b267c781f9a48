"""The figure of the friction laws' page (docs/explanation/friction.md): docs/img/friction_laws.png.

μ from the laws themselves (``dccss.mechanics.friction.LAWS``, ``Law.mu``: the kernels' own function), so
the figure cannot drift from the code: the velocity law against the speed, the velocity-pressure law
against the speed at three pressures, and the temperature law against the plate's temperature (k_T) and
the contact pressure (k_p). The values are the page's examples, not a calibration. Matplotlib's Agg
canvas without pyplot and PNG metadata without the software's version: a rerun writes the same bytes
(with the same matplotlib).

Run: python docs/friction_laws.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from dccss.mechanics.friction import TEMPERATURE, VELOCITY, VELOCITY_PRESSURE

OUT = Path(__file__).resolve().parent / "img" / "friction_laws.png"
MPA = 1e6
SPEED = np.linspace(0.0, 0.5, 501)  # m/s
FAST = 1e3  # m/s: a speed at which exp(-rate v) is 0, k_v = 1


def velocity(ax):
    for rate, style in ((20.0, "-"), (30.0, "--")):
        values = VELOCITY.values({"slow": 0.03, "fast": 0.08, "rate": rate})
        ax.plot(SPEED, VELOCITY.mu(values, SPEED), style, color="tab:blue", label=f"rate = {rate:g} s/m")
    for mu, text in ((0.03, "slow"), (0.08, "fast")):
        ax.axhline(mu, color="0.6", lw=0.8, ls=":")
        ax.text(0.49, mu + 0.002, text, ha="right", va="bottom", fontsize=8, color="0.4")
    ax.set(title="(a) velocity: slow 0.03, fast 0.08", xlabel="sliding speed v (m/s)", ylabel="μ", ylim=(0, 0.13))
    ax.legend(loc="center right", fontsize=8)


def velocity_pressure(ax):
    law = {"slow": 0.03, "fast0": 0.12, "delta": 0.06, "alpha": 3.0e-8, "rate": 20.0, "pressure": 2.5e7}
    values = VELOCITY_PRESSURE.values(law)
    for p, colour in ((10.0, "tab:green"), (25.0, "tab:orange"), (50.0, "tab:red")):
        ax.plot(SPEED, VELOCITY_PRESSURE.mu(values, SPEED, pressure=p * MPA), color=colour, label=f"p = {p:g} MPa")
    ax.axhline(0.12, color="0.6", lw=0.8, ls=":")
    ax.text(0.49, 0.122, "fast0", ha="right", va="bottom", fontsize=8, color="0.4")
    ax.set(title="(b) velocity_pressure: fast0 0.12, delta 0.06,\nalpha 3e-8 /Pa, slow 0.03, rate 20 s/m",
           xlabel="sliding speed v (m/s)", ylabel="μ", ylim=(0, 0.13))
    ax.legend(loc="lower right", fontsize=8)


def temperature(ax):
    law = {"mu_ref": 0.06, "contact_radius": 0.2, "pressure": 5.0e7, "p_ref": 5.0e7}
    values = TEMPERATURE.values(law)
    T = np.linspace(0.0, 300.0, 301)
    ax.plot(T, TEMPERATURE.mu(values, FAST, temperature=T), color="tab:purple", label="sliding fast (k_v = 1)")
    ax.plot(T, TEMPERATURE.mu(values, 0.0, temperature=T), "--", color="tab:purple", label="breakaway (k_v = 0.5)")
    ax.axvline(20.0, color="0.6", lw=0.8, ls=":")
    ax.text(23.0, 0.071, "20 °C: k_T = 1.000", fontsize=8, color="0.4")
    ax.set(title="(c) temperature: mu_ref 0.06 at p = p_ref", xlabel="plate temperature T (°C)", ylabel="μ",
           ylim=(0, 0.075))
    right = ax.secondary_yaxis("right", functions=(lambda mu: mu / 0.06, lambda k: k * 0.06))
    right.set_ylabel("k_T = μ / mu_ref (fast)")
    ax.legend(loc="lower left", fontsize=8)


def pressure(ax):
    law = {"mu_ref": 0.06, "contact_radius": 0.2, "pressure": 5.0e7, "p_ref": 5.0e7}
    values = TEMPERATURE.values(law)
    p = np.linspace(0.0, 100.0, 201)
    ax.plot(p, TEMPERATURE.mu(values, FAST, pressure=p * MPA), color="tab:brown", label="sliding fast (k_v = 1)")
    ax.plot(p, TEMPERATURE.mu(values, 0.0, pressure=p * MPA), "--", color="tab:brown", label="breakaway (k_v = 0.5)")
    ax.axvline(50.0, color="0.6", lw=0.8, ls=":")
    ax.text(51.0, 0.003, "p_ref", fontsize=8, color="0.4")
    ax.set(title="(d) temperature: mu_ref 0.06, p_ref 50 MPa, 20 °C", xlabel="contact pressure p (MPa)",
           ylabel="μ", ylim=(0, 0.1))
    right = ax.secondary_yaxis("right", functions=(lambda mu: mu / 0.06, lambda k: k * 0.06))
    right.set_ylabel("k_p = μ / mu_ref (fast)")
    ax.legend(loc="lower left", fontsize=8)


def main():
    fig = Figure(figsize=(10.0, 7.6), dpi=120, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(2, 2)
    velocity(axes[0, 0])
    velocity_pressure(axes[0, 1])
    temperature(axes[1, 0])
    pressure(axes[1, 1])
    for ax in axes.flat:
        ax.grid(True, lw=0.4, color="0.85")
    OUT.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT, metadata={"Software": None})
    print(OUT)


if __name__ == "__main__":
    main()
