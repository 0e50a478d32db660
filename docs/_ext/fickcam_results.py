"""Tables of measured numbers, rendered from the result files in ``benchmarks/results/``.

No table of measurements in the documentation is typed by hand: a page names a result
file and one of its tables, and the build renders the table with the command that
reproduces it, the date and the machine under it::

    ```{result-table} benchmarks/results/dc_bar.json
    :table: octant
    ```

A result file is JSON with ``command``, ``commit``, ``date``, ``machine`` and
``load_average`` and a ``tables`` mapping, each table a ``columns`` list and ``rows``
(``benchmarks/stamp.py`` writes them); a table may carry its own stamp keys where it was
measured apart from the others. Files written by the older benchmark scripts
(``daily_outputs.json``, ``compensation_runs.json``, ``points_cam.json``) keep their own
layout; :data:`VIEWS` turns each into a table. A file marked ``"transcribed": true``
holds numbers measured before the benchmark wrote result files, copied from the commit
its stamp names (its documentation, or a file the script wrote), and says so under the
table.

The full stamp of every table (the commit and the machine's load average as well) is for
developers: the build writes it to the measurement record, ``docs/measurements.md``
(:func:`measurement_record_markdown`), in the development section.

The functions that build the Markdown need no Sphinx, so the test suite checks them.
"""
from __future__ import annotations

import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RESULTS = ROOT / "benchmarks" / "results"
STAMP_KEYS = ("command", "commit", "date", "machine", "load_average")


# -- tables of the older result files -----------------------------------------------------

def daily_outputs_table(record: dict) -> dict:
    """``daily_outputs.json``: seconds of 10 and of daily outputs, fresh and warm."""
    rows = []
    for scene in record["scenes"]:
        fresh, warm = scene["fresh"], scene["warm"]
        rows.append([f"{scene['what']} (`{scene['scene']}`)", f"{fresh['ten_outputs_s']:.2f}",
                     f"{fresh['daily_outputs_s']:.2f}", f"{fresh['ratio']:.1f}",
                     f"{warm['ratio']:.1f}"])
    daily = record["scenes"][0]["outputs"]["daily"]
    return {"columns": ["scene (TMY3 year)", "10 outputs, fresh [s]", f"{daily} daily, fresh [s]",
                        "ratio", "ratio, warm"], "rows": rows}


def compensation_runs_table(record: dict) -> dict:
    """``compensation_runs.json``: compensation's cost in runs of the scene."""
    def both(scene, key, field, form):
        return f"{scene['fresh'][key][field]:{form}}; {scene['warm'][key][field]:{form}}"

    scenes = record["scenes"]
    target = record["target_runs"]
    labels = [("run", "one run, s", "median_s", ".2f"),
              ("at", f"`--at \"6 months\"` (target: {target['at']})", "runs_worth", ".2f"),
              ("over", f"`--over \"0 d\" \"2 years\"` (target: {target['over']})", "runs_worth",
               ".2f"),
              ("over_plot", "... with `--plot`", "runs_worth", ".2f")]
    rows = [[label] + [both(scene, key, field, form) for scene in scenes]
            for key, label, field, form in labels]
    rows.append(["diffusion solves: one run; `--at`; `--over`"]
                + ["; ".join(str(scene["fresh"][key]["diffusion_solves"])
                             for key in ("run", "at", "over")) for scene in scenes])
    return {"columns": ["runs of the scene's worth (fresh; warm)"]
            + [f"`{scene['scene']}`" for scene in scenes], "rows": rows}


def points_cam_table(record: dict) -> dict:
    """``points_cam.json``: a cam given by points against the same cam in closed form."""
    rows = [[f"`{s['scene']}` ({s['cam']})", f"{s['fresh']['ratio']:.2f}",
             f"{s['warm']['ratio']:.2f}", f"{s['motion_difference_over_lift']:.1e}",
             f"{s['jump_speed_relative_difference']:.1e}"] for s in record["scenes"]]
    return {"columns": ["scene", "time ratio, fresh", "time ratio, warm",
                        "motion difference / lift", "jump speed difference (relative)"],
            "rows": rows}


def startup_table(record: dict) -> dict:
    """``startup.json``: the demo run as a whole process against the import floor."""
    floor, demo = record["floor"], record["demo"]
    return {"columns": ["process (median of runs)", "wall [s]", "CPU [s]"],
            "rows": [["imports of what any run needs (the floor)", f"{floor['wall_s']:.2f}",
                      f"{floor['cpu_s']:.2f}"],
                     [f"`{record['command']}`", f"{demo['wall_s']:.2f}", f"{demo['cpu_s']:.2f}"],
                     ["ratio to the floor", f"{record['ratio_wall']:.2f}",
                      f"{record['ratio_cpu']:.2f}"]]}


def montecarlo_table(record: dict) -> dict:
    """``montecarlo.json``: a Monte Carlo sweep's wall time, as a multiple of one demo run
    (whole processes), and its cost per case; the checkout it ran against side by side, when
    it ran against one, in a second row."""
    def row(commit: str, median: dict) -> list[str]:
        demo = median.get("demo_run_s", float("nan"))
        over = median.get("sweep_over_demo_run", float("nan"))
        return [commit, str(record["cases"]), str(record["workers"]), f"{median['wall_s']:.0f}",
                f"{demo:.2f}", f"{over:.0f}", f"{median['cpu_s_per_case']:.3f}",
                f"{median['case_over_single']:.2f}"]

    rows = [row(record["commit"], record["median"])]
    if record.get("against"):
        rows.append(row(record["against"]["commit"], record["against"]["median"]))
    return {"columns": ["commit", "cases", "workers", "wall [s]", "one demo run [s]",
                        "sweep / demo run", "CPU per case [s]", "a case / one warm single run"],
            "rows": rows}


VIEWS = {"daily_outputs.json": daily_outputs_table,
         "compensation_runs.json": compensation_runs_table,
         "points_cam.json": points_cam_table,
         "startup.json": startup_table,
         "montecarlo.json": montecarlo_table}
COMMANDS = {"daily_outputs.json": "python benchmarks/daily_outputs.py",
            "compensation_runs.json": "python benchmarks/compensation_runs.py",
            "points_cam.json": "python benchmarks/points_cam.py",
            "montecarlo.json": "python benchmarks/bench_montecarlo.py"}


# -- Markdown ---------------------------------------------------------------------------

def load_result(path: Path) -> dict:
    """A result file, its command filled in for the older layouts."""
    record = json.loads(Path(path).read_text())
    record.setdefault("command", COMMANDS.get(Path(path).name, ""))
    return record


def table_of(record: dict, name: str | None, filename: str) -> dict:
    """The table ``name`` of a result file (its only table when ``name`` is None)."""
    if filename in VIEWS:
        return VIEWS[filename](record)
    tables = record["tables"]
    if name is None:
        if len(tables) != 1:
            raise KeyError(f"{filename} holds the tables {sorted(tables)}: name one (:table:)")
        name = next(iter(tables))
    if name not in tables:
        raise KeyError(f"{filename} has no table {name!r}; it holds {sorted(tables)}")
    return tables[name]


def _cell(value) -> str:
    """A table cell; a value not measured (``nan``) shows as a dash."""
    text = str(value)
    if text.lower() == "nan":
        return "–"
    return text.replace("|", "\\|").replace("\n", " ")


def _load_text(load) -> str:
    if isinstance(load, dict):
        start, end = (f"{value:.1f}" for value in sorted((load["start"], load["end"])))
        return start if start == end else f"{start}-{end}"
    return f"{load:.1f}" if isinstance(load, (int, float)) else str(load)


def _machine_text(machine) -> str:
    if isinstance(machine, str):
        return machine
    parts = [machine.get("cpu", ""), f"{machine['cores']} cores" if "cores" in machine else "",
             f"Python {machine['python']}" if "python" in machine else ""]
    return ", ".join(part for part in parts if part)


def stamp_text(record: dict) -> str:
    """One line: the command, and the commit, date, machine and load of the numbers."""
    missing = [key for key in STAMP_KEYS if key not in record]
    if missing:
        raise KeyError(f"result file without {', '.join(missing)}")
    date = record["date"][:10]
    where = (f"{_machine_text(record['machine'])}, load average "
             f"{_load_text(record['load_average'])}")
    if record.get("transcribed"):
        measured = (f"Transcribed from commit `{record['commit']}` ({date}), measured on "
                    f"{where}; not re-run since")
    else:
        measured = f"Measured on commit `{record['commit']}` ({date}), {where}"
    return f"Reproduce: `{record['command']}`. {measured}."


def reader_stamp(record: dict) -> str:
    """One line for the reader: the command that reproduces the numbers, when and where
    they were measured (the commit and the load are in the measurement record)."""
    stamp_text(record)  # every stamp key present
    measured = f"measured {record['date'][:10]} on {_machine_text(record['machine'])}"
    if record.get("transcribed"):
        measured = f"numbers transcribed from an earlier measurement, {measured}"
    return f"Reproduce with `{record['command']}` ({measured})."


def _stamped(record: dict, table: dict) -> dict:
    """A table's stamp: the file's, with the keys the table carries itself."""
    return {**record, **{key: table[key] for key in STAMP_KEYS + ("transcribed",) if key in table}}


def measurement_record_markdown(folder: Path = RESULTS) -> str:
    """The measurement record: every result file's tables with their full stamps."""
    lines = ["# Measurement record", "",
             "Where each table of measurements on the Validation and Benchmarks pages comes "
             "from: the result file, the command, and the commit, date, machine and load "
             "average it was measured at. Generated from `benchmarks/results/` when the "
             "documentation is built.", ""]
    for path in sorted(folder.glob("*.json")):
        record = load_result(path)
        names = [None] if path.name in VIEWS else list(record["tables"])
        lines += [f"## `{path.name}`", ""]
        for name in names:
            table = table_of(record, name, path.name)
            label = f"`{name}`: " if name else ""
            lines += [f"- {label}{stamp_text(_stamped(record, table))}"]
        lines.append("")
    return "\n".join(lines)


def result_markdown(path: Path, name: str | None = None) -> str:
    """The table ``name`` of the result file ``path`` as MyST Markdown, its stamp under it."""
    record = load_result(path)
    table = table_of(record, name, Path(path).name)
    columns = table["columns"]
    lines = ["| " + " | ".join(_cell(c) for c in columns) + " |",
             "|" + "---|" * len(columns)]
    for row in table["rows"]:
        if len(row) != len(columns):
            raise ValueError(f"{Path(path).name}: a row of {len(row)} cells under "
                             f"{len(columns)} columns: {row}")
        lines.append("| " + " | ".join(_cell(c) for c in row) + " |")
    lines += [""]
    if table.get("note"):
        lines += [table["note"], ""]
    lines += [f"*{reader_stamp(_stamped(record, table))}*", ""]
    return "\n".join(lines)


# -- Sphinx -----------------------------------------------------------------------------

def result_table_directive():
    """The ``{result-table}`` directive. docutils and Sphinx are imported here only, so that
    the functions above run with the test extra alone (the suite checks them)."""
    from docutils import nodes
    from docutils.statemachine import StringList
    from sphinx.util.docutils import SphinxDirective

    class ResultTable(SphinxDirective):
        """``{result-table} benchmarks/results/FILE.json`` with an optional ``:table: NAME``."""

        required_arguments = 1
        option_spec = {"table": lambda text: text.strip()}

        def run(self):
            path = ROOT / self.arguments[0]
            self.env.note_dependency(str(path))
            try:
                text = result_markdown(path, self.options.get("table"))
            except (OSError, KeyError, ValueError) as error:
                raise self.error(f"result-table {self.arguments[0]}: {error}") from error
            container = nodes.container(classes=["result-table"])
            self.state.nested_parse(StringList(text.splitlines(), source=str(path)),
                                    self.content_offset, container)
            return [container]

    return ResultTable


def error_vs_accuracy_figure(out: Path, path: Path = RESULTS / "bench.json") -> Path:
    """Draw the error of each diffusion model against the accuracy asked of it, from the
    benchmark's result file (closed-form rows, exact to round-off, and the plain FiPy
    rows, which take no accuracy, left out)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = load_result(path)["tables"]["bench"]["rows"]
    models: dict[str, list[tuple[float, float]]] = {}
    for geometry, model, accuracy, *_, error, _estimate, _reference in rows:
        if model in ("analytic", "fipy-naive"):
            continue
        label = f"{model}: {geometry.split(': ')[0]}"
        models.setdefault(label, []).append((float(accuracy), float(error)))
    fig, ax = plt.subplots(figsize=(9.0, 4.8), layout="constrained")
    for k, (label, points) in enumerate(sorted(models.items())):
        points.sort()
        ax.plot(*zip(*points), marker="osD^v<>ph*"[k % 10], color=plt.cm.tab20(k % 20),
                label=label)
    line = [1e-4, 1e-1]
    ax.plot(line, line, "k--", lw=1, label="error = accuracy asked")
    ax.set(xscale="log", yscale="log", xlabel="accuracy asked (relative)",
           ylabel="error of the mean uptake against\nthe reference (relative)",
           title="Each model's error stays below the accuracy asked")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=130)
    plt.close(fig)
    return out


def _write_record(app) -> None:
    figure = Path(app.srcdir) / "_generated" / "error_vs_accuracy.png"
    error_vs_accuracy_figure(figure)
    path = Path(app.srcdir) / "measurements.md"
    text = measurement_record_markdown()
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def setup(app):
    app.add_directive("result-table", result_table_directive())
    app.connect("builder-inited", _write_record)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
