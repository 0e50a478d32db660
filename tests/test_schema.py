"""The schema (fickcam/schema.py) is the one table of result names: every name a model
returns has its row there, and a name it lacks fails instead of being dropped."""
from pathlib import Path

import numpy as np
import pytest
import yaml

import fickcam
from fickcam.results.dataset import build_dataset
from fickcam.simulation.parts import part_values
from fickcam.schema import VARIABLES
from fickcam.simulation.ageing import as_designed_part, mechanism_values

CONFIGS = Path(__file__).resolve().parents[1] / "configs"
SCENES = sorted(p for p in CONFIGS.glob("*.yaml") if not p.name.startswith("sweep"))


def follower_variants():
    """The example scenes, and the demo cam with each follower kind."""
    for path in SCENES:  # by path: a scene may name files beside it (a cam's profile)
        yield path.stem, path
    for kind in ("knife", "flat"):
        scene = yaml.safe_load((CONFIGS / "singh2017_cam.yaml").read_text())
        scene["cam"]["follower"].update(kind=kind)
        scene["cam"]["follower"].pop("roller_radius")
        yield f"singh2017 {kind}", scene


@pytest.mark.slow
@pytest.mark.parametrize("name, scene", list(follower_variants()), ids=lambda v: v if isinstance(v, str) else "")
def test_every_name_the_models_return_is_in_the_schema(name, scene):
    scene = fickcam.load_scene(scene, file_name=f"{name}.yaml") if isinstance(scene, dict) else \
        fickcam.load_scene(scene)
    environment = scene.environment
    states = [as_designed_part(part, environment) for part in scene.parts]
    mechanisms = mechanism_values(scene, states, np.zeros(1), np.ones(1, bool))
    returned = set(part_values(states)) | set(mechanisms.variables)
    assert returned, name
    assert returned <= set(VARIABLES), f"not in the schema: {sorted(returned - set(VARIABLES))}"


def test_a_name_the_schema_lacks_fails_instead_of_being_dropped():
    with pytest.raises(KeyError, match="not declared in fickcam/schema.py"):
        build_dataset({"lift": np.zeros(2), "lift_in_furlongs": np.zeros(2)}, {"time": [0.0, 1.0]})


def test_no_other_table_of_result_names():
    import fickcam.materials as materials
    import fickcam.simulation.simulate as simulate

    assert not hasattr(materials, "STATE_VARIABLES")
    assert not hasattr(simulate, "_PART_VARIABLES")


def test_simulate_does_not_import_the_package_it_belongs_to():
    import ast

    tree = ast.parse((Path(fickcam.__file__).parent / "simulation" / "simulate.py").read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module is None:
            pytest.fail(f"simulate.py line {node.lineno}: 'from . import ...'")


def test_the_scene_takes_the_diffusion_model_names_from_the_diffusion_package():
    from fickcam.diffusion import MODELS

    text = (Path(fickcam.__file__).parent / "scene" / "load.py").read_text()
    assert "axisymmetric" not in text, "scene.py repeats the list of diffusion models"
    for name in MODELS:
        fickcam.load_scene(dict(yaml.safe_load((CONFIGS / "yadav2017_cam.yaml").read_text()),
                                diffusion={"model": name}))
