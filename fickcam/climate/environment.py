"""Climate history: temperature T(t) and relative humidity RH(t).

A history is a sequence of segments [t_k, t_k+1): held at the segment's values
(a step at t_k) or ramping linearly from the previous segment's end values. A
CSV history (columns time, temperature, relative_humidity; units in the
header, e.g. ``time [d]``) is piecewise linear between its rows. Both are
right-continuous functions of time; past the end the last values are held.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from types import MappingProxyType
from typing import Callable, Mapping

import numpy as np

from .damp_heat import STANDARD_TESTS, Segments, standard_climate
from .records import read_history_csv, read_record, resolve_record_path
from ..diffusion import Exposure

__all__ = ["ClimateSeen", "Environment", "read_history_csv", "summary_edges"]

#: interval lengths of a climate summary [s] (an hour, a day, a week, 30 days): the shortest
#: that cuts the history into at most SUMMARY_INTERVALS intervals
SUMMARY_STEPS = (3600.0, 86400.0, 7 * 86400.0, 30 * 86400.0)
SUMMARY_INTERVALS = 1000


@dataclass(frozen=True, eq=False)
class Environment(Segments):
    """A piecewise climate history, with what a run needs besides.

    Parameters
    ----------
    change_times, temperature_end, humidity_end, ramp, temperature_start, humidity_start
        The history as :class:`~fickcam.climate.damp_heat.Segments` holds it: change times [s],
        end temperatures [K] and humidities [%], ramp flags, and the values at t = 0
        [K, %].
    reference_temperature : float
        The temperature at which the parts are made and dry [K].
    initial_moisture : float
        The parts' moisture at t = 0 [wt %].
    source : str
        Where the history comes from, for messages.
    notes : tuple of str
        What a run should be told (e.g. a record held past its end).
    state_times : numpy.ndarray, optional
        States given directly (``environment.state``): their times [s]; None for a climate
        history.
    state_moisture : numpy.ndarray, optional
        Their moisture [wt %], NaN where the state gives a relative humidity instead.
    """

    reference_temperature: float
    initial_moisture: float
    source: str = "history segments"
    notes: tuple[str, ...] = ()   # what a run should be told (e.g. a record held past its end)
    #: states given directly (``environment.state``): their times (s) and moisture (weight %,
    #: NaN where the state gives a relative humidity instead); None for a climate history
    state_times: np.ndarray | None = None
    state_moisture: np.ndarray | None = None
    #: each material's Exposure, made once (parts of one material share it, and with it
    #: the rescaled clock ``diffusion.clock.clock_of`` builds from a record's rows)
    _exposures: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    # ------------------------------------------------------------------ build
    @classmethod
    def from_section(cls, section, *, base_dir: Path = Path("."),
                     until: float | None = None) -> "Environment":
        """From the validated ``environment:`` section of a scene; ``until`` (s),
        the last requested ageing time, repeats a weather year far enough."""
        reference = (section.reference_temperature, section.initial_moisture)
        if section.history is not None:
            durations = np.array([s.duration for s in section.history])
            temps = np.array([s.temperature for s in section.history])
            rh = np.array([s.relative_humidity for s in section.history])
            ramp = np.array([s.ramp for s in section.history], dtype=bool)
            change = np.concatenate([[0.0], np.cumsum(durations)])
            return cls(change, temps, rh, ramp, float(temps[0]), float(rh[0]), *reference)
        if section.state is not None:
            return cls.from_states(section.states(), *reference)
        if section.test is not None:
            test = standard_climate(section.test, cycles=section.cycles, duration=section.duration,
                                    upper_temperature=section.upper_temperature)
            return cls(test.change_times, test.temperature_end, test.humidity_end, test.ramp,
                       test.temperature_start, test.humidity_start, *reference,
                       source=STANDARD_TESTS[section.test].source)
        record = read_record(resolve_record_path(section.history_file, base_dir))
        if until is not None:
            record = record.covering(until)
        notes = ()
        if until is not None and until <= record.end:
            record = record.cut(until)
        if until is not None and until > record.end * (1 + 1e-12):
            notes = (f"the climate record ({record.source}) ends at "
                     f"{record.end / 86400:g} d: its last state (T = {record.temperature[-1] - 273.15:.1f} degC, "
                     f"RH = {record.relative_humidity[-1]:.0f} %) is held to {until / 86400:g} d",)
        return cls.from_samples(record.time, record.temperature, record.relative_humidity,
                                *reference, source=record.source, notes=notes)

    @classmethod
    def from_samples(cls, times, temperature, relative_humidity, reference_temperature,
                     initial_moisture=0.0, *, source: str = "samples",
                     notes: tuple[str, ...] = ()) -> "Environment":
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
                   float(relative_humidity[0]), reference_temperature, initial_moisture,
                   source=source, notes=notes)

    @classmethod
    def from_states(cls, states, reference_temperature, initial_moisture=0.0) -> "Environment":
        """States given directly (uniform moisture and temperature, no diffusion), each held
        from its time to the next; the last is held for one second past its time so that
        every state is a segment of the history."""
        times = np.array([s.time for s in states], float)
        temps = np.array([s.temperature if s.temperature is not None
                          else reference_temperature + s.temperature_rise for s in states])
        if np.any(temps <= 0):
            raise ValueError("a state's temperature must be above absolute zero")
        rh = np.array([np.nan if s.relative_humidity is None else s.relative_humidity
                       for s in states])
        moisture = np.array([np.nan if s.moisture is None else s.moisture for s in states])
        change = np.concatenate([times, [times[-1] + 1.0]])
        return cls(change, temps, rh, np.zeros(times.size, bool), float(temps[0]), float(rh[0]),
                   reference_temperature, initial_moisture, source="states given directly",
                   state_times=times, state_moisture=moisture)

    def uniform_moisture(self, saturation_moisture, t) -> np.ndarray:
        """Moisture (weight %) of a part at the given states' times: the state's moisture,
        or the part's equilibrium Mm(T, RH) where the state gives a relative humidity."""
        k = np.clip(np.searchsorted(self.state_times, np.asarray(t, float), side="right") - 1,
                    0, self.state_times.size - 1)
        given = self.state_moisture[k]
        equilibrium = saturation_moisture(self.temperature_end[k],
                                          np.nan_to_num(self.humidity_end[k]))
        return np.where(np.isnan(given), equilibrium, given)

    # --------------------------------------------------------------- evaluate
    @property
    def end(self) -> float:
        return float(self.change_times[-1])

    def _segment_start_values(self, end_values: np.ndarray, start: float) -> np.ndarray:
        return np.concatenate([[start], end_values[:-1]])

    def _evaluate(self, t, end_values, start, where=None) -> np.ndarray:
        """The history of ``end_values`` at ``t``; ``where``: ``_where(t)`` when known."""
        k, frac = self._where(t) if where is None else where
        begin = self._segment_start_values(end_values, start)[k]
        held = end_values[k]
        ramped = begin + (end_values[k] - begin) * frac
        return np.where(self.ramp[k], ramped, held)

    def _where(self, t) -> tuple[np.ndarray, np.ndarray]:
        """(segment, fraction of it) of each time ``t``."""
        t = np.asarray(t, float)
        n = self.ramp.size
        k = np.clip(np.searchsorted(self.change_times, t, side="right") - 1, 0, n - 1)
        t0 = self.change_times[k]
        t1 = self.change_times[k + 1]
        return k, np.clip((t - t0) / (t1 - t0), 0.0, 1.0)

    def temperature(self, t) -> np.ndarray:
        """T(t) in K (right-continuous)."""
        return self._evaluate(t, self.temperature_end, self.temperature_start)

    def relative_humidity(self, t) -> np.ndarray:
        """RH(t) in percent (right-continuous)."""
        return self._evaluate(t, self.humidity_end, self.humidity_start)

    def interval_summary(self, edges) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """The climate over each interval between ``edges``: its mean and its range, exact
        for the history's straight pieces and steps (past the end of the history its last
        values are held).

        Parameters
        ----------
        edges : array_like
            Interval edges [s], increasing, at least two.

        Returns
        -------
        dict
            ``"temperature"``: (mean, lowest, highest) [K] and ``"relative_humidity"``:
            (mean, lowest, highest) [%], each an array with one value per interval.
        """
        edges = np.asarray(edges, float)
        out = {}
        for name, ends, start in (("temperature", self.temperature_end, self.temperature_start),
                                  ("relative_humidity", self.humidity_end, self.humidity_start)):
            begin = self._segment_start_values(ends, start)
            after = np.where(self.ramp, begin, ends)  # just after t_k; just before t_k+1: ends
            out[name] = piecewise_linear_summary(self.change_times, after, ends, edges)
        return out

    def seen_at(self, times, saturations: Mapping[str, Callable], *,
                summary: bool = True) -> "ClimateSeen":
        """All a run reads of this climate at its ageing times, asked at once: T and RH
        there, each part's exposure (or, where the states are given, its uniform moisture)
        and the climate between the times.

        Parameters
        ----------
        times : array_like
            Ageing times [s], increasing.
        saturations : mapping of str to callable
            Part name -> its material's saturation moisture Mm(T [K], RH [%]) [weight %],
            for the parts that absorb.
        summary : bool
            Also summarise the climate between the times (a stored run's record).

        Returns
        -------
        ClimateSeen
            The climate at ``times`` [K, %, weight %].
        """
        times = np.asarray(times, float)
        given = self.state_times is not None
        between, centres = {}, None
        if summary and not given and times.size and times[-1] > 0:  # states given: no climate
            edges = summary_edges(times[-1])
            between, centres = self.interval_summary(edges), 0.5 * (edges[:-1] + edges[1:])
        return ClimateSeen(
            self, times, self.temperature(times), self.relative_humidity(times),
            MappingProxyType(dict(saturations)),
            MappingProxyType({name: self.exposure(saturation)
                              for name, saturation in saturations.items()}),
            MappingProxyType({name: self.uniform_moisture(saturation, times) for name, saturation
                              in saturations.items()} if given else {}),
            MappingProxyType(between), centres)

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

        if saturation_moisture in self._exposures:
            return self._exposures[saturation_moisture]

        def surface_moisture(t):  # T and RH share the segment lookup
            where = self._where(t)
            return saturation_moisture(
                self._evaluate(t, self.temperature_end, self.temperature_start, where),
                self._evaluate(t, self.humidity_end, self.humidity_start, where))

        exposure = Exposure(change_times=self.change_times.copy(), ramp=self.ramp.copy(),
                            temperature=self.temperature, surface_moisture=surface_moisture,
                            initial_moisture=self.initial_moisture)
        self._exposures[saturation_moisture] = exposure
        return exposure


@dataclass(frozen=True, eq=False)
class ClimateSeen:
    """What a run reads of its climate history at its ageing times, asked of it once
    (:meth:`Environment.seen_at`): the run's stages read these values, not the history.

    Parameters
    ----------
    environment : Environment
        The history (its reference temperature [K], initial moisture [weight %], change
        times [s] and notes).
    times : numpy.ndarray
        The ageing times [s].
    temperature, relative_humidity : numpy.ndarray
        T [K] and RH [%] at ``times``.
    saturations : mapping of str to callable
        Part name -> Mm(T, RH) [weight %] of the parts that absorb.
    exposures : mapping of str to fickcam.diffusion.Exposure
        Part name -> its diffusion boundary history (where the states are given, the
        states held as segments: what a part's exact sheet reads).
    state_moisture : mapping of str to numpy.ndarray
        Part name -> its uniform moisture at ``times`` [weight %] where the states are
        given directly; empty otherwise.
    summary : mapping of str to tuple of numpy.ndarray
        ``"temperature"`` [K] and ``"relative_humidity"`` [%]: (mean, lowest, highest) over
        each interval of :func:`summary_edges`; empty where the states are given or the
        times end at 0.
    summary_times : numpy.ndarray or None
        The intervals' centres [s].
    """

    environment: Environment
    times: np.ndarray
    temperature: np.ndarray
    relative_humidity: np.ndarray
    saturations: Mapping[str, Callable]
    exposures: Mapping[str, Exposure]
    state_moisture: Mapping[str, np.ndarray]
    summary: Mapping[str, tuple]
    summary_times: np.ndarray | None

    @property
    def states_given(self) -> bool:
        """Whether the environment gives the parts' moisture directly (no diffusion)."""
        return self.environment.state_times is not None

    def at(self, times) -> "ClimateSeen":
        """The same parts' climate at other ageing ``times`` [s] (a limit search's), without
        the summary between them."""
        return self.environment.seen_at(times, self.saturations, summary=False)

    def at_rows(self, rows) -> "ClimateSeen":
        """The climate at the ageing times ``rows`` (indices) only, without the summary."""
        return replace(self, times=self.times[rows], temperature=self.temperature[rows],
                       relative_humidity=self.relative_humidity[rows],
                       state_moisture=MappingProxyType({name: moisture[rows] for name, moisture
                                                        in self.state_moisture.items()}),
                       summary=MappingProxyType({}), summary_times=None)


def summary_edges(end: float) -> np.ndarray:
    """Edges of a climate summary: hourly, daily, weekly or 30-day intervals, the shortest
    of them that gives at most SUMMARY_INTERVALS.

    Parameters
    ----------
    end : float
        End of the summary [s], positive.

    Returns
    -------
    numpy.ndarray
        Edges from 0 to ``end`` [s]; the last interval ends at ``end`` and may be shorter.
    """
    step = next((s for s in SUMMARY_STEPS if end / s <= SUMMARY_INTERVALS), SUMMARY_STEPS[-1])
    starts = np.arange(0.0, end, step)
    return np.append(starts[end - starts > 1e-6 * step], end)


def piecewise_linear_summary(change_times, after, before, edges):
    """Mean, lowest and highest value over intervals of a function made of straight pieces.

    The function runs straight from ``after[k]`` just after ``change_times[k]`` to
    ``before[k]`` just before ``change_times[k+1]`` (a step where ``after[k]`` differs
    from ``before[k-1]``) and holds ``before[-1]`` past the last change time. The mean is
    the exact integral over the interval (trapezoids are exact for straight pieces) divided
    by its length; the extremes are among the interval's end values and the pieces' ends
    inside it.

    Parameters
    ----------
    change_times : numpy.ndarray
        Times where the pieces meet [s], increasing, shape (n + 1,).
    after, before : numpy.ndarray
        Each piece's value at its start and at its end [any unit], shape (n,).
    edges : numpy.ndarray
        Interval edges [s], increasing.

    Returns
    -------
    tuple of numpy.ndarray
        (mean, lowest, highest) per interval, in the unit of ``after`` and ``before``.
    """
    t0, t1 = change_times[:-1], change_times[1:]
    done = np.concatenate([[0.0], np.cumsum((t1 - t0) * (after + before) / 2.0)])

    def value_and_integral(t, side):
        k = np.clip(np.searchsorted(change_times, t, side=side) - 1, 0, after.size - 1)
        inside = np.minimum(t, t1[k])
        value = after[k] + (before[k] - after[k]) * (inside - t0[k]) / (t1[k] - t0[k])
        integral = (done[k] + (inside - t0[k]) * (after[k] + value) / 2.0
                    + np.maximum(t - t1[k], 0.0) * before[k])
        return value, integral

    first, start_integral = value_and_integral(edges[:-1], "right")
    last, end_integral = value_and_integral(edges[1:], "left")
    low, high = np.minimum(first, last), np.maximum(first, last)
    n = edges.size - 1
    bins = np.concatenate([np.searchsorted(edges, t0, "right"), np.searchsorted(edges, t1, "left")]) - 1
    values = np.concatenate([after, before])
    inside = (bins >= 0) & (bins < n)
    np.minimum.at(low, bins[inside], values[inside])
    np.maximum.at(high, bins[inside], values[inside])
    mean = (end_integral - start_integral) / np.diff(edges)
    return np.clip(mean, low, high), low, high  # round-off must not lift a mean off its range
