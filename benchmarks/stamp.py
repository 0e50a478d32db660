"""The stamp every result file in ``benchmarks/results/`` carries, and the file itself.

A result file is JSON: the command that reproduces it, the commit it was measured on, the
date (UTC), the machine (CPU model, cores, Python, platform) and its load average (a
shared machine's load moves wall times, and CPU seconds less so), then its tables, each
a list of column titles and rows. The documentation renders these tables with their
stamp when it builds (``docs/_ext/fickcam_results.py``), so no table in it is typed by
hand. Run from a benchmark script's ``main`` (the scripts' folder is on ``sys.path``).
"""
from __future__ import annotations

import datetime
import json
import os
from pathlib import Path

from points_cam import commit, machine

ROOT = Path(__file__).resolve().parents[1]


def stamp(command: str, load_at_start: float | None = None) -> dict:
    """The command, commit, date, machine and load average of a measurement ending now."""
    load = os.getloadavg()[0]
    return {"command": command, "commit": commit(),
            "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "machine": machine(),
            "load_average": load if load_at_start is None else {"start": load_at_start,
                                                                "end": load}}


def write_result(path: Path, what: str, command: str, tables: dict[str, dict],
                 load_at_start: float | None = None) -> None:
    """Write ``tables`` ({name: {"columns": [...], "rows": [[...], ...]}}) with their stamp
    to ``path`` (a temporary file, then renamed: an interrupted write leaves the old one)."""
    record = {"benchmark": what, **stamp(command, load_at_start), "tables": tables}
    temporary = path.with_suffix(path.suffix + ".tmp")
    temporary.write_text(json.dumps(record, indent=1, ensure_ascii=False) + "\n")
    temporary.replace(path)
    shown = path.resolve()
    print(f"wrote {shown.relative_to(ROOT) if shown.is_relative_to(ROOT) else shown}")
