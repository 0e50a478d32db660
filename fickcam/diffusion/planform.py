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

from .geometry import CamPlate

log = logging.getLogger(__name__)

RAMP_JUMPS = 64
LAYER_POINTS = 12
SMOOTH_TURN = 0.2  # rad: a vertex turning less samples a smooth arc, more is a corner
ARC_POINTS = 256   # samples of a full circle in the expansion's outline
LAYER_TOLERANCE = 4.0  # the contact layer may be a few times less accurate than the mean


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


# ------------------------------------------------- short-time expansion


@dataclass(frozen=True)
class ShortTime:
    """Short-time expansion of the planform's unit-step uptake, scaled coordinates.

    For a plane region with piecewise smooth boundary, Dirichlet data 1, initial
    value 0 and unit diffusivity, the uptake fraction is
    F(t) = [2 P sqrt(t/pi) - (sum_i c(gamma_i)) t + (b_2/2) K_2 t^(3/2)] / A + ...
    (Carslaw & Jaeger 1959 §13.3 / Crank 1975 eq. 5.24 for the disc,
    4 sqrt(t/pi) - t - t^(3/2)/(3 sqrt(pi)); van den Berg & Srisatkunarajah 1990
    for the corner term c(gamma) of a polygon vertex of interior angle gamma; a
    smooth arc is the limit of vertices of small turning e, c = e/2, giving (1/2)
    integral of curvature). The t^(k+1)/2 coefficient of a smooth boundary is local
    and, by dimensions, a universal multiple of K_k = integral kappa^k ds for
    k <= 3, so the disc's coefficients b_k (Crank eq. 5.24 continued,
    ``exact._cylinder_short_coefficients``) fix it: (b_k / 2) K_k. The k = 3 and
    k = 4 terms (doubled, |kappa|) plus kappa t^(3/2) per corner (curved sides at a
    corner) are the error indicator. The layer of depth delta under the contact edge
    follows the half-space solution erfc(x / 2 sqrt t) (Crank 1975 eq. 2.45) with
    first-order curvature terms, averaged over the depth; its indicator is the
    second-order size kappa^2 delta (sqrt t + delta) / 2 (3-13x the error measured on
    discs)."""

    area: float
    perimeter: float
    corner_sum: float
    curvature_square: float       # K_2 over smooth arcs
    curvature_cube: float         # integral |kappa|^3 ds over smooth arcs
    curvature_fourth: float       # integral kappa^4 ds over smooth arcs
    corner_curvature: float       # sum over corners of the adjacent |kappa|
    max_curvature: float
    contact_weights: np.ndarray   # (k,) edge-length weights, sum 1
    contact_depths: np.ndarray    # (k,) scaled layer depth along each contact segment
    contact_curvature: np.ndarray  # (k,) scaled curvature of each contact segment
    contact_kappa_square: float   # layer-weighted mean of kappa^2 over the contact edge

    def uptake(self, tau):
        tau = np.asarray(tau, float)
        b = _disc_coefficients()
        return (2 * self.perimeter * np.sqrt(tau / np.pi) - self.corner_sum * tau
                + 0.5 * b[2] * self.curvature_square * tau ** 1.5) / self.area

    def uptake_error(self, tau):
        tau = np.asarray(tau, float)
        b = _disc_coefficients()
        return (abs(b[3]) * self.curvature_cube * tau ** 2 + abs(b[4]) * self.curvature_fourth
                * tau ** 2.5 + self.corner_curvature * tau ** 1.5) / self.area

    def layer_uptake(self, tau):
        """Mean over the contact layer: erfc(x / 2 sqrt t) (Crank 1975 eq. 2.45) with the
        first-order curvature terms of a cylinder, c = sqrt(a/r) erfc(...) (Carslaw &
        Jaeger 1959 §13.3) and area weight r/a, i.e. (1 - kappa x / 2) erfc over a
        layer of area (1 - kappa delta / 2) delta per unit length (Gauss-Legendre in x)."""
        from scipy.special import erfc

        tau = np.atleast_1d(np.asarray(tau, float))
        x, w = np.polynomial.legendre.leggauss(LAYER_POINTS)
        depth, kappa = self.contact_depths, self.contact_curvature
        x = 0.5 * (x + 1)[:, None] * depth[None, :]            # (q, k)
        root = 2 * np.sqrt(np.maximum(tau, 1e-300))[:, None, None]
        profile = erfc(x[None] / root) * (1 - 0.5 * kappa[None, None, :] * x[None])
        integral = 0.5 * np.einsum("q,tqk->tk", w, profile) * depth[None, :]
        band = integral / (depth * (1 - 0.5 * kappa * depth))[None, :]
        return band @ self.contact_weights

    def layer_error(self, tau):
        tau = np.asarray(tau, float)
        depth = float(np.max(self.contact_depths))  # second order in kappa, measured on discs
        return 0.5 * self.contact_kappa_square * depth * (np.sqrt(tau) + depth)

    def switch(self, tolerance: float) -> float:
        """Largest scaled time (on a log grid) with the uptake error indicator times the
        sheet's unsaturated fraction (Crank 1975 eq. 4.18) <= tolerance."""
        from .exact import sheet_uptake

        grid = np.geomspace(1e-8, 1e4, 1201)
        ok = self.uptake_error(grid) * (1.0 - sheet_uptake(grid)) <= tolerance
        return float(grid[np.argmin(ok)] if not ok.all() else grid[-1]) if ok[0] else 0.0


def _disc_coefficients() -> np.ndarray:
    from .exact import _cylinder_short_coefficients

    return _cylinder_short_coefficients()


def corner_coefficient(gamma: np.ndarray) -> np.ndarray:
    """c(gamma) = integral_0^inf 4 sinh((pi - gamma) x) / (sinh(pi x) cosh(gamma x)) dx
    (van den Berg & Srisatkunarajah 1990; c(pi/2) = 4/pi reproduces the product of
    two half-spaces, Crank 1975 eq. 4.51), by the trapezoidal rule on [0, 60/pi]."""
    gamma = np.asarray(gamma, float)[:, None]
    x = np.linspace(1e-9, 60 / np.pi, 6001)[None, :]
    integrand = 4 * np.sinh((np.pi - gamma) * x) / (np.sinh(np.pi * x) * np.cosh(gamma * x))
    return np.trapezoid(integrand, x, axis=1)


def _arc_circle(cx, cy, radius, spacing) -> np.ndarray:
    return _circle(cx, cy, radius, min(spacing, 2 * np.pi * radius / ARC_POINTS))


def expansion_switch(part, d, tolerance: float) -> float:
    """Scaled time up to which the short-time expansion's mean is within ``tolerance``
    (0 when the outline has no expansion)."""
    expansion = short_time(part, np.asarray(planar_scale(part, d)), part.thickness / 100,
                           part.thickness / 20)
    return 0.0 if expansion is None else expansion.switch(tolerance)


def _boundary_loops(part, spacing: float) -> tuple[list[np.ndarray], list[bool]]:
    """Closed polylines (material on the left: outer CCW, holes CW) and whether each
    is a contact edge; None when the outline is not covered (LinkBar bosses narrower
    than the bar, or overlapping bosses)."""
    if isinstance(part, CamPlate):
        outer = np.column_stack([part.profile_x, part.profile_y]).astype(float)
        loops, contact = [outer], [True]
        if part.bore_radius > 0:
            loops.append(_arc_circle(0.0, 0.0, part.bore_radius, spacing)[::-1])
            contact.append(False)
        return loops, contact
    half, length = 0.5 * part.width, part.length
    ro, ri = part.boss_outer_radius, part.boss_inner_radius
    if half > ro or length <= 2 * ro:
        return None
    phi = math.asin(half / ro)
    x0 = math.sqrt(ro * ro - half * half)
    count = max(ARC_POINTS, math.ceil((2 * np.pi - 2 * phi) * ro / spacing))
    arc_a = np.linspace(phi, 2 * np.pi - phi, count)
    arc_b = np.linspace(-np.pi + phi, np.pi - phi, count)
    bottom = _resample([x0, length - x0], [-half, -half], spacing, closed=False)[1:-1]
    top = _resample([length - x0, x0], [half, half], spacing, closed=False)[1:-1]
    outer = np.vstack([np.column_stack([ro * np.cos(arc_a), ro * np.sin(arc_a)]), bottom,
                       np.column_stack([length + ro * np.cos(arc_b), ro * np.sin(arc_b)]), top])
    holes = [_arc_circle(cx, 0.0, ri, spacing)[::-1] for cx in (0.0, length)] if ri > 0 else []
    return [outer] + holes, [True] * (1 + len(holes))


def short_time(part, scale: np.ndarray, layer_depth: float, spacing: float) -> ShortTime | None:
    """The expansion's coefficients in scaled coordinates (x' = x * scale)."""
    found = _boundary_loops(part, spacing)
    if found is None:
        return None
    loops, contact = found
    area = perimeter = corners = curvature_square = curvature_cube = curvature_fourth = 0.0
    corner_curvature = max_curvature = 0.0
    weights, depths, curvatures = [], [], []
    for loop, is_contact in zip(loops, contact):
        p = loop * scale[None, :]
        edge = np.roll(p, -1, axis=0) - p
        length = np.hypot(*edge.T)
        incoming = np.roll(edge, 1, axis=0)
        turn = np.arctan2(incoming[:, 0] * edge[:, 1] - incoming[:, 1] * edge[:, 0],
                          np.einsum("ij,ij->i", incoming, edge))
        smooth = np.abs(turn) < SMOOTH_TURN
        corners += 0.5 * turn[smooth].sum() + corner_coefficient(np.pi - turn[~smooth]).sum()
        ds = 0.5 * (length + np.roll(length, 1))
        kappa = np.where(smooth, turn / ds, 0.0)
        curvature_square += np.sum(kappa ** 2 * ds)
        curvature_cube += np.sum(np.abs(kappa) ** 3 * ds)
        curvature_fourth += np.sum(kappa ** 4 * ds)
        corner_curvature += np.sum(np.maximum(np.abs(np.roll(kappa, 1)),
                                              np.abs(np.roll(kappa, -1)))[~smooth])
        max_curvature = max(max_curvature, float(np.max(np.abs(kappa))))
        area += 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
        perimeter += length.sum()
        if is_contact:
            # physical normal n of each segment -> scaled strip width delta / |S^-1 n|
            physical = np.roll(loop, -1, axis=0) - loop
            normal = np.column_stack([physical[:, 1], -physical[:, 0]])
            normal /= np.hypot(*normal.T)[:, None]
            depths.append(layer_depth / np.hypot(*(normal / scale[None, :]).T))
            weights.append(length * depths[-1])
            curvatures.append(0.5 * (kappa + np.roll(kappa, -1)))
    weights = np.concatenate(weights)
    if not (area > 0 and weights.sum() > 0):  # clockwise outline or no layer: mesh only
        return None
    return ShortTime(area, perimeter, corners, curvature_square, curvature_cube, curvature_fourth,
                     corner_curvature, max_curvature,
                     weights / weights.sum(), np.concatenate(depths), np.concatenate(curvatures),
                     float(np.concatenate(curvatures) ** 2 @ (weights / weights.sum())))


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


def planar_scale(part, d) -> tuple[float, float]:
    """Physical -> scaled in-plane coordinate factors sqrt(D_z / D_i) / L (Crank eq. 2.13)."""
    return tuple(math.sqrt(d[2] / d[i]) / part.thickness for i in (0, 1))


def _blend(response: StepResponse, values: np.ndarray, series, indicator, tolerance: float,
           weight):
    """Unsaturated fraction from the short-time expansion ``series`` up to a switch node
    and from the mesh after it. Errors are weighted by ``weight``, the sheet's
    unsaturated fraction that multiplies the planform's in the product.

    The expansion is kept while its ``indicator`` is below ``tolerance`` or below half
    the largest mesh-expansion mismatch so far (then the mesh is the worse of the two).
    The mesh's relative uptake error at the switch (mismatch / uptake over the octave
    before it) is assumed to persist (non-orthogonal two-point fluxes err in proportion
    to the flux), so its error after the switch is that ratio times the uptake. Returns
    the fraction and the larger of the two error estimates."""
    nodes = response.nodes[1:]
    w = weight(nodes)
    expected = indicator(nodes) * w
    mismatch = np.abs(values[1:] - (1.0 - series(nodes))) * w
    trusted = expected <= np.maximum(tolerance, 0.5 * np.maximum.accumulate(mismatch))
    last = int(np.argmin(trusted)) - 1 if not trusted.all() else nodes.size - 1
    if last < 0:
        return (lambda tau: response.at(tau, values)), None
    switch = float(nodes[last]) if last < nodes.size - 1 else np.inf  # inf: expansion only
    error = float(expected[last])
    if last < nodes.size - 1:
        octave = (nodes >= 0.5 * switch) & (nodes <= switch)
        uptake = np.maximum(1.0 - values[1:], np.finfo(float).tiny)
        ratio = np.max(mismatch[octave] / (uptake[octave] * w[octave]))
        error = max(error, float(np.max(ratio * uptake[last:] * w[last:])))

    def fraction(tau):
        tau = np.asarray(tau, float)
        early = tau < switch
        out = response.at(tau, values)
        if early.any():
            out[early] = 1.0 - series(tau[early])
        return out
    log.debug("switch to mesh at tau*=%.3g, error %.2g", switch, error)
    return fraction, error


def _expansion_only(expansion, outputs, end, jump_taus, jumps, exposure, times, sheet_fraction,
                    chosen, part):
    """Every output lies where the short-time expansion meets the tolerance: no mesh.
    The error indicators grow with time, so their weighted maximum up to ``end`` bounds
    the error."""
    from .solve import DiffusionResult

    grid = np.geomspace(1e-8 * end, end, 400)
    weight = sheet_fraction(grid)
    mean_error = float(np.max(expansion.uptake_error(grid) * weight))
    layer_error = float(np.max(expansion.layer_error(grid) * weight))

    def mean_fraction(tau):
        return (1.0 - expansion.uptake(tau)) * sheet_fraction(tau)

    def layer_fraction(tau):
        return (1.0 - expansion.layer_uptake(tau)) * sheet_fraction(tau)

    c0 = exposure.initial_moisture
    mean = duhamel(outputs, jump_taus, jumps, c0, mean_fraction)
    layer = duhamel(outputs, jump_taus, jumps, c0, layer_fraction)
    log.debug("%s plane: short-time expansion only, error %.2g (layer %.2g)", part,
              mean_error, layer_error)
    return DiffusionResult(np.asarray(times, float), mean, layer, "plane", 0, 0,
                           mean_error, chosen.reason + "; no mesh needed")


def solve_plane(geometry, diffusivity, exposure, times, chosen, *,
                surface_layer_depth: float = 5e-4, store_fields: bool = False, part: str = ""):
    """CamPlate / LinkBar: planform step response x sheet step response, Duhamel over the history."""
    from . import exact, fv
    from .solve import FIRST_STEP, PAIR_TO_EXTRAPOLATED, TIME_ERROR, DiffusionResult, _scales
    from .timesteps import rescaled_time

    scales = _scales(geometry, diffusivity, exposure)
    d = tuple(float(v) for v in diffusivity.pre_exponential)
    n_x, n_y, n_z = chosen.cells_per_axis
    extent = outline_extent(geometry)
    spacing = max(extent[0] / n_x * math.sqrt(d[2] / d[0]), extent[1] / n_y *
                  math.sqrt(d[2] / d[1])) * math.sqrt(d[0] / d[2])

    def tau_star(t):
        return scales.star(rescaled_time(diffusivity, exposure, t, scales.a_ref))

    def sheet_fraction(tau):  # exact: Crank 1975 eqs. 4.18 / 4.20
        return 1.0 - exact.sheet_uptake(np.maximum(tau, 0.0))

    outputs = tau_star(np.asarray(times, float))
    end = max(float(outputs.max()), 10 * FIRST_STEP)
    jump_taus, jumps = surface_jumps(exposure, tau_star)
    expansion = short_time(geometry, np.asarray(planar_scale(geometry, d)), surface_layer_depth,
                           spacing)
    tolerance = chosen.expansion_tolerance
    if (expansion is not None and not store_fields and tolerance > 0
            and expansion.switch(tolerance) >= end):
        return _expansion_only(expansion, outputs, end, jump_taus, jumps, exposure, times,
                               sheet_fraction, chosen, part)
    mesh = triangulate(geometry, spacing)
    planar = fv.plane(mesh, geometry.thickness, mesh.contact_distance, surface_layer_depth, d)
    sheet = fv.sheet(geometry.thickness, n_z, surface_layer_depth)
    u_plane, pair_plane = step_response(planar, end, chosen.steps_per_doubling, FIRST_STEP,
                                        keep_fields=store_fields, part=part)
    if store_fields:
        u_sheet, _ = step_response(sheet, end, chosen.steps_per_doubling, FIRST_STEP,
                                   keep_fields=True, part=part)
    if expansion is None:
        def plane_mean(tau):
            return u_plane.at(tau, u_plane.mean)

        def plane_layer(tau):
            return u_plane.at(tau, u_plane.layer)
        mean_error = layer_error = None
    else:
        plane_mean, mean_error = _blend(u_plane, u_plane.mean, expansion.uptake,
                                        expansion.uptake_error, tolerance, sheet_fraction)
        plane_layer, layer_error = _blend(u_plane, u_plane.layer, expansion.layer_uptake,
                                          expansion.layer_error, LAYER_TOLERANCE * tolerance,
                                          sheet_fraction)

    def mean_fraction(tau):
        return plane_mean(tau) * sheet_fraction(tau)

    def layer_fraction(tau):  # contact edge band x the whole thickness
        return plane_layer(tau) * sheet_fraction(tau)

    c0 = exposure.initial_moisture
    mean = duhamel(outputs, jump_taus, jumps, c0, mean_fraction)
    layer = duhamel(outputs, jump_taus, jumps, c0, layer_fraction)
    pair = pair_plane  # the sheet is exact (its march only serves the stored fields)
    if mean_error is None:  # no expansion for this outline: the mesh's error model
        mean_error = chosen.error_estimate - TIME_ERROR / chosen.steps_per_doubling ** 2
    estimate = mean_error + PAIR_TO_EXTRAPOLATED * pair ** 2
    log.debug("%s plane: error estimate %.2g (layer %s)", part, estimate, layer_error)
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

