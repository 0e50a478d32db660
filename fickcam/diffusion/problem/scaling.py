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
    """Factor from a physical coordinate to the scaled one along an axis (Crank eq. 2.13).

    Parameters
    ----------
    length : float
        The reference length L, the part's thickness [m].
    d_axis : float
        The diffusivity along the axis [m^2/s].
    d_ref : float
        The reference (through-thickness) diffusivity D_z [m^2/s].

    Returns
    -------
    float
        sqrt(d_ref / d_axis) / length [1/m]: x' = factor x is dimensionless.

    References
    ----------
    Crank (1975), cited in the module docstring.
    """
    return math.sqrt(d_ref / d_axis) / length


def stretch_of(d) -> tuple[float, float]:
    """Stretch of the in-plane axes in the scaled problem: sqrt(D_z / D_x), sqrt(D_z / D_y).

    Parameters
    ----------
    d : sequence of float
        The principal diffusivities (D_x, D_y, D_z) [m^2/s].

    Returns
    -------
    tuple of float
        sqrt(D_z / D_x) and sqrt(D_z / D_y) [-].
    """
    return (axis_scale(1.0, d[0], d[2]), axis_scale(1.0, d[1], d[2]))


def planar_scale(part, d) -> tuple[float, float]:
    """Factors from a part's physical in-plane coordinates to the scaled ones.

    Parameters
    ----------
    part : Geometry
        The part; its ``thickness`` [m] is the reference length L.
    d : sequence of float
        The principal diffusivities (D_x, D_y, D_z) [m^2/s].

    Returns
    -------
    tuple of float
        sqrt(D_z / D_x) / L and sqrt(D_z / D_y) / L [1/m].
    """
    return tuple(axis_scale(part.thickness, d[i], d[2]) for i in (0, 1))
