"""Temperature limits of the materials: every library thermoplastic that melts carries its
melting point and a service limit with their sources; a climate at or above the melting
point is refused at its line, one above the service limit is warned once naming the
material and the limit; the same for a scene's own values and for `fickcam fit`."""
from pathlib import Path

import pytest

from fickcam.cli.main import main
from fickcam.materials import MaterialSpec, resolve, temperature_limit_reasons
from fickcam.materials.library import entry, known_names

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
#: the library's semicrystalline thermoplastics: melting point and service limit known
MELTING = {"acetal": (166.0, 103.0), "nylon": (260.0, 75.0)}


@pytest.mark.parametrize("name", sorted(MELTING))
def test_each_semicrystalline_plastic_carries_its_limits_and_their_source(name):
    values = entry("plastics", name)
    melting, service = MELTING[name]
    assert values["melting_temperature"] - 273.15 == pytest.approx(melting)
    assert values["heat_deflection_temperature"] - 273.15 == pytest.approx(service)
    text = " ".join(values["sources"].split())
    assert f"{melting:g} degC" in text and f"{service:g} degC at 1.80 MPa" in text
    assert "data sheet" in text


def test_a_plastic_without_a_known_limit_says_so():
    assert set(known_names("plastics")) - set(MELTING) == {"polyimide"}
    values = entry("plastics", "polyimide")
    assert "melting_temperature" not in values and "heat_deflection_temperature" not in values
    assert "does not melt" in values["sources"] and "service_temperature" in values["sources"]


def _scene(tmp_path, temperature: str, material: str = "{plastic: nylon}") -> Path:
    text = (CONFIGS / "eccentric_cam.yaml").read_text()
    text = text.replace("temperature: 40 degC", f"temperature: {temperature}")
    text = text.replace("nylon: {plastic: nylon}", f"nylon: {material}")
    path = tmp_path / "hot.yaml"
    path.write_text(text)
    return path


def _line(path: Path, fragment: str) -> int:
    return next(i for i, line in enumerate(path.read_text().splitlines(), 1) if fragment in line)


def test_a_nylon_cam_above_its_service_limit_is_warned_once(tmp_path, capsys):
    path = _scene(tmp_path, "250 degC")
    assert main(["check", str(path)]) == 0
    err = capsys.readouterr().err
    warning = (f"{path}:{_line(path, 'temperature: 250 degC')} environment.history.0.temperature: "
               f"250.0 degC is above the heat deflection temperature (1.80 MPa) of material "
               f"'nylon' (75.0 degC)")
    assert err.count(warning) == 1, err


def test_a_nylon_cam_at_its_melting_point_is_refused_at_the_climate_line(tmp_path, capsys):
    path = _scene(tmp_path, "260 degC")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"{path}:{_line(path, 'temperature: 260 degC')} environment.history.0.temperature: "
                   f"260.0 degC is at or above the melting point of material 'nylon' (260.0 degC)")


def test_a_scene_s_own_limits_are_held_like_the_library_s(tmp_path, capsys):
    own = "{plastic: polyimide, melting_temperature: 300 degC, service_temperature: 200 degC}"
    assert main(["check", str(_scene(tmp_path, "150 degC", own))]) == 0
    assert "service temperature" not in capsys.readouterr().err
    assert main(["check", str(_scene(tmp_path, "250 degC", own))]) == 0
    assert ("250.0 degC is above the maximum continuous service temperature of material 'nylon' "
            "(200.0 degC)") in capsys.readouterr().err
    path = _scene(tmp_path, "300 degC", own)
    assert main(["check", str(path)]) == 2
    assert "at or above the melting point of material 'nylon' (300.0 degC)" in capsys.readouterr().err


def test_a_service_temperature_wins_over_the_heat_deflection_temperature():
    material = resolve("pa", MaterialSpec.model_validate(
        {"plastic": "nylon", "service_temperature": 393.15}))
    refusals, warnings = temperature_limit_reasons(material, "pa", 373.15)
    assert refusals == [] and warnings == []
    refusals, warnings = temperature_limit_reasons(material, "pa", 403.15)
    assert refusals == [] and "maximum continuous service temperature" in warnings[0]


def test_the_new_keys_describe_themselves():
    for key in ("melting_temperature", "service_temperature", "heat_deflection_temperature"):
        assert MaterialSpec.model_fields[key].description


def test_fit_refuses_coupons_aged_above_the_matrix_dry_tg(tmp_path, capsys):
    text = (CONFIGS / "weight_gain_synthetic_epoxy.csv").read_text().splitlines()
    rows = [line.replace("T85-RH85-1,85,", "T85-RH85-1,160,") for line in text]
    path = tmp_path / "hot.csv"
    path.write_text("\n".join(rows) + "\n")
    first = next(i for i, line in enumerate(rows, 1) if line.startswith("T85-RH85-1,160,"))
    assert main(["fit", str(path), "--matrix", "8551-7", "-o", str(tmp_path / "f.yaml")]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"{path}:{first} temperature: specimen 'T85-RH85-1': 160.0 degC is at or above "
                   f"the dry Tg of material '8551-7' (157.0 degC)")
    assert not (tmp_path / "f.yaml").exists()
