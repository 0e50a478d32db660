"""Small things a user expects: one material in full, the example scenes, a description
and an example in every --help, sweep cases named by their values and tabled after the run."""
import argparse
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from fickcam.scene import examples as example_scenes
from fickcam.cli.main import main
from fickcam.cli.parser import build_parser
from fickcam.results.query import format_result, select
from fickcam.cli.reporting import sweep_summary
from fickcam.sweep.spec import load_sweep

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "configs"


def test_materials_name_shows_the_laws_and_sources(capsys):
    assert main(["materials", "8551-7"]) == 0
    out = capsys.readouterr().out
    assert "D0 = 2.3e-05 m2/s, Ea = 45 kJ/mol" in out
    assert "Mm = a (RH/100)^b: a = 2 %, b = 1" in out
    assert 'sources: Em, nu_m, rho_m, Tgd: Singh & Sanyal (2017, "Kinematic' in out
    assert "157 degC" in out  # dry Tg 430.15 K
    assert main(["materials", "unobtainium"]) == 2


def test_examples_lists_prints_and_copies_every_scene(tmp_path, capsys):
    shipped = sorted(p.name for p in CONFIGS.glob("*.yaml"))
    assert sorted(p.name for p in example_scenes.folder().glob("*.yaml")) == shipped
    assert main(["examples"]) == 0
    listing = capsys.readouterr().out
    assert all(Path(name).stem in listing for name in shipped)
    assert main(["examples", "singh2017_cam"]) == 0
    assert capsys.readouterr().out == (CONFIGS / "singh2017_cam.yaml").read_text()
    assert main(["examples", "--copy", str(tmp_path / "scenes")]) == 0
    assert sorted(p.name for p in (tmp_path / "scenes").glob("*.yaml")) == shipped
    assert main(["check", str(tmp_path / "scenes" / "yadav2017_cam.yaml")]) == 0
    assert main(["examples", "--copy", str(tmp_path / "scenes")]) == 2  # never overwrites


def test_examples_are_packaged_in_the_wheel():
    text = (ROOT / "pyproject.toml").read_text()
    assert '"examples/*.yaml"' in text
    assert example_scenes.folder().resolve() == CONFIGS.resolve()


def test_every_subcommand_help_has_a_description_and_an_example():
    parser = build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, sub in commands.choices.items():
        assert sub.description and len(sub.description) > 30, name
        assert sub.epilog and sub.epilog.startswith("examples:\n  fickcam " + name), name


def test_sweep_cases_are_described_by_their_values():
    sweep = load_sweep(CONFIGS / "sweep_singh2017_climate.yaml")
    case = sweep.cases[4]
    description = sweep.scene_dict(case)["description"]
    assert description.startswith("case 4: relative_humidity = 65 %, temperature = 85 degC")


def sweep_result() -> xr.Dataset:
    """A two-case sweep result as `fickcam sweep` writes it (temperatures given in degC)."""
    days = np.array([0.0, 30.0])  # ageing time [d]
    lift = np.array([[38.3, 38.35], [38.4, 38.5]]) * 1e-3
    return xr.Dataset(
        {"lift": (("case", "time"), lift, {"units": "m"}),
         "lift_design": (("case",), [38.1e-3, 38.1e-3], {"units": "m"})},
        coords={"case": [0, 1], "time": days,
                "environment__history__0__temperature": (
                    "case", [333.15, 358.15],
                    {"units": "K", "given_units": "degC",
                     "dotted_path": "environment.history.0.temperature"}),
                "case_status": ("case", np.array(["ok", "ok"], dtype=object))},
        attrs={"scene_name": "cam", "failed_cases": 0})


def test_sweep_summary_tables_each_case_in_the_users_units():
    text = sweep_summary(sweep_result())
    header, first, second = text.splitlines()[1:4]
    assert "temperature [degC]" in header and "lift [mm]" in header
    assert first.split()[:3] == ["0", "60", "ok"] and "38.35 (+0.25)" in first
    assert second.split()[:3] == ["1", "85", "ok"] and "38.5 (+0.4)" in second


def test_query_on_a_sweep_shows_the_varied_values():
    out = format_result(select(sweep_result(), "lift", time="30 d"), "lift", "csv")
    lines = out.splitlines()
    assert lines[0].split(",")[:3] == ["time [d]", "case", "temperature [degC]"]
    assert [float(line.split(",")[2]) for line in lines[1:]] == pytest.approx([60, 85])
