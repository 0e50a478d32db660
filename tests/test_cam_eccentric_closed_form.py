"""The knife or roller on a uniformly swollen eccentric disc in closed form agrees with
the geometric construction (the aged contact point found by Newton, fitted by a
Chebyshev series and differentiated spectrally) to that construction's accuracy, and
its derivatives with finite differences of its own height; the jump speed's search
(a vectorised zoom) finds what a bounded Brent search finds, and the jump speed from
the closed form is the one from the construction."""
from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from fickcam.cam.design import CamDesign, CamState
from fickcam.cam.geometry import evaluate_geometric_motion, fit_geometric_motion, pieces_of
from fickcam.cam.kinematics import dry_lowest_height, motion_function
from fickcam.cam.model import continuous_jump_speed, zoomed_minimum
from fickcam.cam import dynamics as dyn

CASES = [("roller", 0.010, 0.0), ("roller", 0.012, -0.005), ("knife", 0.0, 0.003)]
STATES = [CamState(), CamState(cam_strain_x=0.02, cam_strain_y=0.02, roller_strain=0.005)]


def _disc(kind, roller, offset):
    return CamDesign("eccentric", 0.019, eccentricity=0.004, disc_radius=0.023,
                     follower_kind=kind, roller_radius=roller, offset=offset, thickness=0.01,
                     speed=30.0, follower_mass=0.7)


@pytest.mark.parametrize("state", STATES)
@pytest.mark.parametrize("kind, roller, offset", CASES)
def test_closed_form_matches_the_geometric_construction(kind, roller, offset, state):
    design = _disc(kind, roller, offset)
    theta = np.linspace(0.0, 2 * np.pi, 721)[:-1]
    motion, extremes = motion_function(design, state)
    fitted, origin, fitted_extremes = fit_geometric_motion(
        design, pieces_of(design), state.cam_strain_x, state.cam_strain_y,
        roller * (1 + state.roller_strain), nodes=96)
    exact, spectral = motion(theta), evaluate_geometric_motion(fitted, origin, theta)
    lift = fitted_extremes[1] - fitted_extremes[0]
    # the construction: Newton to 1e-15 in psi with a central-difference slope (h = 1e-6),
    # so each spectral derivative loses about three more digits
    for order, tolerance in enumerate((1e-12, 1e-9, 1e-6, 1e-3)):
        assert np.max(np.abs(exact[order] - spectral[order])) <= tolerance * lift
    np.testing.assert_allclose(extremes, fitted_extremes, rtol=0, atol=1e-12 * lift)


@pytest.mark.parametrize("kind, roller, offset", CASES)
def test_closed_form_derivatives_are_those_of_its_height(kind, roller, offset):
    motion, _ = motion_function(_disc(kind, roller, offset), STATES[1])
    theta = np.linspace(0.0, 2 * np.pi, 97)
    h = 1e-3
    for order in range(3):
        ahead, behind = motion(theta + h)[order], motion(theta - h)[order]
        central = (ahead - behind) / (2 * h)  # error h^2/6 |f'''| ~ 1e-7 of the lift's scale
        scale = np.max(np.abs(motion(theta)[order + 1]))
        assert np.max(np.abs(central - motion(theta)[order + 1])) <= 1e-6 * scale


@pytest.mark.parametrize("function, least", [
    (lambda x: 1.0 + (x - 0.3137) ** 2 * (2.0 + np.sin(x)), 1.0),
    (lambda x: 2.0 + np.abs(x - 0.41) + 0.1 * x * x, 2.0 + 0.1 * 0.41 ** 2),  # a kink
    (lambda x: 1.0 - x, 0.0)])  # at the bracket's end
def test_zoomed_minimum_finds_the_minimum_as_a_bounded_brent_search_does(function, least):
    brent = minimize_scalar(function, bounds=(0.0, 1.0), method="bounded",
                            options={"xatol": 1e-12})
    found = zoomed_minimum(function, 0.0, 1.0)
    # the zoom ends within 1 / 128^5 ~ 3e-11 of the minimiser: a slope-1 kink moves by that
    assert least - 1e-15 <= found <= least + 5e-11
    assert found <= brent.fun + 1e-14


@pytest.mark.parametrize("kind, roller, offset", CASES)
def test_jump_speed_from_the_closed_form_is_that_of_the_construction(kind, roller, offset):
    design = replace(_disc(kind, roller, offset), spring_rate=660.0, gravity=True)
    state = STATES[1]
    theta = np.radians(np.arange(0.0, 360.0, 2.0))
    fitted, origin, _ = fit_geometric_motion(design, pieces_of(design), state.cam_strain_x,
                                             state.cam_strain_y,
                                             roller * (1 + state.roller_strain), nodes=96)
    spectral = functools.partial(evaluate_geometric_motion, fitted, origin)
    speeds = []
    for motion in (motion_function(design, state)[0], spectral):
        height, _, d2, _ = motion(theta)
        holding = dyn.axial_force(design.follower_mass, 0.0, design.spring_rate,
                                  height - dry_lowest_height(design), 0.0, 0.0, design.gravity)
        speeds.append(continuous_jump_speed(design, motion, design.follower_mass, theta, d2,
                                            holding))
    # omega_j^2 ~ S / y'': the spectral y'' is good to ~1e-6 of its scale (above)
    assert speeds[0] == pytest.approx(speeds[1], rel=1e-6)
