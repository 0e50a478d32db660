"""The plane model (CamPlate, LinkBar): short-time expansion of the outline blended
with the 2-D mesh, times the exact sheet, against exact solutions."""
from __future__ import annotations

import numpy as np
import pytest

from fickcam.diffusion import Bar, CamPlate, Diffusivity, Disc, Exposure, LinkBar, solve
from fickcam.diffusion import exact, fv, planform

DAY = 86400.0
D = 1e-12
ISOTROPIC = Diffusivity((D, D, D), 0.0)
SWING = 1.5
# dry -> 1.5 % at t = 0, down to 0.5 % at 200 d (a step up, then a step down)
HISTORY = Exposure.piecewise([0.0, 200 * DAY, 400 * DAY], 330.0, [1.5, 0.5])
TIMES = np.array([0, 1, 7, 30, 100, 200, 201, 207, 230, 300, 400]) * DAY


def circle_plate(radius: float, thickness: float, points: int = 720) -> CamPlate:
    angle = 2 * np.pi * np.arange(points) / points
    return CamPlate(radius * np.cos(angle), radius * np.sin(angle), thickness)


def relative(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) / SWING


def test_circular_plate_matches_the_finite_cylinder_after_a_step_up_and_down():
    """Exact finite cylinder = cylinder x sheet (Crank 1975 eqs. 5.23 and 4.18)."""
    radius, thickness = 0.03, 6e-3
    result = solve(circle_plate(radius, thickness), ISOTROPIC, HISTORY, TIMES, accuracy=1e-3)
    reference = exact.exact_history(Disc(radius, thickness), ISOTROPIC, HISTORY, TIMES)
    assert result.model == "plane"
    assert relative(result.mean, reference["mean"]) <= 1e-3
    assert relative(result.surface, reference["surface"]) <= 4e-3
    assert result.error_estimate <= 2e-3


def test_rectangular_plate_corners_match_the_product_of_sheets():
    """Right-angle corners (c = 4/pi each) against the block solution (Crank eq. 4.51)."""
    length, width, thickness = 0.04, 0.025, 6e-3
    plate = CamPlate(np.array([0, length, length, 0.0]), np.array([0, 0, width, width]),
                     thickness)
    result = solve(plate, ISOTROPIC, HISTORY, TIMES, accuracy=1e-3)
    reference = exact.exact_history(Bar(length, width, thickness), ISOTROPIC, HISTORY, TIMES)
    assert relative(result.mean, reference["mean"]) <= 1e-3


def test_expansion_reproduces_the_cylinder_series_and_the_right_angle_corner():
    radius, thickness = 0.05, 1e-2
    scale = np.array([1.0, 1.0]) / thickness
    tau = np.array([1e-4, 1e-3, 1e-2, 0.1])
    disc = planform.short_time(circle_plate(radius, thickness), scale, 5e-4, 1e-3)
    cylinder = exact.cylinder_uptake(tau * (thickness / radius) ** 2)
    assert np.all(np.abs(disc.uptake(tau) - cylinder) <= disc.uptake_error(tau) + 1e-5 * cylinder)
    assert planform.corner_coefficient(np.array([np.pi / 2]))[0] == pytest.approx(4 / np.pi,
                                                                                rel=1e-6)


def test_link_mean_converges_as_accuracy_tightens():
    """Self-convergence on a stadium link with holes (no exact solution): the error
    against a tight solve shrinks with the requested accuracy and stays within it."""
    link = LinkBar(0.08, 0.03, 0.01, 0.015, 0.005)
    times = np.array([0, 1, 3, 10, 30, 100, 200]) * DAY
    history = Exposure.piecewise([0.0, 200 * DAY], 330.0, [1.5])
    tight = solve(link, ISOTROPIC, history, times, accuracy=2.5e-4)
    errors = {acc: relative(solve(link, ISOTROPIC, history, times, accuracy=acc).mean, tight.mean)
              for acc in (1e-2, 1e-3)}
    assert errors[1e-3] <= 1e-3
    assert errors[1e-3] <= errors[1e-2]


def test_link_expansion_matches_the_mesh_extrapolated_in_space():
    """The stadium link with holes (no exact solution): the short-time expansion's
    planform uptake against finite volumes on two uniform meshes, Richardson-extrapolated
    (second order, h ratio 5/3) where the edge layer is resolved."""
    link = LinkBar(0.08, 0.03, 0.01, 0.015, 0.005)
    d = (1.0, 1.0, 1.0)
    expansion = planform.short_time(link, np.array(planform.planar_scale(link, d)), 5e-4, 5e-4)
    tau = np.array([0.03, 0.05])
    meshes = []
    for spacing in (1.0e-3, 0.6e-3):
        triangles = planform.triangulate(link, spacing)
        disc = fv.plane(triangles, link.thickness, triangles.contact_distance, 5e-4, d)
        response, _ = planform.step_response(disc, 0.06, 6, 1e-6)
        meshes.append(1.0 - response.at(tau, response.mean))
    ratio = (1.0 / 0.6) ** 2
    extrapolated = meshes[1] + (meshes[1] - meshes[0]) / (ratio - 1)
    assert np.all(np.abs(meshes[1] - expansion.uptake(tau)) > 1e-3)  # the mesh alone errs
    assert np.all(np.abs(extrapolated - expansion.uptake(tau)) <= 5e-4)
