"""The fixed point of compensation: run the scene with the current made dimensions,
read each part's strain at the ageing times compensated for, make the dimensions
anew (:mod:`fickcam.compensation.core`), until they stop moving."""
from __future__ import annotations

import copy
import math
import tempfile
from pathlib import Path

import numpy as np
import yaml

from ..errors import FickcamError, InputError, format_duration
from .core import (MAX_ITERATIONS, Compensation, converged, made_value, part_strain,
                   quiet_runs, residual, window_times)


def length_text(value: float) -> str:
    """A length for the written scene, to the nanometre."""
    return f"{value * 1e3:.6f} mm"


def scene_from(data: dict, base_dir: Path, file_name: str):
    """Validate a scene mapping whose relative paths are relative to ``base_dir``."""
    from ..scene import parse_yaml, validate_document

    doc = parse_yaml(yaml.safe_dump(data, sort_keys=False), file=file_name)
    return validate_document(doc, base_dir=base_dir)


def _targets(scene) -> list:
    found = []
    if scene.model.cam is not None:
        from . import cam

        found += cam.targets(scene.model.cam, scene.base_dir)
    if scene.model.linkage is not None:
        from . import linkage

        found += linkage.targets(scene.model.linkage)
    return found


def write_made(data: dict, targets: list, made: list, folder: Path, stem: str) -> dict:
    """A copy of the scene mapping with the made dimensions (a cam's profile written as
    ``<stem>_cam_profile.csv`` in ``folder``)."""
    data = copy.deepcopy(data)
    cam_part = [(t, m) for t, m in zip(targets, made) if t.group in ("cam", "follower")]
    link_part = [(t, m) for t, m in zip(targets, made) if t.group not in ("cam", "follower")]
    if cam_part:
        from . import cam

        cam.write(data, *zip(*cam_part), folder, stem)
    if link_part:
        from . import linkage

        linkage.write(data, *zip(*link_part), length_text)
    return data


def _strain_run(data: dict, base_dir: Path, times: np.ndarray, accuracy):
    """A run at ``times`` only, with a coarse angle grid: the strains are what is read."""
    from ..simulate import run

    data = copy.deepcopy(data)
    outputs = dict(data.get("outputs") or {})
    outputs.update(ageing_times=[float(t) for t in times], angle_step="30 deg", fields=False)
    outputs.pop("file", None)
    data["outputs"] = outputs
    return run(scene_from(data, base_dir, "<compensation>"), accuracy=accuracy)


def compensation_times(scene, at, over) -> np.ndarray:
    """[T] for ``at``, the window grid for ``over`` (s); refuses times outside the history."""
    from ..simulate import ageing_times, scene_environment
    from ..units import parse_duration

    environment = scene_environment(scene)
    if (at is None) == (over is None):
        raise InputError("give exactly one of --at TIME or --over T1 T2")
    values = [at] if at is not None else list(over)
    seconds = []
    for value in values:
        try:
            seconds.append(parse_duration(value) if isinstance(value, str) else float(value))
        except ValueError as exc:
            raise InputError(f"compensation time: {exc}") from None
    for s in seconds:
        if not 0.0 <= s <= environment.end * (1 + 1e-12) or not math.isfinite(s):
            raise InputError(f"compensation time {format_duration(s)} is outside the scene's "
                             f"history (0 to {format_duration(environment.end)})")
    if at is not None:
        return np.array(seconds)
    if seconds[1] <= seconds[0]:
        raise InputError("--over T1 T2 needs T1 < T2")
    return window_times(seconds[0], seconds[1], ageing_times(scene, environment))


def compensate(scene, at=None, over=None, *, accuracy: float | None = None) -> Compensation:
    """The dry dimensions to make so that the mechanism has its design geometry at ageing
    time ``at`` (a duration, e.g. "60 d", or seconds), or stays closest to it over the
    window ``over`` = (T1, T2) (minimax). Returns a :class:`Compensation`; its
    ``scene_data`` is written by :func:`fickcam.compensation.write_scene`."""
    from ..scene import design_data, load_scene

    scene = load_scene(scene)
    times = compensation_times(scene, at, over)
    targets = _targets(scene.as_designed())  # a compensated scene is compensated anew
    data = design_data(copy.deepcopy(scene.document.data))
    made = [t.design for t in targets]
    with tempfile.TemporaryDirectory(prefix="fickcam-compensate-") as folder, quiet_runs():
        ds = _strain_run(data, scene.base_dir, times, accuracy)
        for iteration in range(MAX_ITERATIONS + 1):
            strains = [part_strain(ds, t) for t in targets]
            new = [made_value(t.design, s) for t, s in zip(targets, strains)]
            if iteration and converged(made, new, targets):
                break
            made = new
            trial = write_made(data, targets, made, Path(folder), "trial")
            ds = _strain_run(trial, scene.base_dir, times, accuracy)
        else:
            raise FickcamError(f"compensation did not settle in {MAX_ITERATIONS} iterations")
    leftover = [residual(t.design, m, s) for t, m, s in zip(targets, made, strains)]
    return Compensation(targets, made, times, iteration, data, residual=leftover, scene=scene)
