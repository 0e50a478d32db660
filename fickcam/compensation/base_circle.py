"""`fickcam size` on a scene: the smallest base circle, dry and aged, in at most
``MAX_RUNS`` runs of the scene.

The geometry search (:mod:`fickcam.cam.sizing`) needs no diffusion: it reads the aged cam
through its strains. The moisture history depends on the base circle only through the
cam plate's outline, at first order not at all (the uptake of a plate is set by its
thickness until the in-plane edges matter), so one run of the scene at its own base
circle gives the strains the search uses. A run at the answer then measures how much the
moisture does change with the size. The answer is rounded up to :data:`RUN_TOLERANCE`
and run there; where its own moisture asks for a larger one, the search and the run
are repeated. An answer that a bound makes degenerate (no wall around the bore, a nearly
pointed profile) is told, not run: its plate would ask a mesh out of all proportion.

A flat face's radius of curvature defaults to the one its Hertz contact stress asks
(:func:`~fickcam.cam.sizing.contact_stress_radius`), read from the first run's contact
stresses and the cam material's shear strength.
"""
from __future__ import annotations

import contextlib
import dataclasses
import logging
import math

import numpy as np

from ..elastic.strength import ply_strengths
from ..simulation.planning import plan_parts
from ..simulation.simulate import run
from ..cam.sizing import (POINTED, SIZE_TOLERANCE, Limits, aged_states, contact_stress_radius,
                     degenerate_notes, meets, profile_fault, rounded_up, smallest_base_circle,
                     worst)

#: most runs of the scene one sizing makes
MAX_RUNS = 5
#: the answer is rounded up to this and run there; a size its moisture asks that is no
#: larger ends the search (m)
RUN_TOLERANCE = 1e-6


@dataclasses.dataclass
class Sizing:
    """What ``fickcam size`` found.

    Parameters
    ----------
    name : str
        The scene's name.
    design : CamDesign
        The scene's dry cam.
    limits : Limits
        The limits, the radius of curvature filled in [rad], [m].
    dry : dict of str to float
        :func:`~fickcam.cam.sizing.smallest_base_circle` of the dry cam [m].
    sizes : dict of str to float
        The same over the dry cam and its aged states [m].
    runs : list of tuple
        (base circle radius [m], result) of each run of the scene, in order.
    first : dict of str to float
        The sizes found with the moisture of the scene's own base circle [m].
    curvature : str
        Why the radius of curvature limit is what it is, when it is a default (``"the
        roller's radius"``); empty when given.
    """

    name: str
    design: object
    limits: Limits
    dry: dict
    sizes: dict
    runs: list
    first: dict
    curvature: str = ""

    @property
    def radius(self) -> float:
        """The answer [m]."""
        return self.sizes["base_circle_radius"]

    def text(self) -> str:
        """The report for the terminal: the answer, what sets it, the moisture's dependence
        on the size, the aged check, and what to set where a bound makes it degenerate."""
        lines = [f"{self.name}: smallest base circle radius {self.radius * 1e3:.3f} mm, dry and "
                 f"aged (the scene has {self.design.base_circle_radius * 1e3:.3f} mm; "
                 f"dry alone {rounded_up(self.dry['base_circle_radius'], RUN_TOLERANCE) * 1e3:.3f} mm)",
                 f"  {self._needs()}"]
        lines += [f"  {line}" for line in (self._moisture(), self._aged()) if line]
        lines += [f"  note: {line}" for line in self._degenerate()]
        return "\n".join(lines)

    def _needs(self) -> str:
        rho = self.limits.radius_of_curvature
        why = f" ({self.curvature})" if self.curvature else ""

        def need(key: str) -> str:
            if self.sizes[key] <= self.sizes["floor"] + SIZE_TOLERANCE:
                return "met at any size"
            return f"needs {rounded_up(self.sizes[key], RUN_TOLERANCE) * 1e3:.3f} mm"

        return (f"pressure angle <= {math.degrees(self.limits.pressure_angle):g} deg "
                f"{need('pressure_angle')}; radius of curvature "
                f"{'> 0' if rho == 0 else f'>= {rho * 1e3:.4g} mm'}{why} {need('radius_of_curvature')}")

    def _moisture(self) -> str:
        (start, first), (_, last) = self.runs[0], self.runs[-1]
        if len(self.runs) == 1:
            return ""
        m0 = first["moisture_content"].sel(part="cam").values
        m1 = last["moisture_content"].sel(part="cam").values
        change = np.abs(m1 - m0)
        if not np.isfinite(change).any():
            return ""
        k = int(np.nanargmax(change))
        strains = [np.nanmax(np.abs(last[v].sel(part="cam").values - first[v].sel(part="cam").values))
                   for v in ("strain_longitudinal", "strain_transverse")]
        return (f"moisture: the cam's mean moisture at {self.runs[-1][0] * 1e3:.3f} mm differs from "
                f"that at {start * 1e3:.3f} mm by at most {change[k]:.2g} % moisture "
                f"({change[k] / np.nanmax(np.abs(m0)) * 100:.2g} % relative, at t = "
                f"{float(last['time'][k]):.4g} d), its strains by {max(strains):.2g}; sized with "
                f"the moisture at {start * 1e3:.3f} mm: "
                f"{rounded_up(self.first['base_circle_radius'], RUN_TOLERANCE) * 1e3:.3f} mm ({len(self.runs)} runs of the scene)")

    def _aged(self) -> str:
        design = dataclasses.replace(self.design, base_circle_radius=self.radius)
        ds = self.runs[-1][1]
        states = aged_states(ds, self.design, extremes=False)
        if not states:
            return ""
        found = [worst(design, state) for _, state in states]
        phi = max(range(len(found)), key=lambda i: found[i][0])
        rho = min(range(len(found)), key=lambda i: found[i][1])
        ok = found[phi][0] <= self.limits.pressure_angle + 1e-9 and found[rho][1] > 0 and \
            found[rho][1] >= self.limits.radius_of_curvature * (1 - 1e-6)
        own = abs(self.runs[-1][0] - self.radius) <= 1e-12
        whose = ("the sized cam's own moisture" if own else
                 f"the moisture at {self.runs[-1][0] * 1e3:.3f} mm (no run at a degenerate size)")
        return (f"aged, with {whose}: largest pressure angle "
                f"{math.degrees(found[phi][0]):.4g} deg (t = {states[phi][0]:.4g} d), smallest "
                f"convex radius of curvature {found[rho][1] * 1e3:.4g} mm (t = {states[rho][0]:.4g} d): "
                f"{'meets the limits' if ok else 'does NOT meet the limits'}")

    def _degenerate(self) -> list[str]:
        return degenerate_notes(self.design, self.sizes)


def _with_radius(scene, radius: float):
    cam = scene.model.cam.model_copy(update={"base_circle_radius": radius})
    return scene.with_model(scene.model.model_copy(update={"cam": cam}))


def size_scene(scene, limits: Limits) -> Sizing:
    """Size the base circle of a scene's cam, dry and over its ageing.

    Parameters
    ----------
    scene : Scene
        The loaded scene, with a cam given by motion segments.
    limits : Limits
        The largest pressure angle [rad] and smallest radius of curvature [m] (None: the
        follower's default).

    Returns
    -------
    Sizing
        The sizes [m] and the runs made (at most ``MAX_RUNS``).

    Raises
    ------
    ValueError
        When the cam cannot be sized (not motion segments; no base circle meets the
        limits); before any run.
    fickcam.errors.InputError
        What `fickcam check` refuses of the scene at its first size (the scene's own, or
        the dry answer where the scene's profile has a cusp or an undercut).
    """
    design = scene.mechanism("cam").design
    given = limits.radius_of_curvature is not None
    limits = limits.for_design(design)
    dry = smallest_base_circle(design, limits)  # refuses a cam it cannot size before any run
    bare = dataclasses.replace(scene, limits=[])  # the sizing reads no limit crossing
    start, first_scene = design.base_circle_radius, bare
    if profile_fault(design) is not None:  # the scene's own cam has a cusp: no run of it,
        # nor of a nearly pointed one (its tip would set the mesh): the dry answer, its
        # profile no sharper than POINTED of its base circle
        sharpest = max(limits.radius_of_curvature, POINTED * dry["base_circle_radius"])
        away = smallest_base_circle(design, dataclasses.replace(limits, radius_of_curvature=sharpest))
        start = rounded_up(away["base_circle_radius"], RUN_TOLERANCE)
        first_scene = _with_radius(bare, start)
    plan_parts(first_scene)  # every refusal of `fickcam check` before the search's first run
    with _told_once():
        runs = [(start, run(first_scene))]
        curvature = "" if given else _default_reason(design)
        if not given and design.follower_kind == "flat":
            limits, curvature = _flat_face_limits(scene, design, limits, runs[-1][1])
            dry = smallest_base_circle(design, limits)
        first = sizes = _sized(design, limits, runs[-1][1], dry)
        target = rounded_up(sizes["base_circle_radius"], RUN_TOLERANCE)
        if degenerate_notes(design, sizes):  # no run of a cam without a wall or a point
            target = start
        while len(runs) < MAX_RUNS and abs(target - runs[-1][0]) > 1e-12:
            runs.append((target, run(_with_radius(bare, target))))
            own = [state for _, state in aged_states(runs[-1][1], design)]
            if all(meets(dataclasses.replace(design, base_circle_radius=target), limits, own)):
                break  # the size meets the limits with its own moisture too
            sizes = _sized(design, limits, runs[-1][1], dry)
            target = max(target, rounded_up(sizes["base_circle_radius"], RUN_TOLERANCE))
    answer = runs[-1][0] if len(runs) > 1 else rounded_up(sizes["base_circle_radius"], RUN_TOLERANCE)
    return Sizing(scene.name, design, limits, dry, {**sizes, "base_circle_radius": answer}, runs,
                  first, curvature)


def _default_reason(design) -> str:
    """Why the default radius of curvature is what it is
    (:func:`~fickcam.cam.sizing.default_radius_of_curvature`)."""
    return "the roller's radius" if design.follower_kind == "roller" else "a convex profile"


def _flat_face_limits(scene, design, limits: Limits, ds) -> tuple[Limits, str]:
    """The limits with a flat face's default radius of curvature, the one its contact
    stress asks (:func:`~fickcam.cam.sizing.contact_stress_radius`), read from a run of the
    scene, and why; the limits as they are where the cam's material gives no strength.

    The Hertz pressure p0 at radius rho under force F gives F E* = pi L rho p0^2 at each
    cam angle and ageing time of the run, whatever its base circle; the shear strength
    is the cam material's, times the contact surface's property retention at each time.
    """
    material = scene.materials[scene.model.cam.material]
    retention = np.asarray(ds["surface_property_retention"].sel(part="cam").values, float)
    strengths = ply_strengths(material, retention)
    if strengths is None:
        return limits, _default_reason(design)
    shear = np.asarray(strengths["S"], float)
    length = design.contact_length
    rho = np.asarray(ds["radius_of_curvature"].values, float)
    stress = np.asarray(ds["contact_stress"].values, float)
    with np.errstate(invalid="ignore"):
        radius = contact_stress_radius(np.pi * length * rho * stress ** 2, length, shear[:, None])
    if radius <= limits.radius_of_curvature:
        return limits, _default_reason(design)
    strength = float(np.nanmin(shear))
    return (dataclasses.replace(limits, radius_of_curvature=radius),
            f"the flat face's Hertz contact stress: 0.30 p0 within the cam's shear strength, "
            f"{strength / 1e6:.3g} MPa")


@contextlib.contextmanager
def _told_once():
    """Each message the runs log is shown once: the runs of one sizing share their
    notices (the motion's, the climate's), which the user needs to read only once."""
    seen = set()

    def once(record: logging.LogRecord) -> bool:
        key = (record.levelno, record.getMessage())
        new = key not in seen
        seen.add(key)
        return new

    handlers = [h for name in ("", "fickcam") for h in logging.getLogger(name).handlers]
    for handler in handlers:
        handler.addFilter(once)
    try:
        yield
    finally:
        for handler in handlers:
            handler.removeFilter(once)


def _sized(design, limits: Limits, ds, dry: dict) -> dict:
    """:func:`smallest_base_circle` in the aged states of result ``ds`` and dry (the larger
    of each; both checks are monotone in the base circle), the aged bisections bracketed
    first about the ``dry`` sizes [m]."""
    states = [state for _, state in aged_states(ds, design)]
    if not states:
        return dry
    aged = smallest_base_circle(design, limits, states, near=dry)
    return {key: max(aged[key], dry[key]) for key in aged}
