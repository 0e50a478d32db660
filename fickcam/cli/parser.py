"""The ``fickcam`` command line's arguments: one argparse subcommand per
command, each with a summary, a description and examples in its --help. What each
command does is in :mod:`fickcam.cli.commands`; :mod:`fickcam.cli.main` runs them.
"""
from __future__ import annotations

import argparse

from .._version import __version__


def _command(sub, name: str, summary: str, description: str, *examples: str):
    """A subcommand whose --help says what it does and shows how it is used."""
    command = sub.add_parser(name, help=summary, description=description,
                             epilog="examples:\n" + "\n".join(f"  {e}" for e in examples),
                             formatter_class=argparse.RawDescriptionHelpFormatter)
    _verbosity(command)
    return command


def _verbosity(command) -> None:
    """-v and -q, on every command (:mod:`fickcam.messages`: errors, warnings, notes)."""
    group = command.add_argument_group("messages on stderr")
    group.add_argument("-v", "--verbose", action="count", default=0,
                       help="also debug details of the work")
    group.add_argument("-q", "--quiet", action="count", default=0,
                       help="errors only on stderr: no warnings, notes or progress bar (the "
                            "summary on stdout stays); -qq: no summary either")


def build_parser() -> argparse.ArgumentParser:
    """The ``fickcam`` argument parser: every command, its options, help and examples.

    Returns
    -------
    argparse.ArgumentParser
        A new parser (the command line, the generated command-line reference and the tests
        build theirs from here).
    """
    parser = argparse.ArgumentParser(
        prog="fickcam",
        description="Moisture uptake in polymer/composite cams, followers and four-bar "
                    "linkages, and the mechanism drift it causes.",
        epilog="start with: fickcam examples --copy scenes && fickcam run scenes/singh2017_cam.yaml",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"fickcam {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks of internal errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for add in (_scene_commands, _result_commands, _reference_commands, _design_commands,
                _sweep_command):
        add(sub)
    return parser


def _scene_commands(sub) -> None:
    """run and check: a scene in, a result or a plan out."""
    run = _command(sub, "run", "run a scene and write its result file",
                   "Age the parts of a scene (diffusion, material state, mechanisms at every "
                   "ageing time, and the design for comparison), write the result file "
                   "atomically and print a summary: each key output as design -> t = 0 -> end.",
                   "fickcam run configs/singh2017_cam.yaml -o outputs/cam.h5",
                   "fickcam run scene.yaml --accuracy 1e-4 --quiet")
    run.add_argument("scene", help="scene file (YAML)")
    run.add_argument("-o", "--output", help="result file (default: the scene's outputs.file)")
    run.add_argument("--accuracy", help="override diffusion.accuracy (in (0, 0.1])")

    check = _command(sub, "check", "validate a scene and print the plan",
                     "Validate a scene without running it and print the plan the run uses: "
                     "parts, the diffusion model per part, cells, steps, estimated error.",
                     "fickcam check configs/singh2017_cam.yaml")
    check.add_argument("scene", help="scene file (YAML)")


def _result_commands(sub) -> None:
    """query, export and plot: a result file in."""
    query = _command(sub, "query", "values of a variable from a result file",
                     "Print the values of one result variable, optionally at an ageing time "
                     "(interpolated between stored times), a part, link or angle, or its drift "
                     "against the design or t = 0. On a sweep result the varied values are "
                     "shown beside each case.",
                     'fickcam query outputs/cam.h5 lift --time "45 d"',
                     "fickcam query outputs/cam.h5 lift --drift design",
                     'fickcam query outputs/cam.h5 contact_force --time 30d --cam-angle "120 deg" '
                     '--format json',
                     "fickcam query outputs/cam.h5 lift --units um --format csv > lift.csv")
    query.add_argument("result", help="result file (.h5)")
    query.add_argument("variable", help="a variable name (fickcam schema lists them)")
    query.add_argument("--time", help='ageing time with its unit, e.g. "30 d", "6 months" (a bare '
                       'number is seconds, as in a scene, and refused when it is almost '
                       'certainly a slip: 45 -> did you mean "45 d"?)')
    query.add_argument("--part")
    query.add_argument("--link")
    for mechanism, example in (("cam", "120 deg"), ("crank", "90 deg")):
        query.add_argument(f"--{mechanism}-angle", metavar="ANGLE",
                           help=f'{mechanism} angle with its unit, e.g. "{example}" (a bare '
                                "number is refused: degrees or radians?)")
    query.add_argument("--format", choices=("table", "csv", "json"), default="table")
    query.add_argument("--units", help="unit to show the values in, e.g. um, MPa, degF (default: "
                                       "the variable's display unit, as in the run summary)")
    query.add_argument("--drift", choices=("design", "start"),
                       help="the change from the as-designed value (dry, reference temperature) "
                            "or from the first ageing time, instead of the value")

    export = _command(sub, "export", "export a result as CSV, netCDF or JSON",
                      "Write a result (or some of its variables) for plotting elsewhere: tidy CSV "
                      "(one column per dimension plus value), netCDF or JSON.",
                      "fickcam export outputs/cam.h5 --format csv -o cam.csv --variables lift jump_speed")
    export.add_argument("result", help="result file (.h5)")
    export.add_argument("--format", choices=("csv", "netcdf", "json"), required=True)
    export.add_argument("-o", "--output", required=True)
    export.add_argument("--variables", nargs="+")

    plot = _command(sub, "plot", "PNG figures of a result",
                    "Draw the figures a result has data for (uptake, cam kinematics and dynamics, "
                    "linkage, moisture fields, elastic deflection and swelling stress, or a "
                    "sweep's outputs against its varied values).",
                    "fickcam plot outputs/cam.h5 -o outputs/cam-plots",
                    "fickcam plot outputs/sweep.h5 --kind sweep")
    plot.add_argument("result", help="result file (.h5)")
    plot.add_argument("-o", "--outdir", default=None, help="folder (default: next to the result)")
    plot.add_argument("--kind", default="all",
                      choices=("uptake", "kinematics", "dynamics", "vibration", "linkage", "fields",
                               "elastic", "limits", "sweep", "all"))


def _reference_commands(sub) -> None:
    """bench, materials, schema and examples: what fickcam knows, nothing of the user's."""
    bench = _command(sub, "bench", "the diffusion speed/accuracy trade",
                     "Measure each diffusion model's wall time and error against exact solutions "
                     "on reference geometries (about 3 min; --quick about 10 s); --records: the "
                     "cost of hourly weather records against a constant climate, and a solid "
                     "disc's error through a whole TMY3 year against its exact modes.",
                     "fickcam bench --quick", "fickcam bench --records")
    bench.add_argument("--quick", action="store_true",
                       help="each geometry at its coarsest target, no 3-D solid rows (seconds)")
    bench.add_argument("--records", action="store_true",
                       help="cost of 1, 3, 12 months of hourly weather against a constant climate, "
                       "then a year's accuracy (--quick: 1 and 3 months, no accuracy)")

    materials = _command(sub, "materials", "the built-in material library with sources",
                         "List the built-in materials (key values and sources), or show one "
                         "entry in full: every value, the diffusivity and saturation laws, sources.",
                         "fickcam materials", "fickcam materials 8551-7")
    materials.add_argument("name", nargs="?", help="one library name (fibre, matrix, plastic, metal)")
    _command(sub, "schema", "the result variables (name, dims, units)",
             "Print the table of result variables (name, dims, units, meaning, as-designed row) "
             "as Markdown.", "fickcam schema")
    examples = _command(sub, "examples", "list or copy the example scenes",
                        "List the example scenes shipped with fickcam, print one, or copy them "
                        "into a folder to edit and run.",
                        "fickcam examples", "fickcam examples singh2017_cam > my_cam.yaml",
                        "fickcam examples --copy scenes")
    examples.add_argument("names", nargs="*", help="example names (print one; with --copy: copy these)")
    examples.add_argument("--copy", metavar="DIR", help="copy the examples into DIR")


def _design_commands(sub) -> None:
    """compensate, profile, fit and size: dimensions and materials to make."""
    _compensate_command(sub)
    _making_commands(sub)


def _compensate_command(sub) -> None:
    """compensate: the dry dimensions to make."""
    compensate = _command(
        sub, "compensate", "the dimensions to make so that the mechanism holds its design",
        "Give the dry dimensions at the reference temperature to make so that the mechanism has "
        "its design geometry at an ageing time (--at) or stays closest to it over a service "
        "window (--over, minimax); print them per part, the scene's limits over the life (the "
        "window, or delivery to the end of the history for --at) as designed and compensated, "
        "and the drift of the key outputs; write a scene that makes them (a cam in the form it "
        "was given: eccentric disc, base circle and motion, or points).",
        'fickcam compensate configs/singh2017_cam.yaml --over "0 d" "60 d" --points -o cam_made.yaml',
        'fickcam compensate configs/eccentric_cam.yaml --at "120 d" --profile disc.dxf',
        'fickcam compensate configs/fourbar_r914_humid.yaml --at "180 d" --keep-limits',
        'fickcam compensate configs/fourbar_r914_humid.yaml --over "30 d" "365 d" --plot band.png')
    compensate.add_argument("scene")
    when = compensate.add_mutually_exclusive_group(required=True)
    when.add_argument("--at", metavar="TIME", help='ageing time with units, e.g. "60 d" (a bare '
                      'number is seconds, as in a scene, and refused when it is almost certainly '
                      'a slip: 45 -> did you mean "45 d"?)')
    when.add_argument("--over", nargs=2, metavar=("T1", "T2"),
                      help='a service window, e.g. 0 "60 d": minimise the largest deviation over '
                           "it (times as --at; 0 needs no unit)")
    compensate.add_argument("--keep-limits", action="store_true",
                            help="with --at: if that breaks one of the scene's limits between "
                                 "delivery and the end of the history, make the part for that "
                                 "whole life instead (minimax over it)")
    compensate.add_argument("--points", action="store_true",
                            help="make a cam given by its parameters as points (its working "
                                 "profile, x and y compensated apart): for a cam that swells "
                                 "anisotropically, such as a unidirectional laminate")
    compensate.add_argument("-o", "--output", help="compensated scene (default: "
                                                   "<scene>_compensated.yaml here)")
    compensate.add_argument("--profile", metavar="PATH",
                            help="also write the made cam's dry working profile for manufacture, "
                                 "in mm: PATH.csv, or PATH.dxf (needs the dxf extra)")
    compensate.add_argument("--accuracy", help="override diffusion.accuracy (in (0, 0.1])")
    compensate.add_argument("--plot", metavar="PNG", help="also draw the drift of every "
                            "deviation limit against its band, as designed and compensated")


def _making_commands(sub) -> None:
    """profile, fit and size: a profile for manufacture, a material, a base circle."""
    profile = _command(sub, "profile", "a cam's dry working profile for manufacture (CSV or DXF)",
                       "Write the cam's dry working profile at the reference temperature, in mm, "
                       "as CSV (x [mm], y [mm]) or as a closed DXF polyline, by the output's suffix.",
                       "fickcam profile configs/singh2017_cam.yaml -o cam.dxf")
    profile.add_argument("scene")
    profile.add_argument("-o", "--output", required=True, help="PATH.csv or PATH.dxf")
    profile.add_argument("--points", type=int, default=3600, help="points round the profile")

    outline = _command(sub, "outline", "a cam result's aged outline at an ageing time (CSV or DXF)",
                       "Write the cam's aged working profile at an ageing time, as the result "
                       "stores it, in mm about the cam's axis: CSV (x [mm], y [mm]) or a closed "
                       "DXF polyline on a layer named for the time (AGED_45d), with the axis a "
                       "point on layer AXIS, to overlay on the drawing. Between stored ageing "
                       "times the outline is interpolated in sqrt(t) and the estimated error "
                       "printed (with fewer than three stored times it is refused).",
                       'fickcam outline outputs/cam.h5 --time "60 d" -o aged.dxf',
                       'fickcam outline outputs/cam.h5 --time "45 d" -o aged.csv')
    outline.add_argument("result", help="result file (.h5) of a scene with a cam")
    outline.add_argument("--time", required=True,
                         help='ageing time with its unit, e.g. "60 d" (a bare number is '
                              'seconds, as in a scene, and refused when it is almost '
                              'certainly a slip: 45 -> did you mean "45 d"?)')
    outline.add_argument("-o", "--output", required=True, help="PATH.csv or PATH.dxf")

    fit = _command(sub, "fit", "calibrate a material from ASTM D5229 weight-gain data",
                   "Fit the diffusivity (D0, Ea) and saturation law of a material to weight-gain "
                   "coupon data (ASTM D5229, one row per weighing) and write a scene-ready "
                   "materials: block.",
                   "fickcam fit coupons.csv --matrix 8551-7 -o fitted.yaml --plot fit.png",
                   "fickcam fit laminate.csv --matrix 3502 --fiber T300 --fiber-volume-fraction 0.6 -o fitted.yaml")
    fit.add_argument("data", help="weight-gain CSV (one row per weighing, units in the header)")
    fit.add_argument("--matrix", required=True, help="library matrix (resin) of the coupons")
    fit.add_argument("--fiber", help="library fibre of composite coupons")
    fit.add_argument("--fiber-volume-fraction",
                     help="fibre volume fraction of the coupons, e.g. 0.6 (a fraction, as in a "
                          "scene)")
    fit.add_argument("--name", help="material name in the YAML (default: the CSV's stem)")
    fit.add_argument("-o", "--output", required=True, help="YAML file with the materials: block")
    fit.add_argument("--plot", help="PNG of the data, fitted curves and residuals")

    size = _command(sub, "size", "smallest base circle meeting pressure-angle and curvature limits",
                    "Find the smallest base circle radius whose cam keeps the pressure angle "
                    "and the working radius of curvature within the limits, dry and at the "
                    "strains of its ageing (Norton, Design of Machinery, 2012, sec. 8.7). The "
                    "search is geometry alone: one run of the scene gives the aged strains, a "
                    "run at the answer says how much the moisture changes with the size "
                    "(at most 5 runs).",
                    "fickcam size configs/singh2017_cam.yaml",
                    "fickcam size scene.yaml --pressure-angle 25deg --radius-of-curvature 5mm")
    size.add_argument("scene")
    size.add_argument("--pressure-angle", default="30 deg",
                      help="largest |pressure angle| with its unit (30 deg; a bare number is "
                           "refused: degrees or radians?)")
    size.add_argument("--radius-of-curvature", default=None,
                      help="smallest convex working radius of curvature with its unit (default: "
                           "the roller's radius for a roller follower, Norton's rule; for a flat "
                           "face the radius its Hertz contact stress allows; a positive radius "
                           "for a knife; a bare number is metres, as in a scene)")


def _sweep_command(sub) -> None:
    """sweep: many scenes at once on dask.distributed."""
    sweep = _command(sub, "sweep", "many scenes on dask.distributed",
                     "Run the variants of a scene a sweep file describes (a grid or Monte Carlo "
                     "draws) on a local dask cluster or a running scheduler, write one result "
                     "with a case dimension and print a table of the cases.",
                     "fickcam sweep configs/sweep_singh2017_climate.yaml -o outputs/climate.h5",
                     "fickcam sweep sweep.yaml --scheduler tcp://10.0.0.5:8786 -o out.h5")
    sweep.add_argument("sweep", help="sweep file (YAML)")
    group = sweep.add_mutually_exclusive_group()
    group.add_argument("--workers", type=int, default=None, help="local worker processes")
    group.add_argument("--scheduler", help="address of a running dask scheduler, tcp://HOST:PORT")
    sweep.add_argument("-o", "--output", required=True)

