"""Scene files: YAML → validated, SI scene.

The YAML is read with line numbers by :mod:`fickcam.scene.yamldoc` and its sections validated
by the pydantic models of :mod:`fickcam.scene.sections`; this module adds the checks that
need more than one section (materials in use, the environment against the outputs'
times and the materials' Tg, the cam profile file, ``design:``, ``limits:``), each
reported as ``scene.yaml:LINE key.path: reason``, and gives the :class:`Scene`.
"""
from __future__ import annotations

import dataclasses
import logging
from dataclasses import dataclass, field
from pathlib import Path

import yaml
from pydantic import ValidationError

from ..climate.environment import Environment
from ..errors import Problem, SceneError, format_duration
from ..materials import resolve, temperature_limit_reasons
from ..materials.library import ALIAS_NOTES
from ..materials.spec import KIND_GROUPS
from ..mechanisms import mechanism_types, scene_sections
from ..messages import warn
from ..quantities.plausibility import Findings, geometry_findings, history_findings
from .display import scene_html, scene_text
from .limits import parse_limit
from .sections import (  # noqa: F401  (re-exported: fickcam.scene.load is their public home)
    DesignSection, DiffusionSection, EnvironmentSection, EveryStep, HistorySegment, OutputsSection,
    SceneModel, StandardTest, StateSpec, last_ageing_time)
from .yamldoc import (YamlDocument, check_mapping_bounds, parse_yaml,  # noqa: F401  (re-exported)
                      problems_from_validation, read_yaml)

log = logging.getLogger(__name__)


#: keys that together give a cam's shape: a design shape replaces the made one whole
CAM_SHAPE_KEYS = ("base_circle_radius", "motion", "eccentric", "profile_file", "drawing",
                  "outline", "holes")


def merged(made: dict, overrides: dict, replace_whole: tuple = ()) -> dict:
    """``made`` with ``overrides`` applied, mappings merged key by key.

    Parameters
    ----------
    made : dict
        A section as made.
    overrides : dict
        The keys that differ (nested mappings hold only their differing keys).
    replace_whole : tuple of str
        Keys that go together: when the overrides name any of them, all of them are dropped
        from ``made`` first (a cam's shape: ``motion``, ``eccentric``, ``profile_file``...).

    Returns
    -------
    dict
        A new mapping; ``made`` is unchanged.
    """
    out = {k: v for k, v in made.items()
           if not (k in replace_whole and any(key in overrides for key in replace_whole))}
    for key, value in overrides.items():
        out[key] = merged(out[key], value) if isinstance(value, dict) and isinstance(
            out.get(key), dict) else value
    return out


@dataclass
class Scene:
    """A validated scene: the pydantic model plus where it came from.

    Parameters
    ----------
    model : fickcam.scene.sections.SceneModel
        The validated content (SI values).
    file : str
        The scene file's name.
    text : str
        Its text.
    base_dir : pathlib.Path
        Its folder (relative paths of the scene are read from there).
    document : fickcam.scene.yamldoc.YamlDocument, optional
        The parsed file, with the line of every key.
    materials : dict
        Scene material name -> resolved :class:`fickcam.materials.material.Material`.
    as_designed_model : fickcam.scene.sections.SceneModel, optional
        The mechanisms as designed (from ``design:``); None: as made.
    limits : list of fickcam.scene.limits.Limit
        The limits, in scene order.
    warnings : list of fickcam.errors.Problem
        Unusual bare values and other notes told at validation.
    environment : fickcam.climate.environment.Environment, optional
        The climate history to the last ageing time, built once at validation.
    mechanisms : tuple of fickcam.mechanisms.Mechanism
        The scene's mechanisms, each built once at validation (in the registry's order).
    as_designed_mechanisms : tuple of fickcam.mechanisms.Mechanism, optional
        The mechanisms as designed (``design:``); None: as made.
    """

    model: SceneModel
    file: str
    text: str
    base_dir: Path
    document: YamlDocument | None = field(default=None, repr=False)
    materials: dict = field(default_factory=dict, repr=False)  # name -> resolved Material
    as_designed_model: SceneModel | None = field(default=None, repr=False)  # from ``design:``
    limits: list = field(default_factory=list, repr=False)  # fickcam.scene.limits.Limit, scene order
    warnings: list = field(default_factory=list, repr=False)  # Problem: unusual bare values
    environment: object = field(default=None, repr=False)  # the climate, built once
    mechanisms: tuple = field(default=(), repr=False)  # each built once
    as_designed_mechanisms: tuple | None = field(default=None, repr=False)

    @property
    def name(self) -> str:
        return self.model.name

    def __repr__(self) -> str:
        return scene_text(self.name, self.file, self._as_written())

    def _repr_html_(self) -> str:
        return scene_html(self.name, self.file, self._as_written())

    def _as_written(self) -> dict:
        """The scene's mapping as its user wrote it (units as text)."""
        if self.document is not None:
            return self.document.data
        return yaml.safe_load(self.text) or {} if self.text else {}

    def as_designed(self) -> "Scene":
        """This scene with its mechanisms as designed (``design:``), or itself."""
        if self.as_designed_model is None:
            return self
        return dataclasses.replace(self, model=self.as_designed_model, as_designed_model=None,
                                   mechanisms=self.as_designed_mechanisms,
                                   as_designed_mechanisms=None)

    @property
    def parts(self) -> tuple:
        """The bodies that age, mechanism by mechanism (each mechanism's ``parts``).

        Returns
        -------
        tuple of fickcam.mechanisms.part.Part
            The parts, in a run's order.
        """
        return tuple(part for mechanism in self.mechanisms for part in mechanism.parts)

    @property
    def elastic_parts(self) -> frozenset:
        """The names of the parts whose swelling stress the scene asks for.

        Returns
        -------
        frozenset of str
            The part names.
        """
        return frozenset().union(*(m.elastic_parts for m in self.mechanisms))

    @property
    def field_parts(self) -> frozenset:
        """The names of the parts whose moisture field a run keeps for the mechanisms or
        the swelling stress (``elastic_parts`` and each mechanism's ``field_parts``).

        Returns
        -------
        frozenset of str
            The part names.
        """
        return self.elastic_parts.union(*(m.field_parts for m in self.mechanisms))

    def has(self, section: str) -> bool:
        """Whether the scene has the mechanism of ``section`` (``cam``, ``linkage``).

        Parameters
        ----------
        section : str
            A name of the mechanism registry.

        Returns
        -------
        bool
        """
        return any(m.section_name == section for m in self.mechanisms)

    def with_model(self, model: SceneModel) -> "Scene":
        """This scene with its sections replaced by ``model``'s and its mechanisms rebuilt
        from them (a sizing's cam at another base circle); the climate, materials and
        limits stay.

        Parameters
        ----------
        model : fickcam.scene.sections.SceneModel
            The sections, SI, validated (e.g. this scene's ``model.model_copy(update=...)``).

        Returns
        -------
        Scene
            The scene with ``model`` and its mechanisms.

        Raises
        ------
        fickcam.errors.SceneError
            When a file a section names cannot be read.
        """
        problems, model, files = _files(model, self.document, self.base_dir, {})
        if problems:
            raise SceneError(problems)
        return dataclasses.replace(self, model=model,
                                   mechanisms=_mechanisms(model, self.materials, files))

    def mechanism(self, section: str):
        """The scene's mechanism built from ``section``.

        Parameters
        ----------
        section : str
            A name of the mechanism registry (``cam``, ``linkage``).

        Returns
        -------
        fickcam.mechanisms.Mechanism
            The mechanism.

        Raises
        ------
        KeyError
            When the scene has no such section.
        """
        found = [m for m in self.mechanisms if m.section_name == section]
        if not found:
            raise KeyError(f"the scene has no {section} section")
        return found[0]


# --------------------------------------------------------------------------
# Cross-section checks (need more than one section)


def _used_materials(model: SceneModel) -> list[tuple[tuple, str]]:
    """(key path, material name) for every material reference in the scene."""
    types = mechanism_types()
    return [((name,) + path, material) for name, section in scene_sections(model).items()
            for path, material in types[name].materials_used(section)]


def _part_names(model: SceneModel) -> tuple[str, ...]:
    """Names of the parts a scene's mechanisms build, in their order."""
    types = mechanism_types()
    return tuple(part for name, section in scene_sections(model).items()
                 for part in types[name].part_names(section))


def _cross_checks(model: SceneModel, doc: YamlDocument, base_dir: Path,
                  findings: Findings, files: dict) -> tuple[list[Problem], dict, object]:
    """What no single section can check: parts name defined materials, bare durations are
    plausible for the parts (``findings``; a drawn part's size from its drawing, in
    ``files``, what each mechanism read), the climate stays below their dry Tg, the
    outputs' times fit the climate's history; (problems, the resolved materials, the
    Environment or None where it cannot be built)."""
    problems = _part_problems(model, doc)
    material_problems, resolved = _resolved_materials(model, doc)
    problems += material_problems
    try:
        environment = Environment.from_section(model.environment, base_dir=base_dir,
                                                until=last_ageing_time(model.outputs))
    except ValueError as exc:
        key = next(name for name in ("test", "history_file", "history", "state")
                   if getattr(model.environment, name) is not None)
        problems.append(doc.problem(("environment", key), str(exc)))
        return problems, resolved, None
    types = mechanism_types()
    sizes = [size for name, section in scene_sections(model).items()
             for size in types[name].absorber_sizes(section, files.get(name))]
    durations = history_findings(model, doc, environment, resolved, sizes)
    problems += durations.errors
    problems += _temperature_limit_problems(model, doc, environment, resolved, findings)
    problems += _model_name_problems(model, doc)
    timing = [] if durations.errors else _ageing_time_problems(model, doc, environment)
    # a slipped duration is the cause: name it, not the output times it cuts short
    if timing and durations.warnings:
        problems += durations.warnings
    else:
        problems += timing
        findings.warnings += durations.warnings
    return problems, resolved, environment


def _part_problems(model: SceneModel, doc: YamlDocument) -> list[Problem]:
    """Something to age, and what each mechanism checks of its section (a cam's follower
    arm that fits)."""
    types = mechanism_types()
    sections = scene_sections(model)
    problems: list[Problem] = []
    if not sections:
        problems.append(doc.problem((), f"a scene needs a {' or a '.join(types)} section "
                                        f"(nothing to age)"))
    for name, section in sections.items():
        problems += [doc.problem((name,) + path, reason)
                     for path, reason in types[name].section_problems(section)]
    return problems


def _model_name_problems(model: SceneModel, doc: YamlDocument) -> list[Problem]:
    """A per-part diffusion model must name a part of the scene."""
    if not isinstance(model.diffusion.model, dict):
        return []
    names = _part_names(model)
    return [doc.problem(("diffusion", "model", name),
                        f"no part named {name!r} (parts: {', '.join(names)})")
            for name in model.diffusion.model if name not in names]


def _resolved_materials(model: SceneModel, doc: YamlDocument) -> tuple[list[Problem], dict]:
    """Each material a part uses, resolved once (library name or own values)."""
    problems: list[Problem] = []
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
    return problems, resolved


def _alias_notes(doc: YamlDocument) -> list[Problem]:
    """What a material named by a close alias must know (``plastic: PA6`` reads PA66 data)."""
    notes = {alias.casefold(): note for alias, note in ALIAS_NOTES.items()}
    materials = doc.data.get("materials")
    return [doc.problem(("materials", name, key), notes[str(spec[key]).casefold()])
            for name, spec in (materials.items() if isinstance(materials, dict) else ())
            if isinstance(spec, dict)
            for key in KIND_GROUPS if str(spec.get(key, "")).casefold() in notes]


def _temperature_limit_problems(model: SceneModel, doc: YamlDocument, environment,
                                resolved: dict, findings: Findings) -> list[Problem]:
    """The hottest climate must stay below the dry Tg of every thermoset and the melting
    point of every thermoplastic in use (refused at the climate's line); above a material's
    service limit it is warned once per material (``findings``)."""
    problems: list[Problem] = []
    hottest_index, hottest = environment.hottest()
    path = (("environment", "history", hottest_index, "temperature")
            if model.environment.history is not None else
            ("environment", "test" if model.environment.test else
             "state" if model.environment.state is not None else "history_file"))
    for name, material in resolved.items():
        refusals, warnings = temperature_limit_reasons(material, name, hottest)
        problems += [doc.problem(path, reason) for reason in refusals]
        findings.warnings += [doc.problem(path, reason) for reason in warnings]
    return problems


def _ageing_time_problems(model: SceneModel, doc: YamlDocument, environment) -> list[Problem]:
    """Output times within the climate's history (a record holds its last state)."""
    times = model.outputs.ageing_times
    if model.environment.state is not None and times is not None:
        return [doc.problem(("outputs", "ageing_times"),
                            "a state environment is computed at its states' times "
                            "(environment.state[].time); leave ageing_times out")]
    problems: list[Problem] = []
    record = model.environment.history_file is not None  # a record holds its last state
    if isinstance(times, list) and times[-1] > environment.end * (1 + 1e-12) and not record:
        problems.append(doc.problem(
            ("outputs", "ageing_times", len(times) - 1),
            f"ageing time beyond the end of the environment history ({environment.end / 86400:g} d)"))
    if isinstance(times, EveryStep) and times.every > environment.end:
        origin = (f", as {model.environment.history_file} gives it: check the unit of its time "
                  f"column" if record else "")
        problems.append(doc.problem(("outputs", "ageing_times", "every"),
                                    f"step longer than the environment history "
                                    f"({format_duration(environment.end)}{origin})"))
    return problems


def _files(model: SceneModel, doc: YamlDocument, base_dir: Path,
           read: dict) -> tuple[list[Problem], SceneModel, dict]:
    """Read the files the mechanisms name (a cam's ``profile_file`` or ``drawing``, relative
    to the scene):
    (problems at their lines, the model with the paths made absolute so that a mechanism
    can be built from it anywhere, what each mechanism read by section name); ``read``:
    what this validation has read already, by path."""
    types = mechanism_types()
    problems: list[Problem] = []
    files, update = {}, {}
    for name, section in scene_sections(model).items():
        found, update[name], files[name] = types[name].read_files(
            section, base_dir, read, model.diffusion.accuracy)
        problems += [doc.problem((name,) + path, reason) for path, reason in found]
    return problems, model.model_copy(update=update), files


def _mechanisms(model: SceneModel, materials: dict, files: dict) -> tuple:
    """The scene's mechanisms, each built once from its section, the resolved materials
    and the files it read."""
    types = mechanism_types()
    return tuple(types[name](section, materials, files.get(name))
                 for name, section in scene_sections(model).items())


def _limits(model: SceneModel, doc: YamlDocument) -> tuple[list, list[Problem]]:
    """The scene's limits (fickcam.scene.limits.Limit) and a Problem per limit that cannot apply."""
    sections = set(scene_sections(model))
    limits, problems = [], []
    for name, spec in (model.limits or {}).items():
        try:
            limits.append(parse_limit(name, spec, sections))
        except ValueError as exc:
            problems.append(doc.problem(("limits", name), str(exc)))
    return limits, problems


# --------------------------------------------------------------------------


def validate_document(doc: YamlDocument, *, base_dir: Path) -> Scene:
    """Validate a parsed YAML document into a Scene.

    Bare lengths and speeds that are almost certainly unit slips are named first; then the
    sections, the checks across sections (materials, parts, wet Tg, ageing times), a cam's
    profile file, the ``design:`` section and the limits. Warnings are logged.

    Parameters
    ----------
    doc : fickcam.scene.yamldoc.YamlDocument
        The parsed scene file.
    base_dir : pathlib.Path
        The folder relative paths of the scene are read from.

    Returns
    -------
    Scene
        The scene, validated against the models.

    Raises
    ------
    fickcam.errors.SceneError
        With one ``FILE:LINE key: reason`` problem per fault.
    """
    # A bare length or speed that is almost certainly a unit slip is named first: it would
    # otherwise surface as whatever check of its section it breaks.
    findings = geometry_findings(doc)
    if findings.errors:
        raise SceneError(findings.errors)
    # YAML 1.1 reads '1e-3' (no dot) as text: unit fields parse such strings
    # with fickcam.quantities.types and plain float fields accept them in pydantic's lax mode.
    try:
        model = SceneModel.model_validate(doc.data)
    except ValidationError as exc:
        raise SceneError(problems_from_validation(exc, doc, model=SceneModel)) from None
    read: dict = {}  # the files read, by path: each read once
    file_problems, model, files = _files(model, doc, base_dir, read)
    problems, resolved, environment = _cross_checks(model, doc, base_dir, findings, files)
    problems += file_problems
    design_problems, as_designed = _as_designed_model(model, doc, base_dir, findings, read)
    problems += design_problems
    limits, limit_problems = _limits(model, doc)
    problems += limit_problems
    if problems:
        raise SceneError(problems)
    findings.warnings += _alias_notes(doc)
    for warning in findings.warnings:
        warn("%s", warning)
    as_designed_model, as_designed_mechanisms = None, None
    if as_designed is not None:
        as_designed_model, as_designed_files = as_designed
        as_designed_mechanisms = _mechanisms(as_designed_model, resolved, as_designed_files)
    return Scene(model=model, file=doc.file, text=doc.text, base_dir=base_dir, document=doc,
                 materials=resolved, as_designed_model=as_designed_model, limits=limits,
                 warnings=findings.warnings, environment=environment,
                 mechanisms=_mechanisms(model, resolved, files),
                 as_designed_mechanisms=as_designed_mechanisms)


def as_designed_data(data: dict) -> dict:
    """A scene mapping as designed: its ``design:`` merged into ``cam:`` and ``linkage:``.

    A design cam shape replaces the made one; ``design:`` is dropped.

    Parameters
    ----------
    data : dict
        The scene as read from YAML.

    Returns
    -------
    dict
        A new mapping.
    """
    design = data.get("design") or {}
    out = {k: v for k, v in data.items() if k != "design"}
    for section in ("cam", "linkage"):
        if isinstance(design.get(section), dict) and isinstance(out.get(section), dict):
            out[section] = merged(out[section], design[section],
                                  CAM_SHAPE_KEYS if section == "cam" else ())
    return out


def _design_slips(doc: YamlDocument, data: dict, findings: Findings) -> list[Problem]:
    """Bare values of the ``design:`` overrides that look like unit slips, judged in the
    mechanism as designed and reported at their ``design.`` key (warnings join
    ``findings``); the made sections' own values were judged before."""
    found = geometry_findings(dataclasses.replace(doc, data=data))
    errors: list[Problem] = []
    for problems, into in ((found.errors, errors), (found.warnings, findings.warnings)):
        for problem in problems:
            path = ("design",) + tuple(int(k) if k.isdigit() else k for k in problem.key.split("."))
            if path in doc.lines:  # a value the design gives, not one it keeps from the made
                into.append(doc.problem(path, problem.reason))
    return errors


def _as_designed_model(model: SceneModel, doc: YamlDocument, base_dir: Path, findings: Findings,
                       read: dict):
    """(problems, (the SceneModel as designed, the files its mechanisms read)) from the
    ``design:`` section, or ([], None); ``read``: the files this validation has read."""
    if model.design is None:
        return [], None
    for section in ("cam", "linkage"):
        if getattr(model.design, section) is not None and getattr(model, section) is None:
            return [doc.problem(("design", section), f"the scene has no {section} section")], None
    data = as_designed_data(doc.data)
    slips = _design_slips(doc, data, findings)
    if slips:
        return slips, None
    try:
        design = SceneModel.model_validate(data)
    except ValidationError as exc:
        return [doc.problem(("design",) + tuple(problem.key.split(".")), problem.reason)
                for problem in problems_from_validation(exc, doc)], None
    problems, design, files = _files(design, doc, base_dir, read)
    return problems, (design, files)


def load_scene(source, *, file_name: str | None = None) -> Scene:
    """Load a scene from a YAML path, a YAML text-free dict, or return a Scene as is.

    Parameters
    ----------
    source : str, pathlib.Path, dict or Scene
        A YAML scene file, the scene as a dict, or a loaded Scene (returned as is).
    file_name : str, optional
        The name that error messages give a dict scene (default ``<dict>``); a dict's
        relative file paths are read from the current folder.

    Returns
    -------
    Scene
        The validated scene, quantities in SI (m, s, K, Pa, rad).

    Raises
    ------
    fickcam.errors.SceneError
        One problem per fault, each naming file, line and key.
    """
    if isinstance(source, Scene):
        return source
    if isinstance(source, dict):
        check_mapping_bounds(source, file=file_name or "<dict>")
        text = yaml.safe_dump(source, sort_keys=False)
        doc = parse_yaml(text, file=file_name or "<dict>")
        return validate_document(doc, base_dir=Path.cwd())
    path = Path(source)
    doc = read_yaml(path)
    return validate_document(doc, base_dir=path.resolve().parent)
