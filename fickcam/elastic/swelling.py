"""Hygrothermal (swelling) stress of a free part at each ageing time.

The moisture field M(x, y) of the diffusion engine (its in-plane field: the mid-thickness
plane of a plate or link, the thickness mean of a disc) makes the free strain
eps* = alpha dT + beta (M - M0) along the ply axes (Chamis 1983; seeds/000 eq. 5-6), an
initial strain in the plane-stress model (``fem``). The part is free: three statically
determinate supports stop its rigid motion and carry no load, since the eigenstrain load
is self-equilibrated (Timoshenko & Goodier 1970 sec. 150: a free body under a uniform
free strain is stress-free). Stiffness and strengths follow the local moisture: each
element's matrix retention P/P0 from its own moisture (the wet skin is softer than the
dry core). Results per time: the largest tensile and compressive in-plane principal
stress and the largest Tsai-Wu index (``strength``) over the part; a quasi-isotropic
laminate is checked ply by ply (0, 45, 90, -45 deg plies at the laminate strain,
classical lamination theory, Jones 1999 sec. 4.3), so the moisture and thermal mismatch
between plies counts. Through the thickness the exact sheet profile of the same exposure
is added (``stress_at_time``): the faces swell before the mid-plane. Not modelled: a
shaft fit (the part is free), bending (the profile is symmetric).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from .fem import PlaneElasticity, principal_stresses, reduced_stiffness
from .strength import ply_strengths, tsai_wu_index

ROWS = 100        # mesh spacing = planform size / ROWS at the outline
GROWTH = 0.1      # row-to-row growth inward
QI_PLIES = np.radians([0.0, 45.0, 90.0, -45.0])


def part_plate(geometry):
    """The planform to mesh for a diffusion geometry (a disc about its own centre), or None."""
    from ..diffusion.problem.geometry import CamPlate, Disc, LinkBar
    from .mesh import disc_plate

    if isinstance(geometry, Disc):
        return disc_plate(geometry.outer_radius, geometry.thickness, geometry.inner_radius)
    if isinstance(geometry, (CamPlate, LinkBar)):
        return geometry
    return None


def plate_size(plate) -> float:
    """Largest planform dimension (m)."""
    from ..diffusion.problem.geometry import CamPlate

    if isinstance(plate, CamPlate):
        return float(max(np.ptp(plate.profile_x), np.ptp(plate.profile_y)))
    return float(plate.length + 2 * plate.boss_outer_radius)


def nodal_moisture(result, geometry, points, surface) -> np.ndarray:
    """(times, nodes) moisture (weight %) at the mesh vertices from the engine's stored field:
    linear interpolation of the in-plane field (nearest value outside its hull); a disc's
    radial profile averaged over z with the surface value at the rim."""
    from scipy.interpolate import LinearNDInterpolator, NearestNDInterpolator

    from ..diffusion.problem.geometry import Disc

    fields = np.asarray(result.fields, float)
    coords = result.cell_coordinates
    if isinstance(geometry, Disc):
        radii, inverse = np.unique(np.round(coords["x"], 12), return_inverse=True)
        profile = np.stack([np.bincount(inverse, f) / np.bincount(inverse) for f in fields])
        r = np.hypot(*points.T)
        return np.stack([np.interp(r, np.append(radii, geometry.outer_radius), np.append(p, s))
                         for p, s in zip(profile, surface)])
    source = np.column_stack([coords["x"], coords["y"]])
    linear = LinearNDInterpolator(source, fields.T)(points).T          # (times, nodes)
    nearest = NearestNDInterpolator(source, fields.T)(points).T
    return np.where(np.isfinite(linear), linear, nearest)


def _thermal_factor(material, wet_tg, temperature, reference):
    """The secant factor on the thermal expansion (as ``materials.state``)."""
    from ..materials.hygrothermal import secant_thermal_factor

    tgd = material.dry_glass_transition_temperature
    if tgd is None or material.kind == "metal":
        return np.ones_like(np.asarray(wet_tg, float))
    return secant_thermal_factor(wet_tg, temperature, tgd, reference)


def local_properties(material, moisture, temperature, reference):
    """(laminate props, ply props, retention) at each element's moisture."""
    from ..materials.state import wet_tg_and_retention

    _, wet_tg, retention = wet_tg_and_retention(material, moisture, temperature, reference)
    factor = _thermal_factor(material, wet_tg, temperature, reference)
    laminate = material.ply_properties(retention, factor)
    ply = (dataclasses.replace(material, layup="unidirectional").ply_properties(retention, factor)
           if material.layup == "quasi_isotropic" else laminate)
    return laminate, ply, retention


def free_strain(props, moisture_change, temperature_change) -> tuple:
    """(exx, eyy, gxy) = alpha dT + beta dM along the axes of ``props`` (arrays broadcast)."""
    return (props["alpha11"] * temperature_change + props["beta11"] * moisture_change,
            props["alpha22"] * temperature_change + props["beta22"] * moisture_change,
            0.0 * moisture_change)


def to_ply_axes(strain, angle) -> tuple:
    """Engineering strains (xx, yy, xy) in axes turned by ``angle`` (Jones 1999 eq. 2.80)."""
    exx, eyy, gxy = strain
    c, s = np.cos(angle), np.sin(angle)
    return (c * c * exx + s * s * eyy + c * s * gxy,
            s * s * exx + c * c * eyy - c * s * gxy,
            2 * c * s * (eyy - exx) + (c * c - s * s) * gxy)


def _stiffness(props) -> np.ndarray:
    return reduced_stiffness(props["e11"], props["e22"], props["g12"], props["nu12"])


def _columns(props: dict) -> dict:
    """Per-element property arrays as (elements, 1) columns (scalars unchanged)."""
    return {k: np.asarray(v)[:, None] if np.ndim(v) else v for k, v in props.items()}


def _ply_angles(material):
    return QI_PLIES if material.layup == "quasi_isotropic" and material.fiber is not None else [0.0]


def stress_at_time(pe: PlaneElasticity, material, moisture_nodes, temperature, reference,
                   initial_moisture, depth_profile=None):
    """(largest tensile, largest compressive principal stress, largest failure index, field)
    of the free part with the nodal moisture field at one ageing time; field: per element,
    the principal stress of larger magnitude at the face (the first depth), element mean.

    ``depth_profile`` (optional): moisture of the exposed sheet at depths from a face to the
    mid-plane (face first). Its deviation dz(z) = M(z) - M(mid) is added to the in-plane
    field, M(x, y, z) = M_plane(x, y) + dz(z); a symmetric free plate keeps its sections
    plane, so its total strain gains the uniform beta (mean dz) and at each depth
    sigma = Q (eps_total - eps*(M)) (classical lamination theory with the free strain
    varying through the thickness, Jones 1999 sec. 4.3; the faces go into compression
    while they swell ahead of the mid-plane)."""
    moisture = pe.nodal_at_points(moisture_nodes)             # (elements, points)
    laminate, ply, retention = local_properties(material, moisture.mean(axis=1), temperature,
                                                reference)
    q = _stiffness(laminate)                                  # (3, 3, elements)
    lam, d_t = _columns(laminate), temperature - reference
    star = free_strain(lam, moisture - initial_moisture, d_t)
    u = pe.factorise(pe.stiffness(q), pe.statically_determinate_support())(pe.eigenstrain_load(q, star))
    profile = np.zeros(1) if depth_profile is None else np.asarray(depth_profile, float)
    deviation = profile - profile[-1]
    strain = [e + s for e, s in zip(pe.strain(u), free_strain(lam, np.mean(deviation), 0.0))]
    strengths = ply_strengths(material, retention)
    columns = None if strengths is None else _columns(strengths)
    q_ply, plies = _stiffness(ply), _columns(ply)
    tensile, compressive, index, field = -np.inf, np.inf, np.nan, None
    for dz in deviation:
        change = moisture + dz - initial_moisture
        mechanical = np.stack([e - s for e, s in zip(strain, free_strain(lam, change, d_t))])
        largest, smallest = principal_stresses(np.einsum("ije,jeq->ieq", q, mechanical))
        tensile, compressive = max(tensile, largest.max()), min(compressive, smallest.min())
        if field is None:
            field = np.where(np.abs(largest) >= np.abs(smallest), largest, smallest).mean(axis=1)
        if columns is None:
            continue
        for angle in _ply_angles(material):
            ply_strain = np.stack([e - s for e, s in zip(to_ply_axes(strain, angle),
                                                         free_strain(plies, change, d_t))])
            s1, s2, s12 = np.einsum("ije,jeq->ieq", q_ply, ply_strain)
            index = np.nanmax([index, np.max(tsai_wu_index(s1, s2, s12, columns))])
    return float(tensile), float(compressive), float(index), field


def swelling_history(geometry, material, result, state: dict, temperature, reference,
                     initial_moisture, valid, depth_profiles=None) -> dict[str, np.ndarray]:
    """swelling_stress_tensile, swelling_stress_compressive, failure_index over ageing times
    for one part (NaN where the part is not valid or has no field), and ``field`` /
    ``points``: the face stress field (element centroids, m) at the worst time (largest
    failure index, else largest compression); ``depth_profiles`` (times, depths): the
    sheet's moisture from a face to the mid-plane."""
    from .mesh import planform_mesh

    n = len(temperature)
    out = {name: np.full(n, np.nan) for name in
           ("swelling_stress_tensile", "swelling_stress_compressive", "failure_index")}
    plate = part_plate(geometry)
    if plate is None or result is None or getattr(result, "fields", None) is None:
        return out
    mesh = planform_mesh(plate, plate_size(plate) / ROWS, GROWTH)
    pe = PlaneElasticity(mesh.points, mesh.triangles, geometry.thickness, order=2)
    moisture = nodal_moisture(result, geometry, mesh.points,
                              state.get("equilibrium_moisture_content", np.zeros(n)))
    fields = {}
    for k in np.flatnonzero(np.asarray(valid, bool)):
        *values, fields[k] = stress_at_time(
            pe, material, moisture[k], float(temperature[k]), reference, initial_moisture,
            None if depth_profiles is None else depth_profiles[k])
        for name, value in zip(out, values):
            out[name][k] = value
    if fields:
        worst = out["failure_index"] if np.isfinite(out["failure_index"]).any() else \
            -out["swelling_stress_compressive"]
        out["field"] = fields[int(np.nanargmax(worst))]
        out["points"] = pe.mesh.p[:, pe.mesh.t].mean(axis=1).T
    return out
