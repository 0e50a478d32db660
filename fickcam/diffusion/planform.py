"""Prismatic parts (CamPlate, LinkBar): a 2-D triangle mesh of the outline times
the through-thickness sheet.

For a prism whose every surface holds the same value g and which starts
uniform at c0, the unsaturated fraction u = (g - c)/(g - c0) of a unit step
is the product u_plane(x, y, tau) u_sheet(z, tau) (Crank 1975, §4.3.4,
eq. 4.51 for a rectangular block; the argument is the same for any planform
because the Laplacian separates). A history is then the Duhamel sum over the
jumps of g in rescaled time (Crank 1975, §4.2.1, eq. 4.34); ramps enter as
64 small jumps each.

The planform's unit-step response comes from the exact short-time expansion of
the outline (``ShortTime``) up to a switch time and from P1 finite elements on
a triangle mesh graded from the outline after it (``trimesh``; FiPy's two-point
flux between centroids is not consistent on graded meshes). ``plan_plane``
sizes that mesh and the time steps with the error model the blend reports, so
``fickcam check`` shows the error ``solve`` will estimate. The errors are
measured against the exact product of three sheets (rectangle), the finite
cylinder, the annulus series (plate with a bore) and space-extrapolated fine
meshes (the demo cam) in tests/test_diffusion_plane.py.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field
from functools import cached_property, lru_cache

import numpy as np

from .geometry import CamPlate

log = logging.getLogger(__name__)

RAMP_JUMPS = 64
LAYER_POINTS = 12
SMOOTH_TURN = 0.2  # rad: a vertex turning less samples a smooth arc, more is a corner
ARC_POINTS = 1024  # samples of a full circle in the outline (chord error (2 pi / N)^2 / 8)
LAYER_TOLERANCE = 4.0  # the contact layer may be a few times less accurate than the mean
TAIL_FROM = 4          # first term of the disc series left to the error indicator
CHORD_RAYS = 256       # rays cast per outline loop for the facing-edge term


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
    """Triangles of a planform (physical metres) with each triangle's distance to the contact
    edge; ``on_outline`` marks the points on the outline, ``contact(points, bound)`` gives
    their distance to the contact edge (inf beyond ``bound``)."""

    points: np.ndarray      # (n, 2)
    triangles: np.ndarray   # (m, 3)
    contact_distance: np.ndarray  # (m,)
    on_outline: np.ndarray | None = None  # (n,) bool
    contact: object = field(default=None, repr=False, compare=False)


def triangulate(part, spacing: float, *, growth: float | None = None,
                stretch: tuple[float, float] = (1.0, 1.0)) -> Triangulation:
    """Triangles of a planform with edges of about ``spacing`` (m) along the outline.

    Without ``growth``: boundary samples plus a uniform hexagonal lattice. With ``growth``
    g: rows graded from the outline, spacing (1 + g)^k ``spacing`` (``trimesh``), built in
    the coordinates (stretch_x x, stretch_y y), where ``spacing`` is measured and the
    triangles are near-equilateral (the scaled coordinates of anisotropic diffusion,
    Crank 1975 eq. 2.13). Outlines without closed loops (a LinkBar whose bosses are
    narrower than the bar, or overlap) get the uniform lattice."""
    found = None if growth is None else _boundary_loops(part, spacing / max(stretch))
    if found is None:
        return _lattice_triangulation(part, spacing / max(stretch))
    from . import trimesh

    loops, contact = found
    factor = np.asarray(stretch, float)
    mesh = trimesh.graded_mesh([loop * factor for loop in loops], spacing, growth)
    points = mesh.points / factor
    distance = _distance_to([loop for loop, edge in zip(loops, contact) if edge], spacing / 8)
    log.debug("graded mesh of %s: %d points, %d triangles", type(part).__name__, len(points),
              len(mesh.triangles))
    return Triangulation(points, mesh.triangles, distance(points[mesh.triangles].mean(axis=1)),
                         mesh.on_outline, distance)


def _distance_to(loops: list[np.ndarray], spacing: float):
    """Distance (m) from points to the closed polylines ``loops``, by samples every ``spacing``
    (inf beyond an optional bound: a bounded search is much faster)."""
    from scipy.spatial import cKDTree

    from .trimesh import resample_loop

    return _bounded_query(cKDTree(np.vstack([resample_loop(loop, spacing) for loop in loops])))


def _bounded_query(tree):
    """points, bound -> distance to the nearest sample of ``tree`` (inf beyond ``bound``)."""
    return lambda points, bound=np.inf: tree.query(points, distance_upper_bound=bound)[0]


def _lattice_triangulation(part, spacing: float) -> Triangulation:
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
    log.debug("triangulated %s: %d points, %d triangles", type(part).__name__, len(points),
              len(triangles))
    return Triangulation(points, triangles, contact_tree.query(centroid)[0],
                         used < len(shape.boundary),
                         _bounded_query(contact_tree))


def _resample_points(points: np.ndarray, spacing: float) -> np.ndarray:
    """Denser samples between consecutive boundary points closer than 4 spacings."""
    nxt = np.roll(points, -1, axis=0)
    gap = np.hypot(*(nxt - points).T)
    near = gap < 40 * spacing
    fractions = np.arange(8) / 8
    extra = points[near, None, :] + (nxt - points)[near, None, :] * fractions[None, :, None]
    return np.vstack([points, extra.reshape(-1, 2)])


def plane_operator(mesh: Triangulation, part, layer_depth: float, d, name: str = ""):
    """P1 finite elements of the in-plane problem in scaled coordinates (``trimesh``), the
    outline nodes held at the surface value; layer: the integrals of the hat functions
    over the band within ``layer_depth`` of the contact edge (at least the first row)."""
    from . import trimesh

    depth = max(layer_depth, 1.0001 * float(mesh.contact_distance.min()))
    layer = trimesh.layer_weights(mesh.points, mesh.triangles, mesh.contact, depth)
    scaled = mesh.points * np.asarray(planar_scale(part, d))[None, :]
    coordinates = {"x": mesh.points[:, 0], "y": mesh.points[:, 1]}
    return trimesh.p1_operator(scaled, mesh.triangles, mesh.on_outline, layer, coordinates, name)


# ------------------------------------------------- short-time expansion


@dataclass(frozen=True)
class ShortTime:
    """Short-time expansion of the planform's unit-step uptake, scaled coordinates.

    For a plane region with piecewise smooth boundary, Dirichlet data 1, initial
    value 0 and unit diffusivity, the uptake fraction is
    F(t) = [2 P sqrt(t/pi) - (sum_i c(gamma_i)) t + (b_2/2) K_2 t^(3/2)
    + (b_3/2) K_3 t^2] / A + ...
    (Carslaw & Jaeger 1959 §13.3 / Crank 1975 eq. 5.24 for the disc,
    4 sqrt(t/pi) - t - t^(3/2)/(3 sqrt(pi)); van den Berg & Srisatkunarajah 1990
    for the corner term c(gamma) of a polygon vertex of interior angle gamma; a
    smooth arc is the limit of vertices of small turning e, c = e/2, giving (1/2)
    integral of curvature). The t^(k+1)/2 coefficient of a smooth boundary is an
    integral of local invariants (van den Berg & Gilkey 1994, J. Funct. Anal. 120,
    48-71); for k <= 3 the only one of the right dimension is K_k = integral kappa^k ds
    (kappa signed: negative round a hole; kappa_ss integrates to 0), so the disc's
    coefficients b_k (Crank eq. 5.24 continued, ``exact._cylinder_short_coefficients``)
    fix it: (b_k / 2) K_k. From k = 4 on, kappa_s enters too. The error indicator is
    the disc's tail sum_{k=4..8} |b_k| integral |kappa|^k ds t^(k+1)/2 (the exact tail of
    a circle or annulus) with a geometric remainder that turns infinite where the terms
    stop falling, kappa t^(3/2) per corner (curved sides at a corner), and the edge facing
    each point across the part (``facing_edges``); on annuli it is at least twice the
    error wherever the outlines' own 1e-5 allows to tell. The layer of depth delta under the
    contact edge follows the half-space solution erfc(x / 2 sqrt t) (Crank 1975 eq. 2.45)
    with first-order curvature terms, averaged over the depth; its indicator is the
    second-order size kappa^2 delta (sqrt t + delta) / 2 (3-13x the error measured on
    discs)."""

    area: float
    perimeter: float
    corner_sum: float
    curvature_square: float       # K_2 over smooth arcs
    curvature_cube: float         # K_3 = integral kappa^3 ds (signed) over smooth arcs
    curvature_moments: np.ndarray  # integral |kappa|^k ds over smooth arcs, k = 0..8
    corner_curvature: float       # sum over corners of the adjacent |kappa|
    max_curvature: float
    contact_weights: np.ndarray   # (k,) edge-length weights, sum 1
    contact_depths: np.ndarray    # (k,) scaled layer depth along each contact segment
    contact_curvature: np.ndarray  # (k,) scaled curvature of each contact segment
    contact_kappa_square: float   # layer-weighted mean of kappa^2 over the contact edge
    chords: np.ndarray            # (r,) length of inward normals inside the part (``_chords``)
    chord_lengths: np.ndarray     # (r,) outline length each chord stands for

    def uptake(self, tau):
        tau = np.asarray(tau, float)
        b = _disc_coefficients()
        return (2 * self.perimeter * np.sqrt(tau / np.pi) - self.corner_sum * tau
                + 0.5 * b[2] * self.curvature_square * tau ** 1.5
                + 0.5 * b[3] * self.curvature_cube * tau ** 2) / self.area

    def uptake_error(self, tau):
        tau = np.asarray(tau, float)
        b = _disc_coefficients()
        terms = [abs(b[k]) * self.curvature_moments[k] * tau ** (0.5 * (k + 1))
                 for k in range(TAIL_FROM, b.size)]
        return (sum(terms) + _geometric_remainder(terms[-2], terms[-1])
                + self.corner_curvature * tau ** 1.5 + self.facing_edges(tau)) / self.area

    def facing_edges(self, tau):
        """Uptake from the edge facing each part of the outline across the part, which the
        local expansion leaves out: the first image term of a sheet of the chord's width w,
        4 sqrt(t) ierfc(w / 2 sqrt t) per unit length (Crank 1975 eqs. 4.15, 4.20), doubled
        (on rings of width 0.5-1.5 it alone reached 0.99 of the error)."""
        from .exact import ierfc

        root = np.sqrt(np.asarray(tau, float))[..., None]
        argument = self.chords / (2.0 * np.maximum(root, 1e-300))
        near = argument < 6.0  # ierfc(6) < 1e-17
        image = np.zeros(argument.shape)
        image[near] = ierfc(argument[near])
        return (8.0 * root * image) @ self.chord_lengths

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
        """Largest scaled time (on a log grid) up to which the uptake error indicator times
        the sheet's unsaturated fraction (Crank 1975 eq. 4.18) stays <= tolerance."""
        grid, error = self.weighted_error
        ok = error <= tolerance
        return float(grid[np.argmin(ok) - 1] if not ok.all() else grid[-1]) if ok[0] else 0.0

    @cached_property
    def weighted_error(self) -> tuple[np.ndarray, np.ndarray]:
        """(tau, indicator x sheet unsaturated fraction) on a log grid, 100 points a decade."""
        grid = np.geomspace(1e-8, 1e4, 1201)
        return grid, weighted(self.uptake_error(grid), sheet_fraction(grid))


def _geometric_remainder(before, last):
    """Terms after ``last`` bounded by a geometric series of the ratio r = last / before:
    last r / (1 - r); infinite once the terms stop falling (the asymptotic series has
    left its useful range). On annuli this kept the indicator above the true error
    (it was 1.4x below it without)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(before > 0, last / before, 0.0)
        return np.where(ratio < 1.0, last * ratio / (1.0 - ratio), np.inf)


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


@lru_cache(maxsize=16)  # plan and solve of one part share it (parts are immutable)
def expansion_of(part, d, layer_depth: float | None = None) -> ShortTime | None:
    """The outline's short-time expansion in scaled coordinates as plan and solve both see it
    (circles sampled at thickness / 20 or finer); None when the outline has none."""
    depth = part.thickness / 100 if layer_depth is None else layer_depth
    return short_time(part, np.asarray(planar_scale(part, d)), depth, part.thickness / 20)


def expansion_error(expansion: ShortTime, end: float) -> float:
    """The expansion's error indicator times the sheet's unsaturated fraction (which
    multiplies the planform's in the product), largest over (0, end]: the indicators
    grow with time, so this bounds the error of every output up to ``end``."""
    grid, error = expansion.weighted_error
    last = weighted(expansion.uptake_error(end), sheet_fraction(end))
    return float(max(np.max(error[grid <= end], initial=0.0), last))


def weighted(indicator, weight):
    """indicator x weight, infinite wherever the indicator is (also where the weight is 0)."""
    indicator = np.asarray(indicator, float)
    with np.errstate(invalid="ignore"):  # inf x 0
        product = indicator * weight
    return np.where(np.isfinite(indicator), product, np.inf)


def sheet_fraction(tau):
    """Unsaturated fraction of the through-thickness sheet, exact (Crank 1975 eqs. 4.18 / 4.20)."""
    from .exact import sheet_uptake

    return 1.0 - sheet_uptake(np.maximum(tau, 0.0))


def _boundary_loops(part, spacing: float) -> tuple[list[np.ndarray], list[bool]]:
    """Closed polylines (material on the left: outer CCW, holes CW) and whether each
    is a contact edge; None when the outline is not covered (overlapping bosses)."""
    if isinstance(part, CamPlate):
        outer = np.column_stack([part.profile_x, part.profile_y]).astype(float)
        loops, contact = [outer], [True]
        if part.bore_radius > 0:
            loops.append(_arc_circle(0.0, 0.0, part.bore_radius, spacing)[::-1])
            contact.append(False)
        return loops, contact
    half, length = 0.5 * part.width, part.length
    ro, ri = part.boss_outer_radius, part.boss_inner_radius
    if length <= 2 * ro:
        return None
    holes = [_arc_circle(cx, 0.0, ri, spacing)[::-1] for cx in (0.0, length)] if ri > 0 else []
    if half > ro:  # bosses narrower than the bar: half discs on its ends
        return [_narrow_boss_outline(length, half, ro, spacing)] + holes, [True] * (1 + len(holes))
    phi = math.asin(half / ro)
    x0 = math.sqrt(ro * ro - half * half)
    count = max(ARC_POINTS, math.ceil((2 * np.pi - 2 * phi) * ro / spacing))
    arc_a = np.linspace(phi, 2 * np.pi - phi, count)
    arc_b = np.linspace(-np.pi + phi, np.pi - phi, count)
    bottom = _resample([x0, length - x0], [-half, -half], spacing, closed=False)[1:-1]
    top = _resample([length - x0, x0], [half, half], spacing, closed=False)[1:-1]
    outer = np.vstack([np.column_stack([ro * np.cos(arc_a), ro * np.sin(arc_a)]), bottom,
                       np.column_stack([length + ro * np.cos(arc_b), ro * np.sin(arc_b)]), top])
    return [outer] + holes, [True] * (1 + len(holes))


def _narrow_boss_outline(length: float, half: float, radius: float, spacing: float) -> np.ndarray:
    """Counter-clockwise outline of a bar of half-width ``half`` with half discs of a smaller
    ``radius`` on its ends (x = 0 and x = length): straight pieces every <= ``spacing``."""
    count = max(ARC_POINTS // 2, math.ceil(np.pi * radius / spacing))
    arc = np.linspace(0.5 * np.pi, 1.5 * np.pi, count, endpoint=False)

    def straight(*corners):
        xs, ys = np.array(corners, float).T
        return _resample(xs, ys, spacing, closed=False)[:-1]
    return np.vstack([
        np.column_stack([radius * np.cos(arc), radius * np.sin(arc)]),
        straight((0.0, -radius), (0.0, -half), (length, -half), (length, -radius)),
        np.column_stack([length - radius * np.cos(arc), -radius * np.sin(arc)]),
        straight((length, radius), (length, half), (0.0, half), (0.0, radius))])


def short_time(part, scale: np.ndarray, layer_depth: float, spacing: float) -> ShortTime | None:
    """The expansion's coefficients in scaled coordinates (x' = x * scale)."""
    found = _boundary_loops(part, spacing)
    if found is None:
        return None
    loops, contact = found
    area = perimeter = corners = curvature_square = curvature_cube = 0.0
    corner_curvature = max_curvature = 0.0
    moments = np.zeros(_disc_coefficients().size)
    weights, depths, curvatures = [], [], []
    scaled = [loop * scale[None, :] for loop in loops]
    chords, chord_lengths = _chords(scaled, 0.25 * spacing * float(np.max(scale)))
    for loop, p, is_contact in zip(loops, scaled, contact):
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
        curvature_cube += np.sum(kappa ** 3 * ds)
        moments += np.abs(kappa)[None, :] ** np.arange(moments.size)[:, None] @ ds
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
    return ShortTime(area, perimeter, corners, curvature_square, curvature_cube, moments,
                     corner_curvature, max_curvature,
                     weights / weights.sum(), np.concatenate(depths), np.concatenate(curvatures),
                     float(np.concatenate(curvatures) ** 2 @ (weights / weights.sum())),
                     chords, chord_lengths)


def _chords(loops: list[np.ndarray], spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """(chord, outline length it stands for) at ``CHORD_RAYS`` points evenly spaced along
    each closed polyline of ``loops`` (material on the left): the length of the inward
    normal ray inside the outline, marched on a geometric grid against the signed distance
    of ``trimesh.Wall``, then bisected."""
    from .trimesh import Wall, resample_loop, vertex_normals

    wall = Wall.of(loops, spacing)
    rays = [resample_loop(loop, _loop_length(loop) / CHORD_RAYS) for loop in loops]
    start = np.vstack(rays)
    normal = np.vstack([vertex_normals(ray) for ray in rays])
    lengths = np.concatenate([np.full(len(ray), _loop_length(loop) / len(ray))
                              for ray, loop in zip(rays, loops)])
    steps = np.geomspace(spacing, 4.0 * float(np.max(np.ptp(start, axis=0))), 64)

    def inside(t):
        return wall.distance(start + t[..., None] * normal)[1]
    out = np.column_stack([~inside(np.full(len(start), t)) for t in steps])
    first = np.where(out.any(axis=1), np.argmax(out, axis=1), steps.size - 1)
    low = np.where(first > 0, steps[np.maximum(first - 1, 0)], 0.0)
    high = steps[first]
    for _ in range(16):
        middle = 0.5 * (low + high)
        within = inside(middle)
        low, high = np.where(within, middle, low), np.where(within, high, middle)
    return 0.5 * (low + high), lengths


def _loop_length(loop: np.ndarray) -> float:
    return float(np.sum(np.hypot(*(np.roll(loop, -1, axis=0) - loop).T)))



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
    the largest coarse/fine difference of the mean (the time-error indicator). A P1
    operator's fields come from its monotone lumped-mass march (``trimesh.P1Operator``)."""
    from .timesteps import geometric_steps

    nodes = geometric_steps(0.0, end, first_step, per_doubling)
    fine = np.sort(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
    grids = [(grid, np.searchsorted(grid, nodes)) for grid in (nodes, fine)]
    monotone = keep_fields and hasattr(disc, "march")  # P1: fields by the lumped mass
    coarse, refined = (_unit_march(disc, grid, at, keep_fields and not monotone, part)
                       for grid, at in grids)
    with_fields = ([disc.march(grid, at, True, lumped=True) for grid, at in grids] if monotone
                   else (coarse, refined))

    def unsaturated(a, b):
        return 1.0 - (2.0 * b - a)
    fields = unsaturated(with_fields[0].fields, with_fields[1].fields) if keep_fields else None
    pair = float(np.max(np.abs(refined.mean - coarse.mean)))
    return StepResponse(nodes, unsaturated(coarse.mean, refined.mean),
                        unsaturated(coarse.layer, refined.layer), fields), pair


def _unit_march(disc, grid: np.ndarray, outputs: np.ndarray, keep_fields: bool, part: str):
    """A unit step of the surface value at t = 0 from 0: a P1 operator (``trimesh``)
    marches itself, a FiPy-assembled discretisation goes through ``fv.march``."""
    if hasattr(disc, "march"):
        return disc.march(grid, outputs, keep_fields)
    from . import fv

    return fv.march(disc, grid, np.ones(grid.size), 0.0, outputs, keep_fields=keep_fields,
                    part=part)


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
    the mesh-expansion mismatch at that time (then the mesh is the worse of the two; the
    mesh is graded for the times after the switch, so its early mismatch says nothing
    about later). At each node the mesh's relative uptake error is at most (mismatch +
    indicator) / uptake; by the error model of ``trimesh``, MESH_ERROR (h0 / sqrt(tau) +
    GROWTH_REACH g)^2, it only falls with time, so the least of these bounds over the
    octave before the switch holds after it, and the mesh's error there is that ratio
    times the uptake. Returns the fraction and the larger of the two error estimates."""
    nodes = response.nodes[1:]
    w = weight(nodes)
    expected = weighted(indicator(nodes), w)
    mismatch = np.abs(values[1:] - (1.0 - series(nodes))) * w
    trusted = expected <= np.maximum(tolerance, 0.5 * mismatch)
    last = int(np.argmin(trusted)) - 1 if not trusted.all() else nodes.size - 1
    if last < 0:
        return (lambda tau: response.at(tau, values)), None
    switch = float(nodes[last]) if last < nodes.size - 1 else np.inf  # inf: expansion only
    error = float(expected[last])
    if last < nodes.size - 1:
        octave = (nodes >= 0.5 * switch) & (nodes <= switch)
        uptake = np.maximum(1.0 - values[1:], np.finfo(float).tiny)
        # |mesh error| <= mismatch + |expansion error| <= mismatch + indicator at every
        # node of the octave, and the mesh's relative error only falls: the least bound
        ratio = np.min((mismatch + expected)[octave] / (uptake[octave] * w[octave]))
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


def _expansion_only(expansion, outputs, end, jump_taus, jumps, exposure, times, chosen, part):
    """Every output lies where the short-time expansion meets the tolerance: no mesh;
    the error is ``expansion_error`` (its indicator, weighted, largest up to ``end``)."""
    from .solve import DiffusionResult

    grid = np.geomspace(1e-8 * end, end, 400)
    layer_error = float(np.max(expansion.layer_error(grid) * sheet_fraction(grid)))

    def mean_fraction(tau):
        return (1.0 - expansion.uptake(tau)) * sheet_fraction(tau)

    def layer_fraction(tau):
        return (1.0 - expansion.layer_uptake(tau)) * sheet_fraction(tau)

    c0 = exposure.initial_moisture
    mean = duhamel(outputs, jump_taus, jumps, c0, mean_fraction)
    layer = duhamel(outputs, jump_taus, jumps, c0, layer_fraction)
    mean_error = expansion_error(expansion, end)
    log.debug("%s plane: short-time expansion only, error %.2g (layer %.2g)", part,
              mean_error, layer_error)
    return DiffusionResult(np.asarray(times, float), mean, layer, "plane", 0, 0,
                           mean_error, chosen.reason + "; no mesh needed")


# ------------------------------------------------------------------- plan


TIME_SHARE = 0.1     # share of the accuracy allowed to the time steps (the rest: the mesh)
DESIGN_MARGIN = 0.8  # the plan aims at this share of the accuracy (its models err by 10-20 %)
PLANE_PAIR = 0.03    # planform mean: |fine - coarse march| <= PLANE_PAIR F(end) / m
PAIR_TO_TIME_ERROR = 2.5  # planform: extrapolated time error <= 2.5 pair^2 (1.1-1.9 measured)
# (demo cam and fourbar link, m = 3-12, against m = 32 at the outputs, sheet-weighted)
MESH_FIRST_STEP = 1 / 16  # the mesh's first step, in units of h0^2: earlier it resolves nothing
MESH_LEAD_DOUBLINGS = 7   # ... or this many doublings before the switch (six before its half)
FEATURE_POINTS = 16  # at least this many outline points round the tightest curve


def stretch_of(d) -> tuple[float, float]:
    """sqrt(D_z / D_x), sqrt(D_z / D_y): the in-plane metric of the scaled problem
    (Crank 1975 eq. 2.13)."""
    return (math.sqrt(d[2] / d[0]), math.sqrt(d[2] / d[1]))


def peak_weight(perimeter: float, area: float, start: float, end: float) -> float:
    """Largest planform uptake x sheet unsaturated fraction over [start, end], the factor
    that turns a relative planform error into an error of the mean (``leading_uptake``)."""
    grid = np.geomspace(max(start, 1e-9), max(end, start, 1e-9), 200)
    return float(np.max(leading_uptake(perimeter, area, grid) * sheet_fraction(grid)))


def leading_uptake(perimeter: float, area: float, tau):
    """min(1, 2 P sqrt(tau / pi) / A): the planform uptake's leading term (Crank 1975 eq. 4.20
    per unit edge), an upper bound for convex outlines."""
    return np.minimum(1.0, 2.0 * perimeter * np.sqrt(np.asarray(tau, float) / np.pi) / area)


@dataclass(frozen=True)
class MeshDesign:
    """The graded mesh for a target: finest spacing h0 and growth g (scaled units), the
    estimated number of nodes and the relative uptake error it leaves at ``start``."""

    finest: float
    growth: float
    nodes: int
    relative_error: float


def mesh_design(target: float, start: float, perimeter: float, tightest: float,
                cap: int) -> MeshDesign:
    """h0 and g meeting a relative uptake error ``target`` from scaled time ``start`` on.

    The error model r = MESH_ERROR (h0 / sqrt(t) + GROWTH_REACH g)^2 (``trimesh``) and the
    node count ~ sum_k P / (h0 (1 + g)^k) ~ P / (g h0) (rows of P / s_k points) give the
    cheapest split at
    h0 / sqrt(t) = GROWTH_REACH g = S / 2, S = sqrt(target / MESH_ERROR); g is at most
    ``grading.MAX_GROWTH``, h0 gives ``FEATURE_POINTS`` points round the tightest curve
    (curvature ``tightest``), and both coarsen together when the nodes exceed ``cap``."""
    from .grading import MAX_GROWTH
    from .trimesh import GROWTH_REACH, MESH_ERROR

    reach = math.sqrt(max(target, 1e-300) / MESH_ERROR)
    growth = min(MAX_GROWTH, 0.5 * reach / GROWTH_REACH)
    finest = min((reach - GROWTH_REACH * growth) * math.sqrt(start),
                 2 * math.pi / (FEATURE_POINTS * max(tightest, 1e-9)))
    nodes = perimeter / (growth * finest)
    if nodes > cap:
        coarser = math.sqrt(nodes / cap)
        growth, finest = min(MAX_GROWTH, growth * coarser), finest * coarser
        nodes = perimeter / (growth * finest)
    error = MESH_ERROR * (finest / math.sqrt(start) + GROWTH_REACH * growth) ** 2
    return MeshDesign(finest, growth, int(math.ceil(nodes)), error)


def uniform_design(target: float, start: float, area: float, tightest: float,
                   cap: int) -> MeshDesign:
    """The uniform lattice of outlines without loops (``triangulate`` falls back to it):
    r = MESH_ERROR h^2 / t, about 2 area / (sqrt 3 h^2) nodes, at most ``cap``."""
    from .trimesh import MESH_ERROR

    spacing = min(math.sqrt(max(target, 1e-300) * start / MESH_ERROR),
                  2 * math.pi / (FEATURE_POINTS * max(tightest, 1e-9)))
    spacing = max(spacing, math.sqrt(2 * area / (math.sqrt(3) * cap)))
    nodes = 2 * area / (math.sqrt(3) * spacing ** 2)
    return MeshDesign(spacing, 0.0, int(math.ceil(nodes)), MESH_ERROR * spacing ** 2 / start)


def mesh_first_step(finest: float, switch: float) -> float:
    """First step of the mesh's march where the expansion serves the outputs before
    ``switch``: h0^2 / 16 (before that the mesh resolves nothing) or six doublings before
    half the switch, the larger (backward Euler damps the start: results moved by the time
    error only, 2e-5 on the fourbar link); the common first step without an expansion."""
    from .solve import FIRST_STEP

    if switch <= 0:
        return FIRST_STEP
    return max(FIRST_STEP, MESH_FIRST_STEP * finest ** 2, switch / 2 ** MESH_LEAD_DOUBLINGS)


def plan_plane(geometry, diffusivity, change: np.ndarray, outputs: np.ndarray, accuracy: float):
    """What ``solve_plane`` will do and the error it will report, by the blend's error model:
    the expansion up to its switch (error ``EXPANSION_SHARE`` x accuracy); after it a graded
    P1 mesh whose relative error at half the switch (the blend's first bound: ``mesh_design``
    plus the expansion's own relative error there) times the largest uptake x sheet fraction
    after the switch takes what the time error, PAIR_TO_TIME_ERROR (PLANE_PAIR F(end) / m)^2
    (at most ``TIME_SHARE`` of it), leaves of ``DESIGN_MARGIN`` x accuracy."""
    from .solve import (EXPANSION_SHARE, FIRST_STEP, MAX_CELLS, MIN_CELLS_PER_AXIS, SPACE_ERROR,
                        Plan, _earliest_output)
    from .timesteps import geometric_steps

    d = tuple(float(v) for v in diffusivity.pre_exponential)
    tolerance = EXPANSION_SHARE * accuracy
    expansion = expansion_of(geometry, d)
    end = max(float(np.max(outputs)), 10 * FIRST_STEP)
    t_lo = _earliest_output(change, outputs)
    switch = 0.0 if expansion is None else expansion.switch(tolerance)
    perimeter, area, tightest = _planform_size(geometry, d, expansion)
    pair = PLANE_PAIR * float(leading_uptake(perimeter, area, end))  # times 1 / m
    per_doubling = max(4, math.ceil(pair * math.sqrt(PAIR_TO_TIME_ERROR / (TIME_SHARE * accuracy))))
    time_error = PAIR_TO_TIME_ERROR * (pair / per_doubling) ** 2
    start = 0.5 * min(switch, end) if switch > 0 else t_lo
    peak = peak_weight(perimeter, area, max(switch, t_lo), end)
    leak = 0.0 if switch <= 0 else float(expansion.uptake_error(start) / expansion.uptake(start))
    target = max((DESIGN_MARGIN * accuracy - time_error) / max(peak, 1e-300) - leak,
                 0.1 * accuracy)
    design = (mesh_design if expansion is not None else uniform_design)(
        target, start, perimeter if expansion is not None else area, tightest, MAX_CELLS["plane"])
    sheet = min(MAX_CELLS["slab"], max(MIN_CELLS_PER_AXIS, math.ceil(
        1.0 / math.sqrt(0.5 * accuracy * max(t_lo, switch) / (3 * SPACE_ERROR)))))
    reason = (f"2-D outline x exact sheet: short-time expansion of the outline up to "
              f"tau*={switch:.2g}, then P1 elements on a mesh graded from the outline "
              f"(h0*={design.finest:.2g}, growth {design.growth:.2g}), backward Euler "
              f"{per_doubling} steps/doubling + Richardson")
    if expansion is not None and switch >= end:
        return Plan("plane", 0, 0, reason + " (the expansion covers every output: no mesh)",
                    expansion_error(expansion, end), (design.nodes, sheet), per_doubling,
                    tolerance, finest=design.finest, growth=design.growth)
    mesh_error = (design.relative_error + leak) * peak
    at_switch = expansion_error(expansion, switch) if switch > 0 else 0.0
    estimate = max(at_switch, mesh_error) + time_error
    if estimate > accuracy:
        reason += f"; capped at {MAX_CELLS['plane']} nodes: error above the requested accuracy"
    nodes = geometric_steps(0.0, end, mesh_first_step(design.finest, switch), per_doubling)
    return Plan("plane", design.nodes + sheet, 3 * (nodes.size - 1), reason, float(estimate),
                (design.nodes, sheet), per_doubling, tolerance, finest=design.finest,
                growth=design.growth)


def _planform_size(part, d, expansion) -> tuple[float, float, float]:
    """Scaled perimeter, area and largest curvature of the outline (an outline without an
    expansion: bounding box and hole circumferences, area of the box)."""
    if expansion is not None:
        return expansion.perimeter, expansion.area, max(expansion.max_curvature, 1e-9)
    scale = np.asarray(planar_scale(part, d))
    width, height = np.asarray(outline_extent(part)) * scale
    holes = 4 * math.pi * getattr(part, "boss_inner_radius", 0.0) * float(scale.max())
    radius = getattr(part, "boss_inner_radius", 0.0) or getattr(part, "boss_outer_radius", 1.0)
    return 2 * (width + height) + holes, width * height, 1.0 / (radius * float(scale.min()))


# ------------------------------------------------------------------ solve


def solve_plane(geometry, diffusivity, exposure, times, chosen, *,
                surface_layer_depth: float = 5e-4, store_fields: bool = False, part: str = ""):
    """CamPlate / LinkBar: planform step response x sheet step response, Duhamel over the history."""
    from . import fv
    from .solve import FIRST_STEP, DiffusionResult, _scales
    from .timesteps import rescaled_time

    scales = _scales(geometry, diffusivity, exposure)
    d = tuple(float(v) for v in diffusivity.pre_exponential)
    n_z = chosen.cells_per_axis[-1]

    def tau_star(t):
        return scales.star(rescaled_time(diffusivity, exposure, t, scales.a_ref))

    outputs = tau_star(np.asarray(times, float))
    end = max(float(outputs.max()), 10 * FIRST_STEP)
    jump_taus, jumps = surface_jumps(exposure, tau_star)
    expansion = expansion_of(geometry, d, surface_layer_depth)
    tolerance = chosen.expansion_tolerance
    switch = expansion.switch(tolerance) if expansion is not None and tolerance > 0 else 0.0
    if switch >= end and not store_fields:
        return _expansion_only(expansion, outputs, end, jump_taus, jumps, exposure, times,
                               chosen, part)
    mesh = triangulate(geometry, chosen.finest * geometry.thickness, growth=chosen.growth,
                       stretch=stretch_of(d))
    planar = plane_operator(mesh, geometry, surface_layer_depth, d, part)
    u_plane, pair_plane = step_response(planar, end, chosen.steps_per_doubling,
                                        mesh_first_step(chosen.finest,
                                                        0.0 if store_fields else switch),
                                        keep_fields=store_fields, part=part)
    if store_fields:  # the sheet's field (its mean is exact)
        sheet = fv.sheet(geometry.thickness, n_z, surface_layer_depth)
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
    time_error = PAIR_TO_TIME_ERROR * pair_plane ** 2  # the sheet is exact
    if mean_error is None:  # no expansion for this outline: the plan's model (with its time part)
        mean_error = chosen.error_estimate
    estimate = mean_error + time_error
    log.debug("%s plane: error estimate %.2g (layer %s)", part, estimate, layer_error)
    steps = 3 * (u_plane.nodes.size - 1)
    result = DiffusionResult(np.asarray(times, float), mean, layer, "plane",
                             planar.cells + n_z, steps, float(estimate), chosen.reason)
    if store_fields:
        mid = int(np.argmin(np.abs(sheet.coordinates["z"] - 0.5 * geometry.thickness)))

        def field_fraction(tau):  # mid-thickness plane
            return u_plane.at(tau, u_plane.fields) * u_sheet.at(tau, u_sheet.fields[:, mid])[:, None]
        result.fields = duhamel(outputs, jump_taus, jumps, c0, field_fraction)
        result.cell_coordinates = {"x": planar.coordinates["x"], "y": planar.coordinates["y"],
                                   "z": np.full(planar.cells, sheet.coordinates["z"][mid])}
    log.debug("%s plane: %d nodes x %d sheet cells", part, planar.cells, n_z)
    return result
