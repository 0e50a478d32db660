"""Concentration-dependent diffusion, D(c, T) = D(T) f(c/Mm_ref) (``sorption``;
Crank 1975 ch. 9), on the FiPy slab (Sheet) and (r, z) grid (Disc or annulus).

One Arrhenius factor still multiplies every D, so the rescaled clock of ``clock`` stays
exact: dc/dtau = div(D0 f(c) grad c) (Crank 1975 §7.2 with §9.1). Time and mesh are
scaled with the LARGEST D met, D0 max f, so that the planned steps and cells resolve the
fastest diffusion; the FiPy coefficient is then f(c)/max f <= 1 on the faces, evaluated
at the face value of c (the constrained surface value on exposed faces).

FiPy assembles the mesh's unit operator once (``direct.discretise``); ``Faces`` takes it
apart by face, and the operator of any face coefficient f(c_face) follows from it exactly
as FiPy's ``DiffusionTerm(coeff=FaceVariable)`` would build it (a test sweeps FiPy itself
and agrees to round-off), without FiPy's per-sweep assembly (about 20 ms a sweep).
Each backward-Euler step is swept (Picard: coefficient from the latest iterate) until the
residual of the new iterate in its own operator, checked after every sweep, is below
``SWEEP_TOLERANCE`` of the right side; a step that does not get there in ``MAX_SWEEPS``
sweeps raises ``SolverError`` naming part, step and time. The steps are those of the
direct models (geometric, restarting at every change), run twice for the Richardson pair
(``direct``).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy import sparse
from scipy.sparse import linalg as splinalg

from ..errors import SolverError
from .clock import scales as scales_of
from .direct import _richardson, discretise, step_plan, swing
from .exposure import Diffusivity
from .geometry import Disc, Sheet
from .march import History, _rounded, norm
from .results import DiffusionResult

SWEEP_TOLERANCE = 1e-9   # residual / |right side| at which a step's sweeps stop
MAX_SWEEPS = 60


def fastest(diffusivity: Diffusivity, law, exposure, times) -> Diffusivity:
    """The diffusivity scaled by the largest f met up to the wettest surface value: the
    scale of the plan (cells and steps) and of the march."""
    factor = law.largest_factor(wettest(exposure, times))
    return Diffusivity(tuple(d * factor for d in diffusivity.pre_exponential),
                       diffusivity.activation_energy)


def refined(plan, law, exposure, times):
    """The direct plan with cells refined by 2 sqrt(max f / min f) per axis: where D is
    low (the dry side of a front) the profile is steeper by about sqrt of the D ratio
    (Crank 1975 §9.4, the sharp fronts of strongly varying D); measured on a sheet with
    k = 2 against a fine method of lines, the Fickian cell count left 10x the accuracy."""
    values = law.factor(np.linspace(0.0, wettest(exposure, times), 65))
    factor = 2.0 * float(np.sqrt(np.max(values) / np.min(values)))
    cells = tuple(int(np.ceil(n * factor)) for n in plan.cells_per_axis)
    return replace(plan, cells_per_axis=cells, cells=int(np.prod(cells)),
                   finest=plan.finest / factor,
                   reason=plan.reason + f"; cells x{factor:.2g} for the steepest front")


def solve_nonlinear(geometry, diffusivity, law, exposure, times, chosen, *,
                    surface_layer_depth=5e-4, store_fields=False, part="") -> DiffusionResult:
    """Mean and contact-layer moisture (weight %) at ``times`` (s): the Richardson pair of
    swept backward-Euler marches (module docstring). ``chosen`` was planned with
    ``fastest(...)``."""
    if not isinstance(geometry, (Sheet, Disc)):
        raise TypeError(f"no concentration-dependent model for {type(geometry).__name__}")
    scaled = fastest(diffusivity, law, exposure, times)
    scales = scales_of(geometry, scaled, exposure)
    weights = discretise(geometry, scaled, chosen.cells_per_axis, surface_layer_depth,
                         chosen.finest, chosen.growth)
    faces = Faces.of(weights)
    top = law.largest_factor(wettest(exposure, times))
    runs = []
    for bisect in (False, True):
        steps = step_plan(exposure, times, scales, chosen.steps_per_doubling, bisect)
        runs.append(sweep_march(faces, weights, law, top, steps, exposure.initial_moisture,
                                store_fields, part))
    coarse, fine = runs
    combine, estimate = _richardson(chosen, coarse, fine, swing(exposure, times) or 1.0, True)
    result = DiffusionResult(times, combine(coarse.mean, fine.mean),
                             combine(coarse.layer, fine.layer), chosen.model, weights.cells,
                             coarse.steps + fine.steps, estimate, chosen.reason)
    if store_fields:
        result.fields = combine(coarse.fields, fine.fields)
        result.cell_coordinates = weights.coordinates
    return result


def wettest(exposure, times) -> float:
    """The largest moisture the part meets (surface values, initial moisture)."""
    edges = np.concatenate([exposure.change_times, np.asarray(times, float)])
    return max(float(np.max(exposure.surface_moisture(edges))), exposure.initial_moisture)


@dataclass(frozen=True)
class Faces:
    """FiPy's unit operator taken apart by face: the interior faces (cells i < j, their
    transmissibility area/distance), each cell's exposed-face transmissibility, volumes.
    FiPy builds DiffusionTerm(coeff) from exactly these, times the coefficient at the face
    (``discretisation.assemble``; its arithmetic face value of c, the surface value on
    exposed faces), so the operator of any coefficient follows without re-assembly."""

    rows: np.ndarray
    cols: np.ndarray
    transmissibility: np.ndarray
    boundary: np.ndarray
    volumes: np.ndarray

    @classmethod
    def of(cls, disc) -> "Faces":
        k = disc.stiffness.tocoo()
        upper = k.row < k.col
        return cls(k.row[upper], k.col[upper], -k.data[upper], disc.boundary, disc.volumes)

    def operator(self, c, g, law, top) -> tuple[sparse.csr_matrix, np.ndarray]:
        """(K(c), f(g)): the stiffness with face coefficients f(c_face)/top and the boundary
        vector of the surface value g (its coefficient f(g)/top)."""
        n = self.volumes.size
        flux = law.factor(0.5 * (c[self.rows] + c[self.cols])) / top * self.transmissibility
        edge = law.factor(g) / top * self.boundary
        diagonal = np.bincount(self.rows, flux, n) + np.bincount(self.cols, flux, n) + edge
        k = sparse.coo_matrix((np.concatenate([-flux, -flux, diagonal]),
                               (np.concatenate([self.rows, self.cols, np.arange(n)]),
                                np.concatenate([self.cols, self.rows, np.arange(n)]))), (n, n))
        return k.tocsr(), edge * g


def sweep_march(faces: Faces, weights, law, top, steps, initial, keep_fields, part) -> History:
    """Backward Euler in scaled time, each step swept to convergence (module docstring)."""
    c = np.full(faces.volumes.size, float(initial))
    want = {int(k) for k in steps.outputs}
    record = {0: c.copy()} if 0 in want else {}
    dts = _rounded(np.diff(steps.nodes))
    for k, dt in enumerate(dts, start=1):
        c = _sweep(faces, c, float(steps.surface_before[k]), law, top, dt, part, k, steps.times[k])
        if k in want:
            record[k] = c.copy()
    states = np.array([record[int(k)] for k in steps.outputs])
    return History(mean=states @ weights.mean_weights, layer=states @ weights.layer_weights,
                   fields=states if keep_fields else None, steps=int(dts.size), factorisations=0)


def _sweep(faces: Faces, old, g, law, top, dt, part, index, time) -> np.ndarray:
    """Picard sweeps (M/dt + K(c)) c_new = M old/dt + f(g) with K from the latest iterate,
    until the residual of the new iterate in its own operator is below ``SWEEP_TOLERANCE``
    of the right side; SolverError if ``MAX_SWEEPS`` do not get there."""
    mass = faces.volumes / dt
    c, residual = old, np.inf
    for _ in range(MAX_SWEEPS):
        k, f = faces.operator(c, g, law, top)
        rhs = mass * old + f
        c = splinalg.spsolve((sparse.diags(mass) + k).tocsc(), rhs)
        k, f = faces.operator(c, g, law, top)
        residual = norm(mass * c + k @ c - mass * old - f) / max(norm(mass * old + f), 1e-300)
        if not np.isfinite(residual):
            break
        if residual <= SWEEP_TOLERANCE:
            return c
    raise SolverError(part, index, time, f"concentration-dependent sweeps did not converge: "
                      f"residual {residual:.2e} after {MAX_SWEEPS} sweeps")
