"""Run one scene: the only module that knows the order of the work.

scene → environment → parts (geometry, material) → diffusion per part →
material state per part → mechanisms at each ageing time → Dataset.
"""
from __future__ import annotations

import logging
import time as _time
from dataclasses import dataclass, field

import numpy as np

from . import __version__
from .environment import Environment
from .errors import InputError, format_duration
from .scene import EveryStep, Scene, last_ageing_time, load_scene

log = logging.getLogger(__name__)


@dataclass
class Part:
    """One body that ages: its name, material, diffusion geometry and axes."""

    name: str
    material_name: str
    material: object
    geometry: object | None  # diffusion geometry (None: the part does not absorb)
    dry_mass: float | None = None


@dataclass
class PartHistory:
    """What diffusion and the material state give for one part over ageing."""

    part: Part
    diffusion: object | None
    state: dict = field(default_factory=dict)
    valid: np.ndarray | None = None  # bool over ageing times


# ----------------------------------------------------------------- planning


def scene_environment(scene: Scene) -> Environment:
    """The scene's climate history (a weather year repeated to its last ageing time)."""
    return Environment.from_section(scene.model.environment, base_dir=scene.base_dir,
                                    until=last_ageing_time(scene.model.outputs))


def ageing_times(scene: Scene, environment: Environment) -> np.ndarray:
    """Ageing times in s: the scene's list, a regular ``every`` grid, or 11 points."""
    requested = scene.model.outputs.ageing_times
    end = environment.end
    if isinstance(requested, list):
        return np.asarray(requested, float)
    if isinstance(requested, EveryStep):
        count = int(np.floor(end / requested.every * (1 + 1e-12)))
        return requested.every * np.arange(count + 1)
    return np.linspace(0.0, end, 11)


def build_parts(scene: Scene) -> list[Part]:
    """The parts a scene models, in a fixed order (cam, follower, links)."""
    parts: list[Part] = []
    model = scene.model
    if model.cam is not None:
        from .cam import scene_parts as cam_parts

        parts += [Part(name, mat, scene.materials[mat], geometry, mass)
                  for name, mat, geometry, mass in cam_parts(model.cam, scene.materials)]
    if model.linkage is not None:
        from .linkage import scene_parts as linkage_parts

        parts += [Part(name, mat, scene.materials[mat], geometry, mass)
                  for name, mat, geometry, mass in linkage_parts(model.linkage, scene.materials)]
    for part in parts:
        if not getattr(part.material, "absorbs", False):
            part.geometry = None
    return parts


def _diffusion_options(scene: Scene, accuracy: float | None) -> dict:
    section = scene.model.diffusion
    return {"accuracy": accuracy if accuracy is not None else section.accuracy,
            "model": section.model, "surface_layer_depth": section.surface_layer_depth}


def part_model(options: dict, part: str) -> str:
    """The diffusion model asked for ``part`` (``diffusion.model``: one name or per part)."""
    model = options["model"]
    return model.get(part, "auto") if isinstance(model, dict) else model


def _model_text(model) -> str:
    if isinstance(model, dict):
        return ", ".join(f"{part}: {name}" for part, name in model.items()) + " (others auto)"
    return model


def _for_part(name: str, call, *args, **kwargs):
    """``call`` with an InputError (e.g. a model that does not apply) naming the part."""
    try:
        return call(*args, **kwargs)
    except InputError as exc:
        raise InputError(f"part {name}: {exc}") from None


def describe_plan(scene: Scene, accuracy: float | None = None) -> str:
    """The plan `fickcam check` prints: parts, diffusion model, cells, steps."""
    from .diffusion import plan

    environment = scene_environment(scene)
    times = ageing_times(scene, environment)
    options = _diffusion_options(scene, accuracy)
    lines = [f"scene {scene.name}: valid",
             f"  environment: {len(environment.change_times) - 1} segment(s), "
             f"{format_duration(environment.end)}; {len(times)} ageing times",
             f"  diffusion: model {_model_text(options['model'])}, accuracy {options['accuracy']:g}"]
    for part in build_parts(scene):
        head = f"  part {part.name:<9} material {part.material_name}"
        if part.geometry is None:
            lines.append(f"{head}: does not absorb moisture (thermal strain only)")
            continue
        exposure = environment.exposure(part.material.saturation_moisture)
        diffusivity = part.material.diffusivity_for(part.geometry)
        p = _for_part(part.name, plan, part.geometry, diffusivity, exposure, times,
                      accuracy=options["accuracy"], model=part_model(options, part.name))
        lines.append(f"{head}: {type(part.geometry).__name__} → {p.model}, {p.cells} cells, "
                     f"{p.steps} steps, est. error {p.error_estimate:.1e} ({p.reason})")
    mechanisms = [s for s in ("cam", "linkage") if getattr(scene.model, s) is not None]
    lines.append(f"  mechanisms: {', '.join(mechanisms)}; angle step "
                 f"{np.degrees(scene.model.outputs.angle_step):g} deg")
    return "\n".join(lines)


# ---------------------------------------------------------------------- run


def run(scene, *, accuracy: float | None = None, progress: bool = False):
    """Run one scene and return its xarray.Dataset (SPEC.md §4)."""
    from tqdm.auto import tqdm

    from .dataset import build_dataset
    from .diffusion import solve
    from .materials import material_state

    started = _time.perf_counter()
    scene = load_scene(scene)
    environment = scene_environment(scene)
    times = ageing_times(scene, environment)
    temperature = environment.temperature(times)
    humidity = environment.relative_humidity(times)
    options = _diffusion_options(scene, accuracy)
    parts = build_parts(scene)
    notices: list[str] = list(environment.notes)

    bar = tqdm(total=len(parts) + len(times), disable=not progress, desc=scene.name,
               unit="step", leave=False)
    histories: list[PartHistory] = []
    for part in parts:
        bar.set_postfix_str(f"diffusion {part.name}")
        if part.geometry is not None:
            exposure = environment.exposure(part.material.saturation_moisture)
            result = _for_part(part.name, solve, part.geometry,
                               part.material.diffusivity_for(part.geometry), exposure, times,
                               accuracy=options["accuracy"], model=part_model(options, part.name),
                               surface_layer_depth=options["surface_layer_depth"],
                               store_fields=scene.model.outputs.fields, part=part.name)
            mean, surface = result.mean, result.surface
            saturation = exposure.surface_moisture(times)
            if result.error_estimate > options["accuracy"]:  # e.g. capped at MAX_CELLS
                notices.append(f"{part.name}: estimated diffusion error "
                               f"{result.error_estimate:.1e} above the requested accuracy "
                               f"{options['accuracy']:g} ({result.model})")
        else:
            result = None
            mean = surface = saturation = np.zeros_like(times)
        state = material_state(part.material, temperature, mean, surface,
                               environment.reference_temperature, environment.initial_moisture,
                               part=part.name, times=times)
        state.setdefault("moisture_content", mean)
        state.setdefault("surface_moisture_content", surface)
        state.setdefault("equilibrium_moisture_content", saturation)
        valid = _valid_until_wet_tg(part, state, temperature, times, notices)
        histories.append(PartHistory(part, result, state, valid))
        bar.update()

    values: dict[str, np.ndarray] = {"temperature": temperature, "relative_humidity": humidity}
    coords: dict = {"time": times}
    if parts:
        coords["part"] = [p.name for p in parts]
        for name in _PART_VARIABLES:
            if all(name in h.state for h in histories):
                values[name] = np.stack([np.where(h.valid, h.state[name], np.nan)
                                         for h in histories], axis=1)
        if "mass" not in values:
            values["mass"] = np.stack([_part_mass(h) for h in histories], axis=1)
    valid_all = np.logical_and.reduce([h.valid for h in histories]) if histories else \
        np.ones_like(times, bool)

    if scene.model.cam is not None:
        from .cam import scene_response as cam_response

        angles = _angle_grid(scene.model.outputs.angle_step)
        coords["cam_angle"] = angles
        mech = cam_response(scene.model.cam, {h.part.name: h for h in histories}, times,
                            angles, valid_all, on_step=bar.update)
        values.update(mech.variables)
        notices += mech.notices
    if scene.model.linkage is not None:
        from .linkage import scene_response as linkage_response

        angles = _angle_grid(scene.model.outputs.angle_step)
        coords["crank_angle"] = angles
        from .linkage import JOINTS, LINKS

        coords["link"] = list(LINKS)
        coords["joint"] = list(JOINTS)
        mech = linkage_response(scene.model.linkage, {h.part.name: h for h in histories}, times,
                                angles, valid_all, on_step=bar.update)
        values.update(mech.variables)
        notices += mech.notices
    if scene.model.outputs.fields:
        _add_fields(values, coords, histories, times)
    bar.close()
    for message in notices:
        log.warning(message)

    attrs = {
        "title": f"fickcam result: {scene.name}",
        "fickcam_version": __version__,
        "scene_name": scene.name,
        "scene_description": scene.model.description,
        "scene_file": scene.file,
        "scene_text": scene.text,
        "diffusion": {h.part.name: _diffusion_attrs(h) for h in histories},
        "notices": notices,
        "wall_time": _time.perf_counter() - started,
        "Conventions": "CF-1.8",
    }
    return build_dataset(values, coords, attrs)


_PART_VARIABLES = ("moisture_content", "surface_moisture_content", "equilibrium_moisture_content",
                   "mass", "density", "hygrothermal_strain", "strain_longitudinal",
                   "strain_transverse", "strain_through_thickness",
                   "glass_transition_temperature", "property_retention",
                   "longitudinal_modulus", "transverse_modulus", "shear_modulus",
                   "poisson_ratio", "surface_modulus")


def _angle_grid(step: float) -> np.ndarray:
    count = max(int(round(2 * np.pi / step)), 4)
    return np.linspace(0.0, 2 * np.pi, count, endpoint=False)


def _part_mass(history: PartHistory) -> np.ndarray:
    """m = m_dry (1 + M/100) (seed 000 eq. 3 inverted), NaN where not given."""
    dry = history.part.dry_mass
    moisture = history.state["moisture_content"]
    mass = np.full_like(moisture, np.nan) if dry is None else dry * (1 + moisture / 100.0)
    return np.where(history.valid, mass, np.nan)


def _valid_until_wet_tg(part: Part, state: dict, temperature, times, notices) -> np.ndarray:
    """False from the first ageing time at which T reaches the wet Tg of the
    bulk or of the surface layer (Chamis' degradation law no longer applies)."""
    from .materials.state import wet_tg_error

    within = np.asarray(state.get("within_wet_tg", np.ones(times.shape, bool)), bool)
    valid = np.logical_and.accumulate(within)
    if not valid.all():
        index = int(np.argmin(valid))
        notices.append(str(wet_tg_error(part.name, times, index, temperature, state)))
    return valid


def _diffusion_attrs(history: PartHistory) -> dict:
    result = history.diffusion
    if result is None:
        return {"model": "none", "error_estimate": 0.0, "cells": 0, "steps": 0,
                "reason": "material does not absorb moisture"}
    return {"model": result.model, "error_estimate": float(result.error_estimate),
            "cells": int(result.cells), "steps": int(result.steps), "reason": result.reason}


def _add_fields(values, coords, histories, times) -> None:
    """Moisture fields of every absorbing part, padded with NaN to a common cell count."""
    with_fields = [h for h in histories if h.diffusion is not None and
                   getattr(h.diffusion, "fields", None) is not None]
    if not with_fields:
        return
    n_cells = max(h.diffusion.fields.shape[1] for h in with_fields)
    n_parts = len(histories)
    moisture = np.full((len(times), n_parts, n_cells), np.nan)
    cell = {axis: np.full((n_parts, n_cells), np.nan) for axis in ("x", "y", "z")}
    for index, history in enumerate(histories):
        result = history.diffusion
        if result is None or getattr(result, "fields", None) is None:
            continue
        n = result.fields.shape[1]
        moisture[:, index, :n] = result.fields
        for axis, array in cell.items():
            if axis in result.cell_coordinates:
                array[index, :n] = result.cell_coordinates[axis]
    values["moisture"] = moisture
    for axis, array in cell.items():
        values[f"cell_{axis}"] = array
    coords["cell"] = np.arange(n_cells)


# ------------------------------------------------------------------ summary


def _last_finite(values: np.ndarray) -> tuple[float, float]:
    """(first, last finite) of a series; NaN where none is finite."""
    finite = np.asarray(values, float)[np.isfinite(values)]
    return (finite[0], finite[-1]) if finite.size else (np.nan, np.nan)


def _per_time(reduce, values: np.ndarray) -> np.ndarray:
    """A reduction over the angle axis that gives NaN (not a warning) for all-NaN rows."""
    values = np.asarray(values, float)
    out = np.full(values.shape[0], np.nan)
    rows = np.isfinite(values).any(axis=1)
    out[rows] = reduce(values[rows], axis=1)
    return out


def summary(ds) -> str:
    """A few lines a user reads after `fickcam run`."""
    days = ds["time"].values / np.timedelta64(1, "D")
    lines = [f"{ds.attrs.get('scene_name', '')}: {len(days)} ageing times to {days[-1]:g} d, "
             f"wall time {float(ds.attrs.get('wall_time', 0)):.2f} s"]
    if "part" in ds.coords:
        diffusion = ds.attrs.get("diffusion", {})
        for part in ds["part"].values:
            first, last = _last_finite(ds["moisture_content"].sel(part=part).values)
            info = diffusion.get(str(part), {}) if isinstance(diffusion, dict) else {}
            lines.append(f"  {part:<9} moisture {first:.3g} → {last:.3g} %  "
                         f"({info.get('model', '?')}, est. error {info.get('error_estimate', 0):.1e})")
    for name, label, scale, unit in (("lift", "cam lift", 1e3, "mm"),
                                     ("base_circle_radius", "base circle radius", 1e3, "mm"),
                                     ("jump_speed", "jump speed", 1.0, "rpm"),
                                     ("peak_cam_torque", "peak cam torque", 1.0, "N m"),
                                     ("peak_contact_stress", "peak contact stress", 1e-6, "MPa"),
                                     ("minimum_transmission_angle", "minimum transmission angle", 1.0, "deg"),
                                     ("peak_input_torque", "peak input torque", 1.0, "N m")):
        if name in ds:
            first, last = (v * scale for v in _last_finite(ds[name].values))
            lines.append(f"  {label} {first:.5g} → {last:.5g} {unit} ({last - first:+.3g})")
    if "rocker_angle" in ds:
        rocker = ds["rocker_angle"].values
        shift = _per_time(np.max, np.abs(rocker - rocker[0]))
        if np.isfinite(shift).any():
            lines.append(f"  largest rocker angle shift {np.nanmax(shift):.4f} deg")
    notices = ds.attrs.get("notices", [])
    if isinstance(notices, list) and notices:
        lines.append(f"  {len(notices)} notice(s):")
        lines += [f"    - {n}" for n in notices]
    return "\n".join(lines)
