"""Triangle meshes of the parts' planforms for elasticity: the graded meshes the diffusion
engine builds (``fickcam.diffusion.planform.triangles.triangulate``), imported only here so that one
line follows a reorganisation of the diffusion package."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from ..diffusion.planform.triangles import triangulate
from ..diffusion.problem.geometry import CamPlate
from ..diffusion.planform.polygon import Wall, drop_unused, triangle_areas
from ..diffusion.problem.curves import resample_polyline
from ..diffusion.planform.triangles import MIN_GAP, delaunay_inside, hex_lattice


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

    angle = 2 * np.pi * np.arange(samples) / samples
    return CamPlate(centre[0] + radius * np.cos(angle), centre[1] + radius * np.sin(angle),
                    thickness, bore_radius)


def drawn_mesh(loops, spacing: float) -> PlateMesh:
    """A planform given by closed polygons meshed with every polygon vertex kept, so that the
    mesh covers exactly the polygon: points every <= ``spacing`` along each loop, a
    hexagonal lattice of side ``spacing`` inside (no closer than ``MIN_GAP`` spacings to the
    outline), triangulated by Delaunay and the triangles outside dropped.

    Parameters
    ----------
    loops : list of numpy.ndarray
        Closed polygons [m] (outline counter-clockwise, holes clockwise), shape (n, 2) each.
    spacing : float
        The mesh's edge length [m].

    Returns
    -------
    PlateMesh
        The mesh.

    Raises
    ------
    ValueError
        When the triangles do not cover the polygon (a vertex closer to an edge than the
        mesh can resolve): their area differs from the polygon's by more than 1e-9.
    """

    boundary = np.vstack([resample_polyline(*loop.T, spacing) for loop in loops])
    wall = Wall.of(loops, spacing / 8)
    lattice = hex_lattice(boundary.min(axis=0), boundary.max(axis=0), spacing)
    gap, inside = wall.distance(lattice)
    points = np.vstack([boundary, lattice[inside & (gap > MIN_GAP * spacing)]])
    points, triangles, _ = drop_unused(points, delaunay_inside(points, wall, spacing))
    covered = triangle_areas(points, triangles).sum()
    area = sum(0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) for x, y in (l.T for l in loops))
    if abs(covered - area) > 1e-9 * abs(area):
        raise ValueError(f"the mesh of spacing {spacing:.3g} m covers {covered:.9g} m^2 of a "
                         f"planform of {area:.9g} m^2")
    return PlateMesh(points, triangles)
