"""Part geometries for the diffusion engine (dry dimensions, SI metres).

Axes: x, y in the plane of the part, z through its thickness; for a ``Disc``
x = y = radial. All surfaces named in each docstring are exposed to the
environment. The contact layer, whose mean every result reports beside the part's mean,
lies within a depth of the contact surface (``LAYER_DEPTH`` unless the caller gives one).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

LAYER_DEPTH = 5e-4  # m, the contact layer's depth when none is given


@dataclass(frozen=True)
class Sheet:
    """Infinite plate of ``thickness``, both faces exposed (Crank 1975, §4.3).

    Parameters
    ----------
    thickness : float
        The plate's thickness [m].

    References
    ----------
    J. Crank, *The Mathematics of Diffusion*, 2nd ed., Oxford: Clarendon Press, 1975,
    §4.3 (plane sheet, surface concentration constant).
    """

    thickness: float


@dataclass(frozen=True)
class Disc:
    """Axisymmetric disc (``inner_radius`` = 0) or annulus; faces, rim and bore exposed.

    Parameters
    ----------
    outer_radius : float
        The rim's radius [m].
    thickness : float
        The disc's thickness [m].
    inner_radius : float
        The bore's radius [m]; 0 for a full disc.
    """

    outer_radius: float
    thickness: float
    inner_radius: float = 0.0


@dataclass(frozen=True)
class Bar:
    """Rectangular bar, all six faces exposed (x = length, y = width, z = thickness).

    Parameters
    ----------
    length : float
        The bar's length along x [m].
    width : float
        Its width along y [m].
    thickness : float
        Its thickness along z [m].
    """

    length: float
    width: float
    thickness: float


@dataclass(frozen=True, eq=False)
class CamPlate:
    """Prismatic cam plate: closed counter-clockwise outline (m) of the working
    profile, last point not repeated; the two faces, the profile edge and the
    bore are exposed. The profile edge is the contact surface.

    Parameters
    ----------
    profile_x, profile_y : numpy.ndarray
        The outline's points [m], counter-clockwise, about the cam's centre of rotation
        (copied and made read-only).
    thickness : float
        The plate's thickness [m].
    bore_radius : float
        The bore's radius [m]; 0 for none.
    """

    profile_x: np.ndarray = field(repr=False)
    profile_y: np.ndarray = field(repr=False)
    thickness: float = 0.0
    bore_radius: float = 0.0

    def __post_init__(self):
        """Own read-only copies of the outline: equality and hash below are by value (the
        caches of meshes and step responses are keyed by them), so the arrays must not
        change afterwards."""
        for name in ("profile_x", "profile_y"):
            array = np.array(getattr(self, name), dtype=float)
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    def _values(self) -> tuple:
        return (self.profile_x.tobytes(), self.profile_y.tobytes(), float(self.thickness),
                float(self.bore_radius))

    def __eq__(self, other) -> bool:
        return type(other) is CamPlate and self._values() == other._values()

    def __hash__(self) -> int:
        return hash(self._values())


@dataclass(frozen=True)
class LinkBar:
    """A link: a bar of ``length`` between boss centres, ``width`` x ``thickness``
    section, with a hollow cylindrical boss (outer/inner radius, same thickness)
    at each end; every surface, the two holes included, is exposed.

    Parameters
    ----------
    length : float
        The distance between the boss centres [m].
    width : float
        The bar's width in the plane of the link [m].
    thickness : float
        The thickness of bar and bosses [m].
    boss_outer_radius : float
        The bosses' outer radius [m].
    boss_inner_radius : float
        The radius of the bosses' holes [m].
    """

    length: float
    width: float
    thickness: float
    boss_outer_radius: float
    boss_inner_radius: float


Geometry = Sheet | Disc | Bar | CamPlate | LinkBar
