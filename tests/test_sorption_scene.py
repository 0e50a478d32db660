"""``materials.NAME.sorption``: parsed with units, refused with a line and a key path,
and a two-phase material gives total moisture plus ``bound_moisture_content``."""
from pathlib import Path

import numpy as np
import pytest
import yaml

import fickcam
from fickcam.cli.main import main

DEMO = (Path(__file__).resolve().parents[1] / "configs" / "singh2017_cam.yaml").read_text()
SCENE = (DEMO.split("limits:")[0]
         .replace("    layup: unidirectional\n", "    layup: unidirectional\n  epoxy:\n"
                  "    matrix: \"3502\"\n    sorption: {model: langmuir, binding_rate: 0.02 1/d, "
                  "release_rate: {pre_exponential: 0.05 1/d}}\n")
         .replace("    material: cfrp", "    material: epoxy")
         .replace("duration: 60 d", "duration: 30 d").replace("113 degC", "60 degC")
         .replace("accuracy: 1e-3", "accuracy: 1e-2")
         + "outputs:\n  ageing_times: [0 d, 10 d, 30 d]\n  angle_step: 10 deg\n")


def test_langmuir_material_reads_rates_in_any_unit():
    scene = fickcam.load_scene(yaml.safe_load(SCENE))
    law = scene.materials["epoxy"].sorption_law()
    assert law.binding.pre_exponential == pytest.approx(0.02 / 86400.0)
    assert law.release.pre_exponential == pytest.approx(0.05 / 86400.0)
    assert float(law.free_share(300.0)) == pytest.approx(0.05 / 0.07)


@pytest.mark.parametrize("old, new, key, reason", [
    ("release_rate: {pre_exponential: 0.05 1/d}", "release_rate: 0.05 m",
     "materials.epoxy.sorption.release_rate.pre_exponential", "dimension"),
    ("model: langmuir,", "model: langmuir, exponent: 2,", "materials.epoxy.sorption", "takes no exponent"),
    ("model: langmuir, binding_rate: 0.02 1/d,", "model: langmuir,", "materials.epoxy.sorption",
     "needs binding_rate and release_rate"),
    ("model: langmuir,", "model: langmuir, speed: 1,", "materials.epoxy.sorption.speed", ""),
    ("model: langmuir,", "model: henry,", "materials.epoxy.sorption.model", ""),
])
def test_bad_sorption_keys_are_refused_with_line_and_key(tmp_path, capsys, old, new, key, reason):
    path = tmp_path / "scene.yaml"
    path.write_text(SCENE.replace(old, new))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    line = next(n for n, text in enumerate(SCENE.splitlines(), 1) if "sorption:" in text)
    assert any(e.startswith(f"{path}:{line} {key}") and reason in e for e in err), err


def test_run_reports_total_and_bound_moisture_of_a_two_phase_part():
    ds = fickcam.run(fickcam.load_scene(yaml.safe_load(SCENE)))
    follower = ds.sel(part="follower")
    bound = follower.bound_moisture_content.values
    total = follower.moisture_content.values
    assert np.all(np.isfinite(bound)) and np.all(bound[1:] > 0) and np.all(bound[1:] < total[1:])
    assert np.all(np.isnan(ds.sel(part="cam").bound_moisture_content.values))
    mass = follower.mass.values
    assert mass[-1] / mass[0] - 1.0 == pytest.approx(total[-1] / 100.0, rel=1e-9)
