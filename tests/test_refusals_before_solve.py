"""Every refusal `fickcam check` makes comes before any diffusion is planned or solved, in
`run`, `sweep`, `compensate`, `size` and `fickcam.run` alike: the demo cam with
``diffusion: {model: solid}`` (its follower is a disc) is refused with check's own line
while no part has been solved."""
import sys
from pathlib import Path

import pytest

import fickcam
from fickcam.cli.main import main
from fickcam.diffusion import dispatch
from fickcam.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
REFUSAL = ("part follower: diffusion.model 'solid' does not apply to a Disc "
           "(use one of analytic, axisymmetric or auto)")


@pytest.fixture
def solid_scene(tmp_path):
    """The demo cam asking for the solid model for every part (the follower is a disc)."""
    text = (ROOT / "configs" / "singh2017_cam.yaml").read_text()
    assert "  model: auto\n" in text
    path = tmp_path / "solid.yaml"
    path.write_text(text.replace("  model: auto\n", "  model: solid\n", 1))
    (tmp_path / "sweep.yaml").write_text(
        "base: solid.yaml\ngrid:\n  environment.history.0.relative_humidity: [50 %, 80 %]\n")
    return path


@pytest.fixture
def work_done(monkeypatch):
    """Every diffusion plan and solve of the process, by part shape (none expected)."""
    done = []
    plan, solve = dispatch.plan_problem, dispatch.solve_problem

    def planned(problem, *args, **kwargs):
        done.append(("plan", type(problem.geometry).__name__))
        return plan(problem, *args, **kwargs)

    def solved(problem, *args, **kwargs):
        done.append(("solve", type(problem.geometry).__name__))
        return solve(problem, *args, **kwargs)

    import fickcam.simulation.simulate  # noqa: F401  (every module that holds the two names)

    for module in [m for name, m in sys.modules.items() if name.startswith("fickcam")]:
        for name, original, counted in (("plan_problem", plan, planned),
                                        ("solve_problem", solve, solved)):
            if getattr(module, name, None) is original:
                monkeypatch.setattr(module, name, counted)
    return done


@pytest.mark.parametrize("command", [
    ["check", "solid.yaml"],
    ["run", "solid.yaml", "-o", "out.h5"],
    ["compensate", "solid.yaml", "--at", "30 d"],
    ["size", "solid.yaml"],
    ["sweep", "sweep.yaml", "-o", "sweep.h5", "--workers", "1"],
], ids=lambda c: c[0])
def test_a_refusal_of_check_comes_before_any_solve(solid_scene, work_done, monkeypatch, capsys,
                                                   command):
    monkeypatch.chdir(solid_scene.parent)
    assert main(command) == 2
    assert capsys.readouterr().err.strip() == f"fickcam: error: {REFUSAL}"
    assert work_done == []  # not even the cam was planned, let alone solved
    assert not any(solid_scene.parent.glob("*.h5")) and not any(solid_scene.parent.glob("*.parts"))


def test_fickcam_run_in_python_refuses_before_any_solve(solid_scene, work_done):
    with pytest.raises(InputError, match=r"^part follower: diffusion.model 'solid'"):
        fickcam.run(str(solid_scene))
    assert work_done == []


def test_a_valid_scene_plans_each_part_before_it_solves_the_first(work_done):
    """The run's plans go into its cache, which its solves read: every part is planned
    (cam, follower) before the first solve."""
    fickcam.run(str(ROOT / "configs" / "singh2017_cam.yaml"))
    first_solve = next(k for k, (what, _) in enumerate(work_done) if what == "solve")
    planned = {shape for what, shape in work_done[:first_solve] if what == "plan"}
    solved = {shape for what, shape in work_done if what == "solve"}
    assert solved == planned == {"CamPlate", "Disc"}
