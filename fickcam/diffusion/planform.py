"""Prismatic parts (CamPlate, LinkBar): a 2-D triangle mesh of the outline times
the through-thickness sheet.

For a prism whose every surface holds the same value g and which starts
uniform at c0, the unsaturated fraction u = (g - c)/(g - c0) of a unit step
is the product u_plane(x, y, tau) u_sheet(z, tau) (Crank 1975, §4.3.4,
eq. 4.51 for a rectangular block; the argument is the same for any planform
because the Laplacian separates). A history is then the Duhamel sum over the
jumps of g in rescaled time (Crank 1975, §4.2.1, eq. 4.34); ramps enter as
64 small jumps each.

The mesh is a Delaunay triangulation (scipy.spatial) of boundary points and a
hexagonal lattice inside (near-equilateral triangles, so the two-point flux of
FiPy's plain ``DiffusionTerm`` is nearly orthogonal), made into a FiPy
``Mesh2D`` (Gmsh is not required). The error is measured against the exact
product of three sheets (rectangular outline) in the tests.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from .geometry import CamPlate, LinkBar

log = logging.getLogger(__name__)

RAMP_JUMPS = 64


# ---------------------------------------------------------------- outline


@dataclass(frozen=True)
class Outline:
    """A planform: ``inside(x, y)``, boundary samples (all edges) and the contact edge."""

    part: object
    boundary: np.ndarray   # (n, 2) points along every edge, spacing <= requested
    contact: np.ndarray    # (m, 2) points along the contact edge

    def inside(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return _inside(self.part, x, y)


def _inside(part, x, y) -> np.ndarray:
    if isinstance(part, CamPlate):
        return _in_polygon(np.asarray(part.profile_x), np.asarray(part.profile_y), x, y) & (
            np.hypot(x, y) > part.bore_radius)
    half = 0.5 * part.width
    near_a, near_b = np.hypot(x, y), np.hypot(x - part.length, y)
    solid = (((x >= 0) & (x <= part.length) & (np.abs(y) <= half)) |
             (near_a <= part.boss_outer_radius) | (near_b <= part.boss_outer_radius))
    return solid & (near_a > part.boss_inner_radius) & (near_b > part.boss_inner_radius)


def _in_polygon(px, py, x, y) -> np.ndarray:
    """Even-odd ray casting (Shimrat 1962, CACM algorithm 112), vectorised over points."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    inside = np.zeros(x.shape, bool)
    qx, qy = np.roll(px, 1), np.roll(py, 1)
    for ax, ay, bx, by in zip(px, py, qx, qy):
        crosses = (ay > y) != (by > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            at = ax + (y - ay) * (bx - ax) / (by - ay)
        inside ^= crosses & (x < at)
    return inside


def _resample(px, py, spacing: float, closed: bool = True) -> np.ndarray:
    """Points every <= ``spacing`` along a polyline (closed: back to the start)."""
    pts = np.column_stack([px, py])
    if closed:
        pts = np.vstack([pts, pts[:1]])
    out = []
    for a, b in zip(pts[:-1], pts[1:]):
        count = max(1, math.ceil(np.hypot(*(b - a)) / spacing))
        out.append(a + (b - a) * (np.arange(count) / count)[:, None])
    if not closed:
        out.append(pts[-1:])
    return np.vstack(out)


def _circle(cx, cy, radius, spacing) -> np.ndarray:
    count = max(12, math.ceil(2 * np.pi * radius / spacing))
    angle = 2 * np.pi * np.arange(count) / count
    return np.column_stack([cx + radius * np.cos(angle), cy + radius * np.sin(angle)])


def outline(part, spacing: float) -> Outline:
    """Boundary samples of a CamPlate (contact: the profile) or LinkBar (contact: every edge)."""
    if isinstance(part, CamPlate):
        profile = _resample(np.asarray(part.profile_x), np.asarray(part.profile_y), spacing)
        bore = (_circle(0.0, 0.0, part.bore_radius, spacing) if part.bore_radius > 0
                else np.empty((0, 2)))
        return Outline(part, np.vstack([profile, bore]), profile)
    half, length = 0.5 * part.width, part.length
    ro, ri = part.boss_outer_radius, part.boss_inner_radius
    pieces = [_circle(0.0, 0.0, ro, spacing), _circle(length, 0.0, ro, spacing),
              _resample([0.0, length], [half, half], spacing, closed=False),
              _resample([0.0, length], [-half, -half], spacing, closed=False)]
    candidates = np.vstack(pieces)
    shrink = 1 - 1e-9
    x, y = candidates.T
    strictly_inside = ((x > 0) & (x < length) & (np.abs(y) < half * shrink)) | (
        np.hypot(x, y) < ro * shrink) | (np.hypot(x - length, y) < ro * shrink)
    outer = candidates[~strictly_inside]
    holes = np.vstack([_circle(0.0, 0.0, ri, spacing), _circle(length, 0.0, ri, spacing)])
    boundary = np.vstack([outer, holes])
    return Outline(part, boundary, boundary)


def outline_extent(part) -> tuple[float, float]:
    """Bounding-box size of the planform (m)."""
    if isinstance(part, CamPlate):
        return (float(np.ptp(part.profile_x)), float(np.ptp(part.profile_y)))
    return (part.length + 2 * part.boss_outer_radius, max(part.width, 2 * part.boss_outer_radius))


# ------------------------------------------------------------------- mesh


@dataclass(frozen=True)
class Triangulation:
    """Triangles of a planform (physical metres) with each triangle's distance to the contact edge."""

    points: np.ndarray      # (n, 2)
    triangles: np.ndarray   # (m, 3)
    contact_distance: np.ndarray  # (m,)

    def fipy_mesh(self, scale: np.ndarray):
        """FiPy Mesh2D with coordinates multiplied by ``scale`` per axis."""
        from fipy.meshes.mesh2D import Mesh2D

        edges = np.sort(np.stack([self.triangles[:, [0, 1]], self.triangles[:, [1, 2]],
                                  self.triangles[:, [2, 0]]], axis=1).reshape(-1, 2), axis=1)
        unique, inverse = np.unique(edges, axis=0, return_inverse=True)
        vertices = (self.points * np.asarray(scale)[None, :]).T
        return Mesh2D(vertices, unique.T, inverse.reshape(-1, 3).T)


def triangulate(part, spacing: float) -> Triangulation:
    """Delaunay triangulation of boundary samples plus a hexagonal interior lattice."""
    from scipy.spatial import Delaunay, cKDTree

    shape = outline(part, spacing)
    lo, hi = shape.boundary.min(axis=0), shape.boundary.max(axis=0)
    rows = np.arange(lo[1], hi[1] + spacing, spacing * np.sqrt(3) / 2)
    xs = np.arange(lo[0], hi[0] + spacing, spacing)
    lattice = np.vstack([np.column_stack([xs + (i % 2) * spacing / 2, np.full(xs.size, y)])
                         for i, y in enumerate(rows)])
    boundary_tree = cKDTree(shape.boundary)
    keep = shape.inside(*lattice.T) & (boundary_tree.query(lattice)[0] > 0.5 * spacing)
    points = np.vstack([shape.boundary, lattice[keep]])
    triangles = Delaunay(points).simplices
    centroid = points[triangles].mean(axis=1)
    corners = points[triangles]
    edge_a, edge_b = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    area = 0.5 * np.abs(edge_a[:, 0] * edge_b[:, 1] - edge_a[:, 1] * edge_b[:, 0])
    # inside the outline, and not a sliver of collinear boundary points (zero volume)
    triangles = triangles[shape.inside(*centroid.T) & (area > 1e-6 * spacing ** 2)]
    used = np.unique(triangles)
    renumber = np.full(len(points), -1)
    renumber[used] = np.arange(used.size)
    points, triangles = points[used], renumber[triangles]
    centroid = points[triangles].mean(axis=1)
    contact_tree = cKDTree(_resample_points(shape.contact, spacing / 8))
    distance = contact_tree.query(centroid)[0]
    log.debug("triangulated %s: %d points, %d triangles", type(part).__name__, len(points),
              len(triangles))
    return Triangulation(points, triangles, distance)


def _resample_points(points: np.ndarray, spacing: float) -> np.ndarray:
    """Denser samples between consecutive boundary points closer than 4 spacings."""
    nxt = np.roll(points, -1, axis=0)
    gap = np.hypot(*(nxt - points).T)
    near = gap < 40 * spacing
    fractions = np.arange(8) / 8
    extra = points[near, None, :] + (nxt - points)[near, None, :] * fractions[None, :, None]
    return np.vstack([points, extra.reshape(-1, 2)])


# ------------------------------------------------------------------ solve


@dataclass(frozen=True)
class StepResponse:
    """Unsaturated fraction u(tau*) of a unit surface step on geometric nodes."""

    nodes: np.ndarray        # scaled time, nodes[0] = 0
    mean: np.ndarray         # (n,)
    layer: np.ndarray        # (n,)
    fields: np.ndarray | None  # (n, cells)

    def at(self, tau: np.ndarray, values: np.ndarray) -> np.ndarray:
        """u at arbitrary tau* >= 0: PCHIP in log tau, u = 1 - (1 - u_1) sqrt(tau/tau_1) below
        the first step (Crank 1975 eq. 4.20: early uptake grows as sqrt(t))."""
        from scipy.interpolate import PchipInterpolator

        tau = np.asarray(tau, float)
        first = self.nodes[1]
        spline = PchipInterpolator(np.log(self.nodes[1:]), values[1:], axis=0, extrapolate=True)
        inside = np.clip(tau, first, self.nodes[-1])
        out = spline(np.log(inside))
        early = tau < first
        if early.any():
            ratio = np.sqrt(np.clip(tau[early], 0.0, None) / first)
            out[early] = 1.0 - (1.0 - values[1]) * (ratio[:, None] if values.ndim > 1 else ratio)
        return out


def step_response(disc, end: float, per_doubling: int, first_step: float, *,
                  keep_fields: bool = False, part: str = "") -> tuple[StepResponse, float]:
    """Backward-Euler unit-step response, Richardson-extrapolated in time; also
    the largest coarse/fine difference of the mean (the time-error indicator)."""
    from . import fv
    from .timesteps import geometric_steps

    nodes = geometric_steps(0.0, end, first_step, per_doubling)
    fine = np.sort(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
    runs = [fv.march(disc, grid, np.ones(grid.size), 0.0, np.searchsorted(grid, nodes),
                     keep_fields=keep_fields, part=part) for grid in (nodes, fine)]
    coarse, refined = runs

    def unsaturated(a, b):
        return 1.0 - (2.0 * b - a)
    fields = unsaturated(coarse.fields, refined.fields) if keep_fields else None
    pair = float(np.max(np.abs(refined.mean - coarse.mean)))
    return StepResponse(nodes, unsaturated(coarse.mean, refined.mean),
                        unsaturated(coarse.layer, refined.layer), fields), pair


def surface_jumps(exposure, tau_star_of) -> tuple[np.ndarray, np.ndarray]:
    """(tau*_j, delta g_j): the jumps of the surface value (the start: g(0) - c0),
    each ramp as ``RAMP_JUMPS`` jumps at sub-interval midpoints (midpoint rule of
    the Duhamel-Stieltjes integral, Crank 1975 eq. 4.34)."""
    edges = np.asarray(exposure.change_times, float)
    g = exposure.surface_moisture
    taus, jumps = [], []
    for k in range(edges.size - 1):
        start = edges[k]
        if exposure.ramp[k] and k > 0:
            sub = np.linspace(start, edges[k + 1], RAMP_JUMPS + 1)
            values = np.asarray(g(sub), float)
            values[0] = g(np.array([start - 1e-9 * (start - edges[k - 1])]))[0]
            taus.append(tau_star_of(0.5 * (sub[:-1] + sub[1:])))
            jumps.append(np.diff(values))
            continue
        before = (exposure.initial_moisture if k == 0 else
                  float(g(np.array([start - 1e-9 * (start - edges[k - 1])]))[0]))
        taus.append(tau_star_of(np.array([start])))
        jumps.append(np.array([float(g(np.array([start]))[0]) - before]))
    return np.concatenate(taus), np.concatenate(jumps)


def duhamel(outputs: np.ndarray, jump_taus: np.ndarray, jumps: np.ndarray, c0: float,
            fraction) -> np.ndarray:
    """c(tau) = c0 + sum_j dg_j (1 - u(tau - tau_j)) over the jumps before tau."""
    total = np.full((outputs.size,) + fraction(np.zeros(1)).shape[1:], float(c0))
    for tau_j, dg in zip(jump_taus, jumps):
        later = outputs >= tau_j
        if dg == 0.0 or not later.any():
            continue
        total[later] += dg * (1.0 - fraction(outputs[later] - tau_j))
    return total


def solve_plane(geometry, diffusivity, exposure, times, chosen, *,
                surface_layer_depth: float = 5e-4, store_fields: bool = False, part: str = ""):
    """CamPlate / LinkBar: planform step response x sheet step response, Duhamel over the history."""
    from . import fv
    from .solve import FIRST_STEP, PAIR_TO_EXTRAPOLATED, TIME_ERROR, DiffusionResult, _scales
    from .timesteps import rescaled_time

    scales = _scales(geometry, diffusivity, exposure)
    d = tuple(float(v) for v in diffusivity.pre_exponential)
    n_x, n_y, n_z = chosen.cells_per_axis
    extent = outline_extent(geometry)
    spacing = max(extent[0] / n_x * math.sqrt(d[2] / d[0]), extent[1] / n_y *
                  math.sqrt(d[2] / d[1])) * math.sqrt(d[0] / d[2])
    mesh = triangulate(geometry, spacing)
    planar = fv.plane(mesh, geometry.thickness, mesh.contact_distance, surface_layer_depth, d)
    sheet = fv.sheet(geometry.thickness, n_z, surface_layer_depth)

    def tau_star(t):
        return scales.star(rescaled_time(diffusivity, exposure, t, scales.a_ref))

    outputs = tau_star(np.asarray(times, float))
    end = max(float(outputs.max()), 10 * FIRST_STEP)
    u_plane, pair_plane = step_response(planar, end, chosen.steps_per_doubling, FIRST_STEP,
                                        keep_fields=store_fields, part=part)
    u_sheet, pair_sheet = step_response(sheet, end, chosen.steps_per_doubling, FIRST_STEP,
                                        keep_fields=store_fields, part=part)
    jump_taus, jumps = surface_jumps(exposure, tau_star)

    def mean_fraction(tau):
        return u_plane.at(tau, u_plane.mean) * u_sheet.at(tau, u_sheet.mean)

    def layer_fraction(tau):  # contact edge band x the whole thickness
        return u_plane.at(tau, u_plane.layer) * u_sheet.at(tau, u_sheet.mean)

    c0 = exposure.initial_moisture
    mean = duhamel(outputs, jump_taus, jumps, c0, mean_fraction)
    layer = duhamel(outputs, jump_taus, jumps, c0, layer_fraction)
    pair = max(pair_plane, pair_sheet)
    time_part = TIME_ERROR / chosen.steps_per_doubling ** 2
    estimate = chosen.error_estimate - time_part + PAIR_TO_EXTRAPOLATED * pair ** 2
    steps = 3 * 2 * (u_plane.nodes.size - 1)
    result = DiffusionResult(np.asarray(times, float), mean, layer, "plane",
                             planar.cells + n_z, steps, float(estimate), chosen.reason)
    if store_fields:
        mid = int(np.argmin(np.abs(sheet.coordinates["z"] - 0.5 * geometry.thickness)))

        def field_fraction(tau):  # mid-thickness plane
            return u_plane.at(tau, u_plane.fields) * u_sheet.at(tau, u_sheet.fields[:, mid])[:, None]
        result.fields = duhamel(outputs, jump_taus, jumps, c0, field_fraction)
        result.cell_coordinates = {"x": planar.coordinates["x"], "y": planar.coordinates["y"],
                                   "z": np.full(planar.cells, sheet.coordinates["z"][mid])}
    log.debug("%s plane: %d triangles x %d sheet cells", part, planar.cells, n_z)
    return result

