"""Finite-volume diffusion with operators assembled by FiPy and stepped with scipy.

Every mesh is built in non-dimensional, anisotropy-scaled coordinates
x_i' = (x_i / L) sqrt(D_z / D_i) with L the part thickness, so that the
operator is the isotropic Laplacian with unit coefficient (Crank 1975, §2.6,
eq. 2.13: anisotropic diffusion along principal axes reduces to isotropic
diffusion by scaling each coordinate with sqrt(D_ref / D_i)). Time is then
tau* = tau D_z(T_ref) / L^2.

FiPy assembles ``TransientTerm == DiffusionTerm`` once per mesh with all
exposed faces constrained to 1 (``DiffusionTermCorrection`` is not used: its
non-orthogonal correction is an explicit source built from the current
gradient, so it is not part of a constant matrix); with dt = 1 and c_old = 0 its matrix is
A = M + K and its right side is f, so K and f follow and backward Euler with
any step and any uniform surface value g is (M/dt + K) c_new = M c_old/dt + g f.
One scipy factorisation per distinct dt serves every step of that size
(private FiPy API ``_prepareLinearSystem``: fipy is pinned to 4.0.x and the
extraction is tested against a plain ``eq.solve``).
"""
from __future__ import annotations

import logging
from collections import OrderedDict
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from scipy import sparse
from scipy.sparse import linalg as splinalg

from ..errors import SolverError

log = logging.getLogger(__name__)

DIRECT_LIMIT = {1: 10**9, 2: 40_000, 3: 30_000}  # cells per dimension count; above: CG
# (notes/fipy-measured.md: 3-D LU fills in as cells^2.1, CG stays near linear)
RESIDUAL_TOLERANCE = 1e-9
ORDERING = "MMD_AT_PLUS_A"  # minimum degree on A + A^T, diagonal pivots: K is symmetric (SuperLU)
_FACTOR_CACHE_SIZE = 64
_FACTOR_CACHE_BYTES = 2 * 1024 ** 3


@dataclass
class Discretisation:
    """A FiPy-assembled operator with the weights that integrate its cell values."""

    volumes: np.ndarray            # (n,) scaled cell volumes (M = diag(volumes))
    stiffness: sparse.csr_matrix   # K, (n, n)
    boundary: np.ndarray           # f, (n,) for a unit surface value
    mean_weights: np.ndarray       # (n,), sum 1: volume mean
    layer_weights: np.ndarray      # (n,), sum 1: mean over the surface layer
    coordinates: dict[str, np.ndarray] = field(default_factory=dict)  # physical cell centres, m
    factors: OrderedDict = field(default_factory=OrderedDict, repr=False, compare=False)
    # (dt, theta) -> (matrix, LU or None): shared by every march on this operator

    @property
    def cells(self) -> int:
        return int(self.volumes.size)


# --------------------------------------------------------------- assembly


def assemble(mesh, corrected: bool = False,
             exposed: np.ndarray | None = None) -> tuple[np.ndarray, sparse.csr_matrix, np.ndarray]:
    """(volumes, K, f) of dc/dt = laplacian(c) with c = 1 on every exterior face
    (or on the faces marked in ``exposed``; the other exterior faces are insulated,
    FiPy's default: zero flux, e.g. a mirror plane).

    FiPy's matrix for ``TransientTerm() == DiffusionTerm(1)`` at dt = 1 is
    M + K; its right side with c_old = 0 is f.
    """
    from fipy import (CellVariable, DiffusionTerm, DiffusionTermCorrection, LinearLUSolver,
                      TransientTerm)

    var = CellVariable(mesh=mesh, value=0.0)
    var.constrain(1.0, mesh.exteriorFaces if exposed is None else exposed)
    diffusion = DiffusionTermCorrection if corrected else DiffusionTerm
    equation = TransientTerm(coeff=1.0) == diffusion(coeff=1.0)
    equation.cacheMatrix()
    equation.cacheRHSvector()
    equation._prepareLinearSystem(var, LinearLUSolver(tolerance=1e-10), (), 1.0)
    volumes = np.asarray(mesh.cellVolumes, float).copy()
    matrix = sparse.csr_matrix(equation.matrix.matrix)
    stiffness = (matrix - sparse.diags(volumes)).tocsr()
    boundary = np.asarray(equation.RHSvector, float).copy()
    return volumes, stiffness, boundary


# ------------------------------------------------------------ stepping


class ThetaStepper:
    """theta-scheme steps (M/dt + theta K) c_new = (M/dt - (1-theta) K) c_old
    + (theta g_new + (1-theta) g_old) f (Crank 1975, §8.2.4; theta = 1 backward
    Euler, 1/2 Crank-Nicolson). Backward Euler is bounded for M-matrix operators
    at any step (maximum principle: Morton & Mayers 2005, §2.11); Crank-Nicolson is not.

    Factorisations are cached per distinct (dt, theta) on the ``Discretisation``
    (a Richardson pair of marches shares them), at most ``_FACTOR_CACHE_SIZE`` of
    them and ``_FACTOR_CACHE_BYTES`` in all, least recently used dropped; meshes above
    ``DIRECT_LIMIT`` cells use conjugate gradients with a Jacobi preconditioner
    (the matrix is symmetric positive definite on orthogonal meshes).
    """

    def __init__(self, disc: Discretisation, part: str = ""):
        self.disc = disc
        self.part = part
        self.iterative = disc.cells > DIRECT_LIMIT[max(1, len(disc.coordinates))]
        self._banded = _tridiagonal(disc.stiffness)
        self._factors = disc.factors
        self.factorisations = 0

    def _solver(self, dt: float, theta: float):
        key = (float(dt), float(theta))
        if key in self._factors:
            self._factors.move_to_end(key)
            return self._factors[key]
        matrix = (sparse.diags(self.disc.volumes / dt) + theta * self.disc.stiffness).tocsc()
        lu = None if self.iterative else splinalg.splu(matrix, permc_spec=ORDERING,
                                                       options={"SymmetricMode": True})
        self.factorisations += 1
        self._factors[key] = solver = (matrix, lu, _factor_bytes(matrix, lu))
        while len(self._factors) > 1 and (len(self._factors) > _FACTOR_CACHE_SIZE or sum(
                entry[2] for entry in self._factors.values()) > _FACTOR_CACHE_BYTES):
            self._factors.popitem(last=False)
        return solver

    def step(self, c: np.ndarray, dt: float, g_old: float, g_new: float, index: int,
             time: float, theta: float = 1.0) -> np.ndarray:
        """One step of size dt (scaled time); ``index``/``time`` name it in errors."""
        rhs = self.disc.volumes * c / dt + (theta * g_new + (1 - theta) * g_old) * self.disc.boundary
        if theta != 1.0:
            rhs -= (1 - theta) * (self.disc.stiffness @ c)
        if self._banded is not None:
            return self._step_banded(dt, theta, rhs, index, time)
        matrix, lu, _ = self._solver(dt, theta)
        if lu is not None:
            new = lu.solve(rhs)
        else:
            preconditioner = sparse.diags(1.0 / matrix.diagonal())
            new, info = splinalg.cg(matrix, rhs, x0=c, rtol=1e-11, atol=0.0, M=preconditioner,
                                    maxiter=10 * self.disc.cells)
            if info != 0:
                raise SolverError(self.part, index, time, f"CG did not converge (info {info})")
        self._check(matrix, new, rhs, index, time)
        return new

    def _step_banded(self, dt, theta, rhs, index, time) -> np.ndarray:
        """Tridiagonal (1-D) operators: LAPACK dgtsv (Gaussian elimination with partial
        pivoting, O(n)); nothing to factorise or cache."""
        from scipy.linalg.lapack import dgtsv

        bands = theta * self._banded
        bands[1] += self.disc.volumes / dt
        upper, diagonal, lower = bands
        *_, new, info = dgtsv(lower[:-1], diagonal, upper[1:], rhs)
        if info != 0:
            raise SolverError(self.part, index, time, f"tridiagonal solve failed (info {info})")
        product = diagonal * new
        product[:-1] += upper[1:] * new[1:]
        product[1:] += lower[:-1] * new[:-1]
        self._check_residual(product - rhs, rhs, index, time)
        return new

    def _check(self, matrix, new, rhs, index, time) -> None:
        self._check_residual(matrix @ new - rhs, rhs, index, time)

    def _check_residual(self, difference, rhs, index, time) -> None:
        scale = max(norm(rhs), np.finfo(float).tiny)
        residual = norm(difference) / scale
        if not np.isfinite(residual) or residual > RESIDUAL_TOLERANCE * (
                1e3 if self.iterative else 1.0):
            raise SolverError(self.part, index, time,
                              f"linear solve residual {residual:.2e} (non-finite or too large)")


@dataclass
class History:
    """Cell values integrated at the output nodes of a march."""

    mean: np.ndarray
    layer: np.ndarray
    fields: np.ndarray | None
    steps: int
    factorisations: int


def march(disc: Discretisation, nodes: np.ndarray, surface_values: np.ndarray,
          initial: float, outputs: np.ndarray, times: np.ndarray | None = None, *,
          keep_fields: bool = False, part: str = "", scheme: str = "backward_euler",
          restarts: np.ndarray | None = None, restart_steps: int = 2,
          surface_before: np.ndarray | None = None) -> History:
    """March over the step boundaries ``nodes`` (scaled time) with the surface
    value ``surface_values[k]`` at ``nodes[k]`` (right-continuous; a step
    ending at a jump uses ``surface_before[k]``, the left limit); records the
    state at the node indices ``outputs``. ``times`` (s) only label errors.

    ``scheme`` ``crank_nicolson`` takes ``restart_steps`` backward-Euler steps
    from every node index in ``restarts`` (t = 0 and each environment change),
    which damps the oscillation of the stiff modes a jump excites.
    """
    stepper = ThetaStepper(disc, part)
    c = np.full(disc.cells, float(initial))
    want = np.zeros(nodes.size, bool)
    want[outputs] = True
    theta = np.ones(nodes.size)
    if scheme == "crank_nicolson":
        theta[:] = 0.5
        for start in (np.array([0]) if restarts is None else restarts):
            theta[start + 1:start + 1 + restart_steps] = 1.0
    elif scheme != "backward_euler":
        raise ValueError(f"unknown time scheme {scheme!r}")
    record = {k: None for k in np.unique(outputs)}
    if 0 in record:
        record[0] = c.copy()
    steps = _rounded(np.diff(nodes))
    labels = nodes if times is None else times
    ending = surface_values if surface_before is None else surface_before
    for k, dt in enumerate(steps, start=1):
        c = stepper.step(c, dt, surface_values[k - 1], ending[k], k, labels[k], theta[k])
        if want[k]:
            record[k] = c.copy()
    states = np.array([record[k] for k in outputs])
    return History(mean=states @ disc.mean_weights, layer=states @ disc.layer_weights,
                   fields=states if keep_fields else None, steps=int(steps.size),
                   factorisations=stepper.factorisations)


def _factor_bytes(matrix, lu) -> int:
    """Memory held by a cached matrix and its LU factors: 12 bytes per stored entry."""
    return 12 * (matrix.nnz + (0 if lu is None else lu.nnz))


def norm(vector: np.ndarray) -> float:
    """Euclidean norm without BLAS (a threaded ddot costs about a millisecond per call
    here, more than the triangular solves of a small mesh)."""
    return float(np.sqrt(np.einsum("i,i->", vector, vector)))


def _tridiagonal(matrix: sparse.csr_matrix) -> np.ndarray | None:
    """The (3, n) band storage of a tridiagonal matrix (scipy ``solve_banded``), else None."""
    coo = matrix.tocoo()
    if coo.nnz and np.max(np.abs(coo.row - coo.col)) > 1:
        return None
    n = matrix.shape[0]
    bands = np.zeros((3, n))
    bands[1 + coo.row - coo.col, coo.col] = coo.data
    return bands


def _rounded(steps: np.ndarray) -> np.ndarray:
    """Steps rounded to 12 significant digits so equal blocks share one factorisation."""
    return np.array([float(f"{s:.12g}") for s in steps])


# ------------------------------------------------------------- meshes


def interval_overlap(lo: np.ndarray, hi: np.ndarray, a: float, b: float) -> np.ndarray:
    """Length of [lo, hi] ∩ [a, b], elementwise."""
    return np.clip(np.minimum(hi, b) - np.maximum(lo, a), 0.0, None)


def _normalised(weights: np.ndarray) -> np.ndarray:
    total = weights.sum()
    return weights / total if total > 0 else np.full_like(weights, 1.0 / weights.size)


def _axis_scale(length_scale: float, d_axis: float, d_ref: float) -> float:
    """Physical length -> scaled non-dimensional coordinate factor (Crank eq. 2.13)."""
    return np.sqrt(d_ref / d_axis) / length_scale


def sheet(thickness: float, cells: int, layer_depth: float) -> Discretisation:
    """Sheet through its thickness, Grid1D in z/h; layer: both faces (Crank §4.3)."""
    from fipy import Grid1D

    mesh = Grid1D(nx=cells, dx=1.0 / cells)
    volumes, stiffness, boundary = assemble(mesh)
    z_lo = np.arange(cells) / cells * thickness
    z_hi = z_lo + thickness / cells
    layer = thickness / cells - interval_overlap(z_lo, z_hi, layer_depth, thickness - layer_depth)
    return Discretisation(volumes, stiffness, boundary, _normalised(volumes),
                          _normalised(layer), {"z": 0.5 * (z_lo + z_hi)})


def _uniform_widths(lengths, counts) -> tuple[np.ndarray, ...]:
    return tuple(np.full(int(n), float(size) / int(n)) for size, n in zip(lengths, counts))


def _bounds(widths: np.ndarray, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) edges along one axis of the cells with axis index ``index``."""
    edges = np.concatenate([[0.0], np.cumsum(widths)])
    return edges[index], edges[index + 1]


def _grid_axis(widths: np.ndarray, scale: float, uniform: bool) -> dict:
    """FiPy grid arguments for one axis: a count and a spacing, or the array of widths."""
    return ({"n": widths.size, "d": float(widths[0]) * scale} if uniform
            else {"n": None, "d": widths * scale})


def disc(outer_radius: float, thickness: float, inner_radius: float, radial_cells: int,
         axial_cells: int, layer_depth: float, radial_d: float, axial_d: float,
         widths: tuple[np.ndarray, np.ndarray] | None = None) -> Discretisation:
    """Disc or annulus in (r, z), FiPy CylindricalGrid2D; layer: the outer rim.
    ``widths``: (radial from the bore or axis, axial) cell widths in m, graded
    (FiPy's non-uniform grid), instead of the uniform ``radial_cells`` x ``axial_cells``."""
    from fipy import CylindricalGrid2D

    scale_r = _axis_scale(thickness, radial_d, axial_d)
    uniform = widths is None
    dr, dz = widths or _uniform_widths((outer_radius - inner_radius, thickness),
                                       (radial_cells, axial_cells))
    r_axis, z_axis = _grid_axis(dr, scale_r, uniform), _grid_axis(dz, 1.0 / thickness, uniform)
    mesh = CylindricalGrid2D(nr=r_axis["n"], nz=z_axis["n"], dr=r_axis["d"], dz=z_axis["d"],
                             origin=((inner_radius * scale_r,), (0.0,)))
    volumes, stiffness, boundary = assemble(mesh)
    r_c, z_c = (np.asarray(a) for a in mesh.cellCenters)
    r_lo, r_hi = (inner_radius + edge for edge in _bounds(dr, np.arange(volumes.size) % dr.size))
    band_lo = max(outer_radius - layer_depth, inner_radius)
    ring = np.clip(np.minimum(r_hi, outer_radius) ** 2 - np.maximum(r_lo, band_lo) ** 2, 0, None)
    ring *= dz[np.arange(volumes.size) // dr.size]
    return Discretisation(volumes, stiffness, boundary, _normalised(volumes), _normalised(ring),
                          {"x": r_c / scale_r, "z": z_c * thickness})


def bar(length: float, width: float, thickness: float, cells: tuple[int, int, int],
        layer_depth: float, d: tuple[float, float, float],
        widths: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None) -> Discretisation:
    """Rectangular bar, FiPy Grid3D; layer: within ``layer_depth`` of any face.
    ``widths``: (x, y, z) cell widths in m, graded (FiPy's non-uniform grid),
    instead of the uniform ``cells``."""
    from fipy import Grid3D

    size = np.array([length, width, thickness])
    scale = np.array([_axis_scale(thickness, d[i], d[2]) for i in range(3)])
    uniform = widths is None
    widths = widths or _uniform_widths(size, cells)
    axes = [_grid_axis(w, s, uniform) for w, s in zip(widths, scale)]
    mesh = Grid3D(nx=axes[0]["n"], ny=axes[1]["n"], nz=axes[2]["n"], dx=axes[0]["d"],
                  dy=axes[1]["d"], dz=axes[2]["d"])
    volumes, stiffness, boundary = assemble(mesh)
    centres = [np.asarray(a) / s for a, s in zip(mesh.cellCenters, scale)]
    index = np.unravel_index(np.arange(volumes.size), tuple(w.size for w in widths[::-1]))[::-1]
    whole, inner = np.ones(volumes.size), np.ones(volumes.size)
    for w, i, length_i in zip(widths, index, size):
        lo, hi = _bounds(w, i)
        whole *= hi - lo
        inner *= interval_overlap(lo, hi, layer_depth, length_i - layer_depth)
    return Discretisation(volumes, stiffness, boundary, _normalised(volumes),
                          _normalised(whole - inner), dict(zip("xyz", centres)))


def prism(tess, thickness: float, z_widths: np.ndarray, layer_share: np.ndarray,
          d: tuple[float, float, float], mid_plane: bool = False) -> Discretisation:
    """A planform's admissible cells (``prism.Tessellation``) extruded through the
    thickness into FiPy prisms with the given z widths (m, from a face; summing to
    ``thickness``, or to half of it with ``mid_plane``: the top is then the mid-plane,
    a mirror, insulated; so are the tessellation's mirror lines).

    The mesh is FiPy's generic ``Mesh``: polygon faces top and bottom (triangles,
    or the cyclic polygons of merged cocircular triangles), quadrilateral faces on
    the sides, shorter vertex lists padded with -1 (masked, as FiPy's Gmsh reader
    does for mixed elements). The cell point is the planform cell's circumcentre at
    mid-layer, so every line between neighbouring cell points is normal to their
    face (see ``prism``) and FiPy's two-point flux is consistent. Layer: cells
    weighted by ``layer_share`` (fraction of the planform cell within the contact
    band), over the whole thickness, as in the plane model."""
    scale = np.array([_axis_scale(thickness, d[i], d[2]) for i in range(2)]) / tess.stretch
    if not np.isclose(scale[0], scale[1], rtol=1e-9):
        raise ValueError("the tessellation was stretched for another diffusivity ratio")
    z_nodes = np.concatenate([[0.0], np.cumsum(z_widths)]) / thickness
    mesh, insulated = _prism_mesh(tess, float(scale[0]), z_nodes, mid_plane)
    exterior = np.asarray(mesh.exteriorFaces, bool)
    volumes, stiffness, boundary = assemble(mesh, exposed=exterior & ~insulated)
    layers = z_widths.size
    planar = tess.physical(tess.centres)
    coordinates = {"x": np.tile(planar[:, 0], layers), "y": np.tile(planar[:, 1], layers),
                   "z": np.repeat(0.5 * (z_nodes[1:] + z_nodes[:-1]) * thickness, tess.cells)}
    layer = volumes * np.tile(layer_share, layers)
    return Discretisation(volumes, stiffness, boundary, _normalised(volumes), _normalised(layer),
                          coordinates)


def _padded(rows: list[np.ndarray], width: int) -> np.ndarray:
    """Ragged integer rows as a (width, n) array padded with -1 (FiPy's masked entries)."""
    out = np.full((width, len(rows)), -1, dtype=np.int64)
    for k, row in enumerate(rows):
        out[:row.size, k] = row
    return out


def _cell_sides(tess) -> tuple[np.ndarray, list[np.ndarray]]:
    """Planform edges that bound a cell (between two cells or on the outline), and the
    indices of those edges around each cell."""
    from .prism import unique_edges

    edges, side_edge = unique_edges(tess.triangles)
    pairs = np.unique(np.column_stack([side_edge.ravel(), np.repeat(tess.cell_of, 3)]), axis=0)
    cells_at = np.bincount(pairs[:, 0], minlength=len(edges))        # distinct cells at an edge
    triangles_at = np.bincount(side_edge.ravel(), minlength=len(edges))
    inside_one_cell = (cells_at == 1) & (triangles_at == 2)
    pairs = pairs[~inside_one_cell[pairs[:, 0]]]
    kept, face_of_pair = np.unique(pairs[:, 0], return_inverse=True)
    order = np.argsort(pairs[:, 1], kind="stable")
    split = np.cumsum(np.bincount(pairs[:, 1], minlength=tess.cells))[:-1]
    return edges[kept], np.split(face_of_pair[order], split)


def _prism_mesh(tess, scale: float, z_nodes: np.ndarray, mid_plane: bool):
    """FiPy ``Mesh`` of the prisms (coordinates: stretched planform x ``scale``, z / L)
    and the mask of its insulated faces (mirror lines; the top with ``mid_plane``).
    Numbering: vertex p of level k is k n + p; the planform cells' faces at level k
    come first (k c + cell), then the side faces of layer k (k s + side); cell
    c of layer k is k c + cell."""
    from .prism import cell_loops

    n, cells, layers = len(tess.points), tess.cells, z_nodes.size - 1
    sides, cell_sides = _cell_sides(tess)
    vertices = np.vstack([np.tile(tess.points.T * scale, layers + 1),
                          np.repeat(z_nodes, n)[None, :]])
    faces = _prism_faces(cell_loops(tess), sides, n, layers)
    first_side = cells * (layers + 1)
    around = _padded(cell_sides, max(s.size for s in cell_sides))
    cell_faces = np.concatenate([
        np.vstack([np.arange(cells) + k * cells, np.arange(cells) + (k + 1) * cells,
                   np.where(around >= 0, around + first_side + k * len(sides), -1)])
        for k in range(layers)], axis=1)
    centre_z = np.repeat(0.5 * (z_nodes[1:] + z_nodes[:-1]), cells)
    cell_centres = np.vstack([np.tile(tess.centres.T * scale, layers), centre_z[None, :]])
    face_centres = np.vstack([np.tile(tess.centres.T * scale, layers + 1),
                              np.repeat(z_nodes, cells)[None, :]])
    mesh = _centred_mesh_class()(vertices, faces, cell_faces, cell_centres,
                                 np.arange(first_side), face_centres)
    insulated = np.zeros(faces.shape[1], bool)
    insulated[first_side:] = np.tile(_on_mirror(tess, sides), layers)
    if mid_plane:
        insulated[layers * cells:first_side] = True
    return mesh, insulated


def _prism_faces(loops: list[np.ndarray], sides: np.ndarray, n: int, layers: int) -> np.ndarray:
    """Vertex ids (padded with -1) of the horizontal faces, level by level, then of the
    quadrilateral side faces (a_k, b_k, b_k+1, a_k+1), layer by layer."""
    corners = max(4, max(loop.size for loop in loops))
    flat = _padded(loops, corners)
    horizontal = np.concatenate([np.where(flat >= 0, flat + k * n, -1)
                                 for k in range(layers + 1)], axis=1)
    a, b = sides.T
    vertical = np.concatenate([np.stack([a + k * n, b + k * n, b + (k + 1) * n, a + (k + 1) * n])
                               for k in range(layers)], axis=1)
    return np.concatenate([horizontal, np.pad(vertical, ((0, corners - 4), (0, 0)),
                                              constant_values=-1)], axis=1)


def _on_mirror(tess, sides: np.ndarray) -> np.ndarray:
    """Planform edges lying on one of the tessellation's mirror lines."""
    on = np.zeros(len(sides), bool)
    for axis, value in tess.mirrors:
        on |= np.all(tess.points[sides][:, :, axis] == value, axis=1)
    return on


@lru_cache(maxsize=1)
def _centred_mesh_class():
    """FiPy's generic ``Mesh`` with given cell points (FiPy would average the face
    centres) and the top/bottom faces centred on them, so that the segment from a
    cell point to its top or bottom face is vertical. Cell volumes do not depend on
    those face centres (FiPy's divergence-theorem volume uses the x component of the
    face normals, zero on horizontal faces)."""
    from fipy.meshes.mesh import Mesh

    class CentredMesh(Mesh):
        def __init__(self, vertex_coords, face_vertex_ids, cell_face_ids, cell_centres,
                     centred_faces, face_centres):
            self._given_cells = cell_centres
            self._given_faces = (centred_faces, face_centres)
            super().__init__(vertex_coords, face_vertex_ids, cell_face_ids)

        def _calcCellCenters(self):
            return self._given_cells

        def _calcFaceCenters(self):
            centres = np.array(super()._calcFaceCenters())
            ids, values = self._given_faces
            centres[:, ids] = values
            return centres

    return CentredMesh
