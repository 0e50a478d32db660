"""YAML with line numbers: scene and sweep files are read with ``yaml.SafeLoader`` only
(a ``!!python`` tag is refused, never executed), duplicate keys are refused, and every
key path is mapped to its line so that each problem is reported as ``scene.yaml:LINE
key.path: reason`` (pydantic errors included, :func:`~fickcam.yamldoc.problems_from_validation`).
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml
from pydantic import ValidationError

from .errors import Problem, SceneError
from .keys import closest_key


#: PyYAML's safe loader, on libyaml's parser where PyYAML was built with it (the same
#: documents, nodes and marks; parsing several times faster)
_SAFE_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class _LineLoader(_SAFE_LOADER):
    """Safe loader that refuses duplicate keys (PyYAML silently keeps the last)."""

    def construct_mapping(self, node, deep=False):
        seen: dict[Any, Any] = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=deep)
            if key in seen:
                raise yaml.constructor.ConstructorError(
                    None, None, f"duplicate key {key!r}", key_node.start_mark
                )
            seen[key] = key_node
        return super().construct_mapping(node, deep=deep)


def _tab_at(text: str, mark) -> bool:
    """Whether the character at a YAML error's mark is a tab (libyaml's message omits it)."""
    lines = text.splitlines()
    return mark.line < len(lines) and lines[mark.line][mark.column:mark.column + 1] == "\t"


def _line_map(node, path: tuple = (), lines: dict | None = None) -> dict[tuple, int]:
    """Map every key path (tuple of keys / indices) to its 1-based line."""
    lines = {} if lines is None else lines
    if isinstance(node, yaml.MappingNode):
        for key_node, value_node in node.value:
            key = key_node.value
            lines[path + (key,)] = key_node.start_mark.line + 1
            _line_map(value_node, path + (key,), lines)
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            lines[path + (index,)] = item.start_mark.line + 1
            _line_map(item, path + (index,), lines)
    return lines


@dataclass
class YamlDocument:
    """A parsed YAML mapping with the line of every key path.

    Parameters
    ----------
    data : dict
        The mapping.
    lines : dict of tuple to int
        Key path (keys and list indices) -> its line, from 1.
    file : str
        The file's name, for problems.
    text : str
        The file's text.
    """

    data: dict
    lines: dict[tuple, int]
    file: str
    text: str

    def line_of(self, path: tuple) -> int | None:
        """Line of ``path`` or of its nearest ancestor that has one.

        Parameters
        ----------
        path : tuple of str or int
            A key path.

        Returns
        -------
        int or None
            The line, from 1 (1 when no ancestor has one; None for an empty file).
        """
        path = tuple(path)
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path[:-1]
        return 1 if self.text.strip() else None

    def problem(self, path: tuple, reason: str) -> Problem:
        """A :class:`~fickcam.errors.Problem` at ``path``'s line.

        Parameters
        ----------
        path : tuple of str or int
            The key path at fault.
        reason : str
            Why, in one line.

        Returns
        -------
        fickcam.errors.Problem
            The problem, its key the dotted path.
        """
        key = ".".join(str(p) for p in path)
        return Problem(self.file, self.line_of(path), key, reason)


def read_yaml(source: str | os.PathLike, *, what: str = "scene") -> YamlDocument:
    """Read a YAML mapping safely, with line numbers.

    Parameters
    ----------
    source : str or os.PathLike
        The file.
    what : str
        What the file is, for messages (``"scene"``, ``"sweep"``).

    Returns
    -------
    YamlDocument
        The mapping and its lines.

    Raises
    ------
    fickcam.errors.SceneError
        When the file is missing or unreadable, or as :func:`parse_yaml`.
    """
    path = Path(source)
    file = str(source)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneError([Problem(file, None, "", f"no such {what} file")]) from None
    except IsADirectoryError:
        raise SceneError([Problem(file, None, "", f"is a directory, not a {what} file")]) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise SceneError([Problem(file, None, "", f"cannot read: {exc}")]) from None
    return parse_yaml(text, file=file, what=what)


def parse_yaml(text: str, *, file: str = "<scene>", what: str = "scene") -> YamlDocument:
    """Parse YAML text safely (PyYAML's safe loader, duplicate keys refused), with line numbers.

    Parameters
    ----------
    text : str
        The YAML.
    file : str
        The file's name, for problems.
    what : str
        What the text is, for messages.

    Returns
    -------
    YamlDocument
        The mapping, with the line of every key path.

    Raises
    ------
    fickcam.errors.SceneError
        For an empty document, a syntax error, a tag (never executed), a duplicate key or a
        document that is not a mapping, with its line.
    """
    loader = None
    try:
        loader = _LineLoader(text)
        node = loader.get_single_node()
        if node is None:
            raise SceneError([Problem(file, None, "", f"empty {what} file")])
        data = loader.construct_document(node)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else None
        reason = exc.problem or str(exc)
        if "could not determine a constructor" in reason or "tag" in reason:
            reason = f"tag refused (only plain YAML is read): {reason}"
        reason = " ".join(f"{exc.context or ''} {reason}".split())
        if mark is not None and _tab_at(text, mark):
            reason += " (a tab: YAML indents with spaces)"
        raise SceneError([Problem(file, line, "", f"YAML syntax: {reason}")]) from None
    except yaml.YAMLError as exc:
        reason = " ".join(str(exc).split())
        raise SceneError([Problem(file, None, "", f"YAML: {reason}")]) from None
    finally:
        if loader is not None:
            loader.dispose()
    if not isinstance(data, dict):
        raise SceneError([Problem(file, 1, "", f"a {what} must be a mapping of keys to values, "
                                                f"got {type(data).__name__}")])
    return YamlDocument(data=data, lines=_line_map(node), file=file, text=text)


def problems_from_validation(error: ValidationError, doc: YamlDocument,
                             prefix: tuple = (), model=None) -> list[Problem]:
    """One Problem per pydantic error, located at its key path's line.

    Parameters
    ----------
    error : pydantic.ValidationError
        The validation error.
    doc : YamlDocument
        The file validated.
    prefix : tuple of str or int
        The key path of the validated section inside ``doc``.
    model : type of pydantic.BaseModel, optional
        The validated class: an unknown key names the closest valid key.

    Returns
    -------
    list of fickcam.errors.Problem
        The problems, in pydantic's order.
    """
    problems = []
    for item in error.errors(include_url=False):
        loc = tuple(p for p in item["loc"] if not (isinstance(p, str) and p.startswith("function-")))
        # drop pydantic's union branch tags (class names) from the location
        loc = tuple(p for p in loc if not (isinstance(p, str) and p[:1].isupper()))
        reason = item["msg"]
        if reason.startswith("Value error, "):
            reason = reason[len("Value error, "):]
        if item["type"] == "extra_forbidden":
            near = closest_key(model, loc)
            reason = "unknown key" + (f"; did you mean {near!r}?" if near else "")
        elif item["type"] == "missing":
            reason = "required key is missing"
        problems.append(doc.problem(prefix + loc, reason))
    return problems
