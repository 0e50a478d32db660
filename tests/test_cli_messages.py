"""What the command line prints on stderr: fickcam's own notices once, no library chatter,
no notes with --quiet; `fickcam bench` shows progress and an expected duration."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from fickcam.cli.checkout import benchmark, repository_root
from fickcam.cli.main import main
from fickcam.errors import InputError

ROOT = Path(__file__).resolve().parents[1]


def fickcam_cli(*args, cwd=None):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "fickcam.cli.main", *args], capture_output=True,
                          text=True, env=env, cwd=cwd, timeout=300)


@pytest.fixture(scope="module")
def fourbar(tmp_path_factory):
    """Singh & Sanyal 2016's four-bar (it reports its Grashof class) run loud and --quiet."""
    folder = tmp_path_factory.mktemp("fourbar")
    scene = yaml.safe_load((ROOT / "configs" / "singh2016_fourbar.yaml").read_text())
    scene["outputs"] = {"ageing_times": ["0 d", "1 h"], "angle_step": "6 deg"}
    (folder / "fourbar.yaml").write_text(yaml.safe_dump(scene))
    loud = fickcam_cli("run", "fourbar.yaml", "-o", "loud.h5", cwd=folder)
    quiet = fickcam_cli("run", "fourbar.yaml", "-o", "quiet.h5", "--quiet", cwd=folder)
    return folder, loud, quiet


@pytest.mark.slow
def test_a_notice_is_printed_once(fourbar):
    _, loud, _ = fourbar
    assert loud.returncode == 0, loud.stderr
    assert (loud.stdout + loud.stderr).count("Grashof class: crank-rocker") == 1


def test_quiet_prints_no_notes_but_keeps_the_summary(fourbar):
    _, _, quiet = fourbar
    assert quiet.returncode == 0 and quiet.stderr == ""
    assert "minimum_transmission_angle" in quiet.stdout and "note(s) hidden by -q" in quiet.stdout


@pytest.mark.slow
def test_query_does_not_repeat_the_runs_notices(fourbar):
    folder, _, _ = fourbar
    done = fickcam_cli("query", "loud.h5", "rocker_swing", cwd=folder)
    assert done.returncode == 0 and done.stderr == ""


def test_fipy_solver_chatter_stays_off_stderr():
    code = ("import sys; from fickcam.cli.main import main; main(['schema']); import fipy")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)), timeout=120)
    assert "PyAMG" not in done.stderr and "Solver suite" not in done.stderr, done.stderr


def test_bench_quick_is_quick_and_shows_progress_and_expected_duration(monkeypatch, capsys):
    tradeoff = benchmark("diffusion_tradeoff")  # benchmarks/, loaded from this checkout
    quick = tradeoff.bench_cases(True)
    assert all("solid" not in case.models for case in quick)
    assert tradeoff.row_count(True) < tradeoff.row_count(False) / 2
    started = []

    def fake(quick, progress):
        for k in range(tradeoff.row_count(quick)):
            progress(f"row {k}")
            started.append(k)
        return []

    monkeypatch.setattr(tradeoff, "run_bench", fake)  # the benchmark script's, not fickcam's
    assert main(["bench", "--quick"]) == 0
    err = capsys.readouterr().err
    assert len(started) == tradeoff.row_count(True)
    assert "fickcam: note: bench:" in err and "expected about 10 s" in err


def test_no_checkout_is_found_outside_a_clone(tmp_path):
    assert repository_root() == ROOT
    with pytest.raises(InputError, match="run this from a clone of the repository"):
        repository_root([tmp_path, *tmp_path.parents])


def test_bench_from_an_installed_copy_outside_a_clone_is_refused_in_one_line(tmp_path):
    """The package alone (as a wheel installs it), run from a folder outside any clone."""
    site = tmp_path / "site"
    shutil.copytree(ROOT / "fickcam", site / "fickcam",
                    ignore=shutil.ignore_patterns("__pycache__"))
    done = subprocess.run([sys.executable, "-m", "fickcam.cli.main", "bench", "--quick"],
                          capture_output=True, text=True, cwd=tmp_path, timeout=120,
                          env=dict(os.environ, PYTHONPATH=str(site)))
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.count("\n") == 1 and "clone of the repository" in done.stderr, done.stderr


def test_quick_benchmark_script_keeps_the_committed_results(tmp_path, monkeypatch):
    script = benchmark("diffusion_tradeoff")
    monkeypatch.setattr(script, "run_bench", lambda quick: [])
    monkeypatch.setattr(script, "RESULTS", tmp_path / "results")
    monkeypatch.setattr(sys, "argv", ["diffusion_tradeoff.py", "--quick"])
    script.main()
    assert not (tmp_path / "results").exists()
