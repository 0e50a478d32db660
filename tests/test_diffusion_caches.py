"""The engine's caches hand the same arrays to every caller, so they are read-only: a
caller writing into one raises instead of changing what a later plan or solve reads, and
no caller needs a defensive copy."""
from __future__ import annotations

import numpy as np
import pytest

from fickcam.diffusion import CamPlate, Diffusivity, Exposure, solve
from fickcam.diffusion.exact.series import ROOT_TABLE, bessel_roots, cylinder_short_coefficients
from fickcam.diffusion.forcing.clock import clock_of
from fickcam.diffusion.models.plane import planform_response
from fickcam.diffusion.planform.short_time import outline_chords
from fickcam.diffusion.problem.sorption import Langmuir, Rate
from fickcam.diffusion.stepping.step_plans import output_ages

PLATE = CamPlate(np.array([0.0, 12e-3, 12e-3, 0.0]), np.array([0.0, 0.0, 8e-3, 8e-3]), 3e-3)
D = (1e-12, 1e-12, 1e-12)


def assert_read_only(*arrays):
    for array in arrays:
        assert not array.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            array[...] = 0.0


def test_exact_series_tables_are_read_only():
    assert_read_only(bessel_roots(10), bessel_roots(ROOT_TABLE + 1), cylinder_short_coefficients())


def test_the_clock_outline_chords_and_output_ages_are_read_only():
    exposure = Exposure.piecewise([0.0, 86400.0, 2 * 86400.0], [300.0, 320.0], [1.0, 2.0], 0.0,
                                  ramp=[False, True])
    clock = clock_of(Diffusivity(D, 40e3), exposure)
    assert_read_only(clock.held_rate, clock.cumulative,
                     *outline_chords(PLATE, (1.0, 1.0), 1e-3),
                     output_ages(np.array([0.0, 1e-2, 2e-2]), np.array([5e-3, 3e-2]),
                                 np.array([False, True])))


def test_a_planform_step_response_is_read_only():
    _, response, _ = planform_response(PLATE, 0.2, 1.4, D, 5e-4, 1.0, 4, 1e-6, False, "")
    assert_read_only(response.nodes, response.mean, response.layer)


def test_a_two_phase_plate_result_reads_its_cached_refinement_without_a_copy():
    """The result's arrays are the cached refinement's histories, read-only."""
    rate = Rate(0.1 * np.pi ** 2 * D[0] / PLATE.thickness ** 2)
    exposure = Exposure.piecewise([0.0, 2e6], 300.0, [1.0], 0.0)
    times = np.linspace(0.0, 2e6, 5)
    result = solve(PLATE, Diffusivity(D, 0.0), exposure, times, accuracy=1e-2,
                   sorption=Langmuir(rate, rate), model="plane")
    assert_read_only(result.mean, result.surface, result.bound)
