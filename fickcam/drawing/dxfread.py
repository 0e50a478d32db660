"""A part's planform read from a DXF drawing with ezdxf (the ``dxf`` extra).

Lines, arcs, circles, ellipses, 2-D polylines with bulges and splines become ezdxf paths
(``ezdxf.path.make_path``), flattened by ezdxf within the chord tolerance, every line and
curve into ``LINE_POINTS`` pieces at least, each point on the drawn geometry (a cam
profile's spline through them then sees a line as straight), a polyline's straight
segments kept as drawn (a polyline of many points is a curve sampled); block
references are read through their virtual entities. Annotation (text, dimensions,
hatches) and construction lines (centre, hidden and phantom line types, the ``Defpoints``
layer) are left out and counted; points are kept by layer (a cam's axis); any other entity
is refused by its type and layer. The unit is the header's ``$INSUNITS``, or the one given
where the header has none.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np

from ..extras import require
from ..messages import quieter
from .pieces import Piece, join
from .planform import DrawingError, Planform, planform_of

CURVES = {"LINE", "ARC", "CIRCLE", "ELLIPSE", "LWPOLYLINE", "POLYLINE", "SPLINE"}
ANNOTATION = {"TEXT", "MTEXT", "DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION",
              "LEADER", "MLEADER", "MULTILEADER", "HATCH", "MPOLYGON", "ATTDEF", "ATTRIB",
              "VIEWPORT", "IMAGE", "WIPEOUT", "TOLERANCE", "XLINE", "RAY"}
CONSTRUCTION_LINETYPES = ("CENTER", "HIDDEN", "PHANTOM", "DASH", "DOT", "DIVIDE", "BORDER")
UNITS = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "in": 0.0254, "ft": 0.3048}  # m per unit
TYPICAL_SIZE = 0.05   # m: the size a part's outline most likely has, to judge a missing unit
JOIN = 1e-5           # m: ends closer than this meet
LINE_POINTS = 16      # the fewest pieces a line or curve is cut into (all its points on it)
BEZIER = 2.7e-4       # a cubic Bézier's largest radial error on a quarter circle, per radius


@dataclass(frozen=True, eq=False)
class Drawing:
    """A drawing read as a part.

    Parameters
    ----------
    path : str
        The file.
    planform : Planform
        Its outline and holes [m].
    pieces : tuple of Piece
        Every entity read, flattened [m] (for writing the drawing back).
    unit : float
        Metres per drawing unit [m].
    points : dict
        POINT entities by layer [m], each a list of (x, y).
    left_out : tuple of str
        What was not read, as ``"2 DIMENSION on layer DIM"``.
    """

    path: str
    planform: Planform
    pieces: tuple[Piece, ...] = field(repr=False)
    unit: float
    points: dict = field(default_factory=dict, repr=False)
    left_out: tuple[str, ...] = ()


def unit_of(document, given: str | None, path: str) -> float:
    """Metres per drawing unit: ``$INSUNITS``, else ``given``; refused without either.

    Parameters
    ----------
    document : ezdxf.document.Drawing
        The drawing.
    given : str or None
        The scene's ``units:`` (a key of ``UNITS``).
    path : str
        The file, for messages.

    Returns
    -------
    float
        [m] per unit.

    Raises
    ------
    DrawingError
        No unit, an unknown one, or a given unit the header contradicts.
    """
    # deferred: keeps ezdxf off the start-up path
    from ezdxf.units import METER_FACTOR, unit_name

    code = int(document.header.get("$INSUNITS", 0) or 0)
    header = 1.0 / METER_FACTOR[code] if 0 < code < len(METER_FACTOR) and METER_FACTOR[code] else None
    if given is not None and given not in UNITS:
        raise DrawingError(f"{path}: unknown drawing unit {given!r}; one of {', '.join(UNITS)}")
    chosen = UNITS[given] if given is not None else None
    if header is not None and chosen is not None and not math.isclose(header, chosen):
        raise DrawingError(f"{path}: the drawing says its unit is {unit_name(code).lower()} "
                           f"($INSUNITS), the scene says {given}; leave out units:")
    if header is None and chosen is None:
        raise DrawingError(f"{path}: no units: the drawing's header sets no $INSUNITS and the "
                           f"scene gives no units:{_likely_unit(document)}")
    return header if header is not None else chosen


def _extent(document) -> float:
    """The largest side of the model space's bounding box, in drawing units (0: empty)."""
    # deferred: keeps ezdxf off the start-up path
    from ezdxf import bbox

    box = bbox.extents(document.modelspace())
    return float(max(box.size.x, box.size.y)) if box.has_data else 0.0


def _likely_unit(document) -> str:
    """`` (the outline is S units across: likely mm); add units: mm`` from the extents."""
    size = _extent(document)
    if size <= 0:
        return ""
    unit = min(UNITS, key=lambda name: abs(math.log(size * UNITS[name] / TYPICAL_SIZE)))
    return (f" (the outline is {size:.4g} units across: likely {unit}, {size * UNITS[unit] * 1e3:.4g}"
            f" mm); add units: {unit}")


def _linetype(entity, document) -> str:
    name = entity.dxf.get("linetype", "BYLAYER")
    if name.upper() == "BYLAYER" and document.layers.has_entry(entity.dxf.layer):
        name = document.layers.get(entity.dxf.layer).dxf.get("linetype", "CONTINUOUS")
    return name.upper()


def _entities(space):
    """Every entity of ``space``, block references read through their virtual entities."""
    for entity in space:
        if entity.dxftype() == "INSERT":
            yield from _entities(entity.virtual_entities())
        else:
            yield entity


def _piece(entity, unit: float, tolerance: float) -> Piece | None:
    """The entity flattened within ``tolerance`` [m], in metres; None if it is not flat in
    the drawing's plane."""
    # deferred: keeps ezdxf off the start-up path
    from ezdxf import path as dxfpath

    rough = dxfpath.make_path(entity)
    corners = np.array([(v.x, v.y) for v in rough.control_vertices()]) * unit
    radius = 0.5 * float(np.ptp(corners, axis=0).max()) if len(corners) else 0.0
    # a cubic Bézier strays from a circular arc of angle a by BEZIER r (a / (pi/2))^6
    count = max(1, math.ceil(4 * (BEZIER * radius / tolerance) ** (1 / 6)))
    curve = dxfpath.make_path(entity, segments=count)
    if entity.dxftype() == "LINE":  # a straight Bézier: points along the line
        curve = dxfpath.lines_to_curve4(curve)
    vertices = np.array([(v.x, v.y, v.z) for v in curve.flattening(distance=tolerance / unit,
                                                                    segments=LINE_POINTS)])
    if len(vertices) < 2 or np.ptp(vertices[:, 2]) * unit > tolerance:
        return None
    points = vertices[:, :2] * unit
    closed = len(points) > 2 and np.hypot(*(points[-1] - points[0])) <= tolerance * 1e-3
    return Piece(points[:-1] if closed else points, closed, entity.dxftype(), entity.dxf.layer, entity)


def _sorted_entities(document, path: str, unit: float, tolerance: float, layers):
    """(pieces, points by layer, what was left out) of the model space."""
    pieces, points, left_out = [], {}, {}
    wanted = None if layers is None else {name.casefold() for name in layers}
    for entity in _entities(document.modelspace()):
        kind, layer = entity.dxftype(), entity.dxf.get("layer", "0")
        skipped = (wanted is not None and layer.casefold() not in wanted) or (
            layer.casefold() == "defpoints")
        if kind == "POINT" and not skipped:
            points.setdefault(layer, []).append(tuple(np.asarray(entity.dxf.location)[:2] * unit))
            continue
        if skipped or kind in ANNOTATION or (kind in CURVES and _linetype(entity, document)
                                             .startswith(CONSTRUCTION_LINETYPES)):
            left_out[(kind, layer)] = left_out.get((kind, layer), 0) + 1
            continue
        if kind in CURVES and not (kind == "POLYLINE" and (entity.is_poly_face_mesh
                                                           or entity.is_polygon_mesh)):
            piece = _piece(entity, unit, tolerance)
            if piece is not None:
                pieces.append(piece)
                continue
            raise DrawingError(f"{path}: the {kind} on layer {layer} does not lie in the "
                               f"drawing's plane (z varies)")
        raise DrawingError(f"{path}: cannot read the {kind} on layer {layer}: a part is drawn "
                           f"with lines, arcs, circles, ellipses, polylines and splines; explode "
                           f"it, or leave its layer out")
    return pieces, points, tuple(f"{n} {k} on layer {lay}" for (k, lay), n in left_out.items())


def read_drawing(path, tolerance: float, units: str | None = None, join_tolerance: float = JOIN,
                 layers=None, relative: bool = False) -> Drawing:
    """A part's planform from a DXF drawing.

    Parameters
    ----------
    path : str or pathlib.Path
        The DXF file.
    tolerance : float
        The largest distance between a curve and its chords [m] (``relative``: [-], a share
        of the drawing's largest extent).
    units : str, optional
        The drawing's unit (``mm``, ``cm``, ``m``, ``in``, ``ft``) where its header sets none.
    join_tolerance : float
        Ends closer than this meet [m].
    layers : sequence of str, optional
        Read only these layers (all but ``Defpoints`` by default).
    relative : bool
        ``tolerance`` is a share of the drawing's extent.

    Returns
    -------
    Drawing
        The planform [m] and the pieces it was made of.

    Raises
    ------
    fickcam.extras.MissingExtra
        Without ezdxf (the ``dxf`` extra).
    DrawingError
        An unreadable file or entity, no unit, an open loop, crossing loops, a hole outside
        the outline: one line naming the file, the entity and its layer.
    """
    ezdxf = require("dxf")
    path = str(path)
    with quieter("ezdxf", logging.WARNING):
        try:
            document = ezdxf.readfile(path)
        except (OSError, ezdxf.DXFError) as error:
            raise DrawingError(f"{path}: not a readable DXF drawing ({error})") from None
        unit = unit_of(document, units, path)
        if relative:
            tolerance *= _extent(document) * unit
        pieces, points, left_out = _sorted_entities(document, path, unit, tolerance, layers)
    try:
        planform = planform_of(join(pieces, join_tolerance))
    except DrawingError as error:
        raise DrawingError(f"{path}: {error}") from None
    return Drawing(path, planform, tuple(pieces), unit, points, left_out)
