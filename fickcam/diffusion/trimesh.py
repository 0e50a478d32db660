"""Graded triangle meshes of a planform and the P1 finite-element operator on them.

Mesh. After a change of the surface value the in-plane solution varies over a
layer of depth ~ sqrt(tau) along every edge (Crank 1975 eq. 2.45), so the mesh is
finest at the outline and grows inward: boundary samples at the finest spacing
h0, then rows of points offset inward along the normals, row k with spacing
s_k = h0 (1 + g)^k (geometric growth, as ``grading``) one equilateral height
below the last, d_k - d_{k-1} = (sqrt 3 / 2)(s_{k-1} + s_k) / 2 ("advancing
layers"). A row is resampled at its own spacing, loses the points whose distance
to the outline is not its depth (swallowtails at convex corners, the medial axis
where rows from opposite edges meet) and the points closer than 0.7 s_k to one
already placed; a hexagonal lattice at the coarsest spacing fills what is left.
The points are triangulated by Delaunay (scipy.spatial) and the triangles whose
centroid lies outside are dropped.

Operator. FiPy's two-point flux between triangle centroids is not consistent on
such a mesh (measured on a graded disc: relative uptake error ~0.08 g that does
not fall with h0). The P1 Galerkin method is: stiffness by the cotangent formula
K_jk = -(cot a_jk + cot b_jk) / 2 over the angles opposite edge jk (Duffin 1959;
Pinkall & Polthier 1993; with a lumped mass it is the vertex-centred finite volume
scheme on the Voronoi cells, MacNeal 1953), consistent mass M_jk = |T| (1 + delta_jk) / 12
per triangle, the outline nodes held at the surface value. Its error after a step
of the boundary value is O(h^2 / t) (Thomée 2006, Galerkin Finite Element
Methods for Parabolic Problems, Theorem 3.1, non-smooth data), measured here as
a relative uptake error ~ ``MESH_ERROR`` (h0 / sqrt(tau) + ``GROWTH_REACH`` g)^2
(0.6-1.1x the error on graded discs against Crank eq. 5.23, on the demo cam and a link
against fine meshes). On a
Delaunay mesh cot a + cot b >= 0, so K is an M-matrix (Xu & Zikatanov 1999,
Math. Comp. 68, 1429-1446); the consistent mass (3x more accurate than the
lumped one here) gives up the discrete maximum principle, so early fields may
undershoot slightly (Thomée 2006 ch. 15).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import sparse

from .fv import RESIDUAL_TOLERANCE, norm

ROW = math.sqrt(3.0) / 2.0   # height of an equilateral triangle of unit side
CORNER_TURN = 0.2            # rad: a vertex turning more is a corner (kept as a node)
FAN_STEP = 0.1               # rad between offset normals around a reflex corner
DEPTH_TOLERANCE = 0.25       # a row point must lie within this many spacings of its depth
MIN_GAP = 0.7                # points closer than this many local spacings are dropped
MESH_ERROR = 0.012           # relative uptake error ~ MESH_ERROR (h0/sqrt(tau) + GROWTH_REACH g)^2
GROWTH_REACH = 1.2           # (measured, consistent-mass P1, see the module docstring)


# ------------------------------------------------------------------ outline


def corners_of(loop: np.ndarray) -> np.ndarray:
    """Indices of the vertices of a closed polyline that turn by more than ``CORNER_TURN``."""
    edge = np.roll(loop, -1, axis=0) - loop
    incoming = np.roll(edge, 1, axis=0)
    turn = np.arctan2(incoming[:, 0] * edge[:, 1] - incoming[:, 1] * edge[:, 0],
                      np.einsum("ij,ij->i", incoming, edge))
    return np.flatnonzero(np.abs(turn) >= CORNER_TURN)


def resample_loop(loop: np.ndarray, spacing: float) -> np.ndarray:
    """Points along a closed polyline at equal arc steps <= ``spacing`` between its corners
    (corners kept as points)."""
    closed = np.vstack([loop, loop[:1]])
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    total = arc[-1]
    corners = corners_of(loop)
    starts = arc[corners] if corners.size else np.array([0.0])
    ends = np.append(starts[1:], starts[0] + total)
    steps = [a + (b - a) * np.arange(n) / n
             for a, b in zip(starts, ends) for n in [max(1, math.ceil((b - a) / spacing))]]
    s = np.concatenate(steps) % total
    return np.column_stack([np.interp(s, arc, closed[:, 0]), np.interp(s, arc, closed[:, 1])])


def _edge_normals(points: np.ndarray) -> np.ndarray:
    """Unit normals to the left of each edge i -> i+1 (towards the material)."""
    edge = np.roll(points, -1, axis=0) - points
    edge /= np.hypot(*edge.T)[:, None]
    return np.column_stack([-edge[:, 1], edge[:, 0]])


def vertex_normals(points: np.ndarray) -> np.ndarray:
    """Unit bisectors of the normals of the two edges at each vertex."""
    after = _edge_normals(points)
    both = np.roll(after, 1, axis=0) + after
    return both / np.hypot(*both.T)[:, None]


def fanned(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points with offset normals: the bisector at ordinary vertices and a fan of normals
    every ``FAN_STEP`` at reflex corners (right turns), whose offsets are arcs."""
    after = _edge_normals(points)
    before = np.roll(after, 1, axis=0)
    turn = np.arctan2(before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0],
                      np.einsum("ij,ij->i", before, after))
    count = np.where(turn < -FAN_STEP, np.ceil(-turn / FAN_STEP).astype(int), 0) + 1
    index = np.repeat(np.arange(points.size // 2), count)
    step = np.arange(index.size) - np.repeat(np.cumsum(count) - count, count)
    fan = count[index] > 1
    angle = (np.arctan2(before[index, 1], before[index, 0])
             + turn[index] * step / np.maximum(count[index] - 1, 1))
    normals = np.where(fan[:, None], np.column_stack([np.cos(angle), np.sin(angle)]),
                       vertex_normals(points)[index])
    return points[index], normals


@dataclass(frozen=True)
class Wall:
    """Signed distance to an outline from dense samples: the distance to the nearest sample,
    inside where the offset from it points along its inward normal."""

    samples: np.ndarray
    normals: np.ndarray
    tree: object

    @classmethod
    def of(cls, loops: list[np.ndarray], spacing: float) -> Wall:
        from scipy.spatial import cKDTree

        dense = [resample_loop(loop, spacing) for loop in loops]
        samples = np.vstack(dense)
        return cls(samples, np.vstack([vertex_normals(d) for d in dense]), cKDTree(samples))

    def distance(self, points: np.ndarray, beyond: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
        """(distance, inside) of each point; points farther than ``beyond`` get an infinite
        distance and count as outside (a bounded search is much faster)."""
        gap, nearest = self.tree.query(points, distance_upper_bound=beyond)
        found = np.isfinite(gap)
        offset = points[found] - self.samples[nearest[found]]
        inside = np.zeros(len(points), bool)
        inside[found] = np.einsum("ij,ij->i", offset, self.normals[nearest[found]]) > 0
        return gap, inside


# --------------------------------------------------------------------- rows


def _runs(mask: np.ndarray) -> tuple[list[np.ndarray], bool]:
    """Index runs of True in a cyclic mask, and whether the single run is the whole loop."""
    if mask.all():
        return [np.arange(mask.size)], True
    start = int(np.argmin(mask))
    order = np.roll(np.arange(mask.size), -start)
    flags = np.concatenate([[0], mask[order].astype(int), [0]])
    edges = np.flatnonzero(np.diff(flags))
    return [order[a:b] for a, b in zip(edges[::2], edges[1::2])], False


def _along(points: np.ndarray, spacing: float, closed: bool, shifted: bool) -> np.ndarray:
    """Points along a polyline every ~``spacing`` (``shifted``: half a step along,
    staggering consecutive rows)."""
    if closed:
        points = np.vstack([points, points[:1]])
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
    count = max(1, round(arc[-1] / spacing))
    s = (np.arange(count if closed else count + 1) + 0.5 * shifted) * arc[-1] / count
    s = s[s <= arc[-1]]
    return np.column_stack([np.interp(s, arc, points[:, 0]), np.interp(s, arc, points[:, 1])])


def _sparse_enough(candidates: np.ndarray, placed: np.ndarray, gap: float) -> np.ndarray:
    """Candidates at least ``gap`` from every placed point and from each other (greedy)."""
    from scipy.spatial import cKDTree

    if candidates.size == 0:
        return candidates
    if placed.size:
        candidates = candidates[cKDTree(placed).query(candidates)[0] >= gap]
    pairs = cKDTree(candidates).query_pairs(gap, output_type="ndarray")
    drop = np.zeros(len(candidates), bool)
    for i, j in pairs[np.lexsort(pairs.T[::-1])]:
        if not drop[i]:
            drop[j] = True
    return candidates[~drop]


def row_spacings(finest: float, growth: float, coarsest: float):
    """(spacing, depth) of successive rows: s_k = min(h0 (1+g)^k, coarsest),
    d_k = d_{k-1} + (sqrt 3 / 2)(s_{k-1} + s_k) / 2."""
    spacing, depth = finest, 0.0
    while True:
        wider = min(spacing * (1.0 + growth), coarsest)
        depth += ROW * 0.5 * (spacing + wider)
        spacing = wider
        yield spacing, depth


def graded_points(loops: list[np.ndarray], finest: float, growth: float,
                  coarsest: float = np.inf) -> tuple[np.ndarray, np.ndarray, Wall]:
    """(outline points, interior points, wall) of a graded mesh (see the module docstring)."""
    boundary = np.vstack([resample_loop(loop, finest) for loop in loops])
    wall = Wall.of(loops, finest / 4)
    placed = boundary
    spacing = depth = finest
    for k, (spacing, depth) in enumerate(row_spacings(finest, growth, coarsest), start=1):
        pieces = []
        for points, normals in (fanned(resample_loop(loop, spacing / 4)) for loop in loops):
            moved = points + depth * normals
            gap, inside = wall.distance(moved, depth + DEPTH_TOLERANCE * spacing)
            runs, closed = _runs(inside & (np.abs(gap - depth) <= DEPTH_TOLERANCE * spacing))
            pieces += [_along(moved[run], spacing, closed, bool(k % 2)) for run in runs
                       if run.size > 1]
        row = _sparse_enough(np.vstack(pieces) if pieces else np.empty((0, 2)), placed,
                             MIN_GAP * spacing)
        if row.size == 0:
            break
        placed = np.vstack([placed, row])
        if spacing >= coarsest:
            placed = np.vstack([placed, _lattice_fill(placed, wall, coarsest, depth)])
            break
    return boundary, placed[len(boundary):], wall


def _lattice_fill(placed: np.ndarray, wall: Wall, spacing: float, depth: float) -> np.ndarray:
    """Hexagonal lattice at ``spacing`` deeper than ``depth``, away from placed points."""
    lo, hi = placed.min(axis=0), placed.max(axis=0)
    rows = np.arange(lo[1], hi[1] + spacing, ROW * spacing)
    xs = np.arange(lo[0], hi[0] + spacing, spacing)
    lattice = np.vstack([np.column_stack([xs + 0.5 * spacing * (i % 2), np.full(xs.size, y)])
                         for i, y in enumerate(rows)])
    gap, inside = wall.distance(lattice)
    lattice = lattice[inside & (gap > depth + 0.5 * ROW * spacing)]
    return _sparse_enough(lattice, placed, MIN_GAP * spacing)


def delaunay_inside(points: np.ndarray, wall: Wall, finest: float) -> np.ndarray:
    """Delaunay triangles whose centroid is inside the outline (slivers of collinear
    outline points dropped)."""
    from scipy.spatial import Delaunay

    triangles = Delaunay(points).simplices
    corners = points[triangles]
    inside = wall.distance(corners.mean(axis=1))[1]
    return triangles[inside & (triangle_areas(points, triangles) > 1e-6 * finest ** 2)]


def triangle_areas(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    a = points[triangles[:, 1]] - points[triangles[:, 0]]
    b = points[triangles[:, 2]] - points[triangles[:, 0]]
    return 0.5 * np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])


def angles(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """(m, 3) interior angles (rad) of each triangle."""
    corners = points[triangles]
    out = []
    for i in range(3):
        a = corners[:, (i + 1) % 3] - corners[:, i]
        b = corners[:, (i + 2) % 3] - corners[:, i]
        cosine = np.einsum("ij,ij->i", a, b) / (np.hypot(*a.T) * np.hypot(*b.T))
        out.append(np.arccos(np.clip(cosine, -1.0, 1.0)))
    return np.column_stack(out)


@dataclass(frozen=True)
class GradedMesh:
    """Points (mesh coordinates), triangles and which points lie on the outline."""

    points: np.ndarray
    triangles: np.ndarray
    on_outline: np.ndarray  # (n,) bool


def graded_mesh(loops: list[np.ndarray], finest: float, growth: float,
                coarsest: float = np.inf) -> GradedMesh:
    """Triangulated graded points; unused points removed."""
    boundary, interior, wall = graded_points(loops, finest, growth, coarsest)
    points = np.vstack([boundary, interior])
    triangles = delaunay_inside(points, wall, finest)
    used = np.unique(triangles)
    renumber = np.full(len(points), -1)
    renumber[used] = np.arange(used.size)
    return GradedMesh(points[used], renumber[triangles], used < len(boundary))


# ----------------------------------------------------------------- operator


def cotangent_stiffness(points: np.ndarray, triangles: np.ndarray) -> sparse.csr_matrix:
    """P1 stiffness K_jk = -(1/2) sum over the triangles at edge jk of cot(angle opposite),
    K_jj = -sum_k K_jk (Duffin 1959; Pinkall & Polthier 1993)."""
    n = len(points)
    corners = points[triangles]
    rows, cols, values = [], [], []
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        a, b = corners[:, j] - corners[:, i], corners[:, k] - corners[:, i]
        half_cot = 0.5 * np.einsum("ij,ij->i", a, b) / np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
        rows += [triangles[:, j], triangles[:, k], triangles[:, j], triangles[:, k]]
        cols += [triangles[:, k], triangles[:, j], triangles[:, j], triangles[:, k]]
        values += [-half_cot, -half_cot, half_cot, half_cot]
    return sparse.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                             shape=(n, n))


def consistent_mass(points: np.ndarray, triangles: np.ndarray) -> sparse.csr_matrix:
    """P1 mass M_jk = sum over triangles |T| (1 + delta_jk) / 12."""
    n = len(points)
    local = (np.ones((3, 3)) + np.eye(3)).ravel() / 12.0
    values = triangle_areas(points, triangles)[:, None] * local[None, :]
    rows = np.repeat(triangles, 3, axis=1).ravel()
    cols = np.tile(triangles, (1, 3)).ravel()
    return sparse.csr_matrix((values.ravel(), (rows, cols)), shape=(n, n))


@dataclass
class Marched:
    """Mean, layer mean and (optionally) nodal values at the output nodes of a march."""

    mean: np.ndarray
    layer: np.ndarray
    fields: np.ndarray | None


@dataclass
class P1Operator:
    """Backward-Euler P1 steps of dc/dt = laplacian(c) with the outline nodes at a unit
    value from t = 0+: M (c_new - c_old)/dt + K c_new = f, with f = -K_fb 1 and, on the
    first step, the jump of the outline values through the mass, -M_fb 1 / dt
    (Thomée 2006 ch. 1, Dirichlet nodes eliminated). ``lumped``: the row-sum mass instead,
    less accurate but monotone (M-matrix): the consistent mass undershoots while
    dt < h^2 / 6 (1-D; Thomée 2006 ch. 15), fields down to -0.5 of the step at early
    outputs of coarse meshes. (Lumping only the early steps spoils the accuracy for
    long after: 3.5x the error at 10 h0^2 on a link.)"""

    mass: sparse.csc_matrix        # M_ff
    lumped: sparse.csc_matrix      # diag of the row sums of M over all nodes, free rows
    stiffness: sparse.csc_matrix   # K_ff
    boundary: np.ndarray           # f = -K_fb 1
    jump: np.ndarray               # M_fb 1
    mean_weights: np.ndarray       # (free,) integral weights / area
    mean_outline: float            # share of the area integral carried by the outline nodes
    layer_weights: np.ndarray
    layer_outline: float
    coordinates: dict[str, np.ndarray] = field(default_factory=dict)  # free nodes, physical m
    part: str = ""
    _factors: dict = field(default_factory=dict, repr=False)  # LU of M / dt + K per (dt, lumped)

    @property
    def cells(self) -> int:
        return int(self.boundary.size)

    def march(self, nodes: np.ndarray, outputs: np.ndarray, keep_fields: bool = False,
              lumped: bool = False) -> Marched:
        """Unit-step response from c = 0 over the step boundaries ``nodes`` (scaled time),
        recorded at the node indices ``outputs`` (index 0: the state before the step)."""
        from scipy.sparse.linalg import splu

        from ..errors import SolverError

        c = np.zeros(self.cells)
        factors = self._factors  # shared by the marches: a bisected step is an earlier step
        wanted = set(np.asarray(outputs).tolist())
        states = {0: self._record(c, 0.0, keep_fields)}
        for k in range(1, nodes.size):
            dt = float(f"{nodes[k] - nodes[k - 1]:.12g}")
            mass = self.lumped if lumped else self.mass
            if (dt, lumped) not in factors:
                # symmetric positive definite: symmetric ordering, no pivoting (4x faster)
                factors[dt, lumped] = splu((mass / dt + self.stiffness).tocsc(),
                                           permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                                           options={"SymmetricMode": True})
            jump = self.jump / dt if k == 1 and not lumped else 0.0
            rhs = mass @ c / dt + self.boundary - jump
            c = factors[dt, lumped].solve(rhs)
            residual = norm(mass @ c / dt + self.stiffness @ c - rhs)
            if not residual <= RESIDUAL_TOLERANCE * max(norm(rhs), 1e-300):
                raise SolverError(self.part, k, nodes[k], f"P1 step residual {residual:.2e}")
            if k in wanted:
                states[k] = self._record(c, 1.0, keep_fields)
        mean, layer, fields = (np.array(v) for v in zip(*(states[k] for k in outputs)))
        return Marched(mean, layer, fields if keep_fields else None)

    def _record(self, c: np.ndarray, outline: float, keep_fields: bool):
        """(mean, layer mean, nodal values or None) with the outline nodes at ``outline``."""
        return (float(np.einsum("i,i->", self.mean_weights, c)) + self.mean_outline * outline,
                float(np.einsum("i,i->", self.layer_weights, c)) + self.layer_outline * outline,
                c if keep_fields else None)


def p1_operator(points: np.ndarray, triangles: np.ndarray, fixed: np.ndarray, layer: np.ndarray,
                coordinates: dict[str, np.ndarray], part: str = "") -> P1Operator:
    """The P1 operator on a mesh in scaled coordinates; ``fixed`` marks the outline nodes,
    ``layer`` (n,) the integral weights of the contact layer (any scale)."""
    stiffness = cotangent_stiffness(points, triangles)
    mass = consistent_mass(points, triangles)
    free = ~fixed
    weights = np.asarray(mass.sum(axis=1)).ravel()  # integral of each hat function
    area, layer_total = weights.sum(), layer.sum()
    return P1Operator(
        mass[free][:, free].tocsc(), sparse.diags(weights[free]).tocsc(),
        stiffness[free][:, free].tocsc(),
        -np.asarray(stiffness[free][:, fixed].sum(axis=1)).ravel(),
        np.asarray(mass[free][:, fixed].sum(axis=1)).ravel(),
        weights[free] / area, float(weights[fixed].sum() / area),
        layer[free] / layer_total, float(layer[fixed].sum() / layer_total),
        {name: value[free] for name, value in coordinates.items()}, part)


def layer_weights(points: np.ndarray, triangles: np.ndarray, distance, depth: float,
                  subdivisions: int = 4) -> np.ndarray:
    """Integral of each hat function over the layer {distance(x) <= depth}: the midpoint
    rule on ``subdivisions``^2 sub-triangles of every triangle (``distance(points, bound)``
    may return inf beyond ``bound``)."""
    n = subdivisions
    up = [(i + 1 / 3, j + 1 / 3) for i in range(n) for j in range(n - i)]
    down = [(i + 2 / 3, j + 2 / 3) for i in range(n - 1) for j in range(n - 1 - i)]
    lam = np.array(up + down) / n                                  # (q, 2) barycentric
    bary = np.column_stack([1.0 - lam.sum(axis=1), lam])            # (q, 3)
    corners = points[triangles]                                     # (m, 3, 2)
    samples = np.einsum("qi,mij->mqj", bary, corners)               # (m, q, 2)
    within = (distance(samples.reshape(-1, 2), depth) <= depth).reshape(samples.shape[:2])
    share = triangle_areas(points, triangles)[:, None] / n ** 2 * within  # (m, q)
    weights = np.zeros(len(points))
    np.add.at(weights, triangles.ravel(), (share @ bary).ravel())
    return weights
