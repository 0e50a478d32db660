"""Compensation: the dry dimensions to make (at the reference temperature) so that the
mechanism has its design geometry at an ageing time, or stays closest to it over a window.

A dimension L of a part grows with the part's free hygrothermal strain eps(t) to
L_made (1 + eps(t)) (Singh & Sanyal 2016, on the volume, mass and moment of inertia of
neat-resin four-bar links under a hygrothermal environment, eqs. 11-14, read as
a_1 = a (1 + alpha dT + beta dm); Singh & Sanyal 2017, on a carbon/epoxy cam and
follower under a hygrothermal environment, p. 281, scales the cam the same way). Both
papers end on the same instruction: reduce the dimensions by the drift. Holding L_design at time T gives L_made = L_design / (1 + eps(T)). Over a
window [T1, T2] the largest deviation max_t |L_made (1 + eps(t)) - L_design| is
smallest (minimax) when the deviations at the strain's extremes are equal and opposite:
L_made = L_design / (1 + (eps_min + eps_max) / 2), residual L_made (eps_max - eps_min) / 2.

A made part is smaller than the design, so it takes up moisture (and strains)
slightly differently: L_made = L_design / (1 + eps(L_made)) is solved by fixed-point
iteration, each step a run of the scene with the current made dimensions.
"""
from __future__ import annotations

import os
import contextlib
import dataclasses
import logging
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml
from scipy.spatial import cKDTree

from ..errors import FickcamError
from ..scene.load import parse_yaml, validate_document

log = logging.getLogger(__name__)

#: the fixed point stops when no made dimension moves by more than this fraction of
#: its compensation (design - made), or by less than a picometre
RELATIVE_TOLERANCE = 1e-6
ABSOLUTE_TOLERANCE = 1e-12  # m
MAX_ITERATIONS = 20
#: ageing times at which a window's strain extremes are sought (besides the scene's own)
WINDOW_POINTS = 33
#: the targets of a cam's working profile: its points' x and y [m]
PROFILE_NAMES = ("profile x", "profile y")
#: the result variables of a drawn cam's outline in a compensation's part states: the
#: displacement of its moisture field's unevenness at each vertex (time, vertex, axis) [m],
#: and the vertices it was found at (vertex, axis) [m]
OUTLINE_SHIFT, OUTLINE_VERTEX = "outline_shift", "outline_vertex"
#: a made vertex is the part states' vertex within this share of the made outline's extent
SAME_VERTEX = 1e-9
#: bisection steps of a coordinate's minimax over a window (each halves its bracket)
MINIMAX_STEPS = 80


@dataclass(frozen=True)
class Target:
    """A dimension (or an array of profile coordinates) that swells with one part's strain:
    ``part`` (result part), ``strains`` (result variables averaged into the strain that
    acts on it), ``group``/``name`` (table row), ``design`` (m).

    Parameters
    ----------
    group : str
        The table group (a part or link name).
    name : str
        The dimension's name in the table.
    part : str
        The result part whose strain acts on the dimension.
    strains : tuple of str
        Result variables averaged into that strain.
    design : float or numpy.ndarray
        The design value(s) [m].
    mechanism : str
        The scene section of the mechanism it belongs to (``cam``, ``linkage``).
    grown : tuple of str
        Where the dimension grows otherwise than by the part's mean strain (a drawn link's
        displaced pins): (the result variable of the part's aged length, its coordinate,
        the name of the target that is its dry length), e.g. ``("link_length", "link",
        "length")``: the strain is their ratio less one; empty: by ``strains``.
    shifted : int
        For a drawn cam's outline coordinate (a ``PROFILE_NAMES`` target, field route): the
        axis (0: x, 1: y) of the displacement its moisture field's unevenness adds to the
        mean strain's, ``OUTLINE_SHIFT`` (:func:`target_shifts`); -1: none.
    """

    group: str
    name: str
    part: str
    strains: tuple[str, ...]
    design: float | np.ndarray
    mechanism: str = ""
    grown: tuple[str, ...] = ()
    shifted: int = -1


@dataclass
class Compensation:
    """What :func:`fickcam.compensate` found: the made value of every target (m), the
    ageing times it was made for, the iterations the fixed point took, the scene (YAML
    data, as designed) that makes it, and the runs of the design (``before``) and of the
    made scene (``after``) at the ``check`` times (s) across the ``life`` asked about.

    Parameters
    ----------
    targets : list of Target
        The dimensions compensated.
    made : list
        The made (dry) value of each target [m].
    times : numpy.ndarray
        Ageing times made for: [T] or the window's grid [s].
    iterations : int
        Fixed-point iterations taken.
    scene_data : dict
        The made scene's YAML mapping.
    residual : list of float
        Largest |L_made (1 + eps) - L_design| per target over the window [m].
    scene : Scene, optional
        The design scene.
    life : tuple of float
        Start and end of the life asked about [s].
    check : numpy.ndarray, optional
        Ageing times of ``before`` and ``after`` [s].
    before, after : xarray.Dataset, optional
        Runs of the design and of the made scene.
    asked : object, optional
        What was asked, when the life was widened to keep the limits.

    References
    ----------
    Singh & Sanyal (2016), eqs. 11-14; Singh & Sanyal (2017), p. 281; in full in
    :mod:`fickcam.materials`.
    """

    targets: list[Target]
    made: list
    times: np.ndarray               # s: [T] or the window grid
    iterations: int
    scene_data: dict
    residual: list = field(default_factory=list)  # largest |made (1 + eps) - design| per target, m
    scene: object = None                          # the design scene (fickcam.scene.load.Scene)
    life: tuple = (0.0, 0.0)                      # s: the window, or delivery to the history's end
    check: np.ndarray = None                      # s: the ageing times of before and after
    before: object = None                         # xarray.Dataset of the design
    after: object = None                          # xarray.Dataset of the made scene
    asked: object = None                          # what was asked when keep_limits widened it

    def in_life(self) -> np.ndarray:
        """Which of the ``check`` times lie in the life asked about (a plot adds others)."""
        return (self.check >= self.life[0]) & (self.check <= self.life[1])

    def ratios(self, ds, limit: str) -> tuple[np.ndarray, np.ndarray]:
        """(ageing times in the life, s; the limit ratio of ``limit`` in ``ds`` at them)."""
        inside = self.in_life()
        return self.check[inside], ds.limit_ratio.sel(limit=limit).values[inside]

    def fails(self) -> bool:
        """True when the made part breaks one of the scene's limits across the life."""
        return "limit_ratio" in self.after and any(
            (self.ratios(self.after, name)[1] > 1.0).any() for name in self.after.limit.values)

    def widened(self, times, made, after, iterations, left) -> "Compensation":
        """This compensation made anew for ``times`` (keep_limits); ``asked`` keeps it."""
        return dataclasses.replace(self, made=made, times=np.asarray(times), after=after,
                                   iterations=iterations, residual=left, asked=self)


def part_strain(ds, target: Target, dry=None) -> np.ndarray:
    """The strain acting on ``target`` at every ageing time of a result: the mean of its
    variables, or where it grows otherwise (``target.grown``) the part's aged length over
    its dry length ``dry``, less one.

    Parameters
    ----------
    ds : xarray.Dataset
        A result with a ``part`` dimension (and the variable ``target.grown`` names).
    target : Target
        The dimension.
    dry : float, optional
        The part's dry length in that result [m] (``target.grown``).

    Returns
    -------
    numpy.ndarray
        The strain eps(t) [-].
    """
    if target.grown:
        name, dimension, _ = target.grown
        return ds[name].sel({dimension: target.part}).values / float(dry) - 1.0
    values = [ds[name].sel(part=target.part).values for name in target.strains]
    return np.mean(values, axis=0)


def target_strains(ds, targets: list[Target], made: list) -> list[np.ndarray]:
    """The strain acting on every target in a result whose dimensions are ``made``
    (:func:`part_strain`; a grown target's dry length the made value of the target it
    names).

    Parameters
    ----------
    ds : xarray.Dataset
        The result.
    targets : list of Target
        The dimensions.
    made : list
        Their values in that result [m].

    Returns
    -------
    list of numpy.ndarray
        eps(t) per target [-].
    """
    made_of = {(t.part, t.name): m for t, m in zip(targets, made)}
    return [part_strain(ds, t, made_of[(t.part, t.grown[2])] if t.grown else None)
            for t in targets]


def _midrange(strain: np.ndarray) -> float:
    """(eps_min + eps_max) / 2: the minimax strain of a window (one time: that strain)."""
    return 0.5 * (float(np.min(strain)) + float(np.max(strain)))


def made_value(design, strain: np.ndarray, shift: np.ndarray | None = None):
    """L_made = L_design / (1 + eps_mid), eps_mid the middle of the strain's range: the
    minimax made value over the window (see the module docstring); with a ``shift``, the
    minimax of a coordinate that ages to (1 + eps(t)) L_made + s(t) (:func:`made_shifted`).

    Parameters
    ----------
    design : float or array_like
        L_design [m].
    strain : numpy.ndarray
        The strain over the window [-].
    shift : numpy.ndarray, optional
        The displacement added to the strained coordinate [m], shape (times, n).

    Returns
    -------
    float or numpy.ndarray
        L_made [m].
    """
    if shift is not None:
        return made_shifted(design, strain, shift)
    return np.asarray(design) / (1.0 + _midrange(strain)) if np.ndim(design) else \
        float(design) / (1.0 + _midrange(strain))


def _deviations(design, made, strain, shift) -> np.ndarray:
    """(1 + eps(t)) L_made + s(t) - L_design [m], shape (times, n)."""
    grown = np.multiply.outer(1.0 + np.asarray(strain, float), np.asarray(made, float))
    return grown + (0.0 if shift is None else np.asarray(shift, float)) - np.asarray(design)


def made_shifted(design, strain: np.ndarray, shift: np.ndarray) -> np.ndarray:
    """The made coordinates m that ages to (1 + eps(t)) m + s(t) (the mean strain and the
    displacement of the field's unevenness) closest to the design's D over the window:
    each coordinate's min over m of max_t |a_t m + b_t| (a_t = 1 + eps_t > 0, b_t = s_t - D),
    where the rising max_t (a_t m + b_t) meets the falling max_t (-a_t m - b_t), found by
    bisection from a bracket that holds it. One time: m = (D - s) / (1 + eps) exactly.

    Parameters
    ----------
    design : array_like
        D [m], shape (n,).
    strain : numpy.ndarray
        eps(t) [-], shape (times,).
    shift : numpy.ndarray
        s(t) [m], shape (times, n).

    Returns
    -------
    numpy.ndarray
        The made coordinates [m], shape (n,).
    """
    a = 1.0 + np.asarray(strain, float)[:, None]
    b = np.asarray(shift, float) - np.asarray(design, float)
    if len(a) == 1:
        return -b[0] / a[0]
    middle = -b.mean(axis=0) / a.mean()
    half = np.abs(a * middle + b).max(axis=0) / a.min() + np.finfo(float).tiny
    low, high = middle - half, middle + half  # above high every line is >= 0, below low <= 0
    for _ in range(MINIMAX_STEPS):
        m = 0.5 * (low + high)
        lines = a * m + b
        rising = lines.max(axis=0) >= (-lines).max(axis=0)
        high, low = np.where(rising, m, high), np.where(rising, low, m)
    return 0.5 * (low + high)


def residual(design, made, strain: np.ndarray, shift: np.ndarray | None = None) -> float:
    """max_t |L_made (1 + eps(t)) (+ s(t)) - L_design| over the window, largest over an array.

    Parameters
    ----------
    design : float or array_like
        L_design [m].
    made : float or array_like
        L_made [m].
    strain : numpy.ndarray
        eps(t) over the window [-].
    shift : numpy.ndarray, optional
        The displacement added to the strained coordinate [m], shape (times, n).

    Returns
    -------
    float
        The largest deviation [m].
    """
    return float(np.max(np.abs(_deviations(design, made, strain, shift))))


def target_shifts(ds, targets: list[Target], made: list) -> list:
    """The displacement of the moisture field's unevenness acting on each target whose
    ``shifted`` names an axis, at the made outline's vertices: the part states'
    ``OUTLINE_SHIFT`` matched to them by position (a run that holds none, the design's:
    zeros, the mean strain's outline); None for every other target.

    Parameters
    ----------
    ds : xarray.Dataset
        The result (its ``time`` dimension; a compensation's part states also
        ``OUTLINE_SHIFT`` and ``OUTLINE_VERTEX`` [m]).
    targets : list of Target
        The dimensions.
    made : list
        Their values in that result [m].

    Returns
    -------
    list
        Per target: the shifts (times, n) [m], or None.

    Raises
    ------
    fickcam.errors.FickcamError
        A made vertex that is none of the part states' vertices.
    """
    made_of = {t.name: m for t, m in zip(targets, made)}
    found = []
    for target in targets:
        if target.shifted < 0:
            found.append(None)
            continue
        points = np.column_stack([made_of[name] for name in PROFILE_NAMES])
        if OUTLINE_SHIFT not in ds:
            found.append(np.zeros((ds.sizes["time"], len(points))))
            continue
        gap, index = cKDTree(ds[OUTLINE_VERTEX].values).query(points)
        if np.max(gap) > SAME_VERTEX * np.ptp(points, axis=0).max():
            raise FickcamError("compensation: the made cam's outline lost a vertex when read again")
        found.append(ds[OUTLINE_SHIFT].values[:, index, target.shifted])
    return found


def converged(old: list, new: list, targets: list[Target]) -> bool:
    """True when every made value moved less than the tolerances (module constants).

    Parameters
    ----------
    old, new : list
        Made values of the previous and this iteration [m].
    targets : list of Target
        The dimensions (their design values [m]).

    Returns
    -------
    bool
        Whether the fixed point has converged.
    """
    for before, after, target in zip(old, new, targets):
        moved = np.max(np.abs(np.asarray(after) - np.asarray(before)))
        change = np.max(np.abs(np.asarray(target.design) - np.asarray(after)))
        if moved > max(RELATIVE_TOLERANCE * change, ABSOLUTE_TOLERANCE):
            return False
    return True


@contextlib.contextmanager
def quiet_runs():
    """Silence the notices of the intermediate runs (the final runs report them)."""
    logger = logging.getLogger("fickcam.simulation")  # the runs' stages log under it
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        yield
    finally:
        logger.setLevel(level)


def window_times(start: float, end: float, stored: np.ndarray) -> np.ndarray:
    """Ageing times (s) on which a window's strain extremes are found: a regular grid of
    :data:`WINDOW_POINTS` and the scene's stored times inside the window.

    Parameters
    ----------
    start, end : float
        The window [s].
    stored : numpy.ndarray
        The scene's stored ageing times [s].

    Returns
    -------
    numpy.ndarray
        Sorted ageing times [s]; ``[start]`` for an empty window.
    """
    if end <= start:
        return np.array([float(start)])
    inside = stored[(stored >= start) & (stored <= end)]
    return np.unique(np.concatenate([np.linspace(start, end, WINDOW_POINTS), inside]))


def relative_to(path: str, old_dir: Path, new_dir: Path) -> str:
    """A path of the scene (relative to ``old_dir``) rewritten relative to ``new_dir``.

    Parameters
    ----------
    path : str
        The path as the scene gives it.
    old_dir, new_dir : pathlib.Path
        The folders it was and will be relative to.

    Returns
    -------
    str
        The rewritten path.
    """

    resolved = (old_dir / path).resolve()
    return os.path.relpath(resolved, new_dir.resolve())


def scene_from(data: dict, base_dir: Path, file_name: str):
    """Validate a scene mapping whose relative paths are relative to ``base_dir``.

    Parameters
    ----------
    data : dict
        The scene's YAML mapping.
    base_dir : pathlib.Path
        The folder its relative paths start from.
    file_name : str
        The name its messages give the scene.

    Returns
    -------
    Scene
        The validated scene.

    Raises
    ------
    SceneError
        When the mapping is not a valid scene.
    """

    doc = parse_yaml(yaml.safe_dump(data, sort_keys=False), file=file_name)
    return validate_document(doc, base_dir=base_dir)
