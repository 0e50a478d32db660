"""The examples in the README and the user guide stay true: every ``fickcam`` command
line in them parses, every YAML scene in them loads, and no page names a file outside
the repository."""
from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
import yaml

import fickcam
from fickcam.cli_parser import build_parser

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", ROOT / "CONTRIBUTING.md",
         *sorted((ROOT / "docs").glob("*.md")), *sorted((ROOT / "docs").glob("*/*.md"))]
FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.MULTILINE | re.DOTALL)


def _fences(language: str):
    for page in PAGES:
        for lang, body in FENCE.findall(page.read_text()):
            if lang == language:
                yield page, body


def _command_lines():
    for page, body in _fences("bash"):
        text = re.sub(r"\\\n\s*", " ", body)  # continued lines
        for line in text.splitlines():
            line = line.split(" # ")[0].strip()
            for part in line.split("&&"):
                part = part.strip()
                if part.startswith("fickcam "):
                    yield page.relative_to(ROOT).as_posix(), part


COMMANDS = sorted(set(_command_lines()))


def test_the_pages_hold_commands():
    assert len(COMMANDS) > 30


@pytest.mark.parametrize("page, line", COMMANDS)
def test_every_documented_command_parses(page, line):
    build_parser().parse_args(shlex.split(line)[1:])


def test_the_readme_scene_loads():
    scenes = [yaml.safe_load(body) for _, body in _fences("yaml") if "name:" in body]
    readme = [body for page, body in _fences("yaml") if page.name == "README.md"]
    assert readme, "the README shows a scene"
    scene = fickcam.load_scene(yaml.safe_load(readme[0]))
    assert scene.name == "nylon-eccentric-cam"
    assert scenes


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_no_page_names_a_file_outside_the_repository(page):
    text = page.read_text()
    for outside in ("SPEC.md", "../shared", "seeds/", "/work/"):
        assert outside not in text, f"{page.name} names {outside}"


def test_the_readme_python_quick_start_runs(tmp_path, monkeypatch):
    """The README's Python block, run as written from a folder holding ``configs/``."""
    import matplotlib

    matplotlib.use("Agg")
    (tmp_path / "configs").symlink_to(ROOT / "configs")
    monkeypatch.chdir(tmp_path)
    blocks = [body for page, body in _fences("python") if page.name == "README.md"]
    assert len(blocks) == 1
    namespace: dict = {}
    exec(compile(blocks[0], "README.md", "exec"), namespace)
    assert (tmp_path / "outputs" / "run.h5").exists()
    assert "lift" in namespace["ds"]
