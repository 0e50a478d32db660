"""Malformed scenes are refused: exit 2, one line per problem
``scene.yaml:LINE key.path: reason``, never a traceback, nothing executed."""
import re
import subprocess
import sys
import textwrap

import pytest

from fickcam.cli.main import main

CAM_SCENE = textwrap.dedent("""\
    name: test-cam
    description: a valid cam scene that each case below breaks in one place
    environment:
      reference_temperature: 23 degC
      initial_moisture: 0 %
      history:
        - duration: 60 d
          temperature: 113 degC
          relative_humidity: 80 %
    materials:
      cfrp:
        fiber: T300
        matrix: 8551-7
        fiber_volume_fraction: 0.6
        void_volume_fraction: 0
        layup: unidirectional
      steel: {metal: steel}
    cam:
      material: cfrp
      base_circle_radius: 1.94 in
      thickness: 12 mm
      speed: 600 rpm
      follower:
        kind: roller
        roller_radius: 0.6 in
        offset: 0 mm
        mass: 1.6 kg
        spring_rate: 1376.7 N/in
        spring_preload: 0 N
        external_load: 100 N
      motion:
        - dwell: 105 deg
        - {rise: 1.5 in, over: 75 deg, law: simple_harmonic}
        - {return: 1.5 in, over: 75 deg, law: simple_harmonic}
        - dwell: 105 deg
    diffusion:
      model: auto
      accuracy: 1e-3
    outputs:
      ageing_times: [0 d, 1 d, 7 d, 30 d, 60 d]
      angle_step: 1 deg
      fields: false
    """)

LINKAGE_SCENE = textwrap.dedent("""\
    name: test-fourbar
    environment:
      reference_temperature: 23 degC
      history:
        - {duration: 30 d, temperature: 118 degC, relative_humidity: 100 %}
    materials:
      resin: {matrix: R914}
      steel: {metal: steel}
    linkage:
      material: resin
      frame_material: steel
      crank: 100 mm
      coupler: 160 mm
      rocker: 160 mm
      frame: 200 mm
      coupler_point: {distance: 80 mm, angle: 0 deg}
      section: {width: 30 mm, thickness: 10 mm, boss_outer_radius: 15 mm, boss_inner_radius: 5 mm}
      crank_speed: 100 rpm
      assembly: open
    outputs:
      ageing_times: [0 d, 30 d]
    """)


def _line_of(text: str, fragment: str) -> int:
    for number, line in enumerate(text.splitlines(), start=1):
        if fragment in line:
            return number
    raise AssertionError(f"{fragment!r} not in scene")


# (case id, base scene, old text, new text, key path expected, reason fragment)
CASES = [
    ("negative-base-radius", CAM_SCENE, "base_circle_radius: 1.94 in", "base_circle_radius: -1.94 in",
     "cam.base_circle_radius", "positive"),
    ("zero-thickness", CAM_SCENE, "thickness: 12 mm", "thickness: 0 mm", "cam.thickness", "positive"),
    ("negative-mass", CAM_SCENE, "mass: 1.6 kg", "mass: -1.6 kg", "cam.follower.mass", "positive"),
    ("zero-speed", CAM_SCENE, "speed: 600 rpm", "speed: 0 rpm", "cam.speed", "positive"),
    ("length-in-kilograms", CAM_SCENE, "base_circle_radius: 1.94 in", "base_circle_radius: 1.94 kg",
     "cam.base_circle_radius", "dimension"),
    ("unknown-unit", CAM_SCENE, "thickness: 12 mm", "thickness: 12 furlongz", "cam.thickness", "unit"),
    ("rh-above-100", CAM_SCENE, "relative_humidity: 80 %", "relative_humidity: 120 %",
     "environment.history.0.relative_humidity", "100"),
    ("rh-negative", CAM_SCENE, "relative_humidity: 80 %", "relative_humidity: -5 %",
     "environment.history.0.relative_humidity", "negative"),
    ("fibre-fraction-above-one", CAM_SCENE, "fiber_volume_fraction: 0.6", "fiber_volume_fraction: 1.2",
     "materials.cfrp.fiber_volume_fraction", ""),
    ("void-fraction-negative", CAM_SCENE, "void_volume_fraction: 0", "void_volume_fraction: -0.1",
     "materials.cfrp.void_volume_fraction", ""),
    ("zero-duration", CAM_SCENE, "duration: 60 d", "duration: 0 d", "environment.history.0.duration",
     "positive"),
    ("negative-duration", CAM_SCENE, "duration: 60 d", "duration: -60 d",
     "environment.history.0.duration", "positive"),
    ("decreasing-ageing-times", CAM_SCENE, "[0 d, 1 d, 7 d, 30 d, 60 d]", "[0 d, 7 d, 1 d]",
     "outputs.ageing_times", "increase"),
    ("ageing-beyond-history", CAM_SCENE, "[0 d, 1 d, 7 d, 30 d, 60 d]", "[0 d, 90 d]",
     "outputs.ageing_times", "beyond"),
    ("motion-not-360", CAM_SCENE, "- dwell: 105 deg\n    - {rise", "- dwell: 100 deg\n    - {rise",
     "cam.motion", "360"),
    ("undefined-material", CAM_SCENE, "  material: cfrp", "  material: unobtainium", "cam.material",
     "not defined"),
    ("above-dry-tg", CAM_SCENE, "temperature: 113 degC", "temperature: 170 degC",
     "environment.history.0.temperature", "Tg"),
    ("unknown-law", CAM_SCENE, "law: simple_harmonic}\n    - {return", "law: wobbly}\n    - {return",
     "cam.motion", ""),
    ("unknown-top-level-key", CAM_SCENE, "description:", "colour: red\ndescription:", "colour",
     "unknown key"),
    ("unknown-nested-key", CAM_SCENE, "    kind: roller", "    kind: roller\n    colour: red",
     "cam.follower.colour", "unknown key"),
    ("missing-name", CAM_SCENE, "name: test-cam\n", "", "name", "missing"),
    ("missing-environment-history", CAM_SCENE,
     "  history:\n    - duration: 60 d\n      temperature: 113 degC\n      relative_humidity: 80 %\n", "",
     "environment", "history"),
    ("first-segment-ramps", CAM_SCENE, "      relative_humidity: 80 %\n",
     "      relative_humidity: 80 %\n      ramp: true\n", "environment", "first"),
    ("history-file-missing", CAM_SCENE,
     "  history:\n    - duration: 60 d\n      temperature: 113 degC\n      relative_humidity: 80 %\n",
     "  history_file: no-such-chamber.csv\n", "environment.history_file", "not found"),
    ("unknown-fibre", CAM_SCENE, "fiber: T300", "fiber: T3000", "materials.cfrp", "T300"),
    ("accuracy-zero", CAM_SCENE, "accuracy: 1e-3", "accuracy: 0", "diffusion.accuracy", ""),
    ("accuracy-text", CAM_SCENE, "accuracy: 1e-3", "accuracy: fine", "diffusion.accuracy", ""),
    ("unknown-diffusion-model", CAM_SCENE, "model: auto", "model: magic", "diffusion.model", ""),
    ("fields-not-boolean", CAM_SCENE, "fields: false", "fields: maybe", "outputs.fields", ""),
    ("boolean-as-length", CAM_SCENE, "thickness: 12 mm", "thickness: true", "cam.thickness", ""),
    ("angle-step-too-large", CAM_SCENE, "angle_step: 1 deg", "angle_step: 90 deg",
     "outputs.angle_step", "30"),
    ("negative-crank", LINKAGE_SCENE, "crank: 100 mm", "crank: -100 mm", "linkage.crank", "positive"),
    ("unknown-assembly", LINKAGE_SCENE, "assembly: open", "assembly: sideways", "linkage.assembly", ""),
    ("linkage-cannot-assemble", LINKAGE_SCENE, "frame: 200 mm", "frame: 1000 mm", "linkage", "assemble"),
    ("undefined-frame-material", LINKAGE_SCENE, "frame_material: steel", "frame_material: bronze",
     "linkage.frame_material", "not defined"),
    ("no-mechanism", LINKAGE_SCENE, "linkage:\n", "linkage_typo:\n", "", ""),
    ("model-for-a-part-the-scene-lacks", CAM_SCENE, "model: auto", "model: {cam: plane, rocker: solid}",
     "diffusion.model.rocker", "no part named 'rocker'"),
    ("unknown-model-for-a-part", CAM_SCENE, "model: auto", "model: {cam: finite}",
     "diffusion.model", ""),
    ("elastic-cam-without-bore", CAM_SCENE, "  speed: 600 rpm", "  speed: 600 rpm\n  elastic: true",
     "cam", "bore"),
    ("elastic-not-boolean", LINKAGE_SCENE, "assembly: open", "assembly: open\n  elastic: maybe",
     "linkage.elastic", ""),
    ("unknown-key-suggests-the-closest", CAM_SCENE, "    spring_rate: 1376.7 N/in",
     "    spring: 1376.7 N/in", "cam.follower.spring", "did you mean 'spring_rate'?"),
    ("unknown-top-key-suggests-the-closest", CAM_SCENE, "outputs:\n  ageing_times",
     "outputs:\n  ageing_time", "outputs.ageing_time", "did you mean 'ageing_times'?"),
    ("plastic-given-as-matrix", LINKAGE_SCENE, "resin: {matrix: R914}", "resin: {matrix: acetal}",
     "materials.resin", "acetal is a plastic in the library, write 'plastic: acetal'"),
    ("bare-celsius-temperature", CAM_SCENE, "temperature: 113 degC", "temperature: 40",
     "environment.history.0.temperature", "did you mean '40 degC'?"),
    ("bare-celsius-reference", CAM_SCENE, "reference_temperature: 23 degC", "reference_temperature: 23",
     "environment.reference_temperature", "did you mean '23 degC'?"),
    ("bare-fractional-humidity", CAM_SCENE, "relative_humidity: 80 %", "relative_humidity: 0.9",
     "environment.history.0.relative_humidity", "did you mean '90 %'?"),
    ("bare-unit-humidity", CAM_SCENE, "relative_humidity: 80 %", "relative_humidity: 1",
     "environment.history.0.relative_humidity", "did you mean '100 %'?"),
    ("state-with-moisture-and-humidity", LINKAGE_SCENE, "  history:\n    - {duration: 30 d, temperature: 118 degC, relative_humidity: 100 %}\n",
     "  state: {moisture: 7 %, relative_humidity: 100 %, temperature_rise: 95 K}\n",
     "environment.state.0", "exactly one of moisture, relative_humidity"),
    ("state-without-temperature", LINKAGE_SCENE, "  history:\n    - {duration: 30 d, temperature: 118 degC, relative_humidity: 100 %}\n",
     "  state: {moisture: 7 %}\n", "environment.state.0", "exactly one of temperature"),
    ("state-and-history", LINKAGE_SCENE, "  history:\n",
     "  state: {moisture: 7 %, temperature_rise: 95 K}\n  history:\n", "environment", "exactly one of"),
    ("state-times-decrease", LINKAGE_SCENE, "  history:\n    - {duration: 30 d, temperature: 118 degC, relative_humidity: 100 %}\n",
     "  state:\n    - {time: 1 d, moisture: 0 %, temperature_rise: 0 K}\n"
     "    - {time: 0 d, moisture: 7 %, temperature_rise: 95 K}\n", "environment", "increase"),
    ("state-with-ageing-times", LINKAGE_SCENE, "  history:\n    - {duration: 30 d, temperature: 118 degC, relative_humidity: 100 %}\n",
     "  state: {moisture: 7 %, temperature_rise: 95 K}\n", "outputs.ageing_times", "state"),
    ("unknown-number-name", LINKAGE_SCENE, "resin: {matrix: R914}", "resin: {matrix: 3503}",
     "materials.resin", "unknown matrix '3503'"),
]


@pytest.mark.parametrize("case, base, old, new, key, reason", CASES, ids=[c[0] for c in CASES])
def test_malformed_scene_is_refused_with_file_line_key_and_reason(tmp_path, capsys, case, base, old,
                                                                   new, key, reason):
    assert old in base, f"case {case} does not apply"
    text = base.replace(old, new, 1)
    path = tmp_path / "scene.yaml"
    path.write_text(text)
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.strip()]
    assert lines, "no message"
    assert "Traceback" not in err
    pattern = re.compile(rf"^{re.escape(str(path))}(:\d+)? ?(\S*): (.+)$")
    parsed = [pattern.match(line) for line in lines]
    assert all(parsed), err
    keys = [m.group(2) for m in parsed]
    if key:
        assert any(k == key or k.startswith(key + ".") for k in keys), (keys, err)
    if reason:
        assert reason.lower() in err.lower(), err
    leaf = key.split(".")[-1] if key else ""
    changed = new.strip().splitlines()[-1].strip() if new.strip() else ""
    if leaf and not leaf.isdigit() and changed.startswith(leaf + ":"):
        # the problem is reported at the line of the offending key
        expected = _line_of(text, changed)
        assert any(m.group(1) == f":{expected}" and m.group(2) == key for m in parsed), (expected, err)


RAW_CASES = [
    ("empty-file", "", "empty"),
    ("only-comments", "# nothing here\n", "empty"),
    ("syntax-error", "name: [unclosed\nenvironment: {}\n", "YAML syntax"),
    ("bad-indentation", "name: x\n  environment: 3\n bad: 4\n", "YAML syntax"),
    ("python-tag", "name: !!python/object/apply:os.system ['touch PWNED']\n", "tag"),
    ("duplicate-key", CAM_SCENE.replace("name: test-cam", "name: test-cam\nname: again"), "duplicate"),
    ("top-level-list", "- name: x\n", "mapping"),
    ("binary-garbage", "\x00\x01\x02", "YAML"),
    ("tab-indent", "name: x\nenvironment:\n\thistory: []\n", ":3: YAML syntax"),
    ("tab-indent-hint", "name: x\nenvironment:\n\thistory: []\n", "a tab: YAML indents with spaces"),
]


@pytest.mark.parametrize("case, text, fragment", RAW_CASES, ids=[c[0] for c in RAW_CASES])
def test_unreadable_yaml_is_refused_in_one_line(tmp_path, capsys, case, text, fragment):
    path = tmp_path / "scene.yaml"
    path.write_text(text)
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert err.startswith(str(path))
    assert fragment.lower() in err.lower()
    assert len(err.strip().splitlines()) == 1


def test_python_tag_is_never_executed(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "scene.yaml"
    path.write_text("name: !!python/object/apply:os.system ['touch PWNED']\n")
    assert main(["check", str(path)]) == 2
    assert not (tmp_path / "PWNED").exists()


def test_missing_scene_file_is_refused(tmp_path, capsys):
    assert main(["check", str(tmp_path / "nope.yaml")]) == 2
    assert "no such scene file" in capsys.readouterr().err


def test_several_problems_are_all_reported(tmp_path, capsys):
    text = CAM_SCENE.replace("thickness: 12 mm", "thickness: -1 mm").replace("mass: 1.6 kg", "mass: 0 kg")
    path = tmp_path / "scene.yaml"
    path.write_text(text)
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}:{_line_of(text, 'thickness: -1 mm')} cam.thickness:" in err
    assert f"{path}:{_line_of(text, 'mass: 0 kg')} cam.follower.mass:" in err


@pytest.mark.slow
def test_command_line_exit_status_and_no_traceback(tmp_path):
    path = tmp_path / "scene.yaml"
    path.write_text(CAM_SCENE.replace("speed: 600 rpm", "speed: -600 rpm"))
    done = subprocess.run([sys.executable, "-m", "fickcam.cli.main", "run", str(path)],
                          capture_output=True, text=True)
    assert done.returncode == 2
    assert "Traceback" not in done.stderr
    assert f"{path}:{_line_of(path.read_text(), 'speed: -600 rpm')} cam.speed:" in done.stderr


def test_a_library_name_that_yaml_reads_as_a_number_is_accepted(tmp_path, capsys):
    """`matrix: 3502` (unquoted) is YAML's integer 3502: it names the 3502 epoxy."""
    path = tmp_path / "scene.yaml"
    path.write_text(LINKAGE_SCENE.replace("resin: {matrix: R914}", "resin: {matrix: 3502}"))
    assert main(["check", str(path)]) == 0, capsys.readouterr().err


@pytest.mark.parametrize("old, new", [
    ("temperature: 113 degC", "temperature: 386.15"),          # bare kelvin, plausible
    ("relative_humidity: 80 %", "relative_humidity: 80"),       # bare percent, plausible
    ("relative_humidity: 80 %", "relative_humidity: 0"),        # dry air: 0 is 0 either way
    ("relative_humidity: 80 %", "relative_humidity: 0.9 %"),    # a unit says what is meant
    ("temperature: 113 degC", "temperature: 100 K"),            # ... even if implausible
])
def test_plausible_or_explicit_values_pass(tmp_path, capsys, old, new):
    path = tmp_path / "scene.yaml"
    path.write_text(CAM_SCENE.replace(old, new))
    assert main(["check", str(path)]) == 0, capsys.readouterr().err


def test_valid_scenes_pass_check(tmp_path, capsys):
    for text in (CAM_SCENE, LINKAGE_SCENE):
        path = tmp_path / "scene.yaml"
        path.write_text(text)
        assert main(["check", str(path)]) == 0, capsys.readouterr().err
        assert "valid" in capsys.readouterr().out


def test_a_model_that_does_not_apply_names_the_part(tmp_path, capsys):
    """One model for every part must apply to each; the error says which part refuses it."""
    path = tmp_path / "scene.yaml"
    path.write_text(_absorbing_follower(CAM_SCENE.replace("model: auto", "model: plane")))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "part follower" in err and "Disc" in err, err


def test_per_part_models_apply_to_their_part_and_leave_the_others_on_auto(tmp_path, capsys):
    path = tmp_path / "scene.yaml"
    path.write_text(_absorbing_follower(CAM_SCENE.replace(
        "model: auto", "model: {follower: axisymmetric}").replace("accuracy: 1e-3", "accuracy: 1e-2")))
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "Disc → axisymmetric" in out and "CamPlate → plane" in out, out


def _absorbing_follower(text: str) -> str:
    """The scene with a carbon/epoxy roller (it diffuses as a Disc)."""
    assert "    offset: 0 mm\n" in text
    return text.replace("    offset: 0 mm\n", "    offset: 0 mm\n    material: cfrp\n", 1)
