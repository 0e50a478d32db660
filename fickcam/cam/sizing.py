"""Cam sizing (`fickcam size`): the smallest base circle radius whose cam keeps the
pressure angle and the radius of curvature within limits, dry and at the strains of its
ageing (Norton, Design of Machinery 5th ed., sec. 8.7: 'sizing the cam', pressure angle
below about 30 deg, no undercut, radius of curvature of the working profile above a
minimum).

Both checks are monotone in the base circle radius Rb for a translating follower (the
pressure angle atan((y' - e)/(s0 + y)) falls and the convex radius of curvature grows
as Rb grows), so each is found by bisection to SIZE_TOLERANCE and the larger wins. A
swinging arm on a fixed pivot reaches only a band of base circles (:func:`arm_reach`) and
its pressure angle need not fall with Rb (the arm turns towards the cam axis as Rb grows),
so each check is scanned over that band (ARM_SCAN radii) and the first radius that meets
it refined by bisection against the one before.

The search is geometry alone: an aged cam enters it through its strains
(:func:`aged_states`), which a run of the scene gives; no diffusion is solved here.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from .design import CamState
from .dynamics import SUBSURFACE_SHEAR_RATIO
from .oscillating import follower_response

#: bisection tolerance on the base circle radius (m)
SIZE_TOLERANCE = 1e-7
#: cam angle step of the checks (rad)
SIZE_STEP = math.radians(0.25)
#: base circle radii scanned across a swinging arm's reach
ARM_SCAN = 64
#: the aged search brackets the dry answer by this share first (strains are far smaller)
NEAR = 0.02
#: a smallest radius of curvature below this share of the base circle is a nearly
#: pointed profile (told as a degenerate answer)
POINTED = 0.01


@dataclass(frozen=True)
class Limits:
    """The sizing limits (``fickcam size``).

    Parameters
    ----------
    pressure_angle : float
        The largest |pressure angle| [rad] (default 30 deg).
    radius_of_curvature : float or None
        The smallest convex working radius of curvature [m]; the profile must stay convex
        (> 0) in any case. None: the designer's default for the follower
        (:func:`default_radius_of_curvature`).
    """

    pressure_angle: float = math.radians(30.0)  # largest |pressure angle| (rad)
    radius_of_curvature: float | None = None    # smallest convex working radius (m); > 0 always

    def for_design(self, design) -> Limits:
        """These limits with the default radius of curvature of ``design``'s follower
        filled in.

        Parameters
        ----------
        design : CamDesign
            The cam.

        Returns
        -------
        Limits
            The limits, ``radius_of_curvature`` given [m].
        """
        if self.radius_of_curvature is not None:
            return self
        return replace(self, radius_of_curvature=default_radius_of_curvature(design))


def default_radius_of_curvature(design) -> float:
    """The smallest working radius of curvature a designer asks by default [m].

    A roller follower: the roller's radius. Norton's rule keeps the smallest radius of
    curvature of the pitch curve at 2 to 3 times the roller's radius; at 2 times, the
    working profile (the pitch curve less the roller) keeps one roller radius. A flat face
    or a knife edge: a positive radius (0 here; :func:`within` asks > 0 in any case).

    Parameters
    ----------
    design : CamDesign
        The cam (follower kind, roller radius [m]).

    Returns
    -------
    float
        The radius [m].

    References
    ----------
    R. L. Norton, *Cam Design and Manufacturing Handbook*, 2nd ed., Industrial Press, 2009,
    ch. 7 (radius of curvature); R. L. Norton, *Design of Machinery*, 5th ed., McGraw-Hill,
    2012, sec. 8.7.
    """
    return float(design.roller_radius) if design.follower_kind == "roller" else 0.0


def worst(design, state=None, step: float = SIZE_STEP) -> tuple[float, float]:
    """(largest |pressure angle| rad, smallest convex working radius of curvature m; -inf
    where the profile has a cusp or undercut) of ``design`` at ``state`` (dry by default).

    Parameters
    ----------
    design : CamDesign
        The cam.
    state : CamState, optional
        Its aged state; None: dry at the reference temperature.
    step : float
        The cam angle step of the check [rad].

    Returns
    -------
    tuple of float
        The largest |pressure angle| [rad] and the smallest convex radius of curvature [m].
    """

    theta = np.arange(0.0, 2 * math.pi, step)
    v = follower_response(design, state or CamState(), theta).variables
    return (float(np.max(np.abs(v["pressure_angle"]))),
            _smallest_convex_radius(design.follower_kind, v["radius_of_curvature"],
                                   v["pitch_radius_of_curvature"]))


def profile_fault(design, step: float = SIZE_STEP) -> str | None:
    """Why the dry profile of a cam given by motion segments is no cam, in one line: a flat
    face's profile with a cusp, or a roller's working profile with an undercut (the convex
    radius of curvature at most 0 somewhere, Norton 2012, sec. 8.7); None when it is one,
    or when the cam is not given by motion segments.

    Parameters
    ----------
    design : CamDesign
        The cam, dry.
    step : float
        The cam angle step of the check [rad].

    Returns
    -------
    str or None
        The reason, naming where and the smallest base circle radius whose profile is a
        cam [mm]; None when there is no fault.
    """
    if design.kind != "motion":
        return None
    theta = np.arange(0.0, 2 * math.pi, step)
    v = follower_response(design, CamState(), theta).variables
    kind = design.follower_kind
    rho = np.asarray(v["radius_of_curvature"], float)
    convex = rho if kind == "flat" else np.where(np.asarray(v["pitch_radius_of_curvature"]) > 0,
                                                 rho, np.inf)
    if np.nanmin(convex) > 0.0:
        return None
    k = int(np.nanargmin(convex))
    what = "a cusp" if kind == "flat" else "an undercut"
    where = (f"{design.base_circle_radius * 1e3:.4g} mm gives the {'flat face' if kind == 'flat' else 'roller'}"
             f"'s profile {what} (radius of curvature {rho[k] * 1e3:.3g} mm at "
             f"{math.degrees(theta[k]):.4g} deg)")
    try:  # the smallest radius whose profile is convex, with no pressure angle limit
        size = smallest_base_circle(design, Limits(math.radians(89.0), SIZE_TOLERANCE))
    except ValueError:
        return f"{where}; no base circle within the follower's reach avoids it"
    return (f"{where}: the smallest without one is {rounded_up(size['base_circle_radius']) * 1e3:.3f} mm; "
            f"`fickcam size` gives the one the pressure angle and curvature limits ask")


def rounded_up(radius: float, tolerance: float = 1e-6) -> float:
    """``radius`` rounded up to ``tolerance``, so that a size printed to its digits stays on
    the safe side of the bound.

    Parameters
    ----------
    radius : float
        A smallest radius [m].
    tolerance : float
        The step it is rounded up to [m] (1 um: the printed digits of a size in mm).

    Returns
    -------
    float
        The radius rounded up [m].
    """
    return math.ceil(radius / tolerance - 1e-6) * tolerance


def _smallest_convex_radius(kind: str, rho, pitch) -> float:
    """Smallest working radius of curvature where the pitch curve is convex (m); a flat
    follower's profile must be convex everywhere (rho <= 0 is a cusp), a roller's working
    profile has an undercut where rho = rho_pitch - R_f <= 0 on a convex pitch curve."""
    rho = np.asarray(rho, float)
    convex = rho if kind == "flat" else np.where(np.asarray(pitch) > 0, rho, np.inf)
    return float(np.nanmin(convex))


def within(limits: Limits, phi: float, rho: float) -> tuple[bool, bool]:
    """(pressure angle within its limit, radius of curvature within its limit).

    Parameters
    ----------
    limits : Limits
        The limits (``radius_of_curvature`` None: 0).
    phi : float
        Largest |pressure angle| [rad].
    rho : float
        Smallest convex working radius of curvature [m].

    Returns
    -------
    tuple of bool
        Whether each meets its limit.
    """
    return (phi <= limits.pressure_angle + 1e-12,
            rho > 0.0 and rho >= (limits.radius_of_curvature or 0.0))


def meets(design, limits: Limits, states=(None,)) -> tuple[bool, bool]:
    """:func:`within` for the worst pressure angle and radius of curvature of ``design``
    over ``states``.

    Parameters
    ----------
    design : CamDesign
        The cam.
    limits : Limits
        The limits.
    states : sequence of CamState or None
        The states to check (None: dry).

    Returns
    -------
    tuple of bool
        (pressure angle within its limit, radius of curvature within its limit), each in
        every state.
    """
    found = [within(limits, *worst(design, state)) for state in states]
    return all(f[0] for f in found), all(f[1] for f in found)


def _smallest(design, ok, lowest: float, near: float | None = None) -> float:
    """Smallest Rb >= lowest with ok(design at Rb) (bisection; ok monotone in Rb); ``near``:
    a size close to the answer (the dry one, for the aged search), bracketed first."""
    if near is not None:
        low, high = max(lowest, near * (1 - NEAR)), near * (1 + NEAR)
        if ok(replace(design, base_circle_radius=high)):
            if not ok(replace(design, base_circle_radius=low)):
                return _bisect(design, ok, low, high)
            if low == lowest:
                return lowest
    high = max(2 * lowest, design.base_circle_radius, 1e-3)
    while not ok(replace(design, base_circle_radius=high)):
        high *= 2
        if high > 100.0:
            raise ValueError("no base circle below 100 m meets the limits")
    if ok(replace(design, base_circle_radius=lowest)):
        return lowest
    return _bisect(design, ok, lowest, high)


def _bisect(design, ok, low: float, high: float) -> float:
    """The Rb in (low, high] where ok turns true (ok(low) false, ok(high) true), to SIZE_TOLERANCE."""
    while high - low > SIZE_TOLERANCE:
        middle = 0.5 * (low + high)
        low, high = (low, middle) if ok(replace(design, base_circle_radius=middle)) else (middle, high)
    return high


def arm_reach(design) -> tuple[float, float]:
    """(lowest, highest) base circle radius a swinging arm can follow through its swing
    beta (:mod:`fickcam.cam.arm`): a roller needs |d - l| < Rb + Rf and an opening angle
    delta + beta < pi, i.e. (Rb + Rf)^2 < d^2 + l^2 + 2 d l cos(beta) (law of cosines); a
    flat face needs d cos(beta) > Rb + f.

    Parameters
    ----------
    design : CamDesign
        The design with its arm (pivot distance d, length l, face offset f, roller
        radius Rf [m]; swing [rad]).

    Returns
    -------
    tuple of float
        The lowest and highest base circle radius [m].
    """
    arm, swing = design.arm, max(np.cumsum([s.height for s in design.segments]))
    d = arm.pivot_distance
    if design.follower_kind == "flat":
        return 0.0, d * math.cos(swing) - arm.face_offset
    top = math.sqrt(d * d + arm.length ** 2 + 2 * d * arm.length * math.cos(swing))
    return abs(d - arm.length) - design.roller_radius, top - design.roller_radius


def _smallest_in_reach(design, ok, lowest: float, highest: float) -> float:
    """Smallest Rb in (lowest, highest) with ok(design at Rb): the first of ARM_SCAN radii,
    refined by bisection against the radius scanned before it."""
    radii = np.linspace(lowest, highest, ARM_SCAN + 2)[1:-1]
    passing = [ok(replace(design, base_circle_radius=float(r))) for r in radii]
    if not any(passing):
        raise ValueError(f"no base circle the arm can reach ({lowest * 1e3:.4g}.."
                         f"{highest * 1e3:.4g} mm) meets the limits; move the pivot or change "
                         f"the arm")
    k = passing.index(True)
    if k == 0:
        return float(radii[0])
    return _bisect(design, ok, float(radii[k - 1]), float(radii[k]))


def floor(design) -> tuple[float, str]:
    """(the smallest base circle the cam's geometry allows [m], what sets it): the prime
    circle must clear the follower offset, and the bore needs room.

    Parameters
    ----------
    design : CamDesign
        The cam (offset, roller and bore radius [m]).

    Returns
    -------
    tuple
        The radius [m] (one SIZE_TOLERANCE above the bound) and its reason.
    """
    reasons = [(abs(design.offset) - design.roller_radius, "the follower offset less the roller radius"),
               (design.bore_radius, "the bore radius")]
    value, reason = max(reasons, key=lambda r: r[0])
    return (value + SIZE_TOLERANCE, reason) if value > 0 else (SIZE_TOLERANCE, "zero")


def smallest_base_circle(design, limits: Limits, states=(None,), near: dict | None = None) -> dict[str, float]:
    """Smallest base circle radius for each limit and overall (m), in every state.

    Parameters
    ----------
    design : CamDesign
        A cam given by motion segments.
    limits : Limits
        The pressure angle [rad] and radius of curvature [m] limits (None: the follower's
        default, :func:`default_radius_of_curvature`).
    states : sequence of CamState or None
        The states the cam must meet them in (None: dry); default: dry only.
    near : dict of str to float, optional
        Sizes close to the answers (e.g. the dry ones for an aged search) [m], tried first
        as brackets (within :data:`NEAR`) of a translating follower's bisections.

    Returns
    -------
    dict of str to float
        ``pressure_angle``, ``radius_of_curvature`` (the smallest radius meeting each
        limit), ``base_circle_radius`` (both) and ``floor`` (the smallest the geometry
        allows, :func:`floor`) [m].

    Raises
    ------
    ValueError
        When the cam is not given by motion segments, or no base circle (below 100 m,
        or within a swinging arm's reach) meets the limits.

    References
    ----------
    R. L. Norton, *Design of Machinery*, 5th ed., McGraw-Hill, 2012, ch. 8.
    """
    if design.kind != "motion":
        raise ValueError("sizing needs a cam given by motion segments (not eccentric)")
    limits = limits.for_design(design)
    lowest = floor(design)[0]
    states = tuple(states)

    def angle_ok(d) -> bool:
        return meets(d, limits, states)[0]

    def curvature_ok(d) -> bool:
        return meets(d, limits, states)[1]

    if design.arm is not None:
        low, high = arm_reach(design)
        low = max(low, lowest)
        angle = _smallest_in_reach(design, angle_ok, low, high)
        curvature = _smallest_in_reach(design, curvature_ok, low, high)
    else:
        near = near or {}
        angle = _smallest(design, angle_ok, lowest, near.get("pressure_angle"))
        curvature = _smallest(design, curvature_ok, lowest, near.get("radius_of_curvature"))
    return {"pressure_angle": angle, "radius_of_curvature": curvature,
            "base_circle_radius": max(angle, curvature), "floor": lowest}


def aged_states(ds, design, extremes: bool = True) -> list[tuple]:
    """The cam's aged states, from a result of its scene.

    The pressure angle and the radius of curvature depend on the ageing time only through
    the cam's in-plane strains and the roller's or arm's strain; each grows or shrinks
    the part it belongs to, so the worst of a check lies at an extreme of one of them:
    ``extremes`` keeps only the ageing times that hold one.

    Parameters
    ----------
    ds : xarray.Dataset
        A result of the scene (strains [-] over (time, part), time [d]).
    design : CamDesign
        The cam (follower kind; a swinging arm or not).
    extremes : bool
        Keep only the times of the extreme strains; False: every valid ageing time.

    Returns
    -------
    list of tuple
        (ageing time [d], CamState), valid times only.
    """

    def strain(part: str, name: str) -> np.ndarray:
        if part not in ds["part"].values:
            return np.zeros(ds.sizes["time"])
        return np.asarray(ds[name].sel(part=part).values, float)

    x, y = strain("cam", "strain_longitudinal"), strain("cam", "strain_transverse")
    follower = 0.5 * (strain("follower", "strain_longitudinal") + strain("follower", "strain_transverse"))
    roller = follower if design.follower_kind == "roller" else np.zeros_like(x)
    arm = strain("follower", "strain_longitudinal") if design.arm is not None else np.zeros_like(x)
    valid = np.flatnonzero(np.isfinite(x) & np.isfinite(y) & np.isfinite(roller) & np.isfinite(arm))
    if valid.size == 0:
        return []
    picks = sorted({int(valid[f(series[valid])]) for series in (x, y, roller, arm)
                    for f in (np.argmin, np.argmax)}) if extremes else valid.tolist()
    days = np.asarray(ds["time"].values, float)
    return [(float(days[k]), CamState(cam_strain_x=float(x[k]), cam_strain_y=float(y[k]),
                                      roller_strain=float(roller[k]), arm_strain=float(arm[k])))
            for k in picks]


def degenerate_notes(design, sizes: dict) -> list[str]:
    """What a size that a bound makes degenerate must tell: which bound, and what to set.

    Parameters
    ----------
    design : CamDesign
        The cam.
    sizes : dict of str to float
        :func:`smallest_base_circle` of it [m].

    Returns
    -------
    list of str
        One line per finding; empty when the limits set the size.
    """
    notes = []
    radius = sizes["base_circle_radius"]
    low, reason = floor(design)
    if _at_floor(design, sizes):
        if reason == "zero":
            default = (f" (the roller's radius, {design.roller_radius * 1e3:g} mm, by default)"
                       if design.follower_kind == "roller" else "")
            notes.append(f"no limit sets this size: every base circle down to {low * 1e3:.4f} mm "
                         f"meets both limits, so the answer is the bound of the search, not a "
                         f"design; set cam.bore_radius to the shaft's radius, or a larger "
                         f"--radius-of-curvature{default}")
        else:
            notes.append(f"{reason} sets this size ({low * 1e3:.4f} mm): both limits are met "
                         f"below it, and the cam leaves no wall around its bore there; choose "
                         f"the base circle from the hub the shaft needs")
    rho = worst(replace(design, base_circle_radius=radius))[1]
    if 0 < rho < POINTED * radius and sizes["radius_of_curvature"] >= sizes["pressure_angle"]:
        notes.append(f"the radius of curvature bound sets this size, and the profile is nearly "
                     f"pointed there (smallest radius {rho * 1e3:.3g} mm); set cam.bore_radius "
                     f"to the shaft's radius, or --radius-of-curvature to the smallest radius "
                     f"you will make")
    return notes


def _at_floor(design, sizes: dict) -> bool:
    """Whether no limit sets the size: both are met at the smallest base circle the
    geometry allows (:func:`floor`), so the answer is that bound, not a design.

    Parameters
    ----------
    design : CamDesign
        The cam.
    sizes : dict of str to float
        :func:`smallest_base_circle` of it [m] (the answer may be rounded up).

    Returns
    -------
    bool
        True when the floor sets the size.
    """
    low = floor(design)[0]
    return max(sizes["pressure_angle"], sizes["radius_of_curvature"]) <= low + SIZE_TOLERANCE


def contact_stress_radius(load_modulus, length: float, shear_strength) -> float:
    """The smallest radius of curvature of a cam under a flat face whose Hertz line
    contact keeps the largest shear stress below the surface within the cam's shear
    strength S [m].

    Below a line contact the largest principal shear stress is 0.30 p0 (Johnson 1985
    sec. 4.2), so yield first begins below the surface at p0 = S / 0.30 (Tresca; the
    classical 3.3 k). With p0 = sqrt(F E* / (pi L rho)) (a flat face: 1/R = 1/rho) the
    contact stays elastic where rho >= F E* / (pi L (S / 0.30)^2), the largest of this over
    the cam angles and ageing times.

    Parameters
    ----------
    load_modulus : array_like
        The contact force times the contact modulus, F E* [N Pa], at each cam angle and
        ageing time (independent of the base circle: a flat face's force is the
        follower's, and E* the materials').
    length : float
        The contact length L [m].
    shear_strength : array_like
        The cam's shear strength S at each ageing time (broadcast against
        ``load_modulus``) [Pa].

    Returns
    -------
    float
        The radius [m]; 0 where nothing bears.

    References
    ----------
    K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, sec. 4.2 and
    eq. 4.45, doi:10.1017/CBO9781139171731; R. L. Norton, *Design of Machinery*, 5th ed.,
    McGraw-Hill, 2012, sec. 8.7 (a flat face's smallest radius of curvature is chosen for
    the contact stress).
    """
    allowable = np.asarray(shear_strength, float) / SUBSURFACE_SHEAR_RATIO
    need = np.asarray(load_modulus, float) / (np.pi * length * allowable ** 2)
    need = need[np.isfinite(need)]
    return float(np.max(need, initial=0.0))
