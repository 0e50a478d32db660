"""Material state over ageing: wet Tg, retention, strain, density, the wet-Tg stop."""
import pickle

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.errors import PhysicsDomainError
from fickcam.materials import MaterialSpec, first_invalid_index, material_state, resolve
from fickcam.materials.hygrothermal import (
    KELVIN_OFFSET,
    property_retention,
    secant_thermal_factor,
    wet_glass_transition_temperature,
    wet_mass,
)

C = KELVIN_OFFSET
T0 = 23 + C


def resin(name="8551-7", **overrides):
    return resolve(name, MaterialSpec(matrix=name, **overrides))


def saturated_history(material, temperature_c, rh, n=5):
    temperature = np.full(n, temperature_c + C)
    sat = material.saturation_moisture(temperature, rh)
    return temperature, sat


def test_saturated_neat_resin_follows_chamis_formulas_exactly():
    material = resin("8551-7")
    temperature, m = saturated_history(material, 80.0, 80.0)
    state = material_state(material, temperature, m, m, T0, 0.0)
    assert np.allclose(m, 2.0 * 0.8)  # Mm = a (RH/100)^b, a = 2 %, b = 1
    tgd_c = 157.0
    tgw_c = (0.005 * 1.6 ** 2 - 0.1 * 1.6 + 1) * tgd_c
    assert np.allclose(state["glass_transition_temperature"], tgw_c + C)
    retention = np.sqrt((tgw_c - 80.0) / (tgd_c - 23.0))
    assert np.allclose(state["property_retention"], retention)
    assert np.allclose(state["longitudinal_modulus"], 3.45e9 * retention)
    assert np.allclose(state["surface_modulus"], 3.45e9 * retention)
    # thermal properties: reciprocal (Chamis 1983); the free strain integrates that
    # instantaneous alpha from T0 to T: alpha_sec = 2 sqrt(Tgd-T0)(sqrt(Tgw-T0)-sqrt(Tgw-T))/(T-T0)
    assert np.allclose(state["thermal_expansion_longitudinal"], 46.7e-6 / retention)
    secant = 2 * np.sqrt(tgd_c - 23) * (np.sqrt(tgw_c - 23) - np.sqrt(tgw_c - 80)) / (80 - 23)
    strain = 46.7e-6 * secant * (80.0 - 23.0) + 3.09e-3 * 1.6
    assert np.allclose(state["hygrothermal_strain"], strain)
    assert np.allclose(state["strain_through_thickness"], strain)
    assert np.allclose(state["mass_ratio"], 1.016)
    assert np.allclose(state["density"], 1300 * 1.016 / (1 + strain) ** 3)
    assert state["within_wet_tg"].all()


def test_secant_thermal_factor_integrates_the_reciprocal_rule():
    from scipy.integrate import quad

    tgd, tgw, t0 = 157 + C, 140 + C, T0
    for t in (T0 - 10, T0 + 1e-12, 60 + C, 139.9 + C):
        inst = lambda x: 1 / property_retention(tgw, x, tgd, t0)
        expected = quad(inst, t0, t, limit=200)[0] / (t - t0) if abs(t - t0) > 1e-6 else inst(t0)
        assert float(secant_thermal_factor(tgw, t, tgd, t0)) == pytest.approx(expected, rel=1e-6)
    assert np.isnan(secant_thermal_factor(tgw, tgw + 1, tgd, t0))


def test_wet_tg_scale_is_an_option():
    celsius = wet_glass_transition_temperature(157 + C, 2.0, "celsius")
    fahrenheit = wet_glass_transition_temperature(157 + C, 2.0, "fahrenheit")
    kelvin = wet_glass_transition_temperature(157 + C, 2.0, "kelvin")
    factor = 0.005 * 4 - 0.2 + 1
    assert celsius == pytest.approx(157 * factor + C)
    assert fahrenheit == pytest.approx(((157 * 1.8 + 32) * factor - 32) / 1.8 + C)
    assert kelvin == pytest.approx((157 + C) * factor)
    state = material_state(resin(wet_tg_scale="fahrenheit"), np.array([300.0]), 2.0 / 0.8 * 0.8,
                           2.0, T0, 0.0)
    assert state["glass_transition_temperature"][0] == pytest.approx(fahrenheit)


def test_heating_past_wet_tg_stops_with_time_and_values_and_keeps_earlier_results():
    material = resin("R914")
    times = np.array([0.0, 86400.0, 2 * 86400.0, 3 * 86400.0])
    temperature = np.array([100, 100, 145, 150]) + C
    m = np.array([0.0, 2.0, 3.0, 4.0])
    with pytest.raises(PhysicsDomainError) as info:
        material_state(material, temperature, m, m, T0, 0.0, part="crank", times=times,
                       raise_on_wet_tg=True)
    error = info.value
    tgw = wet_glass_transition_temperature(190 + C, 3.0) - C
    assert error.part == "crank" and error.time == 2 * 86400.0 and error.index == 2
    assert "145.0 degC" in str(error) and f"{tgw:.1f} degC" in str(error) and "2 d" in str(error)
    kept = error.state
    assert kept["longitudinal_modulus"].shape == (2,)
    assert np.isfinite(kept["longitudinal_modulus"]).all()
    state = material_state(material, temperature, m, m, T0, 0.0, part="crank", times=times)
    assert list(state["within_wet_tg"]) == [True, True, False, False]
    assert first_invalid_index(temperature, state["glass_transition_temperature"]) == 2


def test_surface_moisture_reaching_wet_tg_first_also_stops():
    material = resin("R914")
    temperature = np.array([110.0, 110.0]) + C
    state = material_state(material, temperature, np.array([1.0, 1.0]), np.array([1.0, 6.5]), T0, 0.0)
    assert list(state["within_wet_tg"]) == [True, False]
    assert state["surface_longitudinal_modulus"][0] == pytest.approx(state["longitudinal_modulus"][0])


def test_metal_has_thermal_strain_only_and_no_tg():
    steel = resolve("steel", MaterialSpec(metal="steel"))
    state = material_state(steel, np.array([T0, T0 + 90]), 0.0, 0.0, T0, 0.0)
    assert np.allclose(state["hygrothermal_strain"], [0.0, 12e-6 * 90])
    assert np.isnan(state["glass_transition_temperature"]).all()
    assert np.allclose(state["longitudinal_modulus"], 200e9)
    assert not steel.absorbs and steel.diffusivity_for(None).pre_exponential == (0.0, 0.0, 0.0)


def test_composite_strain_is_longitudinal_along_x_and_transverse_across():
    cfrp = resolve("c", MaterialSpec(fiber="T300", matrix="8551-7", fiber_volume_fraction=0.6))
    state = material_state(cfrp, np.array([113 + C]), np.array([0.5]), np.array([0.5]), T0, 0.0)
    assert abs(state["strain_longitudinal"][0]) < 1e-4 < state["strain_transverse"][0]
    assert state["transverse_modulus"][0] < state["surface_modulus"][0] < state["longitudinal_modulus"][0]
    assert np.allclose(state["mass_ratio"], 1.005)


def test_material_is_picklable():
    cfrp = resolve("c", MaterialSpec(fiber="T300", matrix="8551-7", fiber_volume_fraction=0.6))
    clone = pickle.loads(pickle.dumps(cfrp))
    assert clone == cfrp and clone.diffusivity_for(None) == cfrp.diffusivity_for(None)


# ---------------------------------------------------------------- invariants

moisture = st.floats(0.0, 10.0)
service = st.floats(0.0, 80.0)


@settings(max_examples=60, deadline=None)
@given(moisture, moisture, service)
def test_wet_tg_decreases_with_moisture_below_10_percent(m1, m2, t):
    low, high = sorted((m1, m2))
    tg = wet_glass_transition_temperature(157 + C, np.array([low, high]))
    assert tg[1] <= tg[0] + 1e-12


@settings(max_examples=60, deadline=None)
@given(moisture, moisture, service, service)
def test_retention_in_unit_interval_and_decreasing_in_moisture_and_temperature(m1, m2, t1, t2):
    material = resin("3502")  # Tgd 210 degC: 80 degC stays below any wet Tg for M <= 10 %
    m = np.array(sorted((m1, m2)))
    temperature = np.array(sorted((t1, t2))) + 23 + C
    tgd = material.dry_glass_transition_temperature
    for t in temperature:
        r = property_retention(wet_glass_transition_temperature(tgd, m), t, tgd, T0)
        assert np.all((r >= 0) & (r <= 1 + 1e-12)) and r[1] <= r[0] + 1e-12
    for mm in m:
        r = property_retention(wet_glass_transition_temperature(tgd, mm), temperature, tgd, T0)
        assert r[1] <= r[0] + 1e-12


@settings(max_examples=40, deadline=None)
@given(st.floats(0.0, 30.0), st.floats(0.0, 30.0), st.floats(1e-3, 10.0))
def test_mass_monotone_in_moisture(m1, m2, dry):
    low, high = sorted((m1, m2))
    assert wet_mass(dry, low) <= wet_mass(dry, high)


# BASF Ultramid A3K (unreinforced PA66) data sheet, ISO 527 tensile modulus:
# 3000 MPa dry-as-moulded, 1100 MPa conditioned (equilibrium at 23 degC / 50 % RH)
PA66_DRY, PA66_CONDITIONED = 3000e6, 1100e6


def test_nylon_modulus_falls_to_the_conditioned_data_sheet_value():
    """Water plasticises PA66: at the library's 50 % RH equilibrium moisture the modulus is
    the data sheet's conditioned fraction of the dry one (well below half), and every
    property the retention touches follows (E, G; thermal properties by P0/P)."""
    nylon = resolve("nylon", MaterialSpec(plastic="nylon"))
    assert float(nylon.saturation_moisture(T0, 50.0)) == pytest.approx(2.5, rel=1e-2)
    conditioned = 2.5  # weight %, PA66 at equilibrium with 23 degC / 50 % RH
    moisture = np.array([0.0, conditioned / 2, conditioned, 6.0])
    state = material_state(nylon, np.full(4, T0), moisture, moisture, T0, 0.0)
    retention = state["property_retention"]
    assert retention[0] == 1.0
    assert retention[2] == pytest.approx(PA66_CONDITIONED / PA66_DRY, rel=1e-3)
    assert retention[2] < 0.5 and retention[1] == pytest.approx((1 + retention[2]) / 2, rel=1e-12)
    assert retention[3] == retention[2]  # no data beyond the conditioned state: held
    dry_modulus = nylon.matrix["youngs_modulus"]
    np.testing.assert_allclose(state["longitudinal_modulus"], dry_modulus * retention, rtol=1e-12)
    np.testing.assert_allclose(state["surface_modulus"], dry_modulus * retention, rtol=1e-12)
    np.testing.assert_allclose(state["shear_modulus"] / state["longitudinal_modulus"],
                               1 / (2 * (1 + nylon.matrix["poisson_ratio"])), rtol=1e-12)
    alpha = state["thermal_expansion_longitudinal"]
    assert alpha[2] > alpha[0]  # Chamis: thermal properties scale by P0/P
    assert np.isnan(state["glass_transition_temperature"]).all()
    assert state["within_wet_tg"].all()  # a thermoplastic is not stopped at a wet Tg


def test_acetal_keeps_its_modulus_when_wet():
    """POM data sheets give one modulus dry and conditioned: its table is flat."""
    acetal = resolve("acetal", MaterialSpec(plastic="acetal"))
    moisture = np.array([0.0, 0.2, 0.8])
    state = material_state(acetal, np.full(3, T0), moisture, moisture, T0, 0.0)
    np.testing.assert_array_equal(state["property_retention"], 1.0)
