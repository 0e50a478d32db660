"""Climate records: chamber logs and typical-meteorological-year weather files.

Three formats are read into one :class:`ClimateRecord` (time from the first
row in s, temperature in K, relative humidity in %):

- a CSV log with columns ``time, temperature, relative_humidity`` and units in
  the header (``time [h], temperature [degC], relative_humidity [%]``; no unit
  means SI, RH in %, and a column that then reads implausibly, as a record shorter
  than a day or colder than 150 K, is refused with the likely unit);
- a TMY3 CSV (NREL's typical meteorological year, 8760 hourly rows; read with
  ``pvlib.iotools.read_tmy3``) and an EnergyPlus EPW file
  (``pvlib.iotools.read_epw``): dry-bulb temperature and relative humidity.
  pvlib is the optional extra ``fickcam[weather]``.

A weather year is periodic: it repeats for multi-year ageing. A chamber log is
not: past its last row the last state is held (the environment says so).

Problems name the file, the line and the column: ``chamber.csv:57 time:
repeated timestamp (also on line 56)``.
"""
from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..extras import require
from ..quantities.parsing import to_si
from ..quantities.plausibility import (RECORD_LENGTH, RELATIVE_HUMIDITY, TEMPERATURE, Verdict,
                                       plausible_units)
from .csvrows import CsvError, numbered_rows

_HEADER = re.compile(r"^\s*(?P<name>[A-Za-z_]+)\s*(?:[\[(](?P<unit>[^\])]*)[\])])?\s*$")
_COLUMNS = {"time": "time", "temperature": "temperature", "relative_humidity": "percent"}
PVLIB_PREFIX = "pvlib:"
# EnergyPlus Auxiliary Programs, "Weather Converter Program", EPW data
# dictionary: missing dry-bulb is 99.9 degC, missing relative humidity 999 %.
_EPW_MISSING = {"temp_air": 99.9, "relative_humidity": 999.0}
_EPW_HEADER_LINES = 8   # LOCATION ... DATA PERIODS
# the columns read, by their index in a row: EPW data dictionary (dry bulb 7th, RH 9th
# field); TMY3 (Wilcox & Marion 2008, Table 1-1: dry-bulb 32nd, RH 38th)
_EPW_COLUMNS = {"temp_air": 6, "relative_humidity": 8}
_TMY3_COLUMNS = {"temp_air": 31, "relative_humidity": 37}
_TMY3_HEADER_LINES = 2  # site line, column names
#: the hourly rows of a weather year (TMY3 and EPW: 365 days; 8784 in a leap year's file)
YEAR_HOURS = (8760, 8784)
#: how many lines before the last one its form is compared with (:func:`check_last_line`)
NEIGHBOURS = 24
_FIRST_LINE_CHARS = 4096  # what is read of the first line to tell the three formats apart


class RecordError(ValueError):
    """A problem in a climate record, located as ``file:LINE column: reason``.

    Parameters
    ----------
    path : pathlib.Path
        The record file (its name is shown).
    line : int or None
        The line, from 1; None when the problem is the whole file's.
    column : str or None
        The column, if one is at fault.
    reason : str
        What is wrong.
    """

    def __init__(self, path: Path, line: int | None, column: str | None, reason: str):
        where = f"{Path(path).name}:{line}" if line is not None else Path(path).name
        super().__init__(f"{where} {column}: {reason}" if column else f"{where}: {reason}")


@dataclass(frozen=True)
class ClimateRecord:
    """Samples of T(t) and RH(t), linear between rows.

    Parameters
    ----------
    time : numpy.ndarray
        The sample times from the record's start [s], increasing.
    temperature : numpy.ndarray
        The air temperature [K].
    relative_humidity : numpy.ndarray
        The relative humidity [%].
    source : str
        Where the record comes from, for messages.
    period : float, optional
        The period [s] when the record is a weather year that repeats; None when the last
        state holds after its end.
    site : str
        A weather file's site (``"Greensboro Piedmont Triad Int, NC"``), else "".
    """

    time: np.ndarray
    temperature: np.ndarray
    relative_humidity: np.ndarray
    source: str
    period: float | None = None
    site: str = ""  # a weather file's site ("Greensboro Piedmont Triad Int, NC"), else ""

    @property
    def end(self) -> float:
        return float(self.time[-1])

    def covering(self, until: float) -> "ClimateRecord":
        """The record repeated (if periodic) until it reaches ``until``.

        Parameters
        ----------
        until : float
            The time it must cover [s].

        Returns
        -------
        ClimateRecord
            This record when it is not periodic or already long enough.
        """
        if self.period is None or until <= self.end:
            return self
        repeats = math.ceil((until - self.end) / self.period) + 1
        shifts = np.repeat(np.arange(repeats) * self.period, self.time.size)
        return ClimateRecord(np.tile(self.time, repeats) + shifts,
                             np.tile(self.temperature, repeats),
                             np.tile(self.relative_humidity, repeats),
                             f"{self.source}, repeated {repeats} times", self.period,
                             self.site)

    def cut(self, until: float) -> "ClimateRecord":
        """The rows up to the first at or past ``until``.

        A run computes nothing past its last ageing time (a year of hourly rows read for a month
        costs a month).

        Parameters
        ----------
        until : float
            The last time needed [s].

        Returns
        -------
        ClimateRecord
            The shortened record (this one when nothing is cut).
        """
        last = max(int(np.searchsorted(self.time, until, side="left")), 1)
        if last >= self.time.size - 1:
            return self
        keep = slice(0, last + 1)
        return ClimateRecord(self.time[keep], self.temperature[keep],
                             self.relative_humidity[keep], self.source, self.period, self.site)


def resolve_record_path(text: str, base_dir: Path) -> Path:
    """The file a scene's ``history_file`` names.

    Relative to the scene, or ``pvlib:NAME`` for a file shipped in pvlib's data folder (e.g.
    ``pvlib:723170TYA.CSV``, Greensboro NC; ``pvlib:703165TY.csv``, Sand Point AK).

    Parameters
    ----------
    text : str
        The ``history_file`` value.
    base_dir : pathlib.Path
        The scene's folder.

    Returns
    -------
    pathlib.Path
        The file (not checked to exist, but for ``pvlib:``).

    Raises
    ------
    ValueError
        When pvlib ships no such file (naming the weather files it has).
    fickcam.extras.MissingExtra
        For ``pvlib:`` without pvlib installed.
    """
    if text.startswith(PVLIB_PREFIX):
        pvlib = require("weather")
        folder = Path(pvlib.__file__).parent / "data"
        name = text[len(PVLIB_PREFIX):].strip()
        path = folder / name
        if not path.is_file():
            shipped = sorted(p.name for p in folder.glob("*") if p.suffix.lower() in (".csv", ".epw"))
            raise ValueError(f"pvlib ships no file {name!r}; its weather files: "
                             f"{', '.join(n for n in shipped if 'TY' in n)}")
        return path
    path = Path(text)
    return path if path.is_absolute() else base_dir / path


def site_name(text: str, base_dir: Path) -> str:
    """The site of the weather file a scene's ``history_file`` names, for legends.

    TMY3 ``Name``, ``State``; EPW ``city``, ``state-prov``, as pvlib reads them.

    Parameters
    ----------
    text, base_dir
        The ``history_file`` value and the scene's folder, as for
        :func:`resolve_record_path`.

    Returns
    -------
    str
        ``"NAME, REGION"``; "" for a chamber log or a file that cannot be read here.
    """
    try:
        return read_record(resolve_record_path(text, base_dir)).site
    except ValueError:
        return ""


def _site(name, region) -> str:
    """``NAME, REGION`` with an all-capitals name in title case (TMY3 writes capitals)."""
    name = str(name or "").strip('"').strip()
    name = name.title() if name.isupper() else name
    return ", ".join(part for part in (name, str(region or "").strip()) if part)


def read_record(path: Path) -> ClimateRecord:
    """Read a chamber CSV, a TMY3 CSV or an EPW file (chosen by its content).

    A scene reads its record once, when it is validated, and keeps the climate built from
    it (``Scene.environment``).

    Parameters
    ----------
    path : pathlib.Path
        The record file.

    Returns
    -------
    ClimateRecord
        The record, in SI (s, K) and % RH.

    Raises
    ------
    ValueError
        When the file is missing or unreadable; :class:`RecordError` (a ValueError) with its
        line and column for a problem inside it.
    """
    return _read_record(Path(path))


def _read_record(path: Path) -> ClimateRecord:
    try:
        with open(path, newline="", encoding="utf-8", errors="replace") as handle:
            first = handle.readline(_FIRST_LINE_CHARS)  # enough to tell the format
    except FileNotFoundError:
        raise ValueError(f"history file {str(path)!r} not found") from None
    except OSError as exc:
        raise ValueError(f"cannot read history file {str(path)!r}: {exc}") from None
    if path.suffix.lower() == ".epw" or first.startswith("LOCATION,"):
        return _read_epw(path)
    if _looks_like_tmy3(first):
        return _read_tmy3(path)
    return read_history_csv(path)


# -------------------------------------------------------------- chamber CSV
def read_history_csv(path: Path) -> ClimateRecord:
    """Read a chamber log: columns time, temperature, relative_humidity with units in the header.

    Parameters
    ----------
    path : pathlib.Path
        The CSV file (``time [h], temperature [degC], relative_humidity [%]``).

    Returns
    -------
    ClimateRecord
        The record, in SI (s, K) and % RH; not periodic.

    Raises
    ------
    RecordError
        With file, line and column for a missing column, a value that is not a number, a
        time that does not increase, or a column without unit whose values are almost
        certainly a unit slip.
    """
    path = Path(path)
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            rows = [(line, row) for line, row in numbered_rows(handle) if _holds_data(row)]
    except FileNotFoundError:
        raise ValueError(f"history file {str(path)!r} not found") from None
    except CsvError as exc:
        raise RecordError(path, exc.line, None, exc.reason) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"cannot read history file {str(path)!r}: {exc}") from None
    if not rows:
        raise RecordError(path, None, None, "the file is empty")
    header_line, header = rows[0]
    units: dict[str, tuple[int, str]] = {}
    for index, cell in enumerate(header):
        match = _HEADER.match(cell)
        if not match or match.group("name") not in _COLUMNS:
            raise RecordError(path, header_line, cell.strip() or f"column {index + 1}",
                              "expected the columns time, temperature, relative_humidity")
        units[match.group("name")] = (index, (match.group("unit") or "").strip())
    missing = set(_COLUMNS) - set(units)
    if missing:
        raise RecordError(path, header_line, None, f"no column {', '.join(sorted(missing))}")
    check_last_line(path, rows[1:], {name: index for name, (index, _) in units.items()})
    lines = np.array([line for line, _ in rows[1:]])
    columns = {name: _column(path, rows[1:], name, index, unit)
               for name, (index, unit) in units.items()}
    for name, (_, unit) in units.items():
        if not unit:
            _unit_slip(path, header_line, name, columns[name])
    return _checked(path, lines, columns["time"], columns["temperature"],
                    columns["relative_humidity"], f"chamber record {path.name}", None,
                    must_start_at_zero=True)


def _ends_with_newline(path: Path) -> bool:
    with open(path, "rb") as handle:
        handle.seek(0, 2)
        if handle.tell() == 0:
            return True
        handle.seek(-1, 2)
        return handle.read(1) in (b"\n", b"\r")


def _form(cell: str) -> tuple[int, int] | None:
    """(digits, decimals) of a number as written; None for one in exponent form."""
    text = cell.strip()
    if "e" in text.lower():
        return None
    digits = sum(ch.isdigit() for ch in text)
    return digits, len(text.partition(".")[2]) if "." in text else 0


def check_last_line(path: Path, rows: list[tuple[int, list[str]]], columns: dict[str, int]) -> None:
    """Refuse a last line that the file's end cut short.

    A file that ends inside a line (no new line after it) was probably cut while it was
    written or copied: its last line is then held to the form of the :data:`NEIGHBOURS`
    lines before it. It must have as many fields, and each column read must have as many
    decimals, and no fewer digits than the fewest of those lines: ``97,112.86,7`` after lines
    ending in ``70.19`` is a relative humidity torn from 70.19 %, not 7 %.

    Parameters
    ----------
    path : pathlib.Path
        The file.
    rows : list of (int, list of str)
        Its data rows, each with its line (from 1).
    columns : dict of str to int
        The columns read -> their index in a row.

    Raises
    ------
    RecordError
        At the last line, naming the field or the column that is short.
    """
    if len(rows) < 2 or _ends_with_newline(path):
        return
    line, last = rows[-1]
    before = [row for _, row in rows[-1 - NEIGHBOURS:-1]]
    fields = min(len(row) for row in before)
    advice = "complete it and end the file with a new line, or remove it"
    if len(last) < fields:
        raise RecordError(path, line, None, f"the file ends inside this line, which has "
                          f"{len(last)} field(s) where the lines before have {fields}: it looks "
                          f"cut short; {advice}")
    for name, index in columns.items():
        forms = [_form(row[index]) for row in before if index < len(row)]
        mine = _form(last[index])
        if mine is None or not forms or None in forms:
            continue
        digits, decimals = min(f[0] for f in forms), min(f[1] for f in forms)
        if mine[1] < decimals or mine[0] < digits:
            raise RecordError(path, line, name, (
                f"the file ends inside this line, and {last[index].strip()!r} is shorter than "
                f"the column on the lines before ({digits} digits, {decimals} decimals): it "
                f"looks cut short; {advice}"))


def _unit_slip(path, header_line: int, name: str, values: np.ndarray) -> None:
    """Refuse a column without a unit in the header whose values read in SI are almost
    certainly a slip (times in days, temperatures in degC), naming the likely unit."""
    reading, number = {
        "time": (RECORD_LENGTH, float(np.ptp(values)) if values.size else 0.0),
        "temperature": (TEMPERATURE, float(np.min(values, initial=np.inf))),
        "relative_humidity": (RELATIVE_HUMIDITY, float(np.max(values, initial=0.0))),
    }[name]
    if not math.isfinite(number) or reading.verdict(number) is not Verdict.IMPLAUSIBLE:
        return
    units = plausible_units(number, reading) if name != "relative_humidity" else []
    header = " or ".join(f"'{name} [{unit}]'" for unit in units) or "values in percent (0 to 100)"
    raise RecordError(path, header_line, name, (
        f"the header gives no unit, so the column is read in {reading.unit}: {number:g} "
        f"{reading.unit} is an implausible {reading.what} ({reading.context}): write {header}"))


def _holds_data(row: list[str]) -> bool:
    """A row with some text that is not a comment (``#`` first)."""
    first = row[0].strip() if row else ""
    if first:
        return not first.startswith("#")
    return any(cell.strip() for cell in row[1:])


def _column(path, rows, name, index, unit) -> np.ndarray:
    """One column in SI: numbers read at once (row by row only when one is not a finite
    number, so that it names its line), then converted at once by the unit's affine map
    (exact for degC)."""
    try:
        values = np.array([row[index] for _, row in rows], dtype=float)
    except (ValueError, IndexError):
        values = None
    if values is None or not np.all(np.isfinite(values)):
        values = _column_by_row(path, rows, name, index)
    if not unit:
        return values
    try:
        offset = to_si(f"0 {unit}", _COLUMNS[name])
        scale = to_si(f"1 {unit}", _COLUMNS[name]) - offset
    except ValueError as exc:
        raise RecordError(path, rows[0][0] - 1 if rows else None, name, str(exc)) from None
    return offset + scale * values


def _column_by_row(path, rows, name, index) -> np.ndarray:
    """The column read row by row: the first cell that is no finite number names its line."""
    values = np.empty(len(rows))
    for k, (line, row) in enumerate(rows):
        text = row[index].strip() if index < len(row) else ""
        try:
            values[k] = float(text)
        except ValueError:
            reason = "missing value" if text.lower() in ("", "nan", "na", "n/a") \
                else f"{text!r} is not a number"
            raise RecordError(path, line, name, reason) from None
        if not math.isfinite(values[k]):
            raise RecordError(path, line, name, "missing value")
    return values


def _checked(path, lines, time, temperature, humidity, source, period, *,
             must_start_at_zero=False) -> ClimateRecord:
    """Refuse what a record cannot mean, naming the first offending line."""
    if time.size < 2:
        raise RecordError(path, None, None, "a history needs at least two rows")
    if must_start_at_zero and time[0] != 0:
        raise RecordError(path, lines[0], "time", "the first row must be at time 0")
    step = np.diff(time)
    if np.any(step <= 0):
        k = int(np.argmax(step <= 0)) + 1
        earlier = lines[int(np.flatnonzero(time[:k] >= time[k])[0])]
        reason = (f"repeated timestamp (also on line {earlier})" if step[k - 1] == 0
                  else f"time goes back (line {earlier} is later): rows must be sorted")
        raise RecordError(path, lines[k], "time", reason)
    if np.any(temperature <= 0):
        k = int(np.argmax(temperature <= 0))
        raise RecordError(path, lines[k], "temperature", "at or below absolute zero")
    bad = (humidity < 0) | (humidity > 100)
    if np.any(bad):
        k = int(np.argmax(bad))
        raise RecordError(path, lines[k], "relative_humidity",
                          f"{humidity[k]:g} % is outside 0 to 100 %")
    return ClimateRecord(time - time[0], temperature, humidity, source, period)


# ------------------------------------------------------------ weather years
def _pvlib_iotools():
    """pvlib's readers, or the one-line install hint (a ValueError) without pvlib."""
    return require("weather").iotools


def _looks_like_tmy3(first_line: str) -> bool:
    """TMY3's first line: USAF id, "station name", state, time zone, lat, lon, elevation."""
    fields = next(csv.reader([first_line]), [])
    return len(fields) == 7 and fields[0].strip().isdigit() and len(fields[0].strip()) == 6


def _whole_year(path: Path, rows: int, first_data_line: int, columns: dict[str, int]) -> None:
    """Refuse a weather file that does not hold a year of hourly rows, or whose last line
    is torn (:func:`check_last_line`)."""
    if rows not in YEAR_HOURS:
        short = "it looks cut short" if rows < YEAR_HOURS[0] else "more than one year"
        raise RecordError(path, first_data_line + rows - 1 if rows else None, None, (
            f"{rows:,} hourly rows where a weather year has {YEAR_HOURS[0]:,} ({short})"))
    if not _ends_with_newline(path):
        with open(path, newline="", encoding="utf-8", errors="replace") as handle:
            tail = list(numbered_rows(handle))[-1 - NEIGHBOURS:]
        check_last_line(path, tail, columns)


def _weather_record(path, frame, first_data_line, missing, source, site) -> ClimateRecord:
    """Hourly dry-bulb (degC) and RH (%) of one weather year, as a periodic record."""
    lines = first_data_line + np.arange(len(frame))
    for column, sentinel in missing.items():
        values = frame[column].to_numpy(float)
        absent = ~np.isfinite(values) | (values == sentinel if sentinel is not None else False)
        if np.any(absent):
            raise RecordError(path, int(lines[np.argmax(absent)]), column, "missing value")
    seconds = (frame.index - frame.index[0]).total_seconds().to_numpy()
    step = np.diff(seconds)
    if step.size and np.any(step != step[0]):
        k = int(np.argmax(step != step[0])) + 1
        raise RecordError(path, int(lines[k]), "time",
                          f"weather rows must be evenly spaced ({step[0] / 3600:g} h)")
    temperature = frame["temp_air"].to_numpy(float) + 273.15
    humidity = frame["relative_humidity"].to_numpy(float)
    period = seconds[-1] + step[0] if step.size else None
    return replace(_checked(path, lines, seconds, temperature, humidity, source, period),
                   site=site)


def _read_tmy3(path: Path) -> ClimateRecord:
    # pvlib.iotools.read_tmy3 (Wilcox & Marion, "Users Manual for TMY3 Data
    # Sets", NREL/TP-581-43156, 2008); coerce_year gives one continuous year
    # (TMY months come from different years).
    iotools = _pvlib_iotools()
    try:
        frame, meta = iotools.read_tmy3(path, coerce_year=2001, map_variables=True)
    except RecordError:
        raise
    except Exception as exc:  # pvlib raises several types on malformed files
        raise RecordError(path, None, None, f"not a readable TMY3 file ({exc})") from None
    _whole_year(path, len(frame), _TMY3_HEADER_LINES + 1, _TMY3_COLUMNS)
    name = str(meta.get("Name", "")).strip('"').strip()
    source = f"TMY3 {name}, {meta.get('State', '')} (USAF {meta.get('USAF', '?')})"
    return _weather_record(path, frame, _TMY3_HEADER_LINES + 1,
                           {"temp_air": None, "relative_humidity": None}, source,
                           _site(name, meta.get("State")))


def _read_epw(path: Path) -> ClimateRecord:
    # pvlib.iotools.read_epw (EnergyPlus weather format, U.S. DOE EnergyPlus
    # "Auxiliary Programs", Weather Converter: EPW data dictionary).
    iotools = _pvlib_iotools()
    try:
        frame, meta = iotools.read_epw(path, coerce_year=2001)
    except RecordError:
        raise
    except Exception as exc:
        raise RecordError(path, None, None, f"not a readable EPW file ({exc})") from None
    _whole_year(path, len(frame), _EPW_HEADER_LINES + 1, _EPW_COLUMNS)
    source = f"EPW {meta.get('city', '')}, {meta.get('country', '')}".strip(", ")
    return _weather_record(path, frame, _EPW_HEADER_LINES + 1, _EPW_MISSING, source,
                           _site(meta.get("city"), meta.get("state-prov")))
