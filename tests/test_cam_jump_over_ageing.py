"""The jump speeds of a closed-form cam searched for all ageing times at once are those of
each ageing time searched alone, and so are those of the times whose aged motion is a
spectral fit, fitted and searched together (the fits themselves equal to each time's own);
a swinging arm is left to the per-time search, and the zoom over several brackets finds
each bracket's minimum."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from fickcam.cam import CamDesign, CamState, cam_response
from fickcam.cam.arm import Arm
from fickcam.cam.kinematics import closed_form, fitted_motions, motion_function
from fickcam.cam.model import jump_speeds_over_ageing, zoomed_minimum
from fickcam.cam.motion import segments_from_spec
from fickcam.cam.spec import Segment

THETA = np.radians(np.arange(0.0, 360.0, 1.0))


def _eccentric(kind, roller, offset):
    return CamDesign("eccentric", 0.019, eccentricity=0.004, disc_radius=0.023,
                     follower_kind=kind, roller_radius=roller, offset=offset, thickness=0.01,
                     speed=30.0, follower_mass=0.7, spring_rate=660.0, gravity=True)


def _rise_and_return(kind):
    segments = segments_from_spec([Segment(rise=0.012, over=math.radians(150), law="cycloidal"),
                                   Segment(dwell=math.radians(30)),
                                   Segment(**{"return": 0.012}, over=math.radians(150),
                                           law="cycloidal"),
                                   Segment(dwell=math.radians(30))])
    return CamDesign("motion", 0.04, 0.01, 50.0, kind, 0.5, segments=segments,
                     roller_radius=0.01 if kind == "roller" else 0.0, spring_rate=2000.0,
                     spring_preload=20.0, gravity=True)


DESIGNS = {"roller on an eccentric disc": _eccentric("roller", 0.010, 0.0),
           "offset roller on an eccentric disc": _eccentric("roller", 0.012, -0.005),
           "knife on an eccentric disc": _eccentric("knife", 0.0, 0.003),
           "flat face on an eccentric disc": _eccentric("flat", 0.0, 0.0),
           "roller on a cycloidal rise": _rise_and_return("roller"),
           "flat face on a cycloidal rise": _rise_and_return("flat")}


def _states(design):
    """Ageing states: swelling and moisture mass growing, one with anisotropic swelling."""
    states = {}
    for k, strain in enumerate((0.0, 0.004, 0.011, 0.019)):
        roller = strain if design.follower_kind == "roller" else 0.0
        states[k] = CamState(cam_strain_x=strain, cam_strain_y=strain, roller_strain=roller,
                             follower_mass=design.follower_mass * (1 + 2 * strain))
    states[4] = replace(states[2], cam_strain_x=0.015)  # anisotropic
    return states


@pytest.mark.parametrize("name", DESIGNS)
def test_jump_speeds_over_ageing_are_those_of_each_time_alone(name):
    design = DESIGNS[name]
    states = _states(design)
    together = jump_speeds_over_ageing(design, states, THETA)
    assert set(together) == {k for k, state in states.items()
                             if closed_form(design, state) is not None}
    assert len(together) >= 4
    for k, speed in together.items():
        alone = cam_response(design, states[k], THETA).variables["jump_speed"]
        assert math.isfinite(speed) and speed > 0
        # the same search (its last bracket ~2e-12 rad wide) on the same formulas
        assert speed == pytest.approx(alone, rel=1e-12)


def test_a_swinging_arm_is_left_to_the_per_time_search():
    arm = Arm(pivot_x=0.09, pivot_y=0.04, length=0.08, inertia=1.3e-4, spring_rate=2.0)
    design = replace(_rise_and_return("roller"), arm=arm)
    assert closed_form(design, CamState()) is not None  # the dry arm follows its design motion
    assert jump_speeds_over_ageing(design, {0: CamState()}, THETA) == {}
    assert fitted_motions(design, {0: replace(CamState(), cam_strain_x=0.01)}) is None


def test_the_zoom_over_several_brackets_finds_each_brackets_minimum():
    minimisers = np.array([0.3137, 0.41, 0.05, 0.999])

    def function(x):
        return (x - minimisers[:, None]) ** 2 * (2.0 + np.sin(x))

    together = zoomed_minimum(function, np.zeros(4), np.ones(4))
    assert together.shape == (4,)
    # each bracket narrows by 128 a round: the last grid's spacing is 1 / (128^4 x 256), so
    # the least value is at most 3 (half that spacing)^2 ~ 1.6e-22
    bound = 3 * (0.5 / (128 ** 4 * 256)) ** 2
    for k, minimiser in enumerate(minimisers):
        alone = zoomed_minimum(lambda x: (x - minimiser) ** 2 * (2.0 + np.sin(x)), 0.0, 1.0)
        assert isinstance(alone, float)
        assert 0.0 <= together[k] <= bound and 0.0 <= alone <= bound


def _anisotropic(design):
    """Ageing states whose cam swells more along x than along y: no closed form."""
    states = {}
    for k, strain in enumerate((0.001, 0.004, 0.011, 0.019)):
        roller = strain if design.follower_kind == "roller" else 0.0
        states[k] = CamState(cam_strain_x=1.7 * strain, cam_strain_y=strain,
                             roller_strain=roller,
                             follower_mass=design.follower_mass * (1 + 2 * strain))
    return states


FITTED = {name: design for name, design in DESIGNS.items()
          if name in ("roller on a cycloidal rise", "offset roller on an eccentric disc")}


@pytest.mark.parametrize("name", FITTED)
def test_fitted_motions_over_ageing_are_those_of_each_time_alone(name):
    design = FITTED[name]
    states = _anisotropic(design)
    fitted = fitted_motions(design, states)
    assert fitted.indices == list(states)
    together = jump_speeds_over_ageing(design, states, THETA, fitted)
    rows = fitted.rows(np.vstack([THETA] * len(states)))
    for k, state in states.items():
        motion, extremes = motion_function(design, state)
        alone, stacked = motion(THETA), fitted.motion(k)[0](THETA)
        lift = extremes[1] - extremes[0]
        # one least-squares solve for every time and piece instead of one each: the same
        # interpolant to round-off, which each spectral derivative amplifies (measured on the
        # disc's degree-96 fit: 8e-15, 1e-12, 4e-10 and 3e-7 of the lift; the bounds leave
        # 10-30 x for another BLAS kernel, and stay below the fit's own error, 1.3e-5 of
        # the largest jerk)
        for order, tolerance in enumerate((1e-13, 3e-11, 1e-8, 1e-5)):
            assert np.max(np.abs(alone[order] - stacked[order])) <= tolerance * lift
            np.testing.assert_array_equal(rows[order][k], stacked[order])
        np.testing.assert_allclose(fitted.motion(k)[1], extremes, rtol=0, atol=1e-13 * lift)
        speed = cam_response(design, state, THETA).variables["jump_speed"]
        assert math.isfinite(together[k]) and together[k] == pytest.approx(speed, rel=1e-9)
