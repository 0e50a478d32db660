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

import numpy as np
from scipy import sparse
from scipy.sparse import linalg as splinalg

from ..errors import SolverError

log = logging.getLogger(__name__)

DIRECT_LIMIT = {1: 10**9, 2: 40_000, 3: 30_000}  # cells per dimension count; above: CG
# (notes/fipy-measured.md: 3-D LU fills in as cells^2.1, CG stays near linear)
RESIDUAL_TOLERANCE = 1e-9
_FACTOR_CACHE_SIZE = 64


@dataclass
class Discretisation:
    """A FiPy-assembled operator with the weights that integrate its cell values."""

    volumes: np.ndarray            # (n,) scaled cell volumes (M = diag(volumes))
    stiffness: sparse.csr_matrix   # K, (n, n)
    boundary: np.ndarray           # f, (n,) for a unit surface value
    mean_weights: np.ndarray       # (n,), sum 1: volume mean
    layer_weights: np.ndarray      # (n,), sum 1: mean over the surface layer
    coordinates: dict[str, np.ndarray] = field(default_factory=dict)  # physical cell centres, m

    @property
    def cells(self) -> int:
        return int(self.volumes.size)


# --------------------------------------------------------------- assembly


def assemble(mesh, corrected: bool = False) -> tuple[np.ndarray, sparse.csr_matrix, np.ndarray]:
    """(volumes, K, f) of dc/dt = laplacian(c) with c = 1 on every exterior face.

    FiPy's matrix for ``TransientTerm() == DiffusionTerm(1)`` at dt = 1 is
    M + K; its right side with c_old = 0 is f.
    """
    from fipy import (CellVariable, DiffusionTerm, DiffusionTermCorrection, LinearLUSolver,
                      TransientTerm)

    var = CellVariable(mesh=mesh, value=0.0)
    var.constrain(1.0, mesh.exteriorFaces)
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

    Factorisations are cached per distinct (dt, theta); meshes above
    ``DIRECT_LIMIT`` cells use conjugate gradients with a Jacobi preconditioner
    (the matrix is symmetric positive definite on orthogonal meshes).
    """

    def __init__(self, disc: Discretisation, part: str = ""):
        self.disc = disc
        self.part = part
        self.iterative = disc.cells > DIRECT_LIMIT[max(1, len(disc.coordinates))]
        self._banded = _tridiagonal(disc.stiffness)
        self._factors: OrderedDict[tuple[float, float], object] = OrderedDict()
        self.factorisations = 0

    def _solver(self, dt: float, theta: float):
        key = (float(dt), float(theta))
        if key in self._factors:
            self._factors.move_to_end(key)
            return self._factors[key]
        matrix = (sparse.diags(self.disc.volumes / dt) + theta * self.disc.stiffness).tocsc()
        solver = (matrix, None if self.iterative else splinalg.splu(matrix))
        self.factorisations += 1
        self._factors[key] = solver
        if len(self._factors) > _FACTOR_CACHE_SIZE:
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
        matrix, lu = self._solver(dt, theta)
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
        scale = max(np.linalg.norm(rhs), np.finfo(float).tiny)
        residual = np.linalg.norm(difference) / scale
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


def disc(outer_radius: float, thickness: float, inner_radius: float, radial_cells: int,
         axial_cells: int, layer_depth: float, radial_d: float, axial_d: float) -> Discretisation:
    """Disc or annulus in (r, z), FiPy CylindricalGrid2D; layer: the outer rim."""
    from fipy import CylindricalGrid2D

    scale_r = _axis_scale(thickness, radial_d, axial_d)
    width = outer_radius - inner_radius
    mesh = CylindricalGrid2D(nr=radial_cells, nz=axial_cells, dr=width * scale_r / radial_cells,
                             dz=1.0 / axial_cells, origin=((inner_radius * scale_r,), (0.0,)))
    volumes, stiffness, boundary = assemble(mesh)
    r_c, z_c = (np.asarray(a) for a in mesh.cellCenters)
    dr = width / radial_cells
    r_lo = r_c / scale_r - 0.5 * dr
    r_hi = r_lo + dr
    band_lo = max(outer_radius - layer_depth, inner_radius)
    ring = np.clip(np.minimum(r_hi, outer_radius) ** 2 - np.maximum(r_lo, band_lo) ** 2, 0, None)
    return Discretisation(volumes, stiffness, boundary, _normalised(volumes), _normalised(ring),
                          {"x": r_c / scale_r, "z": z_c * thickness})


def bar(length: float, width: float, thickness: float, cells: tuple[int, int, int],
        layer_depth: float, d: tuple[float, float, float]) -> Discretisation:
    """Rectangular bar, FiPy Grid3D; layer: within ``layer_depth`` of any face."""
    from fipy import Grid3D

    size = np.array([length, width, thickness])
    scale = np.array([_axis_scale(thickness, d[i], d[2]) for i in range(3)])
    n = np.asarray(cells)
    spacing = size * scale / n
    mesh = Grid3D(nx=n[0], ny=n[1], nz=n[2], dx=spacing[0], dy=spacing[1], dz=spacing[2])
    volumes, stiffness, boundary = assemble(mesh)
    centres = [np.asarray(a) / s for a, s in zip(mesh.cellCenters, scale)]
    physical = size / n
    inner = np.ones(volumes.size)
    for centre, h, length_i in zip(centres, physical, size):
        lo = centre - 0.5 * h
        inner *= interval_overlap(lo, lo + h, layer_depth, length_i - layer_depth)
    layer = np.prod(physical) - inner
    return Discretisation(volumes, stiffness, boundary, _normalised(volumes), _normalised(layer),
                          dict(zip("xyz", centres)))


def plane(triangulation, thickness: float, layer_distance: np.ndarray, layer_depth: float,
          d: tuple[float, float, float]) -> Discretisation:
    """In-plane 2-D problem on a near-equilateral triangle mesh
    (``planform.Triangulation``; the two-point flux is exact where the
    circumcentre is the centroid); layer: cells whose centroid lies within
    ``layer_depth`` of the contact edge (distances given per triangle)."""
    scale = np.array([_axis_scale(thickness, d[0], d[2]), _axis_scale(thickness, d[1], d[2])])
    mesh = triangulation.fipy_mesh(scale)
    volumes, stiffness, boundary = assemble(mesh)
    centres = [np.asarray(a) / s for a, s in zip(mesh.cellCenters, scale)]
    layer = np.where(layer_distance <= layer_depth, volumes, 0.0)
    if not layer.any():  # layer thinner than one cell row: the boundary row
        layer = np.where(layer_distance <= layer_distance.min() * 1.0001, volumes, 0.0)
    return Discretisation(volumes, stiffness, boundary, _normalised(volumes), _normalised(layer),
                          {"x": centres[0], "y": centres[1]})
