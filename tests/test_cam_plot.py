"""`fickcam plot --kind kinematics|dynamics` on a result Dataset built from the cam's
scene response (fake part histories: swelling cam, heavier follower)."""
from types import SimpleNamespace

import numpy as np
import pytest

from fickcam.cam import CamSection
from fickcam.cam.mechanism import CamMechanism
from fickcam.schema import VARIABLES

xr = pytest.importorskip("xarray")

SECTION = CamSection.model_validate({
    "material": "cfrp", "base_circle_radius": "40 mm", "thickness": "10 mm", "speed": "300 rpm",
    "follower": {"kind": "roller", "roller_radius": "10 mm", "mass": "0.5 kg", "material": "cfrp",
                 "spring_rate": "2 N/mm", "spring_preload": "20 N"},
    "motion": [{"dwell": "90 deg"}, {"rise": "10 mm", "over": "90 deg", "law": "cycloidal"},
               {"dwell": "90 deg"}, {"return": "10 mm", "over": "90 deg", "law": "modified_sine"}],
    "wear": {"archard_coefficient": 1e-5, "hardness": "200 MPa"}})


def histories(n=3):
    grow = np.linspace(0.0, 1.0, n)
    cam = {"strain_longitudinal": 1e-3 * grow, "strain_transverse": 8e-3 * grow,
           "surface_modulus": 9e9 - 3e9 * grow, "surface_poisson_ratio": np.full(n, 0.3),
           "moisture_content": 1.5 * grow}
    follower = {"strain_longitudinal": 4e-3 * grow, "strain_transverse": 6e-3 * grow,
                "moisture_content": 3.0 * grow,
                "surface_modulus": 9e9 - 3e9 * grow, "surface_poisson_ratio": np.full(n, 0.3)}
    return {"cam": SimpleNamespace(state=cam), "follower": SimpleNamespace(state=follower)}


@pytest.fixture(scope="module")
def dataset():
    from fickcam.results.dataset import build_dataset

    times = np.array([0.0, 7.0, 30.0]) * 86400
    angles = np.radians(np.arange(0.0, 360.0, 2.0))
    material = SimpleNamespace(dry_density=1500.0, absorbs=True)
    response = CamMechanism(SECTION, {"cfrp": material}).response(histories(), times, angles,
                                                                  np.ones(3, bool))
    return build_dataset(response.variables, {"time": times, "cam_angle": angles},
                         {"scene_name": "tiny-cam"}), response


def test_the_cam_mechanisms_variables_follow_the_schema_and_age(dataset):
    ds, response = dataset
    for name in ds.data_vars:
        assert ds[name].dims == VARIABLES[name].dims
    assert ds["jump_speed"].attrs["units"] == "rpm"
    assert np.all(np.diff(ds["lift"].values) > 0)
    assert ds["wear_depth"].values[0] == 0 and np.all(np.diff(ds["wear_depth"].values) >= 0)
    # the follower gains 3 % mass -> the inertia part of the force grows
    assert ds["peak_contact_force"].values[-1] != ds["peak_contact_force"].values[0]


@pytest.mark.slow
def test_kinematics_and_dynamics_plots_are_written(dataset, tmp_path):
    from fickcam.plotting.cam import plot_dynamics, plot_kinematics

    ds, _ = dataset
    written = plot_kinematics(ds, tmp_path).paths + plot_dynamics(ds, tmp_path).paths
    assert [p.name for p in written] == ["cam_kinematics.png", "cam_drift.png", "cam_profile.png",
                                         "cam_dynamics.png", "cam_jump_stress.png"]
    assert all(p.exists() and p.stat().st_size > 5000 for p in written)


def test_the_cam_mechanisms_parts_are_the_cam_plate_and_the_roller():
    from fickcam.diffusion.problem.geometry import CamPlate, Disc
    from fickcam.materials.bodies import polygon_section

    material = SimpleNamespace(dry_density=1500.0, absorbs=True)
    parts = CamMechanism(SECTION, {"cfrp": material}).parts
    assert [p.name for p in parts] == ["cam", "follower"]
    cam, follower = parts
    assert isinstance(cam.geometry, CamPlate) and isinstance(follower.geometry, Disc)
    area = polygon_section(cam.geometry.profile_x, cam.geometry.profile_y)[0]
    assert cam.dry_mass == pytest.approx(1500.0 * 0.01 * area, rel=1e-12)
    assert follower.geometry.outer_radius == pytest.approx(0.01)
    assert follower.dry_mass == pytest.approx(0.5)
