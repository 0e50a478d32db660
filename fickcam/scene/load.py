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

from ..errors import Problem, SceneError, format_duration
from ..results.limits import parse_limit
from ..messages import warn
from ..quantities.plausibility import Findings, geometry_findings, history_findings
from .sections import (  # noqa: F401  (re-exported: fickcam.scene.load is their public home)
    DesignSection,
    DiffusionSection,
    EnvironmentSection,
    EveryStep,
    HistorySegment,
    OutputsSection,
    SceneModel,
    StandardTest,
    StateSpec,
    last_ageing_time,
)
from .yamldoc import (  # noqa: F401  (re-exported)
    YamlDocument,
    parse_yaml,
    problems_from_validation,
    read_yaml,
)

log = logging.getLogger(__name__)


#: keys that together give a cam's shape: a design shape replaces the made one whole
CAM_SHAPE_KEYS = ("base_circle_radius", "motion", "eccentric", "profile_file", "drawing")


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
    design_model : fickcam.scene.sections.SceneModel, optional
        The mechanisms as designed (from ``design:``).
    limits : list of fickcam.results.limits.Limit
        The limits, in scene order.
    warnings : list of fickcam.errors.Problem
        Unusual bare values and other notes told at validation.
    """

    model: SceneModel
    file: str
    text: str
    base_dir: Path
    document: YamlDocument | None = field(default=None, repr=False)
    materials: dict = field(default_factory=dict, repr=False)  # name -> resolved Material
    design_model: SceneModel | None = field(default=None, repr=False)  # from ``design:``
    limits: list = field(default_factory=list, repr=False)  # fickcam.results.limits.Limit, scene order
    warnings: list = field(default_factory=list, repr=False)  # Problem: unusual bare values

    @property
    def name(self) -> str:
        return self.model.name

    def __repr__(self) -> str:
        from .display import scene_text

        return scene_text(self.name, self.file, self._as_written())

    def _repr_html_(self) -> str:
        from .display import scene_html

        return scene_html(self.name, self.file, self._as_written())

    def _as_written(self) -> dict:
        """The scene's mapping as its user wrote it (units as text)."""
        if self.document is not None:
            return self.document.data
        return yaml.safe_load(self.text) or {} if self.text else {}

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
    from ..linkage.ageing import LINKS

    cam = ("cam", "follower") if model.cam is not None else ()
    return cam + (LINKS if model.linkage is not None else ())


def _cross_checks(model: SceneModel, doc: YamlDocument, base_dir: Path,
                  findings: Findings) -> tuple[list[Problem], dict]:
    """What no single section can check: parts name defined materials, bare durations are
    plausible for the parts (``findings``), the climate stays below their dry Tg, the
    outputs' times fit the climate's history."""
    from ..climate.environment import Environment

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
        return problems, resolved
    durations = history_findings(model, doc, environment, resolved)
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
    return problems, resolved


def _part_problems(model: SceneModel, doc: YamlDocument) -> list[Problem]:
    """Something to age, and a cam's follower arm that fits."""
    problems: list[Problem] = []
    if model.cam is None and model.linkage is None:
        problems.append(doc.problem((), "a scene needs a cam or a linkage section (nothing to age)"))
    if model.cam is not None:
        from ..cam.spec import arm_problems

        problems += [doc.problem(("cam",) + path, reason) for path, reason in arm_problems(model.cam)]
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
    from ..materials import resolve

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
    from ..materials.library import ALIAS_NOTES
    from ..materials.spec import KIND_GROUPS

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
    from ..materials import temperature_limit_reasons

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


def _cam_profile(model: SceneModel, doc: YamlDocument, base_dir: Path) -> tuple[list[Problem], SceneModel]:
    """Read ``cam.profile_file`` or ``cam.drawing`` (relative to the scene): problems at its
    line, and the model with the path made absolute (and the drawing's part kept) so that the
    cam can be built from it anywhere."""
    cam = model.cam
    if cam is None or (cam.profile_file is None and cam.drawing is None):
        return [], model
    from ..cam.profile import load_profile

    if cam.drawing is not None:
        problems, cam, smallest = _cam_drawing(cam, doc, base_dir, model.diffusion.accuracy)
        if smallest is None:
            return problems, model
    else:
        path = (base_dir / cam.profile_file).resolve()
        try:
            smallest = load_profile(path, cam.follower.roller_radius or 0.0).radii()[0]
        except (OSError, ValueError) as exc:
            return [doc.problem(("cam", "profile_file"), str(exc))], model
        problems, cam = [], cam.model_copy(update={"profile_file": str(path)})
    if cam.bore_radius >= smallest:
        problems.append(doc.problem(("cam", "bore_radius"), f"must be smaller than the profile's "
                                                            f"smallest radius ({smallest * 1e3:g} mm)"))
    if cam.follower.arm is not None:
        from ..cam.arm_spec import reach_problems

        problems += [doc.problem(("cam",) + key, reason) for key, reason in reach_problems(cam, smallest)]
    reach = smallest + (cam.follower.roller_radius or 0.0)
    if cam.follower.kind != "flat" and abs(cam.follower.offset) >= reach:
        problems.append(doc.problem(("cam", "follower", "offset"),
                                    "follower offset must be smaller than the prime circle radius"))
    return problems, model.model_copy(update={"cam": cam})


#: the chord tolerance of a drawing, as a share of its extent times the scene's accuracy: the
#: chords' sagitta s changes a plate's area, and so its mean moisture, by at most
#: (2/3) s x perimeter / area, below 0.1 x accuracy for any plate wider than 1/15 of its extent
CHORD_SHARE = 0.01


def _cam_drawing(cam, doc: YamlDocument, base_dir: Path, accuracy: float):
    """(problems, the cam section with its drawing read, the profile's smallest radius [m] or
    None) for ``cam.drawing``."""
    from ..drawing.dxfread import read_drawing
    from ..drawing.parts import cam_of
    from ..drawing.planform import DrawingError
    from ..extras import MissingExtra

    where = ("cam", "drawing")
    path = (base_dir / cam.drawing.file).resolve()
    try:
        drawing = read_drawing(path, CHORD_SHARE * accuracy, cam.drawing.units, relative=True)
        part = cam_of(drawing.planform, drawing.points, cam.drawing.axis_layer)
    except (DrawingError, MissingExtra) as exc:
        return [doc.problem(where, str(exc))], cam, None
    if part.other_holes:
        sources = ", ".join(h.source for h in part.other_holes)
        return [doc.problem(where, f"{path}: holes besides the bore ({sources}) are not modelled "
                                   f"in a cam yet; draw the plate without them")], cam, None
    problems = []
    if "bore_radius" in cam.model_fields_set and abs(cam.bore_radius - part.bore_radius) > 1e-9:
        problems.append(doc.problem(("cam", "bore_radius"), f"the drawing's bore has radius "
                                    f"{part.bore_radius * 1e3:.6g} mm; leave bore_radius out"))
    spec = cam.drawing.model_copy(update={"file": str(path)})
    spec._part = part
    cam = cam.model_copy(update={"drawing": spec, "bore_radius": part.bore_radius})
    return problems, cam, part.smallest_radius


def _limits(model: SceneModel, doc: YamlDocument) -> tuple[list, list[Problem]]:
    """The scene's limits (fickcam.results.limits.Limit) and a Problem per limit that cannot apply."""
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
    problems, resolved = _cross_checks(model, doc, base_dir, findings)
    profile_problems, model = _cam_profile(model, doc, base_dir)
    problems += profile_problems
    design_problems, design_model = _design_model(model, doc, base_dir, findings)
    problems += design_problems
    limits, limit_problems = _limits(model, doc)
    problems += limit_problems
    if problems:
        raise SceneError(problems)
    findings.warnings += _alias_notes(doc)
    for warning in findings.warnings:
        warn("%s", warning)
    return Scene(model=model, file=doc.file, text=doc.text, base_dir=base_dir, document=doc,
                 materials=resolved, design_model=design_model, limits=limits,
                 warnings=findings.warnings)


def design_data(data: dict) -> dict:
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


def _design_model(model: SceneModel, doc: YamlDocument, base_dir: Path, findings: Findings):
    """(problems, the SceneModel as designed) from the ``design:`` section, or ([], None)."""
    if model.design is None:
        return [], None
    for section in ("cam", "linkage"):
        if getattr(model.design, section) is not None and getattr(model, section) is None:
            return [doc.problem(("design", section), f"the scene has no {section} section")], None
    data = design_data(doc.data)
    slips = _design_slips(doc, data, findings)
    if slips:
        return slips, None
    try:
        design = SceneModel.model_validate(data)
    except ValidationError as exc:
        return [doc.problem(("design",) + tuple(problem.key.split(".")), problem.reason)
                for problem in problems_from_validation(exc, doc)], None
    problems, design = _cam_profile(design, doc, base_dir)
    return problems, design


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
        text = yaml.safe_dump(source, sort_keys=False)
        doc = parse_yaml(text, file=file_name or "<dict>")
        return validate_document(doc, base_dir=Path.cwd())
    path = Path(source)
    doc = read_yaml(path)
    return validate_document(doc, base_dir=path.resolve().parent)
