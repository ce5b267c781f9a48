"""The figure of the articulated slider's pages (docs/explanation/articulated-slider.md,
docs/how-to/articulated-slider.md): docs/img/articulated_slider.png.

The how-to's case, run as ``dccss`` runs it (``dccss.case.case_from``): DFP1 under the paper's sine, its
slider articulated with μ1 = 0.03 on RB1 and μ3 = 0.06 on RB3, driven quasi-statically by the imposed
displacement; drawn by ``dccss plot``'s figure (``dccss.hinged.figure``) at 100 dpi instead of 150, so that
the page stays light. Laid out once (``drawing.freeze``) and written without the software's version in its
metadata: a rerun writes the same bytes (with the same matplotlib).

Run: python docs/articulated_slider.py
"""

from __future__ import annotations

from pathlib import Path

from dccss import drawing, hinged
from dccss.case import case_from

OUT = Path(__file__).resolve().parent / "img" / "articulated_slider.png"
CASE = {"prototype": "DFP1", "excitation": {"kind": "sine", "amplitude": 0.27, "omega": 30.0, "duration": 1.0},
        "dt": 0.001, "model": "compliant", "slider": "articulated", "friction": [0.03, 0.06]}


def main():
    ds = case_from(CASE).run()
    fig = hinged.figure(ds)
    drawing.freeze(fig)
    fig.savefig(OUT, format="png", dpi=100, metadata=drawing.PNG_METADATA)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
