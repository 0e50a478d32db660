"""What `fickcam compensate` prints and writes: the table of dimensions to make per part,
the drift of the key outputs before and after, and the runnable compensated scene."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import yaml

from ..errors import format_duration
from .core import Compensation, quiet_runs, relative_to
from .solve import write_made

#: key outputs over angle whose largest deviation from the design is reported:
#: result variable, label, scale from the stored unit, unit shown
KEY_OUTPUTS = (("follower_displacement", "follower displacement", 1e6, "µm"),
               ("follower_arm_angle", "arm angle", 1.0, "deg"),
               ("pressure_angle", "pressure angle", 1.0, "deg"),
               ("rocker_angle", "rocker angle", 1.0, "deg"),
               ("coupler_angle", "coupler angle", 1.0, "deg"),
               ("coupler_point", "coupler point", 1e6, "µm"))


def dimension_rows(comp: Compensation) -> list[tuple]:
    """(group, dimension, design m, made m) per scalar target; a profile gives its
    smallest and largest radius from the cam axis (base circle, base circle + lift)."""
    rows = []
    for target, made in zip(comp.targets, comp.made):
        if np.ndim(target.design):
            continue
        rows.append((target.group, target.name, float(target.design), float(made)))
    if any(t.group == "cam" for t in comp.targets):
        from .cam import profile_radii

        rows = profile_radii(comp) + rows
    return rows


def dimension_table(comp: Compensation) -> str:
    """The table per part: dimension, design, to make, change in µm and %."""
    lines = [f"{'part':<9} {'dimension':<26} {'design mm':>13} {'to make mm':>13} "
             f"{'change µm':>11} {'change %':>9}"]
    for group, name, design, made in dimension_rows(comp):
        change = made - design
        lines.append(f"{group:<9} {name:<26} {design * 1e3:13.6f} {made * 1e3:13.6f} "
                     f"{change * 1e6:+11.2f} {change / design * 100:+9.4f}")
    return "\n".join(lines)


def when_text(comp: Compensation) -> str:
    """'at 60 d' or 'over 0 s to 365 d (minimax, 38 ageing times)'."""
    times = comp.times
    if times.size == 1:
        return f"at {format_duration(times[0])}"
    return (f"over {format_duration(times[0], times[-1])} to {format_duration(times[-1])} (minimax, "
            f"{times.size} ageing times)")


def header(comp: Compensation, scene) -> str:
    """One line: what was compensated for and how the fixed point went."""
    when = when_text(comp)
    return (f"{scene.name}: dry dimensions at the reference temperature to make, {when}; "
            f"fixed point settled after {comp.iterations} iteration(s)")


def residual_lines(comp: Compensation) -> list[str]:
    """For a window: the largest deviation left on each target (m -> µm)."""
    if comp.times.size == 1:
        return []
    lines = ["largest dimension deviation left over the window (minimax residual):"]
    for target, left in zip(comp.targets, comp.residual):
        lines.append(f"  {target.group:<9} {target.name:<26} {left * 1e6:9.2f} µm")
    return lines


def _with_design(data: dict, comp: Compensation) -> dict:
    """The made scene with its ``design:`` section (what drift and limits are measured
    against) after the mechanism sections."""
    from . import cam, linkage

    design = {}
    if "cam" in data:
        design["cam"] = cam.design_entry(comp.scene_data["cam"], comp.targets)
    if "linkage" in data:
        design["linkage"] = linkage.design_entry(comp.scene_data["linkage"])
    out = {}
    for key, value in data.items():
        if key != "design":
            out[key] = value
        if key == ("linkage" if "linkage" in data else "cam"):
            out["design"] = design
    return out


def write_scene(comp: Compensation, scene, path) -> Path:
    """Write the compensated scene (and a cam's profile CSV beside it); it runs as is."""
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    folder.mkdir(parents=True, exist_ok=True)
    data = write_made(comp.scene_data, comp.targets, comp.made, folder, path.stem)
    if "cam" in data and "profile_file" in data["cam"]:
        from .cam import write_dxf

        profile = Path(data["cam"]["profile_file"])
        data["cam"]["profile_file"] = profile.name  # beside the scene
        write_dxf(comp.targets, comp.made, profile.with_suffix(".dxf"))
    data = _with_design(data, comp)
    environment = data.get("environment") or {}
    if isinstance(environment.get("history_file"), str):
        environment["history_file"] = relative_to(environment["history_file"], scene.base_dir,
                                                  folder)
    shape = data.get("design", {}).get("cam", {})
    if isinstance(shape.get("profile_file"), str):
        shape["profile_file"] = relative_to(shape["profile_file"], scene.base_dir, folder)
    data["name"] = f"{scene.name}-compensated"
    data["description"] = f"{scene.model.description} (compensated {when_text(comp)})".strip()
    outputs = dict(data.get("outputs") or {})
    outputs["file"] = f"outputs/{data['name']}.h5"
    data["outputs"] = outputs
    text = (f"# Written by `fickcam compensate` from {scene.file}.\n"
            f"# {header(comp, scene)}.\n"
            + "".join(f"# {line}\n" for line in dimension_table(comp).splitlines())
            + yaml.safe_dump(data, sort_keys=False, allow_unicode=True))
    path.write_text(text, encoding="utf-8")
    return path


def largest_deviation(ds, name: str) -> np.ndarray | None:
    """Largest |value - design value| over the cycle at each ageing time (stored unit;
    :func:`fickcam.query.drift` against the result's as-designed state, which for a
    compensated scene is its ``design:``); the coupler point is the distance between the
    two points. None where the result lacks ``name``."""
    from ..query import drift

    if name == "coupler_point":
        if "coupler_point_x" not in ds:
            return None
        change = np.hypot(drift(ds, "coupler_point_x").values, drift(ds, "coupler_point_y").values)
    elif name in ds:
        change = drift(ds, name).values
    else:
        return None
    return np.nanmax(np.abs(change), axis=-1)


def _run_at(data: dict, base_dir: Path, times: np.ndarray, accuracy):
    from ..simulate import run
    from .solve import scene_from

    data = dict(data)
    outputs = dict(data.get("outputs") or {})
    outputs.update(ageing_times=[float(t) for t in times], fields=False)
    data["outputs"] = outputs
    return run(scene_from(data, base_dir, "<compensation check>"), accuracy=accuracy)


#: ageing times across the history at which a --plot draws the drift
PLOT_POINTS = 49


def check_times(comp: Compensation, scene, dense: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(times to run, times to tabulate), s: the scene's ageing times and the ends of the
    compensation, and for a plot also the compensation's own times and a regular grid."""
    from ..simulate import ageing_times, scene_environment

    environment = scene_environment(scene)
    shown = np.unique(np.concatenate([ageing_times(scene, environment), comp.times[[0, -1]]]))
    if not dense:
        return shown, shown
    grid = np.linspace(0.0, environment.end, PLOT_POINTS)
    return np.unique(np.concatenate([shown, comp.times, grid])), shown


def drift_runs(comp: Compensation, scene, path, times, accuracy=None):
    """(uncompensated result, compensated result) at ``times``, the compensated scene read
    back from ``path`` as written."""
    from ..scene import read_yaml

    path = Path(path)
    written = read_yaml(path).data
    with quiet_runs():
        before = _run_at(scene.document.data, scene.base_dir, times, accuracy)
        after = _run_at(written, path.resolve().parent, times, accuracy)
    return before, after


def drift_lines(times, before, after, shown) -> list[str]:
    """The drift of the key outputs from the design, before and after compensation, at the
    ageing times ``shown``."""
    columns = []
    for name, label, scale, unit in KEY_OUTPUTS:
        old = largest_deviation(before, name)
        if old is not None:
            new = largest_deviation(after, name)
            columns.append((f"{label} {unit}", old * scale, new * scale))
    if not columns:
        return []
    lines = ["largest deviation from the design over the cycle (before -> after compensation):",
             f"  {'time':>9}  " + "  ".join(f"{title:>26}" for title, _, _ in columns)]
    for k in np.flatnonzero(np.isin(times, shown)):
        t = times[k]
        cells = "  ".join(f"{old[k]:12.4g} -> {new[k]:10.4g}" for _, old, new in columns)
        lines.append(f"  {format_duration(t, times[-1]):>9}  {cells}")  # one unit of time
    return lines


def report(comp: Compensation, scene, path, accuracy=None, plot=None) -> str:
    """Everything `fickcam compensate` prints; ``plot``: also draw the drift against the
    band there (PNG)."""
    times, shown = check_times(comp, scene, dense=plot is not None)
    before, after = drift_runs(comp, scene, path, times, accuracy)
    lines = [header(comp, scene), dimension_table(comp)] + residual_lines(comp) + \
        drift_lines(times, before, after, shown)
    if plot is not None:
        from ..plotting.compensation import plot_against_band

        window = tuple(np.unique(comp.times[[0, -1]]) / 86400.0)
        lines.append(f"wrote {plot_against_band(before, after, plot, window)}")
    return "\n".join(lines)
