"""What lives in a source checkout of fickcam and not in the installed package: the
benchmarks (``benchmarks/*.py``), which read the repository's ``configs/`` and
``tests/data/``. ``fickcam bench`` loads them from the checkout it finds; a wheel
alone has none and is refused in one line saying what to do.
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

from ..errors import InputError

#: a folder is a fickcam checkout when it holds these
MARKERS = ("pyproject.toml", "fickcam/__init__.py", "benchmarks")


def is_checkout(folder: Path) -> bool:
    """Whether ``folder`` is the root of a fickcam source checkout.

    Parameters
    ----------
    folder : pathlib.Path
        The folder.

    Returns
    -------
    bool
        True when it holds every one of :data:`MARKERS`.
    """
    return all((folder / marker).exists() for marker in MARKERS)


def repository_root(places: list[Path] | None = None) -> Path:
    """The first fickcam checkout among ``places``.

    Parameters
    ----------
    places : list of pathlib.Path, optional
        Folders to try, in order; by default the folder this package was installed from (an
        editable install), then the current directory and its parents.

    Returns
    -------
    pathlib.Path
        The checkout's root.

    Raises
    ------
    InputError
        No checkout is found (fickcam installed from a wheel, run outside a clone).
    """
    if places is None:
        here = Path.cwd().resolve()
        places = [Path(__file__).resolve().parents[2], here, *here.parents]
    for folder in places:
        if is_checkout(folder):
            return folder
    raise InputError("the benchmarks live in fickcam's source repository, not in the "
                     "installed package: run this from a clone of the repository "
                     "(git clone, then cd into it)")


def benchmark(name: str, root: Path | None = None) -> ModuleType:
    """The module ``benchmarks/NAME.py`` of the checkout (loaded once per process).

    Parameters
    ----------
    name : str
        The file's stem, e.g. ``"diffusion_tradeoff"``.
    root : pathlib.Path, optional
        The checkout's root; found by :func:`repository_root` when not given.
    """
    path = (root or repository_root()) / "benchmarks" / f"{name}.py"
    key = f"fickcam_benchmarks.{name}"
    if key not in sys.modules:
        spec = importlib.util.spec_from_file_location(key, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[key] = module  # dataclasses look their module up while it loads
        try:
            spec.loader.exec_module(module)
        except BaseException:
            del sys.modules[key]
            raise
    return sys.modules[key]
