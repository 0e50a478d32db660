"""YAML with line numbers: scene and sweep files are read with ``yaml.SafeLoader`` only
(a ``!!python`` tag is refused, never executed), duplicate keys are refused, and every
key path is mapped to its line so that each problem is reported as ``scene.yaml:LINE
key.path: reason`` (pydantic errors included, :func:`~fickcam.scene.yamldoc.problems_from_validation`).

A document is bounded before it is built (:func:`~fickcam.scene.yamldoc.check_bounds`): its size in bytes, and,
from the parser's events alone, its number of values and its depth once every alias is
expanded. An alias bomb (nine levels of nine-fold aliases: billions of values from a
kilobyte) is refused at the alias that crosses the bound, without building anything.
"""
from __future__ import annotations

import itertools
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml
from pydantic import ValidationError

from ..errors import Problem, SceneError
from .keys import closest_key


#: the largest scene or sweep file read [bytes] (the example scenes are under 3 kB)
MAX_BYTES = 2 * 2**20
#: the most values (keys, scalars, lists and mappings) a document may hold once its
#: aliases are expanded: each use of an alias counts its whole anchored value
MAX_NODES = 100_000
#: the deepest nesting of lists and mappings, aliases expanded (a scene nests about 6)
MAX_DEPTH = 40

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


def _too_large(file: str, what: str, size: int) -> SceneError:
    return SceneError([Problem(file, None, "", f"{what} refused: {size / 2**20:.1f} MiB; a "
                               f"{what} file is at most {MAX_BYTES / 2**20:g} MiB")])


def _bound_problem(file: str, what: str, mark, reason: str) -> SceneError:
    return SceneError([Problem(file, mark.line + 1 if mark is not None else None, "",
                               f"{what} refused: {reason}")])


def check_bounds(text: str, *, file: str = "<scene>", what: str = "scene") -> None:
    """Refuse a YAML document larger than the bounds, before any of it is built.

    The parser's events are read once: each scalar, list and mapping counts one value, each
    alias the values of its anchor (its whole subtree, as walking the built document would
    visit it), and the depth is the nesting of the expanded tree. The first event past a
    bound stops the reading, so the time and memory are those of :data:`MAX_NODES` events at
    most.

    Parameters
    ----------
    text, file, what : str
        The YAML, the file's name and what it is (``"scene"``, ``"sweep"``), as for
        :func:`parse_yaml`.

    Raises
    ------
    fickcam.errors.SceneError
        One problem, at the line where the document passes :data:`MAX_BYTES`,
        :data:`MAX_NODES` or :data:`MAX_DEPTH`.
    yaml.YAMLError
        For a syntax error met on the way (reported by :func:`parse_yaml`).
    """
    size = len(text.encode("utf-8", errors="surrogatepass"))
    if size > MAX_BYTES:
        raise _too_large(file, what, size)
    anchored: dict[str, tuple[int, int]] = {}  # anchor -> (values, depth) of its subtree
    open_nodes: list[list] = []  # [values so far, deepest child, anchor] per open collection
    total = 0
    loader = _SAFE_LOADER(text)
    try:
        while not loader.check_event(yaml.StreamEndEvent):
            event = loader.get_event()
            if isinstance(event, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
                open_nodes.append([1, 0, event.anchor])
                values, depth = 1, 0  # its depth is that of the open collections
            elif isinstance(event, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
                values, below, anchor = open_nodes.pop()
                if anchor is not None:
                    anchored[anchor] = (values, below + 1)
                if open_nodes:
                    open_nodes[-1][0] += values
                    open_nodes[-1][1] = max(open_nodes[-1][1], below + 1)
                continue
            elif isinstance(event, (yaml.ScalarEvent, yaml.AliasEvent)):
                values, depth = anchored.get(event.anchor, (1, 0)) \
                    if isinstance(event, yaml.AliasEvent) else (1, 0)
                if isinstance(event, yaml.ScalarEvent) and event.anchor is not None:
                    anchored[event.anchor] = (1, 0)
                if open_nodes:
                    open_nodes[-1][0] += values
                    open_nodes[-1][1] = max(open_nodes[-1][1], depth)
            else:
                continue
            total += values
            if total > MAX_NODES:
                raise _bound_problem(file, what, event.start_mark, (
                    f"more than {MAX_NODES:,} values once its aliases are expanded "
                    f"(each use of an alias counts all of its values)"))
            if len(open_nodes) + depth > MAX_DEPTH:
                raise _bound_problem(file, what, event.start_mark, (
                    f"nested more than {MAX_DEPTH} levels deep once its aliases are expanded"))
    finally:
        loader.dispose()


def check_mapping_bounds(data, *, file: str = "<dict>", what: str = "scene") -> None:
    """Refuse a scene given as Python data (a dict of lists, mappings and scalars) beyond
    the bounds of a YAML document, before anything is written or built from it.

    The data are walked once, without recursion, as :func:`check_bounds` reads events:
    each key, scalar, list and mapping counts one value (an object shared by several
    places counts at each, as an alias does), the nesting is bounded (a mapping that holds
    itself is refused by its depth), and the text of its keys and scalars by
    :data:`MAX_BYTES`. The first value past a bound stops the walk, so the cost is that of
    :data:`MAX_NODES` values at most.

    Parameters
    ----------
    data : object
        The scene's data (a mapping, as :func:`fickcam.load_scene` takes it).
    file : str
        The name problems give it (``"<dict>"``).
    what : str
        What the data are, for messages (``"scene"``).

    Raises
    ------
    fickcam.errors.SceneError
        One problem naming the bound passed.
    """
    total, size = 1, 0
    stack = [(data, 1)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, (dict, list, tuple)):  # its items (and keys) count as they come
            total += len(value) * (2 if isinstance(value, dict) else 1)
        if total > MAX_NODES:
            raise _bound_problem(file, what, None, f"more than {MAX_NODES:,} values (each "
                                 f"place a shared object is used counts all of its values)")
        if depth > MAX_DEPTH:
            raise _bound_problem(file, what, None, f"nested more than {MAX_DEPTH} levels deep "
                                 f"(or holds itself)")
        if isinstance(value, dict):
            size += sum(len(str(key)) for key in value)
            stack.extend((item, depth + 1) for item in value.values())
        elif isinstance(value, (list, tuple)):
            stack.extend((item, depth + 1) for item in itertools.islice(value, MAX_NODES))
        else:
            size += len(value) if isinstance(value, (str, bytes)) else 8
        if size > MAX_BYTES:
            raise _bound_problem(file, what, None, f"more than {MAX_BYTES / 2**20:g} MiB of "
                                 f"keys and values; a {what} file is at most "
                                 f"{MAX_BYTES / 2**20:g} MiB")


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
        with open(path, "rb") as handle:  # no more than the bound is read
            data = handle.read(MAX_BYTES + 1)
            if len(data) > MAX_BYTES:
                raise _too_large(file, what, max(os.fstat(handle.fileno()).st_size, len(data)))
        text = data.decode("utf-8")
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
        check_bounds(text, file=file, what=what)
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
