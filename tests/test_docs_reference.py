"""The generated reference pages (scene keys, result variables, command line) list
everything the code accepts or produces. The generators are tested directly, so these
tests need no Sphinx; each list is compared with a source the generator does not read
(the models' JSON schema, the example scenes, the help text of every command)."""
from __future__ import annotations

import contextlib
import importlib.util
import io
import re
from pathlib import Path

import pytest

from fickcam import schema
from fickcam.cli.parser import build_parser
from fickcam.scene.sections import SceneModel

ROOT = Path(__file__).resolve().parents[1]


def _load_generator():
    spec = importlib.util.spec_from_file_location(
        "fickcam_reference", ROOT / "docs" / "_ext" / "fickcam_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


reference = _load_generator()


def _listed_keys(markdown: str) -> set[str]:
    """The keys in the first column of the reference tables, each under the dotted name of
    the section heading above its table (``### `cam.follower``` then ``| `mass` |``)."""
    keys, section = set(), ""
    for line in markdown.splitlines():
        heading = re.match(r"^#+ (?:`([^`]+)`|.*)$", line)
        if heading:
            section = heading.group(1) or ""
        row = re.match(r"^\| `([^`]+)` \|", line)
        if row:
            keys.add(f"{section}.{row.group(1)}" if section else row.group(1))
    return keys


def _schema_keys(node: dict, defs: dict, prefix: str, out: set, depth: int = 0) -> None:
    """Dotted keys of a JSON schema (``NAME`` for the entries of a free-named mapping)."""
    if depth > 12:
        return
    if "$ref" in node:
        _schema_keys(defs[node["$ref"].split("/")[-1]], defs, prefix, out, depth + 1)
        return
    for branch in node.get("anyOf", []) + node.get("oneOf", []) + node.get("allOf", []):
        _schema_keys(branch, defs, prefix, out, depth + 1)
    if node.get("type") == "array" and isinstance(node.get("items"), dict):
        _schema_keys(node["items"], defs, prefix, out, depth + 1)
    for name, sub in node.get("properties", {}).items():
        key = f"{prefix}{name}"
        out.add(key)
        _schema_keys(sub, defs, f"{key}.", out, depth + 1)
    extra = node.get("additionalProperties")
    if isinstance(extra, dict) and extra:
        _schema_keys(extra, defs, f"{prefix}NAME.", out, depth + 1)


def test_every_scene_key_of_the_models_is_in_the_reference():
    json_schema = SceneModel.model_json_schema()
    keys: set[str] = set()
    _schema_keys(json_schema, json_schema.get("$defs", {}), "", keys)
    listed = _listed_keys(reference.scene_reference_markdown())
    assert len(keys) > 150
    assert not sorted(keys - listed), "scene keys missing from the reference"


def test_every_key_of_the_example_scenes_is_in_the_reference():
    listed = _listed_keys(reference.scene_reference_markdown())
    used = {key.removeprefix("design.") for key in reference.example_values() if key}
    assert "cam.follower.roller_radius" in used
    assert not sorted(used - listed), "keys of configs/ missing from the scene reference"


def test_scene_reference_gives_units_defaults_and_allowed_values():
    rows = {row["key"]: row for row in reference.scene_key_rows()}
    assert rows["environment.history.temperature"]["unit"] == "K"
    assert rows["environment.history.relative_humidity"]["bounds"] == ">= 0, <= 100"
    assert rows["diffusion.surface_layer_depth"]["default"] == "`0.0005`"
    assert "cyclic_damp_heat" in rows["environment.test"]["allowed"]
    assert rows["name"]["default"] == "required"


def test_every_result_variable_and_coordinate_is_in_the_reference():
    listed = _listed_keys(reference.results_reference_markdown())
    designs = {schema.design_name(name) for name, var in schema.VARIABLES.items() if var.has_design}
    expected = (set(schema.VARIABLES) - designs) | set(schema.COORDINATES)
    assert not sorted(expected - listed), "result variables missing from the reference"
    text = reference.results_reference_markdown()
    assert all(f"`{name}`" in text for name in designs)


def _help_text(*argv: str) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        build_parser().parse_args([*argv, "--help"])
    return out.getvalue()


def _commands_in_help() -> list[str]:
    """The command names the top-level --help lists under COMMAND."""
    block = _help_text().split("COMMAND\n", 1)[1].split("\n\n", 1)[0]
    return re.findall(r"^ {4}([a-z]+)\b", block, flags=re.MULTILINE)


def test_every_command_and_option_is_in_the_cli_reference():
    text = reference.cli_reference_markdown()
    sections = dict(re.findall(r"^## `fickcam ([a-z]+)`\n(.*?)(?=^## |\Z)", text,
                               flags=re.MULTILINE | re.DOTALL))
    commands = _commands_in_help()
    assert {"run", "check", "query", "sweep", "fit", "compensate"} <= set(commands)
    for command in commands:
        assert command in sections, f"fickcam {command} missing from the CLI reference"
        usage = _help_text(command).split("\n\n", 1)[0]  # every option, once
        options = set(re.findall(r"(?<![\w-])(--?[a-zA-Z][\w-]*)", usage))
        missing = {option for option in options - {"-h", "--help"}
                   if f"`{option}`" not in sections[command]}
        assert not missing, f"fickcam {command}: options missing from the reference: {missing}"


def test_every_scene_key_has_a_one_line_meaning_with_its_unit():
    """Every key of the scene models carries ``Field(description=...)``: one line, and for a
    quantity its unit in brackets (``[m]``, ``[K]``, ``[1]`` for a ratio)."""
    rows = reference.scene_key_rows()
    missing = [row["key"] for row in rows if not row["description"]]
    assert not missing, f"scene keys without Field(description=...): {missing}"
    multi = [row["key"] for row in rows if "\n" in row["description"] or len(row["description"]) > 110]
    assert not multi, f"scene key meanings longer than one line: {multi}"
    no_unit = [row["key"] for row in rows
               if row["type"] == "quantity" and not re.search(r"\[[^\]]+\]", row["description"])
               and "variable's unit" not in row["description"]]
    assert not no_unit, f"quantity keys whose meaning gives no [unit]: {no_unit}"


def test_the_scene_reference_shows_the_meaning_column():
    markdown = reference.scene_reference_markdown()
    assert "| key | meaning | value | default | example |" in markdown
    state = markdown.split("### `environment.state`\n", 1)[1].split("\n#", 1)[0]
    assert "| `temperature_rise` | Temperature of every part above" in state
    assert "| `reference_temperature` | Temperature at which the parts are made and dry [K] | " \
           "quantity in K, > 0 | `296.15` | `23 degC` |" in markdown


def test_every_result_variable_and_coordinate_has_a_meaning():
    short = [name for name, var in schema.VARIABLES.items() if len(var.long_name.split()) < 2]
    assert not short, f"result variables without a meaning: {short}"
    assert all(meaning.strip() for _, meaning in schema.COORDINATES.values())
