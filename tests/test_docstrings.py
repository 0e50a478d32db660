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
    # diffusion: dispatch, models, exact, accuracy, operators, planform
    "fickcam.diffusion.dispatch.FickModel": ("plan",),
    "fickcam.diffusion.dispatch.numerical_model": ("geometry",),
    "fickcam.diffusion.dispatch.SolverSettings": ("cells",),
    "fickcam.diffusion.dispatch.Route": (),
    "fickcam.diffusion.dispatch.route_of": ("problem",),
    "fickcam.diffusion.dispatch.law_of": (),
    "fickcam.diffusion.dispatch.read_ages": ("clock", "times", "most"),
    "fickcam.diffusion.models.analytic.exact_history": ("geometry", "diffusivity", "exposure",
                                                        "times", "surface_layer_depth"),
    "fickcam.diffusion.models.analytic.exact_history_field": ("geometry", "diffusivity",
                                                              "exposure", "times", "points"),
    "fickcam.diffusion.models.analytic.record_history": ("geometry", "diffusivity", "times",
                                                         "accuracy", "surface_layer_depth"),
    "fickcam.diffusion.models.analytic.solve_analytic": ("problem", "record_accuracy"),
    "fickcam.diffusion.models.finite_volume.plan_direct": ("problem", "caps"),
    "fickcam.diffusion.models.finite_volume.discretise": ("geometry", "diffusivity", "cells",
                                                          "surface_layer_depth", "finest",
                                                          "growth"),
    "fickcam.diffusion.models.finite_volume.StepPlan": ("nodes", "times", "surface",
                                                        "surface_before", "outputs",
                                                        "restarts"),
    "fickcam.diffusion.models.finite_volume.step_plan": ("exposure", "times", "scales",
                                                         "per_doubling"),
    "fickcam.diffusion.models.finite_volume.solve_direct": ("problem",),
    "fickcam.diffusion.models.finite_volume.richardson_pair": ("chosen", "coarse", "fine",
                                                               "scale"),
    "fickcam.diffusion.models.plane.peak_weight": ("perimeter", "area", "ages"),
    "fickcam.diffusion.models.plane.leading_uptake": ("perimeter", "area", "tau"),
    "fickcam.diffusion.models.plane.MeshDesign": ("finest", "growth", "nodes",
                                                  "relative_error"),
    "fickcam.diffusion.models.plane.mesh_design": ("target", "start", "perimeter", "tightest",
                                                   "cap"),
    "fickcam.diffusion.models.plane.uniform_design": ("target", "start", "area", "tightest",
                                                      "cap"),
    "fickcam.diffusion.models.plane.mesh_first_step": ("finest", "switch"),
    "fickcam.diffusion.models.plane.planform_mesh": ("part", "finest", "growth", "stretch"),
    "fickcam.diffusion.models.plane.planform_response": ("geometry", "finest", "growth", "d",
                                                         "layer_depth", "end", "per_doubling",
                                                         "first_step"),
    "fickcam.diffusion.models.plane.expansion_error_at": ("ages",),
    "fickcam.diffusion.models.plane.plan_plane": ("problem", "caps"),
    "fickcam.diffusion.models.plane.solve_plane": ("problem",),
    "fickcam.diffusion.models.plane.PrismSuperposition": ("diffusivity", "exposure", "times",
                                                         "geometry"),
    "fickcam.diffusion.models.plane.extension": ("result", "superposed"),
    "fickcam.diffusion.exact.separable.exact_available": ("geometry",),
    "fickcam.diffusion.exact.separable.step_response": ("geometry", "pre_exponential", "tau",
                                                        "surface_layer_depth"),
    "fickcam.diffusion.exact.separable.step_field": ("geometry", "pre_exponential", "tau",
                                                     "points"),
    "fickcam.diffusion.exact.separable.saturation_tau": ("geometry", "pre_exponential"),
    "fickcam.diffusion.exact.series.ierfc": ("x",),
    "fickcam.diffusion.exact.series.sheet_interval_mean_images": ("z1", "z2", "fourier"),
    "fickcam.diffusion.exact.series.sheet_interval_mean_series": ("z1", "z2", "fourier"),
    "fickcam.diffusion.exact.series.sheet_interval_mean": ("z1", "z2", "fourier"),
    "fickcam.diffusion.exact.series.sheet_series_remainder": ("fourier", "n_terms"),
    "fickcam.diffusion.exact.series.bessel_roots": ("count",),
    "fickcam.diffusion.exact.series.roots_for": ("fourier_min",),
    "fickcam.diffusion.exact.series.cylinder_short_coefficients": (),
    "fickcam.diffusion.exact.series.cylinder_uptake_short": ("fourier",),
    "fickcam.diffusion.exact.series.cylinder_core_deficit": ("rho", "fourier", "roots"),
    "fickcam.diffusion.exact.series.cylinder_core_mean": ("rho", "fourier_r"),
    "fickcam.diffusion.exact.series.cylinder_profile": ("r", "fourier_r"),
    "fickcam.diffusion.exact.two_phase.TwoPhaseUptake": ("total", "free", "bound"),
    "fickcam.diffusion.exact.two_phase.equilibrium_shares": ("gamma", "beta"),
    "fickcam.diffusion.exact.two_phase.Propagator": ("a11", "a12", "a21", "a22", "m", "c", "d",
                                                     "c_int", "d_int"),
    "fickcam.diffusion.exact.two_phase.exchange_propagator": ("rate", "t", "gamma", "beta"),
    "fickcam.diffusion.exact.two_phase.two_phase_mode_deficit": ("rate", "t", "gamma", "beta"),
    "fickcam.diffusion.exact.two_phase.two_phase_sheet_profile": ("z", "t", "diffusivity",
                                                                  "thickness", "gamma", "beta",
                                                                  "tolerance"),
    "fickcam.diffusion.accuracy.error_model.space_error": ("earliest",),
    "fickcam.diffusion.accuracy.error_model.CellCaps": ("slab", "axisymmetric", "solid",
                                                        "plane"),
    "fickcam.diffusion.accuracy.grid_convergence.taken": (),
    "fickcam.diffusion.accuracy.grid_convergence.three_levels": (),
    "fickcam.diffusion.operators.discretisation.Discretisation": ("volumes", "stiffness",
                                                                  "boundary", "mean_weights",
                                                                  "layer_weights",
                                                                  "coordinates"),
    "fickcam.diffusion.operators.fipy_backend.interval_mesh": ("dx", "nx"),
    "fickcam.diffusion.operators.fipy_backend.cylindrical_mesh": ("radial", "axial",
                                                                  "inner_radius"),
    "fickcam.diffusion.operators.fipy_backend.box_mesh": ("axes",),
    "fickcam.diffusion.operators.grading.growth_rate": ("tolerance",),
    "fickcam.diffusion.operators.grading.graded_widths": ("length", "finest", "growth"),
    "fickcam.diffusion.operators.grids.interval_overlap": ("lo", "hi", "a", "b"),
    "fickcam.diffusion.operators.grids.normalised": ("weights",),
    "fickcam.diffusion.operators.grids.sheet": ("thickness", "cells", "layer_depth"),
    "fickcam.diffusion.operators.grids.sheet_mesh": ("cells",),
    "fickcam.diffusion.operators.grids.grid_axis": ("widths", "scale"),
    "fickcam.diffusion.operators.grids.disc": ("outer_radius", "thickness", "inner_radius",
                                               "radial_cells", "axial_cells", "layer_depth",
                                               "radial_d", "axial_d", "widths"),
    "fickcam.diffusion.operators.grids.disc_mesh": ("outer_radius", "thickness",
                                                    "inner_radius", "radial_d", "axial_d",
                                                    "widths"),
    "fickcam.diffusion.operators.grids.bar": ("length", "width", "thickness", "cells",
                                              "layer_depth", "d", "widths"),
    "fickcam.diffusion.operators.grids.near_faces": ("widths", "size", "layer_depth"),
    "fickcam.diffusion.operators.p1.cotangent_stiffness": ("points",),
    "fickcam.diffusion.operators.p1.consistent_mass": ("points",),
    "fickcam.diffusion.operators.p1.p1_operator": ("points", "coordinates"),
    "fickcam.diffusion.operators.p1.layer_weights": ("points", "distance", "depth"),
    "fickcam.diffusion.operators.p1.plane_operator": ("part", "layer_depth", "d"),
    "fickcam.diffusion.operators.prisms.prism": ("tess", "thickness", "z_widths",
                                                 "layer_share", "d"),
    "fickcam.diffusion.operators.prisms.planar": ("tess", "scale", "layer_share"),
    "fickcam.diffusion.operators.prisms.sides_of_cells": ("tess",),
    "fickcam.diffusion.operators.prisms.prism_mesh": ("tess", "scale", "z_nodes"),
    "fickcam.diffusion.operators.symmetry_cuts.halved_axes": ("geometry",),
    "fickcam.diffusion.operators.symmetry_cuts.half": ("widths",),
    "fickcam.diffusion.operators.symmetry_cuts.mirrored": ("geometry", "d", "cells", "finest",
                                                           "growth", "layer_depth"),
    "fickcam.diffusion.operators.symmetry_cuts.octant": ("bar", "d", "cells", "finest",
                                                         "growth", "layer_depth"),
    "fickcam.diffusion.operators.sizing.Layout": ("space_error", "finest", "growth"),
    "fickcam.diffusion.operators.sizing.unknowns": ("cells",),
    "fickcam.diffusion.operators.sizing.extents": ("geometry", "d"),
    "fickcam.diffusion.operators.sizing.exposed_ends": (),
    "fickcam.diffusion.operators.sizing.uniform": ("extents", "accuracy", "t_lo", "cap",
                                                   "space_error"),
    "fickcam.diffusion.operators.sizing.graded_error": ("finest", "growth", "t_lo",
                                                        "space_error"),
    "fickcam.diffusion.operators.sizing.graded_design": ("accuracy", "t_lo", "space_error"),
    "fickcam.diffusion.operators.sizing.axis_widths": ("extents", "finest", "growth"),
    "fickcam.diffusion.operators.sizing.physical_widths": ("geometry", "extents", "d",
                                                           "finest", "growth"),
    "fickcam.diffusion.operators.sizing.graded": ("extents", "accuracy", "t_lo", "cap",
                                                  "space_error"),
    "fickcam.diffusion.operators.sizing.choose": ("geometry", "extents", "accuracy", "t_lo",
                                                  "cap", "space_error"),
    "fickcam.diffusion.operators.sizing.planform_cells": ("part", "finest", "growth",
                                                          "stretch"),
    "fickcam.diffusion.operators.sizing.prism_widths": ("finest", "growth"),
    "fickcam.diffusion.operators.sizing.prism_layout": ("geometry", "d", "accuracy", "t_lo",
                                                        "cap", "space_error"),
    "fickcam.diffusion.operators.sizing.widest_row": ("part", "stretch"),
    "fickcam.diffusion.operators.sizing.estimated_prism_cells": ("part", "finest", "growth",
                                                                 "stretch"),
    "fickcam.diffusion.planform.polygon.turning_angles": ("loop",),
    "fickcam.diffusion.planform.polygon.corners_of": ("loop",),
    "fickcam.diffusion.planform.polygon.resample_loop": ("loop", "spacing"),
    "fickcam.diffusion.planform.polygon.resample_polyline": ("px", "py", "spacing"),
    "fickcam.diffusion.planform.polygon.circle": ("cx", "cy", "radius", "spacing"),
    "fickcam.diffusion.planform.polygon.loop_length": ("loop",),
    "fickcam.diffusion.planform.polygon.edge_normals": ("points",),
    "fickcam.diffusion.planform.polygon.vertex_normals": ("points",),
    "fickcam.diffusion.planform.polygon.Wall": ("samples", "normals"),
    "fickcam.diffusion.planform.polygon.polygon_segments": ("px", "py"),
    "fickcam.diffusion.planform.polygon.inside_polygon": ("query", "segments"),
    "fickcam.diffusion.planform.polygon.triangle_areas": ("points",),
    "fickcam.diffusion.planform.polygon.unique_edges": (),
    "fickcam.diffusion.planform.polygon.circumcentres": ("points",),
    "fickcam.diffusion.planform.polygon.centre_offsets": ("points", "centres"),
    "fickcam.diffusion.planform.polygon.segment_distance": ("query", "segments"),
    "fickcam.diffusion.planform.polygon.drop_unused": ("points",),
    "fickcam.diffusion.planform.outline.Outline": ("part", "boundary", "contact"),
    "fickcam.diffusion.planform.outline.inside_part": ("part", "x", "y"),
    "fickcam.diffusion.planform.outline.outline": ("part", "spacing"),
    "fickcam.diffusion.planform.outline.outline_extent": ("part",),
    "fickcam.diffusion.planform.outline.arc_circle": ("cx", "cy", "radius", "spacing"),
    "fickcam.diffusion.planform.outline.boundary_loops": ("part", "spacing"),
    "fickcam.diffusion.planform.outline.narrow_boss_outline": ("length", "half", "radius",
                                                               "spacing"),
    "fickcam.diffusion.planform.short_time.ShortTime": ("area", "perimeter", "curvature_square",
                                                        "contact_depths", "chords"),
    "fickcam.diffusion.planform.short_time.layer_integrals": ("z",),
    "fickcam.diffusion.planform.short_time.corner_coefficient": ("gamma",),
    "fickcam.diffusion.planform.short_time.expansion_of": ("part", "d", "layer_depth"),
    "fickcam.diffusion.planform.short_time.weighted": ("indicator", "weight"),
    "fickcam.diffusion.planform.short_time.sheet_fraction": ("tau",),
    "fickcam.diffusion.planform.short_time.short_time": ("part", "scale", "layer_depth",
                                                         "spacing"),
    "fickcam.diffusion.planform.short_time.outline_chords": ("part", "scale", "spacing"),
    "fickcam.diffusion.planform.short_time.inward_chords": ("loops", "spacing"),
    "fickcam.diffusion.planform.admissible.Tessellation": ("points", "centres", "outline",
                                                           "contact", "stretch"),
    "fickcam.diffusion.planform.admissible.tessellation": ("points", "outline", "contact",
                                                           "stretch"),
    "fickcam.diffusion.planform.admissible.admissible": ("stretch", "mirrors"),
    "fickcam.diffusion.planform.admissible.refine": (),
    "fickcam.diffusion.planform.admissible.cell_areas": (),
    "fickcam.diffusion.planform.admissible.cell_loops": (),
    "fickcam.diffusion.planform.admissible.band_share": ("depth",),
    "fickcam.diffusion.planform.admissible.linear_sublevel_fraction": ("values", "level"),
    "fickcam.diffusion.planform.cell_moments.sublevel_moments": ("corners", "values", "level"),
    "fickcam.diffusion.planform.cell_moments.gradient_matrix": (),
    "fickcam.diffusion.planform.cell_moments.contact_distance": ("depth",),
    "fickcam.diffusion.planform.cell_moments.corrected_weights": ("depth",),
    "fickcam.diffusion.planform.triangles.fanned": ("points",),
    "fickcam.diffusion.planform.triangles.row_spacings": ("finest", "growth", "coarsest"),
    "fickcam.diffusion.planform.triangles.graded_points": ("loops", "finest", "growth",
                                                           "coarsest"),
    "fickcam.diffusion.planform.triangles.hex_lattice": ("lo", "hi", "spacing"),
    "fickcam.diffusion.planform.triangles.delaunay_inside": ("points", "finest"),
    "fickcam.diffusion.planform.triangles.angles": ("points",),
    "fickcam.diffusion.planform.triangles.GradedMesh": ("points",),
    "fickcam.diffusion.planform.triangles.graded_mesh": ("loops", "finest", "growth", "coarsest"),
    "fickcam.diffusion.planform.triangles.Triangulation": ("points", "contact_distance",
                                                           "contact"),
    "fickcam.diffusion.planform.triangles.triangulate": ("part", "spacing", "growth", "stretch"),
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
             "fickcam.diffusion.exact.modes.", "fickcam.diffusion.dispatch.",
             "fickcam.diffusion.models.", "fickcam.diffusion.exact.",
             "fickcam.diffusion.accuracy.", "fickcam.diffusion.operators.",
             "fickcam.diffusion.planform.")


@pytest.mark.parametrize("dotted", sorted(d for d in ENTRY_POINTS if d.startswith(RETURNING)
                                          and not inspect.isclass(_entry_point(d))))
def test_entry_point_documents_what_it_returns(dotted):
    assert "Returns" in sections(_entry_point(dotted).__doc__), f"{dotted}: no Returns section"
