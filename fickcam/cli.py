"""The ``fickcam`` command line (SPEC.md §2).

Exit status: 0 success; 2 bad input (one line per problem on stderr, no
traceback); 1 anything else (one line; ``--debug`` shows the traceback).
"""
from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

from ._version import __version__
from .errors import FickcamError, InputError, SceneError

log = logging.getLogger("fickcam")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="fickcam",
        description="Moisture uptake in polymer/composite cams, followers and four-bar "
                    "linkages, and the mechanism drift it causes.")
    parser.add_argument("--version", action="version", version=f"fickcam {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks of internal errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    run = sub.add_parser("run", help="run a scene and write its result file")
    run.add_argument("scene")
    run.add_argument("-o", "--output", help="result file (default: the scene's outputs.file)")
    run.add_argument("--accuracy", type=float, help="override diffusion.accuracy")
    run.add_argument("--quiet", action="store_true", help="no progress bar, no summary")

    check = sub.add_parser("check", help="validate a scene and print the plan")
    check.add_argument("scene")

    query = sub.add_parser("query", help="values of a variable from a result file")
    query.add_argument("result")
    query.add_argument("variable")
    query.add_argument("--time", help='ageing time with its unit, e.g. "30 d", "6 months" (a bare number is refused)')
    query.add_argument("--part")
    query.add_argument("--link")
    query.add_argument("--cam-angle", type=float, help="degrees")
    query.add_argument("--crank-angle", type=float, help="degrees")
    query.add_argument("--format", choices=("table", "csv", "json"), default="table")
    query.add_argument("--drift", choices=("design", "start"),
                       help="the change from the as-designed value (dry, reference temperature) "
                            "or from the first ageing time, instead of the value")

    export = sub.add_parser("export", help="export a result as CSV, netCDF or JSON")
    export.add_argument("result")
    export.add_argument("--format", choices=("csv", "netcdf", "json"), required=True)
    export.add_argument("-o", "--output", required=True)
    export.add_argument("--variables", nargs="+")

    plot = sub.add_parser("plot", help="PNG figures of a result")
    plot.add_argument("result")
    plot.add_argument("-o", "--outdir", default=None, help="folder (default: next to the result)")
    plot.add_argument("--kind", default="all",
                      choices=("uptake", "kinematics", "dynamics", "linkage", "fields", "limits", "sweep",
                               "all"))

    bench = sub.add_parser("bench", help="the diffusion speed/accuracy trade")
    bench.add_argument("--quick", action="store_true", help="fewer configurations")

    sub.add_parser("materials", help="the built-in material library with sources")
    sub.add_parser("schema", help="the result variables (name, dims, units)")

    compensate = sub.add_parser(
        "compensate", help="the dry dimensions to make so that the mechanism has its design "
                           "geometry at an ageing time (or over a window)")
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

    profile = sub.add_parser("profile", help="the cam's dry working profile for manufacture "
                                             "(CSV or DXF, by the output's suffix)")
    profile.add_argument("scene")
    profile.add_argument("-o", "--output", required=True, help="PATH.csv or PATH.dxf")
    profile.add_argument("--points", type=int, default=3600, help="points round the profile")

    fit = sub.add_parser("fit", help="calibrate a material from ASTM D5229 weight-gain data")
    fit.add_argument("data", help="weight-gain CSV (one row per weighing, units in the header)")
    fit.add_argument("--matrix", required=True, help="library matrix (resin) of the coupons")
    fit.add_argument("--fiber", help="library fibre of composite coupons")
    fit.add_argument("--fiber-volume-fraction", type=float, help="fibre volume fraction of the coupons")
    fit.add_argument("--name", help="material name in the YAML (default: the CSV's stem)")
    fit.add_argument("-o", "--output", required=True, help="YAML file with the materials: block")
    fit.add_argument("--plot", help="PNG of the data, fitted curves and residuals")

    sweep = sub.add_parser("sweep", help="many scenes on dask.distributed")
    sweep.add_argument("sweep")
    group = sweep.add_mutually_exclusive_group()
    group.add_argument("--workers", type=int, default=None, help="local worker processes")
    group.add_argument("--scheduler", help="address of a running dask scheduler")
    sweep.add_argument("-o", "--output", required=True)
    sweep.add_argument("--quiet", action="store_true")
    return parser


def _cmd_run(args) -> int:
    from .scene import load_scene
    from .reporting import summary
    from .simulate import run
    from .store import save

    scene = load_scene(args.scene)
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


def _cmd_bench(args) -> int:
    from .bench import format_table, run_bench

    print(format_table(run_bench(quick=args.quick)))
    return 0


def _cmd_materials(args) -> int:
    from .materials import library_table

    print(library_table())
    return 0


def _cmd_schema(args) -> int:
    from .schema import markdown_table

    print(markdown_table())
    return 0


def _cmd_sweep(args) -> int:
    from .sweep import run_sweep

    from .store import open_result
    from .sweep.scatter import summary_lines

    run_sweep(args.sweep, args.output, workers=args.workers, scheduler=args.scheduler,
              progress=not args.quiet)
    if not args.quiet:
        for line in summary_lines(open_result(args.output)):
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
    from .cam.model import design_from_scene, working_profile
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
            "compensate": _cmd_compensate, "profile": _cmd_profile}


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    logging.basicConfig(level=logging.WARNING if getattr(args, "quiet", False) else logging.INFO,
                        format="fickcam: %(message)s", stream=sys.stderr)
    logging.getLogger("fickcam").setLevel(
        logging.WARNING if getattr(args, "quiet", False) else logging.INFO)
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
    sys.exit(main())
