"""Bare numbers that are almost certainly unit slips are refused (or warned about) at their
key's line with the likely unit, judged against their own part; plausible bare values,
values with units and every shipped scene pass silently."""
import math
import re
import subprocess
import sys
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from fickcam.cli.main import main
from fickcam.errors import SceneError
from fickcam.materials.library import find_entry, library_table
from fickcam.quantities.plausibility import (CAM_MEMBERS, CAM_RADIUS, LENGTH_ALTERNATIVES, Band, Reading,
                                  Verdict, bare_judgement, plate_uptake)
from fickcam.scene.load import load_scene
from fickcam.quantities.parsing import to_si

EXAMPLES = Path(str(resources.files("fickcam") / "examples"))
SCENES = sorted(p for p in EXAMPLES.glob("*.yaml") if not p.name.startswith("sweep_"))


def _scene(tmp_path, example: str, old: str, new: str) -> Path:
    text = (EXAMPLES / example).read_text()
    assert old in text, f"{old!r} not in {example}"
    path = tmp_path / example
    path.write_text(text.replace(old, new, 1))
    for extra in EXAMPLES.glob("*.csv"):
        (tmp_path / extra.name).write_text(extra.read_text())
    return path


def _line_of(path: Path, fragment: str) -> int:
    return next(n for n, line in enumerate(path.read_text().splitlines(), 1) if fragment in line)


SLIPS = [
    # example, old, new, key, suggested
    ("eccentric_cam.yaml", "thickness: 10 mm", "thickness: 12", "cam.thickness", "12 mm"),
    ("eccentric_cam.yaml", "roller_radius: 10 mm", "roller_radius: 8", "cam.follower.roller_radius", "8 mm"),
    ("eccentric_cam.yaml", "duration: 180 d", "duration: 730", "environment.history.0.duration", "730 d"),
    ("eccentric_cam.yaml", "every: 30 d", "every: 30", "outputs.ageing_times.every", "30 d"),
    ("singh2017_cam.yaml", "base_circle_radius: 1.94 in", "base_circle_radius: 25",
     "cam.base_circle_radius", "25 mm"),
    ("singh2017_cam.yaml", "{rise: 1.5 in,", "{rise: 38,", "cam.motion.1.rise", "38 mm"),
    ("singh2017_cam.yaml", "[0 d, 1 d, 7 d, 30 d, 60 d]", "[0, 1, 7, 30, 60]",
     "outputs.ageing_times.4", "60 d"),
    ("singh2016_fourbar.yaml", "crank: 100 mm", "crank: 100", "linkage.crank", "100 mm"),
    ("singh2016_fourbar.yaml", "thickness: 10 mm,", "thickness: 10,", "linkage.section.thickness", "10 mm"),
    ("singh2017_cam.yaml", "dwell: 105 deg", "dwell: 105", "cam.motion.0.dwell", "105 deg"),
    ("nylon_swinging_arm.yaml", "{rise: 20 deg,", "{rise: 20,", "cam.motion.1.rise", "20 deg"),
    ("singh2017_cam_compensated.yaml", "base_circle_radius: 1.94 in", "base_circle_radius: 49",
     "design.cam.base_circle_radius", "49 mm"),
    ("singh2017_cam.yaml", "{deviation: 0.25 mm}", "{deviation: 0.25}",
     "limits.follower_displacement.deviation", "0.25 mm"),
    ("fourbar_r914_humid.yaml", "coupler_point_x: {deviation: 1 mm}", "coupler_point_x: {deviation: 1}",
     "limits.coupler_point_x.deviation", "1 mm"),
]


@pytest.mark.parametrize("example, old, new, key, meant", SLIPS, ids=[s[3] for s in SLIPS])
def test_a_unit_slip_is_refused_at_its_key_with_the_likely_unit(tmp_path, capsys, example, old,
                                                                new, key, meant):
    path = _scene(tmp_path, example, old, new)
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    line = _line_of(path, new.rstrip(","))
    assert re.match(rf"^{re.escape(str(path))}:{line} {re.escape(key)}: .*implausible.*"
                    rf"did you mean '{re.escape(meant)}'\?", err), err
    assert len(err.splitlines()) == 1, err  # the cause alone, not what it breaks downstream


def test_values_that_are_no_numbers_are_refused_by_their_section_not_judged(tmp_path, capsys):
    path = _scene(tmp_path, "singh2016_fourbar.yaml", "crank: 100 mm", "crank: [1]")
    text = path.read_text().replace("thickness: 10 mm,", "thickness: -10,").replace(
        "    - dwell: 105 deg", "    - 7")
    path.write_text(text)
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "linkage.crank: expected a number" in err
    assert "implausible" not in err


def test_a_slipped_history_is_named_not_the_output_step_it_breaks(tmp_path, capsys):
    path = _scene(tmp_path, "eccentric_cam.yaml", "duration: 180 d", "duration: 730")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "environment.history.0.duration" in err and "ageing_times" not in err


def test_an_unusual_duration_is_named_when_the_output_times_do_not_fit_it(tmp_path, capsys):
    """1000 s of 85 degC / 85 % RH lets the 10 mm nylon disc take up about 3 % of its
    equilibrium moisture: unusual, not refused; but a 100 h step does not fit in it."""
    path = _scene(tmp_path, "eccentric_cam.yaml", "  history:\n    - {duration: 180 d, temperature: "
                  "40 degC, relative_humidity: 90 %}", "  test: damp_heat_85_85\n  duration: 1000")
    path.write_text(path.read_text().replace("every: 30 d", "every: 100 h"))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert f":{_line_of(path, 'duration: 1000')} environment.duration: 1000 s is an unusual" in err
    assert "did you mean '1000 h'?" in err and "ageing_times" not in err


BARE_SPEEDS = [
    # example, old, new, key: rad/s and rpm are both common, a factor of 9.55 apart
    ("singh2017_cam.yaml", "speed: 600 rpm", "speed: 200", "cam.speed"),
    ("eccentric_cam.yaml", "speed: 300 rpm", "speed: 31.4", "cam.speed"),  # 300 rpm in rad/s
    ("singh2016_fourbar.yaml", "crank_speed: 100 rpm", "crank_speed: 600", "linkage.crank_speed"),
    ("singh2017_cam.yaml", "{min: 1000 rpm}", "{min: 1000}", "limits.jump_speed.min"),
    ("singh2017_cam.yaml", "{min: 1000 rpm}", "{min: 104.7}", "limits.jump_speed.min"),
]


@pytest.mark.parametrize("example, old, new, key", BARE_SPEEDS, ids=[s[2] for s in BARE_SPEEDS])
def test_a_bare_speed_is_refused_whatever_its_size_with_rpm_suggested(tmp_path, capsys, example,
                                                                       old, new, key):
    path = _scene(tmp_path, example, old, new)
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    number = re.search(r"[\d.]+\}?$", new).group(0).rstrip("}")
    assert err == (f"{path}:{_line_of(path, new)} {key}: {number} without a unit is ambiguous for "
                   f"a rotational speed (rpm or rad/s): did you mean '{number} rpm'? Give the "
                   f"unit ('{number} rpm' or '{number} rad/s')")


def test_a_bare_speed_is_refused_in_a_scene_given_as_a_mapping_and_zero_is_judged_as_zero():
    scene = yaml.safe_load((EXAMPLES / "eccentric_cam.yaml").read_text())
    for speed, reason in ((62.83, "did you mean '62.83 rpm'?"), (0, "must be positive")):
        scene["cam"]["speed"] = speed
        with pytest.raises(SceneError) as refused:
            load_scene(scene)
        [problem] = refused.value.problems
        assert problem.key == "cam.speed" and reason in problem.reason


@pytest.mark.parametrize("example, old, new", [
    ("eccentric_cam.yaml", "thickness: 10 mm", "thickness: 0.01"),
    ("eccentric_cam.yaml", "roller_radius: 10 mm", "roller_radius: 0.01"),
    ("eccentric_cam.yaml", "duration: 180 d", "duration: 15552000"),
    ("eccentric_cam.yaml", "every: 30 d", "every: 2592000"),
    ("singh2016_fourbar.yaml", "crank: 100 mm", "crank: 0.1"),
    ("singh2016_fourbar.yaml", "duration: 3 h", "duration: 10800"),
    ("eccentric_cam.yaml", "thickness: 10 mm", "thickness: 12 m"),  # a unit says what is meant
    ("singh2017_cam.yaml", "{deviation: 0.25 mm}", "{deviation: 0.00025}"),
])
def test_plausible_bare_values_pass_without_a_warning(tmp_path, recwarn, example, old, new):
    path = _scene(tmp_path, example, old, new)
    scene = load_scene(path)
    assert scene.warnings == [] and not recwarn.list


@pytest.mark.parametrize("path", SCENES, ids=[p.name for p in SCENES])
def test_every_shipped_scene_loads_without_a_warning(path, recwarn):
    scene = load_scene(path)
    assert scene.warnings == [] and not recwarn.list


def test_the_command_line_prints_one_line_and_no_traceback(tmp_path):
    path = _scene(tmp_path, "eccentric_cam.yaml", "thickness: 10 mm", "thickness: 12")
    for command in ("check", "run"):
        done = subprocess.run([sys.executable, "-m", "fickcam.cli.main", command, str(path)],
                              capture_output=True, text=True, cwd=tmp_path)
        assert done.returncode == 2, done.stderr
        assert "Traceback" not in done.stderr
        assert len(done.stderr.strip().splitlines()) == 1
        assert "cam.thickness" in done.stderr and "'12 mm'" in done.stderr


# ---------------------------------------------------------------- units and spellings

@pytest.mark.parametrize("text, dimension, suggestion", [
    ("100 F", "temperature", "'100 degF'"),     # F is the farad
    ("30 C", "temperature", "'30 degC'"),       # C is the coulomb
    ("5 lb", "force", "'5 lbf'"),               # lb is a mass
    ("3 MM", "length", "'3 mm'"),               # MM is megamolar
    ("600 1/min", "angular_speed", "'600 rpm'"),  # pint: rad/min, a workshop: rev/min
    ("10 Hz", "angular_speed", "'10 rps'"),
])
def test_a_misread_unit_names_the_unit_it_most_likely_meant(text, dimension, suggestion):
    with pytest.raises(ValueError, match=re.escape(f"did you mean {suggestion}?")):
        to_si(text, dimension)


@pytest.mark.parametrize("text, dimension, expected", [
    ("300 RPM", "angular_speed", 10 * math.pi),
    ("300 r/min", "angular_speed", 10 * math.pi),
    ("300 rev/min", "angular_speed", 10 * math.pi),
    ("80 %RH", "percent", 80.0),
])
def test_unambiguous_shop_spellings_are_read(text, dimension, expected):
    assert to_si(text, dimension) == pytest.approx(expected, rel=1e-12)


def test_a_scene_with_a_farad_temperature_says_degf(tmp_path, capsys):
    path = _scene(tmp_path, "eccentric_cam.yaml", "temperature: 40 degC", "temperature: 100 F")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert f":{_line_of(path, '100 F')} environment.history.0.temperature:" in err
    assert "did you mean '100 degF'?" in err


# ---------------------------------------------------------------- material aliases

@pytest.mark.parametrize("alias, name", [("PA66", "nylon"), ("PA6", "nylon"), ("POM", "acetal"),
                                         ("PI", "polyimide"), ("pa66", "nylon")])
def test_an_alias_resolves_to_the_same_material_as_its_name(tmp_path, alias, name):
    by_alias = load_scene(_scene(tmp_path, "eccentric_cam.yaml", "plastic: nylon", f"plastic: {alias}"))
    by_name = load_scene(_scene(tmp_path, "eccentric_cam.yaml", "plastic: nylon", f"plastic: {name}"))
    assert by_alias.materials["nylon"] == by_name.materials["nylon"]
    assert find_entry(alias) == find_entry(name)


def test_aliases_are_listed_and_pa6_is_told_it_reads_pa66_data(tmp_path, capsys):
    table = library_table()
    path = _scene(tmp_path, "eccentric_cam.yaml", "plastic: nylon", "plastic: PA12")
    assert main(["check", str(path)]) == 2
    assert "nylon (PA66, PA6)" in capsys.readouterr().err
    assert "PA66, PA6 = nylon" in table and "POM = acetal" in table and "PI = polyimide" in table
    scene = load_scene(_scene(tmp_path, "eccentric_cam.yaml", "plastic: nylon", "plastic: PA6"))
    [note] = scene.warnings
    assert note.key == "materials.nylon.plastic" and "PA66" in note.reason


# ---------------------------------------------------------------- history files

@pytest.mark.parametrize("header, column, meant", [
    ("time,temperature [degC],relative_humidity [%]", "time", "'time [d]'"),
    ("time [d],temperature,relative_humidity [%]", "temperature", "'temperature [degC]'"),
])
def test_a_history_file_without_units_is_refused_at_its_header(tmp_path, capsys, header, column, meant):
    path = _scene(tmp_path, "singh2017_cam_two_phase_daily.yaml", "x", "x")
    record = tmp_path / "chamber_daily_113C.csv"
    rows = record.read_text().splitlines()
    record.write_text("\n".join([header] + rows[1:]) + "\n")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert f"chamber_daily_113C.csv:1 {column}: the header gives no unit" in err, err
    assert meant in err and "ageing_times" not in err


# ---------------------------------------------------------------- the judgement itself

def test_band_verdicts_and_scaling():
    band = Band(1.0, 2.0, 0.5, 4.0)
    assert [band.verdict(x) for x in (1.5, 3.0, 0.7, 5.0, 0.1)] == [
        Verdict.PLAUSIBLE, Verdict.UNUSUAL, Verdict.UNUSUAL, Verdict.IMPLAUSIBLE, Verdict.IMPLAUSIBLE]
    assert band.times(1e-3).verdict(1.5e-3) is Verdict.PLAUSIBLE
    assert CAM_RADIUS.verdict(12.0) is Verdict.IMPLAUSIBLE and CAM_RADIUS.verdict(0.012) is Verdict.PLAUSIBLE


def _plate_uptake_series(tau: float, terms: int = 2000) -> float:
    """Crank (1975) eq. 4.18, sheet of half-thickness l: 1 - sum 8/((2n+1)^2 pi^2)
    exp(-(2n+1)^2 pi^2 tau / 4), tau = D t / l^2."""
    k = 2 * np.arange(terms) + 1
    return float(1.0 - np.sum(8.0 / (k * math.pi) ** 2 * np.exp(-(k * math.pi) ** 2 * tau / 4.0)))


@pytest.mark.parametrize("tau", [1e-4, 1e-3, 1e-2, 0.04])
def test_plate_uptake_is_the_exact_early_time_series(tau):
    """The neglected terms of eq. 4.20 are 4 sqrt(tau) ierfc(1/sqrt(tau)) ~ 1e-13 at
    tau = 0.04; the series' truncation (2000 terms) is below 1e-9 at tau >= 1e-4."""
    half, d = 5e-3, 1e-12
    assert plate_uptake(d, tau * half ** 2 / d, half) == pytest.approx(_plate_uptake_series(tau), rel=1e-6)


@pytest.mark.parametrize("tau", [0.05, 0.2, 0.5, 1.0, 3.0])
def test_plate_uptake_bounds_the_exact_uptake_from_above(tau):
    half, d = 5e-3, 1e-12
    assert plate_uptake(d, tau * half ** 2 / d, half) >= _plate_uptake_series(tau)


THICKNESS = CAM_MEMBERS[0].ratio.times(0.02)  # a cam of 20 mm base circle radius


@settings(max_examples=200, deadline=None)
@given(st.floats(1e-6, 1e6))
def test_a_judgement_refuses_exactly_the_implausible_and_suggests_only_what_reads_better(metres):
    reading = Reading("cam thickness", "length", "m", THICKNESS.verdict, LENGTH_ALTERNATIVES)
    judged = bare_judgement(metres, reading)
    verdict = THICKNESS.verdict(metres)
    if verdict is Verdict.PLAUSIBLE:
        assert judged is None
    if verdict is Verdict.IMPLAUSIBLE:
        assert judged is not None and judged[0] is Verdict.IMPLAUSIBLE
    if judged is not None and "did you mean" in judged[1]:
        meant = re.search(r"did you mean '([^']+)'", judged[1]).group(1)
        assert THICKNESS.verdict(to_si(meant, "length")) < judged[0]
    if judged is not None and judged[0] is Verdict.UNUSUAL:
        assert "did you mean" in judged[1]  # an unusual value is only told with a better unit
