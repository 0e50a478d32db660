"""Every benchmark script in ``benchmarks/`` parses its arguments and reaches the sibling
helpers it imports (``--help`` in a fresh interpreter): a script that no longer imports,
or a shared helper that fails on its first call path, shows here rather than when someone
next measures. The measurements themselves are not timed here."""
import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = sorted(path for path in (ROOT / "benchmarks").glob("*.py")
                 if "argparse" in path.read_text())


def test_the_scripts_are_found():
    assert len(SCRIPTS) >= 8


@pytest.mark.slow
@pytest.mark.parametrize("script", SCRIPTS, ids=lambda path: path.name)
def test_a_benchmark_script_answers_help(script):
    done = subprocess.run([sys.executable, script.name, "--help"], cwd=script.parent,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "usage:" in done.stdout


def test_the_machine_is_announced(capsys):
    """The helper every timing script prints its machine with (it once called itself)."""
    spec = importlib.util.spec_from_file_location("points_cam_bench",
                                                  ROOT / "benchmarks" / "points_cam.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    about = module.announced_machine()
    assert about["cores"] >= 1
    assert capsys.readouterr().out.startswith("machine: ")
