"""The example scenes shipped with fickcam (``fickcam examples``).

They are the repository's ``configs/`` folder, packaged as ``fickcam/examples``
(a link in the source tree, real files in a wheel), so the command works the
same from a clone and from an installed package.
"""
from __future__ import annotations

import shutil
from pathlib import Path

import yaml

from ..errors import InputError

SUFFIXES = (".yaml", ".csv", ".dxf")


def folder() -> Path:
    """Where the example scenes are."""
    return Path(__file__).resolve().parents[1] / "examples"


def names() -> list[str]:
    """The example scene and sweep names (file names without ``.yaml``)."""
    return sorted(p.stem for p in folder().glob("*.yaml"))


def path(name: str) -> Path:
    """The file of example ``name``.

    Parameters
    ----------
    name : str
        The example, with or without ``.yaml``.

    Returns
    -------
    pathlib.Path
        Its file.

    Raises
    ------
    fickcam.errors.InputError
        When there is no such example (naming those there are).
    """
    stem = name[:-5] if name.endswith(".yaml") else name
    file = folder() / f"{stem}.yaml"
    if not file.is_file():
        raise InputError(f"no example {name!r} (have: {', '.join(names())})")
    return file


def describe(name: str) -> str:
    """One line: the scene's description, or what a sweep varies.

    Parameters
    ----------
    name : str
        The example.

    Returns
    -------
    str
        The line.

    Raises
    ------
    fickcam.errors.InputError
        When there is no such example.
    """
    data = yaml.safe_load(path(name).read_text(encoding="utf-8")) or {}
    if "base" in data:
        varied = ", ".join(data.get("grid") or data.get("random") or {})
        return f"sweep of {data['base']}: {varied}"
    return str(data.get("description") or data.get("name") or "")


def listing() -> str:
    """The examples with their descriptions, and how to use them."""
    width = max(len(n) for n in names())
    lines = [f"  {n:<{width}}  {describe(n)}" for n in names()]
    return "\n".join(["example scenes (fickcam examples NAME prints one; "
                      "--copy DIR copies them to edit):", *lines])


def _uses(file: Path) -> list[str]:
    """Files next to ``file`` that it names: a sweep's base scene, a history file, a cam's
    profile file (as made and as designed), the drawings of a cam and of links."""
    data = yaml.safe_load(file.read_text(encoding="utf-8")) or {}
    cam, linkage = data.get("cam") or {}, data.get("linkage") or {}
    used = [data.get("base"), (data.get("environment") or {}).get("history_file"),
            cam.get("profile_file"),
            ((data.get("design") or {}).get("cam") or {}).get("profile_file")]
    shapes = [cam] + [linkage.get(link) for link in ("crank", "coupler", "rocker")]
    for drawing in (shape.get("drawing") for shape in shapes if isinstance(shape, dict)):
        used.append(drawing.get("file") if isinstance(drawing, dict) else drawing)
    return [u for u in used if isinstance(u, str) and (folder() / u).is_file()]


def copy_to(target, which: list[str] | None = None) -> list[Path]:
    """Copy the named examples, with the files they use, into ``target``.

    Parameters
    ----------
    target : str or pathlib.Path
        The folder (made if needed).
    which : list of str, optional
        The examples; all of them (and their climate and profile files) when None or empty.

    Returns
    -------
    list of pathlib.Path
        The copies, in ``target``.

    Raises
    ------
    fickcam.errors.InputError
        When a file would be overwritten (nothing is copied then) or an example is unknown.
    """
    target = Path(target)
    files = ([path(n) for n in which] if which else
             sorted(p for p in folder().iterdir() if p.suffix in SUFFIXES))
    if which:  # a sweep needs its base scene, a scene its climate file
        files += [folder() / used for f in list(files) for used in _uses(f)
                  if (folder() / used) not in files]
    clashes = [str(target / f.name) for f in files if (target / f.name).exists()]
    if clashes:
        raise InputError(f"not overwriting {', '.join(clashes)}")
    target.mkdir(parents=True, exist_ok=True)
    return [Path(shutil.copyfile(f, target / f.name)) for f in files]
