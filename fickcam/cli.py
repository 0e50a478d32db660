"""The ``fickcam`` command line (SPEC.md §2).

Exit status: 0 success; 2 bad input (one line per problem on stderr, no
traceback); 1 anything else (one line; ``--debug`` shows the traceback).
"""
from __future__ import annotations

import argparse
import atexit
import gc
import logging
import sys
from pathlib import Path

from ._version import __version__
from .errors import FickcamError, InputError, SceneError

log = logging.getLogger("fickcam")


def _command(sub, name: str, summary: str, description: str, *examples: str):
    """A subcommand whose --help says what it does and shows how it is used."""
    return sub.add_parser(name, help=summary, description=description,
                          epilog="examples:\n" + "\n".join(f"  {e}" for e in examples),
                          formatter_class=argparse.RawDescriptionHelpFormatter)


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="fickcam",
        description="Moisture uptake in polymer/composite cams, followers and four-bar "
                    "linkages, and the mechanism drift it causes.",
        epilog="start with: fickcam examples --copy scenes && fickcam run scenes/singh2017_cam.yaml",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"fickcam {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks of internal errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    run = _command(sub, "run", "run a scene and write its result file",
                   "Age the parts of a scene (diffusion, material state, mechanisms at every "
                   "ageing time, and the design for comparison), write the result file "
                   "atomically and print a summary: each key output as design -> t = 0 -> end.",
                   "fickcam run configs/singh2017_cam.yaml -o outputs/cam.h5",
                   "fickcam run scene.yaml --accuracy 1e-4 --quiet")
    run.add_argument("scene", help="scene file (YAML)")
    run.add_argument("-o", "--output", help="result file (default: the scene's outputs.file)")
    run.add_argument("--accuracy", type=float, help="override diffusion.accuracy")
    run.add_argument("--quiet", action="store_true", help="no progress bar, summary or notices")

    check = _command(sub, "check", "validate a scene and print the plan",
                     "Validate a scene without running it and print the plan the run uses: "
                     "parts, the diffusion model per part, cells, steps, estimated error.",
                     "fickcam check configs/singh2017_cam.yaml")
    check.add_argument("scene", help="scene file (YAML)")

    query = _command(sub, "query", "values of a variable from a result file",
                     "Print the values of one result variable, optionally at an ageing time "
                     "(interpolated between stored times), a part, link or angle, or its drift "
                     "against the design or t = 0. On a sweep result the varied values are "
                     "shown beside each case.",
                     'fickcam query outputs/cam.h5 lift --time "45 d"',
                     "fickcam query outputs/cam.h5 lift --drift design",
                     "fickcam query outputs/cam.h5 contact_force --time 30d --cam-angle 120 --format json")
    query.add_argument("result", help="result file (.h5)")
    query.add_argument("variable", help="a variable name (fickcam schema lists them)")
    query.add_argument("--time", help='ageing time with its unit, e.g. "30 d", "6 months" (a bare number is refused)')
    query.add_argument("--part")
    query.add_argument("--link")
    query.add_argument("--cam-angle", type=float, help="degrees")
    query.add_argument("--crank-angle", type=float, help="degrees")
    query.add_argument("--format", choices=("table", "csv", "json"), default="table")
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

    bench = _command(sub, "bench", "the diffusion speed/accuracy trade",
                     "Measure each diffusion model's wall time and error against exact solutions "
                     "on reference geometries (about 3 min; --quick about 10 s); --records: the "
                     "cost of hourly weather records against a constant climate, and a solid "
                     "disc's error through a whole TMY3 year against its exact modes.",
                     "fickcam bench --quick", "fickcam bench --records")
    bench.add_argument("--quick", action="store_true",
                       help="each geometry at its coarsest target, no 3-D solid rows (seconds)")
    bench.add_argument("--quiet", action="store_true", help="no progress bar, only the table")
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

    compensate = _command(
        sub, "compensate", "the dimensions to make so that the mechanism holds its design",
        "Give the dry dimensions at the reference temperature to make so that the mechanism has "
        "its design geometry at an ageing time (--at) or stays closest to it over a service "
        "window (--over, minimax); print them per part with the drift of the key outputs before "
        "and after, and write a scene that makes them (a cam as profile points, CSV and DXF).",
        'fickcam compensate configs/singh2017_cam.yaml --at "60 d" -o cam_made.yaml',
        'fickcam compensate configs/fourbar_r914_humid.yaml --over "30 d" "365 d" --plot band.png')
    compensate.add_argument("scene")
    when = compensate.add_mutually_exclusive_group(required=True)
    when.add_argument("--at", metavar="TIME", help='ageing time with units, e.g. "60 d"')
    when.add_argument("--over", nargs=2, metavar=("T1", "T2"),
                      help="a service window: minimise the largest deviation over it")
    compensate.add_argument("-o", "--output", help="compensated scene (default: "
                                                   "<scene>_compensated.yaml here)")
    compensate.add_argument("--accuracy", type=float, help="override diffusion.accuracy")
    compensate.add_argument("--plot", metavar="PNG", help="also draw the drift of every "
                            "deviation limit against its band, as designed and compensated")

    profile = _command(sub, "profile", "a cam's dry working profile for manufacture (CSV or DXF)",
                       "Write the cam's dry working profile at the reference temperature, in mm, "
                       "as CSV (x [mm], y [mm]) or as a closed DXF polyline, by the output's suffix.",
                       "fickcam profile configs/singh2017_cam.yaml -o cam.dxf")
    profile.add_argument("scene")
    profile.add_argument("-o", "--output", required=True, help="PATH.csv or PATH.dxf")
    profile.add_argument("--points", type=int, default=3600, help="points round the profile")

    fit = _command(sub, "fit", "calibrate a material from ASTM D5229 weight-gain data",
                   "Fit the diffusivity (D0, Ea) and saturation law of a material to weight-gain "
                   "coupon data (ASTM D5229, one row per weighing) and write a scene-ready "
                   "materials: block.",
                   "fickcam fit coupons.csv --matrix 8551-7 -o fitted.yaml --plot fit.png",
                   "fickcam fit laminate.csv --matrix 3502 --fiber T300 --fiber-volume-fraction 0.6 -o fitted.yaml")
    fit.add_argument("data", help="weight-gain CSV (one row per weighing, units in the header)")
    fit.add_argument("--matrix", required=True, help="library matrix (resin) of the coupons")
    fit.add_argument("--fiber", help="library fibre of composite coupons")
    fit.add_argument("--fiber-volume-fraction", type=float, help="fibre volume fraction of the coupons")
    fit.add_argument("--name", help="material name in the YAML (default: the CSV's stem)")
    fit.add_argument("-o", "--output", required=True, help="YAML file with the materials: block")
    fit.add_argument("--plot", help="PNG of the data, fitted curves and residuals")

    size = _command(sub, "size", "smallest base circle meeting pressure-angle and curvature limits",
                    "Find the smallest base circle radius whose dry cam keeps the pressure angle "
                    "and the working radius of curvature within the limits (Norton sec. 8.7), "
                    "then run the scene with it and say whether the aged cam still meets them "
                    "at the end of the ageing.",
                    "fickcam size configs/singh2017_cam.yaml",
                    "fickcam size scene.yaml --pressure-angle 25deg --radius-of-curvature 5mm")
    size.add_argument("scene")
    size.add_argument("--pressure-angle", default="30 deg", help="largest |pressure angle| (30 deg)")
    size.add_argument("--radius-of-curvature", default="0 mm",
                      help="smallest convex working radius of curvature (0: no cusp or undercut)")

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
    sweep.add_argument("--quiet", action="store_true")
    return parser


def _cmd_run(args) -> int:
    from .scene import load_scene
    from .reporting import summary
    from .simulate import run
    from .store import save

    scene = load_scene(args.scene)
    if args.whole_process:
        gc.freeze()  # the modules loaded so far live to the end: the run's collections skip them
    if args.accuracy is not None and not (0 < args.accuracy <= 0.1):
        raise InputError("--accuracy must lie in (0, 0.1]")
    output = Path(args.output) if args.output else default_output(scene)
    ds = run(scene, accuracy=args.accuracy, progress=not args.quiet)
    save(ds, output)
    if not args.quiet:
        print(summary(ds, notices=False))  # the run has logged them on stderr
        print(f"wrote {output}")
    return 0


def default_output(scene) -> Path:
    """The scene's ``outputs.file`` or ``outputs/<name>.h5`` (relative to the working folder)."""
    if scene.model.outputs.file:
        return Path(scene.model.outputs.file)
    return Path("outputs") / f"{scene.name}.h5"


def _cmd_check(args) -> int:
    from .scene import load_scene
    from .reporting import describe_plan

    scene = load_scene(args.scene)
    print(describe_plan(scene))
    return 0


def _cmd_size(args) -> int:
    import dataclasses
    import math

    from .cam import design_from_scene
    from .cam.sizing import Limits, aged_check, smallest_base_circle
    from .scene import load_scene
    from .simulate import run
    from .units import to_si

    scene = load_scene(args.scene)
    if scene.model.cam is None:
        raise InputError("the scene has no cam: section to size")
    try:
        limits = Limits(to_si(args.pressure_angle, "angle"), to_si(args.radius_of_curvature, "length"))
        sizes = smallest_base_circle(design_from_scene(scene.model.cam), limits)
    except ValueError as exc:
        raise InputError(str(exc)) from None
    radius = sizes["base_circle_radius"]
    design = design_from_scene(scene.model.cam)
    print(f"{scene.name}: smallest base circle radius {radius * 1e3:.4f} mm "
          f"(pressure angle <= {math.degrees(limits.pressure_angle):g} deg needs "
          f"{sizes['pressure_angle'] * 1e3:.4f} mm; radius of curvature >= "
          f"{limits.radius_of_curvature * 1e3:g} mm needs {sizes['radius_of_curvature'] * 1e3:.4f} mm); "
          f"the scene has {scene.model.cam.base_circle_radius * 1e3:.4f} mm")
    cam = scene.model.cam.model_copy(update={"base_circle_radius": radius})
    ds = run(dataclasses.replace(scene, model=scene.model.model_copy(update={"cam": cam})))
    print(aged_check(ds, limits, design.follower_kind))
    return 0


def _cmd_query(args) -> int:
    from .reporting import limit_line
    from .query import format_result, select
    from .store import open_result

    ds = open_result(args.result)
    array = select(ds, args.variable, time=args.time, part=args.part, link=args.link,
                   cam_angle=args.cam_angle, crank_angle=args.crank_angle, against=args.drift)
    print(format_result(array, args.variable, args.format, args.drift,
                        limit=limit_line(ds, args.variable)))
    return 0


def _cmd_export(args) -> int:
    from .export import export
    from .store import open_result

    ds = open_result(args.result)
    path = export(ds, args.output, args.format, args.variables)
    print(f"wrote {path}")
    return 0


def _cmd_plot(args) -> int:
    from .plotting import plot
    from .store import open_result

    ds = open_result(args.result)
    outdir = Path(args.outdir) if args.outdir else Path(args.result).with_suffix("")
    for path in plot(ds, outdir, args.kind):
        print(f"wrote {path}")
    return 0


#: wall time of `fickcam bench`, measured on the project's idle 2-core machine
BENCH_EXPECTED = {False: "about 3 min", True: "about 10 s"}


def _cmd_bench(args) -> int:
    if args.records:
        from .bench_records import (format_record_table, format_year_accuracy,
                                    run_record_bench, year_accuracy)

        print(format_record_table(run_record_bench(months=(1, 3) if args.quick else (1, 3, 12))))
        if not args.quick:
            print(format_year_accuracy(year_accuracy()))
        return 0
    from tqdm.auto import tqdm

    from .bench import format_table, row_count, run_bench

    total = row_count(args.quick)
    log.info("bench: %d rows, expected %s on an idle 2-core machine%s", total,
             BENCH_EXPECTED[args.quick], "" if args.quick else " (--quick: "
             f"{BENCH_EXPECTED[True]})")
    with tqdm(total=total, disable=args.quiet, unit="row", desc="bench", leave=False) as bar:
        started = []

        def starting(label: str) -> None:
            bar.update(1 if started else 0)  # the previous row has finished
            started.append(label)  # (a disabled bar, --quiet, keeps no postfix)
            bar.set_postfix_str(label)

        rows = run_bench(quick=args.quick, progress=starting)
    print(format_table(rows))
    return 0


def _cmd_materials(args) -> int:
    from .materials.library import entry_text, find_entry, library_table

    if args.name is None:
        print(library_table())
        return 0
    try:
        find_entry(args.name)
    except KeyError:
        raise InputError(f"no material {args.name!r} in the library (fickcam materials lists "
                         f"them)") from None
    print(entry_text(args.name))
    return 0


def _cmd_examples(args) -> int:
    from . import example_scenes

    if args.copy:
        for path in example_scenes.copy_to(args.copy, args.names):
            print(f"wrote {path}")
    elif args.names:
        for name in args.names:
            print(example_scenes.path(name).read_text(encoding="utf-8"), end="")
    else:
        print(example_scenes.listing())
    return 0


def _cmd_schema(args) -> int:
    from .schema import markdown_table

    print(markdown_table())
    return 0


def _cmd_sweep(args) -> int:
    from .reporting import sweep_summary
    from .store import open_result
    from .sweep import run_sweep
    from .sweep.scatter import summary_lines

    run_sweep(args.sweep, args.output, workers=args.workers, scheduler=args.scheduler,
              progress=not args.quiet)
    if not args.quiet:
        result = open_result(args.output)
        print(sweep_summary(result))
        for line in summary_lines(result):
            print(line)
        print(f"wrote {args.output}")
    return 0


def _cmd_compensate(args) -> int:
    from .compensation import compensate, write_scene
    from .compensation.report import report
    from .scene import load_scene

    scene = load_scene(args.scene)
    comp = compensate(scene, at=args.at, over=args.over, accuracy=args.accuracy)
    output = Path(args.output) if args.output else Path(f"{Path(args.scene).stem}_compensated.yaml")
    path = write_scene(comp, scene, output)
    print(report(comp, scene, path, accuracy=args.accuracy, plot=args.plot))
    print(f"wrote {path}")
    return 0


def _cmd_profile(args) -> int:
    from .cam.design import design_from_scene
    from .cam.kinematics import working_profile
    from .cam.profile import write_profile_csv, write_profile_dxf
    from .scene import load_scene

    scene = load_scene(args.scene)
    if scene.model.cam is None:
        raise InputError(f"{args.scene}: the scene has no cam")
    writers = {".csv": write_profile_csv, ".dxf": write_profile_dxf}
    suffix = Path(args.output).suffix.lower()
    if suffix not in writers or args.points < 16:
        raise InputError("profile: the output must end in .csv or .dxf and --points be >= 16")
    x, y = working_profile(design_from_scene(scene.model.cam), n=args.points)
    print(f"wrote {writers[suffix](args.output, x, y)}")
    return 0


def _cmd_fit(args) -> int:
    from .fit import fit_weight_gain, materials_yaml, parameter_table, plot_fit

    if (args.fiber is None) != (args.fiber_volume_fraction is None):
        raise InputError("--fiber and --fiber-volume-fraction go together")
    report = fit_weight_gain(args.data, args.matrix, fiber=args.fiber,
                             fiber_volume_fraction=args.fiber_volume_fraction, name=args.name)
    output = Path(args.output)
    output.write_text(materials_yaml(report), encoding="utf-8")
    print(parameter_table(report))
    print(f"wrote {output}")
    if args.plot:
        print(f"wrote {plot_fit(report, args.plot)}")
    return 0


COMMANDS = {"run": _cmd_run, "check": _cmd_check, "query": _cmd_query, "export": _cmd_export,
            "plot": _cmd_plot, "bench": _cmd_bench, "materials": _cmd_materials,
            "schema": _cmd_schema, "sweep": _cmd_sweep, "fit": _cmd_fit,
            "examples": _cmd_examples, "size": _cmd_size, "compensate": _cmd_compensate,
            "profile": _cmd_profile}


def process_main() -> int:
    """The `fickcam` command as its own process. The interpreter's garbage collections
    walk every object the imports made (numpy, scipy, pandas, xarray, h5py), at exit only
    to free them with the process; frozen first (gc.freeze) they are skipped: 0.2-0.3 CPU s
    of a demo run, measured as whole processes. Only here: in a caller's process (tests,
    notebooks) a freeze would keep whatever garbage exists at that moment for good."""
    atexit.register(gc.freeze)
    return main(whole_process=True)


def main(argv: list[str] | None = None, whole_process: bool = False) -> int:
    args = _parser().parse_args(argv)
    args.whole_process = whole_process
    # fickcam's own messages (INFO and notices) on stderr; other libraries' only from WARNING
    # (FiPy logs its solver suite at INFO); --quiet keeps notices off too (errors still print)
    logging.basicConfig(level=logging.WARNING, format="fickcam: %(message)s", stream=sys.stderr)
    logging.getLogger("fickcam").setLevel(
        logging.ERROR if getattr(args, "quiet", False) else logging.INFO)
    try:
        return COMMANDS[args.command](args)
    except SceneError as exc:
        for problem in exc.problems:
            print(str(problem), file=sys.stderr)
        return 2
    except InputError as exc:
        print(f"fickcam: {exc}", file=sys.stderr)
        return 2
    except FickcamError as exc:
        print(f"fickcam: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("fickcam: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except Exception as exc:  # last resort: one line, never a traceback unless --debug
        if args.debug:
            raise
        print(f"fickcam: internal error: {type(exc).__name__}: {exc} (rerun with --debug)",
              file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(process_main())
