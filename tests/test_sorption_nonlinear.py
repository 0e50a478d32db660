"""Concentration-dependent diffusion (D = D(T) exp(k c/Mm), Crank 1975 ch. 9) against an
independent fine method of lines (scipy solve_ivp), FiPy's own sweeps and Fick (k = 0)."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.sparse import diags

from fickcam.diffusion import SolverSettings, solve
from fickcam.diffusion.models.finite_volume import discretise
from fickcam.diffusion.nonfickian import concentration_dependent
from fickcam.diffusion.problem.exposure import Diffusivity, Exposure
from fickcam.diffusion.problem.geometry import Disc, Sheet
from fickcam.diffusion.problem.sorption import ConcentrationDependent
from fickcam.errors import SolverError

H, D, MM = 2e-3, 5e-12, 2.0
ISOTROPIC = Diffusivity((D, D, D), 0.0)
TIMES = np.array([0.01, 0.03, 0.1, 0.3]) * H ** 2 / D


def method_of_lines(k, start, surface, nodes=400):
    """dc/dt* = d/dz (exp(k c/Mm) dc/dz) on z/h in [0, 1], second-order conservative
    differences (face D at the mean of its cells), BDF at tight tolerances."""
    dz = 1.0 / nodes

    def rhs(_, c):
        full = np.concatenate([[surface], c, [surface]])
        flux = np.exp(k * 0.5 * (full[1:] + full[:-1]) / MM) * np.diff(full) / dz
        return np.diff(flux) / dz

    solution = solve_ivp(rhs, (0.0, TIMES[-1] * D / H ** 2), np.full(nodes - 1, start),
                         t_eval=TIMES * D / H ** 2, method="BDF", rtol=1e-9, atol=1e-11,
                         jac_sparsity=diags([1.0, 1.0, 1.0], [-1, 0, 1], shape=(nodes - 1, nodes - 1)))
    full = np.vstack([np.full(TIMES.size, surface), solution.y, np.full(TIMES.size, surface)])
    return np.trapezoid(full, dx=dz, axis=0)


def exposure(start, surface):
    return Exposure.piecewise([0.0, TIMES[-1]], [330.0], [surface], initial_moisture=start)


@pytest.mark.slow
@pytest.mark.parametrize("k, accuracy, start, surface", [
    (2.0, 1e-2, 0.0, MM), (2.0, 1e-2, MM, 0.0), (5.0, 1e-3, MM, 0.0)])
def test_exponential_diffusivity_matches_a_fine_method_of_lines(k, accuracy, start, surface):
    """Absorption and desorption (the dry skin, ``concentration_dependent.dries_to_a_skin``, the
    case
    that sizes the cells at the smallest D): within the accuracy and within the estimate.
    Measured: k = 2 at 1e-2: 2.7e-3 (estimate 5.3e-3) absorbing, 5.1e-4 (5.7e-3)
    desorbing; k = 5 desorbing at 1e-3: 9.9e-5 (8.6e-4) (with f(surface value) on the
    exposed faces, before the Kirchhoff mean: 3.7e-3, 5.3e-3, 4.5e-4). With SKIN_CELLS_MARGIN = 1
    the skin cells keep a safety of 3 (1.4e-3 at k = 2, 1e-2 drying); with none (0) that
    case erred 3.8e-3 and fails the bound below."""
    law = ConcentrationDependent(MM, exponent=k)
    result = solve(Sheet(H), ISOTROPIC, exposure(start, surface), TIMES, accuracy=accuracy,
                   sorption=law)
    reference = method_of_lines(k, start, surface, nodes=800 if k > 2 else 400)
    error = np.max(np.abs(result.mean - reference)) / MM
    assert error <= result.error_estimate <= accuracy
    assert error <= accuracy / 3.0  # the planning safety (nonlinear_plan)


@pytest.mark.slow
def test_absorption_is_faster_than_desorption_when_d_rises_with_moisture():
    """Crank 1975 §9.3 (Fig. 9.4): with D increasing with c, sorption runs ahead of
    desorption at every time; the reverse for D falling with c."""
    for k, faster in ((2.0, "absorption"), (-2.0, "desorption")):
        law = ConcentrationDependent(MM, exponent=k)
        up = solve(Sheet(H), ISOTROPIC, exposure(0.0, MM), TIMES, accuracy=1e-2, sorption=law)
        down = solve(Sheet(H), ISOTROPIC, exposure(MM, 0.0), TIMES, accuracy=1e-2, sorption=law)
        absorbed, desorbed = up.mean / MM, 1.0 - down.mean / MM
        gap = absorbed - desorbed if faster == "absorption" else desorbed - absorbed
        assert np.all(gap[:3] > 0.02)


def test_zero_exponent_is_fickian():
    law = ConcentrationDependent(MM, exponent=0.0)
    disc = Disc(0.006, H)
    result = solve(disc, ISOTROPIC, exposure(0.0, MM), TIMES, accuracy=1e-2, sorption=law)
    fick = solve(disc, ISOTROPIC, exposure(0.0, MM), TIMES, accuracy=1e-6)
    assert result.model == "axisymmetric"
    assert np.max(np.abs(result.mean - fick.mean)) / MM < 1e-2


@pytest.mark.parametrize("law", [
    ConcentrationDependent(MM, exponent=3.0), ConcentrationDependent(MM, exponent=-2.0),
    ConcentrationDependent(MM, ratios=(0.1, 0.5, 1.0), factors=(1.0, 2.0, 6.0))],
    ids=["exp(3c)", "exp(-2c)", "table"])
def test_face_coefficient_is_the_mean_of_f_between_the_two_sides(law):
    """``mean_factor`` against scipy's adaptive quadrature of f over [low, high] / width
    (the table held beyond its ends; either order; a zero-width interval is f there)."""
    from scipy.integrate import quad

    pairs = [(0.0, MM), (MM, 0.0), (0.3, 1.7), (-0.1, 2.5), (0.05, 0.15), (1.0, 1.0 + 1e-9)]
    for low, high in pairs:
        exact = quad(law.factor, low, high, points=[0.2, 1.0, 2.0], epsabs=1e-13)[0]
        assert law.mean_factor(low, high) == pytest.approx(exact / (high - low), rel=1e-9)
    assert law.mean_factor(0.7, 0.7) == pytest.approx(law.factor(0.7), rel=1e-15)


def kirchhoff_face_coefficient(law, c, surface):
    """Each face's mean of f between its two cells, or between its cell and the surface
    value on an exterior face (``ConcentrationDependent.mean_factor``)."""
    cells = c.mesh.faceCellIDs
    values = np.asarray(c.value)
    inner = values[cells[0]]
    outer = np.where(np.ma.getmaskarray(cells[1]), surface, values[cells[1].filled(0)])
    return law.mean_factor(inner, outer)


def test_operator_sweeps_are_fipys_own_sweeps():
    """One backward-Euler step swept by FiPy (DiffusionTerm with a FaceVariable
    coefficient, the mean of f between the face's two sides) and by ``Faces`` agree to
    round-off."""
    from fipy import (CellVariable, DiffusionTerm, FaceVariable, Grid1D, LinearLUSolver,
                      TransientTerm)

    law = ConcentrationDependent(MM, exponent=3.0)
    weights = discretise(Sheet(H), ISOTROPIC, (20,), 5e-4)
    start = np.linspace(0.2, 1.5, 20)
    shared = concentration_dependent.SweptMarch(concentration_dependent.Faces.of(weights), law,
                                                20.0)
    ours = concentration_dependent.sweep_step(shared, start, MM, 1e-3, 1, 0.0)
    c = CellVariable(mesh=Grid1D(nx=20, dx=0.05), value=start, hasOld=True)
    c.constrain(MM, c.mesh.exteriorFaces)
    coefficient = FaceVariable(mesh=c.mesh, value=1.0)
    equation = TransientTerm() == DiffusionTerm(coeff=coefficient)
    c.updateOld()
    for _ in range(40):
        coefficient.setValue(kirchhoff_face_coefficient(law, c, MM) / 20.0)
        equation.sweep(var=c, dt=1e-3, solver=LinearLUSolver(tolerance=1e-14))
    assert np.max(np.abs(np.asarray(c.value) - ours)) < 1e-9


def test_a_step_that_does_not_converge_raises_a_solver_error():
    law = ConcentrationDependent(MM, exponent=5.0)
    one_sweep = SolverSettings(sweeps=concentration_dependent.Sweeps(most=1))
    with pytest.raises(SolverError, match="did not converge"):
        solve(Sheet(H), ISOTROPIC, exposure(0.0, MM), TIMES, accuracy=1e-2, sorption=law,
              part="cam", settings=one_sweep)


def test_the_skin_is_resolved_from_its_start_on():
    """Wetted to Mm for 1.5 h^2/D, then dried, outputs from 1e-3 h^2/D (k = 5, the corrected
    path's finer 3-D plan of a 4 x 3 x 2 mm plate): the skin starts at the drying (within
    one sample of it), the skin's cells (smallest D) are sized at the outputs after it, the
    wetting outputs take the largest D's cells; the plan covers both (no wider first row, no
    faster growth) with far fewer cells than the skin's cells at every output (35 568)."""
    from fickcam.diffusion import CamPlate, DiffusionProblem
    from fickcam.diffusion.models.finite_volume import plan_direct

    tau = H ** 2 / D
    plate = CamPlate(np.array([0, 4e-3, 4e-3, 0.0]), np.array([0, 0, 3e-3, 3e-3]), H)
    history = Exposure.piecewise([0.0, 1.5 * tau, 3.0 * tau], [330.0, 330.0], [MM, 0.0])
    times = np.array([1e-3, 1e-2, 0.1, 0.5, 1.0, 1.6, 2.0, 3.0]) * tau
    law = ConcentrationDependent(MM, exponent=5.0)
    asked = []

    def planner(d, a, outputs):
        asked.append((a, np.asarray(outputs, float),
                      plan_direct(DiffusionProblem(plate, d, history, outputs, a), "solid")))
        return asked[-1][2]

    start = concentration_dependent.skin_start(law, history)
    assert 1.5 * tau - 1.5 * tau / 8 <= start <= 1.5 * tau
    chosen = concentration_dependent.nonlinear_plan(planner, ISOTROPIC, law, history, times, 0.5)
    margin = np.exp(2.5)  # 1 + SKIN_CELLS_MARGIN (sqrt(e^5) - 1)
    skin = next(p for a, at, p in asked if np.isclose(a, 0.5 / margin) and at.min() >= start)
    soak = next(p for a, at, p in asked if np.isclose(a, 0.25) and at.max() < start)
    everywhere = next(p for a, at, p in asked if np.isclose(a, 0.5 / margin) and at.size == 8)
    for constraint in (skin, soak):
        assert chosen.finest <= constraint.finest and chosen.growth <= constraint.growth
    assert chosen.cells < everywhere.cells / 5
