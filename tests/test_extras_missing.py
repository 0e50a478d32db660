"""Each optional extra missing (ezdxf, pvlib, dask.distributed), simulated by hiding its
module (``sys.modules[name] = None`` makes its import fail): every command that needs it is
refused at once with one line naming the install command, exit status 2, and writes
nothing. With the extras installed (the test extra installs them all) the same commands
write their files."""
import sys
import tomllib
from pathlib import Path

import pytest
import yaml

from fickcam.cli.main import main
from fickcam.extras import EXTRAS, MissingExtra, installed
from fickcam.files import replaced_atomically

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "configs"
INSTALL = {name: f'pip install "fickcam[{name}]"' for name in EXTRAS}
#: the first line of a TMY3 file (USAF id, station, state, time zone, lat, lon, elevation)
TMY3_FIRST_LINE = '723170,"GREENSBORO PIEDMONT TRIAD INT",NC,-5.0,36.100,-79.950,272\n'


def hide(monkeypatch, extra: str) -> None:
    """Make the extra's module unimportable for this test."""
    monkeypatch.setitem(sys.modules, EXTRAS[extra].module, None)


def refused(capsys, code: int, extra: str) -> str:
    """The one stderr line of a refused command, checked to name the install command."""
    err = capsys.readouterr().err.strip()
    assert code == 2, err
    assert len(err.splitlines()) == 1 and INSTALL[extra] in err, err
    assert "internal error" not in err and "Traceback" not in err
    return err


def written(folder: Path) -> list[str]:
    """Every file under ``folder`` but the inputs the test wrote (``*.yaml``, ``in_*``)."""
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*")
                  if p.suffix != ".yaml" and not p.name.startswith("in_"))


def cam_scene(folder: Path, **environment) -> Path:
    """The demo cam with three ageing times and the given environment section."""
    scene = yaml.safe_load((CONFIGS / "singh2017_cam.yaml").read_text())
    scene["environment"] = {"reference_temperature": "23 degC", **environment}
    scene["outputs"] = {"ageing_times": ["0 d", "1 d", "2 d"], "angle_step": "10 deg"}
    path = folder / "cam.yaml"
    path.write_text(yaml.safe_dump(scene, sort_keys=False))
    return path


# ------------------------------------------------------------------------------ dxf


def test_profile_as_dxf_without_ezdxf_is_refused_and_writes_nothing(tmp_path, monkeypatch, capsys):
    hide(monkeypatch, "dxf")
    output = tmp_path / "cam.dxf"
    err = refused(capsys, main(["profile", str(CONFIGS / "singh2017_cam.yaml"), "-o", str(output)]),
                  "dxf")
    assert "or write the profile as .csv" in err
    assert written(tmp_path) == []
    assert main(["profile", str(CONFIGS / "singh2017_cam.yaml"), "-o", str(tmp_path / "cam.csv")]) == 0
    assert written(tmp_path) == ["cam.csv"]  # CSV needs no extra


def test_dxf_writer_without_ezdxf_raises_the_one_line_refusal(tmp_path, monkeypatch):
    from fickcam.cam.profile import write_profile_dxf

    hide(monkeypatch, "dxf")
    with pytest.raises(MissingExtra, match=r'reading or writing DXF drawings needs ezdxf: pip install "fickcam\[dxf\]"'):
        write_profile_dxf(tmp_path / "cam.dxf", [0.01, 0.0, -0.01], [0.0, 0.01, 0.0])
    assert written(tmp_path) == []


def test_profile_as_dxf_with_ezdxf_is_written_whole(tmp_path, capsys):
    ezdxf = pytest.importorskip("ezdxf")
    output = tmp_path / "cam.dxf"
    assert main(["profile", str(CONFIGS / "singh2017_cam.yaml"), "-o", str(output),
                 "--points", "360"]) == 0
    assert capsys.readouterr().out.strip() == f"wrote {output}"
    assert written(tmp_path) == ["cam.dxf"]  # no temporary file left beside it
    (polyline,) = ezdxf.readfile(output).modelspace().query("LWPOLYLINE")
    assert polyline.closed and len(polyline) == 360


# -------------------------------------------------------------------------- weather


def test_a_pvlib_weather_year_without_pvlib_is_refused_at_its_key(tmp_path, monkeypatch, capsys):
    hide(monkeypatch, "weather")
    scene = cam_scene(tmp_path, history_file="pvlib:723170TYA.CSV")
    for command in (["check", str(scene)], ["run", str(scene), "-o", str(tmp_path / "out.h5")]):
        err = refused(capsys, main(command), "weather")
        assert err.startswith(f"{scene}:") and "environment.history_file" in err
    assert written(tmp_path) == []


@pytest.mark.parametrize("name, first_line", [("in_year.csv", TMY3_FIRST_LINE),
                                              ("in_year.epw", "LOCATION,GREENSBORO,NC,USA\n")])
def test_a_weather_file_of_ones_own_without_pvlib_is_refused_not_called_unreadable(
        tmp_path, monkeypatch, capsys, name, first_line):
    hide(monkeypatch, "weather")
    (tmp_path / name).write_text(first_line + "rows that only pvlib would read\n")
    scene = cam_scene(tmp_path, history_file=name)
    err = refused(capsys, main(["run", str(scene), "-o", str(tmp_path / "out.h5")]), "weather")
    assert "not a readable" not in err
    assert written(tmp_path) == []


def test_a_sweep_over_weather_years_without_pvlib_is_refused_before_any_case(
        tmp_path, monkeypatch, capsys):
    hide(monkeypatch, "weather")
    (tmp_path / "in_chamber.csv").write_text(
        "time [d],temperature [degC],relative_humidity [%]\n0,40,50\n2,40,50\n")
    cam_scene(tmp_path, history_file="in_chamber.csv")
    sweep = tmp_path / "sweep.yaml"
    sweep.write_text("base: cam.yaml\ngrid:\n"
                     '  environment.history_file: ["in_chamber.csv", "pvlib:723170TYA.CSV"]\n')
    err = refused(capsys, main(["sweep", str(sweep), "--workers", "1", "-o", str(tmp_path / "s.h5")]),
                  "weather")
    assert err.startswith(f"{sweep}:3 grid.environment.history_file.1:")
    assert written(tmp_path) == []


def test_the_records_bench_without_pvlib_is_refused_at_once(monkeypatch, capsys):
    hide(monkeypatch, "weather")
    refused(capsys, main(["bench", "--records", "--quick", "--quiet"]), "weather")
    assert capsys.readouterr().out == ""


# ---------------------------------------------------------------------------- sweep


@pytest.mark.parametrize("where", [["--workers", "2"], ["--scheduler", "tcp://127.0.0.1:1"]])
def test_a_sweep_on_workers_without_distributed_is_refused_and_writes_nothing(
        tmp_path, monkeypatch, capsys, where):
    hide(monkeypatch, "sweep")
    cam_scene(tmp_path, history=[{"duration": "2 d", "temperature": "40 degC",
                                  "relative_humidity": "50 %"}])
    sweep = tmp_path / "sweep.yaml"
    sweep.write_text("base: cam.yaml\ngrid:\n  environment.history.0.relative_humidity: [40 %, 60 %]\n")
    err = refused(capsys, main(["sweep", str(sweep), *where, "-o", str(tmp_path / "s.h5")]), "sweep")
    assert "or run with --workers 1" in err
    assert written(tmp_path) == []  # neither the result nor its work folder


def test_a_sweep_without_distributed_and_no_worker_count_runs_here(monkeypatch):
    from fickcam.sweep.runner import in_process

    hide(monkeypatch, "sweep")
    assert not installed("sweep")
    assert in_process(None, None, 8)


# ------------------------------------------------------------------- the extras' tests


def test_the_test_extra_installs_every_optional_extra():
    """The README's test command installs ``.[test]``: with it the suite exercises what
    each extra enables (the tests above that need one skip only without it)."""
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    test = set(extras["test"])
    for name in EXTRAS:
        assert set(extras[name]) <= test, name
        assert EXTRAS[name].module.replace("distributed", "dask") in " ".join(extras[name])


def test_an_interrupted_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "profile.csv"
    target.write_text("old\n")
    with pytest.raises(RuntimeError), replaced_atomically(target) as tmp:
        Path(tmp).write_text("half")
        raise RuntimeError("stopped")
    assert target.read_text() == "old\n" and sorted(p.name for p in tmp_path.iterdir()) == ["profile.csv"]
