"""Standard damp-heat test climates, by name (``environment: {test: NAME}``).

Each test becomes a climate history of held and ramped segments (the same
form as ``environment.history``). Nominal values sit at the centre of the
standard's tolerance band. Sources:

- ``steady_damp_heat``: IEC 60068-2-78 Test Cab, damp heat steady state:
  40 +/- 2 degC, 93 +/- 3 % RH, durations 12 h to 56 d (21 d is common).
- ``damp_heat_85_85``: JEDEC JESD22-A101 (temperature-humidity bias life) and
  IEC 61215-2 MQT 13 (damp heat for PV modules): 85 +/- 2 degC, 85 +/- 5 % RH,
  1000 h.
- ``cyclic_damp_heat``: IEC 60068-2-30 Test Db, damp heat cyclic (12 h + 12 h
  cycle), variant 1, upper temperature 40 or 55 degC, lower 25 +/- 3 degC.
  The cycle's timing is as summarised in OIML R 60-2 (2017) s. 2.10.5.12: a
  rise over 3 h, the upper temperature held until 12 h from the start of the
  cycle, a fall to the lower temperature (3 to 6 h; variant 1 at the rate that
  reaches it in 3 h, taken here), the lower temperature held until 24 h.
  Relative humidity: 93 +/- 3 % at the upper temperature and at least 95 %
  during the rise, the fall (variant 1) and at the lower temperature. The
  standard's own text is not public; these figures come from public
  summaries of it (OIML R 60-2; test laboratories' descriptions), and the
  humidity during the rise and fall, given only as a lower bound, is taken at
  that bound (95 %). Condensation on the part, which the test provokes during
  the rise, is not modelled: the surface is at most at saturation for 95 % RH.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

HOUR = 3600.0
DAY = 86400.0
ZERO_CELSIUS = 273.15


@dataclass(frozen=True)
class Segments:
    """A climate history as change times, end values and ramp flags.

    Parameters
    ----------
    change_times : numpy.ndarray
        (n + 1,): the segments' start and end times [s].
    temperature_end : numpy.ndarray
        (n,): each segment's temperature at its end [K].
    humidity_end : numpy.ndarray
        (n,): each segment's relative humidity at its end [%].
    ramp : numpy.ndarray of bool
        (n,): the segment ramps linearly from the previous values (else it holds its own).
    temperature_start : float
        The temperature before the first segment [K].
    humidity_start : float
        The relative humidity before the first segment [%].
    """

    change_times: np.ndarray
    temperature_end: np.ndarray
    humidity_end: np.ndarray
    ramp: np.ndarray
    temperature_start: float
    humidity_start: float


@dataclass(frozen=True)
class SteadyTest:
    """A steady damp-heat test: one climate held for a duration.

    Parameters
    ----------
    temperature : float
        The test temperature [K].
    relative_humidity : float
        The test relative humidity [%].
    default_duration : float
        The duration when the scene gives none [s].
    source : str
        The standard and its tolerances, for messages.
    """
    temperature: float      # K
    relative_humidity: float  # %
    default_duration: float  # s
    source: str

    def segments(self, duration: float | None) -> Segments:
        """The test's history: one held segment.

        Parameters
        ----------
        duration : float, optional
            How long [s]; None for the default duration.

        Returns
        -------
        Segments
            The history.
        """
        end = self.default_duration if duration is None else duration
        return Segments(np.array([0.0, end]), np.array([self.temperature]),
                        np.array([self.relative_humidity]), np.array([False]),
                        self.temperature, self.relative_humidity)


@dataclass(frozen=True)
class CyclicTest:
    """A cyclic damp-heat test: per cycle a rise, an upper hold, a fall and a lower hold.

    Parameters
    ----------
    upper_temperatures : tuple of float
        The standard's upper temperatures (severities) [K].
    lower_temperature : float
        The lower temperature [K].
    humid : float
        The relative humidity during the rise, the fall and at the lower temperature [%].
    upper_humidity : float
        The relative humidity at the upper temperature [%].
    rise : float
        The duration of the rise [s].
    hold_until : float
        When the upper hold ends, from the start of the cycle [s].
    fall : float
        The duration of the fall [s].
    cycle : float
        The cycle's length [s].
    default_cycles : int
        The number of cycles when the scene gives none [1].
    source : str
        The standard, for messages.
    """
    upper_temperatures: tuple[float, ...]  # K, the standard's severities
    lower_temperature: float  # K
    humid: float   # % RH during rise, fall and at the lower temperature
    upper_humidity: float  # % RH at the upper temperature
    rise: float    # s
    hold_until: float  # s from the start of the cycle
    fall: float    # s
    cycle: float   # s
    default_cycles: int
    source: str

    def segments(self, cycles: int | None, upper_temperature: float | None) -> Segments:
        """Per cycle: ramp up, hold at the upper temperature, ramp down, hold low.

        Parameters
        ----------
        cycles : int, optional
            The number of cycles [1]; None for the default.
        upper_temperature : float, optional
            The upper temperature [K]; None for the highest severity.

        Returns
        -------
        Segments
            The history, starting from the lower temperature and humid state.
        """
        upper = self.upper_temperatures[-1] if upper_temperature is None else upper_temperature
        count = self.default_cycles if cycles is None else cycles
        offsets = np.array([self.rise, self.hold_until, self.hold_until + self.fall, self.cycle])
        starts = np.arange(count)[:, None] * self.cycle
        change = np.concatenate([[0.0], (starts + offsets).ravel()])
        temperature = np.tile([upper, upper, self.lower_temperature, self.lower_temperature], count)
        humidity = np.tile([self.humid, self.upper_humidity, self.humid, self.humid], count)
        ramp = np.tile([True, False, True, False], count)
        return Segments(change, temperature, humidity, ramp, self.lower_temperature, self.humid)


STANDARD_TESTS = {
    "steady_damp_heat": SteadyTest(
        40 + ZERO_CELSIUS, 93.0, 21 * DAY,
        "IEC 60068-2-78 Test Cab: 40 +/- 2 degC, 93 +/- 3 % RH"),
    "damp_heat_85_85": SteadyTest(
        85 + ZERO_CELSIUS, 85.0, 1000 * HOUR,
        "JEDEC JESD22-A101 / IEC 61215-2 MQT 13: 85 +/- 2 degC, 85 +/- 5 % RH, 1000 h"),
    "cyclic_damp_heat": CyclicTest(
        (40 + ZERO_CELSIUS, 55 + ZERO_CELSIUS), 25 + ZERO_CELSIUS, 95.0, 93.0,
        3 * HOUR, 12 * HOUR, 3 * HOUR, 24 * HOUR, 6,
        "IEC 60068-2-30 Test Db variant 1 (12 h + 12 h), timing per OIML R 60-2 s. 2.10.5.12"),
}


def standard_climate(name: str, *, cycles: int | None = None, duration: float | None = None,
                 upper_temperature: float | None = None) -> Segments:
    """The history of a standard damp-heat test, by name.

    Nominal values sit at the centre of the standard's tolerance band (the module's
    docstring lists the tests and their sources).

    Parameters
    ----------
    name : {"steady_damp_heat", "damp_heat_85_85", "cyclic_damp_heat"}
        The test.
    cycles : int, optional
        Cyclic test: the number of 24 h cycles [1].
    duration : float, optional
        Steady tests: how long [s].
    upper_temperature : float, optional
        Cyclic test: the upper temperature [K], 40 or 55 degC.

    Returns
    -------
    Segments
        The history.

    Raises
    ------
    ValueError
        For a duration given to the cyclic test, cycles or an upper temperature given to a
        steady one, or an upper temperature the standard does not have.

    References
    ----------
    IEC 60068-2-78, Environmental testing - Part 2-78: Tests - Test Cab: Damp heat,
    steady state, International Electrotechnical Commission, 2012.

    JEDEC JESD22-A101, Steady-state temperature-humidity bias life test, JEDEC Solid
    State Technology Association.

    IEC 61215-2, Terrestrial photovoltaic (PV) modules - Design qualification and type
    approval - Part 2: Test procedures (MQT 13, damp heat), International
    Electrotechnical Commission, 2021.

    IEC 60068-2-30, Environmental testing - Part 2-30: Tests - Test Db: Damp heat,
    cyclic (12 h + 12 h cycle), International Electrotechnical Commission, 2005.

    OIML R 60-2, Metrological regulation for load cells - Part 2: Metrological controls
    and performance tests, International Organization of Legal Metrology, 2017,
    s. 2.10.5.12.
    """
    test = STANDARD_TESTS[name]
    if isinstance(test, CyclicTest):
        if duration is not None:
            raise ValueError(f"{name} is set by its number of cycles, not a duration")
        if upper_temperature is not None and not np.any(
                np.isclose(upper_temperature, test.upper_temperatures, atol=0.01)):
            allowed = " or ".join(f"{t - ZERO_CELSIUS:g} degC" for t in test.upper_temperatures)
            raise ValueError(f"upper_temperature of {name} is {allowed} ({test.source})")
        return test.segments(cycles, upper_temperature)
    if cycles is not None or upper_temperature is not None:
        raise ValueError(f"{name} is a steady test: give its duration, not cycles or an upper temperature")
    return test.segments(duration)
