"""What `fickcam compensate` prints and writes: the table of dimensions to make per part,
the scene's limits over the life asked about (as designed and compensated), what to do
when compensating at one time breaks them, the drift of the key outputs before and after,
and the runnable compensated scene (all files written together, or none)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import yaml

from .core import Compensation, relative_to
from .cam import profile_radii
from ..results.limits import stored_limits
from ..results.query import drift
from ..simulation.times import ageing_times
from .cam import anisotropy_note
from ..cam.profile import write_profile_csv, write_profile_dxf
from .cam import PROFILE_POINTS, made_outline
from ..files import replaced_together
from .cam import drawn, profile_path
from .solve import write_made, write_points
from ..linkage.spec import DRAWN_LINKS

#: key outputs over angle whose largest deviation from the design is reported:
#: result variable, label, scale from the stored unit, unit shown
KEY_OUTPUTS = (("follower_displacement", "follower displacement", 1e6, "µm"),
               ("follower_arm_angle", "arm angle", 1.0, "deg"),
               ("pressure_angle", "pressure angle", 1.0, "deg"),
               ("rocker_angle", "rocker angle", 1.0, "deg"),
               ("coupler_angle", "coupler angle", 1.0, "deg"),
               ("coupler_point", "coupler point", 1e6, "µm"))
DAY = 86400.0


def days(seconds: float) -> str:
    """An ageing time as the user's scenes give them: '182.6 d'.

    Parameters
    ----------
    seconds : float
        The ageing time [s].

    Returns
    -------
    str
        The time in days, 4 significant digits.
    """
    return f"{seconds / DAY:.4g} d"


def _dimension_rows(comp: Compensation) -> list[tuple]:
    """(group, dimension, design m, made m) per scalar target; a cam given by points
    gives its smallest and largest radius and its extents."""

    rows = [(t.group, t.name, float(t.design), float(m))
            for t, m in zip(comp.targets, comp.made) if not np.ndim(t.design)]
    return profile_radii(comp) + rows


def dimension_table(comp: Compensation) -> str:
    """The table per part: dimension, design, to make, change in µm and %.

    Parameters
    ----------
    comp : Compensation
        The compensation: its targets and made values [m].

    Returns
    -------
    str
        The table (lengths in mm).
    """
    lines = [f"{'part':<9} {'dimension':<26} {'design mm':>13} {'to make mm':>13} "
             f"{'change µm':>11} {'change %':>9}"]
    for group, name, design, made in _dimension_rows(comp):
        change = made - design
        lines.append(f"{group:<9} {name:<26} {design * 1e3:13.6f} {made * 1e3:13.6f} "
                     f"{change * 1e6:+11.2f} {change / design * 100:+9.4f}")
    return "\n".join(lines)


def _when_text(comp: Compensation) -> str:
    """'at 60 d' or 'over 0 d to 365 d (minimax, 38 ageing times)'."""
    times = comp.times
    if times.size == 1:
        return f"at {days(times[0])}"
    return f"over {days(times[0])} to {days(times[-1])} (minimax, {times.size} ageing times)"


def header(comp: Compensation, scene) -> str:
    """One line: what was compensated for and how the fixed point went.

    Parameters
    ----------
    comp : Compensation
        The compensation: when it was made for and its iterations.
    scene : Scene
        The design scene (its name).

    Returns
    -------
    str
        The line.
    """
    return (f"{scene.name}: dry dimensions at the reference temperature to make, "
            f"{_when_text(comp)}; fixed point settled after {comp.iterations} iteration(s)")


def _residual_lines(comp: Compensation) -> list[str]:
    """For a window: the largest deviation left on each target (m -> µm)."""
    if comp.times.size == 1:
        return []
    lines = ["largest dimension deviation left over the window (minimax residual):"]
    for target, left in zip(comp.targets, comp.residual):
        lines.append(f"  {target.group:<9} {target.name:<26} {left * 1e6:9.2f} µm")
    return lines


# ------------------------------------------------------------------ limits


def worst(ratio: np.ndarray, times: np.ndarray) -> tuple[float, float]:
    """(largest limit ratio, the ageing time of it) over a run's times; NaN where unknown.

    Parameters
    ----------
    ratio : numpy.ndarray
        Limit ratio at each time (1 at the limit) [-].
    times : numpy.ndarray
        The ageing times [s].

    Returns
    -------
    tuple of float
        The largest ratio [-] and its time [s].
    """
    if not np.isfinite(ratio).any():
        return math.nan, math.nan
    k = int(np.nanargmax(ratio))
    return float(ratio[k]), float(times[k])


def out_of_spec_spans(ratio: np.ndarray, times: np.ndarray) -> list[str]:
    """Each stretch of ageing times out of spec (ratio above 1): 'at 0 d, back in spec by
    7 d', 'from 30 d to 90 d, back in spec by 120 d', 'from 300 d to the end'.

    Parameters
    ----------
    ratio : numpy.ndarray
        Limit ratio at each time [-].
    times : numpy.ndarray
        The ageing times [s].

    Returns
    -------
    list of str
        One phrase per stretch.
    """
    above = ratio > 1.0
    spans = []
    k = 0
    while k < len(times):
        if not above[k]:
            k += 1
            continue
        last = k
        while last + 1 < len(times) and above[last + 1]:
            last += 1
        text = f"at {days(times[k])}" if last == k else \
            f"from {days(times[k])} to {days(times[last])}"
        if last + 1 < len(times):
            text += f", back in spec by {days(times[last + 1])}"
        elif last > k:
            text = f"from {days(times[k])} to the end"
        spans.append(text)
        k = last + 1
    return spans


def _cell(times: np.ndarray, ratio: np.ndarray) -> str:
    value, when = worst(ratio, times)
    if math.isnan(value):
        return f"{'unknown':<26}"
    verdict = "holds" if value <= 1.0 else "OUT OF SPEC"
    return f"{value:6.3f} at {days(when):>9}  {verdict:<11}"


def limit_lines(comp: Compensation) -> list[str]:
    """The scene's limits over the life: worst ratio (1 at the limit), when, and whether
    it holds, as designed and as compensated.

    Parameters
    ----------
    comp : Compensation
        The compensation (its runs before and after).

    Returns
    -------
    list of str
        The lines.
    """

    if "limit_ratio" not in comp.before:
        return ["the scene has no limits: section, so the made part is not checked against a "
                "spec (add one to see each limit here, as designed and compensated)"]
    limits = stored_limits(comp.before)
    life = f"{days(comp.life[0])} to {days(comp.life[1])}"
    lines = [f"limits from {life} (worst limit ratio, 1 = at the limit, and when):",
             f"  {'limit':<44} {'as designed':<34} compensated"]
    for name in comp.before.limit.values:
        label = f"{name} ({limits[name].text})"
        lines.append(f"  {label:<44} {_cell(*comp.ratios(comp.before, name))}  "
                     f"{_cell(*comp.ratios(comp.after, name))}".rstrip())
    return lines


def _failures(comp: Compensation, ds, brief: bool = False) -> list[str]:
    """'follower_displacement out of spec at 0 d, back in spec by 7 d (worst 1.35 at 0 d)'
    per failing limit; ``brief``: 'follower_displacement (worst 1.35 at 0 d)'."""
    found = []
    for name in ds.limit.values:
        times, ratio = comp.ratios(ds, name)
        spans = out_of_spec_spans(ratio, times)
        if spans:
            value, when = worst(ratio, times)
            where = "" if brief else " out of spec " + " and ".join(spans)
            found.append(f"{name}{where} (worst {value:.3g} at {days(when)})")
    return found


def _worse_line(comp: Compensation) -> list[str]:
    """'further out of spec than as designed at 2 of 6 ageing times (0 d, 7 d)', by the
    largest limit ratio at each time; nothing where compensation never makes it worse."""
    names = comp.after.limit.values
    times = comp.ratios(comp.after, names[0])[0]
    before = np.nanmax([comp.ratios(comp.before, name)[1] for name in names], axis=0)
    after = np.nanmax([comp.ratios(comp.after, name)[1] for name in names], axis=0)
    worse = np.flatnonzero((after > before) & (after > 1.0))
    if not worse.size:
        return []
    return [f"as compensated it is further out of spec than as designed at {worse.size} of "
            f"{times.size} ageing times ({', '.join(days(t) for t in times[worse])})"]


def _advice_lines(comp: Compensation, scene) -> list[str]:
    """What the limits say about the compensation asked for, and what to do instead."""
    if "limit_ratio" not in comp.after:
        return []
    life = f"{days(comp.life[0])} to {days(comp.life[1])}"
    failures = _failures(comp, comp.after)
    lines = []
    if comp.asked is not None:
        lines.append(f"--keep-limits: compensating {_when_text(comp.asked)} broke "
                     + ", ".join(_failures(comp.asked, comp.asked.after, brief=True))
                     + f"; made for the whole life, {life}, instead")
    if not failures:
        return lines + [f"every limit holds from {life} as compensated"]
    lines += ["as compensated: " + "; ".join(failures)] + _worse_line(comp)
    if comp.times.size == 1:
        lines.append(f"Compensating at one time cannot hold the part from delivery on. Make it "
                     f"for its whole life instead (minimax: closest to the design over it):\n"
                     f"  fickcam compensate {scene.file} --over \"{comp.life[0] / DAY:g} d\" "
                     f"\"{comp.life[1] / DAY:g} d\"\n"
                     f"or add --keep-limits to do so whenever the time asked for breaks a limit.")
    else:
        lines.append(f"these dimensions come no closer to the design over {life} (minimax): "
                     f"to keep every limit, shorten the window or choose a material that "
                     f"swells less")
    return lines


def _largest_deviation(ds, name: str) -> np.ndarray | None:
    """Largest |value - design value| over the cycle at each ageing time (stored unit;
    :func:`fickcam.results.query.drift` against the result's as-designed state, which for a
    compensated scene is its ``design:``); the coupler point is the distance between the
    two points. None where the result lacks ``name``."""

    if name == "coupler_point":
        if "coupler_point_x" not in ds:
            return None
        change = np.hypot(drift(ds, "coupler_point_x").values, drift(ds, "coupler_point_y").values)
    elif name in ds:
        change = drift(ds, name).values
    else:
        return None
    return np.nanmax(np.abs(change), axis=-1)


def _shown_times(comp: Compensation) -> np.ndarray:
    """The ageing times (s) the drift table shows: the scene's inside the life, its ends
    and the ends of the compensation."""

    scene = comp.scene
    stored = ageing_times(scene, scene.environment)
    inside = stored[(stored >= comp.life[0]) & (stored <= comp.life[1])]
    return np.unique(np.concatenate([inside, np.array(comp.life), comp.times[[0, -1]]]))


def _drift_lines(comp: Compensation) -> list[str]:
    """The drift of the key outputs from the design, before and after compensation."""
    columns = []
    for name, label, scale, unit in KEY_OUTPUTS:
        old = _largest_deviation(comp.before, name)
        if old is not None:
            new = _largest_deviation(comp.after, name)
            columns.append((f"{label} {unit}", old * scale, new * scale))
    if not columns:
        return []
    lines = ["largest deviation from the design over the cycle (before -> after compensation):",
             f"  {'time':>9}  " + "  ".join(f"{title:>26}" for title, _, _ in columns)]
    for k in np.flatnonzero(np.isin(comp.check, _shown_times(comp))):
        cells = "  ".join(f"{old[k]:12.4g} -> {new[k]:10.4g}" for _, old, new in columns)
        lines.append(f"  {days(comp.check[k]):>9}  {cells}")
    return lines


def report(comp: Compensation, scene) -> str:
    """Everything `fickcam compensate` prints before the files it wrote (no runs: it reads
    the runs the compensation made).

    Parameters
    ----------
    comp : Compensation
        The compensation, with its runs as designed and as made.
    scene : Scene
        The design scene (its name and limits).

    Returns
    -------
    str
        The report.
    """

    lines = [header(comp, scene), dimension_table(comp)] + _residual_lines(comp) + \
        limit_lines(comp) + _advice_lines(comp, scene) + anisotropy_note(comp) + _drift_lines(comp)
    return "\n".join(lines)


# ------------------------------------------------------------------ files


def _design_paths(design: dict, base_dir: Path, folder: Path) -> None:
    """The files the ``design:`` entry names (a cam's points or drawing, a link's drawing),
    rewritten from ``base_dir`` relative to ``folder`` (in place)."""
    linkage = design.get("linkage") or {}
    for owner in [design.get("cam") or {}] + [linkage.get(link) for link in DRAWN_LINKS]:
        if not isinstance(owner, dict):  # a link given by its length
            continue
        for key in ("profile_file", "drawing"):
            given = owner.get(key)
            if isinstance(given, dict) and isinstance(given.get("file"), str):
                owner[key] = {**given, "file": relative_to(given["file"], base_dir, folder)}
            elif isinstance(given, str):
                owner[key] = relative_to(given, base_dir, folder)


def scene_text(comp: Compensation, scene, data: dict, folder: Path) -> str:
    """The compensated scene's YAML: the made dimensions, ``design:`` the drawing's intent,
    paths relative to ``folder``, the table and the limits as comments.

    Parameters
    ----------
    comp : Compensation
        The compensation (the table and limits written as comments).
    scene : Scene
        The design scene (its name, description and folder).
    data : dict
        The made scene mapping (changed in place: name, outputs, paths).
    folder : pathlib.Path
        The folder the scene is written to.

    Returns
    -------
    str
        The YAML text.
    """
    environment = data.get("environment") or {}
    if isinstance(environment.get("history_file"), str) and ":" not in environment["history_file"]:
        environment["history_file"] = relative_to(environment["history_file"], scene.base_dir,
                                                  folder)
    _design_paths(data.get("design") or {}, scene.base_dir, folder)
    data["name"] = f"{scene.name}-compensated"
    data["description"] = f"{scene.model.description} (compensated {_when_text(comp)})".strip()
    outputs = dict(data.get("outputs") or {})
    outputs["file"] = f"outputs/{data['name']}.h5"
    data["outputs"] = outputs
    comments = [header(comp, scene) + "."] + dimension_table(comp).splitlines() + limit_lines(comp)
    return (f"# Written by `fickcam compensate` from {scene.file}.\n"
            + "".join(f"# {line}\n" for line in comments)
            + yaml.safe_dump(data, sort_keys=False, allow_unicode=True))


def _drawing_writer(data: dict, points, base_dir: Path, path: Path):
    """A writer of the made cam's dry working profile to ``path`` (.csv or .dxf, mm);
    ``data``: the made scene mapping, its paths relative to ``base_dir``."""

    x, y = (points[:, 0], points[:, 1]) if points is not None else \
        made_outline(data, base_dir, PROFILE_POINTS)
    write = write_profile_dxf if path.suffix.lower() == ".dxf" else write_profile_csv
    return lambda tmp: write(tmp, x, y)


def write_scene(comp: Compensation, scene, path, *, profile=None, plot=None) -> Path:
    """Write the compensated scene and what goes with it (:func:`write_files`); returns the
    scene's path.

    Parameters
    ----------
    comp, scene, path, profile, plot
        As :func:`write_files` takes them.

    Returns
    -------
    pathlib.Path
        The scene's path.
    """
    return write_files(comp, scene, path, profile=profile, plot=plot)[0]


def write_files(comp: Compensation, scene, path, *, profile=None, plot=None) -> list[Path]:
    """Write the compensated scene (a cam given by points: its points beside it as
    ``<stem>_cam_profile.csv``; a drawn cam its made drawing as ``<stem>_cam.dxf``, a
    drawn link its made drawing as ``<stem>_<link>.dxf``, which the made scene names,
    :mod:`fickcam.compensation.drawn`), and when asked the made cam's profile (``profile``, .csv
    or .dxf) and the drift against the bands (``plot``, PNG); all together through
    temporary files and renames, so that nothing is written if one fails. Returns the
    paths written, the scene's first.

    Parameters
    ----------
    comp : Compensation
        The compensation (its made scene mapping, targets and made values).
    scene : Scene
        The design scene, as designed.
    path : str or pathlib.Path
        The scene file to write.
    profile : str or pathlib.Path, optional
        Also write the made cam's profile here (.csv or .dxf).
    plot : str or pathlib.Path, optional
        Also draw the drift against the bands here (PNG).

    Returns
    -------
    list of pathlib.Path
        The paths written, the scene's first.
    """

    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    csv = profile_path(folder, path.stem)
    data, points, drawings = write_made(comp.scene_data, scene.as_designed(), comp.targets,
                                        comp.made, Path(path.stem))
    writers = {path: None}  # the scene's text last: the drawing may validate the made scene
    if points is not None and not drawn(scene.model.cam):  # a drawn plate: in its drawing
        writers[csv] = lambda tmp: write_points(tmp, points)
    writers.update((folder / name, write) for name, write in drawings.items())
    if profile is not None:
        writers[Path(profile)] = _drawing_writer(data, points, scene.base_dir,
                                                       Path(profile))
    if plot is not None:
        # deferred: keeps matplotlib off the path unless a plot is asked
        from ..plotting.compensation import plot_against_band

        window = tuple(np.unique(comp.times[[0, -1]]) / DAY)
        writers[Path(plot)] = lambda tmp: plot_against_band(comp.before, comp.after, tmp, window)
    text = scene_text(comp, scene, data, folder)
    writers[path] = lambda tmp: Path(tmp).write_text(text, encoding="utf-8")
    with replaced_together(list(writers)) as temps:
        for tmp, write in zip(temps, writers.values()):
            write(tmp)
    return list(writers)
