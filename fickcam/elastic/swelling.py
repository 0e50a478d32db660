"""Hygrothermal (swelling) stress of a free part at each ageing time.

The moisture field of the diffusion engine on the level of the thickness nearest the
mid-plane (``_nodal_moisture``), carried through the thickness with the exact sheet of the
same exposure as the product of the planform's and the sheet's unaccomplished fractions
(``thickness``; Crank 1975 §5.3), makes the free strain eps* = alpha dT + beta (M - M0)
along the ply axes (Chamis, Simplified composite micromechanics equations for
hygral, thermal and mechanical properties, NASA TM-83320, 1983; Singh & Sanyal 2017,
IJIRSET 6(3), eqs. 5-6). The plate's thickness-mean free strain is the initial strain of
the plane-stress model (``fem``); each depth's stress is then the stiffness times the
in-plane strain less that depth's free strain (``stress_at_time``): the faces swell
before the mid-plane. The part is free: three statically determinate supports stop its
rigid motion and carry no load, since the eigenstrain load is self-equilibrated
(Timoshenko & Goodier 1970 sec. 150: a free body under a uniform free strain is
stress-free). Stiffness and strengths follow the local moisture: each element's matrix
retention P/P0 from its own thickness-mean moisture (the wet skin is softer than the dry
core). Results per time: the largest tensile and compressive in-plane principal stress
and the largest Tsai-Wu index (``strength``) over the part and its depths; a
quasi-isotropic laminate is checked ply by ply (0, 45, 90, -45 deg plies at the laminate
strain, classical lamination theory, Jones 1999 sec. 4.3), so the moisture and thermal
mismatch between plies counts. Not modelled: a shaft fit (the part is free), bending
(the profile is symmetric), the free-edge boundary layer of 3-D elasticity within about
one thickness of an edge.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from ..materials.hygrothermal import free_strain
from .fem import PlaneElasticity, principal_stresses, stiffness_matrix
from .strength import ply_strengths, tsai_wu_index
from .thickness import SheetProfile, planform_accomplished_fraction, product_moisture
from .mesh import disc_plate
from .nodal import NodalField
from ..materials.hygrothermal import secant_thermal_factor
from ..materials.state import wet_tg_and_retention
from .mesh import planform_mesh

ROWS = 100        # mesh spacing = planform size / ROWS at the outline
GROWTH = 0.1      # row-to-row growth inward
QI_PLIES = np.radians([0.0, 45.0, 90.0, -45.0])


def _part_plate(geometry):
    """The planform to mesh for a diffusion geometry (a disc about its own centre), or None
    (a part that takes up no moisture, a steel frame: no geometry)."""

    if geometry is None:
        return None
    if geometry.axisymmetric:
        return disc_plate(geometry.outer_radius, geometry.thickness, geometry.inner_radius)
    return geometry if geometry.planform else None


def plate_size(plate) -> float:
    """Largest planform dimension.

    Parameters
    ----------
    plate : CamPlate or LinkBar
        The planform.

    Returns
    -------
    float
        The dimension [m].
    """
    return float(max(plate.extent()))


def mid_plane_cells(coordinates: dict, thickness: float) -> np.ndarray:
    """Which stored cells lie on the level of the thickness nearest the mid-plane (both
    levels where two are equally near): the cells of an in-plane field (one level) or of
    an (r, z) or 3-D field.

    Parameters
    ----------
    coordinates : dict
        The engine's ``cell_coordinates`` [m]; without ``z`` every cell counts.
    thickness : float
        The part's thickness [m].

    Returns
    -------
    numpy.ndarray
        Boolean mask over the cells.
    """
    if "z" not in coordinates:
        return np.ones(len(coordinates["x"]), bool)
    distance = np.abs(np.asarray(coordinates["z"], float) - 0.5 * thickness)
    return distance <= distance.min() + 1e-9 * thickness


def _level_depth(coordinates: dict, thickness: float) -> float:
    """Depth below the nearer face [m] of the level ``mid_plane_cells`` picks."""
    if "z" not in coordinates:
        return 0.5 * thickness
    z = np.asarray(coordinates["z"], float)[mid_plane_cells(coordinates, thickness)]
    return float(np.mean(np.minimum(z, thickness - z)))


def _nodal_moisture(result, geometry, points, surface, outline=None) -> np.ndarray:
    """(times, nodes) moisture [weight %] at the mesh vertices ``points`` [m] on the level
    of the engine's stored field nearest the mid-plane (``mid_plane_cells``), with the
    surface value ``surface`` (times,) on the exposed outline: a disc's radial profile
    between its rim and bore; a plate's field linearly interpolated on the triangles of
    its cell points and the vertices ``outline`` (indices into ``points``: the mesh's
    boundary, where the part is exposed)."""
    # deferred: keeps scipy.interpolate off the start-up path
    from scipy.interpolate import LinearNDInterpolator, NearestNDInterpolator

    coords = result.cell_coordinates
    level = mid_plane_cells(coords, geometry.thickness)
    fields = np.asarray(result.fields, float)[:, level]
    surface = np.asarray(surface, float)
    if geometry.axisymmetric:
        radii, inverse = np.unique(np.round(coords["x"][level], 12), return_inverse=True)
        profile = np.stack([np.bincount(inverse, f) / np.bincount(inverse) for f in fields])
        ends = [geometry.inner_radius] if geometry.inner_radius > 0 else []
        radii = np.concatenate([ends, radii, [geometry.outer_radius]])
        r = np.hypot(*points.T)
        return np.stack([np.interp(r, radii, np.concatenate([[s] * len(ends), p, [s]]))
                         for p, s in zip(profile, surface)])
    source = np.column_stack([coords["x"][level], coords["y"][level]])
    if outline is not None:
        source = np.vstack([source, points[outline]])
        fields = np.hstack([fields, np.repeat(surface[:, None], len(outline), axis=1)])
    linear = LinearNDInterpolator(source, fields.T)(points).T          # (times, nodes)
    nearest = NearestNDInterpolator(source, fields.T)(points).T
    return np.where(np.isfinite(linear), linear, nearest)


def through_thickness(in_plane, depth: float, sheet: SheetProfile | None
                      ) -> tuple[np.ndarray, np.ndarray]:
    """(layers, mean): the plate's moisture [weight %] at the sheet's depths, face first,
    (times, depths, nodes), and its thickness mean (times, nodes), from the in-plane field
    ``in_plane`` (times, nodes) on the level ``depth`` [m] below a face, as the product
    of the planform's and the sheet's unaccomplished fractions (``thickness``); without
    a sheet, the in-plane field alone (one layer).

    Parameters
    ----------
    in_plane : numpy.ndarray
        Moisture on the level ``depth``, shape (times, nodes) [weight %].
    depth : float
        Depth of that level below a face [m].
    sheet : SheetProfile or None
        The exact sheet of the part's thickness.

    Returns
    -------
    layers : numpy.ndarray
        Moisture at the sheet's depths, shape (times, depths, nodes) [weight %].
    mean : numpy.ndarray
        Thickness mean, shape (times, nodes) [weight %].
    """
    if sheet is None:
        return in_plane[:, None, :], in_plane
    surface = sheet.surface[:, None]
    w = planform_accomplished_fraction(in_plane, sheet.at(depth)[:, None], surface)
    layers = product_moisture(w[:, None, :], sheet.moisture[:, :, None], surface[:, :, None])
    return layers, product_moisture(w, sheet.mean[:, None], surface)


def _thermal_factor(material, wet_tg, temperature, reference):
    """The secant factor on the thermal expansion (as ``materials.state``)."""

    tgd = material.dry_glass_transition_temperature
    if tgd is None or material.kind == "metal":
        return np.ones_like(np.asarray(wet_tg, float))
    return secant_thermal_factor(wet_tg, temperature, tgd, reference)


def _local_properties(material, moisture, temperature, reference):
    """(laminate props, ply props, retention) at each element's moisture."""

    _, wet_tg, retention = wet_tg_and_retention(material, moisture, temperature, reference)
    factor = _thermal_factor(material, wet_tg, temperature, reference)
    laminate = material.ply_properties(retention, factor)
    ply = (dataclasses.replace(material, layup="unidirectional").ply_properties(retention, factor)
           if material.layup == "quasi_isotropic" else laminate)
    return laminate, ply, retention


def ply_free_strains(props, moisture_change, temperature_change) -> tuple:
    """(exx, eyy, gxy) = alpha dT + beta dM along the axes of ``props`` (arrays broadcast;
    ``materials.hygrothermal.free_strain`` along each axis).

    Parameters
    ----------
    props : dict of str to array_like
        Ply properties (:meth:`fickcam.materials.material.Material.ply_properties`): alpha11,
        alpha22 [1/K], beta11, beta22 [1/weight %].
    moisture_change : float or array_like
        dM from the strain-free moisture [weight %].
    temperature_change : float or array_like
        dT from the strain-free temperature [K].

    Returns
    -------
    tuple of numpy.ndarray
        The free strains exx, eyy and gxy [-] (gxy = 0 along the property axes).
    """
    return (free_strain(props["alpha11"], props["beta11"], temperature_change, 0.0,
                        moisture_change, 0.0),
            free_strain(props["alpha22"], props["beta22"], temperature_change, 0.0,
                        moisture_change, 0.0),
            0.0 * moisture_change)


def to_ply_axes(strain, angle) -> tuple:
    """Engineering strains (xx, yy, xy) in axes turned by ``angle`` (Jones 1999 eq. 2.80).

    Parameters
    ----------
    strain : tuple of array_like
        exx, eyy, gxy [-] in the x, y axes.
    angle : float or array_like
        The turn of the new axes from x, counter-clockwise [rad].

    Returns
    -------
    tuple of numpy.ndarray
        The engineering strains [-] in the turned axes.
    """
    exx, eyy, gxy = strain
    c, s = np.cos(angle), np.sin(angle)
    return (c * c * exx + s * s * eyy + c * s * gxy,
            s * s * exx + c * c * eyy - c * s * gxy,
            2 * c * s * (eyy - exx) + (c * c - s * s) * gxy)


def _stiffness(props) -> np.ndarray:
    return stiffness_matrix(props["e11"], props["e22"], props["g12"], props["nu12"])


def _columns(props: dict) -> dict:
    """Per-element property arrays as (elements, 1) columns (scalars unchanged)."""
    return {k: np.asarray(v)[:, None] if np.ndim(v) else v for k, v in props.items()}


def _ply_angles(material):
    return QI_PLIES if material.layup == "quasi_isotropic" and material.fiber is not None else [0.0]


def stress_at_time(pe: PlaneElasticity, material, layers, mean, temperature, reference,
                   initial_moisture):
    """The free plate's swelling stress at one ageing time.

    A symmetric free plate keeps its sections plane and does not bend: its in-plane
    strain is that of the plane-stress model under the thickness-mean free strain, and at
    each depth sigma = Q (eps - eps*(M(z))) (classical lamination theory with the free
    strain varying through the thickness, Jones, Mechanics of Composite Materials, 2nd
    ed., Taylor & Francis 1999, sec. 4.3; Timoshenko & Goodier, Theory of Elasticity, 3rd
    ed., McGraw-Hill 1970, sec. 150): the faces go into compression while they swell ahead
    of the mid-plane. Stiffness and strengths per element at its thickness-mean moisture.

    Parameters
    ----------
    pe : PlaneElasticity
        The planform's plane-stress model.
    material : fickcam.materials.Material
        The part's material.
    layers : array_like
        Moisture at the mesh vertices [weight %], (depths, nodes), the face first.
    mean : array_like
        Thickness-mean moisture at the mesh vertices [weight %], (nodes,).
    temperature, reference : float
        Temperature and the stress-free reference temperature [K].
    initial_moisture : float
        The stress-free (initial) moisture [weight %].

    Returns
    -------
    tuple
        (largest tensile [Pa], largest compressive principal stress [Pa], largest
        Tsai-Wu index [-], field): field per element, the principal stress of larger
        magnitude at the face (the first layer), element mean [Pa].
    """
    average = pe.nodal_at_points(mean)                       # (elements, points)
    laminate, ply, retention = _local_properties(material, average.mean(axis=1), temperature,
                                                reference)
    q = _stiffness(laminate)                                  # (3, 3, elements)
    lam, d_t = _columns(laminate), temperature - reference
    star = ply_free_strains(lam, average - initial_moisture, d_t)
    u = pe.factorise(pe.stiffness(q), pe.statically_determinate_support())(pe.eigenstrain_load(q, star))
    strain = pe.strain(u)
    strengths = ply_strengths(material, retention)
    columns = None if strengths is None else _columns(strengths)
    q_ply, plies = _stiffness(ply), _columns(ply)
    tensile, compressive, index, field = -np.inf, np.inf, np.nan, None
    for layer in np.asarray(layers, float):
        change = pe.nodal_at_points(layer) - initial_moisture
        mechanical = np.stack([e - s for e, s in zip(strain, ply_free_strains(lam, change, d_t))])
        largest, smallest = principal_stresses(np.einsum("ije,jeq->ieq", q, mechanical))
        tensile, compressive = max(tensile, largest.max()), min(compressive, smallest.min())
        if field is None:
            field = np.where(np.abs(largest) >= np.abs(smallest), largest, smallest).mean(axis=1)
        if columns is None:
            continue
        for angle in _ply_angles(material):
            ply_strain = np.stack([e - s for e, s in zip(to_ply_axes(strain, angle),
                                                         ply_free_strains(plies, change, d_t))])
            s1, s2, s12 = np.einsum("ije,jeq->ieq", q_ply, ply_strain)
            index = np.nanmax([index, np.max(tsai_wu_index(s1, s2, s12, columns))])
    return float(tensile), float(compressive), float(index), field


def plate_moisture(result, geometry, points, surface, sheet: SheetProfile | None = None,
                   outline=None) -> tuple[np.ndarray, np.ndarray]:
    """The part's moisture at the mesh vertices through its thickness.

    Parameters
    ----------
    result : fickcam.diffusion.DiffusionResult
        The part's diffusion result with its stored ``fields``.
    geometry : fickcam.diffusion.Geometry
        The part's diffusion geometry (a ``Disc``, ``CamPlate`` or ``LinkBar``).
    points : numpy.ndarray
        Mesh vertices [m], (nodes, 2).
    surface : array_like
        Surface value [weight %] per time, (times,): a disc's rim and bore (the sheet's
        face value replaces it when ``sheet`` is given).
    sheet : SheetProfile, optional
        The exact sheet of the part's thickness under its exposure.
    outline : numpy.ndarray, optional
        Indices of the vertices on the exposed outline (the mesh's boundary nodes).

    Returns
    -------
    tuple of numpy.ndarray
        (layers, mean) [weight %]: (times, depths, nodes) at the sheet's depths, face
        first, and the thickness mean (times, nodes) (``through_thickness``).
    """
    surface = np.asarray(surface, float) if sheet is None else sheet.surface
    in_plane = _nodal_moisture(result, geometry, points, surface, outline)
    depth = _level_depth(result.cell_coordinates, geometry.thickness)
    return through_thickness(in_plane, depth, sheet)


def plane_nodal_moisture(result, thickness: float, sheet: SheetProfile):
    """The plane model's thickness-mean moisture at the nodes of its own triangle mesh
    (``result.planform``): the mid-thickness level's P1 field, the outline's nodes at the
    sheet's face value, carried through the thickness with the exact sheet
    (:func:`through_thickness`); None where the result keeps no such mesh (another model).

    Parameters
    ----------
    result : fickcam.diffusion.DiffusionResult
        The part's diffusion result, with its ``fields`` [weight %] and ``planform``.
    thickness : float
        The plate's thickness [m].
    sheet : SheetProfile
        The exact sheet of its thickness under its exposure [weight %].

    Returns
    -------
    fickcam.elastic.nodal.NodalField or None
        The moisture [weight %] at the mesh's nodes [m], (times, nodes).
    """
    mesh = getattr(result, "planform", None)
    if mesh is None or result.fields is None:
        return None
    held = np.asarray(mesh.on_outline, bool)
    fields = np.asarray(result.fields, float)
    level = mid_plane_cells(result.cell_coordinates, thickness)
    if fields[:, level].shape[1] != np.count_nonzero(~held):
        raise ValueError("the plane model's stored field does not match its mesh's free nodes")
    in_plane = np.empty((len(fields), len(mesh.points)))
    in_plane[:, ~held], in_plane[:, held] = fields[:, level], sheet.surface[:, None]
    _, mean = through_thickness(in_plane, _level_depth(result.cell_coordinates, thickness), sheet)
    return NodalField(np.asarray(mesh.points, float), np.asarray(mesh.triangles), mean)


def swelling_history(geometry, material, result, state: dict, temperature, reference,
                     initial_moisture, valid, sheet: SheetProfile | None = None
                     ) -> dict[str, np.ndarray]:
    """swelling_stress_tensile, swelling_stress_compressive, failure_index over ageing times
    for one part (NaN where the part is not valid or has no field), and ``field`` /
    ``points``: the face stress field (element centroids, m) at the worst time (largest
    failure index, else largest compression); ``sheet``: the exact sheet of the part's
    thickness under its exposure (``plate_moisture``; None: the in-plane field alone).

    Parameters
    ----------
    geometry : Geometry
        The part's diffusion geometry (dimensions [m]).
    material : Material
        Its material.
    result : DiffusionResult or None
        Its diffusion result, with moisture fields.
    state : dict
        Its material state over ageing times (moduli [Pa], expansion coefficients).
    temperature : numpy.ndarray
        Temperature at the ageing times [K].
    reference : float
        Reference (stress-free) temperature [K].
    initial_moisture : float
        Stress-free moisture [weight %].
    valid : array_like of bool
        Which ageing times to solve.
    sheet : SheetProfile, optional
        The exact sheet of the part's thickness.

    Returns
    -------
    dict
        swelling_stress_tensile/compressive [Pa] and failure_index [-] over ageing times,
        and ``field`` [Pa] / ``points`` [m] of the worst time.
    """

    n = len(temperature)
    out = {name: np.full(n, np.nan) for name in
           ("swelling_stress_tensile", "swelling_stress_compressive", "failure_index")}
    plate = _part_plate(geometry)
    if plate is None or result is None or getattr(result, "fields", None) is None:
        return out
    mesh = planform_mesh(plate, plate_size(plate) / ROWS, GROWTH)
    pe = PlaneElasticity(mesh.points, mesh.triangles, geometry.thickness, order=2)
    layers, mean = plate_moisture(result, geometry, mesh.points,
                                  state.get("equilibrium_moisture_content", np.zeros(n)), sheet,
                                  pe.mesh.boundary_nodes())
    fields = {}
    for k in np.flatnonzero(np.asarray(valid, bool)):
        *values, fields[k] = stress_at_time(pe, material, layers[k], mean[k],
                                            float(temperature[k]), reference, initial_moisture)
        for name, value in zip(out, values):
            out[name][k] = value
    if fields:
        worst = out["failure_index"] if np.isfinite(out["failure_index"]).any() else \
            -out["swelling_stress_compressive"]
        out["field"] = fields[int(np.nanargmax(worst))]
        out["points"] = pe.mesh.p[:, pe.mesh.t].mean(axis=1).T
    return out
