"""Sweep files: validation with file:line reports, grid expansion, Monte Carlo draws,
dotted-path overrides and unit-aware coordinates (no physics run needed)."""
import itertools
import math
import tempfile
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.cli.main import main
from fickcam.errors import SceneError
from fickcam.sweep import load_sweep

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
BASE = (CONFIGS / "singh2017_cam.yaml").read_text()


def write_sweep(folder: Path, text: str, base_text: str = BASE) -> Path:
    (folder / "base.yaml").write_text(base_text)
    path = folder / "sweep.yaml"
    path.write_text(text)
    return path


def problems(path) -> list[str]:
    with pytest.raises(SceneError) as info:
        load_sweep(path)
    return [str(p) for p in info.value.problems]


GRID = """\
base: base.yaml
grid:
  environment.history.0.relative_humidity: [50 %, 65 %, 80 %]
  environment.history.0.temperature: [60 degC, 90 degC]
"""


def test_grid_expands_to_every_combination_with_the_last_key_fastest(tmp_path):
    sweep = load_sweep(write_sweep(tmp_path, GRID))
    assert sweep.kind == "grid"
    pairs = [(c.values["environment.history.0.relative_humidity"],
              c.values["environment.history.0.temperature"]) for c in sweep.cases]
    assert pairs == [("50 %", "60 degC"), ("50 %", "90 degC"), ("65 %", "60 degC"),
                     ("65 %", "90 degC"), ("80 %", "60 degC"), ("80 %", "90 degC")]
    assert [c.index for c in sweep.cases] == list(range(6))


def test_grid_coordinates_are_si_with_units_named_by_netcdf_safe_path(tmp_path):
    sweep = load_sweep(write_sweep(tmp_path, GRID + "  cam.motion.0.dwell: [100 deg, 105 deg]\n"
                                                    "  materials.cfrp.fiber_volume_fraction: [55 %]\n"))
    coords = sweep.coordinates()
    by_path = {p.path: p for p in sweep.parameters}
    rh = by_path["environment.history.0.relative_humidity"]
    assert rh.name == "environment__history__0__relative_humidity" and rh.units == "%"
    np.testing.assert_allclose(np.unique(coords[rh.name]), [50, 65, 80])
    temperature = by_path["environment.history.0.temperature"]
    assert temperature.units == "K"
    np.testing.assert_allclose(np.unique(coords[temperature.name]), [333.15, 363.15])
    dwell = by_path["cam.motion.0.dwell"]
    assert dwell.units == "degree"  # angles leave as degrees, as in every result
    np.testing.assert_allclose(np.unique(coords[dwell.name]), [100, 105])
    fraction = by_path["materials.cfrp.fiber_volume_fraction"]
    assert fraction.units == "1"
    np.testing.assert_allclose(coords[fraction.name], 0.55)


def test_a_case_scene_is_the_base_with_only_the_varied_values_changed(tmp_path):
    sweep = load_sweep(write_sweep(tmp_path, GRID))
    base = yaml.safe_load(BASE)
    scene = sweep.scene_dict(sweep.cases[3])
    assert scene["environment"]["history"][0]["relative_humidity"] == "65 %"
    assert scene["environment"]["history"][0]["temperature"] == "90 degC"
    assert scene.pop("description").startswith("case 3: relative_humidity = 65 %, temperature = 90 degC")
    scene["environment"]["history"][0].update(base["environment"]["history"][0])
    if "description" in base:
        scene["description"] = base["description"]
    assert scene == base
    assert sweep.base_data == base, "building a case must not change the base scene"


MONTE_CARLO = """\
base: base.yaml
samples: 400
seed: {seed}
random:
  environment.history.0.temperature: {{normal: [85 degC, 2 degC]}}
  materials.cfrp.fiber_volume_fraction: {{uniform: [0.55, 0.65]}}
  diffusion.accuracy: {{lognormal: [-7, 0.2]}}
"""


def test_monte_carlo_draws_follow_their_distributions_in_the_given_unit(tmp_path):
    sweep = load_sweep(write_sweep(tmp_path, MONTE_CARLO.format(seed=1)))
    assert sweep.kind == "monte_carlo" and len(sweep.cases) == 400
    raw = [c.values["environment.history.0.temperature"] for c in sweep.cases]
    assert all(isinstance(v, str) and v.endswith(" degC") for v in raw)
    coords = sweep.coordinates()
    kelvin = coords["environment__history__0__temperature"]
    assert abs(kelvin.mean() - 358.15) < 0.4 and abs(kelvin.std() - 2.0) < 0.3
    fraction = coords["materials__cfrp__fiber_volume_fraction"]
    assert fraction.min() >= 0.55 and fraction.max() <= 0.65
    accuracy = coords["diffusion__accuracy"]
    assert (accuracy > 0).all()
    assert abs(np.log(np.median(accuracy)) + 7) < 0.05


def test_monte_carlo_draws_repeat_with_the_same_seed_and_change_with_another(tmp_path):
    first = load_sweep(write_sweep(tmp_path, MONTE_CARLO.format(seed=1))).cases
    again = load_sweep(write_sweep(tmp_path, MONTE_CARLO.format(seed=1))).cases
    other = load_sweep(write_sweep(tmp_path, MONTE_CARLO.format(seed=2))).cases
    assert first == again
    assert first != other


def test_distribution_parameters_in_one_unit_or_bare_with_unit_key(tmp_path):
    text = ("base: base.yaml\nsamples: 3\nrandom:\n"
            "  cam.thickness: {normal: [12, 0.5], unit: mm}\n")
    sweep = load_sweep(write_sweep(tmp_path, text))
    assert all(c.values["cam.thickness"].endswith(" mm") for c in sweep.cases)
    assert sweep.parameters[0].units == "m"
    assert np.all(np.abs(sweep.coordinates()["cam__thickness"] - 0.012) < 0.005)


@pytest.mark.parametrize("text, expected", [
    ("base: base.yaml\ngrid:\n  environment.history.1.relative_humidity: [50 %]\n",
     "sweep.yaml:3 grid.environment.history.1.relative_humidity: not in the base scene: "
     "environment.history is a list of 1 item(s)"),
    ("base: base.yaml\ngrid:\n  cam.colour: [red]\n",
     "sweep.yaml:3 grid.cam.colour: not in the base scene: cam has no key 'colour'"),
    ("base: base.yaml\ngrid:\n  cam: [1]\n",
     "sweep.yaml:3 grid.cam: names a section, not a value"),
    ("base: base.yaml\ngrid:\n  cam.thickness: [1 mm]\nrepeat: 3\n",
     "sweep.yaml:4 repeat: unknown key"),
    ("base: base.yaml\ngrid:\n  cam.thickness: [1 mm]\nsamples: 3\n",
     "sweep.yaml:1: samples goes with random, not with grid"),
    ("base: base.yaml\nrandom:\n  cam.thickness: {normal: [12 mm, 1 mm]}\n",
     "sweep.yaml:1: Monte Carlo draws need samples: N"),
    ("base: base.yaml\nsamples: 2\nrandom:\n  cam.thickness: {normal: [12 mm, 1 K]}\n",
     "sweep.yaml:4 random.cam.thickness.normal: parameters must share one unit"),
    ("base: base.yaml\nsamples: 2\nrandom:\n  cam.thickness: {uniform: [2 mm, 1 mm]}\n",
     "sweep.yaml:4 random.cam.thickness: uniform needs low < high"),
    ("base: base.yaml\nsamples: 2\nrandom:\n  cam.thickness: {gamma: [2, 1]}\n",
     "sweep.yaml:4 random.cam.thickness.gamma: unknown key"),
    ("base: missing.yaml\ngrid:\n  cam.thickness: [1 mm]\n",
     "sweep.yaml:1 base: no such scene file"),
    ("base: base.yaml\ngrid:\n  cam.thickness: []\n",
     "sweep.yaml:2 grid: cam.thickness: give at least one value"),
])
def test_bad_sweep_files_are_reported_by_file_line_and_key(tmp_path, text, expected):
    reported = problems(write_sweep(tmp_path, text))
    assert any(p.endswith(expected) or expected in p for p in reported), reported
    assert all(p.startswith(str(tmp_path / "sweep.yaml")) for p in reported)


def test_an_invalid_base_scene_is_reported_against_the_base_file(tmp_path):
    base = BASE.replace("  thickness: 12 mm\n", "  thickness: 12 mm\n  colour: red\n")
    reported = problems(write_sweep(tmp_path, GRID, base_text=base))
    assert any(p.startswith(f"{tmp_path / 'base.yaml'}:") and "cam.colour: unknown key" in p
               for p in reported), reported


def test_cli_sweep_with_a_bad_file_exits_2_with_one_line_per_problem(tmp_path, capsys):
    path = write_sweep(tmp_path, "base: base.yaml\ngrid:\n  cam.colour: [red]\n  cam.mass: [1 kg]\n")
    assert main(["sweep", str(path), "-o", str(tmp_path / "out.h5")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and err[0].startswith(f"{path}:3 grid.cam.colour:") and \
        err[1].startswith(f"{path}:4 grid.cam.mass:"), err
    assert not (tmp_path / "out.h5").exists() and not (tmp_path / "out.h5.parts").exists()


def test_sweep_identity_changes_with_the_base_scene(tmp_path):
    first = load_sweep(write_sweep(tmp_path, GRID)).identity
    changed = load_sweep(write_sweep(tmp_path, GRID, base_text=BASE.replace("1.6 kg", "1.7 kg"))).identity
    assert first != changed and math.isfinite(len(first))


def test_bare_and_text_values_become_number_or_text_coordinates(tmp_path):
    text = ("base: base.yaml\ngrid:\n  diffusion.accuracy: [1e-3, 0.01]\n"
            "  cam.follower.kind: [roller, knife]\n  outputs.fields: [false]\n")
    sweep = load_sweep(write_sweep(tmp_path, text))
    coords = sweep.coordinates()
    np.testing.assert_allclose(coords["diffusion__accuracy"], [1e-3, 1e-3, 1e-2, 1e-2])
    assert coords["cam__follower__kind"].tolist() == ["roller", "knife"] * 2
    assert coords["outputs__fields"].tolist() == ["False"] * 4


PATHS = ["environment.history.0.relative_humidity", "environment.history.0.temperature",
         "cam.thickness", "materials.cfrp.fiber_volume_fraction"]


@given(st.lists(st.sampled_from(PATHS), min_size=1, max_size=3, unique=True),
       st.lists(st.integers(1, 3), min_size=3, max_size=3))
@settings(max_examples=15, deadline=None)
def test_a_grid_has_each_combination_exactly_once(paths, counts):
    grid = {path: [f"v{path}{k}" for k in range(n)] for path, n in zip(paths, counts)}
    with tempfile.TemporaryDirectory() as folder:
        sweep = load_sweep(write_sweep(Path(folder), yaml.safe_dump({"base": "base.yaml", "grid": grid})))
    combos = [tuple(case.values[p] for p in paths) for case in sweep.cases]
    assert len(combos) == len(set(combos)) == int(np.prod([len(v) for v in grid.values()]))
    assert set(combos) == set(itertools.product(*grid.values()))
