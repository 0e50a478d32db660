"""What each ``fickcam`` subcommand does, given its parsed arguments
(:mod:`fickcam.cli.parser`); each returns the exit status. Heavy imports stay inside the
command that needs them.
"""
from __future__ import annotations

import gc
import logging
from pathlib import Path

from ..errors import InputError

log = logging.getLogger("fickcam")


def _cmd_run(args) -> int:
    # deferred: keeps numpy, pydantic, yaml off the start-up path
    from ..scene.load import load_scene
    from .reporting import summary
    from ..simulation.simulate import run
    from ..simulation.resultsize import result_fits
    from ..results.store import save

    accuracy = scene_accuracy(args.accuracy)
    scene = load_scene(args.scene)
    if args.whole_process:
        gc.freeze()  # the modules loaded so far live to the end: the run's collections skip them
    output = Path(args.output) if args.output else default_output(scene)
    result_fits(scene, output)
    ds = run(scene, accuracy=accuracy, progress=not args.quiet)
    save(ds, output)
    if args.quiet < 2:
        print(summary(ds, notices=False))  # the run has logged them on stderr
        print(notices_line(ds.attrs.get("notices", []), args.quiet))
        print(f"wrote {output}")
    return 0


def scene_accuracy(text) -> float | None:
    """``--accuracy`` read as the scene's ``diffusion.accuracy`` (a fraction in (0, 0.1]).

    Parameters
    ----------
    text : str or None
        The option as given; None when it was not.

    Returns
    -------
    float or None
        The relative accuracy [-]; None: the scene's.
    """
    # deferred: keeps the command's modules off the start-up path
    from ..quantities.options import field_value
    from ..scene.load import DiffusionSection

    return field_value("--accuracy", text, DiffusionSection, "accuracy")


def notices_line(notices, quiet: int) -> str:
    """Under the run summary: how many warnings and notes the run reported on stderr.

    All of them are kept in the result's ``notices`` attribute.

    Parameters
    ----------
    notices : iterable of str
        The run's notices.
    quiet : int
        The ``-q`` count: with one or more, the warnings and notes were hidden and the line
        says so.

    Returns
    -------
    str
        The indented line.
    """
    # deferred: keeps the command's modules off the start-up path
    from ..messages import count_levels

    counts = count_levels(notices)
    if not sum(counts.values()):
        return "  no warnings or notes"
    warnings = f"{counts['warning']} warning(s)" if counts["warning"] else ""
    notes = f"{counts['note']} note(s)" if counts["note"] else ""
    if quiet:
        said = " and ".join(text for text in (warnings, notes) if text) + " hidden by -q"
    else:
        said = " and ".join(text for text in (warnings, notes) if text) + " above"
    return f"  {said} (all kept in the result's notices attribute)"


def default_output(scene) -> Path:
    """The scene's ``outputs.file`` or ``outputs/<name>.h5`` (relative to the working folder).

    Parameters
    ----------
    scene : fickcam.scene.load.Scene
        The scene being run.

    Returns
    -------
    pathlib.Path
        The result file to write.
    """
    if scene.model.outputs.file:
        return Path(scene.model.outputs.file)
    return Path("outputs") / f"{scene.name}.h5"


def _cmd_check(args) -> int:
    # deferred: keeps numpy, pydantic off the start-up path
    from ..scene.load import load_scene

    scene = load_scene(args.scene)
    # deferred until the scene is valid: a refused scene never loads the diffusion engine
    from .reporting import describe_plan
    from ..simulation.resultsize import estimate, size_warning

    print(describe_plan(scene))
    warning = size_warning(estimate(scene))
    if warning:
        log.warning(warning)
    return 0


def _cmd_size(args) -> int:
    # deferred: keeps numpy, pydantic off the start-up path
    from ..cam.sizing import Limits
    from ..compensation.base_circle import size_scene
    from ..quantities.options import angle, option_value
    from ..quantities.plausibility import cam_length_reading
    from ..scene.load import load_scene
    from ..quantities.types import NonNegativeLength, PositiveAngle

    pressure_angle = angle("--pressure-angle", args.pressure_angle, PositiveAngle)
    scene = load_scene(args.scene)
    if not scene.has("cam"):
        raise InputError("the scene has no cam: section to size")
    curvature = None if args.radius_of_curvature is None else option_value(
        "--radius-of-curvature", args.radius_of_curvature, NonNegativeLength,
        cam_length_reading("smallest radius of curvature", scene.document.data))
    try:
        sizing = size_scene(scene, Limits(pressure_angle, curvature))
    except ValueError as exc:
        raise InputError(str(exc)) from None
    print(sizing.text())
    return 0


def _cmd_query(args) -> int:
    # deferred: keeps the command's modules off the start-up path
    from ..quantities.options import angle_degrees
    from .reporting import limit_line
    from ..results.query import format_result, select, time_units
    from ..results.store import open_result

    ds = open_result(args.result)
    array = select(ds, args.variable, time=args.time, part=args.part, link=args.link,
                   cam_angle=angle_degrees("--cam-angle", args.cam_angle),
                   crank_angle=angle_degrees("--crank-angle", args.crank_angle),
                   against=args.drift)
    print(format_result(array, args.variable, args.format, args.drift,
                        limit=limit_line(ds, args.variable),
                        units=args.units or time_units(ds, args.variable)))
    return 0


def _cmd_export(args) -> int:
    # deferred: keeps numpy, pydantic off the start-up path
    from ..results.export import export
    from ..results.store import open_result

    ds = open_result(args.result)
    path = export(ds, args.output, args.format, args.variables)
    print(f"wrote {path}")
    return 0


def _cmd_plot(args) -> int:
    # deferred: keeps the command's modules off the start-up path
    from ..plotting import plot
    from ..results.store import open_result

    ds = open_result(args.result)
    outdir = Path(args.outdir) if args.outdir else Path(args.result).with_suffix("")
    for path in plot(ds, outdir, args.kind).paths:
        print(f"wrote {path}")
    return 0


#: wall time of `fickcam bench` (measured: benchmarks/results/tuned_constants.md)
BENCH_EXPECTED = {False: "about 3 min", True: "about 10 s"}


def _cmd_bench(args) -> int:
    """The benchmarks of the source checkout (``benchmarks/``): not part of a wheel."""
    # deferred: keeps the command's modules off the start-up path
    from .checkout import benchmark

    if args.records:
        # deferred: each command loads what it runs (start-up)
        from ..extras import require

        require("weather")  # the records bench reads a TMY3 year that pvlib ships
        records = benchmark("climate_records")
        print(records.format_record_table(
            records.run_record_bench(months=(1, 3) if args.quick else (1, 3, 12))))
        if not args.quick:
            print(records.format_year_accuracy(records.year_accuracy()))
        return 0
    # deferred: keeps the command's modules off the start-up path
    from ..messages import progress_bar

    tradeoff = benchmark("diffusion_tradeoff")
    total = tradeoff.row_count(args.quick)
    log.info("bench: %d rows, expected %s on an idle 2-core machine%s", total,
             BENCH_EXPECTED[args.quick], "" if args.quick else " (--quick: "
             f"{BENCH_EXPECTED[True]})")
    with progress_bar(total, enabled=not args.quiet, eta=False, unit="rows", desc="bench",
                      leave=False) as bar:  # rows differ in cost a hundredfold: no ETA
        started = []

        def starting(label: str) -> None:
            bar.update(1 if started else 0)  # the previous row has finished
            started.append(label)  # (a disabled bar, --quiet, keeps no postfix)
            bar.set_postfix_str(label)

        rows = tradeoff.run_bench(quick=args.quick, progress=starting)
    print(tradeoff.format_table(rows))
    return 0


def _cmd_materials(args) -> int:
    # deferred: keeps pydantic off the start-up path
    from ..scene.keys import closest_names
    from ..materials.library import GROUPS, entry_text, find_entry, known_names, library_table

    if args.name is None:
        print(library_table())
        return 0
    try:
        find_entry(args.name)
    except KeyError:
        names = {name.lower(): name for group in GROUPS for name in known_names(group)}
        near = [names[n] for n in closest_names(args.name.lower(), names)]
        hint = f"did you mean {', '.join(near)}?" if near else "fickcam materials lists them"
        raise InputError(f"no material {args.name!r} in the library; {hint}") from None
    print(entry_text(args.name))
    return 0


def _cmd_examples(args) -> int:
    # deferred: keeps yaml off the start-up path
    from ..scene import examples as example_scenes

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
    # deferred: keeps the command's modules off the start-up path
    from ..schema import markdown_table

    print(markdown_table())
    return 0


def _cmd_sweep(args) -> int:
    # deferred: each command loads what it runs (start-up)
    from .reporting import sweep_limit_lines, sweep_summary
    from ..results.store import open_result
    from ..sweep import run_sweep

    run_sweep(args.sweep, args.output, workers=args.workers, scheduler=args.scheduler,
              progress=not args.quiet)
    if args.quiet < 2:
        result = open_result(args.output)
        print(sweep_summary(result))
        for line in sweep_limit_lines(result):
            print(line)
        print(f"wrote {args.output}")
    return 0


def _cmd_compensate(args) -> int:
    # deferred: keeps numpy, yaml off the start-up path
    from ..compensation import compensate
    from ..compensation.report import report, write_files
    from ..scene.load import load_scene

    if args.profile is not None:
        suffix = Path(args.profile).suffix.lower()
        if suffix not in (".csv", ".dxf"):
            raise InputError(f"--profile {args.profile}: the made cam's profile is written as "
                             f".csv or .dxf (by the suffix)")
        if suffix == ".dxf":  # before any computation: the extra may be missing
            # deferred: each command loads what it runs (start-up)
            from ..cam.profile import dxf_module

            dxf_module()
    scene = load_scene(args.scene)
    if args.profile is not None and not scene.has("cam"):
        raise InputError(f"{args.scene}: --profile needs a cam (the scene has none)")
    comp = compensate(scene, at=args.at, over=args.over, accuracy=scene_accuracy(args.accuracy),
                      plot=args.plot is not None, keep_limits=args.keep_limits,
                      points=args.points)
    output = Path(args.output) if args.output else Path(f"{Path(args.scene).stem}_compensated.yaml")
    text = report(comp, scene)
    written = write_files(comp, scene, output, profile=args.profile, plot=args.plot)
    print(text)
    for path in written:
        print(f"wrote {path}")
    return 0


def _cmd_profile(args) -> int:
    # deferred: keeps numpy, pydantic off the start-up path
    from ..cam.kinematics import working_profile
    from ..cam.profile import dxf_module, write_profile_csv, write_profile_dxf
    from ..scene.load import load_scene

    writers = {".csv": write_profile_csv, ".dxf": write_profile_dxf}
    suffix = Path(args.output).suffix.lower()
    if suffix not in writers or args.points < 16:
        raise InputError("profile: the output must end in .csv or .dxf and --points be >= 16")
    if suffix == ".dxf":
        dxf_module()  # refused before any work without the dxf extra
    scene = load_scene(args.scene)
    if not scene.has("cam"):
        raise InputError(f"{args.scene}: the scene has no cam")
    x, y = working_profile(scene.mechanism("cam").design, n=args.points)
    print(f"wrote {writers[suffix](args.output, x, y)}")
    return 0


def _cmd_outline(args) -> int:
    # deferred: keeps numpy, xarray off the start-up path
    from ..cam.profile import dxf_module, write_profile_csv, write_profile_dxf
    from ..results.outline import aged_outline
    from ..results.store import open_result

    suffix = Path(args.output).suffix.lower()
    if suffix not in (".csv", ".dxf"):
        raise InputError(f"outline: -o {args.output}: the aged outline is written as .csv or "
                         f".dxf (by the suffix)")
    if suffix == ".dxf":
        dxf_module()  # refused before any work without the dxf extra
    outline = aged_outline(open_result(args.result), args.time)
    if suffix == ".dxf":
        path = write_profile_dxf(args.output, outline.x, outline.y, layer=outline.layer)
        where = f", layer {outline.layer}, mm"
    else:
        path = write_profile_csv(args.output, outline.x, outline.y)
        where = ", mm"
    print(f"wrote {path}: the cam's aged working profile at {outline.label}, {outline.how}"
          f"{where}")
    return 0


def _cmd_fit(args) -> int:
    # deferred: keeps the command's modules off the start-up path
    from ..quantities.options import field_value
    from ..fit import fit_weight_gain, materials_yaml, parameter_table, plot_fit
    from ..materials import MaterialSpec
    from ..files import write_text_atomically

    if (args.fiber is None) != (args.fiber_volume_fraction is None):
        raise InputError("--fiber and --fiber-volume-fraction go together")
    fraction = field_value("--fiber-volume-fraction", args.fiber_volume_fraction, MaterialSpec,
                           "fiber_volume_fraction")
    report = fit_weight_gain(args.data, args.matrix, fiber=args.fiber,
                             fiber_volume_fraction=fraction, name=args.name)
    output = write_text_atomically(args.output, materials_yaml(report))
    print(parameter_table(report))
    print(f"wrote {output}")
    if args.plot:
        print(f"wrote {plot_fit(report, args.plot).paths[0]}")
    return 0


COMMANDS = {"run": _cmd_run, "check": _cmd_check, "query": _cmd_query, "export": _cmd_export,
            "plot": _cmd_plot, "bench": _cmd_bench, "materials": _cmd_materials,
            "schema": _cmd_schema, "sweep": _cmd_sweep, "fit": _cmd_fit,
            "examples": _cmd_examples, "size": _cmd_size, "compensate": _cmd_compensate,
            "profile": _cmd_profile, "outline": _cmd_outline}
