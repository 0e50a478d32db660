"""What a user reads in a terminal: errors, warnings and notes told apart by their prefix,
-q and -qq, progress bars only on a terminal (with a remaining time only where the steps cost
alike), one unit of time per run, query values in display units with named columns, the
closest names for a misspelling, and library values with their units."""
import csv
import json
import logging
import os
import select
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

from fickcam.cli.main import main
from fickcam.results.dataset import build_dataset
from fickcam.errors import format_duration
from fickcam.linkage.classify import class_changes
from fickcam.messages import Note, count_levels, level_of, note, progress_bar, restated
from fickcam.results.store import save

ROOT = Path(__file__).resolve().parents[1]
DAY = 86400.0
YEAR = 365.25 * DAY
PREFIXES = ("fickcam: error: ", "fickcam: warning: ", "fickcam: note: ")


@pytest.fixture()
def fourbar(tmp_path):
    """Singh & Sanyal 2016's four-bar to 2.5 h: notes (Grashof class, toggles) and warnings (the
    links reach their wet Tg at 2.5 h)."""
    scene = yaml.safe_load((ROOT / "configs" / "singh2016_fourbar.yaml").read_text())
    scene["outputs"] = {"ageing_times": ["0 h", "1 h", "2.5 h"], "angle_step": "6 deg"}
    path = tmp_path / "fourbar.yaml"
    path.write_text(yaml.safe_dump(scene))
    return path


def run_cli(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_every_message_line_says_its_level_and_notes_are_not_warnings(fourbar, capsys):
    code, out, err = run_cli(capsys, "run", fourbar, "-o", fourbar.with_suffix(".h5"))
    assert code == 0
    lines = err.splitlines()
    assert lines and all(line.startswith(PREFIXES) for line in lines), err
    grashof = [line for line in lines if "Grashof class: crank-rocker" in line]
    wet_tg = [line for line in lines if "wet Tg" in line]
    # said at 0 h and 1 h (the links are past their wet Tg at 2.5 h): one line, both times
    assert grashof == ["fickcam: note: at t = 0 h to 1 h (2 ageing times): Grashof class: "
                       "crank-rocker"]
    assert len(wet_tg) == 3 and all(line.startswith("fickcam: warning: ") for line in wet_tg)
    assert "\r" not in err  # stderr is not a terminal: no progress frames
    assert "3 warning(s) and 3 note(s) above" in out


def test_quiet_leaves_only_errors_on_stderr_and_the_summary_counts_what_it_hid(fourbar, capsys):
    code, out, err = run_cli(capsys, "run", fourbar, "-o", fourbar.with_suffix(".h5"), "-q")
    assert (code, err) == (0, "")
    assert "peak_input_torque" in out and "3 warning(s) and 3 note(s) hidden by -q" in out


def test_twice_quiet_prints_nothing_but_errors(fourbar, capsys, tmp_path):
    code, out, err = run_cli(capsys, "run", fourbar, "-o", fourbar.with_suffix(".h5"), "-qq")
    assert (code, out, err) == (0, "", "")
    code, out, err = run_cli(capsys, "query", tmp_path / "none.h5", "lift", "-qq")
    assert code == 2 and err.startswith("fickcam: error: ") and out == ""


def test_times_in_a_run_share_one_unit_chosen_from_its_span(fourbar, capsys):
    _, out, err = run_cli(capsys, "run", fourbar, "-o", fourbar.with_suffix(".h5"))
    said = [word for line in (out + err).splitlines() for word in line.split()
            if word in ("s", "min", "h", "d", "yr") and "wall time" not in line]
    assert set(said) == {"h"}, out + err  # 2.5 h of ageing: every time in h


@pytest.mark.parametrize("seconds, span, text", [
    (0.0, 60 * DAY, "0 d"), (182.625 * DAY, 2 * YEAR, "182.6 d"), (2 * YEAR, 2 * YEAR, "730.5 d"),
    (2 * YEAR, 10 * YEAR, "2 yr"), (5400.0, 3 * 3600.0, "1.5 h"), (600.0, 3600.0, "10 min"),
    (30.0, None, "30 s"), (3 * DAY, None, "3 d"),
])
def test_a_duration_is_given_in_the_unit_of_its_span(seconds, span, text):
    assert format_duration(seconds, span) == text


def test_notes_keep_their_level_when_restated_and_plain_notices_warn():
    grashof = note("Grashof class: crank-rocker")
    assert isinstance(restated(grashof, "at t = 0 d: " + grashof), Note)
    assert level_of(restated(grashof, "x")) == logging.INFO
    assert level_of("follower jumps at 312 deg") == logging.WARNING
    assert count_levels([grashof, "jump", "undercut"]) == {"warning": 2, "note": 1}
    lost, again = class_changes(["crank-rocker", "non-Grashof", "crank-rocker"],
                                [0.0, DAY, 2 * DAY])[-2:]
    assert level_of(lost) == logging.WARNING and "no longer make a full revolution" in lost
    assert level_of(again) == logging.INFO and "full revolution again" in again


# -------------------------------------------------------------------- progress bars


def test_no_progress_bar_when_stderr_is_not_a_terminal(capsys):
    bar = progress_bar(3, desc="work", unit="steps")
    bar.update(3)
    bar.close()
    assert bar.disable and capsys.readouterr().err == ""


def _on_a_terminal(monkeypatch, draw) -> str:
    """What ``draw()`` writes on stderr when stderr is a (pseudo-)terminal."""
    import fcntl
    import struct
    import termios

    master, slave = os.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # 100 columns
    terminal = os.fdopen(slave, "w", encoding="utf-8")
    monkeypatch.setattr(sys, "stderr", terminal)
    try:
        draw()
        terminal.flush()
        written = b""
        while select.select([master], [], [], 0.0)[0]:
            written += os.read(master, 65536)
        return written.decode("utf-8", "replace")
    finally:
        terminal.close()
        os.close(master)


def test_a_terminal_shows_the_bar_with_an_eta_only_for_steps_of_equal_cost(monkeypatch):
    def draw(eta):
        def steps():
            with progress_bar(4, eta=eta, desc="scene: part", unit="parts") as bar:
                bar.update(2)
        return steps

    counted = _on_a_terminal(monkeypatch, draw(False))
    timed = _on_a_terminal(monkeypatch, draw(True))
    assert "\r" in counted and "scene: part: 2/4 parts [" in counted
    assert "<" not in counted  # no remaining time: the parts cost unlike amounts
    assert "2/4 parts [" in timed and "<" in timed


def test_a_run_with_progress_on_writes_no_frames_into_a_log(fourbar, capsys):
    import fickcam

    fickcam.run(fourbar, progress=True)
    assert "\r" not in capsys.readouterr().err


# -------------------------------------------------------------------------- query


@pytest.fixture()
def result(tmp_path):
    times = np.array([0.0, 0.5, 2.0]) * YEAR
    angles = np.radians(np.arange(0, 360, 90))
    ds = build_dataset(
        {"temperature": np.array([293.15, 303.15, 298.15]),
         "lift": np.array([0.0080, 0.0082, 0.0081]),
         "follower_displacement": np.full((3, angles.size), 0.001)},
        {"time": times, "cam_angle": angles}, {"scene_name": "synthetic", "notices": []})
    ds["lift_design"] = ((), 0.0079, {"units": "m", "long_name": "lift, as designed"})
    path = tmp_path / "r.h5"
    save(ds, path)
    return path


def test_query_shows_display_units_and_names_every_column(result, capsys):
    code, out, _ = run_cli(capsys, "query", result, "lift", "--format", "csv")
    rows = list(csv.DictReader(out.splitlines()))
    assert code == 0 and list(rows[0]) == ["time [d]", "lift [mm]"]
    assert [float(r["lift [mm]"]) for r in rows] == pytest.approx([8.0, 8.2, 8.1], rel=1e-12)
    assert [float(r["time [d]"]) for r in rows] == pytest.approx([0.0, 182.625, 730.5])
    code, out, _ = run_cli(capsys, "query", result, "lift", "--time", "182.625 d")
    assert out.splitlines() == ["lift at time = 182.6 d (stored)", "lift [mm]", "      8.2"]


def test_query_units_choose_another_unit_and_refuse_a_misfit(result, capsys):
    code, out, _ = run_cli(capsys, "query", result, "follower_displacement", "--time", "0 d",
                           "--units", "um", "--format", "json")
    answer = json.loads(out)
    assert answer["units"] == "um" and answer["columns"] == ["cam_angle [degree]",
                                                            "follower_displacement [um]"]
    assert [row[-1] for row in answer["rows"]] == pytest.approx([1000.0] * 4, rel=1e-12)
    code, _, err = run_cli(capsys, "query", result, "lift", "--units", "kg")
    assert code == 2 and err.startswith("fickcam: error: --units kg: ") and "\n" == err[-1:]
    assert err.count("\n") == 1


def test_a_temperature_drift_is_a_difference_in_kelvin(result, capsys):
    code, out, _ = run_cli(capsys, "query", result, "temperature", "--drift", "start",
                           "--format", "csv")
    rows = list(csv.DictReader(out.splitlines()))
    column = "temperature drift vs start [K]"
    assert [float(r[column]) for r in rows] == pytest.approx([0.0, 10.0, 5.0], abs=1e-9)
    code, out, _ = run_cli(capsys, "query", result, "temperature", "--format", "csv")
    assert [float(r["temperature [degC]"]) for r in csv.DictReader(out.splitlines())] == \
        pytest.approx([20.0, 30.0, 25.0], abs=1e-9)


def test_a_misspelt_variable_gets_the_closest_names_not_the_whole_list(result, capsys):
    code, _, err = run_cli(capsys, "query", result, "lfit")
    assert code == 2 and err == "fickcam: error: no variable 'lfit' in this result; " \
                                "did you mean lift?\n"
    code, _, err = run_cli(capsys, "query", result, "rocker_angle")
    assert code == 2 and "a linkage variable: the scene does not compute it" in err


# ---------------------------------------------------------------------- materials


def test_materials_name_gives_every_value_a_unit(capsys):
    code, out, _ = run_cli(capsys, "materials", "nylon")
    assert code == 0 and "83000000" not in out
    strength = next(line for line in out.splitlines() if "tensile strength" in line)
    assert strength.split()[2:4] == ["83", "MPa"] and "ASSUMPTION" in strength
    assert "1140 kg/m3" in out and "0.3667 at 2.5 %" in out
    values = out.split("  sources:")[0].splitlines()[1:]
    assert all(not line.split()[-1].replace(".", "").isdigit() for line in values
               if "Poisson" not in line)  # a number without its unit


def test_a_misspelt_material_gets_the_closest_names(capsys):
    code, _, err = run_cli(capsys, "materials", "nylonn")
    assert code == 2 and err == "fickcam: error: no material 'nylonn' in the library; " \
                                "did you mean nylon?\n"
