"""The example gallery: one page per example scene in ``configs/``, with what it shows,
the scene, the commands, and its figures, drawn when the documentation builds.

Each scene is run in the build process with :func:`fickcam.run` and drawn with
:func:`fickcam.plotting.plot`; figures are kept in ``docs/gallery/_figures/`` and
redrawn when the scene file is newer than them (a fresh build draws them all).
"""
from __future__ import annotations

import re
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
SCENE_TABLE = ROOT / "docs" / "guide" / "scenes.md"


def example_scenes(folder: Path = CONFIGS) -> list[Path]:
    """The example scenes (sweep files, which have a ``base:`` scene, left out)."""
    scenes = []
    for path in sorted(folder.glob("*.yaml")):
        document = yaml.safe_load(path.read_text())
        if isinstance(document, dict) and "base" not in document:
            scenes.append(path)
    return scenes


def what_each_shows(table: Path = SCENE_TABLE) -> dict[str, str]:
    """The "what it shows" column of the example table on the scenes page, by file name."""
    found = {}
    for name, text in re.findall(r"^\| `configs/([\w.]+)` \| (.*) \|$", table.read_text(),
                                 flags=re.MULTILINE):
        found[name] = text
    return found


def draw_figures(scene: Path, outdir: Path) -> list[Path]:
    """Run ``scene`` and write every figure its result has data for into ``outdir``."""
    import fickcam
    from fickcam.plotting import plot

    newest = max((p.stat().st_mtime for p in outdir.glob("*.png")), default=0.0)
    if newest > scene.stat().st_mtime:
        return sorted(outdir.glob("*.png"))
    for old in outdir.glob("*.png"):
        old.unlink()
    return sorted(plot(fickcam.run(fickcam.load_scene(scene)), outdir, "all").paths)


def scene_page(scene: Path, shows: str, figures: list[Path], folder: Path) -> str:
    """The gallery page of one example scene, as MyST Markdown."""
    document = yaml.safe_load(scene.read_text())
    title = document.get("description") or document["name"]
    lines = [f"# {title}", "", shows or "", "",
             f"The scene, `configs/{scene.name}` (also `fickcam examples --copy DIR`):", "",
             f"```{{literalinclude}} ../../configs/{scene.name}", ":language: yaml",
             ':start-at: "name:"', "```", "", "Run it and draw its figures:", "", "```bash",
             f"fickcam run configs/{scene.name} -o outputs/{scene.stem}.h5",
             f"fickcam plot outputs/{scene.stem}.h5 -o outputs/{scene.stem}-plots", "```", ""]
    for figure in figures:
        lines += [f"![{figure.stem}]({figure.relative_to(folder).as_posix()})", ""]
    return "\n".join(lines)


def write_gallery(folder: Path) -> None:
    """Run every example scene and write its page and the gallery index into ``folder``."""
    shows = what_each_shows()
    names = []
    for scene in example_scenes():
        figures = draw_figures(scene, folder / "_figures" / scene.stem)
        page = scene_page(scene, shows.get(scene.name, ""), figures, folder)
        path = folder / f"{scene.stem}.md"
        if not path.exists() or path.read_text() != page:
            path.write_text(page)
        names.append(scene.stem)
    index = ["# Example gallery", "",
             "Each example scene of `configs/`, run and drawn when this documentation was "
             "built. `fickcam examples --copy DIR` copies them (with the data files they read).",
             "", "```{toctree}", ":maxdepth: 1", "", *names, "```", ""]
    (folder / "index.md").write_text("\n".join(index))


def _on_builder_inited(app) -> None:
    folder = Path(app.srcdir) / "gallery"
    folder.mkdir(exist_ok=True)
    write_gallery(folder)


def setup(app):
    app.connect("builder-inited", _on_builder_inited)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
