"""The scene keys of a drawn part, shared by a cam and the links of a four-bar:
``drawing:`` (a DXF file) and ``outline:`` with ``holes:`` (a polygon written in the scene,
read as a drawing is). Values are lengths with their units (``25 mm``); a bare number is in
metres, and an outline that would then span more than ``SPAN_SLIP`` is refused with the
unit its size suggests.
"""
from __future__ import annotations

import math
import re
from typing import Literal

import numpy as np
from pydantic import ConfigDict, Field

from ..quantities.types import Length, SignedLength, StrictModel
from .dxfread import TYPICAL_SIZE, UNITS
from .planform import Planform, polygon_planform

#: an outline written in the scene that spans more than this [m] is almost certainly a unit slip
SPAN_SLIP = 2.0
#: a hole's index in a message of :func:`fickcam.drawing.planform.polygon_planform`
_HOLE = re.compile(r"holes\[(\d+)\]")

Point = tuple[SignedLength, SignedLength]


class _Strict(StrictModel):
    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)


def plausible_outline(value):
    """An ``outline:`` as given, refused (ValueError) when its span is a unit slip
    (:func:`span_slip`): a pydantic validator of the key.

    Parameters
    ----------
    value : list of tuple of float or None
        The outline's points [m].

    Returns
    -------
    list of tuple of float or None
        The value, unchanged.
    """
    reason = None if value is None else span_slip(value)
    if reason:
        raise ValueError(reason)
    return value


class DrawingFile(_Strict):
    """A part given by its DXF drawing (``drawing: FILE.dxf`` is short for ``{file: FILE.dxf}``).

    Parameters
    ----------
    file : str
        The DXF file, relative to the scene.
    units : {"mm", "cm", "m", "in", "ft"}, optional
        The drawing's unit where its header sets none ($INSUNITS).
    """

    file: str = Field(description="The DXF drawing, relative to the scene (outer loop: the outline)")
    units: Literal["mm", "cm", "m", "in", "ft"] | None = Field(
        None, description="The drawing's unit where its header sets none ($INSUNITS)")


def drawing_file(value):
    """``drawing: FILE.dxf`` read as ``{file: FILE.dxf}`` (a pydantic before-validator)."""
    return {"file": value} if isinstance(value, str) else value


class RoundHole(_Strict):
    """A round hole of a polygon written in the scene.

    Parameters
    ----------
    centre : tuple of float
        Its centre (x, y) [m].
    radius : float
        Its radius [m].
    """

    centre: Point = Field(description="The hole's centre (x, y) [m]")
    radius: Length = Field(description="The hole's radius [m]")


Hole = RoundHole | list[Point]


def span_slip(outline) -> str | None:
    """Why an outline's span is almost certainly a unit slip, or None.

    Parameters
    ----------
    outline : sequence of tuple of float
        The outline's points [m].

    Returns
    -------
    str or None
        The reason, with the likely unit, when the outline spans more than ``SPAN_SLIP``.
    """
    span = float(np.ptp(np.asarray(outline, float), axis=0).max())
    if span <= SPAN_SLIP:
        return None
    unit = min(UNITS, key=lambda name: abs(math.log(span * UNITS[name] / TYPICAL_SIZE)))
    return (f"the outline spans {span:.4g} m: likely given in {unit} without its unit; write "
            f"each value with its unit (25 {unit})")


def polygon_of(outline, holes, tolerance: float) -> Planform:
    """The checked planform of ``outline:`` and ``holes:``.

    Parameters
    ----------
    outline : sequence of tuple of float
        The outline's points [m].
    holes : sequence of RoundHole or sequence of tuple of float
        The holes [m].
    tolerance : float
        The chord tolerance of round holes [m].

    Returns
    -------
    Planform
        The outline counter-clockwise, the holes clockwise.

    Raises
    ------
    fickcam.drawing.planform.DrawingError
        As :func:`fickcam.drawing.planform.polygon_planform`.
    """
    loops = [(tuple(h.centre), h.radius) if isinstance(h, RoundHole) else np.asarray(h, float)
             for h in holes or ()]
    return polygon_planform(np.asarray(outline, float), loops, tolerance)



def polygon_key(reason: str) -> tuple:
    """The key a polygon's refusal is about: ``("holes", i)`` when it names ``holes[i]``,
    else ``("outline",)``.

    Parameters
    ----------
    reason : str
        The refusal (:class:`fickcam.drawing.planform.DrawingError`).

    Returns
    -------
    tuple
        The key path inside the section.
    """
    found = _HOLE.search(reason)
    return ("holes", int(found.group(1))) if found else ("outline",)
