"""The jump speeds of a closed-form cam searched for all ageing times at once are those of
each ageing time searched alone, the times whose aged motion has no closed form are left
to the per-time search, and the zoom over several brackets finds each bracket's minimum."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from fickcam.cam import CamDesign, CamState, cam_response
from fickcam.cam.arm import Arm
from fickcam.cam.kinematics import closed_form
from fickcam.cam.model import closed_form_jump_speeds, zoomed_minimum
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
    together = closed_form_jump_speeds(design, states, THETA)
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
    assert closed_form_jump_speeds(design, {0: CamState()}, THETA) == {}


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
