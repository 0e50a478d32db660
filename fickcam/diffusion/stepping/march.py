"""Time-marching of an operator (``discretisation.Discretisation``): theta-scheme steps
(backward Euler by default) with one sparse factorisation per distinct step size,
shared by every march on that operator, and a residual check after every solve.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.linalg.lapack import dgtsv
from scipy.sparse import linalg as splinalg

from ...errors import SolverError
from ..operators.discretisation import Discretisation
from .step_plans import StepPlan

DIRECT_LIMIT = {1: 10**9, 2: 40_000, 3: 30_000}  # cells per dimension count; above: CG
# (3-D sparse LU fills in as cells^2.1 on FiPy's grids, plain CG stays near linear;
# measured: benchmarks/results/tuned_constants.md)
RESIDUAL_TOLERANCE = 1e-9
ORDERING = "MMD_AT_PLUS_A"  # minimum degree on A + A^T, diagonal pivots: K is symmetric (SuperLU)
_FACTOR_CACHE_SIZE = 64
_FACTOR_CACHE_BYTES = 2 * 1024 ** 3


class ThetaStepper:
    """Theta-scheme time steps of a discretised diffusion operator.

    (M/dt + theta K) c_new = (M/dt - (1-theta) K) c_old
    + (theta g_new + (1-theta) g_old) f (Crank 1975, §8.2.4; theta = 1 backward
    Euler, 1/2 Crank-Nicolson). Backward Euler is bounded for M-matrix operators
    at any step (maximum principle: Morton & Mayers 2005, §2.11); Crank-Nicolson is not.

    Factorisations are cached per distinct (dt, theta) on the ``Discretisation``
    (a Richardson pair of marches shares them), at most ``_FACTOR_CACHE_SIZE`` of
    them and ``_FACTOR_CACHE_BYTES`` in all, least recently used dropped; meshes above
    ``DIRECT_LIMIT`` cells use conjugate gradients with a Jacobi preconditioner
    (the matrix is symmetric positive definite on orthogonal meshes).

    Parameters
    ----------
    disc : Discretisation
        The operator (mass M, stiffness K, boundary vector f) in scaled coordinates.
    part : str
        The part's name, for error messages.

    Raises
    ------
    SolverError
        From ``step``, when a linear solve fails or leaves a residual above
        ``RESIDUAL_TOLERANCE``.

    References
    ----------
    - Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
    - Morton, K. W. & Mayers, D. F. (2005). Numerical Solution of Partial Differential
      Equations: An Introduction, 2nd ed. Cambridge University Press.
      doi:10.1017/CBO9780511812248
    """

    def __init__(self, disc: Discretisation, part: str = ""):
        self.disc = disc
        self.part = part
        self.iterative = disc.cells > DIRECT_LIMIT[max(1, len(disc.coordinates))]
        self._banded = _tridiagonal(disc.stiffness) if disc.mass is None else None
        self._factors = disc.factors
        self.factorisations = 0

    def _solver(self, dt: float, theta: float):
        key = (float(dt), float(theta))
        if key in self._factors:
            self._factors.move_to_end(key)
            return self._factors[key]
        matrix = (self.disc.mass_matrix() / dt + theta * self.disc.stiffness).tocsc()
        # symmetric positive definite: symmetric ordering, diagonal pivots only
        lu = None if self.iterative else splinalg.splu(matrix, permc_spec=ORDERING,
                                                       diag_pivot_thresh=0.0,
                                                       options={"SymmetricMode": True})
        self.factorisations += 1
        self._factors[key] = solver = (matrix, lu, _factor_bytes(matrix, lu))
        while len(self._factors) > 1 and (len(self._factors) > _FACTOR_CACHE_SIZE or sum(
                entry[2] for entry in self._factors.values()) > _FACTOR_CACHE_BYTES):
            self._factors.popitem(last=False)
        return solver

    def step(self, c: np.ndarray, dt: float, g_old: float, g_new: float, index: int,
             time: float, theta: float = 1.0, held_change: float = 0.0) -> np.ndarray:
        """One step of size dt (scaled time); ``index``/``time`` name it in errors.
        ``held_change``: the change of the held nodes' value over the step (their mass
        coupling moves it into the free nodes: - M_fb (g_end - g_start) / dt)."""
        disc = self.disc
        mass_c = disc.volumes * c if disc.mass is None else disc.mass @ c
        rhs = mass_c / dt + (theta * g_new + (1 - theta) * g_old) * disc.boundary
        if disc.held_mass is not None and held_change != 0.0:
            rhs -= disc.held_mass * (held_change / dt)
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
    """Cell values integrated at the output nodes of a march.

    Parameters
    ----------
    mean : numpy.ndarray
        The mean moisture [weight %] at each output node.
    layer : numpy.ndarray
        The surface layer's mean moisture [weight %] at each output node.
    fields : numpy.ndarray or None
        The cell values [weight %], shape (outputs, cells), when kept.
    steps : int
        Steps taken.
    factorisations : int
        Sparse factorisations made.
    track : numpy.ndarray or None
        A swept march's weighted sums at every node [weight %] (``dense_output``).
    """

    mean: np.ndarray
    layer: np.ndarray
    fields: np.ndarray | None
    steps: int
    factorisations: int
    # swept marches: weighted sums at every node (``dense_output``)
    track: np.ndarray | None = None


def march(disc: Discretisation, steps: StepPlan, initial: float, *, keep_fields: bool = False,
          part: str = "", scheme: str = "backward_euler", restart_steps: int = 2) -> History:
    """March an operator over a plan's step boundaries and record its outputs.

    The surface value is ``steps.surface[k]`` at ``steps.nodes[k]`` (right-continuous; a
    step ending at a jump uses ``steps.surface_before[k]``, the left limit). ``scheme``
    ``crank_nicolson`` takes ``restart_steps`` backward-Euler steps from every node index
    in ``steps.restarts`` (t = 0 and each environment change), which damps the oscillation
    of the stiff modes a jump excites.

    Parameters
    ----------
    disc : Discretisation
        The operator in scaled coordinates.
    steps : StepPlan
        The step boundaries in scaled time tau* [-], their times [s] (labelling errors),
        the surface moisture [weight %] at each (right and left limits), the node indices
        recorded and those Crank-Nicolson restarts after.
    initial : float
        The uniform initial moisture [weight %].
    keep_fields : bool
        Also return the cell values.
    part : str
        The part's name, for error messages.
    scheme : str
        ``"backward_euler"`` or ``"crank_nicolson"``.
    restart_steps : int
        Backward-Euler steps at each restart [-].

    Returns
    -------
    History
        The mean and layer moisture [weight %] at the outputs, and the march's counts.

    Raises
    ------
    ValueError
        For an unknown ``scheme``.
    SolverError
        When a step's linear solve fails.
    """
    nodes, outputs = steps.nodes, steps.outputs
    stepper = ThetaStepper(disc, part)
    c = np.full(disc.cells, float(initial))
    want = np.zeros(nodes.size, bool)
    want[outputs] = True
    theta = np.ones(nodes.size)
    if scheme == "crank_nicolson":
        theta[:] = 0.5
        for start in steps.restarts:
            theta[start + 1:start + 1 + restart_steps] = 1.0
    elif scheme != "backward_euler":
        raise ValueError(f"unknown time scheme {scheme!r}")
    record = {k: None for k in np.unique(outputs)}
    if 0 in record:
        record[0] = c.copy()
    sizes = rounded_steps(np.diff(nodes))
    labels, surface, ending = steps.times, steps.surface, steps.surface_before
    held = held_values(ending, initial)
    for k, dt in enumerate(sizes, start=1):
        c = stepper.step(c, dt, surface[k - 1], ending[k], k, labels[k], theta[k],
                         held[k] - held[k - 1])
        if want[k]:
            record[k] = c.copy()
    states = np.array([record[k] for k in outputs])
    return History(mean=states @ disc.mean_weights + disc.held_mean * held[outputs],
                   layer=states @ disc.layer_weights + disc.held_layer * held[outputs],
                   fields=states if keep_fields else None, steps=int(sizes.size),
                   factorisations=stepper.factorisations)


def held_values(ending: np.ndarray, initial: float) -> np.ndarray:
    """The value of the nodes held at the surface value, at each node of the march.

    Node 0 holds the state's own ``initial`` (before any jump there); later nodes the
    left limit of the surface value.

    Parameters
    ----------
    ending : numpy.ndarray
        The surface moisture [weight %] at the end of each step (left limit).
    initial : float
        The initial moisture [weight %].

    Returns
    -------
    numpy.ndarray
        The held nodes' moisture [weight %] at each node.
    """
    held = np.asarray(ending, float).copy()
    held[0] = initial
    return held


def _factor_bytes(matrix, lu) -> int:
    """Memory held by a cached matrix and its LU factors: 12 bytes per stored entry."""
    return 12 * (matrix.nnz + (0 if lu is None else lu.nnz))


def norm(vector: np.ndarray) -> float:
    """Euclidean norm of a vector, computed without BLAS.

    A threaded ddot costs about a millisecond per call here, more than the triangular
    solves of a small mesh.

    Parameters
    ----------
    vector : numpy.ndarray
        A 1-D array, in any unit.

    Returns
    -------
    float
        sqrt(sum of squares), in the vector's unit.
    """
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


def rounded_steps(steps: np.ndarray) -> np.ndarray:
    """Round steps to 12 significant digits so that equal blocks share one factorisation.

    Parameters
    ----------
    steps : numpy.ndarray
        The step sizes [-] (scaled time).

    Returns
    -------
    numpy.ndarray
        The rounded steps [-].
    """
    return np.array([float(f"{s:.12g}") for s in steps])

