"""The one change of variables every model uses: anisotropic diffusion along principal
axes is isotropic in the coordinates x_i' = (x_i / L) sqrt(D_z / D_i), L the part's
thickness (Crank 1975 §2.6, eq. 2.13), where time becomes tau* = tau D_z / L^2.

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

import math


def axis_scale(length: float, d_axis: float, d_ref: float) -> float:
    """Physical length (m) -> scaled coordinate: sqrt(d_ref / d_axis) / length (eq. 2.13)."""
    return math.sqrt(d_ref / d_axis) / length


def stretch_of(d) -> tuple[float, float]:
    """sqrt(D_z / D_x), sqrt(D_z / D_y): the in-plane metric of the scaled problem."""
    return (axis_scale(1.0, d[0], d[2]), axis_scale(1.0, d[1], d[2]))


def planar_scale(part, d) -> tuple[float, float]:
    """Physical -> scaled in-plane coordinate factors of a part: sqrt(D_z / D_i) / L."""
    return tuple(axis_scale(part.thickness, d[i], d[2]) for i in (0, 1))
