"""A cam given by its profile points (``cam.profile_file``): a CSV of the working or the
pitch profile, the follower motion found from it geometrically, and the profile written
for manufacture (CSV, DXF).

The closed dry profile is a periodic quintic interpolating spline W0(u) of the points,
u the cumulative chord fraction (scipy.interpolate.make_interp_spline; de Boor, A
Practical Guide to Splines, 2001, ch. XIII). Swelling maps it by D = diag(1 + eps_x,
1 + eps_y) (tangents too). The follower touches the aged profile where, after turning
the cam by theta, the roller centre W + R n (knife: W) lies on the follower line x = e,
or (flat face) where the outward normal n points along +y (kinematic inversion, Norton,
Design of Machinery 5th ed., ch. 8); u(theta) is found by Newton's method, started
from a table of theta(u) over the profile's dense samples. From the
same contact, without differentiating data (a swinging arm: :func:`fickcam.cam.arm.arm_slope`):
knife/roller dY/dtheta = e + Y tan(phi),
tan(phi) = (R(theta) T)_y / (R(theta) T)_x with T the profile tangent (the pitch curve is
parallel to the working profile; Norton ch. 8); flat dY/dtheta = (R(theta) W)_x
(Norton ch. 8). The second and third derivatives come from a periodic quintic spline
of dY/dtheta on a uniform grid of cam angles, the extremes of Y from the roots of that
spline. All of it is solved once per aged state (:func:`aged_profile_motion`); any later
angle (the output grid, the jump-speed search) costs one vectorised Newton solve from
the table. The dry spline is evaluated as a :class:`scipy.interpolate.PPoly`.
"""
from __future__ import annotations

import functools
import logging
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..climate.csvrows import CsvError, numbered_rows
from ..extras import require
from ..files import replaced_atomically
from ..quantities.parsing import to_si
from .arm import aged_profile_contact
from .motion import ORDERS

TWO_PI = 2.0 * np.pi
_HEADER = re.compile(r"^\s*(?P<name>[A-Za-z_]+)\s*(?:[\[(](?P<unit>[^\])]*)[\])])?\s*$")
#: column pairs a profile file may give: the working profile or the pitch curve
CURVES = {("x", "y"): "working", ("pitch_x", "pitch_y"): "pitch"}
#: uniform cam-angle grid on which dY/dtheta is splined for the higher derivatives
ANGLE_NODES = 2048
DEGREE = 5


def _rotate(angle, x, y):
    c, s = np.cos(angle), np.sin(angle)
    return c * x - s * y, s * x + c * y


@dataclass(frozen=True, eq=False)
class CamProfile:
    """A closed dry working profile.

    Parameters
    ----------
    spline : scipy.interpolate.BSpline
        Periodic quintic spline u -> (x, y) [m] in the cam frame, counter-clockwise, of the
        chord fraction u in [0, 1) [-] (:func:`periodic_spline`).
    points : int
        How many points it was made from.
    planform : fickcam.drawing.planform.Planform, optional
        A drawn plate's outline and holes about the axis [m] (None: a cam given by points).
    """

    spline: object  # scipy BSpline, u -> (x, y)
    points: int     # how many points it was made from
    planform: object = None  # the drawn plate (fickcam.drawing.planform.Planform) or None

    @functools.cached_property
    def pieces(self):
        """The spline as a :class:`scipy.interpolate.PPoly` (coefficients (6, pieces, 2)):
        the same curve, evaluated several times faster."""
        from scipy.interpolate import PPoly  # only a cam given by points

        t, c, k = self.spline.tck
        x, y = (PPoly.from_spline((t, c[:, j], k)) for j in (0, 1))
        return PPoly(np.stack([x.c, y.c], axis=-1), x.x, extrapolate="periodic")

    @functools.cached_property
    def samples(self):
        """(u, x, y, dx/du, dy/du) at max(4 points, ANGLE_NODES) + 1 evenly spaced u in
        [0, 1] (m): the dense table from which the contact of any aged profile starts."""
        count = max(4 * self.points, ANGLE_NODES)
        u = np.arange(count + 1) / count
        return (u,) + self.at(u) + self.at(u, 1)

    def at(self, u, derivative: int = 0):
        """(x, y) of the profile (or its u-derivative) at u (taken modulo 1)."""
        xy = self.pieces(np.mod(u, 1.0), nu=derivative)
        return xy[..., 0], xy[..., 1]

    def outline(self, n: int):
        """n points evenly spaced in u, counter-clockwise, last != first (m)."""
        return self.at(np.arange(n) / n)

    def radii(self, strain_x: float = 0.0, strain_y: float = 0.0, n: int = 8192):
        """(smallest, largest) distance of the aged profile from the cam axis (m)."""
        x, y = self.outline(n)
        r = np.hypot((1 + strain_x) * x, (1 + strain_y) * y)
        return float(r.min()), float(r.max())


def periodic_spline(x, y):
    """Periodic quintic interpolating spline through a closed polygon (chord parameter).

    Parameters
    ----------
    x, y : array_like
        Profile points in the cam frame [m].
        (the closing point not repeated).

    Returns
    -------
    scipy.interpolate.BSpline
        (x, y)(u) [m] over the cumulative chord fraction u in [0, 1] [-], periodic.

    References
    ----------
    de Boor (2001), ch. XIII; in full in :mod:`fickcam.cam`.
    """
    from scipy.interpolate import make_interp_spline  # only a cam given by points

    xy = np.c_[x, y]
    closed = np.r_[xy, xy[:1]]
    chord = np.r_[0.0, np.cumsum(np.hypot(*np.diff(closed, axis=0).T))]
    return make_interp_spline(chord / chord[-1], closed, k=DEGREE, bc_type="periodic")


def counter_clockwise(x, y):
    """The polygon in counter-clockwise order (shoelace area > 0), closing point dropped.

    Parameters
    ----------
    x, y : array_like
        Profile points in the cam frame [m].

    Returns
    -------
    tuple of numpy.ndarray
        (x, y) [m], counter-clockwise.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    if np.hypot(x[-1] - x[0], y[-1] - y[0]) <= 1e-12 * np.max(np.hypot(x, y)):
        x, y = x[:-1], y[:-1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    return (x, y) if area > 0 else (x[::-1].copy(), y[::-1].copy())


def _outward_normal(tx, ty):
    norm = np.hypot(tx, ty)
    return ty / norm, -tx / norm  # counter-clockwise traversal: outside on the right


def working_from_pitch(x, y, roller_radius: float):
    """Working profile points W = P - R n from pitch-curve points P (Norton ch. 8),
    n the pitch curve's outward normal.

    Parameters
    ----------
    x, y : array_like
        Pitch-curve points, counter-clockwise [m].
    roller_radius : float
        Roller radius R [m].

    Returns
    -------
    tuple of numpy.ndarray
        The working profile's (x, y) [m].

    References
    ----------
    Norton (2012), ch. 8; in full in :mod:`fickcam.cam`.
    """
    spline = periodic_spline(*counter_clockwise(x, y))
    u = np.arange(4 * len(x)) / (4 * len(x))
    (px, py), (tx, ty) = spline(u).T, spline(u, nu=1).T
    nx, ny = _outward_normal(tx, ty)
    return px - roller_radius * nx, py - roller_radius * ny


def make_profile(x, y, curve: str = "working", roller_radius: float = 0.0) -> CamProfile:
    """A :class:`CamProfile` from profile points; a pitch curve is first moved in by
    the roller radius.

    Parameters
    ----------
    x, y : array_like
        Profile points in the cam frame [m].
    curve : {"working", "pitch"}
        What the points are.
    roller_radius : float
        Roller radius [m] (used for a pitch curve).

    Returns
    -------
    CamProfile
        The closed dry working profile.
    """
    x, y = counter_clockwise(x, y)
    if curve == "pitch" and roller_radius > 0:
        x, y = working_from_pitch(x, y, roller_radius)
    return CamProfile(periodic_spline(x, y), len(x))


# ------------------------------------------------------------------ files


def _column_scale(cell: str, path) -> tuple[str, float]:
    match = _HEADER.match(cell)
    if not match:
        raise ValueError(f"profile file {str(path)!r}: header {cell!r} is not 'name [unit]'")
    unit = (match.group("unit") or "").strip()
    return match.group("name"), (to_si(f"1 {unit}", "length") if unit else 1.0)


def read_profile_csv(path) -> tuple[np.ndarray, np.ndarray, str]:
    """(x, y in m, 'working' | 'pitch') from a CSV whose header names the columns with
    units: ``x [mm], y [mm]`` (working profile) or ``pitch_x [in], pitch_y [in]``
    (pitch curve); '#' lines are comments, no unit means metres.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.

    Returns
    -------
    tuple
        (x [m], y [m], "working" or "pitch").

    Raises
    ------
    ValueError
        One line naming the file (and the line) when it is missing, unreadable, empty,
        has other columns or a header cell that is not 'name [unit]', a row that is not two
        numbers, values that are not finite, or too few points.
    """
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            rows = [(n, r) for n, r in numbered_rows(handle)
                    if r and not r[0].lstrip().startswith("#")]
    except FileNotFoundError:
        raise ValueError(f"profile file {str(path)!r} not found") from None
    except CsvError as exc:
        raise ValueError(f"profile file {str(path)!r}: {exc}") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"cannot read profile file {str(path)!r}: {exc}") from None
    if not rows:
        raise ValueError(f"profile file {str(path)!r} is empty")
    header = rows[0][1]
    columns = dict(_column_scale(cell, path) for cell in header)
    pair = next((p for p in CURVES if set(p) <= set(columns)), None)
    if pair is None:
        raise ValueError(f"profile file {str(path)!r}: expected columns x, y (working profile) "
                         f"or pitch_x, pitch_y (pitch curve) with units, e.g. 'x [mm]'")
    names = [_HEADER.match(cell).group("name") for cell in header]
    index = [names.index(n) for n in pair]
    values = []
    for line, row in rows[1:]:
        try:
            values.append([float(row[i]) * columns[n] for i, n in zip(index, pair)])
        except (IndexError, ValueError):
            raise ValueError(f"profile file {str(path)!r} line {line}: expected two numbers") from None
    if len(values) < 3 * DEGREE:
        raise ValueError(f"profile file {str(path)!r}: {len(values)} points are too few for a "
                         f"closed profile (need at least {3 * DEGREE})")
    xy = np.array(values)
    if not np.all(np.isfinite(xy)):
        raise ValueError(f"profile file {str(path)!r}: values must be finite")
    return xy[:, 0], xy[:, 1], CURVES[pair]


def load_profile(path, roller_radius: float = 0.0, mirror: bool = False) -> CamProfile:
    """The :class:`CamProfile` of a profile file, read each time it is asked for (a scene
    reads its profile once, when it is validated, and keeps it);
    ``mirror``: its mirror image x -> -x (a clockwise cam, :mod:`fickcam.cam.kinematics`).

    Parameters
    ----------
    path : str or pathlib.Path
        The profile file (:func:`read_profile_csv`).
    roller_radius : float
        Roller radius [m], to move a pitch curve in to the working profile.
    mirror : bool
        Whether to mirror the points (x -> -x).

    Returns
    -------
    CamProfile
        The closed dry working profile.

    Raises
    ------
    ValueError
        As :func:`read_profile_csv`.
    """
    return profile_of(read_profile_csv(path), roller_radius, mirror)


def profile_of(points: tuple, roller_radius: float = 0.0, mirror: bool = False) -> CamProfile:
    """The :class:`CamProfile` of a profile file's points as read (:func:`read_profile_csv`).

    Parameters
    ----------
    points : tuple
        (x [m], y [m], "working" or "pitch").
    roller_radius : float
        Roller radius [m], to move a pitch curve in to the working profile.
    mirror : bool
        Whether to mirror the points (x -> -x).

    Returns
    -------
    CamProfile
        The closed dry working profile.
    """
    x, y, curve = points
    return make_profile(-x if mirror else x, y, curve, float(roller_radius))


def write_profile_csv(path, x, y, curve: str = "working") -> Path:
    """Write profile points as CSV in mm with units in the header (readable back), through
    a temporary file and a rename.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file to write.
    x, y : array_like
        Profile points [m].
    curve : {"working", "pitch"}
        What the points are (it names the columns).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    names = ("x [mm]", "y [mm]") if curve == "working" else ("pitch_x [mm]", "pitch_y [mm]")
    with replaced_atomically(path) as tmp:
        np.savetxt(tmp, np.c_[x, y] * 1e3, delimiter=",", header=",".join(names), comments="",
                   fmt="%.9f")
    return Path(path)


def dxf_module():
    """ezdxf, or the one-line refusal with its install command (:func:`fickcam.extras.require`):
    a command that will write DXF asks first, before it computes anything.

    Returns
    -------
    module
        ezdxf.

    Raises
    ------
    fickcam.extras.MissingExtra
        Without the extra ``fickcam[dxf]``.
    """
    return require("dxf", advice="or write the profile as .csv")


def write_profile_dxf(path, x, y, layer: str = "PROFILE") -> Path:
    """Write a closed profile (m) as a DXF closed polyline in mm (ezdxf, ``$INSUNITS``
    millimetres) on ``layer``, with the cam axis marked by a point at the origin on layer
    ``AXIS``. Needs the extra ``fickcam[dxf]`` (ezdxf): without it,
    :class:`~fickcam.extras.MissingExtra` and no file.

    Parameters
    ----------
    path : str or pathlib.Path
        The DXF file to write.
    x, y : array_like
        Profile points [m].
    layer : str
        The polyline's layer (``PROFILE``: the dry profile; an aged one is named for its time).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    fickcam.extras.MissingExtra
        Without ezdxf.
    """
    ezdxf = dxf_module()
    logging.getLogger("ezdxf").setLevel(logging.WARNING)  # its INFO lines are about DXF internals
    document = ezdxf.new("R2010", units=ezdxf.units.MM)
    for name in {layer, "AXIS"}:  # declared, as CAD tools expect of every layer used
        document.layers.add(name)
    space = document.modelspace()
    space.add_lwpolyline(list(zip(np.asarray(x) * 1e3, np.asarray(y) * 1e3)), close=True,
                         dxfattribs={"layer": layer})
    space.add_point((0.0, 0.0), dxfattribs={"layer": "AXIS"})
    with replaced_atomically(path) as tmp:
        document.saveas(tmp)
    return Path(path)


# ------------------------------------------------------------------ kinematics




@dataclass(frozen=True)
class AgedContact:
    """The aged profile seen by one follower. Called with profile parameters u [-] it
    returns (theta [rad, mod 2 pi], Y [m; an arm: rad], dY/dtheta [m/rad; an arm: -]) at
    the contact of profile point u: the cam angle at which u touches, the follower height
    (or arm angle) then, and its rate over the cam angle.

    Parameters
    ----------
    profile : CamProfile
        The dry profile.
    strain_x, strain_y : float
        The cam's swelling strains along x and y [-].
    roller : float
        Roller radius [m] (0: knife edge).
    offset : float
        Offset of the follower line x = offset [m].
    flat : bool
        A flat-faced follower.
    arm : fickcam.cam.arm.Arm or None
        A swinging arm, grown; None: a translating follower.
    base : float
        The arm's dry base angle [rad].
    """

    profile: CamProfile
    strain_x: float
    strain_y: float
    roller: float
    offset: float
    flat: bool
    arm: object = None  # a swinging arm (fickcam.cam.arm.Arm, grown) and its dry base angle
    base: float = 0.0

    def __call__(self, u):
        (wx, wy), (tx, ty) = self.profile.at(u), self.profile.at(u, 1)
        return self.touching(wx, wy, tx, ty)

    def touching(self, wx, wy, tx, ty):
        """(theta [rad], Y, dY/dtheta) of dry profile points W [m] with tangents
        T = dW/du [m] (as ``__call__``, from points already evaluated)."""
        sx, sy = 1 + self.strain_x, 1 + self.strain_y
        wx, wy, tx, ty = sx * wx, sy * wy, sx * tx, sy * ty
        nx, ny = _outward_normal(tx, ty)
        if self.arm is not None:
            return aged_profile_contact(self.arm, "flat" if self.flat else "roller", self.base,
                                        self.roller, wx, wy, nx, ny)
        if self.flat:
            theta = np.pi / 2 - np.arctan2(ny, nx)
            height = wx * nx + wy * ny
            slope = _rotate(theta, wx, wy)[0]
            return theta, height, slope
        cx, cy = wx + self.roller * nx, wy + self.roller * ny
        r = np.hypot(cx, cy)
        theta = np.arccos(self.offset / r) - np.arctan2(cy, cx)
        height = np.sqrt(r ** 2 - self.offset ** 2)
        rx, ry = _rotate(theta, tx, ty)
        return theta, height, self.offset + height * ry / rx


def _wrap(angle):
    return np.mod(angle + np.pi, TWO_PI) - np.pi


def contact_table(contact: AgedContact):
    """The cam angle at which each of the profile's dense samples touches.

    Parameters
    ----------
    contact : AgedContact
        The aged profile and its follower.

    Returns
    -------
    (theta, u, rate) : tuple of ndarray
        theta [rad] unwrapped and decreasing (the contact runs clockwise round the
        profile), the samples' u [-] and dtheta/du [rad] there (second-order differences
        of the table): the starts and the slopes of :func:`solve_contact`.

    Raises
    ------
    ValueError
        Where theta(u) is not monotone (an undercut, or concave beyond the roller).
    """
    u_table, w_x, w_y, t_x, t_y = contact.profile.samples
    table = np.unwrap(contact.touching(w_x, w_y, t_x, t_y)[0])
    if not (np.all(np.diff(table) < 0) or np.all(np.diff(table) > 0)):
        raise ValueError("the profile does not touch the follower at one point per cam "
                         "angle (undercut or concave beyond the roller)")
    rate = np.gradient(table, u_table, edge_order=2)
    if table[-1] > table[0]:
        return table[::-1], u_table[::-1], rate[::-1]
    return table, u_table, rate


def solve_contact(contact: AgedContact, table, theta, steps: int = 40):
    """The profile point touching at each cam angle: a start and a slope dtheta/du
    interpolated in ``table``, then Newton's method on theta(u) = theta with that slope,
    until every step is below 1e-12 in u (a picometre of profile); vectorised over theta.
    The table's samples are so close (spacing du <= 1/2048) that the start and the slope
    are right to O(du^2): each step gains about nine digits, and two steps settle.

    Parameters
    ----------
    contact : AgedContact
        The aged profile and its follower.
    table : tuple of ndarray
        (theta [rad], u [-], dtheta/du [rad]) from :func:`contact_table` for this
        ``contact``.
    theta : array_like
        Cam angles [rad], any range.
    steps : int
        Most Newton steps.

    Returns
    -------
    ndarray
        u [-] (the chord fraction round the profile) for each theta.
    """
    angles, u_table, rate = table
    target = angles[0] - np.mod(angles[0] - np.asarray(theta, float), TWO_PI)
    u = np.interp(target, angles[::-1], u_table[::-1])
    slope = np.interp(target, angles[::-1], rate[::-1])
    for _ in range(steps):
        step = _wrap(contact(u)[0] - target) / slope
        u = u - step
        if np.max(np.abs(step), initial=0.0) < 1e-12:
            break
    return u


def piece_roots(curve):
    """The real roots of a piecewise polynomial inside its breakpoints, solving only the
    pieces that can reach zero: those whose value at the left end is no larger than the
    bound sum_k |c_k| dx^k on the change over the piece. Those are solved at once, as the
    eigenvalues of their stacked companion matrices (numpy.linalg.eigvals), in place of
    :meth:`scipy.interpolate.PPoly.roots`, which solves every piece in turn.

    Parameters
    ----------
    curve : scipy.interpolate.PPoly
        Scalar piecewise polynomial of x [any unit].

    Returns
    -------
    ndarray
        Its real roots [unit of x], sorted, unique.
    """
    c, x = curve.c, curve.x
    width = np.diff(x)
    degree = c.shape[0] - 1
    powers = width[None, :] ** np.arange(degree, 0, -1)[:, None]
    reach = np.sum(np.abs(c[:-1]) * powers, axis=0)
    # a root at a piece's far end makes the bound an equality: keep it within round-off
    pieces = np.nonzero((np.abs(c[-1]) <= reach * (1 + 1e-12)) & (reach > 0))[0]
    if not pieces.size:
        return np.empty(0)
    lead = c[0, pieces]
    # a vanishing leading coefficient would blow the companion matrix up: drop to the
    # highest non-negligible power (relative to the piece's reach)
    scale = np.where(np.abs(lead) * width[pieces] ** degree > 1e-14 * reach[pieces], lead, np.nan)
    companion = np.zeros((pieces.size, degree, degree))
    companion[:, 0, :] = -c[1:, pieces].T / scale[:, None]
    companion[:, np.arange(1, degree), np.arange(degree - 1)] = 1.0
    good = np.isfinite(scale)
    local = np.full((pieces.size, degree), np.nan, complex)
    local[good] = np.linalg.eigvals(companion[good])
    for k in np.nonzero(~good)[0]:  # rare: a piece of lower degree
        negligible = np.abs(c[:-1, pieces[k]]) * powers[:, pieces[k]] <= 1e-14 * reach[pieces[k]]
        leading = int(np.argmin(negligible)) if not negligible.all() else degree
        r = np.roots(c[leading:, pieces[k]])
        local[k, :r.size] = r
    span = width[pieces, None]
    real = np.abs(local.imag) <= 1e-9 * span
    inside = real & (local.real >= -1e-12 * span) & (local.real <= (1 + 1e-12) * span)
    roots = (x[pieces, None] + np.clip(local.real, 0.0, span))[inside]
    return np.unique(roots)


@dataclass(frozen=True, eq=False)
class ProfileMotion:
    """The follower motion of one aged profile, solved once (:func:`aged_profile_motion`).

    Called with cam angles theta [rad] (any range), it returns (Y [m], dY/dtheta [m/rad],
    d2Y/dtheta2 [m/rad^2], d3Y/dtheta3 [m/rad^3]), or the derivative orders ``orders``
    (each in 0..3) in that order; a swinging arm's Y is its angle [rad].
    Y and dY/dtheta come from the contact at theta itself (:func:`solve_contact` from the
    table: one vectorised Newton solve), the higher derivatives from the spline.

    Parameters
    ----------
    contact : AgedContact
        The aged profile and its follower.
    table : tuple of numpy.ndarray
        The contact's table (:func:`contact_table`): theta [rad], u [-], dtheta/du [rad].
    slope : scipy.interpolate.BSpline
        Periodic quintic spline of dY/dtheta [m/rad; an arm: -] over theta in [0, 2 pi]
        [rad].
    extremes : tuple of float
        (lowest, highest) Y over the turn [m; an arm: rad].
    """

    contact: AgedContact
    table: tuple
    slope: object  # scipy BSpline of dY/dtheta over [0, 2 pi], periodic
    extremes: tuple

    def __call__(self, theta, orders=ORDERS):
        theta = np.mod(np.asarray(theta, float), TWO_PI)
        _, height, slope = self.contact(solve_contact(self.contact, self.table, theta))
        found = {0: height, 1: slope}  # the higher orders from the spline, when asked for
        return tuple(found[k] if k in found else self.slope(theta, nu=k - 1) for k in orders)


def aged_profile_motion(profile: CamProfile, strain_x: float, strain_y: float, roller: float,
                        offset: float, flat: bool, arm=None, base: float = 0.0) -> ProfileMotion:
    """The follower motion of an aged profile, solved once: the contact on the uniform
    grid of ANGLE_NODES cam angles (one vectorised Newton solve), the periodic quintic
    spline of dY/dtheta through it, and the extremes of Y: the grid's and those at the
    roots of the slope spline (:func:`piece_roots`).

    Parameters
    ----------
    profile : CamProfile
        The dry profile.
    strain_x, strain_y : float
        Swelling strains of the cam along x and y [-].
    roller : float
        Roller radius [m] (0: knife edge; ignored for a flat face).
    offset : float
        Offset of the follower line x = offset [m].
    flat : bool
        A flat-faced follower.
    arm : fickcam.cam.arm.Arm, optional
        A swinging arm, already grown: Y is then its angle [rad] from ``base``.
    base : float
        The arm's dry base angle [rad].

    Returns
    -------
    ProfileMotion
    """
    from scipy.interpolate import PPoly, make_interp_spline  # only a cam given by points

    contact = AgedContact(profile, strain_x, strain_y, roller, offset, flat, arm, base)
    table = contact_table(contact)
    grid = TWO_PI * np.arange(ANGLE_NODES + 1) / ANGLE_NODES
    _, height, slope = contact(solve_contact(contact, table, grid[:-1]))
    spline = make_interp_spline(grid, np.r_[slope, slope[0]], k=DEGREE, bc_type="periodic")
    turning = np.unique(np.mod(piece_roots(PPoly.from_spline(spline)), TWO_PI))
    extremes = np.r_[height, contact(solve_contact(contact, table, turning))[1]
                     if turning.size else []]
    return ProfileMotion(contact, table, spline, (float(extremes.min()), float(extremes.max())))


def profile_motion(profile: CamProfile, strain_x: float, strain_y: float, roller: float,
                   offset: float, flat: bool, theta, arm=None, base: float = 0.0):
    """(Y [m], dY/dtheta [m/rad], d2Y/dtheta2 [m/rad^2], d3Y/dtheta3 [m/rad^3]) at cam
    angles ``theta`` [rad], and (lowest, highest) Y [m] over the turn, of the aged profile;
    the other parameters are those of :func:`aged_profile_motion` (an arm's Y in rad).

    Parameters
    ----------
    profile, strain_x, strain_y, roller, offset, flat, arm, base
        As in :func:`aged_profile_motion`: the dry profile, the cam's strains [-], the
        roller radius and follower offset [m], a flat face, the arm and its base angle [rad].
    theta : array_like
        Cam angles [rad].

    Returns
    -------
    tuple
        ((Y [m], dY/dtheta [m/rad], d2Y/dtheta2 [m/rad^2], d3Y/dtheta3 [m/rad^3]),
        (lowest, highest) Y [m]); an arm's Y in rad.

    References
    ----------
    Norton (2012), ch. 8; in full in :mod:`fickcam.cam`.
    """
    motion = aged_profile_motion(profile, strain_x, strain_y, roller, offset, flat, arm, base)
    return motion(theta), motion.extremes
