"""Run the diffusion speed/accuracy benchmark and write its table and figure.

    python benchmarks/diffusion_tradeoff.py [--quick] [--out benchmarks/results]

Writes ``bench.md`` (the table `fickcam bench` prints), ``bench.csv`` and
``error_vs_time.png`` (error against the exact solution vs CPU time, log-log,
one marker series per geometry and model) for the README. A ``--quick`` run
only prints its table (it must not replace the committed full results) unless
``--out`` names a folder.
"""
from __future__ import annotations

import argparse
import csv
import logging
from pathlib import Path

import numpy as np

from fickcam.bench import format_table, run_bench

log = logging.getLogger("benchmarks.diffusion_tradeoff")
RESULTS = Path(__file__).resolve().parent / "results"


def write_figure(rows: list[dict], path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    series: dict[tuple[str, str], list[dict]] = {}
    for row in rows:
        if np.isfinite(row["cpu_time"]) and row["error"] > 0:
            series.setdefault((row["geometry"], row["model"]), []).append(row)
    for (geometry, model), points in series.items():
        points.sort(key=lambda r: r["cpu_time"])
        ax.loglog([p["cpu_time"] for p in points], [p["error"] for p in points], "o-",
                  label=f"{geometry}: {model}")
    ax.set_xlabel("CPU time per full uptake curve [s]")
    ax.set_ylabel("max error of the mean uptake (fraction of the step)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--out", type=Path, default=None,
                        help="folder for the results (default: benchmarks/results; "
                             "a --quick run writes nothing unless given)")
    args = parser.parse_args()
    logging.basicConfig(level=logging.WARNING, format="%(message)s")  # libraries: warnings only
    log.setLevel(logging.INFO)
    rows = run_bench(quick=args.quick)
    if args.out is None and args.quick:
        log.info("%s", format_table(rows))
        log.info("--quick: results not written (give --out FOLDER to keep them)")
        return
    args.out = args.out or RESULTS
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "bench.md").write_text("```\n" + format_table(rows) + "\n```\n")
    with open(args.out / "bench.csv", "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    log.info("%s", format_table(rows))
    log.info("figure: %s", write_figure(rows, args.out / "error_vs_time.png"))


if __name__ == "__main__":
    main()
