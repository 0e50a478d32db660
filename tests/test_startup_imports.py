"""What a run of the demo scene imports: nothing the scene does not use (no dask, matplotlib,
FiPy, scikit-fem or ezdxf, and neither scipy.interpolate nor the scipy.optimize and scipy.fft
it brings, a tenth of the demo's run), checked in a fresh interpreter each (``sys.modules`` after
the run)."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

DEMO = Path(__file__).resolve().parents[1] / "configs" / "singh2017_cam.yaml"
#: packages the demo scene does not use (plots, FiPy and scikit-fem solvers, sweeps, DXF
#: drawings, SciPy's splines and root finders)
UNUSED = ("dask", "distributed", "matplotlib", "fipy", "skfem", "ezdxf", "scipy.interpolate",
          "scipy.optimize")
IMPORTED = f"[m for m in {UNUSED!r} if sys.modules.get(m) is not None]"


def imported_after(code: str) -> list[str]:
    """The packages of UNUSED imported once ``code`` has run in a new interpreter."""
    done = subprocess.run([sys.executable, "-c", f"import json, sys\n{code}\n"
                           f"print(json.dumps({IMPORTED}))"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_the_demo_command_imports_nothing_the_scene_does_not_use(tmp_path):
    output = tmp_path / "demo.h5"
    code = (f"sys.argv = ['fickcam', 'run', '-q', '-q', {str(DEMO)!r}, '-o', {str(output)!r}]\n"
            "from fickcam.cli.main import process_main\n"
            "assert process_main() == 0")
    assert imported_after(code) == []
    assert output.is_file()


@pytest.mark.slow
def test_loading_and_running_the_demo_scene_in_python_imports_no_optional_package():
    # dask itself may come in through pint and xarray, which import it whenever it is
    # installed; nothing of fickcam's own does (the next test runs without it)
    code = f"import fickcam\nfickcam.run(fickcam.load_scene({str(DEMO)!r}))"
    assert [m for m in imported_after(code) if m != "dask"] == []


@pytest.mark.slow
def test_the_demo_scene_runs_without_dask_installed():
    # None in sys.modules: the import system's mark of a module that cannot be imported
    code = ("sys.modules['dask'] = None\nimport fickcam\n"
            f"fickcam.run(fickcam.load_scene({str(DEMO)!r}))")
    assert imported_after(code) == []
