"""Hostile and failing input: documents bounded before they are built (an alias bomb, a huge
scene, a deep one, a long CSV cell), a full disk, a sweep's leftovers, and climate files cut
short. Each is refused in one line naming the file (and line), never a traceback or a crash."""
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
import yaml

from fickcam.cli.main import main
from fickcam.errors import SceneError
from fickcam.climate.records import read_record
from fickcam.scene.load import load_scene
from fickcam.scene.yamldoc import MAX_BYTES, MAX_DEPTH, MAX_NODES, parse_yaml, read_yaml
from test_scene_errors import CAM_SCENE

ROOT = Path(__file__).resolve().parents[1]
MEMORY_LIMIT = 1 << 30  # [bytes] of address space for the child that reads the bomb


def alias_bomb(levels: int = 9, fan: int = 9) -> str:
    """A scene whose name is ``levels`` levels of ``fan``-fold aliases (fan**levels values)."""
    lines = ['a0: &a0 "lol"']
    lines += [f"a{k}: &a{k} [" + ", ".join([f"*a{k - 1}"] * fan) + "]" for k in range(1, levels + 1)]
    return "\n".join(lines) + f"\nname: *a{levels}\n"


def limited_child(code: str, *, address_space=None, file_size=None, timeout=120):
    """Run ``code`` in a Python child under the given limits [bytes]: RLIMIT_AS (memory) or
    RLIMIT_FSIZE (the largest file it may write: past it a write fails as on a full disk)."""
    limits = textwrap.dedent(f"""\
        import resource, sys
        for which, value in ((resource.RLIMIT_AS, {address_space!r}),
                             (resource.RLIMIT_FSIZE, {file_size!r})):
            if value is not None:
                resource.setrlimit(which, (value, value))
        """)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-c", limits + textwrap.dedent(code)],
                          capture_output=True, text=True, timeout=timeout, env=env, cwd=ROOT)


def test_an_alias_bomb_is_refused_at_once_with_little_memory(tmp_path):
    scene = tmp_path / "bomb.yaml"
    scene.write_text(alias_bomb())  # about 3.9e8 values once expanded; 9**6 on line 7
    child = limited_child(f"""
        from fickcam.cli.main import main
        print(main(["check", {str(scene)!r}]))
        """, address_space=MEMORY_LIMIT)
    assert child.stdout.split() == ["2"], child.stderr  # refused within the memory bound
    assert child.stderr.strip().splitlines() == [
        f"{scene}:7: scene refused: more than {MAX_NODES:,} values once its aliases are "
        f"expanded (each use of an alias counts all of its values)"]


def test_aliases_used_as_yaml_intends_keep_working(tmp_path, capsys):
    text = CAM_SCENE.replace("materials:\n", "materials:\n  base: &dry {metal: steel}\n", 1)
    text = text.replace("steel: {metal: steel}", "steel: *dry")
    text = text.replace("  history:\n", "  history: &h\n", 1)
    scene = tmp_path / "aliases.yaml"
    scene.write_text(text)
    assert main(["check", str(scene)]) == 0, capsys.readouterr().err
    doc = read_yaml(scene)
    assert doc.data["materials"]["steel"] == {"metal": "steel"}


@pytest.mark.parametrize("text, line, reason", [
    ("name: x\nlist: " + "[" * (MAX_DEPTH + 1) + "]" * (MAX_DEPTH + 1) + "\n", 2,
     f"nested more than {MAX_DEPTH} levels deep"),
    ("name: x\ndeep: &d " + "[" * 30 + "1" + "]" * 30 + "\nagain: [[[[[[[[[[[*d]]]]]]]]]]]\n", 3,
     f"nested more than {MAX_DEPTH} levels deep"),
    ("name: x\noutputs:\n  ageing_times: [" + ", ".join(["1 d"] * (MAX_NODES + 10)) + "]\n", 3,
     f"more than {MAX_NODES:,} values"),
])
def test_deep_or_long_documents_are_refused_at_their_line(text, line, reason):
    with pytest.raises(SceneError) as error:
        parse_yaml(text, file="s.yaml")
    (problem,) = error.value.problems
    assert (problem.line, problem.file) == (line, "s.yaml") and reason in problem.reason


def test_a_huge_scene_is_refused_unread(tmp_path, monkeypatch):
    """A 29 MB scene of 1.5 million keys, and a list of 2.7 million ageing times, took 27 s
    and 2 min before they were refused. Now no more than the bound is read, and nothing of
    it is parsed."""
    import fickcam.scene.yamldoc as yamldoc

    def parsed(*args, **kwargs):
        raise AssertionError("a scene over the size bound was parsed")

    monkeypatch.setattr(yamldoc, "parse_yaml", parsed)
    scene = tmp_path / "keys.yaml"
    with open(scene, "w") as handle:
        handle.write("name: big\n")
        handle.writelines(f"key_{k:07d}: {k} mm\n" for k in range(1_500_000))
    with pytest.raises(SceneError, match=r"keys.yaml: scene refused: \d+\.\d MiB; a scene file "
                                         rf"is at most {MAX_BYTES / 2**20:g} MiB"):
        read_yaml(scene)
    times = tmp_path / "times.yaml"
    times.write_text("name: t\noutputs:\n  ageing_times:\n" + "    - 1 h\n" * 2_700_000)
    with pytest.raises(SceneError, match="times.yaml: scene refused"):
        read_yaml(times)


def _shared_bomb(levels: int = 9, fan: int = 9) -> dict:
    """The alias bomb as Python data: one list shared ``fan`` times at each level."""
    value = ["lol"]
    for _ in range(levels):
        value = [value] * fan
    return {"name": value}


def _holds_itself() -> dict:
    scene = {"name": "loop"}
    scene["cam"] = scene
    return scene


@pytest.mark.parametrize("make, reason", [
    (_shared_bomb, f"more than {MAX_NODES:,} values"),
    (lambda: {"name": "big", **{f"key_{k}": k for k in range(1_500_000)}},
     f"more than {MAX_NODES:,} values"),
    (lambda: {"name": "t", "outputs": {"ageing_times": ["1 h"] * 2_700_000}},
     f"more than {MAX_NODES:,} values"),
    (lambda: {"name": "x" * (MAX_BYTES + 1)}, f"a scene file is at most {MAX_BYTES / 2**20:g} MiB"),
    (lambda: {"name": "x", "deep": json_nest(MAX_DEPTH + 1)}, f"nested more than {MAX_DEPTH} levels"),
    (_holds_itself, "or holds itself"),
])
def test_a_scene_given_as_a_dict_is_bounded_as_a_file_is(make, reason, monkeypatch):
    """``load_scene(dict)`` wrote the data as YAML before the file's bounds applied: a
    dict of 1.5 million keys took seconds and a deep or self-holding one a RecursionError.
    The bounds now come first: the data is refused without ever being written as YAML."""
    scene = make()

    def written(*args, **kwargs):
        raise AssertionError("the scene was written as YAML before its bounds were checked")

    monkeypatch.setattr(yaml, "safe_dump", written)
    with pytest.raises(SceneError) as error:
        load_scene(scene)
    (problem,) = error.value.problems
    assert problem.file == "<dict>" and problem.reason.startswith("scene refused: ")
    assert reason in problem.reason and "\n" not in str(error.value)


def json_nest(levels: int) -> dict:
    value: dict = {}
    for _ in range(levels):
        value = {"a": value}
    return value


def test_a_sweep_file_is_bounded_too(tmp_path):
    sweep = tmp_path / "sweep.yaml"
    sweep.write_text("base: base.yaml\n" + alias_bomb(levels=7, fan=9).replace("name:", "grid:"))
    with pytest.raises(SceneError, match=r"sweep.yaml:\d+: sweep refused: more than"):
        read_yaml(sweep, what="sweep")


def test_a_csv_cell_past_the_csv_limit_names_its_line(tmp_path):
    log = tmp_path / "log.csv"
    log.write_text('time [h],temperature [degC],relative_humidity [%]\n0,20,50\n1,"'
                   + "9" * 200_000 + '",50\n')
    with pytest.raises(ValueError, match=r"log.csv:3: a cell longer than 131,072 characters"):
        read_record(log)


# ------------------------------------------------------------------ a full disk
DEMO = ROOT / "configs" / "singh2017_cam.yaml"


def test_a_full_disk_gives_one_line_and_keeps_the_earlier_file(tmp_path):
    """The write fails past 200 kB (RLIMIT_FSIZE: EFBIG, as ENOSPC would on a full disk):
    one line naming the path and the space needed, exit status 1, no crash (it was a
    segmentation fault, status 139, after pages of h5py tracebacks)."""
    output = tmp_path / "cam.h5"
    output.write_bytes(b"the earlier result")
    child = limited_child(f"""
        from fickcam.cli.main import process_main
        sys.argv = ["fickcam", "run", "-q", {str(DEMO)!r}, "-o", {str(output)!r}]
        sys.exit(process_main())
        """, file_size=200_000)
    errors = [line for line in child.stderr.splitlines() if "warning:" not in line]
    assert child.returncode == 1, child.stderr[-2000:]
    assert len(errors) == 1, child.stderr[-2000:]
    assert re.fullmatch(rf"fickcam: error: {re.escape(str(output))}: cannot write \(file too "
                        r"large\): the result needs \d+ kB, [\d.]+ [kMGT]?B free there; the "
                        r"earlier file there is kept", errors[0]), errors[0]
    assert output.read_bytes() == b"the earlier result"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cam.h5"]


def test_a_journal_that_cannot_grow_names_its_path(tmp_path, monkeypatch):
    from fickcam.errors import WriteError
    from fickcam.sweep.journal import Journal

    journal = Journal(tmp_path / "journal.bin")

    def full(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("builtins.open", full)
    with pytest.raises(WriteError, match=re.escape(str(journal.path)) + r": cannot add a "
                       r"finished case \(no space left on device\): it needs \d+ B more"):
        journal.append(b"x" * 100)


def test_a_resumed_sweep_removes_the_temporary_file_of_a_killed_write(tmp_path):
    from test_sweep_resume import write_sweep

    from fickcam.sweep import run_sweep

    sweep = write_sweep(tmp_path)
    sweep.write_text("base: base.yaml\ngrid:\n  environment.history.0.relative_humidity: "
                     "[55 %]\n")  # one case: what is tested is the result's write
    output = tmp_path / "out.h5"
    stale = tmp_path / ".out.h5.k3j_9x2q.tmp"  # what a kill during the result's write leaves
    stale.write_bytes(b"half a result")
    other = tmp_path / ".other.h5.k3j_9x2q.tmp"
    other.write_bytes(b"another file's")
    run_sweep(sweep, output)
    assert not stale.exists() and other.exists() and output.is_file()


# ------------------------------------------------------------------ climate files cut short
def test_a_chamber_log_torn_inside_its_last_field_is_refused_at_that_line(tmp_path):
    """``97,112.86,70.19`` cut to ``97,112.86,7`` was read as 7 % RH without a word."""
    log = tmp_path / "chamber.csv"
    rows = [f"{day},112.86,70.19" for day in range(98)]
    log.write_text("time [d],temperature [degC],relative_humidity [%]\n" + "\n".join(rows)[:-4])
    with pytest.raises(ValueError, match=r"chamber.csv:99 relative_humidity: the file ends "
                                         r"inside this line, and '7' is shorter"):
        read_record(log)
    log.write_text("time [d],temperature [degC],relative_humidity [%]\n" + "\n".join(rows))
    assert read_record(log).relative_humidity[-1] == 70.19  # whole, without a final new line


def test_a_line_with_fewer_fields_at_the_end_is_refused(tmp_path):
    log = tmp_path / "chamber.csv"
    log.write_text("time [d],temperature [degC],relative_humidity [%]\n0,40,90\n1,40,90\n2,4")
    with pytest.raises(ValueError, match=r"chamber.csv:4: the file ends inside this line, "
                                         r"which has 2 field\(s\) where the lines before have 3"):
        read_record(log)


pvlib = pytest.importorskip("pvlib")  # the weather files below need the extra


def _tmy3_bytes() -> bytes:
    return (Path(pvlib.__file__).parent / "data" / "723170TYA.CSV").read_bytes()


def test_a_weather_file_cut_at_half_is_refused_with_its_row_count(tmp_path):
    half = tmp_path / "half.csv"
    whole = _tmy3_bytes()
    half.write_bytes(whole[:len(whole) // 2])
    with pytest.raises(ValueError, match=r"half.csv:\d+: 4,367 hourly rows where a weather "
                                         r"year has 8,760 \(it looks cut short\)"):
        read_record(half)


def test_a_weather_file_torn_in_its_last_line_is_refused(tmp_path):
    torn = tmp_path / "torn.csv"
    torn.write_bytes(_tmy3_bytes().rstrip(b"\r\n")[:-40])
    with pytest.raises(ValueError, match=r"torn.csv:8762: the file ends inside this line, "
                                         r"which has \d+ field\(s\) where the lines before have 71"):
        read_record(torn)
