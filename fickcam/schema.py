"""The one table of result variables: name → dims, units, long name.

It builds the Dataset (:mod:`fickcam.results.dataset`), checks queries
(:mod:`fickcam.results.query`) and writes the variable list in the docs
(``fickcam schema`` / :func:`markdown_table`). Physics modules return SI
arrays under these names (angles in rad, speeds in rad/s); ``scale``
converts SI to the stored unit (rad → deg, rad/s → rpm).

Every time-dependent variable of the material state and of the mechanisms
(sections ``parts``, ``cam``, ``linkage``) also has an as-designed row
``<name>_design`` (the same dims without ``time``): the value the same models
give for the design, dry at the reference temperature. ``Var.design`` turns it
on or off per variable; the rows are generated from this table
(:func:`design_name`, ``DESIGN_NOTE``). ``Var.display`` is the unit a
person reads the value in (the run summary), converted from ``units`` by pint.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

DEG = 180.0 / math.pi
RPM = 60.0 / (2.0 * math.pi)


@dataclass(frozen=True)
class Var:
    """One result variable of the schema.

    Parameters
    ----------
    dims : tuple of str
        Its dimensions (``time``, ``part``, ``cam_angle``...).
    units : str
        Its stored unit (UDUNITS spelling: ``m``, ``N m``, ``degree``, ``1``).
    long_name : str
        What it is.
    section : str
        Where it comes from: environment, parts, cam, linkage, elastic, limits or fields.
    scale : float
        Stored value / SI value [stored unit / SI unit] (e.g. 180/pi for degrees).
    design : bool, optional
        Store ``<name>_design`` too; None: yes for a time-dependent variable of the material
        state or a mechanism.
    display : str
        The unit a person reads it in (the summary); "" for the stored unit.
    error : str
        The variable holding its error estimate (same dims and unit), by which reports
        print only the digits it supports; "" for none.
    """
    dims: tuple[str, ...]
    units: str
    long_name: str
    section: str  # environment | parts | cam | linkage | elastic | limits | fields
    scale: float = 1.0  # stored value = SI value * scale
    design: bool | None = None  # store "<name>_design"; None: yes for a time-dependent
    #                             variable of the material state or a mechanism
    display: str = ""  # unit a person reads it in (summary); "" = the stored unit
    error: str = ""  # the variable holding its error estimate; "" = none

    @property
    def has_design(self) -> bool:
        """True when the result also holds the as-designed value ``<name>_design``."""
        if self.design is not None:
            return self.design
        return self.section in DESIGN_SECTIONS and "time" in self.dims


DESIGN_SECTIONS = ("parts", "cam", "linkage")
DESIGN_NOTE = ", as designed (dry, reference temperature)"

T, TP, TC, TK, TL = ("time",), ("time", "part"), ("time", "cam_angle"), ("time", "crank_angle"), ("time", "link")
CT = ("climate_time",)

VARIABLES: dict[str, Var] = {
    # environment
    "temperature": Var(T, "K", "service temperature", "environment", display="degC"),
    "relative_humidity": Var(T, "%", "relative humidity", "environment"),
    # the climate between the ageing times: mean and range over each interval of climate_time
    "climate_temperature": Var(CT, "K", "mean temperature over the interval", "environment",
                               display="degC"),
    "climate_temperature_min": Var(CT, "K", "lowest temperature in the interval", "environment",
                                   display="degC"),
    "climate_temperature_max": Var(CT, "K", "highest temperature in the interval", "environment",
                                   display="degC"),
    "climate_relative_humidity": Var(CT, "%", "mean relative humidity over the interval",
                                     "environment"),
    "climate_relative_humidity_min": Var(CT, "%", "lowest relative humidity in the interval",
                                         "environment"),
    "climate_relative_humidity_max": Var(CT, "%", "highest relative humidity in the interval",
                                         "environment"),
    # per part: moisture and material state
    "moisture_content": Var(TP, "%", "volume-mean moisture content (weight % of dry mass)", "parts"),
    "surface_moisture_content": Var(TP, "%", "moisture content of the contact-surface layer", "parts"),
    "bound_moisture_content": Var(TP, "%", "bound-water share of the moisture content (two-phase "
                                  "sorption, Carter & Kibler 1978; only with a langmuir material)",
                                  "parts", design=False),
    "equilibrium_moisture_content": Var(TP, "%", "saturation moisture at the surface, Mm(T, RH)", "parts",
                                        design=False),
    "mass": Var(TP, "kg", "part mass, m_dry (1 + M/100)", "parts", display="g"),
    "density": Var(TP, "kg m-3", "mean density of the swollen part", "parts"),
    "hygrothermal_strain": Var(TP, "1", "free hygrothermal strain, in-plane or axial", "parts"),
    "strain_longitudinal": Var(TP, "1", "free hygrothermal strain along x (fibre direction)", "parts"),
    "strain_transverse": Var(TP, "1", "free hygrothermal strain along y (in-plane transverse)", "parts"),
    "strain_through_thickness": Var(TP, "1", "free hygrothermal strain through the thickness", "parts"),
    "glass_transition_temperature": Var(TP, "K", "wet glass transition temperature", "parts",
                                        display="degC"),
    "property_retention": Var(TP, "1", "Chamis matrix property retention P/P0", "parts"),
    "longitudinal_modulus": Var(TP, "Pa", "longitudinal Young's modulus E11", "parts", display="GPa"),
    "transverse_modulus": Var(TP, "Pa", "transverse Young's modulus E22", "parts", display="GPa"),
    "shear_modulus": Var(TP, "Pa", "in-plane shear modulus G12", "parts", display="GPa"),
    "poisson_ratio": Var(TP, "1", "major Poisson ratio nu12", "parts"),
    "surface_modulus": Var(TP, "Pa", "in-plane modulus of the wet contact-surface layer", "parts",
                           display="GPa"),
    "matrix_moisture_content": Var(TP, "%", "moisture content of the matrix (Chamis)", "parts"),
    "surface_matrix_moisture_content": Var(TP, "%", "matrix moisture content of the contact-surface layer",
                                           "parts"),
    "surface_glass_transition_temperature": Var(TP, "K", "wet glass transition temperature of the "
                                                "contact-surface layer", "parts", display="degC"),
    "surface_property_retention": Var(TP, "1", "Chamis property retention of the contact-surface layer",
                                      "parts"),
    "mass_ratio": Var(TP, "1", "mass over dry mass, 1 + M/100", "parts"),
    "transverse_shear_modulus": Var(TP, "Pa", "transverse shear modulus G23", "parts", display="GPa"),
    "transverse_poisson_ratio": Var(TP, "1", "transverse Poisson ratio nu23", "parts"),
    "surface_longitudinal_modulus": Var(TP, "Pa", "E11 of the contact-surface layer", "parts", display="GPa"),
    "surface_transverse_modulus": Var(TP, "Pa", "E22 of the contact-surface layer", "parts", display="GPa"),
    "surface_shear_modulus": Var(TP, "Pa", "G12 of the contact-surface layer", "parts", display="GPa"),
    "surface_poisson_ratio": Var(TP, "1", "nu12 of the contact-surface layer", "parts"),
    "thermal_expansion_longitudinal": Var(TP, "K-1", "thermal expansion coefficient alpha11 "
                                          "(Chamis, instantaneous)", "parts"),
    "thermal_expansion_transverse": Var(TP, "K-1", "thermal expansion coefficient alpha22 "
                                        "(Chamis, instantaneous)", "parts"),
    "secant_thermal_expansion_longitudinal": Var(TP, "K-1", "secant thermal expansion alpha11 "
                                                 "from the reference temperature", "parts"),
    "secant_thermal_expansion_transverse": Var(TP, "K-1", "secant thermal expansion alpha22 "
                                               "from the reference temperature", "parts"),
    "moisture_expansion_longitudinal": Var(TP, "%-1", "moisture expansion coefficient beta11 "
                                           "(strain per weight %)", "parts"),
    "moisture_expansion_transverse": Var(TP, "%-1", "moisture expansion coefficient beta22 "
                                         "(strain per weight %)", "parts"),
    "thermal_conductivity_longitudinal": Var(TP, "W m-1 K-1", "thermal conductivity k11", "parts"),
    "thermal_conductivity_transverse": Var(TP, "W m-1 K-1", "thermal conductivity k22", "parts"),
    "within_wet_tg": Var(TP, "1", "1 while the service temperature is below the wet Tg of bulk and "
                         "surface layer (Chamis' degradation law applies)", "parts", design=False),
    # cam and follower: scalars over ageing
    "base_circle_radius": Var(T, "m", "base circle radius of the cam", "cam", display="mm"),
    "lift": Var(T, "m", "total follower lift", "cam", display="mm"),
    "jump_speed": Var(T, "rpm", "cam speed at which the follower first leaves the cam", "cam", RPM),
    "peak_contact_force": Var(T, "N", "largest contact force over a revolution", "cam"),
    "peak_cam_torque": Var(T, "N m", "largest absolute cam torque over a revolution", "cam"),
    "peak_contact_stress": Var(T, "Pa", "largest Hertz contact stress over a revolution", "cam",
                               display="MPa"),
    "peak_subsurface_shear_stress": Var(T, "Pa", "largest subsurface shear stress over a "
                                        "revolution", "cam", display="MPa"),
    "wear_depth": Var(T, "m", "accumulated wear depth of the cam surface (Archard)", "cam", display="um"),
    "wear_rate": Var(T, "m s-1", "largest Archard wear rate on the cam surface", "cam"),
    # elastic follower train (cam.follower.stiffness; fickcam.cam.train)
    "natural_frequency": Var(T, "Hz", "natural frequency of the follower train, sqrt((k + k_s)/m)/2 pi", "cam"),
    "follower_train_stiffness": Var(T, "N m-1", "follower train stiffness k", "cam"),
    "dynamic_jump_speed": Var(T, "rpm", "lowest cam speed at which the elastic follower leaves the cam",
                              "cam", RPM),
    "residual_vibration": Var(T, "m", "largest free-vibration amplitude in a dwell after a rise or "
                              "return, first turn from rest", "cam", display="um"),
    "minimum_dynamic_contact_force": Var(T, "N", "smallest dynamic contact force over a revolution",
                                         "cam"),
    "arm_swing": Var(T, "degree", "total swing of a swinging-arm follower", "cam", DEG),
    "peak_polydyne_output_error": Var(T, "m", "largest |output - chosen motion| of a polydyne cam",
                                      "cam", display="um"),
    # cam and follower: over the cam angle
    "follower_displacement": Var(TC, "m", "follower displacement from its lowest position on "
                                 "the aged cam (the motion; a grown base circle is not in it: "
                                 "see follower_position)", "cam", display="mm"),
    "follower_position": Var(TC, "m", "follower position: height of the roller centre, knife "
                             "tip or flat face above the cam axis, along the follower's line "
                             "of travel (a grown base circle is in it)", "cam", display="mm"),
    "follower_velocity": Var(TC, "m s-1", "follower velocity", "cam"),
    "follower_acceleration": Var(TC, "m s-2", "follower acceleration", "cam"),
    "follower_jerk": Var(TC, "m s-3", "follower jerk", "cam"),
    "follower_arm_angle": Var(TC, "degree", "swinging-arm follower angle from its lowest position",
                              "cam", DEG),
    "follower_arm_angular_velocity": Var(TC, "rad s-1", "swinging-arm angular velocity", "cam"),
    "follower_arm_angular_acceleration": Var(TC, "rad s-2", "swinging-arm angular acceleration", "cam"),
    "follower_arm_angular_jerk": Var(TC, "rad s-3", "swinging-arm angular jerk", "cam"),
    "arm_torque": Var(TC, "N m", "torque the cam must exert on the swinging arm about its pivot "
                      "(inertia, spring, preload, load)", "cam"),
    "pressure_angle": Var(TC, "degree", "pressure angle", "cam", DEG),
    "radius_of_curvature": Var(TC, "m", "radius of curvature of the working profile at the contact", "cam"),
    "pitch_radius_of_curvature": Var(TC, "m", "radius of curvature of the pitch curve", "cam"),
    "contact_force": Var(TC, "N", "contact force along the common normal", "cam"),
    "friction_force": Var(TC, "N", "sliding friction force at the cam contact", "cam"),
    "guide_friction_force": Var(TC, "N", "friction force in the follower guide", "cam"),
    "friction_torque": Var(TC, "N m", "camshaft torque from contact friction (not in cam_torque)", "cam"),
    "wear_per_revolution": Var(TC, "m", "Archard wear depth per revolution at each profile point", "cam"),
    "cam_torque": Var(TC, "N m", "torque on the camshaft", "cam"),
    "contact_stress": Var(TC, "Pa", "Hertz contact stress", "cam", display="MPa"),
    "subsurface_shear_stress": Var(TC, "Pa", "largest subsurface shear stress of the Hertz line "
                                   "contact, 0.30 p0", "cam", display="MPa"),
    "subsurface_shear_depth": Var(TC, "m", "depth of the largest subsurface shear stress, "
                                  "0.786 b", "cam", display="um"),
    "profile_x": Var(TC, "m", "working profile x (cam frame)", "cam", display="mm"),
    "profile_y": Var(TC, "m", "working profile y (cam frame)", "cam", display="mm"),
    "dynamic_follower_displacement": Var(TC, "m", "follower mass displacement, elastic train, "
                                         "periodic steady state", "cam", display="mm"),
    "dynamic_displacement_error": Var(TC, "m", "dynamic minus kinematic follower displacement", "cam",
                                      display="mm"),
    "dynamic_contact_force": Var(TC, "N", "contact force along the common normal, elastic train, "
                                 "periodic steady state", "cam"),
    "startup_follower_displacement": Var(TC, "m", "follower mass displacement over the first turn "
                                         "from rest, elastic train", "cam", display="mm"),
    "polydyne_correction": Var(TC, "m", "polydyne profile correction: cam motion minus chosen motion",
                               "cam", display="mm"),
    "polydyne_output_error": Var(TC, "m", "polydyne cam: follower output minus chosen motion", "cam",
                                 display="um"),
    # four-bar linkage
    "link_length": Var(TL, "m", "link length (pivot to pivot)", "linkage", display="mm"),
    "link_mass": Var(TL, "kg", "link mass", "linkage"),
    "link_inertia": Var(TL, "kg m2", "link moment of inertia about its centre of mass", "linkage"),
    "grashof_class": Var(T, "", "Grashof class of the linkage", "linkage"),
    "coupler_angle": Var(TK, "degree", "coupler angle theta3", "linkage", DEG),
    "rocker_angle": Var(TK, "degree", "rocker (output) angle theta4", "linkage", DEG),
    "transmission_angle": Var(TK, "degree", "transmission angle", "linkage", DEG),
    "coupler_point_x": Var(TK, "m", "coupler point x", "linkage", display="mm"),
    "coupler_point_y": Var(TK, "m", "coupler point y", "linkage", display="mm"),
    "coupler_angular_velocity": Var(TK, "rad s-1", "coupler angular velocity", "linkage"),
    "rocker_angular_velocity": Var(TK, "rad s-1", "rocker angular velocity", "linkage"),
    "coupler_angular_acceleration": Var(TK, "rad s-2", "coupler angular acceleration", "linkage"),
    "rocker_angular_acceleration": Var(TK, "rad s-2", "rocker angular acceleration", "linkage"),
    "input_torque": Var(TK, "N m", "crank input torque", "linkage"),
    "joint_force": Var(("time", "joint", "crank_angle"), "N", "pin force magnitude", "linkage"),
    "link_com_velocity_x": Var(("time", "link", "crank_angle"), "m s-1",
                               "velocity of the link's centre of mass, x", "linkage"),
    "link_com_velocity_y": Var(("time", "link", "crank_angle"), "m s-1",
                               "velocity of the link's centre of mass, y", "linkage"),
    "link_com_acceleration_x": Var(("time", "link", "crank_angle"), "m s-2",
                                   "acceleration of the link's centre of mass, x", "linkage"),
    "link_com_acceleration_y": Var(("time", "link", "crank_angle"), "m s-2",
                                   "acceleration of the link's centre of mass, y", "linkage"),
    "minimum_transmission_angle": Var(T, "degree", "smallest transmission angle over a revolution",
                                      "linkage", DEG),
    "maximum_transmission_angle": Var(T, "degree", "largest transmission angle over a revolution",
                                      "linkage", DEG),
    "peak_input_torque": Var(T, "N m", "largest absolute input torque over a revolution", "linkage"),
    "rms_input_torque": Var(T, "N m", "root mean square input torque over a revolution", "linkage"),
    "rocker_swing": Var(T, "degree", "range of the rocker angle over a revolution", "linkage", DEG),
    "toggle_crank_angle_extended": Var(T, "degree", "crank angle with crank and coupler extended in line",
                                       "linkage", DEG),
    "toggle_crank_angle_folded": Var(T, "degree", "crank angle with crank and coupler folded in line",
                                     "linkage", DEG),
    "joint_force_x": Var(("time", "joint", "crank_angle"), "N",
                         "pin force x: O2 frame on crank, A coupler on crank, B rocker on coupler, O4 frame on rocker", "linkage"),
    "joint_force_y": Var(("time", "joint", "crank_angle"), "N",
                         "pin force y: O2 frame on crank, A coupler on crank, B rocker on coupler, O4 frame on rocker", "linkage"),
    # elasticity (cam.elastic / linkage.elastic: true)
    "elastic_deflection": Var(TC, "m", "deflection of the cam profile along the common normal under the contact force", "elastic", design=True),
    "elastic_stress_tensile": Var(TC, "Pa", "largest tensile principal stress in the cam plate under the contact force", "elastic", design=True),
    "elastic_stress_compressive": Var(TC, "Pa", "largest compressive principal stress in the cam plate under the contact force (negative)", "elastic", design=True),
    "elastic_lift_error": Var(T, "m", "follower lift lost to the elastic deflection of the cam (negative: gained)", "elastic", design=True, display="um"),
    "swelling_stress_tensile": Var(TP, "Pa", "largest tensile principal hygrothermal stress in the part", "elastic"),
    "swelling_stress_compressive": Var(TP, "Pa", "largest compressive principal hygrothermal stress in the part (negative)", "elastic"),
    "swelling_stress_field": Var(("part", "stress_point"), "Pa", "hygrothermal principal stress of larger magnitude at the faces, at the time of the largest failure index", "elastic"),
    "stress_point_x": Var(("part", "stress_point"), "m", "element centroid x of the stress field", "elastic"),
    "stress_point_y": Var(("part", "stress_point"), "m", "element centroid y of the stress field", "elastic"),
    "failure_index": Var(TP, "1", "largest failure index of the hygrothermal stress against the wet strengths (1: failure)", "elastic"),
    # limits (scene limits: section)
    "limit_ratio": Var(("time", "limit"), "1", "limit ratio: 1 at the limit, above 1 out of spec",
                       "limits"),
    "time_out_of_spec": Var(("limit",), "d", "first ageing time the limit fails (NaN: never)",
                            "limits", 1.0 / 86400.0, error="time_out_of_spec_error"),
    "time_out_of_spec_error": Var(("limit",), "d", "estimated error of time_out_of_spec: the "
                                  "search's, at most 0.1 % of it or 1 h (finer with a finer "
                                  "diffusion accuracy)", "limits", 1.0 / 86400.0),
    # a sweep with limits: scatter (fickcam.sweep.scatter)
    "fraction_out_of_spec": Var(("time", "limit"), "%", "fraction of the cases out of spec by this "
                                "ageing time", "limits", 100.0),
    "fraction_out_of_spec_low": Var(("time", "limit"), "%", "lower bound of the Wilson 95 % "
                                    "interval of fraction_out_of_spec", "limits", 100.0),
    "fraction_out_of_spec_high": Var(("time", "limit"), "%", "upper bound of the Wilson 95 % "
                                     "interval of fraction_out_of_spec", "limits", 100.0),
    "cases_out_of_spec": Var(("time", "limit"), "1", "number of cases out of spec by this ageing "
                             "time (attribute cases: how many ran)", "limits"),
    # moisture fields (outputs.fields: true)
    "moisture": Var(("time", "part", "cell"), "%", "moisture content field", "fields"),
    "cell_x": Var(("part", "cell"), "m", "cell centre x", "fields"),
    "cell_y": Var(("part", "cell"), "m", "cell centre y", "fields"),
    "cell_z": Var(("part", "cell"), "m", "cell centre z", "fields"),
}



def design_name(name: str) -> str:
    """The name of the as-designed value of ``name`` (``lift`` gives ``lift_design``).

    Parameters
    ----------
    name : str
        A variable.

    Returns
    -------
    str
        ``<name>_design``.
    """
    return f"{name}_design"


def _design_rows(table: dict[str, Var]) -> dict[str, Var]:
    """``<name>_design`` for every variable with ``has_design``: dims without time."""
    return {design_name(name): Var(tuple(d for d in var.dims if d != "time"), var.units,
                                   var.long_name + DESIGN_NOTE, var.section, var.scale,
                                   design=False, display=var.display)
            for name, var in table.items() if var.has_design}


VARIABLES.update(_design_rows(VARIABLES))

COORDINATES: dict[str, tuple[str, str]] = {
    # float days: matplotlib plots them and `sel`/`interp` take numbers of days; "d" (the
    # UDUNITS day) is not a CF time unit, so no netCDF reader turns the column into dates
    "time": ("d", "ageing time"),
    "ageing_time": ("d", "ageing time in days"),  # the same days, kept for older code
    # hourly, daily, weekly or 30-day intervals (the finest that gives at most 1000)
    "climate_time": ("d", "ageing time, middle of the climate interval"),
    "part": ("", "part name"),
    "link": ("", "link name"),
    "joint": ("", "pin joint (O2 crank-frame, A crank-coupler, B coupler-rocker, O4 rocker-frame)"),
    "cam_angle": ("degree", "cam angle"),
    "crank_angle": ("degree", "crank angle"),
    "cell": ("", "cell index"),
    "stress_point": ("", "element index of a stress field"),
    "limit": ("", "limited result variable (scene limits: section)"),
}


def markdown_table() -> str:
    """The variable table as Markdown (for the docs' reference and `fickcam schema`); the
    as-designed rows are named in the last column of the variable they belong to."""
    rows = ["| variable | dims | units | meaning | as designed |", "|---|---|---|---|---|"]
    designs = {design_name(name) for name, var in VARIABLES.items() if var.has_design}
    for name, var in VARIABLES.items():
        if name in designs:
            continue
        design = f"`{design_name(name)}`" if var.has_design else ""
        rows.append(f"| `{name}` | {', '.join(var.dims)} | {var.units or '-'} | {var.long_name} "
                    f"| {design} |")
    return "\n".join(rows)
