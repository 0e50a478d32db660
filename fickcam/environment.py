"""Climate history: temperature T(t) and relative humidity RH(t).

A history is a sequence of segments [t_k, t_k+1): held at the segment's values
(a step at t_k) or ramping linearly from the previous segment's end values. A
CSV history (columns time, temperature, relative_humidity; units in the
header, e.g. ``time [d]``) is piecewise linear between its rows. Both are
right-continuous functions of time; past the end the last values are held.
"""
from __future__ import annotations

import csv
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .units import to_si

_HEADER = re.compile(r"^\s*(?P<name>[A-Za-z_]+)\s*(?:[\[(](?P<unit>[^\])]*)[\])])?\s*$")
_COLUMNS = {"time": ("time", "s"), "temperature": ("temperature", "K"),
            "relative_humidity": ("percent", "%")}


@dataclass(frozen=True, eq=False)
class Environment:
    """Piecewise history: ``change_times`` (n+1, s), segment end values
    ``temperature_end`` / ``humidity_end`` (n), ``ramp`` flags (n) and the
    values at t = 0 (``temperature_start``, ``humidity_start``)."""

    change_times: np.ndarray
    temperature_end: np.ndarray
    humidity_end: np.ndarray
    ramp: np.ndarray
    temperature_start: float
    humidity_start: float
    reference_temperature: float
    initial_moisture: float

    # ------------------------------------------------------------------ build
    @classmethod
    def from_section(cls, section, *, base_dir: Path = Path(".")) -> "Environment":
        """From the validated ``environment:`` section of a scene."""
        if section.history is not None:
            durations = np.array([s.duration for s in section.history])
            temps = np.array([s.temperature for s in section.history])
            rh = np.array([s.relative_humidity for s in section.history])
            ramp = np.array([s.ramp for s in section.history], dtype=bool)
            change = np.concatenate([[0.0], np.cumsum(durations)])
            return cls(change, temps, rh, ramp, float(temps[0]), float(rh[0]),
                       section.reference_temperature, section.initial_moisture)
        path = Path(section.history_file)
        if not path.is_absolute():
            path = base_dir / path
        times, temps, rh = read_history_csv(path)
        return cls.from_samples(times, temps, rh, section.reference_temperature,
                                section.initial_moisture)

    @classmethod
    def from_samples(cls, times, temperature, relative_humidity, reference_temperature,
                     initial_moisture=0.0) -> "Environment":
        """Piecewise-linear history through samples (first time must be 0)."""
        times = np.asarray(times, float)
        if times.size < 2:
            raise ValueError("a history file needs at least two rows")
        if times[0] != 0:
            raise ValueError("a history file must start at time 0")
        if np.any(np.diff(times) <= 0):
            raise ValueError("history times must increase strictly")
        temperature = np.asarray(temperature, float)
        relative_humidity = np.asarray(relative_humidity, float)
        if np.any(temperature <= 0):
            raise ValueError("history temperatures must be above absolute zero")
        if np.any((relative_humidity < 0) | (relative_humidity > 100)):
            raise ValueError("relative humidity must lie between 0 and 100 %")
        return cls(times, temperature[1:], relative_humidity[1:],
                   np.ones(times.size - 1, dtype=bool), float(temperature[0]),
                   float(relative_humidity[0]), reference_temperature, initial_moisture)

    # --------------------------------------------------------------- evaluate
    @property
    def end(self) -> float:
        return float(self.change_times[-1])

    def _segment_start_values(self, end_values: np.ndarray, start: float) -> np.ndarray:
        return np.concatenate([[start], end_values[:-1]])

    def _evaluate(self, t, end_values, start) -> np.ndarray:
        t = np.asarray(t, float)
        n = end_values.size
        k = np.clip(np.searchsorted(self.change_times, t, side="right") - 1, 0, n - 1)
        t0 = self.change_times[k]
        t1 = self.change_times[k + 1]
        begin = self._segment_start_values(end_values, start)[k]
        frac = np.clip((t - t0) / (t1 - t0), 0.0, 1.0)
        held = end_values[k]
        ramped = begin + (end_values[k] - begin) * frac
        return np.where(self.ramp[k], ramped, held)

    def temperature(self, t) -> np.ndarray:
        """T(t) in K (right-continuous)."""
        return self._evaluate(t, self.temperature_end, self.temperature_start)

    def relative_humidity(self, t) -> np.ndarray:
        """RH(t) in percent (right-continuous)."""
        return self._evaluate(t, self.humidity_end, self.humidity_start)

    def hottest(self) -> tuple[int, float]:
        """(segment index, temperature) of the hottest point of the history."""
        index = int(np.argmax(self.temperature_end))
        value = float(self.temperature_end[index])
        if self.temperature_start > value:
            return 0, self.temperature_start
        return index, value

    def exposure(self, saturation_moisture):
        """The diffusion boundary history of a part whose material saturates at
        ``saturation_moisture(T, RH)`` (weight %)."""
        from .diffusion import Exposure

        def surface_moisture(t):
            return saturation_moisture(self.temperature(t), self.relative_humidity(t))

        return Exposure(change_times=self.change_times.copy(), ramp=self.ramp.copy(),
                        temperature=self.temperature, surface_moisture=surface_moisture,
                        initial_moisture=self.initial_moisture)


def read_history_csv(path: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Read columns time, temperature, relative_humidity with units in the header
    (``time [d], temperature [degC], relative_humidity [%]``; no unit = SI, RH in %)."""
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            rows = [row for row in csv.reader(handle) if row and not row[0].lstrip().startswith("#")]
    except FileNotFoundError:
        raise ValueError(f"history file {str(path)!r} not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"cannot read history file {str(path)!r}: {exc}") from None
    if not rows:
        raise ValueError(f"history file {str(path)!r} is empty")
    units: dict[str, tuple[int, str]] = {}
    for index, cell in enumerate(rows[0]):
        match = _HEADER.match(cell)
        if not match or match.group("name") not in _COLUMNS:
            raise ValueError(f"history file header {cell!r}: expected time, temperature, relative_humidity")
        units[match.group("name")] = (index, (match.group("unit") or "").strip())
    missing = set(_COLUMNS) - set(units)
    if missing:
        raise ValueError(f"history file lacks column(s) {', '.join(sorted(missing))}")
    columns = {}
    for name, (index, unit) in units.items():
        dimension = _COLUMNS[name][0]
        values = []
        for line, row in enumerate(rows[1:], start=2):
            try:
                text = row[index].strip()
                values.append(to_si(f"{text} {unit}" if unit else float(text), dimension))
            except (IndexError, ValueError) as exc:
                raise ValueError(f"history file line {line}, column {name}: {exc}") from None
        columns[name] = np.array(values)
    return columns["time"], columns["temperature"], columns["relative_humidity"]
