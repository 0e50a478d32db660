"""``fickcam bench --records``: the cost of a real climate record against a constant climate.

Each case is a shipped scene aged through the first 1, 3 and 12 months (730 h each) of
Greensboro's TMY3 year (``pvlib:723170TYA.CSV``, hourly rows; 12 months = its 8760 rows)
and, for the ratio, through the same span under a constant climate (the record's mean
temperature and humidity), with the same ageing times. Whole scene runs, in-process
(``simulate.run``), after a warm-up of each kind. Costs are CPU seconds of this process
(``time.process_time``: other work on a shared machine does not move them). The growth
exponent is the slope of log(cost) against log(rows).
"""
from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

MONTH_HOURS = 730
ROOT = Path(__file__).resolve().parents[1]
CASES = {"demo cam (plane)": "configs/singh2017_cam.yaml",
         "nylon eccentric cam (exact disc)": "configs/eccentric_cam.yaml",
         "four-bar (plane)": "configs/fourbar_r914_humid.yaml"}


def _scene(config: Path, environment: dict, months: int) -> dict:
    """The config with ``environment`` replaced, aged weekly-ish (10 ageing times)."""
    scene = yaml.safe_load(config.read_text())
    scene["environment"] = {"reference_temperature": scene["environment"]
                            .get("reference_temperature", "23 degC"), **environment}
    span = _rows(months) - 1
    scene["outputs"] = {**scene.get("outputs", {}), "file": None,
                        "ageing_times": [f"{h:g} h" for h in np.linspace(0, span, 10)]}
    return scene


def _record_csv(folder: Path, months: int) -> tuple[Path, float, float]:
    """The first ``months`` of Greensboro as a CSV history; also its mean T (degC) and RH."""
    from .records import read_record, resolve_record_path

    record = read_record(resolve_record_path("pvlib:723170TYA.CSV", ROOT))
    rows = _rows(months)
    hours = record.time[:rows] / 3600.0
    celsius = record.temperature[:rows] - 273.15
    humidity = record.relative_humidity[:rows]
    path = folder / f"greensboro_{months}m.csv"
    lines = [f"{h:g},{t:.2f},{rh:.2f}" for h, t, rh in zip(hours, celsius, humidity)]
    path.write_text("time [h],temperature [degC],relative_humidity [%]\n" + "\n".join(lines))
    return path, float(np.mean(celsius)), float(np.mean(humidity))


def _rows(months: int) -> int:
    return min(months * MONTH_HOURS + 1, 8760)


def _cost(scene: dict) -> float:
    """CPU time (s) of one in-process run of ``scene``."""
    from .simulate import run

    start = time.process_time()
    run(scene)
    return time.process_time() - start


def run_record_bench(months=(1, 3, 12), cases=None) -> list[dict]:
    """Rows (case, months, rows, record s, constant s, ratio) and, per case, the exponent."""
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for name, config in (cases or CASES).items():
            config = ROOT / config
            timings = []
            for count in months:
                path, celsius, humidity = _record_csv(Path(folder), count)
                record = _scene(config, {"history_file": str(path)}, count)
                constant = _scene(config, {"history": [{
                    "duration": f"{count * MONTH_HOURS} h", "temperature": f"{celsius:.2f} degC",
                    "relative_humidity": f"{humidity:.2f} %"}]}, count)
                if not timings:
                    _cost(constant), _cost(record)  # warm-up: imports, caches
                held, cost = _cost(constant), _cost(record)
                timings.append((_rows(count), cost))
                rows.append({"case": name, "months": count, "rows": _rows(count),
                             "record": cost, "constant": held, "ratio": cost / held})
            counts, walls = np.log([t[0] for t in timings]), np.log([t[1] for t in timings])
            exponent = float(np.polyfit(counts, walls, 1)[0]) if len(timings) > 1 else np.nan
            for row in rows[-len(months):]:
                row["exponent"] = exponent
    return rows


# (key, title, width, format): the case left-aligned, numbers right-aligned
COLUMNS = (("case", "case", 36, "s"), ("months", "months", 6, "d"), ("rows", "rows", 6, "d"),
           ("record", "record [s]", 10, ".2f"), ("constant", "constant [s]", 12, ".2f"),
           ("ratio", "ratio", 6, ".2f"), ("exponent", "growth exponent", 16, ".2f"))


def format_record_table(rows: list[dict]) -> str:
    """One line per (case, months): CPU seconds under the record and the constant climate."""
    def align(key):
        return "<" if key == "case" else ">"

    header = " ".join(f"{title:{align(key)}{width}}" for key, title, width, _ in COLUMNS)
    body = [" ".join(f"{row[key]:{align(key)}{width}{form}}" for key, _, width, form in COLUMNS)
            for row in rows]
    return "\n".join([header, "-" * len(header), *body])
