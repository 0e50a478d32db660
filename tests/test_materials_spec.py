"""MaterialSpec validation, library overrides, resolve and the library listing."""
import pytest
from pydantic import ValidationError

from fickcam.materials import MaterialSpec, library_rows, library_table, resolve


def test_unknown_fiber_lists_known_names():
    with pytest.raises(ValidationError) as info:
        MaterialSpec(fiber="T999", matrix="8551-7", fiber_volume_fraction=0.6)
    message = str(info.value)
    assert "unknown fiber 'T999'" in message and "T300" in message and "Kevlar49" in message


def test_unknown_matrix_and_unknown_key_fail():
    with pytest.raises(ValidationError, match="known: 3502"):
        MaterialSpec(matrix="epoxy")
    with pytest.raises(ValidationError, match="Extra inputs"):
        MaterialSpec(matrix="R914", colour="red")


@pytest.mark.parametrize("kwargs", [
    {"fiber": "T300", "matrix": "8551-7"},                                   # no fraction
    {"fiber": "T300", "matrix": "8551-7", "fiber_volume_fraction": 0.6, "fiber_weight_fraction": 0.7},
    {"matrix": "R914", "metal": "steel"},                                    # two kinds
    {"fiber": "T300", "fiber_volume_fraction": 0.6},                         # fibre without matrix
    {"matrix": "R914", "layup": "quasi_isotropic"},                          # layup needs fibres
    {"metal": "steel", "moisture_expansion": 1e-3},                          # metals take no moisture
    {"fiber": "T300", "matrix": "8551-7", "fiber_volume_fraction": 0.7, "void_volume_fraction": 0.3},
])
def test_inconsistent_specs_are_rejected(kwargs):
    with pytest.raises(ValidationError):
        MaterialSpec(**kwargs)


def test_overrides_with_units_reach_the_material():
    spec = MaterialSpec(matrix="R914", diffusivity={"pre_exponential": "5e-4 m^2/s",
                                                   "activation_energy": "40 kJ/mol"},
                        saturation={"coefficient": "6 %", "exponent": 1.5},
                        youngs_modulus="3 GPa", dry_glass_transition_temperature="180 degC")
    material = resolve("r", spec)
    d = material.diffusivity_for(None)
    assert d.pre_exponential == (5e-4, 5e-4, 5e-4) and d.activation_energy == 40e3
    assert material.saturation_moisture(300.0, 50.0) == pytest.approx(6 * 0.5 ** 1.5)
    assert material.matrix["youngs_modulus"] == 3e9
    assert material.dry_glass_transition_temperature == pytest.approx(453.15)
    assert "overridden in the scene" in material.sources[-1]


def test_composite_constituent_overrides():
    spec = MaterialSpec(fiber="T300", matrix="8551-7", fiber_volume_fraction=0.6,
                        fiber_properties={"longitudinal_modulus": "230 GPa"},
                        matrix_properties={"youngs_modulus": "4 GPa"})
    p = resolve("c", spec).ply_properties(1.0)
    assert float(p["e11"]) == pytest.approx(0.6 * 230e9 + 0.4 * 4e9)


def test_library_table_lists_every_material_with_sources():
    text = library_table()
    for name in ("T300", "Kevlar49", "boron", "8551-7", "3502", "R914", "PMR-15", "acetal",
                 "nylon", "polyimide", "steel", "aluminium"):
        assert name in text
    assert all(row["sources"] for row in library_rows())
    assert "Singh & Sanyal (2017" in text and "ASSUMPTION" in text
