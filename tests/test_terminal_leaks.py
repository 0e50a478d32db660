"""Every line on the terminal is fickcam's own: after a part reaches its wet glass
transition no numpy warning (``RuntimeWarning: All-NaN slice encountered``) reaches
stderr, ``-q`` leaves nothing but errors, solver details wait for ``-v``, and the same
scene in Python warns with FickcamWarning only."""
from __future__ import annotations

import os
import subprocess
import sys
import warnings
from pathlib import Path

import pytest
import yaml

import fickcam

ROOT = Path(__file__).resolve().parents[1]
FOREIGN = ("Warning:", "Traceback", "site-packages", "warnings.warn", "All-NaN")


@pytest.fixture(scope="module")
def hot_cam(tmp_path_factory):
    """The demo cam at 150 degC: both parts pass their wet Tg at 30 d of 60."""
    data = yaml.safe_load((ROOT / "configs" / "singh2017_cam.yaml").read_text())
    data["environment"]["history"] = [{"duration": "60 d", "temperature": "150 degC",
                                       "relative_humidity": "85 %"}]
    data["outputs"] = {"ageing_times": ["0 d", "30 d", "60 d"], "angle_step": "6 deg"}
    path = tmp_path_factory.mktemp("hot") / "hot_cam.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def cli(*argv, cwd):
    return subprocess.run([sys.executable, "-m", "fickcam.cli.main", *map(str, argv)], cwd=cwd,
                          capture_output=True, text=True, timeout=600,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)))


def test_a_wet_tg_stop_prints_only_fickcams_lines_and_quiet_prints_none(hot_cam):
    loud = cli("run", hot_cam, "-o", "loud.h5", cwd=hot_cam.parent)
    quiet = cli("run", hot_cam, "-o", "quiet.h5", "-q", cwd=hot_cam.parent)
    assert loud.returncode == quiet.returncode == 0, loud.stderr
    lines = loud.stderr.splitlines()
    assert any("reached the wet Tg" in line for line in lines)
    assert all(line.startswith(("fickcam: warning: ", "fickcam: note: ")) for line in lines), \
        loud.stderr
    assert not any(text in loud.stderr for text in FOREIGN)
    assert "solved again" not in loud.stderr  # a solver's detail: debug level (-v)
    assert quiet.stderr == "" and "hidden by -q" in quiet.stdout


def test_in_python_the_same_scene_warns_with_fickcam_warnings_only(hot_cam):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        warnings.filterwarnings("ignore", category=DeprecationWarning)
        fickcam.run(hot_cam)
    assert seen and all(issubclass(w.category, fickcam.FickcamWarning) for w in seen), \
        [f"{w.category.__name__}: {w.message}" for w in seen]
    assert all(w.filename == __file__ for w in seen)  # at the caller's line, not fickcam's


def test_a_notice_at_several_ageing_times_is_one_line_and_the_designs_once(hot_cam):
    """The motion law's acceleration steps are the design's, true at every age: one
    warning, without ageing times, naming both joints."""
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always", fickcam.FickcamWarning)
        ds = fickcam.run(dict(yaml.safe_load(hot_cam.read_text()),
                              environment={"history": [{"duration": "60 d",
                                                        "temperature": "40 degC",
                                                        "relative_humidity": "50 %"}]}))
    jumps = [str(w.message) for w in seen if "acceleration jumps" in str(w.message)]
    assert jumps == ["motion as designed: acceleration jumps at the 105 and 255 deg joints of "
                     "its simple_harmonic segments: infinite jerk there, which excites "
                     "vibration (a cycloidal or polynomial law has none)"]
    assert ds.attrs["notices"].count(jumps[0]) == 1


def test_merged_notices_give_the_range_over_times_but_keep_alike_notices_of_one_time_apart():
    from fickcam.mechanisms.ageing import merged_notices
    from fickcam.messages import design_notice

    day = 86400.0
    seen = [(0.0, "pressure angle 31 deg near 104 deg"), (0.0, "pressure angle 33 deg near 250 deg"),
            (0.0, design_notice("motion as designed: steps at 105 deg")),
            (30 * day, "pressure angle 32 deg near 106 deg"),
            (30 * day, "pressure angle 34 deg near 250 deg"),
            (30 * day, design_notice("motion as designed: steps at 105 deg"))]
    assert merged_notices(seen, 30 * day) == [
        "at t = 0 d to 30 d (2 ageing times): pressure angle 31–32 deg near 104–106 deg",
        "at t = 0 d to 30 d (2 ageing times): pressure angle 33–34 deg near 250 deg",
        "motion as designed: steps at 105 deg"]


def test_times_are_told_in_the_unit_the_scene_wrote_them_in(tmp_path):
    """A five-year history written in days is reported in days, not years."""
    data = yaml.safe_load((ROOT / "configs" / "fourbar_r914_humid.yaml").read_text())
    data["environment"]["history"][0]["duration"] = "1826 d"
    data["outputs"] = {"ageing_times": ["0 d", "30 d", "1826 d"], "angle_step": "10 deg"}
    path = tmp_path / "five_years.yaml"
    path.write_text(yaml.safe_dump(data))
    done = cli("run", path, "-o", "five.h5", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "3 ageing times to 1826 d" in done.stdout and " yr" not in done.stdout + done.stderr
    data["environment"]["history"][0]["duration"] = "5 yr"  # written in years: years
    data["outputs"]["ageing_times"] = ["0 yr", "0.1 yr", "5 yr"]
    path.write_text(yaml.safe_dump(data))
    assert "3 ageing times to 5 yr" in cli("run", path, "-o", "five.h5", cwd=tmp_path).stdout
