"""Concentration-dependent diffusion, D(c, T) = D(T) f(c/Mm_ref) (``sorption``;
Crank 1975 ch. 9), on the FiPy slab (Sheet), (r, z) grid (Disc or annulus) and the 3-D
cells of a Bar (Grid3D) or of a CamPlate or LinkBar (prisms of Delaunay-admissible
planform cells), the latter cut at their mirror planes (``symmetry_cuts``).

One Arrhenius factor still multiplies every D, so the rescaled clock of ``clock`` stays
exact: dc/dtau = div(D0 f(c) grad c) (Crank 1975 §7.2 with §9.1). Time and mesh are
scaled with the LARGEST D met, D0 max f, so that the planned steps resolve the fastest
diffusion, and the cells are sized at the smallest (``nonlinear_plan``); the FiPy coefficient is then f/max f <= 1 on the faces, f the mean of f
between the face's two sides (a cell and its neighbour, or a cell and the surface value on
an exposed face): the two-point flux of the Kirchhoff potential Phi = integral of f
(``ConcentrationDependent.mean_factor``). f at the surface value alone on the exposed
half cell (FiPy's face value there) is the end-point rule of that flux, first order in the
jump across the half cell; its error, opposite in sign to the cells' own, made the
observed order erratic (-0.6 to 7.0 on the sheet, k = 1, 2) and skins 10x less accurate; with
the mean every face is second order (2.00, tests/test_sorption_nonlinear_solid.py).

FiPy assembles the mesh's unit operator once (``finite_volume.discretise``); ``Faces`` takes it
apart by face, and the operator of any face coefficient f(c_face) follows from it exactly
as FiPy's ``DiffusionTerm(coeff=FaceVariable)`` would build it (a test sweeps FiPy itself
and agrees to round-off), without FiPy's per-sweep assembly (about 20 ms a sweep).
Each backward-Euler step is swept (Picard: coefficient from the latest iterate) until the
residual of the new iterate in its own operator, checked after every sweep, is below
``SWEEP_TOLERANCE`` of the right side; a step that does not get there in ``MAX_SWEEPS``
sweeps raises ``SolverError`` naming part, step and time. The linear systems of the
sweeps are solved by CG on lagged LU factors (``Lagged``), each only to ``FORCING`` x the
residual of the iterate it starts from (inexact Picard), and a step's sweeps start from
the last two states extrapolated in time (``extrapolated``): on a 6 x 4 x 2 mm bar (k = 2,
absorbing, accuracy 1e-2, 4 968 cells) 20.3 CPU s against 27.6 with exact solves from the
old state, the same means to 1.6e-9 of Mm (benchmarks/dc_bar.py sweeps; its profile
showed the triangular solves of the lagged factors at 60-75 % of the CPU). The steps are
those of the direct models (geometric, restarting at every change), run twice for the
Richardson pair (``finite_volume``).

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy import sparse
from scipy.sparse import linalg as splinalg

from ..accuracy.budget import ABSORPTION_MARGIN, SKIN_CELLS_MARGIN
from ...errors import SolverError
from ..accuracy.error_model import TIME_ERROR
from ..forcing.clock import scales as scales_of
from ..models.finite_volume import discretise, richardson_pair, step_plan
from ..operators.symmetry_cuts import mirrored
from ..problem.cache import RunCache
from ..problem.definition import DiffusionProblem
from ..problem.exposure import Diffusivity, sample_times, swing
from ..problem.results import DiffusionResult
from ..stepping.dense_output import Extension, StepRecord
from ..stepping.march import ORDERING, History, rounded_steps, norm

SWEEP_TOLERANCE = 1e-9   # residual / |right side| at which a step's sweeps stop
MAX_SWEEPS = 60
LAG_ITERATIONS = 15  # CG iterations on the lagged factors before a refactorisation
LINEAR_TOLERANCE = 1e-12
FORCING = 0.01  # a sweep's CG stops at FORCING x the residual of the iterate it starts from
# (measured: benchmarks/results/tuned_constants.md)


@dataclass(frozen=True)
class Sweeps:
    """When a step's Picard sweeps stop, and how exactly each sweep solves.

    The sweeps stop at ``tolerance`` x the right side, or with a
    ``SolverError`` after ``most`` sweeps; each sweep's linear system solved to ``forcing``
    x the residual of the iterate it starts from (``sweep_step``). The defaults are the run's;
    tests pass others instead of changing the module's values.

    Parameters
    ----------
    tolerance : float
        The residual [-], relative to the right side, at which a step's sweeps stop.
    most : int
        Sweeps allowed before ``SolverError``.
    forcing : float
        Each sweep's linear solve stops at this share [-] of the residual it starts from.
    """

    tolerance: float = SWEEP_TOLERANCE
    most: int = MAX_SWEEPS
    forcing: float = FORCING


SWEEPS = Sweeps()

SPACE_TO_ERROR = 1.0  # error / (m x the space estimate of the cells' plan) (measured:
#   benchmarks/results/tuned_constants.md)


def fastest(diffusivity: Diffusivity, law, exposure, times) -> Diffusivity:
    """The diffusivity scaled by the largest factor f met: the plan's and march's scale.

    f is read up to the wettest surface value; the result scales the plan (cells and
    steps) and the march.

    Parameters
    ----------
    diffusivity : Diffusivity
        The material's diffusivity (pre-exponential [m^2/s], activation energy [J/mol]).
    law : ConcentrationDependent
        The factor f(c/Mm_ref) [-].
    exposure : Exposure
        The history (times [s], temperature [K], surface moisture [weight %]).
    times : numpy.ndarray
        The output times [s].

    Returns
    -------
    Diffusivity
        D0 max f [m^2/s] per axis, the same activation energy.
    """
    factor = law.largest_factor(wettest(exposure, times))
    return Diffusivity(tuple(d * factor for d in diffusivity.pre_exponential),
                       diffusivity.activation_energy)


def slowest(diffusivity: Diffusivity, law, exposure, times) -> Diffusivity:
    """The diffusivity scaled by the smallest factor f met: the steepest layer's scale.

    Parameters
    ----------
    diffusivity : Diffusivity
        Pre-exponential factors [m^2/s] and activation energy [J/mol] of the material.
    law : ConcentrationDependent
        f(c/Mm_ref) [-], read from dry to the wettest moisture met.
    exposure : Exposure
        Times [s], temperatures [K] and surface moisture [weight %] of the history.
    times : numpy.ndarray
        The outputs [s].

    Returns
    -------
    Diffusivity
        D0 min f [m^2/s] per axis, the same activation energy.
    """
    values = law.factor(np.linspace(0.0, wettest(exposure, times), 65))
    return Diffusivity(tuple(d * float(np.min(values)) for d in diffusivity.pre_exponential),
                       diffusivity.activation_energy)


def spread(law, exposure, times) -> float:
    """The ratio of the largest to the smallest diffusivity factor the part meets.

    Parameters
    ----------
    law : ConcentrationDependent
        The law f(c/Mm_ref) [-] compared at its ends.
    exposure : Exposure
        Its surface values [weight %] set the wettest moisture.
    times : numpy.ndarray
        The output times [s].

    Returns
    -------
    float
        max f / min f [-] over the moisture from 0 to the wettest value met.
    """
    values = law.factor(np.linspace(0.0, wettest(exposure, times), 65))
    return float(np.max(values) / np.min(values))


def skin_start(law, exposure) -> float | None:
    """When the surface may first dry to a skin of low diffusivity.

    It is the sample (``exposure.sample_times``) before the first one whose surface
    moisture has a D below the largest D met before (initial moisture, earlier surface values). From then on the part
    has a skin where the whole drop of c crosses a layer sqrt(D_min t) deep (desorption when
    D rises with c, Crank 1975 §9.3-9.4, absorption when it falls); before it, none.

    Parameters
    ----------
    law : ConcentrationDependent
        The factor f(c/Mm_ref) [-].
    exposure : Exposure
        The history (times [s], surface and initial moisture [weight %]).

    Returns
    -------
    float or None
        The time [s] the skin may start, or None.

    References
    ----------
    Crank (1975) §9.3-9.4, cited in the module docstring.
    """
    t = sample_times(exposure)
    g = np.asarray(exposure.surface_moisture(t), float)
    f = law.factor(np.concatenate([[exposure.initial_moisture], g]))
    below = f[1:] < np.maximum.accumulate(f)[:-1] * (1 - 1e-9)
    if not np.any(below):
        return None
    first = int(np.argmax(below))
    return float(t[max(first - 1, 0)])


def dries_to_a_skin(law, exposure) -> bool:
    """Whether the surface ever dries to a skin (``skin_start``).

    Parameters
    ----------
    law : ConcentrationDependent
        The moisture dependence f [-] of D.
    exposure : Exposure
        The exposure whose surface values [weight %] are read.

    Returns
    -------
    bool
        True when ``skin_start`` finds a start.
    """
    return skin_start(law, exposure) is not None


@dataclass(frozen=True)
class Sizing:
    """One constraint on the cells of a nonlinear plan.

    One constraint on the cells of a nonlinear plan: the Fickian ``plan`` of one D for
    accuracy / ``margin`` at some of the outputs (the earliest of them sets the layer to
    resolve); ``why`` for the plan's reason.

    Parameters
    ----------
    plan : Plan
        The Fickian plan of one D.
    margin : float
        m: the plan was made for accuracy / m [-].
    why : str
        The reason given in the plan.
    """

    plan: object
    margin: float
    why: str

    @property
    def error(self) -> float:
        """m x the space estimate of the plan (its time share taken out)."""
        return self.margin * (self.plan.error_estimate
                              - TIME_ERROR / self.plan.steps_per_doubling ** 2)

    def covers(self, other: "Sizing") -> bool:
        """Whether these cells are nowhere coarser than ``other``'s (finest and growth; the
        layout's error model grows with both; a uniform grid, finest 0, by its cells)."""
        return ((self.plan.finest > 0) == (other.plan.finest > 0)
                and self.plan.finest <= other.plan.finest and self.plan.growth <= other.plan.growth
                and self.plan.cells >= other.plan.cells)


def nonlinear_plan(planner, diffusivity, law, exposure, times, accuracy: float):
    """The direct plan (cells and steps) of a concentration-dependent part.

    The direct plan of a concentration-dependent part: steps from the fastest D (its
    scaled time is the march's). PrismCells: those of the fastest D at accuracy / m, m =
    ``ABSORPTION_MARGIN``, unless the surface dries to a skin (``skin_start``); then
    those of the slowest D at accuracy / m, m = 1 + SKIN_CELLS_MARGIN (sqrt(max f / min f) - 1),
    sized at the outputs from the skin's start on (the layer the skin makes is as young as the
    earliest of them; earlier outputs see no skin and take the fastest D's cells at
    accuracy / ``ABSORPTION_MARGIN``; the plan takes the cells that cover both, else, as
    before this split, the skin's at every output). On the 4 x 3 x 2 mm plate wetted for 1.5
    tau then dried (k = 5, first output 1e-3 tau; benchmarks/dc_defect_correction.py
    soak-dry) the skin's cells at every output made the corrected path's finer 3-D plan
    35 568 prisms (the run did not finish in 14 min); sized from the skin's start on, 3 840.
    Measured on the sheet against a fine
    method of lines (tests/test_sorption_nonlinear.py; k = 2 and 5, accuracy 1e-2 and
    1e-3): absorption with the fastest D's own cells erred up to 0.9 of the accuracy (the
    dry side of the front is steep but holds little water), hence ``ABSORPTION_MARGIN``;
    desorption with the slowest D's own cells erred 1.3-1.6 sqrt(max f / min f) times the
    accuracy before the Kirchhoff face mean (``Faces``); re-measured after it (sheet drying
    from Mm, k = 1, 2, 3, 5, accuracy 1e-2, 1e-3, 1e-4, vs a 1600-node method of lines):
    a margin 0 (the slowest D's own cells) erred up to 0.47 of the accuracy, 1 up to
    0.32, 4 up to 0.28, so ``SKIN_CELLS_MARGIN`` = 1 keeps a safety of 3 at 0.77-0.88 of the
    CPU of 4 (k = 5). The estimate: SPACE_TO_ERROR m x the space estimate of the cells' plan
    (the larger over the constraints met).
    ``planner(diffusivity, accuracy, outputs)``: the Fickian direct plan of the part.

    Parameters
    ----------
    planner : callable
        ``planner(diffusivity, accuracy, outputs)``: the Fickian direct plan of the part.
    diffusivity : Diffusivity
        D of the material at f = 1 (D0 [m^2/s], Ea [J/mol]).
    law : ConcentrationDependent
        f(c/Mm_ref) [-], which sets the spread of D.
    exposure : Exposure
        What the part is exposed to: times [s], T [K], surface moisture [weight %].
    times : numpy.ndarray
        The times [s] the plan must reach.
    accuracy : float
        The requested error relative to the swing [-].

    Returns
    -------
    Plan
        The steps of the fastest D and the chosen cells, with their error estimate [-].
    """
    times = np.asarray(times, float)
    fast_d = fastest(diffusivity, law, exposure, times)
    fast = planner(fast_d, accuracy, times)
    start = skin_start(law, exposure)
    wet_margin = ABSORPTION_MARGIN if spread(law, exposure, times) > 1 + 1e-9 else 1.0  # 1: Fick
    wet_why = f"no dry skin: cells sized at the largest D for accuracy / {wet_margin:g}"
    if start is None:
        chosen = [Sizing(planner(fast_d, accuracy / wet_margin, times), wet_margin, wet_why)]
    else:
        margin = 1.0 + SKIN_CELLS_MARGIN * (np.sqrt(spread(law, exposure, times)) - 1.0)
        slow_d = slowest(diffusivity, law, exposure, times)
        why = f"drying to a skin: cells sized at the smallest D for accuracy / {margin:.3g}"
        chosen = _skin_sizing(planner, slow_d, fast_d, accuracy, times, start, margin,
                              wet_margin, why)
    cells = chosen[0].plan
    estimate = float(SPACE_TO_ERROR * max(s.error for s in chosen[1:] or chosen)
                     + TIME_ERROR / fast.steps_per_doubling ** 2)
    reason = f"{fast.reason.split('; capped')[0]}; {chosen[0].why}"
    if estimate > accuracy:
        reason += "; capped: error above the requested accuracy"
    return replace(fast, cells=cells.cells, cells_per_axis=cells.cells_per_axis,
                   finest=cells.finest, growth=cells.growth, error_estimate=estimate,
                   reason=reason)


def _skin_sizing(planner, slow_d, fast_d, accuracy, times, start, margin, wet_margin,
                 why) -> list[Sizing]:
    """The cells of a part that dries to a skin from ``start`` on (``nonlinear_plan``): the
    chosen Sizing first, then the constraints it covers. Candidates: the skin's cells (slowest
    D, accuracy / ``margin``, outputs from ``start`` on), the soak's (fastest D, accuracy /
    ``wet_margin``, earlier outputs), each again at the smaller of the two accuracies (the
    growth of one, the finest width of the other); the fewest cells that cover both win, else
    the skin's cells at every output (the rule before the split)."""
    wet, dry = times[times < start], times[times >= start]
    everywhere = Sizing(planner(slow_d, accuracy / margin, times), margin, why)
    if wet.size == 0 or dry.size == 0:
        return [everywhere]
    both = (f"{why} at the outputs from {start:.3g} s on (the skin's start), at the largest D "
            f"for accuracy / {wet_margin:g} before")
    skin = Sizing(planner(slow_d, accuracy / margin, dry), margin, both)
    soak = Sizing(planner(fast_d, accuracy / wet_margin, wet), wet_margin, both)
    tighter = accuracy / max(margin, wet_margin)
    candidates = [skin, soak, Sizing(planner(fast_d, tighter, wet), margin, both),
                  Sizing(planner(slow_d, tighter, dry), margin, both)]
    covering = [c for c in candidates if c.covers(skin) and c.covers(soak)]
    if not covering:
        return [everywhere]
    best = min(covering, key=lambda c: c.plan.cells)
    return [best, skin, soak]


def solve_nonlinear(problem: DiffusionProblem, chosen, sweeps: Sweeps = SWEEPS,
                    cache: RunCache | None = None) -> DiffusionResult:
    """Solve a concentration-dependent problem by swept backward Euler.

    Mean and contact-layer moisture (weight %) at the ``problem``'s times (s), its
    ``sorption`` a ``ConcentrationDependent`` law: the Richardson pair of swept
    backward-Euler marches (module docstring). ``chosen`` was planned with
    ``fastest(...)``; ``sweeps``: when each step's sweeps stop; ``cache``: the run's.

    Parameters
    ----------
    problem : DiffusionProblem
        The part, material, exposure and output times [s]; its ``sorption`` a
        ``ConcentrationDependent`` law.
    chosen : Plan
        The plan, made with ``fastest(...)``.
    sweeps : Sweeps
        When each step's sweeps stop.
    cache : RunCache, optional
        The run's cache (None: a fresh one).

    Returns
    -------
    DiffusionResult
        Mean and contact-layer moisture [weight %] at the times, the error estimate [-].

    Raises
    ------
    SolverError
        When a step's sweeps do not converge.
    """
    geometry, diffusivity, law = problem.geometry, problem.diffusivity, problem.sorption
    exposure, times, part = problem.exposure, problem.times, problem.part
    surface_layer_depth, store_fields = problem.surface_layer_depth, problem.store_fields
    scaled = fastest(diffusivity, law, exposure, times)
    scales = scales_of(geometry, scaled, exposure, cache)
    weights = (discretise(geometry, scaled, chosen.cells_per_axis, surface_layer_depth,
                          chosen.finest, chosen.growth, cache)
               if not geometry.mirror_axes
               else mirrored(geometry, tuple(float(v) for v in scaled.pre_exponential),
                             chosen.cells_per_axis, chosen.finest, chosen.growth,
                             surface_layer_depth, cache))
    shared = SweptMarch(Faces.of(weights), law, law.largest_factor(wettest(exposure, times)),
                        part, sweeps)
    plans = [step_plan(exposure, times, scales, chosen.steps_per_doubling, bisect)
             for bisect in (False, True)]
    coarse, fine = (sweep_march(shared, weights, steps, exposure.initial_moisture, store_fields)
                    for steps in plans)
    combine, estimate = richardson_pair(chosen, coarse, fine, swing(exposure, times) or 1.0, True)
    result = DiffusionResult(times, combine(coarse.mean, fine.mean),
                             combine(coarse.layer, fine.layer), chosen.model, weights.cells,
                             coarse.steps + fine.steps, estimate, chosen.reason)
    if store_fields:
        return replace(result, fields=combine(coarse.fields, fine.fields),
                       cell_coordinates=weights.coordinates)
    # the limit search's extra times, read between the steps (``dense_output``)
    return replace(result, extend=Extension(
        result, [StepRecord.of(plans[0], coarse, fine, scales, exposure)],
        lambda values, _: (values[0][:, 0], values[0][:, 1]), swing(exposure, times) or 1.0,
        chosen.error_estimate, lambda both: solve_nonlinear(
            replace(problem.at(both), store_fields=False), chosen, sweeps, cache), part))


def wettest(exposure, times) -> float:
    """The largest moisture the part meets (surface values, initial moisture).

    Parameters
    ----------
    exposure : Exposure
        The history (surface and initial moisture [weight %]).
    times : numpy.ndarray
        The output times [s].

    Returns
    -------
    float
        The largest moisture [weight %].
    """
    edges = np.concatenate([exposure.change_times, np.asarray(times, float)])
    return max(float(np.max(exposure.surface_moisture(edges))), exposure.initial_moisture)


@dataclass(frozen=True)
class Faces:
    """FiPy's unit operator taken apart by face, to rebuild it for any coefficient.

    FiPy's unit operator taken apart by face: the interior faces (cells i < j, their
    transmissibility area/distance), each cell's exposed-face transmissibility, volumes.
    FiPy builds DiffusionTerm(coeff) from exactly these, times the coefficient at the face
    (``fipy_backend.assemble``), so the operator of any face coefficient (here the mean
    of f between the face's two sides) follows without re-assembly. The CSR pattern of
    that operator (``indptr``, ``indices``; ``order`` takes the values [upper, lower,
    diagonal] to it) is fixed, so a sweep only fills its values.

    Parameters
    ----------
    rows, cols : numpy.ndarray of int
        The cells either side of each interior face (rows < cols).
    transmissibility : numpy.ndarray
        Each interior face's area / distance in scaled coordinates [-].
    boundary : numpy.ndarray
        Each cell's exposed-face transmissibility [-].
    volumes : numpy.ndarray
        The cells' scaled volumes [-].
    indptr, indices : numpy.ndarray of int
        The fixed CSR pattern of the operator.
    order : numpy.ndarray of int
        Takes the values [upper, lower, diagonal] to that pattern.
    """

    rows: np.ndarray
    cols: np.ndarray
    transmissibility: np.ndarray
    boundary: np.ndarray
    volumes: np.ndarray
    indptr: np.ndarray
    indices: np.ndarray
    order: np.ndarray

    @classmethod
    def of(cls, disc) -> "Faces":
        k = disc.stiffness.tocoo()
        upper = k.row < k.col
        rows, cols, n = k.row[upper], k.col[upper], disc.volumes.size
        slots = 2 * rows.size + n
        pattern = sparse.coo_matrix(
            (np.arange(1, slots + 1, dtype=float),   # from 1: a 0 could be dropped
             (np.concatenate([rows, cols, np.arange(n)]),
              np.concatenate([cols, rows, np.arange(n)]))), (n, n)).tocsr()
        return cls(rows, cols, -k.data[upper], disc.boundary, disc.volumes, pattern.indptr,
                   pattern.indices, pattern.data.astype(np.int64) - 1)

    def operator(self, c, g, law, top, mass=0.0) -> tuple[sparse.csr_matrix, np.ndarray]:
        """(diag(mass) + K(c), b): the stiffness with face coefficients mean f(c_i..c_j)/top
        and the boundary vector of the surface value g (each exposed cell's coefficient the
        mean f(c..g)/top), so the flux into a cell is T (Phi(g) - Phi(c)) / top."""
        n = self.volumes.size
        flux = law.mean_factor(c[self.rows], c[self.cols]) / top * self.transmissibility
        edge = law.mean_factor(c, g) / top * self.boundary
        diagonal = np.bincount(self.rows, flux, n) + np.bincount(self.cols, flux, n) + edge + mass
        values = np.concatenate([-flux, -flux, diagonal])
        return (sparse.csr_matrix((values[self.order], self.indices, self.indptr), (n, n)),
                edge * g)


@dataclass(frozen=True)
class SweptMarch:
    """What every step of a swept march shares: the operator, the law, its scale, the part
    and when the sweeps stop.

    Parameters
    ----------
    faces : Faces
        The operator taken apart by face.
    law : ConcentrationDependent
        The factor f(c/Mm_ref) [-].
    top : float
        The largest f met [-], which scales the march.
    part : str
        The part's name, for errors.
    sweeps : Sweeps
        When each step's sweeps stop.
    """

    faces: Faces
    law: object
    top: float
    part: str = ""
    sweeps: Sweeps = SWEEPS


def sweep_march(shared: SweptMarch, weights, steps, initial, keep_fields=False,
                columns=()) -> History:
    """March a concentration-dependent operator, each step swept to convergence.

    Backward Euler in scaled time, each step swept to convergence (module docstring).
    The history's ``track``: the mean, the layer and the weighted sums of ``columns`` (cell
    weight vectors) at every node (``dense_output``).

    Parameters
    ----------
    shared : SweptMarch
        The operator, the law f [-], its scale top [-], the part's name and the sweeps'
        stopping rule.
    weights : Discretisation
        Its mean and layer weights.
    steps : StepPlan
        Nodes in scaled time [-], their times [s], outputs, surface moisture before each
        node [weight %].
    initial : float
        The initial moisture [weight %].
    keep_fields : bool
        Also return the cell values.
    columns : tuple of numpy.ndarray
        More cell weight vectors to track at every node.

    Returns
    -------
    History
        Mean and layer moisture [weight %] at the outputs, and the ``track``.

    Raises
    ------
    SolverError
        When a step's sweeps do not converge.
    """
    c = np.full(shared.faces.volumes.size, float(initial))
    want = {int(k) for k in steps.outputs}
    record = {0: c.copy()} if 0 in want else {}
    sums = np.column_stack([weights.mean_weights, weights.layer_weights, *columns])
    track = [c @ sums]
    dts = rounded_steps(np.diff(steps.nodes))
    solver = Lagged()
    previous = None
    for k, dt in enumerate(dts, start=1):
        g = float(steps.surface_before[k])
        guess = None if previous is None else extrapolated(previous, c, dts[k - 2], dt, g)
        previous = c
        c = sweep_step(shared, c, g, dt, k, steps.times[k], solver, guess)
        track.append(c @ sums)
        if k in want:
            record[k] = c.copy()
    states = np.array([record[int(k)] for k in steps.outputs])
    return History(mean=states @ weights.mean_weights, layer=states @ weights.layer_weights,
                   fields=states if keep_fields else None, steps=int(dts.size),
                   factorisations=solver.factorisations, track=np.array(track))


class Lagged:
    """Solve a march's SPD systems by CG on lagged LU factors.

    Solves the SPD systems (M/dt + K(c)) x = b of a march: conjugate gradients
    preconditioned by the LU factors of an earlier system (its coefficient moves little
    from sweep to sweep and step to step; a doubled dt bounds the condition number by 2),
    refactorised (SuperLU, symmetric ordering) when CG needs more than ``LAG_ITERATIONS``.
    On the 3-D meshes this replaces a factorisation per sweep by a few triangular solves.
    The CG is scipy's: written out without its per-call set-up it saved no more than the
    machine's noise (``march-cost``: 3-D 4.1-4.6 against 4.7-5.7 CPU s, sheet 1.1-1.6
    against 1.3-1.4, side by side on a loaded machine); the fixed CSR pattern of ``Faces``
    is what made the sweeps cheaper.

    Examples
    --------
    ``Lagged().solve(matrix, rhs, guess)`` factorises on its first call and preconditions
    with those factors afterwards.
    """

    def __init__(self):
        self.lu = None
        self.factorisations = 0

    def solve(self, matrix: sparse.csr_matrix, rhs: np.ndarray, guess: np.ndarray,
              rtol: float = LINEAR_TOLERANCE) -> np.ndarray:
        if self.lu is not None:
            preconditioner = splinalg.LinearOperator(matrix.shape, self.lu.solve)
            x, info = splinalg.cg(matrix, rhs, x0=guess, rtol=rtol, atol=0.0,
                                  M=preconditioner, maxiter=LAG_ITERATIONS)
            if info == 0:
                return x
        self.lu = splinalg.splu(matrix.tocsc(), permc_spec=ORDERING, diag_pivot_thresh=0.0,
                                options={"SymmetricMode": True})
        self.factorisations += 1
        return self.lu.solve(rhs)


def extrapolated(before, latest, dt_before, dt, g) -> np.ndarray:
    """The first iterate of a step: the last two states extrapolated in time.

    The first iterate of a step: the last two states extrapolated linearly in time
    (the step's explicit predictor), held within the range of the latest state and the
    surface value (the backward-Euler step keeps it: a discrete maximum principle). Only
    where the sweeps start: their converged state does not depend on it.

    Parameters
    ----------
    before, latest : numpy.ndarray
        The states [weight %] at the two last nodes.
    dt_before : float
        The previous step [-] (scaled time).
    dt : float
        This step [-] (scaled time).
    g : float
        The surface moisture [weight %] over the step.

    Returns
    -------
    numpy.ndarray
        The first iterate [weight %].
    """
    guess = latest + (dt / dt_before) * (latest - before)
    return np.clip(guess, min(float(latest.min()), g), max(float(latest.max()), g))


def sweep_step(shared: SweptMarch, old, g, dt, index, time, solver=None,
               guess=None) -> np.ndarray:
    """One backward-Euler step of the nonlinear operator, by Picard sweeps.

    Picard sweeps (M/dt + K(c)) c_new = M old/dt + f(g) with K from the latest iterate
    (the first: ``guess``, else ``old``), until the residual of the new iterate in its own
    operator (the next sweep's) is below ``shared.sweeps.tolerance`` of the right side;
    SolverError if ``shared.sweeps.most`` do not get there. Each sweep's linear system is
    solved only to ``shared.sweeps.forcing`` x the residual of the iterate it starts from (inexact Picard: the forcing
    terms of inexact Newton, Eisenstat & Walker 1996, SIAM J. Sci. Comput. 17:16-32): an
    early sweep's system is itself off by that residual, and the stopping test is on the
    nonlinear residual, so the converged step is unchanged.

    Parameters
    ----------
    shared : SweptMarch
        The operator, the law f [-], its scale top [-], the part's name and the sweeps'
        stopping rule.
    old : numpy.ndarray
        The state at the step's start [weight %].
    g : float
        The surface moisture [weight %] at the step's end.
    dt : float
        The step [-] (scaled time).
    index : int
        The step's number, for errors.
    time : float
        The step's end [s], for errors.
    solver : Lagged, optional
        The lagged solver to reuse (None: a fresh one).
    guess : numpy.ndarray, optional
        The first iterate [weight %] (None: ``old``).

    Returns
    -------
    numpy.ndarray
        The state at the step's end [weight %].

    Raises
    ------
    SolverError
        When ``shared.sweeps.most`` sweeps do not reach ``shared.sweeps.tolerance``.

    References
    ----------
    Eisenstat, S. C. & Walker, H. F. (1996). Choosing the forcing terms in an inexact Newton
    method. SIAM Journal on Scientific Computing 17(1):16-32. doi:10.1137/0917003
    """
    faces, law, top, sweeps = shared.faces, shared.law, shared.top, shared.sweeps
    solver = solver or Lagged()
    mass = faces.volumes / dt
    c = old if guess is None else guess
    system, f = faces.operator(c, g, law, top, mass)
    scale = max(norm(mass * old + f), 1e-300)
    residual = norm(system @ c - mass * old - f) / scale
    for _ in range(sweeps.most):
        c = solver.solve(system, mass * old + f, c,
                         max(LINEAR_TOLERANCE, sweeps.forcing * residual))
        system, f = faces.operator(c, g, law, top, mass)
        residual = norm(system @ c - mass * old - f) / max(norm(mass * old + f), 1e-300)
        if not np.isfinite(residual):
            break
        if residual <= sweeps.tolerance:
            return c
    raise SolverError(shared.part, index, time, f"concentration-dependent sweeps did not converge: "
                      f"residual {residual:.2e} after {sweeps.most} sweeps")
