"""Each example scene in configs/ runs and keeps its key numbers.

Identities that must hold whatever the diffusion model (lift and radii scale
with the part's free strain; a steel part's strain is alpha dT) are checked
exactly; numbers with no independent closed form are pinned: tightly where
no moisture is involved (t = 0, steel), loosely where they depend on the
diffusion model's accuracy.
"""
from pathlib import Path

import numpy as np
import pytest

import fickcam

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
STEEL_ALPHA = 12e-6  # 1/K, fickcam/data/materials.yaml (steel)


@pytest.fixture(scope="module")
def results(example_result):
    return example_result


def test_yadav2017_steel_cam_grows_by_alpha_dt_only(results):
    ds = results("yadav2017_cam")
    strain = ds.hygrothermal_strain.sel(part="cam").values
    assert np.allclose(strain, STEEL_ALPHA * (90 - 23), rtol=1e-12)
    assert np.all(ds.moisture_content.values == 0)
    assert np.allclose(ds.lift.values, 25.4e-3 * (1 + strain), rtol=1e-9)
    assert np.allclose(ds.base_circle_radius.values, 40e-3 * (1 + strain), rtol=1e-9)
    assert ds.jump_speed.values[0] == pytest.approx(1091.1478, rel=1e-6)  # continuous minimum
    assert ds.peak_cam_torque.values[0] == pytest.approx(15.066397, rel=1e-6)
    assert ds.peak_contact_stress.values[0] == pytest.approx(212.26077e6, rel=1e-6)


def test_eccentric_nylon_cam_stroke_is_twice_the_swollen_eccentricity(results):
    ds = results("eccentric_cam")
    strain = ds.hygrothermal_strain.sel(part="cam").values
    assert np.allclose(ds.lift.values, 2 * 4e-3 * (1 + strain), rtol=1e-9)
    moisture = ds.moisture_content.sel(part="cam").values
    assert moisture[0] == 0 and np.all(np.diff(moisture) > 0)
    assert moisture[-1] == pytest.approx(6.846, rel=1e-2)  # D0 from the D570 24-h uptake
    assert np.all(moisture < ds.equilibrium_moisture_content.sel(part="cam").values)
    assert ds.jump_speed.values[0] == pytest.approx(587.5824, rel=1e-6)
    assert np.all(np.diff(ds.jump_speed.values) > 0)  # heavier but larger: here it gains


def test_eccentric_nylon_cam_softens_so_its_contact_stress_drops(results):
    """Water plasticises the nylon cam (PA66 data sheet: conditioned modulus 0.367 of dry):
    its surface modulus falls and the Hertz stress, p0 ~ sqrt(E*), drops with it although
    the contact force grows."""
    ds = results("eccentric_cam")
    surface = ds.surface_modulus.sel(part="cam").values
    assert surface[0] == pytest.approx(2.8e9, rel=1e-12)
    assert surface[-1] == pytest.approx(2.8e9 * 1100 / 3000, rel=1e-3)
    stress = ds.peak_contact_stress.values
    assert stress[-1] < 0.7 * stress[0]
    assert ds.peak_contact_force.values[-1] > ds.peak_contact_force.values[0]


def test_singh2017_cam_dry_kinematics_and_follower_uptake(results):
    ds = results("singh2017_cam")
    first = ds.isel(time=0)
    assert float(first.lift) == pytest.approx(38.30618e-3, rel=1e-6)
    assert float(first.jump_speed) == pytest.approx(1058.6526, rel=1e-6)
    assert float(first.peak_cam_torque) == pytest.approx(54.567269, rel=1e-6)
    # the roller is a solid disc: exact series, so pinned tightly
    follower = ds.moisture_content.sel(part="follower").values
    assert follower[-1] == pytest.approx(0.4589979, rel=1e-5)
    cam = ds.moisture_content.sel(part="cam").values
    assert cam[-1] == pytest.approx(0.4232, rel=2e-2)
    mass = ds.mass.sel(part="follower").values
    assert np.allclose(mass, 1.6 * (1 + follower / 100), rtol=1e-12)
    assert np.all(np.diff(ds.lift.values) > 0)


def test_singh2016_fourbar_stops_its_links_at_the_wet_tg_and_keeps_earlier_results(results):
    ds = results("singh2016_fourbar")
    notices = ds.attrs["notices"]
    for link in ("crank", "coupler", "rocker"):
        assert any(n.startswith(f"{link} at t = ") and "wet Tg" in n for n in notices)
    valid = np.isfinite(ds.rocker_angle.values).all(axis=1)
    assert valid[0] and not valid[-1]
    assert np.all(valid[: valid.argmin()]) and not np.any(valid[valid.argmin():])
    assert np.all(np.isnan(ds.moisture_content.sel(part="crank").values[~valid]))
    frame = ds.hygrothermal_strain.sel(part="frame").values
    assert np.allclose(frame, STEEL_ALPHA * 95, rtol=1e-12)
    nominal = np.array([0.1, 0.16, 0.16, 0.2])
    strain = ds.hygrothermal_strain.values[valid]
    assert np.allclose(ds.link_length.values[valid], nominal * (1 + strain), rtol=1e-12)
    assert float(ds.minimum_transmission_angle[0]) == pytest.approx(36.003899, rel=1e-6)
    assert str(ds.grashof_class.values[0]) == "crank-rocker"


def test_epoxy_follower_natural_frequency_falls_with_the_wet_modulus_and_mass(results):
    ds = results("epoxy_follower_vibration")
    modulus = ds.longitudinal_modulus.sel(part="follower").values
    moisture = ds.moisture_content.sel(part="follower").values
    stiffness = modulus * np.pi * 0.008 ** 2 / 4 / 0.150
    expected = np.sqrt((stiffness + 12e3) / (0.12 * (1 + moisture / 100))) / (2 * np.pi)
    assert np.allclose(ds.natural_frequency.values, expected, rtol=1e-12)
    assert np.all(np.diff(ds.natural_frequency.values) < 0)
    assert ds.natural_frequency.values[-1] < 0.95 * ds.natural_frequency.values[0]
    jump = ds.dynamic_jump_speed.values
    assert np.all(jump < ds.jump_speed.values) and jump[-1] < jump[0] - 30  # rpm


def test_nylon_swinging_arm_swing_shrinks_as_the_arm_grows(results):
    """The design swing is the motion program's 20 deg exactly; the wet nylon
    arm grows along its length, so the same cam lift turns it through a smaller angle, and its
    softer roller lowers the Hertz stress. Pinned loosely: they rest on the diffusion model."""
    ds = results("nylon_swinging_arm")
    assert float(ds.arm_swing_design) == pytest.approx(20.0, rel=1e-12)  # stored in degrees
    swing = ds.arm_swing.values
    assert np.all(np.diff(swing) < 0) and swing[-1] == pytest.approx(19.709, rel=2e-3)
    follower = ds.moisture_content.sel(part="follower").values
    assert np.all(np.diff(follower) >= 0) and follower[-1] == pytest.approx(6.36, rel=1e-2)
    assert ds.peak_contact_stress.values[-1] < 0.75 * ds.peak_contact_stress.values[0]
    power = ds.cam_torque * 2 * np.pi * 300 / 60  # camshaft power = arm power (virtual work)
    arm_power = ds.arm_torque * ds.follower_arm_angular_velocity
    assert float(abs(power - arm_power).max()) < 1e-9 * float(abs(power).max())
