"""The size of a scene's result, estimated from the scene before any work.

The result holds, for each variable of the schema (:mod:`fickcam.schema`) that the scene
computes, one 8-byte number per point of its dimensions: ageing times, parts, cam or crank
angles (one per ``angle_step``), links and joints of a four-bar, limits, and the cells of
each part when ``outputs.fields`` keeps the moisture fields. `fickcam check` prints the
estimate; `fickcam check` and `fickcam run` warn above :data:`WARN_ABOVE`, with the
settings that shrink it, and `run` refuses a result the disk cannot hold before it starts.
A sweep's combined result is its base scene's times its cases, warned of and refused the
same way before its first case.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import WriteError
from ..messages import warn
from ..results.store import CHUNKED_ABOVE, byte_size, free_space
from ..schema import VARIABLES
from .planning import plan_parts
from .times import ageing_times

#: a result above this [bytes] is warned of, with the settings that shrink it
WARN_ABOVE = 2**30
#: the bytes a file adds per variable (its header, attributes and dimension scales),
#: measured on the example scenes' results
PER_VARIABLE = 1500
#: the most a large result's compression (zlib after the byte shuffle) is taken to gain:
#: a compressed result is refused for want of space only when even this would not fit
COMPRESSION_BOUND = 3.0
#: the points of a four-bar's ``link`` and ``joint`` dimensions
FOURBAR_POINTS = {"link": 4, "joint": 4}
#: name prefixes of cam variables that only some cams compute, with the scene's switch
_OPTIONAL_CAM = (("follower_arm_", "arm"), ("arm_", "arm"), ("dynamic_", "stiffness"),
                 ("startup_", "stiffness"), ("polydyne_", "polydyne"))


@dataclass(frozen=True)
class ResultSize:
    """A result's estimated size and the dimensions it comes from.

    Parameters
    ----------
    bytes : int
        The estimated file size, uncompressed [bytes].
    sizes : dict of str to int
        Dimension -> its length (``time``, ``cam_angle``, ...).
    fields : bool
        Whether the moisture fields are kept (``outputs.fields``).
    """

    bytes: int
    sizes: dict
    fields: bool

    def text(self) -> str:
        """``about 4.8 GB (87,601 ageing times x 360 cam angles)``: the estimate in words."""
        named = [("case", "cases"), ("time", "ageing times"), ("cam_angle", "cam angles"),
                 ("crank_angle", "crank angles"), ("cell", "cells")]
        factors = [f"{self.sizes[dim]:,} {words}" for dim, words in named
                   if self.sizes.get(dim) and not (dim == "case" and self.sizes[dim] == 1)]
        return f"about {byte_size(self.bytes)} ({' x '.join(factors)})"

    def advice(self) -> str:
        """What shrinks the result, in scene keys."""
        ways = ["fewer ageing times (outputs.ageing_times)"]
        if self.sizes.get("case", 1) > 1:
            ways.insert(0, "fewer cases")
        if self.sizes.get("cam_angle") or self.sizes.get("crank_angle"):
            ways.append("a coarser outputs.angle_step")
        if self.fields:
            ways.append("outputs.fields: false")
        return ", ".join(ways[:-1]) + f" or {ways[-1]}" if len(ways) > 1 else ways[0]


def _computed(name: str, section: str, scene) -> bool:
    """Whether the scene computes the schema variable ``name`` (of ``section``)."""
    model = scene.model
    if section == "fields":
        return bool(model.outputs.fields)
    if section == "elastic":
        return bool(scene.elastic_parts)
    if section == "cam" and scene.has("cam"):
        cam = scene.mechanism("cam").section
        switches = {"arm": cam.follower.arm, "stiffness": cam.follower.stiffness,
                    "polydyne": cam.polydyne}
        return all(switches[switch] is not None for prefix, switch in _OPTIONAL_CAM
                   if name.startswith(prefix))
    return True


def estimate(scene, times=None, cells: int | None = None, cases: int = 1) -> ResultSize:
    """The result's size, from the scene alone.

    Parameters
    ----------
    scene : fickcam.scene.load.Scene
        A validated scene.
    times : array_like, optional
        Its ageing times [s] (None: worked out from the scene, as a run would).
    cells : int, optional
        The most cells of a part's moisture field [1], when the fields are kept (None:
        planned here when ``outputs.fields`` is true).
    cases : int
        The cases of a sweep whose base scene ``scene`` is [1]: each variable of the
        combined result holds one case's values per case.

    Returns
    -------
    ResultSize
        The estimate, uncompressed.
    """

    model = scene.model
    if times is None:
        times = ageing_times(scene, scene.environment)
    if model.outputs.fields and cells is None:
        cells = max((p.cells for _, p in plan_parts(scene)[3] if hasattr(p, "cells")), default=0)
    angles = round(2 * math.pi / model.outputs.angle_step)
    coordinates = {name: len(values) for mechanism in scene.mechanisms
                   for name, values in mechanism.coordinates(range(angles)).items()}
    sizes = {"time": len(times), "part": len(scene.parts), "cam_angle": 0, "crank_angle": 0,
             **FOURBAR_POINTS, **coordinates,
             "limit": len(scene.limits or ()), "cell": (cells or 0) if model.outputs.fields else 0,
             "case": cases}
    total = 0
    for name, var in VARIABLES.items():
        if not _computed(name, var.section, scene):
            continue
        points = math.prod(sizes.get(dim, 0) for dim in var.dims)
        if points:
            total += 8 * points * cases + PER_VARIABLE
    return ResultSize(total, sizes, bool(model.outputs.fields))


def size_warning(size: ResultSize) -> str | None:
    """The warning for a result above :data:`WARN_ABOVE`, else None.

    Parameters
    ----------
    size : ResultSize
        The estimate.

    Returns
    -------
    str or None
        One line: the estimate and what shrinks it.
    """
    if size.bytes <= WARN_ABOVE:
        return None
    return (f"the result will be {size.text()}, written compressed; to shrink it: "
            f"{size.advice()}")


def check_space(size: ResultSize, path) -> None:
    """Refuse, before the run, a result that cannot fit on the disk at ``path``.

    Parameters
    ----------
    size : ResultSize
        The estimate.
    path : str or pathlib.Path
        The file the result goes to.
        A result above :data:`fickcam.results.store.CHUNKED_ABOVE` is written compressed: then only
        a disk too small for ``size.bytes / COMPRESSION_BOUND`` is refused (the write itself
        reports the rest, in one line).

    Raises
    ------
    fickcam.errors.WriteError
        Naming the path, the space needed and the space free.
    """
    path = Path(path)
    folder = next((p for p in (path.parent, *path.parent.parents) if p.is_dir()), Path("."))
    free = free_space(folder)
    compressed = size.bytes > CHUNKED_ABOVE
    needed = size.bytes / COMPRESSION_BOUND if compressed else size.bytes
    if free is not None and needed > free:
        least = " at least" if compressed else ""
        raise WriteError(f"{path}: the result will be {size.text()} and needs{least} "
                         f"{byte_size(needed)} on the disk, which has {byte_size(free)} free: "
                         f"nothing was run; to shrink it: {size.advice()}")


def result_fits(scene, output, cases: int = 1) -> None:
    """Before a run or a sweep: warn of a result above :data:`WARN_ABOVE`, with the
    settings that shrink it, and refuse one that the disk at ``output`` cannot hold.

    Parameters
    ----------
    scene : fickcam.scene.load.Scene
        The scene to run, or a sweep's base scene.
    output : str or pathlib.Path
        The result file.
    cases : int
        The sweep's cases [1]; 1 for a run.

    Raises
    ------
    fickcam.errors.WriteError
        When the disk cannot hold the result.
    """
    size = estimate(scene, cases=cases)
    warning = size_warning(size)
    if warning:
        warn(warning)
    check_space(size, output)
