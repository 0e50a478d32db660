"""The run pipeline as a user meets it: scene → run → result file → query/plot."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

import fickcam
from fickcam.cli.main import main
from fickcam.schema import VARIABLES

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "configs"


def mild_fourbar() -> dict:
    """Singh & Sanyal 2016's R914 four-bar at 60 degC / 85 % RH (well below its wet Tg)."""
    scene = yaml.safe_load((CONFIGS / "singh2016_fourbar.yaml").read_text())
    scene["environment"]["history"] = [{"duration": "90 d", "temperature": "60 degC",
                                        "relative_humidity": "85 %"}]
    scene["outputs"].pop("file")
    scene["outputs"]["ageing_times"] = ["0 d", "1 d", "7 d", "30 d", "90 d"]
    return scene


@pytest.fixture(scope="module")
def fourbar(tmp_path_factory):
    path = tmp_path_factory.mktemp("run") / "fourbar.h5"
    ds = fickcam.run(fickcam.load_scene(mild_fourbar()))
    fickcam.save(ds, path)
    return fickcam.open_result(path)


def test_import_fickcam_stays_light():
    code = ("import sys, fickcam; heavy = [m for m in ('fipy', 'matplotlib', 'dask', 'distributed') "
            "if m in sys.modules]; print(heavy); sys.exit(1 if heavy else 0)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr


def test_readme_starts_with_the_two_commands_and_links_every_variable():
    text = (ROOT / "README.md").read_text()
    lines = text.splitlines()
    assert lines[3].endswith("fickcam run configs/singh2017_cam.yaml") and "pip install" in lines[3]
    assert "&& pytest" in lines[4] and 'pip install -e ".[test]"' in lines[4]
    assert len(lines) <= 250
    # the variable table is generated into the docs when they build
    # (tests/test_docs_reference.py checks the generator)
    assert "(docs/reference/results.md)" in text


@pytest.mark.slow
def test_result_variables_follow_the_schema(fourbar):
    for name in fourbar.data_vars:
        var = VARIABLES[name]
        assert fourbar[name].dims == var.dims
        assert fourbar[name].attrs["units"] == (var.units or "1")
        assert fourbar[name].attrs["long_name"] == var.long_name


def test_sections_a_scene_omits_are_absent(fourbar):
    cam_only = [n for n, v in VARIABLES.items() if v.section == "cam"]
    assert not any(n in fourbar for n in cam_only)
    assert "cam_angle" not in fourbar.dims and "moisture" not in fourbar


def test_result_attributes_record_version_scene_diffusion_and_wall_time(fourbar):
    attrs = fourbar.attrs
    assert attrs["fickcam_version"] == fickcam.__version__
    assert "R914" in attrs["scene_text"]
    assert set(attrs["diffusion"]) == set(fourbar.part.values.tolist())
    for part, info in attrs["diffusion"].items():
        assert {"model", "error_estimate", "cells", "steps"} <= set(info)
    assert float(attrs["wall_time_s"]) > 0


def test_ageing_time_is_in_days(fourbar):
    assert fourbar.time.dtype.kind == "f" and fourbar.time.attrs["units"] == "d"
    assert float(fourbar.moisture_content.sel(part="crank", time=30)) == pytest.approx(
        float(fourbar.moisture_content.sel(part="crank").values[3]))


def test_moisture_rises_towards_saturation_and_mass_follows(fourbar):
    m = fourbar.moisture_content.sel(part="crank").values
    assert m[0] == 0 and np.all(np.diff(m) > 0)
    sat = fourbar.equilibrium_moisture_content.sel(part="crank").values
    assert np.all(m <= sat + 1e-9)
    mass = fourbar.mass.sel(part="crank").values
    assert np.allclose(mass, mass[0] * (1 + m / 100), rtol=1e-12)


def test_metal_frame_takes_up_no_moisture(fourbar):
    assert np.all(fourbar.moisture_content.sel(part="frame").values == 0)


@pytest.mark.slow
def test_cli_run_query_export_plot_round_trip(tmp_path, capsys):
    out = tmp_path / "r.h5"
    scene = tmp_path / "scene.yaml"
    scene.write_text(yaml.safe_dump(mild_fourbar()))
    assert main(["run", str(scene), "-o", str(out), "--quiet"]) == 0
    assert main(["query", str(out), "moisture_content", "--time", "15 d", "--part", "coupler",
                 "--format", "json"]) == 0
    assert '"moisture_content"' in capsys.readouterr().out
    assert main(["export", str(out), "--format", "csv", "-o", str(tmp_path / "r.csv")]) == 0
    assert main(["plot", str(out), "-o", str(tmp_path / "plots"), "--kind", "uptake"]) == 0
    assert (tmp_path / "plots" / "uptake.png").stat().st_size > 10_000


def test_rerun_of_an_unreadable_result_path_is_a_clear_error(tmp_path, capsys):
    bad = tmp_path / "junk.h5"
    bad.write_text("not hdf5")
    assert main(["query", str(bad), "mass"]) == 2
    err = capsys.readouterr().err
    assert "not a fickcam result" in err and "Traceback" not in err
