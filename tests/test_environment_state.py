"""An environment that gives the state directly: uniform moisture and temperature, no
diffusion; Singh & Sanyal (2016)'s quasi-static calculation as a scene."""
from pathlib import Path

import numpy as np
import pytest

import fickcam
from fickcam.linkage.positions import continuous, positions
from fickcam.sweep.spec import load_sweep

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
T0, RISE = 296.15, 95.0


@pytest.fixture(scope="module")
def states(example_result):
    return example_result("singh2016_states")


def test_states_are_uniform_and_taken_as_given(states):
    """As built, hot and dry, hot at 3502's equilibrium moisture Mm(100 %) = 5 %
    (Singh & Sanyal 2016 Table 4): moisture and temperature exactly as stated, no diffusion."""
    np.testing.assert_array_equal(states.ageing_time.values, [0.0, 1.0, 2.0])
    np.testing.assert_allclose(states.temperature.values, [T0, T0 + RISE, T0 + RISE], rtol=1e-15)
    for part in ("crank", "coupler", "rocker"):
        np.testing.assert_allclose(states.moisture_content.sel(part=part).values, [0, 0, 5.0],
                                   rtol=1e-15)
        np.testing.assert_array_equal(states.surface_moisture_content.sel(part=part).values,
                                      states.moisture_content.sel(part=part).values)
        assert states.attrs["diffusion"][part]["model"] == "state"
    rh = states.relative_humidity.values
    assert np.isnan(rh[:2]).all() and rh[2] == 100.0


def test_state_drift_is_freudenstein_with_the_swollen_lengths(states):
    """The rocker angle at each state is Freudenstein's with that state's link lengths
    (Singh & Sanyal 2016 eqs. 15-18), an independent closed form; the drift is far from
    trivial."""
    theta2 = np.radians(states.crank_angle.values)
    lengths = states.link_length.values
    strain = states.hygrothermal_strain.values
    np.testing.assert_allclose(lengths, np.array([0.1, 0.16, 0.16, 0.2]) * (1 + strain), rtol=1e-14)
    for k in range(3):
        _, t4 = positions(*lengths[k], theta2)
        gap = continuous(np.radians(states.rocker_angle.values[k]) - t4)
        assert np.abs(gap).max() < 1e-9, k
    shift = np.abs(states.rocker_angle.values - states.rocker_angle.values[0]).max(axis=1)
    assert shift[0] == 0 and 0.3 < shift[1] < shift[2] and shift[2] > 1.5


def test_singh2016_three_resins_drift_in_the_order_of_their_moisture():
    """Singh & Sanyal 2016's cases (sweep file): 3502 (5 %) drifts more than 8551-7 (2 %);
    R914 (7 %) reaches its Chamis wet Tg (103.6 degC < 118 degC) in the saturated state,
    where fickcam stops its links with a notice and keeps the two earlier states."""
    sweep = load_sweep(CONFIGS / "sweep_singh2016_resins.yaml")
    shift = {}
    for case in sweep.cases:
        ds = fickcam.run(fickcam.load_scene(sweep.scene_dict(case)))
        resin = case.values["materials.resin.matrix"]
        rocker = ds.rocker_angle.values
        shift[resin] = np.abs(rocker - rocker[0]).max(axis=1)
        if resin == "R914":
            assert np.isnan(rocker[2]).all() and np.isfinite(rocker[:2]).all()
            assert any(n.startswith("crank at t = 2 d") and "wet Tg" in n for n in ds.attrs["notices"])
    assert shift["3502"][2] > shift["8551-7"][2] > shift["8551-7"][1] > 0
