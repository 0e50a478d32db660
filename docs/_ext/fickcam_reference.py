"""Reference pages generated from the code: scene keys from the pydantic scene models,
result variables from :mod:`fickcam.schema`, the command line from its argparse parser.

Sphinx calls :func:`setup`; the pages are written to ``docs/reference/`` when the build
starts, so they cannot fall behind the code. The functions that build the Markdown need
no Sphinx, so the test suite checks them directly.
"""
from __future__ import annotations

import argparse
import inspect
import typing
from pathlib import Path

import yaml

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from fickcam import schema
from fickcam.cli.parser import build_parser
from fickcam.scene.sections import SceneModel
from fickcam.quantities.parsing import SI_UNITS

EXAMPLES = Path(__file__).resolve().parents[2] / "configs"
NAMED_MAPPINGS = ("materials", "limits")
GENERATED = ("scene.md", "results.md", "cli.md")


# -- scene keys -------------------------------------------------------------------------

def _closure_values(metadata) -> dict:
    """The values a unit validator was built with (``dimension``, ``si_unit``, bounds)."""
    values = {}
    for item in metadata:
        func = getattr(item, "func", None)
        if func is None:
            continue
        if func.__name__ == "temperature_difference":
            values["unit"] = "K (a difference)"
        try:
            values.update(inspect.getclosurevars(func).nonlocals)
        except TypeError:
            continue
    return values


def _unit_and_bounds(annotation) -> tuple[str, str]:
    """The SI unit a bare number is read in, and the bounds, of a unit-parsed field."""
    metadata = getattr(annotation, "__metadata__", ())
    values = _closure_values(metadata)
    unit = values.get("unit") or SI_UNITS.get(values.get("dimension", ""), "") or values.get("si_unit", "")
    unit = {"percent": "%", "": "1" if values.get("dimension") == "fraction" else ""}.get(unit, unit)
    bounds = [text for flag, text in (("positive", "> 0"), ("nonnegative", ">= 0")) if values.get(flag)]
    if values.get("upper") is not None:
        bounds.append(f"<= {values['upper']:g}")
    return unit.replace("**", "^").replace("*", " "), ", ".join(bounds)


def _models_in(annotation) -> list[type[BaseModel]]:
    """The scene-section models an annotation holds (through Optional, list, dict, Union)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    found = []
    for arg in typing.get_args(annotation):
        found += [m for m in _models_in(arg) if m not in found]
    return found


def _type_text(annotation) -> str:
    """A short readable type: unit-parsed floats as ``quantity``, sections by model name."""
    if annotation is type(None):
        return ""
    origin = typing.get_origin(annotation)
    args = typing.get_args(annotation)
    if origin is typing.Annotated:
        return "quantity" if args[0] is float else _type_text(args[0])
    if origin is typing.Literal:
        return "name"
    if origin in (list, tuple):
        return "list of " + " / ".join(filter(None, {_type_text(a) for a in args if a is not Ellipsis}))
    if origin is dict:
        return "mapping of " + _type_text(args[1])
    if args:
        parts = [_type_text(a) for a in args]
        return " or ".join(dict.fromkeys(p for p in parts if p))
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return "section"
    return getattr(annotation, "__name__", str(annotation))


def _allowed(annotation) -> str:
    """The allowed names of a Literal field, anywhere inside the annotation."""
    if typing.get_origin(annotation) is typing.Literal:
        return ", ".join(f"`{a}`" for a in typing.get_args(annotation))
    found = [_allowed(arg) for arg in typing.get_args(annotation)]
    return "; ".join(text for text in found if text)


def _default_text(field) -> str:
    if field.is_required():
        return "required"
    default = field.default
    if default is PydanticUndefined:
        return "computed"
    if isinstance(default, BaseModel):
        return "(section defaults)"
    return "none" if default is None else f"`{default!r}`"


def scene_key_rows(model: type[BaseModel] = SceneModel, prefix: str = "",
                   seen: tuple = ()) -> list[dict]:
    """One row per key the scene models accept: the dotted key (``NAME`` for a name the
    user chooses), its type, unit, bounds, default, allowed values and description."""
    rows = []
    for name, field in model.model_fields.items():
        key = f"{prefix}{field.alias or name}"
        annotation = field.annotation
        unit, bounds = _unit_and_bounds(typing.Annotated[annotation, *field.metadata]
                                        if field.metadata else annotation)
        if not unit:
            for arg in typing.get_args(annotation):
                unit, bounds = _unit_and_bounds(arg)
                if unit:
                    break
        shown = "quantity" if field.metadata and unit else _type_text(annotation)
        rows.append({"key": key, "type": shown, "unit": unit, "bounds": bounds,
                     "default": _default_text(field), "allowed": _allowed(annotation),
                     "description": (field.description or "").strip()})
        keyed = typing.get_origin(annotation) is dict or "dict[str," in str(annotation)
        for sub in _models_in(annotation):
            if sub in seen:
                continue
            sub_prefix = f"{key}.NAME." if keyed and _is_named_mapping(annotation, sub) else f"{key}."
            rows += scene_key_rows(sub, sub_prefix, seen + (model,))
    return rows


def _is_named_mapping(annotation, model) -> bool:
    """True when ``model`` appears as the values of a ``dict[str, model]``."""
    if typing.get_origin(annotation) is dict:
        return model in _models_in(typing.get_args(annotation)[1])
    return any(_is_named_mapping(arg, model) for arg in typing.get_args(annotation))


def _flatten(value, prefix: str, out: dict) -> None:
    """Dotted keys of a scene's values (the entries of named mappings as ``NAME``)."""
    if isinstance(value, list):
        for item in value:
            _flatten(item, prefix, out)
        return
    if not isinstance(value, dict):
        out.setdefault(prefix, value)
        return
    out.setdefault(prefix, None)
    for key, item in value.items():
        named = prefix.split(".")[-1] in NAMED_MAPPINGS and prefix.count(".") == 0
        _flatten(item, f"{prefix}.NAME" if named else f"{prefix}.{key}" if prefix else str(key), out)


def example_values(folder: Path = EXAMPLES) -> dict[str, object]:
    """The first value each dotted key takes in the example scenes (sweep files left out)."""
    found: dict[str, object] = {}
    for path in sorted(folder.glob("*.yaml")):
        scene = yaml.safe_load(path.read_text())
        if isinstance(scene, dict) and "base" not in scene:
            flat: dict[str, object] = {}
            _flatten(scene, "", flat)
            for key, value in flat.items():
                if value is not None and key not in found:
                    found[key] = value
    return found


def _value_text(row: dict) -> str:
    """What a key takes, in one cell: ``quantity in K, > 0``, ``str; one of `a`, `b```."""
    text = _cell(row["type"]) + (f" in {row['unit']}" if row["unit"] else "")
    text += f", {row['bounds']}" if row["bounds"] else ""
    return text + (f"; one of {row['allowed']}" if row["allowed"] else "")


SCENE_COLUMNS = ["| key | meaning | value | default | example |", "|---|---|---|---|---|"]


def scene_reference_markdown() -> str:
    """The scene reference page as MyST Markdown: a table per section of the scene, each
    key under the dotted name of the section it is written in."""
    lines = ["# Scene keys", "",
             "Every key a scene accepts, generated from the scene models when the documentation "
             "is built, in a table per section: `temperature_rise` under `environment.state` is "
             "written `environment: {state: {temperature_rise: ...}}`. `NAME` stands for a name "
             "you choose (a material, a limited variable). "
             "A quantity is a number in the SI unit given (a percentage for `%`) or a string with "
             "its unit (`\"30 mm\"`, `\"113 degC\"`, `\"60 d\"`); defaults are in that SI unit. "
             "The meaning gives the unit of a quantity in brackets. The example is the first "
             "value the key takes in the example scenes (`fickcam examples --copy DIR`). "
             "A key that is not listed is refused as `scene.yaml:LINE key: unknown key; did you "
             "mean ...?`, and a value out of its bounds or of the wrong dimension as "
             "`scene.yaml:LINE key: reason`, exit status 2.", ""]
    examples = example_values()
    tables: dict[str, list[str]] = {}
    for row in scene_key_rows():
        parent, _, leaf = row["key"].rpartition(".")
        example = examples.get(row["key"])
        shown = "" if example is None else f"`{_cell(str(example))}`"
        tables.setdefault(parent, []).append(
            f"| `{leaf}` | {_cell(row['description'])} | {_value_text(row)} "
            f"| {_cell(row['default'])} | {shown} |")
    opened = set()
    for parent, rows in tables.items():
        top = parent.split(".")[0]
        if parent and top not in opened:  # each section of the scene opens with its own heading
            lines += ["", f"## `{top}`"]
            opened.add(top)
        heading = "## Top level" if not parent else f"### `{parent}`" if "." in parent else ""
        lines += ["", heading, ""] if heading else [""]
        lines += [*SCENE_COLUMNS, *rows]
    return "\n".join(lines) + "\n"


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


# -- result variables -------------------------------------------------------------------

def results_reference_markdown() -> str:
    """The result variables and coordinates page, from :mod:`fickcam.schema`."""
    lines = ["# Result variables", "",
             "Every variable a result Dataset can hold, generated from the schema when the "
             "documentation is built (`fickcam schema` prints the same list). A variable is "
             "present when the scene computes it; `NAME_design` rows hold the as-designed "
             "value (dry, at the reference temperature).", "",
             "## Coordinates", "", "| coordinate | units | meaning |", "|---|---|---|"]
    for name, (units, meaning) in schema.COORDINATES.items():
        lines.append(f"| `{name}` | {units or '-'} | {meaning} |")
    lines += ["", "## Variables", "", schema.markdown_table()]
    return "\n".join(lines) + "\n"


# -- command line -----------------------------------------------------------------------

def subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    """The parser's subcommands by name."""
    for action in parser._actions:  # argparse has no public accessor for subparsers
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _options_table(parser: argparse.ArgumentParser) -> list[str]:
    rows = ["| argument | default | help |", "|---|---|---|"]
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
            continue
        names = ", ".join(f"`{s}`" for s in action.option_strings) or f"`{action.dest}`"
        if action.option_strings and action.nargs != 0:
            names += f" `{action.metavar or action.dest.upper()}`"
        default = "" if action.default in (None, argparse.SUPPRESS, False) else f"`{action.default!r}`"
        rows.append(f"| {names} | {default} | {_cell(' '.join((action.help or '').split()))} |")
    return rows


def cli_reference_markdown() -> str:
    """The command-line reference page, from the argparse parser."""
    parser = build_parser()
    lines = ["# Command line", "",
             "Generated from the argument parser when the documentation is built; "
             "`fickcam COMMAND --help` prints the same with examples.", "",
             "```text", parser.format_usage().strip(), "```", ""] + _options_table(parser)
    for name, command in subcommands(parser).items():
        lines += ["", f"## `fickcam {name}`", "", " ".join((command.description or "").split()), "",
                  "```text", command.format_usage().strip(), "```", ""] + _options_table(command)
        if command.epilog:
            lines += ["", "```text", command.epilog.strip(), "```"]
    return "\n".join(lines) + "\n"


# -- Sphinx -----------------------------------------------------------------------------

def write_reference_pages(folder: Path) -> None:
    """Write the generated pages into ``folder`` (only when their text changed)."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in zip(GENERATED, (scene_reference_markdown(), results_reference_markdown(),
                                      cli_reference_markdown())):
        path = folder / name
        if not path.exists() or path.read_text() != text:
            path.write_text(text)


def _on_builder_inited(app) -> None:
    write_reference_pages(Path(app.srcdir) / "reference")


def setup(app):
    app.connect("builder-inited", _on_builder_inited)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
