"""The public entry points document their parameters (numpydoc): a ``Parameters``
section naming every parameter with its type, and a ``[unit]`` on every physical one.

The section is read with a small parser of the numpydoc layout (a header underlined with
dashes, then ``name : type`` lines each followed by an indented description), so the test
runs without numpydoc installed.
"""
from __future__ import annotations

import importlib
import inspect
import re

import pytest

# entry point -> its physical parameters (each needs a ``[unit]`` in its description)
ENTRY_POINTS = {
    "fickcam.load_scene": (),
    "fickcam.run": ("accuracy",),
    "fickcam.save": (),
    "fickcam.open_result": (),
    "fickcam.compensate": ("at", "over", "accuracy"),
    "fickcam.fit_weight_gain": (),
    "fickcam.scene.load_scene": (),
    "fickcam.query.select": ("time", "cam_angle", "crank_angle"),
    "fickcam.query.drift": (),
    "fickcam.export.export": (),
    "fickcam.export.export_csv": (),
    "fickcam.export.export_json": (),
    "fickcam.export.export_netcdf": (),
    "fickcam.diffusion.solve": ("times", "accuracy", "surface_layer_depth"),
    "fickcam.diffusion.plan": ("times", "accuracy", "surface_layer_depth"),
    "fickcam.diffusion.Sheet": ("thickness",),
    "fickcam.diffusion.Disc": ("outer_radius", "thickness", "inner_radius"),
    "fickcam.diffusion.Bar": ("length", "width", "thickness"),
    "fickcam.diffusion.CamPlate": ("profile_x", "profile_y", "thickness", "bore_radius"),
    "fickcam.diffusion.LinkBar": ("length", "width", "thickness", "boss_outer_radius",
                                  "boss_inner_radius"),
    "fickcam.diffusion.Exposure": ("change_times", "temperature", "surface_moisture",
                                   "initial_moisture"),
    "fickcam.diffusion.Exposure.piecewise": ("change_times", "temperatures",
                                             "surface_values", "initial_moisture"),
    "fickcam.diffusion.Diffusivity": ("pre_exponential", "activation_energy"),
    "fickcam.diffusion.DiffusionResult": ("times", "mean", "surface", "error_estimate"),
    "fickcam.compensation.compensate": ("at", "over", "accuracy"),
    "fickcam.sweep.run_sweep": (),
    "fickcam.sweep.load_sweep": (),
    "fickcam.fit.fit_weight_gain": ("fiber_volume_fraction",),
    "fickcam.fit.read_weight_gain": (),
    "fickcam.limits.stored_value": (),
    "fickcam.limits.parse_limit": (),
    "fickcam.limits.worst_value": (),
    "fickcam.limits.limit_ratio": (),
    "fickcam.limits.first_crossings": ("times", "ratios"),
    "fickcam.plotting.plot": (),
    "fickcam.materials.hygrothermal.wet_glass_transition_temperature": ("dry_tg",
                                                                        "matrix_moisture"),
    "fickcam.materials.hygrothermal.property_retention": ("wet_tg", "temperature", "dry_tg",
                                                          "reference_temperature"),
    "fickcam.materials.hygrothermal.free_strain": ("alpha", "beta", "temperature",
                                                   "reference_temperature", "moisture",
                                                   "initial_moisture"),
    "fickcam.cam.dynamics.pressure_angle": ("height", "dy", "offset"),
    "fickcam.cam.dynamics.pitch_radius_of_curvature": ("height", "dy", "d2y", "offset"),
    "fickcam.cam.dynamics.axial_force": ("mass", "acceleration", "spring_rate",
                                         "spring_deflection", "preload", "external_load"),
    "fickcam.cam.dynamics.jump_speed": ("mass", "d2y", "holding_force"),
    "fickcam.cam.dynamics.effective_modulus": ("e1", "nu1", "e2", "nu2"),
    "fickcam.cam.dynamics.hertz_line_pressure": ("force", "length", "cam_radius",
                                                 "follower_radius", "e_star"),
    "fickcam.cam.dynamics.archard_wear_per_revolution": ("coefficient", "hardness", "force",
                                                         "length", "slide_ratio"),
    "fickcam.cam.motion.follower_motion": ("theta",),
    "fickcam.elastic.contact.hertz_half_width": ("force", "peak_pressure", "length"),
    "fickcam.elastic.strength.tsai_wu_index": ("s1", "s2", "s12"),
    "fickcam.materials.bodies.disc_body": ("outer_radius", "thickness", "inner_radius",
                                           "density"),
    "fickcam.materials.state.material_state": ("temperature", "moisture", "surface_moisture",
                                               "reference_temperature", "initial_moisture"),
    "fickcam.materials.micromechanics.transverse_diffusivity": ("kf", "matrix_d"),
    "fickcam.linkage.positions.rocker_angle": ("a", "b", "c", "d", "theta2"),
    "fickcam.linkage.positions.coupler_angle": ("a", "b", "c", "d", "theta2"),
    "fickcam.linkage.positions.positions": ("a", "b", "c", "d", "theta2"),
    "fickcam.linkage.positions.continuous": ("theta",),
    "fickcam.linkage.positions.transmission_angle": ("theta3", "theta4"),
    "fickcam.linkage.positions.joint_positions": ("a", "b", "c", "d", "theta2", "theta3",
                                                  "theta4"),
    "fickcam.linkage.positions.coupler_point": ("a", "theta2", "theta3", "distance", "angle"),
    "fickcam.linkage.positions.assembly_gaps": ("theta2",),
    "fickcam.linkage.positions.toggle_crank_angles": ("a", "b", "c", "d"),
    "fickcam.linkage.classify.grashof_condition": ("a", "b", "c", "d"),
    "fickcam.linkage.classify.grashof_class": ("a", "b", "c", "d", "tolerance"),
    "fickcam.linkage.classify.class_changes": ("times",),
    "fickcam.cam.spline.SplineLaw": ("degree", "x", "s", "start", "end"),
    "fickcam.cam.spline.end_condition_count": ("degree",),
    "fickcam.cam.spline.spline_motion": ("x",),
    "fickcam.cam.spline.spline_law": ("points", "height", "span", "degree", "start", "end"),
    "fickcam.diffusion.exact.modes.Factor": ("rates", "mean", "core", "core_share"),
    "fickcam.diffusion.exact.modes.sheet_factor": ("length", "d0", "depth", "count"),
    "fickcam.diffusion.exact.modes.cylinder_factor": ("radius", "d0", "depth", "count"),
    "fickcam.diffusion.exact.modes.factors": ("d0", "depth", "counts"),
    "fickcam.diffusion.exact.modes.dimensions": (),
    "fickcam.diffusion.exact.modes.Modes": ("rates", "mean", "layer", "tail_rate"),
    "fickcam.diffusion.exact.modes.product_modes": ("d0", "depth", "counts"),
    "fickcam.diffusion.exact.modes.lump": ("per_octave",),
    "fickcam.diffusion.exact.modes.step_corrections": ("d0", "depth", "response"),
    "fickcam.linkage.kinematics.angular_velocities": ("a", "b", "c", "theta2", "theta3",
                                                      "theta4", "omega2"),
    "fickcam.linkage.kinematics.angular_accelerations": ("a", "b", "c", "theta2", "omega2",
                                                         "omega3", "omega4", "alpha2"),
    "fickcam.linkage.kinematics.rotating_point": ("r", "theta", "omega", "alpha"),
    "fickcam.linkage.kinematics.centre_of_mass_motion": ("lengths", "fractions", "thetas",
                                                         "omegas", "alphas"),
    "fickcam.linkage.dynamics.kinetostatics": ("masses", "inertias", "com_acceleration",
                                               "alphas", "pins", "com_position", "gravity",
                                               "rocker_torque"),
    "fickcam.linkage.dynamics.kinetic_energy": ("masses", "inertias", "com_velocity",
                                                "omegas"),
    "fickcam.linkage.dynamics.rms": ("values",),
    "fickcam.linkage.model.FourBarDesign": ("crank", "coupler", "rocker", "frame",
                                            "coupler_point_distance", "coupler_point_angle",
                                            "crank_speed", "crank_angular_acceleration",
                                            "rocker_load_torque"),
    "fickcam.linkage.model.FourBarState": ("link_lengths", "link_masses", "link_inertias",
                                           "centre_of_mass", "coupler_point_distance"),
    "fickcam.linkage.model.fourbar_response": ("crank_angle",),
    "fickcam.cam.profile.periodic_spline": ("x", "y"),
    "fickcam.cam.profile.counter_clockwise": ("x", "y"),
    "fickcam.cam.profile.working_from_pitch": ("x", "y", "roller_radius"),
    "fickcam.cam.profile.make_profile": ("x", "y", "roller_radius"),
    "fickcam.cam.profile.read_profile_csv": (),
    "fickcam.cam.profile.load_profile": ("roller_radius",),
    "fickcam.cam.profile.write_profile_csv": ("x", "y"),
    "fickcam.cam.profile.dxf_module": (),
    "fickcam.cam.profile.write_profile_dxf": ("x", "y"),
    "fickcam.cam.profile.profile_motion": ("strain_x", "strain_y", "roller", "offset", "theta",
                                           "base"),
    "fickcam.cam.profile.contact_table": (),
    "fickcam.cam.profile.solve_contact": ("theta",),
    "fickcam.cam.profile.aged_profile_motion": ("strain_x", "strain_y", "roller", "offset",
                                                "base"),
    "fickcam.cam.arm.Arm": ("pivot_x", "pivot_y", "length", "face_offset", "inertia",
                            "spring_rate", "spring_preload", "load_torque"),
    "fickcam.cam.arm.perp": (),
    "fickcam.cam.arm.cross": (),
    "fickcam.cam.arm.roller_arm_opening": ("d", "length", "radius"),
    "fickcam.cam.arm.roller_base_angle": ("prime_radius", "length"),
    "fickcam.cam.arm.face_opening": ("d", "face_offset", "support"),
    "fickcam.cam.arm.face_base_angle": ("base_radius", "face_offset"),
    "fickcam.cam.arm.roller_centre": ("phi0", "psi", "d1", "d2"),
    "fickcam.cam.arm.pitch_derivatives": ("centre", "velocity", "acceleration"),
    "fickcam.cam.arm.pitch_radius_of_curvature": ("a", "b"),
    "fickcam.cam.arm.pitch_normal": ("a",),
    "fickcam.cam.arm.face_support": ("gamma0", "psi", "d1", "d2"),
    "fickcam.cam.arm.face_envelope": ("p", "p1", "p2", "g1", "g2"),
    "fickcam.cam.arm.pressure_angle": ("ux", "uy", "nx", "ny"),
    "fickcam.cam.arm.rotate": ("angle", "x", "y"),
    "fickcam.cam.arm.Contact": ("x", "y", "nx", "ny", "lever", "pressure_angle", "pitch_radius",
                                "radius"),
    "fickcam.cam.arm.roller_contact": ("phi0", "roller", "psi", "d1", "d2"),
    "fickcam.cam.arm.face_contact": ("gamma0", "psi", "d1", "d2"),
    "fickcam.cam.arm.dry_profile": ("base_radius", "roller", "theta", "motion"),
    "fickcam.cam.arm.aged_roller_contact": ("phi0_dry", "length", "wx", "wy", "nx", "ny",
                                            "roller"),
    "fickcam.cam.arm.aged_face_contact": ("gamma0_dry", "face_offset", "wx", "wy", "nx", "ny"),
    "fickcam.cam.arm.arm_slope": ("px", "py", "nx", "ny"),
    "fickcam.cam.arm.aged_profile_contact": ("base", "roller", "wx", "wy", "nx", "ny"),
    "fickcam.linkage.ageing.scene_parts": (),
    "fickcam.linkage.ageing.link_state": (),
    "fickcam.linkage.ageing.link_states": (),
    "fickcam.linkage.ageing.scene_response": ("times", "angles"),
    "fickcam.linkage.spec.can_assemble_somewhere": ("crank", "coupler", "rocker", "frame"),
    "fickcam.cam.profile.CamProfile": ("spline",),
    "fickcam.cam.profile.AgedContact": ("strain_x", "strain_y", "roller", "offset", "base"),
    "fickcam.cam.profile.ProfileMotion": ("table", "extremes"),
    "fickcam.linkage.spec.CouplerPoint": ("distance", "angle"),
    "fickcam.linkage.spec.LinkSectionSpec": ("width", "thickness", "boss_outer_radius",
                                             "boss_inner_radius"),
    "fickcam.linkage.spec.LinkageSection": ("crank", "coupler", "rocker", "frame", "crank_speed",
                                            "crank_angular_acceleration", "rocker_load_torque",
                                            "centre_of_mass"),
    # diffusion: problem, stepping, superposition, forcing, non-Fickian
    "fickcam.diffusion.problem.cache.freeze": (),
    "fickcam.diffusion.problem.cache.size_of": (),
    "fickcam.diffusion.problem.cache.run_cache": (),
    "fickcam.diffusion.problem.scaling.axis_scale": ("length", "d_axis", "d_ref"),
    "fickcam.diffusion.problem.scaling.stretch_of": ("d",),
    "fickcam.diffusion.problem.scaling.planar_scale": ("part", "d"),
    "fickcam.diffusion.problem.sorption.Rate": ("pre_exponential", "activation_energy"),
    "fickcam.diffusion.problem.sorption.Langmuir": ("binding", "release"),
    "fickcam.diffusion.problem.sorption.ConcentrationDependent":
        ("reference_moisture", "exponent", "ratios", "factors"),
    "fickcam.diffusion.problem.sorption.is_langmuir": (),
    "fickcam.diffusion.problem.sorption.is_nonlinear": (),
    "fickcam.diffusion.problem.sorption.describe": (),
    "fickcam.diffusion.stepping.step_plans.geometric_steps":
        ("start", "stop", "first_step", "max_step"),
    "fickcam.diffusion.stepping.step_plans.step_nodes":
        ("change_taus", "output_taus", "first_step"),
    "fickcam.diffusion.stepping.step_plans.drop_slivers": ("nodes", "first_step"),
    "fickcam.diffusion.stepping.step_plans.nearest_nodes": ("nodes", "values"),
    "fickcam.diffusion.stepping.step_plans.inverse_time": ("tau_nodes", "change_times"),
    "fickcam.diffusion.stepping.step_plans.earliest_output": ("change_stars", "output_stars"),
    "fickcam.diffusion.stepping.step_plans.output_ages": ("change_stars", "output_stars"),
    "fickcam.diffusion.stepping.step_response.StepResponse": ("nodes", "mean", "layer", "fields"),
    "fickcam.diffusion.stepping.step_response.step_response": ("end", "first_step"),
    "fickcam.diffusion.stepping.step_response.blend": ("values", "tolerance"),
    "fickcam.diffusion.stepping.march.ThetaStepper": (),
    "fickcam.diffusion.stepping.march.History": ("mean", "layer", "fields", "track"),
    "fickcam.diffusion.stepping.march.march":
        ("nodes", "surface_values", "initial", "times", "surface_before"),
    "fickcam.diffusion.stepping.march.held_values": ("ending", "initial"),
    "fickcam.diffusion.stepping.march.norm": (),
    "fickcam.diffusion.stepping.march.rounded_steps": ("steps",),
    "fickcam.diffusion.stepping.dense_output.StepRecord": ("nodes", "values", "surface", "changes"),
    "fickcam.diffusion.stepping.dense_output.lagrange": ("x",),
    "fickcam.diffusion.stepping.dense_output.Extension": ("scale", "accuracy"),
    "fickcam.diffusion.stepping.dense_output.held_to_plan": (),
    "fickcam.diffusion.forcing.clock.RescaledTime": (),
    "fickcam.diffusion.forcing.clock.clock_of": (),
    "fickcam.diffusion.forcing.clock.reference_factor": (),
    "fickcam.diffusion.forcing.clock.rescaled_time": ("t", "a_ref"),
    "fickcam.diffusion.forcing.clock.Scales": ("a_ref", "d_ref", "length"),
    "fickcam.diffusion.forcing.clock.scales": (),
    "fickcam.diffusion.forcing.record.is_long_record": (),
    "fickcam.diffusion.forcing.record.Forcing": ("tau", "right", "left", "interpolation", "nodes"),
    "fickcam.diffusion.forcing.record.linear_pieces": ("tolerance",),
    "fickcam.diffusion.forcing.record.forcing": ("times", "tolerance"),
    "fickcam.diffusion.superposition.duhamel.surface_jumps": (),
    "fickcam.diffusion.superposition.duhamel.duhamel": ("kernel", "times", "diffusion_times"),
    "fickcam.diffusion.superposition.tabulated.Table":
        ("start", "end", "step", "kernel", "integral"),
    "fickcam.diffusion.superposition.tabulated.tabulate": ("kernel", "first", "last"),
    "fickcam.diffusion.superposition.tabulated.Lattice": ("end", "step"),
    "fickcam.diffusion.superposition.tabulated.Sources": ("steps", "slopes"),
    "fickcam.diffusion.superposition.tabulated.Ramps": ("times", "changes", "moments", "outputs"),
    "fickcam.diffusion.superposition.tabulated.Pairs": ("tau", "coefficient", "at"),
    "fickcam.diffusion.superposition.tabulated.sources": ("force",),
    "fickcam.diffusion.superposition.tabulated.read": ("first",),
    "fickcam.diffusion.superposition.tabulated.LongRecord": ("swing", "tolerance", "first", "last"),
    "fickcam.diffusion.superposition.tabulated.KernelKey": (),
    "fickcam.diffusion.nonfickian.two_phase_mesh.TwoPhaseHistory":
        ("mean", "layer", "bound", "fields"),
    "fickcam.diffusion.nonfickian.two_phase_mesh.two_phase_marcher": (),
    "fickcam.diffusion.nonfickian.two_phase_mesh.march_coupled":
        ("nodes", "free_before", "binding", "release", "initial", "initial_share", "labels"),
    "fickcam.diffusion.nonfickian.two_phase_modes.Nodes":
        ("t", "tau", "free_right", "free_left", "gamma", "beta", "ratio", "initial_bound",
         "interpolation"),
    "fickcam.diffusion.nonfickian.two_phase_modes.march_nodes": ("times", "tolerance"),
    "fickcam.diffusion.nonfickian.two_phase_modes.march_modes": ("rates", "amplitudes"),
    "fickcam.diffusion.nonfickian.two_phase_modes.ModeSource": ("modes", "response"),
    "fickcam.diffusion.nonfickian.two_phase_modes.separable_source": ("d0", "depth"),
    "fickcam.diffusion.nonfickian.two_phase_modes.langmuir_history":
        ("times", "accuracy", "surface_layer_depth"),
    "fickcam.diffusion.nonfickian.concentration_dependent.Sweeps": ("tolerance", "forcing"),
    "fickcam.diffusion.nonfickian.concentration_dependent.fastest": ("diffusivity", "times"),
    "fickcam.diffusion.nonfickian.concentration_dependent.slowest": ("diffusivity", "times"),
    "fickcam.diffusion.nonfickian.concentration_dependent.spread": ("times",),
    "fickcam.diffusion.nonfickian.concentration_dependent.skin_start": (),
    "fickcam.diffusion.nonfickian.concentration_dependent.dries_to_a_skin": (),
    "fickcam.diffusion.nonfickian.concentration_dependent.Sizing": ("margin",),
    "fickcam.diffusion.nonfickian.concentration_dependent.nonlinear_plan":
        ("diffusivity", "times", "accuracy"),
    "fickcam.diffusion.nonfickian.concentration_dependent.solve_nonlinear": ("problem",),
    "fickcam.diffusion.nonfickian.concentration_dependent.wettest": ("times",),
    "fickcam.diffusion.nonfickian.concentration_dependent.Faces":
        ("transmissibility", "boundary", "volumes"),
    "fickcam.diffusion.nonfickian.concentration_dependent.sweep_march": ("top", "initial"),
    "fickcam.diffusion.nonfickian.concentration_dependent.Lagged": (),
    "fickcam.diffusion.nonfickian.concentration_dependent.extrapolated":
        ("before", "latest", "dt_before", "dt", "g"),
    "fickcam.diffusion.nonfickian.concentration_dependent.sweep_step":
        ("old", "g", "top", "dt", "time", "guess"),
    "fickcam.diffusion.nonfickian.corrected_fields.planform_at": ("values", "points"),
    "fickcam.diffusion.nonfickian.corrected_fields.reading": ("points",),
    "fickcam.diffusion.nonfickian.corrected_fields.exposed_points": (),
    "fickcam.diffusion.nonfickian.corrected_fields.sheet_at":
        ("z_sheet", "unaccomplished", "z", "thickness"),
    "fickcam.diffusion.nonfickian.corrected_fields.References": ("sheet", "planform", "coarser"),
    "fickcam.diffusion.nonfickian.corrected_fields.corrected_fields":
        ("sheet_ref", "planform_ref", "surface"),
    "fickcam.diffusion.nonfickian.corrected_fields.restricted": (),
    "fickcam.diffusion.nonfickian.corrected_fields.unseparated_share": ("fields", "surface"),
    "fickcam.diffusion.nonfickian.corrected_fields.FieldErrors":
        ("correction", "sheet", "planform", "three_d"),
    "fickcam.diffusion.nonfickian.corrected_fields.field_errors": (),
    "fickcam.diffusion.nonfickian.corrected_fields.stored": (),
    "fickcam.diffusion.nonfickian.corrected_pieces.CombinedMarch":
        ("mean", "layer", "fields", "pair"),
    "fickcam.diffusion.nonfickian.corrected_pieces.as_prism": ("geometry", "diffusivity"),
    "fickcam.diffusion.nonfickian.corrected_pieces.bar_size": (),
    "fickcam.diffusion.nonfickian.corrected_pieces.section_axes": ("diffusivity",),
    "fickcam.diffusion.nonfickian.corrected_pieces.bar_coordinates": ("coordinates",),
    "fickcam.diffusion.nonfickian.corrected_pieces.z_band": ("z_widths", "depth"),
    "fickcam.diffusion.nonfickian.corrected_pieces.half_slab": ("z_widths",),
    "fickcam.diffusion.nonfickian.corrected_pieces.planform_disc": ("d", "depth"),
    "fickcam.diffusion.nonfickian.corrected_pieces.PrismCells": ("z",),
    "fickcam.diffusion.nonfickian.corrected_pieces.cross": (),
    "fickcam.diffusion.nonfickian.corrected_pieces.combination": (),
    "fickcam.diffusion.nonfickian.corrected_pieces.richardson_march": ("top", "times"),
    "fickcam.diffusion.nonfickian.corrected_pieces.unaccomplished_ratio":
        ("reference", "coarse", "floor"),
    "fickcam.diffusion.nonfickian.corrected_pieces.corrected": ("surface", "union"),
    "fickcam.diffusion.nonfickian.corrected_pieces.steps_for": ("accuracy",),
    "fickcam.diffusion.nonfickian.corrected_pieces.level_plan": ("times", "mesh_accuracy"),
    "fickcam.diffusion.nonfickian.corrected_pieces.sheet_reference": ("times", "accuracy", "depth"),
    "fickcam.diffusion.nonfickian.corrected_pieces.SharedInputs": ("times", "d", "top", "depth"),
    "fickcam.diffusion.nonfickian.corrected_pieces.MeshMarches": ("coordinates", "union"),
    "fickcam.diffusion.nonfickian.corrected_pieces.three_d": (),
    "fickcam.diffusion.nonfickian.corrected_product.MeshCaps": ("nested", "cross"),
    "fickcam.diffusion.nonfickian.corrected_product.skin_margin": ("times",),
    "fickcam.diffusion.nonfickian.corrected_product.CorrectedMeshes":
        ("results", "planform_error", "factor", "scale"),
    "fickcam.diffusion.nonfickian.corrected_product.base_level": ("accuracy",),
    "fickcam.diffusion.nonfickian.corrected_product.base_plan": ("accuracy",),
    "fickcam.diffusion.nonfickian.corrected_product.surface_of": (),
    "fickcam.diffusion.nonfickian.corrected_product.corrected_levels":
        ("geometry", "times", "accuracy", "surface_layer_depth"),
    "fickcam.diffusion.nonfickian.corrected_product.estimate_parts": ("margin",),
    "fickcam.diffusion.nonfickian.corrected_product.unseparated": ("margin",),
    "fickcam.diffusion.nonfickian.corrected_product.finest": ("results",),
    "fickcam.diffusion.nonfickian.corrected_product.extension": ("accuracy",),
    "fickcam.diffusion.nonfickian.corrected_product.refined_run":
        ("geometry", "times", "accuracy", "surface_layer_depth"),
    "fickcam.diffusion.nonfickian.corrected_product.solve_corrected": ("problem",),
    "fickcam.diffusion.nonfickian.corrected_product.plan_corrected": ("problem",),
    "fickcam.diffusion.nonfickian.corrected_product.refined_reference": ("accuracy", "scale"),
    "fickcam.diffusion.nonfickian.corrected_product.gap": ("a", "b", "scale"),
    "fickcam.diffusion.nonfickian.corrected_product.combined": ("pairs",),
    "fickcam.diffusion.nonfickian.planform_modes.planform_design": ("d", "accuracy", "t_lo"),
    "fickcam.diffusion.nonfickian.planform_modes.Planform": ("operator",),
    "fickcam.diffusion.nonfickian.planform_modes.planform_operator":
        ("d", "depth", "finest", "growth"),
    "fickcam.diffusion.nonfickian.planform_modes.lanczos_spectrum": (),
    "fickcam.diffusion.nonfickian.planform_modes.planar_fraction": ("spectrum", "ages"),
    "fickcam.diffusion.nonfickian.planform_modes.lanczos_count": ("ages", "tolerance"),
    "fickcam.diffusion.nonfickian.planform_modes.whole_at_start": ("spectrum",),
    "fickcam.diffusion.nonfickian.planform_modes.planform_source": ("d", "spectrum"),
    "fickcam.diffusion.nonfickian.planform_modes.RefinedPlanform": ("error", "finest", "growth"),
    "fickcam.diffusion.nonfickian.planform_modes.Refinement": ("cap",),
    "fickcam.diffusion.nonfickian.planform_modes.refined_planform":
        ("d", "depth", "finest", "growth", "ages", "tolerance"),
    "fickcam.diffusion.nonfickian.planform_modes.error_coefficients": ("meshes",),
    "fickcam.diffusion.nonfickian.planform_modes.mesh_error": ("finest", "growth"),
}

_HEADER = re.compile(r"^(?P<title>[A-Z][A-Za-z ]+)\n-{3,}$", re.MULTILINE)
_ENTRY = re.compile(r"^(?P<names>\*{0,2}\w+(?:, \*{0,2}\w+)*)(?: : (?P<type>\S.*))?$")
_UNIT = re.compile(r"\[[^\]]+\]")


def _entry_point(dotted: str):
    module_name, _, rest = dotted.partition(".")
    target = importlib.import_module(module_name)
    parts = rest.split(".")
    for k, part in enumerate(parts):
        if not hasattr(target, part):  # a sub-module not imported by its package
            target = importlib.import_module(".".join([module_name, *parts[:k + 1]]))
        else:
            target = getattr(target, part)
    return target


def sections(doc: str) -> dict[str, str]:
    """The docstring's numpydoc sections, title -> body (dedented)."""
    text = inspect.cleandoc(doc or "")
    headers = list(_HEADER.finditer(text))
    return {h["title"].strip(): text[h.end():(headers[k + 1].start() if k + 1 < len(headers)
                                               else len(text))]
            for k, h in enumerate(headers)}


def parameter_entries(body: str) -> dict[str, tuple[str, str]]:
    """``name -> (type, description)`` of a Parameters section (``a, b : float`` names
    two parameters)."""
    entries: dict[str, tuple[str, str]] = {}
    names: list[str] = []
    for line in body.splitlines():
        match = _ENTRY.match(line)
        if match:
            names = [n.lstrip("*") for n in match["names"].split(", ")]
            for name in names:
                entries[name] = (match["type"] or "", "")
        elif line.startswith(" ") and names:
            for name in names:
                kind, description = entries[name]
                entries[name] = (kind, f"{description} {line.strip()}")
    return entries


def signature_parameters(target) -> list[str]:
    if inspect.isclass(target) and hasattr(target, "model_fields"):  # a pydantic model
        return list(target.model_fields)
    function = target.__init__ if inspect.isclass(target) and not hasattr(
        target, "__dataclass_fields__") else target
    if inspect.isclass(target) and hasattr(target, "__dataclass_fields__"):
        return list(target.__dataclass_fields__)
    return [name for name in inspect.signature(function).parameters
            if name not in ("self", "cls")]


@pytest.mark.parametrize("dotted", sorted(ENTRY_POINTS))
def test_entry_point_documents_every_parameter(dotted):
    target = _entry_point(dotted)
    expected = signature_parameters(target)
    found = sections(target.__doc__)
    if not expected:
        return
    assert "Parameters" in found, f"{dotted}: no numpydoc Parameters section"
    documented = parameter_entries(found["Parameters"])
    missing = [name for name in expected if name not in documented]
    assert not missing, f"{dotted}: parameters not documented: {', '.join(missing)}"
    extra = [name for name in documented if name not in expected]
    assert not extra, f"{dotted}: documents parameters it does not take: {', '.join(extra)}"


@pytest.mark.parametrize("dotted", sorted(d for d, physical in ENTRY_POINTS.items() if physical))
def test_physical_parameters_carry_a_unit(dotted):
    documented = parameter_entries(sections(_entry_point(dotted).__doc__)["Parameters"])
    without = [name for name in ENTRY_POINTS[dotted]
               if not _UNIT.search(documented.get(name, ("", ""))[1])]
    assert not without, f"{dotted}: no [unit] for {', '.join(without)}"


def test_the_parser_reads_a_numpydoc_section():
    doc = """Summary.

    Parameters
    ----------
    length, width : float
        The sides [m].
    flag : bool
        A switch.

    Returns
    -------
    float
        The area [m^2].
    """
    found = sections(doc)
    assert set(found) == {"Parameters", "Returns"}
    entries = parameter_entries(found["Parameters"])
    sides = ("float", " The sides [m].")
    assert entries == {"length": sides, "width": sides, "flag": ("bool", " A switch.")}
    assert sections("One line, no sections.") == {}


#: modules whose documented functions also state what they return
RETURNING = ("fickcam.linkage.positions.", "fickcam.linkage.classify.",
             "fickcam.linkage.kinematics.", "fickcam.linkage.dynamics.", "fickcam.linkage.model.",
             "fickcam.linkage.ageing.", "fickcam.linkage.spec.can",
             "fickcam.cam.spline.", "fickcam.cam.profile.", "fickcam.cam.arm.",
             "fickcam.diffusion.exact.modes.")


@pytest.mark.parametrize("dotted", sorted(d for d in ENTRY_POINTS if d.startswith(RETURNING)
                                          and not inspect.isclass(_entry_point(d))))
def test_entry_point_documents_what_it_returns(dotted):
    assert "Returns" in sections(_entry_point(dotted).__doc__), f"{dotted}: no Returns section"
