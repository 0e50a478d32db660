"""Scene files: YAML → validated, SI scene (see SPEC.md §1).

YAML is read with ``yaml.SafeLoader`` only (a ``!!python`` tag is refused,
never executed), duplicate keys are refused, and every key path is mapped to
its line so that each problem is reported as ``scene.yaml:LINE key.path:
reason``. Values are validated by pydantic models whose dimensional fields
parse units with pint (:mod:`fickcam.units`).
"""
from __future__ import annotations

import dataclasses
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal, Union

import yaml
from pydantic import BeforeValidator, Field, ValidationError, field_validator, model_validator

from .cam.spec import CamSection
from .diffusion import MODELS
from .errors import Problem, SceneError
from .keys import closest_key
from .limits import LimitSpec, parse_limit
from .linkage.spec import LinkageSection
from .materials import MaterialSpec
from .units import (
    Duration,
    Length,
    NonNegativePercent,
    NonNegativeTime,
    RelativeHumidity,
    PositiveAngle,
    StrictModel,
    Temperature,
    TemperatureRise,
)

# --------------------------------------------------------------------------
# YAML with line numbers


class _LineLoader(yaml.SafeLoader):
    """SafeLoader that refuses duplicate keys (PyYAML silently keeps the last)."""

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
    """A parsed YAML mapping with the line of every key path."""

    data: dict
    lines: dict[tuple, int]
    file: str
    text: str

    def line_of(self, path: tuple) -> int | None:
        """Line of ``path`` or of its nearest ancestor that has one."""
        path = tuple(path)
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path[:-1]
        return 1 if self.text.strip() else None

    def problem(self, path: tuple, reason: str) -> Problem:
        key = ".".join(str(p) for p in path)
        return Problem(self.file, self.line_of(path), key, reason)


def read_yaml(source: str | os.PathLike, *, what: str = "scene") -> YamlDocument:
    """Read a YAML mapping safely, with line numbers; raise SceneError on faults."""
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
    """One Problem per pydantic error, located at its key path's line; an unknown key of
    ``model`` (the validated pydantic class) names the closest valid key."""
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


# --------------------------------------------------------------------------
# Scene models (SI floats after validation)




class HistorySegment(StrictModel):
    """One segment of the climate history (held, or a linear ramp)."""

    duration: Duration
    temperature: Temperature
    relative_humidity: RelativeHumidity
    ramp: bool = False


class StateSpec(StrictModel):
    """A state given directly (SPEC.md section 5): uniform moisture and temperature in every
    part, no diffusion. Moisture is ``moisture`` (the same weight % in every absorbing
    part) or ``relative_humidity`` (each part at its material's equilibrium moisture
    Mm(RH), as seed 001 takes 'maximum moisture absorption'); temperature is
    ``temperature`` or ``temperature_rise`` above the reference temperature."""

    time: NonNegativeTime = 0.0
    moisture: NonNegativePercent | None = None
    relative_humidity: RelativeHumidity | None = None
    temperature: Temperature | None = None
    temperature_rise: TemperatureRise | None = None

    @model_validator(mode="after")
    def _one_of_each(self):
        if (self.moisture is None) == (self.relative_humidity is None):
            raise ValueError("a state needs exactly one of moisture, relative_humidity")
        if (self.temperature is None) == (self.temperature_rise is None):
            raise ValueError("a state needs exactly one of temperature, temperature_rise")
        return self


def _as_list(value):
    """One mapping is a list of one (``state: {...}`` or ``state: [{...}, ...]``)."""
    return [value] if isinstance(value, dict) else value


StandardTest = Literal["steady_damp_heat", "damp_heat_85_85", "cyclic_damp_heat"]


class EnvironmentSection(StrictModel):
    reference_temperature: Temperature = 296.15
    initial_moisture: NonNegativePercent = 0.0
    history: list[HistorySegment] | None = None
    history_file: str | None = None          # chamber CSV, TMY3 CSV, EPW, or pvlib:NAME
    test: StandardTest | None = None         # a standard damp-heat test (fickcam.damp_heat)
    cycles: int | None = Field(None, gt=0)   # cyclic_damp_heat: number of 24 h cycles
    duration: Duration | None = None         # steady tests: how long
    upper_temperature: Temperature | None = None  # cyclic_damp_heat: 40 or 55 degC
    # states given directly, no diffusion: one mapping or a list of them
    state: Annotated[list[StateSpec] | None, BeforeValidator(_as_list)] = None

    @model_validator(mode="after")
    def _one_history(self):
        given = [name for name in ("history", "history_file", "test", "state")
                 if getattr(self, name) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of history (segments), history_file (a record), "
                             "test (a standard damp-heat test) or state (given directly)")
        states = self.states()
        if self.state is not None and not states:
            raise ValueError("state needs at least one entry")
        if any(b.time <= a.time for a, b in zip(states, states[1:])):
            raise ValueError("the states' times must increase strictly")
        if self.history is not None:
            if not self.history:
                raise ValueError("history needs at least one segment")
            if self.history[0].ramp:
                raise ValueError("the first history segment cannot ramp: there is no previous segment")
        if self.test is None:
            extra = [name for name in ("cycles", "duration", "upper_temperature")
                     if getattr(self, name) is not None]
            if extra:
                raise ValueError(f"{', '.join(extra)} belong(s) to a standard test (environment.test)")
        return self


    def states(self) -> list[StateSpec]:
        """The given states as a list (empty without ``state``)."""
        return list(self.state or [])


def last_ageing_time(outputs) -> float | None:
    """The last ageing time an ``outputs:`` section lists (None for ``every``)."""
    times = outputs.ageing_times
    return times[-1] if isinstance(times, list) else None


class DiffusionSection(StrictModel):
    # one model for every part, or per part name (parts not named: auto)
    model: Union[str, dict[str, str]] = "auto"
    accuracy: float = Field(1e-3, gt=0, le=0.1)
    surface_layer_depth: Length = 5e-4

    @field_validator("model")
    @classmethod
    def _model_names(cls, value):
        names = MODELS  # the diffusion package's own list
        for part, name in (value.items() if isinstance(value, dict) else [(None, value)]):
            if name not in names:
                where = f"part {part!r}: " if part is not None else ""
                raise ValueError(f"{where}{name!r} is not a model (one of {', '.join(names)})")
        return value


class EveryStep(StrictModel):
    every: Duration


class OutputsSection(StrictModel):
    ageing_times: Union[list[NonNegativeTime], EveryStep, None] = None
    angle_step: PositiveAngle = math.radians(1.0)
    fields: bool = False
    file: str | None = None

    @field_validator("ageing_times")
    @classmethod
    def _increasing(cls, value):
        if isinstance(value, list):
            if not value:
                raise ValueError("give at least one ageing time")
            if any(b <= a for a, b in zip(value, value[1:])):
                raise ValueError("ageing times must increase strictly")
        return value

    @field_validator("angle_step")
    @classmethod
    def _divides_turn(cls, value):
        if value > math.radians(30):
            raise ValueError("angle_step must not exceed 30 deg")
        return value


class DesignSection(StrictModel):
    """``design:``: the geometry the mechanism must have in service, where the ``cam:`` /
    ``linkage:`` sections give the dimensions as made (``fickcam compensate`` writes it).
    Each entry holds only the keys that differ from the made section; the as-designed
    state (``<name>_design``, drift, limits) is computed from it."""

    cam: dict | None = None
    linkage: dict | None = None


#: keys that together give a cam's shape: a design shape replaces the made one whole
CAM_SHAPE_KEYS = ("base_circle_radius", "motion", "eccentric", "profile_file")


def merged(made: dict, overrides: dict, replace_whole: tuple = ()) -> dict:
    """``made`` with ``overrides`` applied (mappings merged key by key); when the overrides
    name any of ``replace_whole``, all of those keys of ``made`` are dropped first."""
    out = {k: v for k, v in made.items()
           if not (k in replace_whole and any(key in overrides for key in replace_whole))}
    for key, value in overrides.items():
        out[key] = merged(out[key], value) if isinstance(value, dict) and isinstance(
            out.get(key), dict) else value
    return out


class SceneModel(StrictModel):
    name: str = Field(min_length=1)
    description: str = ""
    environment: EnvironmentSection
    materials: dict[str, MaterialSpec] = Field(min_length=1)
    cam: CamSection | None = None
    linkage: LinkageSection | None = None
    diffusion: DiffusionSection = DiffusionSection()
    outputs: OutputsSection = OutputsSection()
    design: DesignSection | None = None
    limits: dict[str, LimitSpec] | None = None

    @field_validator("name")
    @classmethod
    def _printable(cls, value):
        if not value.strip():
            raise ValueError("must not be blank")
        return value


@dataclass
class Scene:
    """A validated scene: the pydantic model plus where it came from."""

    model: SceneModel
    file: str
    text: str
    base_dir: Path
    document: YamlDocument | None = field(default=None, repr=False)
    materials: dict = field(default_factory=dict, repr=False)  # name -> resolved Material
    design_model: SceneModel | None = field(default=None, repr=False)  # from ``design:``
    limits: list = field(default_factory=list, repr=False)  # fickcam.limits.Limit, scene order

    @property
    def name(self) -> str:
        return self.model.name

    def as_designed(self) -> "Scene":
        """This scene with its mechanisms as designed (``design:``), or itself."""
        if self.design_model is None:
            return self
        return dataclasses.replace(self, model=self.design_model, design_model=None)


# --------------------------------------------------------------------------
# Cross-section checks (need more than one section)


def _used_materials(model: SceneModel) -> list[tuple[tuple, str]]:
    """(key path, material name) for every material reference in the scene."""
    refs = []
    if model.cam is not None:
        refs.append((("cam", "material"), model.cam.material))
        follower_material = getattr(model.cam.follower, "material", None)
        if follower_material:
            refs.append((("cam", "follower", "material"), follower_material))
    if model.linkage is not None:
        refs.append((("linkage", "material"), model.linkage.material))
        if model.linkage.frame_material:
            refs.append((("linkage", "frame_material"), model.linkage.frame_material))
    return refs


def _part_names(model: SceneModel) -> tuple[str, ...]:
    """Names of the parts a scene builds (``simulate.build_parts``), in its order."""
    from .linkage.ageing import LINKS

    cam = ("cam", "follower") if model.cam is not None else ()
    return cam + (LINKS if model.linkage is not None else ())


def _cross_checks(model: SceneModel, doc: YamlDocument, base_dir: Path) -> tuple[list[Problem], dict]:
    from .environment import Environment
    from .materials import resolve

    problems: list[Problem] = []
    if model.cam is None and model.linkage is None:
        problems.append(doc.problem((), "a scene needs a cam or a linkage section (nothing to age)"))
    if model.cam is not None:
        from .cam.spec import arm_problems

        problems += [doc.problem(("cam",) + path, reason) for path, reason in arm_problems(model.cam)]
    resolved = {}
    for path, name in _used_materials(model):
        if name not in model.materials:
            known = ", ".join(sorted(model.materials))
            problems.append(doc.problem(path, f"material {name!r} is not defined under materials (defined: {known})"))
            continue
        if name not in resolved:
            try:
                resolved[name] = resolve(name, model.materials[name])
            except ValueError as exc:
                problems.append(doc.problem(("materials", name), str(exc)))
    try:
        environment = Environment.from_section(model.environment, base_dir=base_dir,
                                                until=last_ageing_time(model.outputs))
    except ValueError as exc:
        key = next(name for name in ("test", "history_file", "history", "state")
                   if getattr(model.environment, name) is not None)
        problems.append(doc.problem(("environment", key), str(exc)))
        return problems, resolved
    # the service temperature must stay below the dry Tg of every absorbing material in use
    hottest_index, hottest = environment.hottest()
    for name, material in resolved.items():
        tg = getattr(material, "dry_glass_transition_temperature", None)
        if tg is not None and hottest >= tg:
            path = (("environment", "history", hottest_index, "temperature")
                    if model.environment.history is not None else
                    ("environment", "test" if model.environment.test else
                     "state" if model.environment.state is not None else "history_file"))
            problems.append(doc.problem(
                path, f"{hottest - 273.15:.1f} degC is at or above the dry Tg of material "
                      f"{name!r} ({tg - 273.15:.1f} degC)"))
    if isinstance(model.diffusion.model, dict):
        names = _part_names(model)
        for name in model.diffusion.model:
            if name not in names:
                problems.append(doc.problem(("diffusion", "model", name),
                                            f"no part named {name!r} (parts: {', '.join(names)})"))
    times = model.outputs.ageing_times
    if model.environment.state is not None and times is not None:
        problems.append(doc.problem(("outputs", "ageing_times"),
                                    "a state environment is computed at its states' times "
                                    "(environment.state[].time); leave ageing_times out"))
        return problems, resolved
    record = model.environment.history_file is not None  # a record holds its last state
    if isinstance(times, list) and times[-1] > environment.end * (1 + 1e-12) and not record:
        problems.append(doc.problem(
            ("outputs", "ageing_times", len(times) - 1),
            f"ageing time beyond the end of the environment history ({environment.end / 86400:g} d)"))
    if isinstance(times, EveryStep) and times.every > environment.end:
        problems.append(doc.problem(("outputs", "ageing_times", "every"),
                                    "step longer than the environment history"))
    return problems, resolved


def _cam_profile(model: SceneModel, doc: YamlDocument, base_dir: Path) -> tuple[list[Problem], SceneModel]:
    """Read ``cam.profile_file`` (relative to the scene): problems at its line, and the model
    with the path made absolute so that the cam can be built from it anywhere."""
    cam = model.cam
    if cam is None or cam.profile_file is None:
        return [], model
    from .cam.profile import load_profile

    path = (base_dir / cam.profile_file).resolve()
    where = ("cam", "profile_file")
    try:
        smallest = load_profile(path, cam.follower.roller_radius or 0.0).radii()[0]
    except (OSError, ValueError) as exc:
        return [doc.problem(where, str(exc))], model
    problems = []
    if cam.bore_radius >= smallest:
        problems.append(doc.problem(("cam", "bore_radius"), f"must be smaller than the profile's "
                                                            f"smallest radius ({smallest * 1e3:g} mm)"))
    if cam.follower.arm is not None:
        from .cam.arm_spec import reach_problems

        problems += [doc.problem(("cam",) + key, reason) for key, reason in reach_problems(cam, smallest)]
    reach = smallest + (cam.follower.roller_radius or 0.0)
    if cam.follower.kind != "flat" and abs(cam.follower.offset) >= reach:
        problems.append(doc.problem(("cam", "follower", "offset"),
                                    "follower offset must be smaller than the prime circle radius"))
    return problems, model.model_copy(update={"cam": cam.model_copy(update={"profile_file": str(path)})})


def _limits(model: SceneModel, doc: YamlDocument) -> tuple[list, list[Problem]]:
    """The scene's limits (fickcam.limits.Limit) and a Problem per limit that cannot apply."""
    sections = {name for name in ("cam", "linkage") if getattr(model, name) is not None}
    limits, problems = [], []
    for name, spec in (model.limits or {}).items():
        try:
            limits.append(parse_limit(name, spec, sections))
        except ValueError as exc:
            problems.append(doc.problem(("limits", name), str(exc)))
    return limits, problems


# --------------------------------------------------------------------------


def validate_document(doc: YamlDocument, *, base_dir: Path) -> Scene:
    """Validate a parsed YAML document into a Scene or raise SceneError."""
    # YAML 1.1 reads '1e-3' (no dot) as text: unit fields parse such strings
    # with fickcam.units and plain float fields accept them in pydantic's lax mode.
    try:
        model = SceneModel.model_validate(doc.data)
    except ValidationError as exc:
        raise SceneError(problems_from_validation(exc, doc, model=SceneModel)) from None
    problems, resolved = _cross_checks(model, doc, base_dir)
    profile_problems, model = _cam_profile(model, doc, base_dir)
    problems += profile_problems
    design_problems, design_model = _design_model(model, doc, base_dir)
    problems += design_problems
    limits, limit_problems = _limits(model, doc)
    problems += limit_problems
    if problems:
        raise SceneError(problems)
    return Scene(model=model, file=doc.file, text=doc.text, base_dir=base_dir,
                 document=doc, materials=resolved, design_model=design_model, limits=limits)


def design_data(data: dict) -> dict:
    """A scene mapping as designed: its ``design:`` overrides merged into ``cam:`` and
    ``linkage:`` (a design cam shape replaces the made one), ``design:`` dropped."""
    design = data.get("design") or {}
    out = {k: v for k, v in data.items() if k != "design"}
    for section in ("cam", "linkage"):
        if isinstance(design.get(section), dict) and isinstance(out.get(section), dict):
            out[section] = merged(out[section], design[section],
                                  CAM_SHAPE_KEYS if section == "cam" else ())
    return out


def _design_model(model: SceneModel, doc: YamlDocument, base_dir: Path):
    """(problems, the SceneModel as designed) from the ``design:`` section, or ([], None)."""
    if model.design is None:
        return [], None
    for section in ("cam", "linkage"):
        if getattr(model.design, section) is not None and getattr(model, section) is None:
            return [doc.problem(("design", section), f"the scene has no {section} section")], None
    data = design_data(doc.data)
    try:
        design = SceneModel.model_validate(data)
    except ValidationError as exc:
        return [doc.problem(("design",) + tuple(problem.key.split(".")), problem.reason)
                for problem in problems_from_validation(exc, doc)], None
    problems, design = _cam_profile(design, doc, base_dir)
    return problems, design


def load_scene(source, *, file_name: str | None = None) -> Scene:
    """Load a scene from a YAML path, a YAML text-free dict, or return a Scene as is."""
    if isinstance(source, Scene):
        return source
    if isinstance(source, dict):
        text = yaml.safe_dump(source, sort_keys=False)
        doc = parse_yaml(text, file=file_name or "<dict>")
        return validate_document(doc, base_dir=Path.cwd())
    path = Path(source)
    doc = read_yaml(path)
    return validate_document(doc, base_dir=path.resolve().parent)
