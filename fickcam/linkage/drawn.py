"""Links as drawn (``linkage.crank: {drawing: crank.dxf}``, or ``{outline:, holes:}``): the
outer loop with its holes, the pin centres from the two pin holes (on the drawing's pin
layer, or the two largest round holes), the link's length their distance
(:func:`fickcam.drawing.parts.link_of`).

Its diffusion geometry is the drawn planform (:class:`fickcam.diffusion.problem.geometry.DrawnPlate`,
every edge exposed); its dry mass, centre of mass and moment of inertia come from the
planform x thickness x density by Green's theorem
(:meth:`fickcam.drawing.planform.Planform.mass_properties`). Aged, the planform stretches
by (1 + eps_x) along the link and (1 + eps_y) across it: the moment about the centre of
mass of the wet mass m (1 + M/100) spread over the swollen plate is
m_wet (I_yy sx^2 + I_xx sy^2) / A, the second moments of area I about the centroid.

The four-bar's dynamics take a link's centre of mass on the line of its pins, as a
fraction of its length: a drawn link whose centre of mass lies off that line by more than
``OFF_LINE`` of its length is refused.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..drawing.dxfread import read_drawing
from ..drawing.parts import DrawnLink, link_of
from ..drawing.planform import DrawingError
from ..drawing.spec import polygon_key, polygon_of
from ..extras import MissingExtra
from ..materials.hygrothermal import wet_mass
from .spec import DRAWN_LINKS, DrawnLinkSpec, four_bar_problem

#: the chord tolerance of a drawing, as a share of its extent times the scene's accuracy
#: (as a cam's: :data:`fickcam.cam.drawn.CHORD_SHARE`)
CHORD_SHARE = 0.01
#: the largest distance of a drawn link's centre of mass from the line of its pins, as a
#: share of its length
OFF_LINE = 0.01
#: the displacement mesh's edge, a share 1/MESH_ROWS of the drawing's extent (P2 elements:
#: on the dog-bone example 1.3 mm, the pin shift within 1e-4 of the swelling of a mesh
#: twice as fine)
MESH_ROWS = 100


def drawn_link(spec: DrawnLinkSpec, accuracy: float) -> DrawnLink:
    """The link a spec draws, in its frame (first pin at the origin, second on +x).

    Parameters
    ----------
    spec : DrawnLinkSpec
        The link's ``drawing`` (path absolute, or relative to the working folder) or its
        ``outline`` and ``holes``.
    accuracy : float
        The scene's relative accuracy [-]: the chords stray ``CHORD_SHARE`` x it x the
        drawing's extent at most.

    Returns
    -------
    fickcam.drawing.parts.DrawnLink
        The link in its frame [m].

    Raises
    ------
    fickcam.drawing.planform.DrawingError
        A drawing that cannot be a link (no pin holes, an open loop...), in one line.
    fickcam.extras.MissingExtra
        A drawing without the ``dxf`` extra.
    """
    if spec.drawing is None:
        extent = max(max(abs(v) for v in point) for point in spec.outline)
        return link_of(polygon_of(spec.outline, spec.holes, CHORD_SHARE * accuracy * extent))
    drawing = read_drawing(spec.drawing.file, CHORD_SHARE * accuracy, spec.drawing.units,
                           relative=True)
    return link_of(drawing.planform, spec.drawing.pin_layer)


def _read_one(name: str, spec: DrawnLinkSpec, base_dir: Path, accuracy: float):
    """(problems, the spec with its path absolute, the link or None) of one drawn link."""
    if spec.drawing is not None:
        path = str((base_dir / spec.drawing.file).resolve())
        spec = spec.model_copy(update={"drawing": spec.drawing.model_copy(update={"file": path})})
    try:
        link = drawn_link(spec, accuracy)
    except (DrawingError, MissingExtra) as exc:
        key = ("drawing",) if spec.drawing is not None else polygon_key(str(exc))
        if spec.drawing is not None and not str(exc).startswith(spec.drawing.file):
            exc = f"{spec.drawing.file}: {exc}"
        return [((name,) + key, str(exc))], spec, None
    off = abs(link.planform.centroid[1])
    if off > OFF_LINE * link.length:
        return [((name,), f"its centre of mass lies {off * 1e3:.3g} mm off the line of its pins "
                          f"({off / link.length:.1%} of its length); the four-bar's dynamics "
                          f"take it on that line")], spec, None
    return [], spec, link


def read_drawn_links(section, base_dir: Path, accuracy: float):
    """Read the drawn links of a ``linkage:`` section: (problems as (key path inside the
    section, reason), the section with the drawings' paths absolute, the links by name).

    Parameters
    ----------
    section : LinkageSection
        The validated section.
    base_dir : pathlib.Path
        The folder the scene's relative paths start from.
    accuracy : float
        The scene's relative accuracy [-].

    Returns
    -------
    tuple
        As above; the links an empty dict when none is drawn or one is refused.
    """
    problems, update, links = [], {}, {}
    for name in DRAWN_LINKS:
        spec = getattr(section, name)
        if isinstance(spec, DrawnLinkSpec):
            found, update[name], links[name] = _read_one(name, spec, base_dir, accuracy)
            problems += found
    section = section.model_copy(update=update)
    if problems or not links:
        return problems, section, {}
    reason = four_bar_problem(link_lengths(section, links), section.section.boss_outer_radius,
                              links)
    return ([((), reason)] if reason else []), section, links


def link_lengths(section, links: dict) -> tuple[float, float, float, float]:
    """The links' pin-to-pin lengths a, b, c, d [m]: a drawn link's from its pins.

    Parameters
    ----------
    section : LinkageSection
        The validated section.
    links : dict of str to DrawnLink
        The drawn links by name.

    Returns
    -------
    tuple of float
        Crank, coupler, rocker and frame [m].
    """
    return tuple(links[name].length if name in links else float(getattr(section, name))
                 for name in ("crank", "coupler", "rocker", "frame"))


def aged_drawn_body(link: DrawnLink, thickness: float, dry_density: float, moisture,
                    strain_x, strain_y):
    """(wet mass [kg], moment of inertia about the centre of mass [kg m^2]) of a drawn
    link swollen by (1 + eps_x) along it and (1 + eps_y) across it (module docstring).

    Parameters
    ----------
    link : fickcam.drawing.parts.DrawnLink
        The dry link in its frame [m].
    thickness : float
        Its dry thickness [m].
    dry_density : float
        Its dry density [kg/m^3].
    moisture, strain_x, strain_y : float or array_like
        Its mean moisture M [weight %] and free strains along and across it [-].

    Returns
    -------
    tuple of numpy.ndarray
        The wet mass [kg] and moment of inertia [kg m^2].
    """
    planform = link.planform
    dry = planform.mass_properties(thickness, dry_density)
    ixx, iyy, _ = planform.second_moments()
    mass = wet_mass(dry.mass, np.asarray(moisture, float))
    sx, sy = 1.0 + np.asarray(strain_x, float), 1.0 + np.asarray(strain_y, float)
    return mass, mass * (iyy * sx ** 2 + ixx * sy ** 2) / planform.area


def aged_drawn_length(link: DrawnLink, history, strain_x) -> np.ndarray:
    """A drawn link's aged pin-to-pin length [m] at each ageing time: the distance between
    its displaced pin centres (:func:`fickcam.elastic.displacement.field_pin_shifts` on the
    plane model's own mesh, graded toward the drawn corners), the
    mean strain's L (1 + eps_x) plus the shift of its moisture field's unevenness over the
    drawn planform (the plane model's mid-plane field through the thickness with the exact
    sheet); L (1 + eps_x) where the history holds no field (the as-designed state, a state
    given directly).

    Parameters
    ----------
    link : fickcam.drawing.parts.DrawnLink
        The dry link in its frame [m].
    history : fickcam.simulation.parts.PartHistory
        Its ageing: the diffusion result with its fields and the sheet [weight %], the
        moisture expansion along and across it [1/weight %] in its state.
    strain_x : array_like
        The free strain along it of its mean moisture and temperature [-], (times,).

    Returns
    -------
    numpy.ndarray
        The aged lengths [m], (times,).
    """
    result = history.diffusion
    if getattr(result, "fields", None) is None or history.sheet is None:
        return link.length * (1.0 + np.asarray(strain_x, float))
    # imported here: scikit-fem and scipy's interpolation, which only a drawn link's run needs
    from ..elastic import displacement
    from ..elastic.swelling import plane_nodal_moisture

    moisture, expansion, stiffness = displacement.field_inputs(history, link.planform)
    nodal = plane_nodal_moisture(result, history.part.geometry.thickness, history.sheet)
    if nodal is None:  # a model without its own mesh: the field read on a mesh of the drawing
        shift = displacement.uneven_pin_shifts(link.planform, link.pins, moisture, expansion,
                                               link.planform.extent() / MESH_ROWS,
                                               stiffness=stiffness)
    else:
        shift = displacement.field_pin_shifts(nodal, link.planform, link.pins, expansion,
                                              stiffness=stiffness)
    return displacement.aged_pin_distance(link.length, strain_x, shift)


def in_plane_half_size(link: DrawnLink) -> float:
    """A drawn link's in-plane half-size [m]: its planform's area over its perimeter (every
    edge exposed, the holes' too), the half-width of a long strip, the size whose early
    uptake through the edges is the planform's (the surface-to-volume ratio of Crank,
    The Mathematics of Diffusion, 2nd ed., Oxford 1975, eq. 4.20 for a plate): a thin
    web between heavy bosses counts for what it is, not for the section's width.

    Parameters
    ----------
    link : fickcam.drawing.parts.DrawnLink
        The link in its frame [m].

    Returns
    -------
    float
        A / P [m].
    """
    return link.planform.area / link.planform.perimeter


def centre_fraction(link: DrawnLink) -> float:
    """A drawn link's centre of mass along it, as a fraction of its length [-].

    Parameters
    ----------
    link : fickcam.drawing.parts.DrawnLink
        The link in its frame [m].

    Returns
    -------
    float
        x_c / L.
    """
    return float(link.planform.centroid[0] / link.length)


def describe_link(link: DrawnLink, thickness: float, density: float) -> str:
    """``drawn, L mm pin to pin, M g, centre of mass at F of its length`` (dry).

    Parameters
    ----------
    link : fickcam.drawing.parts.DrawnLink
        The link in its frame [m].
    thickness : float
        Its thickness [m].
    density : float
        Its dry density [kg/m^3].

    Returns
    -------
    str
        The line: the length to the micrometre, mass to four significant digits.
    """
    mass = link.planform.mass_properties(thickness, density)
    return (f"drawn, {link.length * 1e3:.3f} mm pin to pin, {mass.mass * 1e3:.4g} g (dry), "
            f"centre of mass at {centre_fraction(link):.4f} of its length")
