"""The limit search's ``DiffusionResult.extend`` on Duhamel's panels (a few exposure
segments): the plane model (CamPlate) and the exact series (Sheet) read at new times inside
the stored span give what a solve at the stored and new times together gives, to round-off,
with its error estimate; a new time that changes the plane plan is solved again."""
from dataclasses import replace

import numpy as np
import pytest

from fickcam.diffusion import CamPlate, Diffusivity, Exposure, Sheet, solve
from fickcam.diffusion.models.plane import PanelExtension

DAY = 86400.0
PLATE = CamPlate(np.array([0.0, 12e-3, 12e-3, 0.0]), np.array([0.0, 0.0, 8e-3, 8e-3]), 3e-3)
D = Diffusivity((2e-5, 2e-5, 1e-5), 40e3)


def stepped_history():
    """Three held steps and a ramp over 60 days (panels, not a long record)."""
    edges = np.array([0, 10, 25, 40, 60]) * DAY
    ramp = np.array([0, 0, 1, 0], bool)
    return Exposure.piecewise(edges, [300, 330, 320, 310.0], [1.0, 2.0, 0.5, 1.5], 0.1, ramp)


def assert_as_solved_together(stored, extended, together, times, new):
    both = np.union1d(times, new)
    rows, kept = np.searchsorted(both, new), np.searchsorted(both, times)
    assert np.array_equal(extended.times, both)
    scale = float(np.max(np.abs(together.mean)))
    for name in ("mean", "surface"):
        assert np.allclose(getattr(extended, name)[rows], getattr(together, name)[rows],
                           rtol=0, atol=64 * np.finfo(float).eps * scale)
        assert np.array_equal(getattr(extended, name)[kept], getattr(stored, name))
    assert extended.error_estimate == pytest.approx(together.error_estimate, rel=1e-12)


@pytest.mark.parametrize("geometry", [PLATE, Sheet(2e-3)], ids=["plate", "sheet"])
def test_a_panel_result_extended_to_new_times_equals_a_solve_at_both(geometry):
    exposure, times = stepped_history(), np.array([0.0, 1.0, 7.0, 30.0, 60.0]) * DAY
    stored = solve(geometry, D, exposure, times, accuracy=1e-3)
    new = np.array([33.7, 36.2, 41.0, 52.5]) * DAY
    both = np.union1d(times, new)
    extended = stored.extend(both)
    assert_as_solved_together(stored, extended, solve(geometry, D, exposure, both, accuracy=1e-3),
                              times, new)


def test_a_plan_at_both_that_changes_the_solve_solves_again():
    """The extension reads new rows only while the plan of the stored and new times
    together fixes the solve as the stored plan did (mesh, sheet, steps); otherwise (e.g. a
    new time younger than every stored output where that sizes the cells) it solves at both."""
    exposure, times = stepped_history(), np.array([5.0, 20.0, 30.0, 60.0]) * DAY
    stored = solve(PLATE, D, exposure, times, accuracy=1e-3)
    extension = stored.extend
    assert isinstance(extension, PanelExtension)   # the dispatcher binds its plan and solve
    assert extension.replan is not None and extension.resolve is not None
    chosen, asked = extension.chosen, []

    def resolve(at):
        asked.append(np.asarray(at))
        return stored
    finer = replace(extension, replan=lambda at: replace(chosen, finest=0.5 * chosen.finest),
                    resolve=resolve)
    both = np.union1d(times, [12.0 * DAY])
    assert finer(both) is stored and np.array_equal(asked[0], both)
    same = replace(extension, replan=lambda at: replace(chosen, error_estimate=0.0),
                   resolve=resolve)
    assert same(both).times.size == both.size and len(asked) == 1
