"""Triangle meshes of the parts' planforms for elasticity: the graded meshes the diffusion
engine builds (``fickcam.diffusion.planform.triangles.triangulate``), imported only here so that one
line follows a reorganisation of the diffusion package."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PlateMesh:
    """Vertices (n, 2) in m and triangles (m, 3) of a planform.

    Parameters
    ----------
    points : numpy.ndarray
        The planform's vertices, shape (n, 2) [m].
    triangles : numpy.ndarray
        Three vertex indices per triangle, shape (m, 3).
    """

    points: np.ndarray
    triangles: np.ndarray


def planform_mesh(geometry, spacing: float, growth: float | None = None) -> PlateMesh:
    """The diffusion engine's triangulation of a ``CamPlate`` or ``LinkBar`` planform: edges
    of ``spacing`` (m) along the outline, growing by (1 + ``growth``) per row inward
    (``None``: a uniform lattice).

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The planform.
    spacing : float
        Edge length along the outline [m].
    growth : float, optional
        Row-to-row growth of the edge length inward [-]; None: uniform.

    Returns
    -------
    PlateMesh
        The mesh.
    """
    from ..diffusion.planform.triangles import triangulate

    mesh = triangulate(geometry, spacing, growth=growth)
    return PlateMesh(np.asarray(mesh.points, float), np.asarray(mesh.triangles, int))


def disc_plate(radius: float, thickness: float, bore_radius: float = 0.0, centre=(0.0, 0.0),
               samples: int = 720):
    """A circular disc (an eccentric cam, a roller) as a ``CamPlate`` outline, so that it
    meshes like any plate; ``centre`` shifts the circle off the origin (the bore axis).

    Parameters
    ----------
    radius : float
        The disc's radius [m].
    thickness : float
        Its thickness [m].
    bore_radius : float
        The bore's radius, about the origin [m].
    centre : tuple of float
        The disc's centre [m].
    samples : int
        Number of outline points.

    Returns
    -------
    CamPlate
        The disc's plate.
    """
    from ..diffusion.problem.geometry import CamPlate

    angle = 2 * np.pi * np.arange(samples) / samples
    return CamPlate(centre[0] + radius * np.cos(angle), centre[1] + radius * np.sin(angle),
                    thickness, bore_radius)
