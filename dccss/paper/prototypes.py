"""The two prototypes of Table 1 (Bianco, Monti & Belfiore 2021), lengths in m, angles in degrees."""

from ..mechanics.geometry import Geometry

TABLE1 = {
    "DFP1": dict(R1=1.0, R3=1.0, alpha1=21.0, alpha3=21.0, h2=0.15, alpha21=10.0, alpha23=10.0,
                 hr1=0.02, hr3=0.02, hmin1=0.10, hmin3=0.10, tr1=0.0258, tr3=0.0258),
    "DFP2": dict(R1=1.0, R3=1.0, alpha1=18.0, alpha3=18.0, h2=0.15, alpha21=5.0, alpha23=5.0,
                 hr1=0.02, hr3=0.02, hmin1=0.10, hmin3=0.10, tr1=0.0258, tr3=0.0258),
}

DFP1 = Geometry.from_degrees(**TABLE1["DFP1"])
DFP2 = Geometry.from_degrees(**TABLE1["DFP2"])
