"""The valid keys at a place in a scene model, to suggest the one a user meant.

An unknown key's location (pydantic's ``loc``) is walked through the model's field
annotations (unions, optionals, lists and dicts opened), and the closest field name of
the model(s) found there is offered (difflib's ratio, Python standard library).
"""
from __future__ import annotations

import difflib
import types
import typing

from pydantic import BaseModel


def _open(annotation) -> list:
    """The concrete types inside Annotated / Optional / Union."""
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        return _open(typing.get_args(annotation)[0])
    if origin in (typing.Union, types.UnionType):
        return [t for a in typing.get_args(annotation) for t in _open(a)]
    return [annotation]


def _step(annotation, key) -> list:
    """The annotation(s) one location step below ``annotation``."""
    found = []
    for t in _open(annotation):
        origin = typing.get_origin(t)
        if isinstance(t, type) and issubclass(t, BaseModel):
            if isinstance(key, str) and key in t.model_fields:
                found.append(t.model_fields[key].annotation)
        elif origin in (list, tuple) and isinstance(key, int):
            found += list(typing.get_args(t)[:1])
        elif origin is dict and isinstance(key, str):
            found += list(typing.get_args(t)[1:2])
    return found


def valid_keys(model: type[BaseModel], loc: tuple) -> list[str]:
    """Field names of the model(s) at ``loc``, the location of an unknown key.

    Parameters
    ----------
    model : type of pydantic.BaseModel
        The top model (e.g. the scene's).
    loc : tuple of str or int
        pydantic's location of the unknown key, which is its last element; union branch tags
        (class names) in it are skipped.

    Returns
    -------
    list of str
        The field names of every model found there, without repeats.
    """
    current = [model]
    for key in loc[:-1]:
        below = [a for t in current for a in _step(t, key)]
        if below:
            current = below
    names = []
    for t in (x for a in current for x in _open(a)):
        if isinstance(t, type) and issubclass(t, BaseModel):
            names += [n for n in t.model_fields if n not in names]
    return names


def closest_key(model: type[BaseModel] | None, loc: tuple) -> str | None:
    """The valid key nearest to the unknown one at ``loc``, if any is close.

    Parameters
    ----------
    model : type of pydantic.BaseModel or None
        The top model; None gives None.
    loc : tuple of str or int
        pydantic's location of the unknown key (its last element).

    Returns
    -------
    str or None
        The suggestion (:func:`closest_names`), or None.
    """
    if model is None or not loc or not isinstance(loc[-1], str):
        return None
    matches = closest_names(loc[-1], valid_keys(model, loc), n=1)
    return matches[0] if matches else None


def closest_names(name: str, names, n: int = 3) -> list[str]:
    """Up to ``n`` of ``names`` nearest to the unknown ``name``.

    Parameters
    ----------
    name : str
        The unknown name.
    names : iterable of str
        The valid names.
    n : int
        The most suggestions returned [1].

    Returns
    -------
    list of str
        Those with difflib's ratio >= 0.6, closest first; when none is, those that ``name``
        begins (``spring_rate`` for ``spring``).
    """
    names = list(names)
    matches = difflib.get_close_matches(name, names, n=n, cutoff=0.6)
    if not matches and name:
        matches = [k for k in names if k.startswith(name)][:n]
    return matches


def short_names(paths: list[str]) -> dict[str, str]:
    """The shortest tail of each dotted path that tells the paths apart.

    Parameters
    ----------
    paths : list of str
        Dotted paths (``environment.history.0.temperature``).

    Returns
    -------
    dict of str to str
        Each path -> its shortest distinct tail (``temperature``).
    """
    depth = 1
    while True:
        tails = {p: ".".join(p.split(".")[-depth:]) for p in paths}
        if len(set(tails.values())) == len(paths) or depth > max(p.count(".") for p in paths):
            return tails
        depth += 1
