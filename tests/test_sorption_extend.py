"""``DiffusionResult.extend`` of the concentration-dependent marches
(``diffusion.stepping.dense_output``): new times read between the stored march's steps agree with
a solve at those times within
the extended result's estimate, the reading never crosses an exposure change, and its
estimate grows as the steps thin out. The exact Fickian sheet uptake (Crank 1975 eq. 4.18,
4.20; ``series.sheet_uptake``) is the independent reference of the interpolation alone."""
import numpy as np
import pytest

from fickcam.diffusion import CamPlate, Diffusivity, Exposure, Sheet, solve
from fickcam.diffusion.accuracy.error_model import FIRST_STEP
from fickcam.diffusion.exact.series import sheet_uptake
from fickcam.diffusion.nonfickian.corrected_product import gap
from fickcam.diffusion.problem.sorption import ConcentrationDependent
from fickcam.diffusion.stepping.dense_output import StepRecord
from fickcam.diffusion.stepping.step_plans import step_nodes

pytest.importorskip("fipy")

H, D, MM = 2e-3, 5e-12, 2.0
T = H ** 2 / D
ISOTROPIC = Diffusivity((D, D, D), 0.0)
TIMES = np.array([0.0, 0.01, 0.03, 0.1, 0.2, 0.3, 0.31, 0.6, 1.0]) * T
STEP_DOWN = Exposure.piecewise([0.0, 0.3 * T, TIMES[-1]], [330.0, 330.0], [MM, 0.5 * MM],
                               initial_moisture=0.0)


def track_of(values, per_doubling, changes=(0.0, 1.0), outputs=(0.5, 1.0)):
    """A StepRecord on the march's own node plan (scaled time = time) with ``values(tau)``."""
    nodes = step_nodes(np.array(changes), np.array(outputs), FIRST_STEP, per_doubling)
    return StepRecord(nodes, np.column_stack([values(nodes)] * 2), np.zeros(nodes.size),
                 np.array(changes, float), lambda t: np.asarray(t, float))


@pytest.fixture(scope="module")
def stepped_sheet():
    return solve(Sheet(H), ISOTROPIC, STEP_DOWN, TIMES, accuracy=1e-2,
                 sorption=ConcentrationDependent(MM, exponent=2.0))


@pytest.mark.slow
def test_extend_agrees_with_a_solve_at_the_new_times_within_its_estimate(stepped_sheet):
    """k = 2, wetted then stepped down at 0.3 h^2/D: 20 new times inside the stored span (none
    younger after its change than the stored outputs, so the cells stay) read between the
    steps, against the solve at the stored and new times together."""
    new = np.concatenate([np.linspace(0.012, 0.29, 10), np.linspace(0.32, 0.99, 10)]) * T
    extended = stepped_sheet.extend(new)
    again = solve(Sheet(H), ISOTROPIC, STEP_DOWN, extended.times, accuracy=1e-2,
                  sorption=ConcentrationDependent(MM, exponent=2.0))
    assert "read between the march's steps" in extended.reason
    np.testing.assert_array_equal(extended.times, np.union1d(TIMES, new))
    stored = np.isin(extended.times, TIMES)
    np.testing.assert_array_equal(extended.mean[stored], stepped_sheet.mean)
    distance = gap((extended.mean, extended.surface), (again.mean, again.surface), MM)
    assert 0.0 < distance <= extended.error_estimate
    assert extended.error_estimate >= stepped_sheet.error_estimate


@pytest.mark.slow
def test_the_corrected_plate_read_between_its_steps_agrees_with_its_solve_at_the_new_times():
    """The 4 x 3 x 2 mm plate (k = 2, absorbing; the corrected product of ``corrected_product``) at
    3e-2:
    read at its own outputs, the tracks of its marches (plate, slab, planform, planform
    reference, sheet) give the stored result to round-off; 7 new times read between the
    steps are within the extended estimate of a solve at the stored and new times, and
    within a tenth of it (the solves differ by the re-planned steps, not the method's error)."""
    plate = CamPlate(np.array([0, 4e-3, 4e-3, 0.0]), np.array([0, 0, 3e-3, 3e-3]), H)
    times = np.array([0.0, 0.01, 0.03, 0.1, 0.3]) * T
    wet = Exposure.piecewise([0.0, times[-1]], [330.0], [MM], initial_moisture=0.0)
    law = ConcentrationDependent(MM, exponent=2.0)
    stored = solve(plate, ISOTROPIC, wet, times, accuracy=3e-2, sorption=law)
    mean, layer, estimate = stored.extend.interpolated(times)
    np.testing.assert_allclose(mean, stored.mean, rtol=0, atol=1e-12)
    np.testing.assert_allclose(layer, stored.surface, rtol=0, atol=1e-12)
    assert np.all(estimate == 0.0)
    extended = stored.extend(np.array([0.015, 0.02, 0.05, 0.07, 0.15, 0.2, 0.25]) * T)
    assert "read between the march's steps" in extended.reason
    again = solve(plate, ISOTROPIC, wet, extended.times, accuracy=3e-2, sorption=law)
    distance = gap((extended.mean, extended.surface), (again.mean, again.surface), MM)
    assert 0.0 < distance <= 0.1 * extended.error_estimate


@pytest.mark.slow
def test_a_new_time_younger_than_the_stored_outputs_is_solved_again(stepped_sheet):
    """2e-3 h^2/D after the step down: the cells were sized for the youngest stored output
    (1e-2 h^2/D after a change), so extend solves again (the result says nothing of reading)."""
    extended = stepped_sheet.extend(np.array([0.302]) * T)
    assert "read between" not in extended.reason
    assert 0.302 * T in extended.times


@pytest.mark.slow
def test_a_new_time_younger_than_the_stored_outputs_of_the_skin_is_solved_again():
    """Stored outputs 0.3 and 0.7 h^2/D after the step down (the skin's cells sized for 0.3),
    a new one 0.02 after it: older than the youngest stored output of the whole history (1e-2
    after the start), but the skin's plan changes (``dense_output.held_to_plan``), so it is solved
    again and agrees with ``solve`` at both to round-off."""
    law = ConcentrationDependent(MM, exponent=2.0)
    stored_times = TIMES[TIMES != 0.31 * T]
    stored = solve(Sheet(H), ISOTROPIC, STEP_DOWN, stored_times, accuracy=1e-2, sorption=law)
    extended = stored.extend(np.array([0.32]) * T)
    assert "read between" not in extended.reason
    again = solve(Sheet(H), ISOTROPIC, STEP_DOWN, extended.times, accuracy=1e-2, sorption=law)
    np.testing.assert_array_equal(extended.mean, again.mean)


def test_the_reading_never_crosses_an_exposure_change():
    """Two segments with different cubics in log(age): read just after the change (its first
    stencil) and just before, each is its own segment's cubic to round-off (a stencil across
    the change would mix the two); at the change itself the node's value (the state at t-)."""
    def values(tau):
        age = np.where(tau <= 1.0, tau, tau - 1.0)
        s = np.log(np.maximum(age, 1e-300))
        return np.where(tau <= 1.0, 1.0 + 0.1 * s + 0.01 * s ** 3, -2.0 + 0.3 * s - 0.02 * s ** 2)
    track = track_of(values, 4, changes=(0.0, 1.0, 2.0), outputs=(0.5, 1.0, 1.5, 2.0))
    at = np.array([0.999, 1.0 + 3e-6, 1.0 + 1e-3, 1.0])
    cubic, _ = track.at(at)
    np.testing.assert_allclose(cubic[:, 0], values(at), rtol=0, atol=1e-10)
    assert cubic[-1, 0] == values(np.array([1.0]))[0]


@pytest.mark.parametrize("coarse, fine", [(4, 16)])
def test_the_estimate_grows_as_the_steps_thin_out_and_bounds_the_error(coarse, fine):
    """The exact Fickian sheet uptake on the march's node plans (m steps per doubling): the
    estimate |cubic - quadratic| is larger with 4 steps than with 16 (the cubic's last term,
    ~ (ln 2 / m)^3: 64 times), and the cubic's error against the exact uptake is within it at
    every time read, up to 1e-7 of the swing (where the estimate happens to vanish)."""
    at = np.geomspace(3e-5, 0.9, 40)
    estimates = {}
    for m in (coarse, fine):
        cubic, quadratic = track_of(sheet_uptake, m).at(at)
        estimate = np.abs(cubic[:, 0] - quadratic[:, 0])
        assert np.all(np.abs(cubic[:, 0] - sheet_uptake(at)) <= estimate + 1e-7)
        estimates[m] = float(np.max(estimate))
    assert estimates[coarse] > 16.0 * estimates[fine]
