"""Cam sizing (`fickcam size`): the smallest base circle radius whose dry cam keeps the
pressure angle and the radius of curvature within limits, and whether the aged cam of
that size still does at the end of the ageing (Norton, Design of Machinery 5th ed.,
sec. 8.7: 'sizing the cam', pressure angle below about 30 deg, no undercut, radius of
curvature of the working profile above a minimum).

Both checks are monotone in the base circle radius Rb for a translating follower (the
pressure angle atan((y' - e)/(s0 + y)) falls and the convex radius of curvature grows
as Rb grows), so each is found by bisection to SIZE_TOLERANCE and the larger wins. A
swinging arm on a fixed pivot reaches only a band of base circles (:func:`arm_reach`) and
its pressure angle need not fall with Rb (the arm turns towards the cam axis as Rb grows),
so each check is scanned over that band (ARM_SCAN radii) and the first radius that meets
it refined by bisection against the one before.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

#: bisection tolerance on the base circle radius (m)
SIZE_TOLERANCE = 1e-7
#: cam angle step of the checks (rad)
SIZE_STEP = math.radians(0.25)
#: base circle radii scanned across a swinging arm's reach
ARM_SCAN = 64


@dataclass(frozen=True)
class Limits:
    """The sizing limits (``fickcam size``).

    Parameters
    ----------
    pressure_angle : float
        The largest |pressure angle| [rad] (default 30 deg).
    radius_of_curvature : float
        The smallest convex working radius of curvature [m]; the profile must stay convex
        (> 0) in any case.
    """

    pressure_angle: float = math.radians(30.0)  # largest |pressure angle| (rad)
    radius_of_curvature: float = 0.0            # smallest convex working radius (m); > 0 always


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
    from .design import CamState
    from .oscillating import follower_response

    theta = np.arange(0.0, 2 * math.pi, step)
    v = follower_response(design, state or CamState(), theta).variables
    return (float(np.max(np.abs(v["pressure_angle"]))),
            _smallest_convex_radius(design.follower_kind, v["radius_of_curvature"],
                                   v["pitch_radius_of_curvature"]))


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
        The limits.
    phi : float
        Largest |pressure angle| [rad].
    rho : float
        Smallest convex working radius of curvature [m].

    Returns
    -------
    tuple of bool
        Whether each meets its limit.
    """
    return phi <= limits.pressure_angle + 1e-12, rho > 0.0 and rho >= limits.radius_of_curvature


def meets(design, limits: Limits, state=None) -> tuple[bool, bool]:
    """:func:`within` for the worst pressure angle and radius of curvature of ``design``.

    Parameters
    ----------
    design : CamDesign
        The cam.
    limits : Limits
        The limits.
    state : CamState, optional
        Its aged state; None: dry.

    Returns
    -------
    tuple of bool
        (pressure angle within its limit, radius of curvature within its limit).
    """
    return within(limits, *worst(design, state))


def _smallest(design, ok, lowest: float) -> float:
    """Smallest Rb >= lowest with ok(design at Rb) (bisection; ok monotone in Rb)."""
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


def smallest_base_circle(design, limits: Limits) -> dict[str, float]:
    """Smallest dry base circle radius for each limit and overall (m).

    Parameters
    ----------
    design : CamDesign
        A cam given by motion segments.
    limits : Limits
        The pressure angle [rad] and radius of curvature [m] limits.

    Returns
    -------
    dict of str to float
        ``pressure_angle``, ``radius_of_curvature`` (the smallest radius meeting each
        limit) and ``base_circle_radius`` (both) [m].

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
    # the prime circle must clear the offset, and the bore needs room
    lowest = max(abs(design.offset) - design.roller_radius, design.bore_radius, 0.0) + SIZE_TOLERANCE
    if design.arm is not None:
        low, high = arm_reach(design)
        low = max(low, lowest)
        angle = _smallest_in_reach(design, lambda d: meets(d, limits)[0], low, high)
        curvature = _smallest_in_reach(design, lambda d: meets(d, limits)[1], low, high)
        return {"pressure_angle": angle, "radius_of_curvature": curvature,
                "base_circle_radius": max(angle, curvature)}
    angle = _smallest(design, lambda d: meets(d, limits)[0], lowest)
    curvature = _smallest(design, lambda d: meets(d, limits)[1], lowest)
    return {"pressure_angle": angle, "radius_of_curvature": curvature,
            "base_circle_radius": max(angle, curvature)}


def aged_check(ds, limits: Limits, kind: str) -> str:
    """Whether the last valid ageing time of a (sized) result still meets the limits.

    Parameters
    ----------
    ds : xarray.Dataset
        The result (pressure angle stored in [deg], radii [m], time [d]).
    limits : Limits
        The limits.
    kind : str
        The follower kind (``"flat"``, ``"roller"``, ``"knife"``).

    Returns
    -------
    str
        One sentence for the user.
    """
    last = ds.isel(time=int(np.flatnonzero(np.isfinite(ds["base_circle_radius"].values))[-1]))
    phi = math.radians(float(np.nanmax(np.abs(last["pressure_angle"].values))))  # stored in deg
    rho = _smallest_convex_radius(kind, last["radius_of_curvature"].values,
                                 last["pitch_radius_of_curvature"].values)
    days = float(last["time"])
    ok = all(within(limits, phi, rho))
    return (f"aged at t = {days:g} d: largest pressure angle {math.degrees(phi):.4g} deg, smallest "
            f"convex radius of curvature {rho * 1e3:.4g} mm: "
            f"{'still meets the limits' if ok else 'NO LONGER meets the limits'}")
