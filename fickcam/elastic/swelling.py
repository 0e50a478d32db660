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
between plies counts. Not modelled: the through-thickness gradient of a plate (its
faces swell before its mid-plane) and a shaft fit.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from .fem import PlaneElasticity, principal_stresses, reduced_stiffness
from .strength import ply_strengths, tsai_wu_index

ROWS = 150        # mesh spacing = planform size / ROWS at the outline
GROWTH = 0.1      # row-to-row growth inward
QI_PLIES = np.radians([0.0, 45.0, 90.0, -45.0])


def part_plate(geometry):
    """The planform to mesh for a diffusion geometry (a disc about its own centre), or None."""
    from ..diffusion.geometry import CamPlate, Disc, LinkBar
    from .mesh import disc_plate

    if isinstance(geometry, Disc):
        return disc_plate(geometry.outer_radius, geometry.thickness, geometry.inner_radius)
    if isinstance(geometry, (CamPlate, LinkBar)):
        return geometry
    return None


def plate_size(plate) -> float:
    """Largest planform dimension (m)."""
    from ..diffusion.geometry import CamPlate

    if isinstance(plate, CamPlate):
        return float(max(np.ptp(plate.profile_x), np.ptp(plate.profile_y)))
    return float(plate.length + 2 * plate.boss_outer_radius)


def nodal_moisture(result, geometry, points, surface) -> np.ndarray:
    """(times, nodes) moisture (weight %) at the mesh vertices from the engine's stored field:
    linear interpolation of the in-plane field (nearest value outside its hull); a disc's
    radial profile averaged over z with the surface value at the rim."""
    from scipy.interpolate import LinearNDInterpolator, NearestNDInterpolator

    from ..diffusion.geometry import Disc

    fields = np.asarray(result.fields, float)
    coords = result.cell_coordinates
    if isinstance(geometry, Disc):
        radii, inverse = np.unique(np.round(coords["x"], 12), return_inverse=True)
        profile = np.stack([np.bincount(inverse, f) / np.bincount(inverse) for f in fields])
        r = np.hypot(*points.T)
        return np.stack([np.interp(r, np.append(radii, geometry.outer_radius), np.append(p, s))
                         for p, s in zip(profile, surface)])
    source = np.column_stack([coords["x"], coords["y"]])
    out = []
    for values in fields:
        linear = LinearNDInterpolator(source, values)(points)
        nearest = NearestNDInterpolator(source, values)(points)
        out.append(np.where(np.isfinite(linear), linear, nearest))
    return np.stack(out)


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


def stress_at_time(pe: PlaneElasticity, material, moisture_nodes, temperature, reference,
                   initial_moisture):
    """(largest tensile, largest compressive principal stress, largest failure index) of the
    free part with the nodal moisture field at one ageing time."""
    moisture = pe.nodal_at_points(moisture_nodes)             # (elements, points)
    element_moisture = moisture.mean(axis=1)
    laminate, ply, retention = local_properties(material, element_moisture, temperature, reference)
    q = _stiffness(laminate)                                  # (3, 3, elements)
    d_m, d_t = moisture - initial_moisture, temperature - reference
    star = free_strain({k: np.asarray(v)[:, None] if np.ndim(v) else v for k, v in laminate.items()},
                       d_m, d_t)
    u = pe.factorise(pe.stiffness(q), pe.statically_determinate_support())(pe.eigenstrain_load(q, star))
    largest, smallest = principal_stresses(pe.stress(u, q, star))
    strengths = ply_strengths(material, retention)
    index = np.nan
    if strengths is not None:
        strain = pe.strain(u)
        ply_q = _stiffness(ply)[..., None]
        ply_star = free_strain({k: np.asarray(v)[:, None] if np.ndim(v) else v for k, v in ply.items()},
                               d_m, d_t)
        columns = {k: np.asarray(v)[:, None] for k, v in strengths.items()}
        angles = QI_PLIES if material.layup == "quasi_isotropic" and material.fiber is not None else [0.0]
        for angle in angles:
            mechanical = [e - s for e, s in zip(to_ply_axes(strain, angle), ply_star)]
            s1, s2, s12 = (sum(ply_q[i, j] * mechanical[j] for j in range(3)) for i in range(3))
            index = np.nanmax([index, np.max(tsai_wu_index(s1, s2, s12, columns))])
    return float(largest.max()), float(smallest.min()), float(index)


def swelling_history(geometry, material, result, state: dict, temperature, reference,
                     initial_moisture, valid) -> dict[str, np.ndarray]:
    """swelling_stress_tensile, swelling_stress_compressive, failure_index over ageing times
    for one part (NaN where the part is not valid or has no field)."""
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
    for k in np.flatnonzero(np.asarray(valid, bool)):
        values = stress_at_time(pe, material, moisture[k], float(temperature[k]), reference,
                                initial_moisture)
        for name, value in zip(out, values):
            out[name][k] = value
    return out
