"""A result's aged cam outline at an ageing time (``fickcam outline``).

A cam result stores its working profile at every ageing time as the contact points over
the cam-angle grid (``profile_x``, ``profile_y`` in the cam frame, about the axis). At a
stored ageing time the outline is that polygon, as stored. Between two stored times each
point is interpolated linearly in the square root of time, the variable in which Fickian
uptake, and so the swelling, is most nearly linear (Crank, The Mathematics of Diffusion,
2nd ed., 1975, sec. 4.3.2: M(t) proportional to sqrt(t) while the sheet is far from
saturation). Its error is estimated by the quadratic in sqrt(t) through the two
neighbours and the next stored time: the largest distance between the two outlines. With
fewer than three stored times there is no estimate, and a time between them is refused
with the nearest stored times named.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, format_duration
from ..quantities.options import ageing_time
from .dataset import ageing_seconds, report_time_unit

#: an asked time this close to a stored one [s] is that stored time (a millisecond)
SAME_TIME = 1e-3


@dataclass(frozen=True)
class AgedOutline:
    """The cam's aged working profile at one ageing time.

    Parameters
    ----------
    x, y : numpy.ndarray
        The outline's points in the cam frame, about the axis [m].
    seconds : float
        The ageing time [s].
    label : str
        The time as text in the result's unit (``45 d``).
    how : str
        How it was found: ``stored``, or the interpolation and its estimated error.
    error : float or None
        The estimated interpolation error [m]; None at a stored time.
    """

    x: np.ndarray
    y: np.ndarray
    seconds: float
    label: str
    how: str
    error: float | None = None

    @property
    def layer(self) -> str:
        """The DXF layer the outline is written on: ``AGED_45d`` (``AGED_45d_INTERPOLATED``
        between stored times)."""
        name = "AGED_" + self.label.replace(" ", "")
        return name + ("" if self.error is None else "_INTERPOLATED")


def _profile(ds, command: str) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) [m] of the stored profile, shape (time, cam_angle); refused without a cam."""
    if "profile_x" not in ds or "profile_y" not in ds:
        raise InputError(f"{command}: the result holds no cam (no profile_x, profile_y): "
                         f"only a cam result has an outline")
    x, y = ds["profile_x"], ds["profile_y"]
    if tuple(x.dims) != ("time", "cam_angle"):
        extra = ", ".join(d for d in x.dims if d not in ("time", "cam_angle"))
        raise InputError(f"{command}: the cam's profile varies along {extra} too (a sweep "
                         f"result): query one case's scene with fickcam run, then outline it")
    return np.asarray(x.values, float), np.asarray(y.values, float)


def _sqrt_quadratic(times, values, at: float) -> np.ndarray:
    """The quadratic in sqrt(t) through three (time [s], values) pairs, at ``at`` [s]."""
    s, a = np.sqrt(np.asarray(times, float)), np.sqrt(at)
    weights = [np.prod([(a - s[j]) / (s[i] - s[j]) for j in range(3) if j != i]) for i in range(3)]
    return sum(w * v for w, v in zip(weights, values))


def aged_outline(ds, time, command: str = "outline") -> AgedOutline:
    """The cam's aged working profile at ageing time ``time``.

    Parameters
    ----------
    ds : xarray.Dataset
        A cam result (``profile_x``, ``profile_y`` over time and cam angle).
    time : str
        The ageing time with its unit (``"45 d"``; a bare number is seconds, as in a scene,
        and refused when it is almost certainly a slip).
    command : str
        The command, for messages.

    Returns
    -------
    AgedOutline
        The stored profile at a stored time; between stored times, interpolated in sqrt(t)
        with its estimated error [m].

    Raises
    ------
    fickcam.errors.InputError
        No cam in the result, a time outside the stored ones, or a time between stored
        ones where no error estimate can be made (fewer than three stored times): one line.
    """
    x, y = _profile(ds, command)
    stored = ageing_seconds(ds)
    seconds = ageing_time("--time", time, stored[-1])
    unit, length = report_time_unit(ds)

    def label(t: float) -> str:  # a time [s] in the result's own unit
        return f"{t / length:.4g} {unit}"

    if seconds < stored[0] - SAME_TIME or seconds > stored[-1] + SAME_TIME:
        raise InputError(f"--time {time}: outside the stored ageing times ({label(stored[0])} "
                         f"to {label(stored[-1])})")
    nearest = int(np.argmin(np.abs(stored - seconds)))
    if abs(stored[nearest] - seconds) <= SAME_TIME:
        return AgedOutline(x[nearest], y[nearest], float(stored[nearest]),
                           label(stored[nearest]), "as stored")
    after = int(np.searchsorted(stored, seconds))
    pair = (after - 1, after)
    if len(stored) < 3:
        raise InputError(f"--time {time}: not a stored ageing time, and with two stored times "
                         f"an interpolation has no error estimate; the stored times are "
                         f"{label(stored[0])} and {label(stored[1])}: ask for one, or add "
                         f"{format_duration(seconds, stored[-1])} to the scene's ageing_times")
    return _interpolated(x, y, stored, seconds, pair, label)


def _interpolated(x, y, stored, seconds: float, pair: tuple, label) -> AgedOutline:
    """The outline interpolated in sqrt(t) between the stored times ``pair`` (indices), its
    error the largest distance [m] to the quadratic in sqrt(t) with the next stored time."""
    i, j = pair
    s0, s1 = np.sqrt(stored[i]), np.sqrt(stored[j])
    w = (np.sqrt(seconds) - s0) / (s1 - s0)
    ix, iy = (1 - w) * x[i] + w * x[j], (1 - w) * y[i] + w * y[j]
    third = j + 1 if j + 1 < len(stored) and (i == 0 or np.sqrt(stored[j + 1]) - s1
                                               < s0 - np.sqrt(stored[i - 1])) else i - 1
    three = sorted((i, j, third))
    qx = _sqrt_quadratic(stored[three], x[three], seconds)
    qy = _sqrt_quadratic(stored[three], y[three], seconds)
    error = float(np.max(np.hypot(qx - ix, qy - iy)))
    how = (f"interpolated in sqrt(t) between the stored {label(stored[i])} and "
           f"{label(stored[j])}; estimated error {error * 1e6:.2g} um (the quadratic in "
           f"sqrt(t) through {', '.join(label(stored[k]) for k in three)} differs by that)")
    return AgedOutline(ix, iy, float(seconds), label(seconds), how, error)
