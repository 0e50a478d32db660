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
    """Field names of the model(s) at ``loc`` (the location of an unknown key, which is
    its last element). Union branch tags in ``loc`` (class names) are skipped."""
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
    """The valid key nearest to the unknown one at ``loc``, if any is close."""
    if model is None or not loc or not isinstance(loc[-1], str):
        return None
    matches = closest_names(loc[-1], valid_keys(model, loc), n=1)
    return matches[0] if matches else None


def closest_names(name: str, names, n: int = 3) -> list[str]:
    """Up to ``n`` of ``names`` nearest to the unknown ``name`` (difflib's ratio >= 0.6,
    closest first; else those it begins, 'spring' for 'spring_rate')."""
    names = list(names)
    matches = difflib.get_close_matches(name, names, n=n, cutoff=0.6)
    if not matches and name:
        matches = [k for k in names if k.startswith(name)][:n]
    return matches


def short_names(paths: list[str]) -> dict[str, str]:
    """The shortest tail of each dotted path that tells the paths apart
    (``environment.history.0.temperature`` → ``temperature``)."""
    depth = 1
    while True:
        tails = {p: ".".join(p.split(".")[-depth:]) for p in paths}
        if len(set(tails.values())) == len(paths) or depth > max(p.count(".") for p in paths):
            return tails
        depth += 1
