"""The example gallery (sphinx-gallery, ``docs/examples/``) has a page for every example
scene, and every figure on it is captioned: each cell that draws is introduced by a text
cell with a heading and at least one sentence saying what the figure shows."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from fickcam.scene import examples as example_scenes
EXAMPLES = Path(__file__).resolve().parents[1] / "docs" / "examples"


def scene_names() -> list[str]:
    """The example scenes (sweep files, which have a ``base:`` scene, left out)."""
    return [name for name in example_scenes.names()
            if "base" not in yaml.safe_load(example_scenes.path(name).read_text())]


def cells(script: str) -> list[str]:
    """The cells of a sphinx-gallery script (split at ``# %%``), the title docstring first."""
    return re.split(r"^# %%\n", script, flags=re.MULTILINE)


def test_every_example_scene_has_a_gallery_script():
    missing = [name for name in scene_names() if not (EXAMPLES / f"plot_{name}.py").is_file()]
    assert not missing, f"example scenes without docs/examples/plot_NAME.py: {missing}"


@pytest.mark.parametrize("script", sorted(EXAMPLES.glob("plot_*.py")), ids=lambda p: p.name)
def test_every_figure_of_a_gallery_script_is_captioned(script):
    parts = cells(script.read_text())
    title = parts[0].strip().strip('"').strip().split("\n")
    assert "degC" not in title[0], f"{script.name}: write °C in the title"
    for cell in parts[1:]:
        if "plot(" not in cell:
            continue
        text = [line[2:] for line in cell.split("\n") if line.startswith("# ")]
        assert len(text) >= 3 and set(text[1]) == {"-"}, f"{script.name}: a figure without a heading"
        assert len(" ".join(text[2:]).split()) >= 5, f"{script.name}: a figure without a caption"
