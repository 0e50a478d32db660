"""The optional extras (``pip install "fickcam[NAME]"``) and the one-line refusal when a
command needs one that is not installed.

A command that needs an extra asks for it with :func:`require` before it computes
anything, so that a missing extra costs the user neither time nor a partly written
output; :func:`installed` answers without importing the package (``distributed``
takes about 0.5 s to import).
"""
from __future__ import annotations

import importlib
import sys
from dataclasses import dataclass
from importlib.util import find_spec

from .errors import InputError


@dataclass(frozen=True)
class Extra:
    """One optional extra of ``pip install "fickcam[NAME]"``.

    Parameters
    ----------
    name : str
        Its name in ``fickcam[...]``.
    module : str
        The module it provides, as imported (``distributed``).
    package : str
        That module as users know it (``dask.distributed``).
    purpose : str
        What needs it: the start of the refusal.
    """

    name: str
    module: str
    package: str
    purpose: str


EXTRAS = {
    "dxf": Extra("dxf", "ezdxf", "ezdxf", "reading or writing DXF drawings"),
    "weather": Extra("weather", "pvlib", "pvlib", "reading weather files (TMY3, EPW, pvlib:NAME)"),
    "sweep": Extra("sweep", "distributed", "dask.distributed",
                   "a sweep on several worker processes or on a scheduler"),
}


class MissingExtra(InputError, ValueError):
    """A command (or a scene's file) needs an optional extra that is not installed.

    A ValueError too, so that a scene's checks report it at the key that needs it.

    Parameters
    ----------
    *args, **kwargs
        The message (:func:`install_hint`), as for :class:`Exception`.
    """


def install_hint(name: str) -> str:
    """``PURPOSE needs PACKAGE: pip install "fickcam[NAME]"``.

    Parameters
    ----------
    name : str
        A key of ``EXTRAS``.

    Returns
    -------
    str
        The line.
    """
    extra = EXTRAS[name]
    return f'{extra.purpose} needs {extra.package}: pip install "fickcam[{extra.name}]"'


def installed(name: str) -> bool:
    """Whether the extra ``name``'s module can be imported (found, not imported).

    Parameters
    ----------
    name : str
        The extra (``"dxf"``, ``"weather"``, ``"sweep"``).

    Returns
    -------
    bool
        True when its module is imported already or can be found.
    """
    module = EXTRAS[name].module
    if module in sys.modules:
        return sys.modules[module] is not None
    return find_spec(module) is not None


def require(name: str, advice: str = ""):
    """The module of the extra ``name``, imported.

    Parameters
    ----------
    name : str
        The extra, a key of ``EXTRAS``.
    advice : str
        What else the user can do, appended in brackets (``"or run with --workers 1"``).

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    MissingExtra
        When it is not installed: one line with the install command (exit status 2).
    """
    try:
        return importlib.import_module(EXTRAS[name].module)
    except ImportError:
        raise MissingExtra(install_hint(name) + (f" ({advice})" if advice else "")) from None
