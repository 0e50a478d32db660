"""The modes of a CamPlate or LinkBar: the planform's spectrum, seen by the mean and the
contact layer, times the exact through-thickness sheet modes, for the two-phase march
(``two_phase_modes``) where the plane model's superposed step responses do not apply.

The part is a prism (planform x thickness), so in the scaled coordinates of
``discretisation`` its Laplacian separates (Crank 1975 §5.3; Carslaw & Jaeger 1959
§1.16): modes psi_i(x, y) sin(k pi z/h), rates mu_i + (k pi)^2. The planform operator is
FiPy's two-point-flux operator K_p on the Delaunay-admissible cells of ``admissible``
(``prisms.planar``: the cells' sides as faces, their circumcentres as cell points; the
in-plane part of a prism layer's operator to 1e-13, for a third of its cost). With
M = diag(volumes) and S = M^-1/2 K_p M^-1/2 (symmetric positive definite), the mean and
the layer are linear functionals w^T u of the cell values (weights corrected for where
each cell value sits, ``cell_moments``: second order where the plain volume weights are
first order on graded cells), so any function of the planform decay they see,
sum_i A_i f(mu_i) = w^T M^-1/2 f(S) v with v = M^1/2 1, is a bilinear form over S's
spectrum. m steps of Lanczos started at v give its m-point quadrature: Ritz values
theta_j as rates, the first components of T's eigenvectors times w's projections as
amplitudes, exact for polynomials in S^-1 of degree < m (Golub & Meurant 2010,
"Matrices, Moments and Quadrature with Applications", §§6.2, 7.1). The
Lanczos runs on S^-1 (shift-and-invert at 0, one sparse LU): exp(-mu t) is smooth in
1/mu, so the quadrature converges at a rate set by the outputs' ages, not by the mesh's
stiffest mode (van den Eshof & Hochbruck 2006, SIAM J. Sci. Comput. 27:1438, §3; Moret &
Novati 2004, BIT 44:595). Full reorthogonalisation keeps the layer's bilinear form
accurate. m doubles until the unit-step response at the ages read changes by less than
``LANCZOS_SHARE`` of the tolerance (``lanczos_count``).

The mesh is refined a posteriori (``refined_planform``): second order in the finest
width w0 and growth g together (``sizing``: error (w0/sqrt(t) + c g)^2), so the two-phase
histories on two meshes w0 and w0/r estimate the finer one's error as their difference /
(r^2 - 1) (Richardson), and the next r follows from that estimate, until the planform's
share of the accuracy is met or ``PLANFORM_CAP`` cells are reached. (The Fickian step
response alone would not do: bound water lives on the slowest modes long after their
free water has settled, so an error of the slowest planform rates shows late.) Where the
estimate predicts that even the cap's r cannot meet the share, w0 and g are refined apart
(``_separately``): the error is alpha w0^2 + beta g^2 per compared value, each term from
its own Richardson difference (a mesh with w0 / 2 alone, one with g / 2 alone), and the
next mesh is the one of the fewest cells predicted to meet the share: on the demo cam
through its daily record the contact layer's error is mostly w0's, the mean's both
(opposite signs), and refining them together spent the cap on a finer g than either
needed (README, "Non-Fickian sorption").

References
----------
- Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
- Carslaw, H. S. & Jaeger, J. C. (1959). Conduction of Heat in Solids, 2nd ed. Oxford:
  Clarendon Press.
- Golub, G. H. & Meurant, G. (2010). Matrices, Moments and Quadrature with Applications.
  Princeton University Press.
- van den Eshof, J. & Hochbruck, M. (2006). Preconditioning Lanczos approximations to the
  matrix exponential. SIAM Journal on Scientific Computing 27(4):1438-1457.
  doi:10.1137/040605461
- Moret, I. & Novati, P. (2004). RD-rational approximations of the matrix exponential. BIT
  Numerical Mathematics 44(3):595-615. doi:10.1023/B:BITN.0000046805.27551.3b
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np
from scipy import sparse
from scipy.linalg import eigh_tridiagonal
from scipy.sparse.linalg import splu

from ...errors import InputError
from ..accuracy.budget import LANCZOS_SHARE, LAYER_TOLERANCE, REFINEMENT_SAFETY
from ..accuracy.error_model import space_error
from ..exact.modes import Modes, sheet_factor
from ..exact.series import sheet_uptake
from ..operators import sizing
from ..operators.prisms import planar
from ..planform.cell_moments import corrected_weights
from ..problem.cache import RunCache, run_cache
from ..problem.scaling import axis_scale, stretch_of
from ..stepping.march import ORDERING
from .two_phase_modes import ModeSource

log = logging.getLogger(__name__)

FIRST_CAP = 2500      # cells of the first planform mesh (the plan's a-priori sizing)
PLANFORM_CAP = 60_000  # the finest planform mesh refined to, cells
FIRST_LANCZOS = 32    # Lanczos steps to start with (doubled while the response moves)
MAX_LANCZOS = 512     # steps at most: Q holds 512 x cells doubles (250 MB at the cap)
MAX_REFINE = 4.0      # refine w0 by at most this factor per level (the estimate's reach)
MIN_REFINE = 1.5      # ... and at least this (a smaller step's Richardson difference, / (r^2 - 1),
#                       magnifies what is not yet asymptotic, and costs a level)
SPLIT_REACH = 6.0     # w0 and g apart (``_target``): each within this factor of the last mesh
SPLIT_GRID = 49       # ... searched on this many ratios each (geometric)


def first_planform_mesh(geometry, d, accuracy: float, t_lo: float) -> sizing.Layout:
    """The first planform mesh of the two-phase modal solve.

    The first mesh: graded planform rows (w0, g) from the error model, shrunk under
    ``FIRST_CAP`` cells (``refined_planform`` refines it from the measured error).

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The cam plate or link to mesh (sizes [m]).
    d : tuple of float
        Its diffusivities along x, y, z [m^2/s].
    accuracy : float
        The requested error relative to the swing [-].
    t_lo : float
        The earliest output after a change, scaled time [-].

    Returns
    -------
    Layout
        The graded rows (finest width w0 [-], growth g [-]) of the first mesh.
    """
    stretch = stretch_of(d)
    return sizing.graded((1.0, 1.0), ("both", "both"), accuracy, t_lo, FIRST_CAP,
                         space_error(t_lo), lambda w0, g: (
                             sizing.estimated_prism_cells(geometry, w0, g, stretch)[0],))


@dataclass(frozen=True, eq=False)
class Planform:
    """The symmetrised planform operator and its mean and layer vectors.

    S = M^-1/2 K_p M^-1/2 (rescaled 1/s) and the vectors of the mean (v = M^1/2 1 / V)
    and the layer (the band's M^1/2 share / V_band) against M^1/2 1.

    Parameters
    ----------
    operator : scipy.sparse.csc_matrix
        S = M^-1/2 K_p M^-1/2 [1/s] (per rescaled second).
    start : numpy.ndarray
        M^1/2 1, the Lanczos start vector [-].
    mean : numpy.ndarray
        The mean's vector against M^1/2 1 [-].
    layer : numpy.ndarray
        The layer's vector against M^1/2 1 [-].
    cells : int
        The planform's cells.
    cache : RunCache
        The run's cache (its LU, its Lanczos recurrence).
    """

    operator: sparse.csc_matrix
    start: np.ndarray
    mean: np.ndarray
    layer: np.ndarray
    cells: int
    cache: RunCache = field(default_factory=RunCache, repr=False)  # the run's: its LU, Lanczos


def planform_operator(geometry, d, depth: float, finest: float, growth: float,
                      cache: RunCache | None = None) -> Planform:
    """The planform's symmetrised FiPy operator on graded admissible cells.

    The planform's FiPy operator (module docstring) on the graded admissible cells, made
    once per run (``cache``; None: a fresh one).

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The prism part (lengths [m]).
    d : tuple of float
        The principal diffusivities (D_x, D_y, D_z) [m^2/s].
    depth : float
        The contact layer's depth [m].
    finest : float
        The finest cell width w0 [-] (scaled).
    growth : float
        The cells' growth rate g [-].
    cache : RunCache, optional
        The run's cache (None: a fresh one).

    Returns
    -------
    Planform
        The operator [1/s] and its vectors.
    """
    cache = run_cache(cache)

    def build():
        tess = sizing.planform_cells(geometry, finest, growth, stretch_of(d), cache)
        coordinates = axis_scale(geometry.thickness, d[1], d[2]) / float(tess.stretch[1])
        disc = planar(tess, coordinates, np.ones(tess.cells))  # (plain band weights unused)
        root = np.sqrt(disc.volumes)
        inverse = sparse.diags(1.0 / root)
        scale = d[2] / geometry.thickness ** 2   # scaled -> rescaled time
        operator = scale * (inverse @ disc.stiffness @ inverse)
        mean, layer = corrected_weights(tess, depth)
        return Planform(operator.tocsc(), root, mean / root, layer / root, tess.cells, cache)
    return cache.get(("planform operator", geometry, d, depth, finest, growth), build)


def _factor(planform: Planform):
    """Sparse LU of the symmetric positive definite S: symmetric ordering, diagonal pivots
    (as ``march``), once per planform in the run's cache."""
    return planform.cache.get(("planform LU",), lambda: splu(
        planform.operator, permc_spec=ORDERING, diag_pivot_thresh=0.0,
        options={"SymmetricMode": True}), owner=planform)


class _Recurrence:
    """The shift-and-invert Lanczos recurrence of one planform from M^1/2 1, with full
    reorthogonalisation, run further on demand: m steps are the leading m rows of any longer
    run (step j uses only the rows before it), so doubling the steps (``lanczos_count``)
    continues the run instead of starting again."""

    def __init__(self, planform: Planform):
        self.planform = planform
        self.norm = float(np.linalg.norm(planform.start))
        self.basis = np.zeros((FIRST_LANCZOS, planform.cells))
        self.basis[0] = planform.start / self.norm
        self.alpha, self.beta = [], []
        self.count = planform.cells       # steps at most (fewer at an invariant subspace)

    def run(self, steps: int) -> int:
        """Steps taken so far, at least min(``steps``, ``count``)."""
        inverse = _factor(self.planform)
        while len(self.alpha) < min(steps, self.count):
            j = len(self.alpha)
            w = inverse.solve(self.basis[j])
            self.alpha.append(float(self.basis[j] @ w))
            done = self.basis[:j + 1]
            w -= done.T @ (done @ w)       # full reorthogonalisation, twice
            w -= done.T @ (done @ w)
            self.beta.append(float(np.linalg.norm(w)))
            if self.beta[j] <= 1e-14 * abs(self.alpha[j]):   # invariant subspace: exact
                self.count = j + 1
            elif j + 1 < self.count:
                if j + 1 == len(self.basis):
                    self.basis = np.vstack([self.basis, np.zeros_like(self.basis)])
                self.basis[j + 1] = w / self.beta[j]
        return min(len(self.alpha), max(steps, 1))


def lanczos_spectrum(planform: Planform, steps: int):
    """The Gauss quadrature of the planform's decay from the Lanczos recurrence.

    (rates, mean amplitudes, layer amplitudes): the ``steps``-point Gauss quadrature of
    the planform's decay (module docstring), from the first ``steps`` rows of the Lanczos
    recurrence (``_Recurrence``, one per planform in the run's cache, run further on
    demand). Read-only arrays (kept in the run's cache).

    Parameters
    ----------
    planform : Planform
        The planform operator.
    steps : int
        Lanczos steps, the quadrature's points.

    Returns
    -------
    rates : numpy.ndarray
        The quadrature's decay rates [1/s] (per rescaled second).
    mean, layer : numpy.ndarray
        Their amplitudes in the mean and in the layer [-].
    """
    def build():
        recurrence = planform.cache.get(("lanczos recurrence",), lambda: _Recurrence(planform),
                                        owner=planform)
        taken = recurrence.run(steps)
        alpha, beta = np.array(recurrence.alpha[:taken]), np.array(recurrence.beta[:taken - 1])
        theta, vectors = eigh_tridiagonal(alpha, beta)
        first = recurrence.norm * vectors[0]
        basis = recurrence.basis[:taken]
        return (1.0 / theta, (planform.mean @ basis.T @ vectors) * first,
                (planform.layer @ basis.T @ vectors) * first)
    return planform.cache.get(("lanczos spectrum", steps), build, owner=planform)


def planar_fraction(spectrum, ages) -> np.ndarray:
    """The planform's unsaturated mean and layer fractions after a unit step.

    (ages, 2): the planform's unsaturated mean and layer fractions of a unit step.

    Parameters
    ----------
    spectrum : tuple of numpy.ndarray
        (rates [1/s], mean amplitudes [-], layer amplitudes [-]).
    ages : numpy.ndarray
        Rescaled ages since the step [s].

    Returns
    -------
    numpy.ndarray
        The unsaturated mean and layer fractions [-], shape (ages, 2).
    """
    rates, mean, layer = spectrum
    return np.exp(-np.outer(np.asarray(ages, float), rates)) @ np.stack([mean, layer], axis=1)


def lanczos_count(planform: Planform, ages, tolerance: float) -> tuple[int, float]:
    """How many Lanczos steps the quadrature of the unit-step response needs.

    Lanczos steps whose quadrature of the unit-step response at ``ages`` moves by less
    than ``LANCZOS_SHARE`` x ``tolerance`` when halved, and that change (the mean's; the
    layer's / ``LAYER_TOLERANCE``).

    Parameters
    ----------
    planform : Planform
        The planform operator.
    ages : numpy.ndarray
        Rescaled ages [s] at which the response is compared.
    tolerance : float
        The error allowed [-], relative to the swing.

    Returns
    -------
    steps : int
        The Lanczos steps.
    change : float
        The change when halved [-].
    """
    steps = FIRST_LANCZOS
    previous = planar_fraction(lanczos_spectrum(planform, steps), ages)
    while True:
        steps *= 2
        current = planar_fraction(lanczos_spectrum(planform, steps), ages)
        difference = np.abs(current - previous)
        change = float(max(np.max(difference[:, 0], initial=0.0),
                           np.max(difference[:, 1], initial=0.0) / LAYER_TOLERANCE))
        if change <= LANCZOS_SHARE * tolerance or steps >= min(MAX_LANCZOS, planform.cells):
            return steps, change
        previous = current


def whole_at_start(spectrum):
    """The quadrature with its mean and layer amplitudes summing to 1.

    The quadrature with the amplitudes of the mean and of the layer summing to 1 (the
    part starts whole at its initial value): the corrected means (``cell_moments``) sum to
    1 - sum grad u . (c - x) of a unit field that steps to 0 at the surface, the share of
    the edge cells between their circumcentres and the surface, which settles within the
    finest cells' time w0^2/D; it is given to the fastest quadrature node.

    Parameters
    ----------
    spectrum : tuple of numpy.ndarray
        (rates [1/s], mean amplitudes [-], layer amplitudes [-]).

    Returns
    -------
    tuple of numpy.ndarray
        The same rates [1/s]; amplitudes [-] that sum to 1.
    """
    rates, mean, layer = (np.array(a) for a in spectrum)
    fastest = np.argmax(rates)
    mean[fastest] += 1.0 - mean.sum()
    layer[fastest] += 1.0 - layer.sum()
    return rates, mean, layer


def planform_source(geometry, d, spectrum) -> ModeSource:
    """The mode source of a prism part: planform quadrature times sheet modes.

    The product modes (planform quadrature x ``count`` sheet modes) and the unit-step
    response of the same planform quadrature times Crank's sheet (eq. 4.18).

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The prism part; its ``thickness`` [m] is the sheet's.
    d : tuple of float
        The principal diffusivities (D_x, D_y, D_z) [m^2/s].
    spectrum : tuple of numpy.ndarray
        The planform quadrature: (rates [1/s], mean [-], layer [-]).

    Returns
    -------
    ModeSource
        The product modes and the exact unit-step response.

    References
    ----------
    Crank, J. (1975). The Mathematics of Diffusion, 2nd ed. Oxford: Clarendon Press.
    """
    spectrum = whole_at_start(spectrum)
    rates, mean, layer = spectrum

    def modes(counts) -> Modes:
        sheet = sheet_factor(geometry.thickness, d[2], 0.0, counts[0])
        return Modes((rates[:, None] + sheet.rates[None, :]).ravel(),
                     (mean[:, None] * sheet.mean[None, :]).ravel(),
                     (layer[:, None] * sheet.mean[None, :]).ravel(), float(sheet.rates[-1]))

    def response(age):
        age = np.asarray(age, float)
        planar = planar_fraction(spectrum, age)
        through = (1.0 - sheet_uptake(d[2] * age / geometry.thickness ** 2))[:, None]
        return tuple((1.0 - planar * through).T)

    return ModeSource(modes, response, 1, rates.size)


@dataclass(frozen=True)
class RefinedPlanform:
    """The finest planform a refinement used, and what it measured.

    The finest planform used: the estimated error of its mesh and quadrature (fraction
    of the swing), cells, Lanczos steps, meshes built, what ``measure`` gave on it, and its
    finest width and growth (scaled).

    Parameters
    ----------
    error : float
        The estimated error of its mesh and quadrature [-], relative to the swing.
    cells : int
        Its cells.
    steps : int
        Its Lanczos steps.
    levels : int
        The meshes built.
    result : object
        What ``measure`` gave on it.
    finest : float
        Its finest cell width w0 [-] (scaled).
    growth : float
        Its growth rate g [-].
    """

    error: float
    cells: int
    steps: int
    levels: int
    result: object
    finest: float
    growth: float


@dataclass(frozen=True)
class PlanformMeasure:
    """What a planform refinement measures on each of its meshes.

    Parameters
    ----------
    geometry : CamPlate or LinkBar
        The cam plate or link whose planform is refined (sizes [m]).
    d : tuple of float
        D along x, y and through the thickness [m^2/s].
    depth : float
        Depth of the contact layer read [m].
    ages : numpy.ndarray
        Rescaled ages [s] at which the quadrature is checked.
    tolerance : float
        The error allowed [-], relative to the swing.
    measure : callable
        source -> (compared values [-], payload).
    """

    geometry: object
    d: tuple
    depth: float
    ages: np.ndarray
    tolerance: float
    measure: Callable


def _level(task: PlanformMeasure, finest, growth, cache: RunCache):
    """(compared values, payload, cells, steps, quadrature change) of ``task.measure`` on the
    product modes of the mesh (finest, growth); ``cache``: the run's."""
    geometry, d = task.geometry, task.d
    planform = planform_operator(geometry, d, task.depth, finest, growth, cache)
    steps, change = lanczos_count(planform, task.ages, task.tolerance)
    values, payload = task.measure(planform_source(geometry, d,
                                                   lanczos_spectrum(planform, steps)))
    return np.asarray(values, float), payload, planform.cells, steps, change


@dataclass(frozen=True)
class Refinement:
    """How ``refined_planform`` refines.

    How ``refined_planform`` refines: up to ``cap`` cells, w0 and g ``apart`` where
    together cannot meet the tolerance under the cap, each mesh measured by ``level``
    (``(task, finest, growth, cache)`` -> (compared values, payload, cells, steps, quadrature
    change), ``task`` a ``PlanformMeasure``). The defaults are the run's; tests pass
    others (a smaller cap, a modelled level) instead of changing the module.

    Parameters
    ----------
    cap : int
        The largest mesh [cells].
    apart : bool
        Refine w0 and g apart where together cannot meet the tolerance.
    level : callable
        Measures one mesh.
    """

    cap: int = PLANFORM_CAP
    apart: bool = True
    level: Callable = _level


REFINEMENT = Refinement()


def refined_planform(task: PlanformMeasure, finest: float, growth: float,
                     refinement: Refinement = REFINEMENT,
                     cache: RunCache | None = None) -> RefinedPlanform:
    """Refine the planform mesh until the Richardson estimate meets the tolerance.

    Refine the first mesh (``first_planform_mesh``) by r = w0 / w0' (finest width and growth
    together) until the Richardson estimate |y' - y| / (r^2 - 1) of what ``measure(source)``
    compares (its first return: the two-phase history relative to the swing, the layer's
    / ``LAYER_TOLERANCE``; the second is kept), plus the quadrature's change at ``ages``
    (rescaled s), is at most ``tolerance``; r = 2 first, then from the estimate. Where even
    the cap's r would leave the estimate above the tolerance, w0 and g are refined apart
    (``_separately``); if that ends above the tolerance too (the prediction at the cap is
    only as good as the coarse meshes' estimate), together on, and the lower estimate is
    kept. The error is infinite if the mesh cannot be refined. ``cache``: the run's (None: a
    fresh one), which keeps each mesh's operator for the solve.

    Parameters
    ----------
    task : PlanformMeasure
        The part (sizes [m]), D per axis [m^2/s], the contact layer's depth [m], the
        rescaled ages [s] at which the quadrature is checked, the error allowed [-]
        relative to the swing and the ``measure``, source -> (compared values [-], payload).
    finest : float
        The first mesh's finest width w0 [-] (scaled).
    growth : float
        Its growth rate g [-].
    refinement : Refinement
        How to refine.
    cache : RunCache, optional
        The run's cache (None: a fresh one).

    Returns
    -------
    RefinedPlanform
        The finest planform used and its error estimate [-] (infinite if the mesh cannot be
        refined).
    """
    cache = run_cache(cache)
    ages = np.asarray(task.ages, float)
    task = replace(task, ages=ages[ages > 0])
    tolerance = task.tolerance
    coarse = refinement.level(task, finest, growth, cache)
    ratio, levels, apart = 2.0, 1, None
    while True:
        try:
            fine = refinement.level(task, finest / ratio, growth / ratio, cache)
        except InputError:
            break
        levels += 1
        finest, growth = finest / ratio, growth / ratio
        mesh = float(np.max(np.abs(fine[0] - coarse[0]), initial=0.0)) / (ratio ** 2 - 1.0)
        error = mesh + fine[4]
        if error <= tolerance or fine[2] * 2 > refinement.cap:
            return _lower(RefinedPlanform(error, fine[2], fine[3], levels, fine[1], finest,
                                          growth), apart)
        reach = np.sqrt(refinement.cap / fine[2])
        log.debug("planform w0 %.3g g %.3g: %d cells, estimate %.2e; at the cap together %.2e",
                  finest, growth, fine[2], error, mesh / reach ** 2 + fine[4])
        if refinement.apart and apart is None and mesh / reach ** 2 > tolerance - fine[4]:
            apart = _separately(task, (finest, growth, fine), levels, refinement, cache)
            if apart is not None and apart.error <= tolerance:
                return apart
            levels = levels if apart is None else apart.levels
        ratio = float(np.clip(REFINEMENT_SAFETY
                              * np.sqrt(mesh / max(tolerance - fine[4], 0.5 * tolerance)),
                              MIN_REFINE, min(MAX_REFINE, reach)))
        coarse = fine
    return _lower(RefinedPlanform(float("inf"), coarse[2], coarse[3], levels, coarse[1], finest,
                                  growth), apart)


def _lower(together: RefinedPlanform, apart) -> RefinedPlanform:
    """Of the refinement together and the one apart (None if not tried), the one of the
    lower estimate, with the meshes of both counted."""
    if apart is None or together.error <= apart.error:
        return together
    return replace(apart, levels=together.levels)


def error_coefficients(meshes) -> np.ndarray:
    """The error coefficients of y = y* + alpha w0^2 + beta g^2 through the meshes.

    (2, compared values): the error coefficients (alpha, beta) of y = y* + alpha w0^2 +
    beta g^2 through the ``meshes`` (finest, growth, ``_level``; three or more, not on one
    line in (w0^2, g^2)), each compared value on its own: Richardson extrapolation in two
    step sizes, exact through three meshes (where two differ from the third in w0 or g
    alone, each term is its own one-parameter Richardson difference), least squares through
    more (Eca & Hoekstra 2014, J. Comput. Phys. 262:104, §3: more grids than unknowns).

    Parameters
    ----------
    meshes : sequence of tuple
        (finest w0 [-], growth g [-], ``_level``'s result) per mesh.

    Returns
    -------
    numpy.ndarray
        (alpha, beta) per compared value, shape (2, values), in the values' unit.

    References
    ----------
    Eca, L. & Hoekstra, M. (2014). A procedure for the estimation of the numerical
    uncertainty of CFD calculations based on grid refinement studies. Journal of
    Computational Physics 262:104-130. doi:10.1016/j.jcp.2014.01.006
    """
    steps = np.array([[1.0, w ** 2, g ** 2] for w, g, _ in meshes])
    values = np.stack([level[0].ravel() for _, _, level in meshes])
    return np.linalg.lstsq(steps, values, rcond=None)[0][1:]


def mesh_error(parts, finest: float, growth: float) -> float:
    """The predicted mesh error of a (finest, growth) mesh.

    The mesh error of (finest, growth): the w0 and g terms' magnitudes added, the
    largest over the compared values (their signs are not trusted to cancel).

    Parameters
    ----------
    parts : numpy.ndarray
        (alpha, beta) per compared value (``error_coefficients``).
    finest : float
        The finest width w0 [-] (scaled).
    growth : float
        The growth rate g [-].

    Returns
    -------
    float
        The predicted mesh error [-], relative to the swing.
    """
    return float(np.max(np.abs(parts[0]) * finest ** 2 + np.abs(parts[1]) * growth ** 2,
                        initial=0.0))


def _target(geometry, d, parts, meshes, budget: float, cap: int):
    """(finest, growth), within ``SPLIT_REACH`` of the last of ``meshes``, of the fewest
    cells whose predicted mesh error (``mesh_error``) is ``budget`` /
    ``REFINEMENT_SAFETY``^2, under
    ``cap``, else of the least error under it. The cells: the cap's cheap count
    (``sizing.estimated_prism_cells``) times the largest ratio of the cells built to it
    so far (it misses by up to 20 % as w0 and g part)."""
    stretch = stretch_of(d)
    finest, growth, _ = meshes[-1]
    ratio = max(level[2] / sizing.estimated_prism_cells(geometry, w, g, stretch)[0]
                for w, g, level in meshes)
    best = None
    for w in finest * np.geomspace(1.0 / SPLIT_REACH, SPLIT_REACH, SPLIT_GRID):
        for g in growth * np.geomspace(1.0 / SPLIT_REACH, SPLIT_REACH, SPLIT_GRID):
            if g > sizing.MAX_GROWTH:
                continue
            count = ratio * sizing.estimated_prism_cells(geometry, w, g, stretch)[0]
            if count > cap:
                continue
            error = mesh_error(parts, w, g)
            # met: fewest cells; else: least error
            key = (max(error * REFINEMENT_SAFETY ** 2, budget), count)
            if best is None or key < best[0]:
                best = (key, float(w), float(g))
    return None if best is None else best[1:]


def _separately(task: PlanformMeasure, start, levels, refinement, cache: RunCache):
    """Refine w0 and g apart from the mesh ``start`` (finest, growth, ``_level``): one mesh
    with w0 / 2 alone and one with g / 2 alone give each term's own Richardson difference
    (``error_coefficients``); the mesh of the fewest cells predicted to meet the tolerance follows
    (``_target``), its estimate from all the meshes apart (least squares), and so on while
    the last mesh is under half the cap. The cheapest mesh whose estimate meets the
    tolerance is kept, else the last. None if a probe mesh cannot be built."""
    geometry, d, tolerance = task.geometry, task.d, task.tolerance
    finest, growth, _ = start
    meshes = [start]
    try:
        for w, g in ((finest / 2.0, growth), (finest, growth / 2.0)):
            meshes.append((w, g, refinement.level(task, w, g, cache)))
    except InputError:
        return None
    levels += 2
    while True:
        parts = error_coefficients(meshes)
        met = [(mesh[2][2], mesh_error(parts, mesh[0], mesh[1]) + mesh[2][4], mesh)
               for mesh in meshes]
        cheapest = min((m for m in met if m[1] <= tolerance), default=None, key=lambda m: m[0])
        last = met[-1]
        log.debug("planform w0 %.3g g %.3g apart: %d cells, estimate %.2e", meshes[-1][0],
                  meshes[-1][1], last[0], last[1])
        if cheapest is not None or last[0] * 2 > refinement.cap:
            cells, error, (w, g, level) = cheapest or last
            return RefinedPlanform(error, cells, level[3], levels, level[1], w, g)
        w, g, level = meshes[-1]
        target = _target(geometry, d, parts, meshes, tolerance - level[4], refinement.cap)
        if target is None or np.allclose(target, (w, g), rtol=1e-3):
            return RefinedPlanform(last[1], last[0], level[3], levels, level[1], w, g)
        try:
            meshes.append((*target, refinement.level(task, *target, cache)))
        except InputError:
            return RefinedPlanform(last[1], last[0], level[3], levels, level[1], w, g)
        levels += 1
