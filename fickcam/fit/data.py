"""Weight-gain data (ASTM D5229/D5229M procedure A): a tidy CSV, one row per weighing.

Columns (units in the header, any unit pint knows, like ``history_file``):
``specimen, temperature [degC], relative_humidity [%], thickness [mm], width [mm],
length [mm], dry_mass [g], time [d], mass [g]``. ``moisture [%]`` may replace
``dry_mass`` and ``mass``; ``width`` and ``length`` may be left out for a sheet
with sealed edges (both or neither): as columns, or as empty cells (not given, as in
pandas), so that sealed and open coupons share one file. A coupon's width and length
may be given on one of its rows only. Lines starting with ``#`` are comments.
Every fault is a ``file:LINE column: reason`` problem (exit 2 at the command line).
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..climate.csvrows import CsvError, numbered_rows
from ..errors import Problem, SceneError
from ..quantities.parsing import to_si

_HEADER = re.compile(r"^\s*(?P<name>[A-Za-z_]+)\s*(?:\[(?P<unit>[^\]]*)\])?\s*$")
DIMENSIONS = {"temperature": "temperature", "relative_humidity": "percent", "thickness": "length",
              "width": "length", "length": "length", "dry_mass": "mass", "time": "time",
              "mass": "mass", "moisture": "percent"}
CONSTANT = ("temperature", "relative_humidity", "thickness", "width", "length", "dry_mass")
#: columns whose empty cell means "not given" (a coupon with sealed edges)
EDGES = ("width", "length")
MAX_PROBLEMS = 20
MIN_WEIGHINGS = 3   # two parameters (D, Mm) and one degree of freedom for their intervals


@dataclass(frozen=True, eq=False)
class Specimen:
    """One coupon: conditions (K, %), dimensions (m; width/length None = sealed
    edges), weighing times (s), moisture content (weight %) and their CSV lines.

    Parameters
    ----------
    name : str
        The coupon's name.
    temperature : float
        Exposure temperature [K].
    relative_humidity : float
        Exposure relative humidity [%].
    thickness : float
        Thickness [m].
    width, length : float or None
        In-plane sides [m]; None: edges sealed.
    time : numpy.ndarray
        Weighing times [s].
    moisture : numpy.ndarray
        Moisture content [weight %].
    lines : numpy.ndarray
        CSV line of each weighing.
    """

    name: str
    temperature: float
    relative_humidity: float
    thickness: float
    width: float | None
    length: float | None
    time: np.ndarray
    moisture: np.ndarray
    lines: np.ndarray

    @property
    def condition(self) -> tuple[float, float]:
        """(T in K, RH in %) rounded so that equal conditions group together."""
        return round(self.temperature, 2), round(self.relative_humidity, 2)


def condition_label(condition: tuple[float, float]) -> str:
    """A condition as the user reads it: '85 degC / 85 % RH'.

    Parameters
    ----------
    condition : tuple of float
        Temperature [K] and relative humidity [%].

    Returns
    -------
    str
        The label.
    """
    return f"{condition[0] - 273.15:g} degC / {condition[1]:g} % RH"


class _Reader:
    """Collects the problems of one file while its cells are read."""

    def __init__(self, file: str):
        self.file = file
        self.problems: list[Problem] = []

    def fail(self, line: int | None, column: str, reason: str) -> None:
        if len(self.problems) < MAX_PROBLEMS:
            self.problems.append(Problem(self.file, line, column, reason))

    def header(self, cells: list[str]) -> dict[str, tuple[int, str]]:
        columns: dict[str, tuple[int, str]] = {}
        for index, cell in enumerate(cells):
            match = _HEADER.match(cell)
            name = match.group("name") if match else cell.strip()
            if not match or (name not in DIMENSIONS and name != "specimen"):
                self.fail(1, name, f"unknown column (expected specimen, {', '.join(DIMENSIONS)})")
                continue
            if name in columns:
                self.fail(1, name, "column given twice")
            unit = (match.group("unit") or "").strip()
            if name in DIMENSIONS and not unit:
                self.fail(1, name, f"missing unit: write e.g. '{name} [{_EXAMPLE_UNITS[name]}]'")
            columns[name] = (index, unit)
        self._required(columns)
        return columns

    def _required(self, columns) -> None:
        needed = ["specimen", "temperature", "relative_humidity", "thickness", "time"]
        if "moisture" not in columns:
            needed += ["dry_mass", "mass"]
        elif {"dry_mass", "mass"} & set(columns):
            self.fail(1, "moisture", "give either moisture or dry_mass and mass, not both")
        for name in needed:
            if name not in columns:
                self.fail(1, name, "missing column")
        if ("width" in columns) != ("length" in columns):
            self.fail(1, "width" if "width" not in columns else "length",
                      "give width and length together (or neither for a sheet with sealed edges)")

    def value(self, row, line, columns, name) -> float | None:
        index, unit = columns[name]
        text = row[index].strip() if index < len(row) else ""
        if not text:
            if name not in EDGES:
                self.fail(line, name, "empty cell")
            return None
        try:
            number = float(text)
        except ValueError:
            self.fail(line, name, f"{text!r} is not a number (the unit goes in the header)")
            return None
        try:
            return to_si(f"{number!r} {unit}", DIMENSIONS[name])
        except ValueError as exc:
            self.fail(line, name, str(exc))
            return None


_EXAMPLE_UNITS = {"temperature": "degC", "relative_humidity": "%", "thickness": "mm", "width": "mm",
                  "length": "mm", "dry_mass": "g", "time": "d", "mass": "g", "moisture": "%"}


def _rows(path: Path, reader: _Reader) -> list[tuple[int, list[str]]]:
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            numbered = list(numbered_rows(handle))
    except FileNotFoundError:
        raise SceneError([Problem(reader.file, None, "", "no such data file")]) from None
    except CsvError as exc:
        raise SceneError([Problem(reader.file, exc.line, "", exc.reason)]) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise SceneError([Problem(reader.file, None, "", f"cannot read: {exc}")]) from None
    return [(n, row) for n, row in numbered if row and any(c.strip() for c in row)
            and not row[0].lstrip().startswith("#")]


def read_weight_gain(path) -> list[Specimen]:
    """Read and validate a weight-gain CSV; raise SceneError listing every fault.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV: one row per weighing, a ``specimen`` column and columns with units in
        their header (``temperature [degC]``, ``time [h]``, ``mass [g]``, ...).

    Returns
    -------
    list of Specimen
        The coupons, in SI: conditions [K, %], dimensions [m], times [s], moisture
        [weight %].

    Raises
    ------
    fickcam.errors.SceneError
        Every fault, each with file, line and column.
    """
    path = Path(path)
    reader = _Reader(str(path))
    rows = _rows(path, reader)
    if len(rows) < 2:
        raise SceneError([Problem(reader.file, None, "", "needs a header and at least one row")])
    header_line, header = rows[0]
    columns = reader.header(header)
    if reader.problems:
        raise SceneError([Problem(p.file, header_line, p.key, p.reason) for p in reader.problems])
    records: dict[str, list[dict]] = {}
    for line, row in rows[1:]:
        record = {name: reader.value(row, line, columns, name) for name in columns if name != "specimen"}
        name = row[columns["specimen"][0]].strip() if columns["specimen"][0] < len(row) else ""
        if not name:
            reader.fail(line, "specimen", "empty cell")
        record["line"] = line
        records.setdefault(name, []).append(record)
    specimens = [_specimen(name, rows_, reader) for name, rows_ in records.items() if name]
    if reader.problems:
        raise SceneError(reader.problems)
    return specimens


def _edge_problems(rows: list[dict], reader: _Reader) -> None:
    """Width and length come together on a row (both empty: not given there; a coupon
    with sealed edges leaves them empty on every row)."""
    for row in rows:
        given = [key for key in EDGES if row.get(key) is not None]
        unreadable = any(p.line == row["line"] and p.key in EDGES for p in reader.problems)
        if len(given) == 1 and not unreadable:
            missing = next(key for key in EDGES if key not in given)
            reader.fail(row["line"], missing, "empty cell: give width and length together "
                                              "(both empty for a coupon with sealed edges)")


def _specimen(name: str, rows: list[dict], reader: _Reader) -> Specimen | None:
    first = rows[0]
    for key in CONSTANT:  # each compared with the first row that gives it
        given = [row for row in rows if row.get(key) is not None]
        for row in given[1:]:
            if not np.isclose(row[key], given[0][key], rtol=1e-9, atol=0.0):
                reader.fail(row["line"], key, f"specimen {name!r} changes its {key} "
                                              f"(line {given[0]['line']} has another value)")
    _edge_problems(rows, reader)
    for row in rows:
        for key in ("mass", "dry_mass", "thickness", "width", "length"):
            if row.get(key) is not None and row[key] <= 0:
                reader.fail(row["line"], key, "must be positive")
        if row.get("time") is not None and row["time"] < 0:
            reader.fail(row["line"], "time", "must not be negative")
        if row.get("relative_humidity") is not None and not 0 < row["relative_humidity"] <= 100:
            reader.fail(row["line"], "relative_humidity", "must lie in (0, 100] %")
    times = [row["time"] for row in rows]
    for previous, row in zip(rows, rows[1:]):
        if None not in (previous["time"], row["time"]) and row["time"] <= previous["time"]:
            reader.fail(row["line"], "time", f"specimen {name!r}: times must increase "
                                             f"(line {previous['line']} is not earlier)")
    if len(rows) < MIN_WEIGHINGS:
        reader.fail(first["line"], "specimen", f"specimen {name!r} has {len(rows)} weighing(s); "
                                               f"a fit needs at least {MIN_WEIGHINGS}")
    if reader.problems:
        return None
    if "moisture" in first:
        moisture = np.array([row["moisture"] for row in rows])
    else:  # D5229 eq. 1: M = (W_i - W_b) / W_b x 100 %
        moisture = np.array([(row["mass"] - row["dry_mass"]) / row["dry_mass"] * 100.0 for row in rows])
    if moisture.max() <= 0:
        column = "moisture" if "moisture" in first else "mass"
        reader.fail(rows[-1]["line"], column, f"specimen {name!r} gains no moisture "
                                              f"(largest gain {moisture.max():.4g} %): nothing to fit")
        return None
    width, length = (next((row[key] for row in rows if row.get(key) is not None), None)
                     for key in EDGES)
    return Specimen(name=name, temperature=first["temperature"],
                    relative_humidity=first["relative_humidity"], thickness=first["thickness"],
                    width=width, length=length, time=np.array(times),
                    moisture=moisture, lines=np.array([row["line"] for row in rows]))
