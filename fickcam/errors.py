"""Exceptions that fickcam raises on purpose.

Every error a user can cause is a :class:`FickcamError`; the command line turns
these into one line each on stderr (exit 2 for bad input, 1 otherwise) and never
shows a traceback for them.
"""
from __future__ import annotations

import contextlib
import contextvars
import math
from dataclasses import dataclass


class FickcamError(Exception):
    """Base class of the errors fickcam raises deliberately.

    The command line shows one line for each (exit 2 for bad input, 1 otherwise), never a
    traceback.

    Parameters
    ----------
    *args, **kwargs
        The message (the arguments of :class:`Exception`).
    """


class UserInputError(FickcamError):
    """A mistake in what the user gave (a scene, a path, an argument), told by its message
    alone: IPython and Jupyter show these without a traceback (``_render_traceback_``), as
    the command line does; the frames inside fickcam would only hide the file, line and
    key. Every other error keeps its full traceback.

    Parameters
    ----------
    *args, **kwargs
        The message (the arguments of :class:`Exception`).
    """

    def _render_traceback_(self) -> list[str]:
        """What IPython shows for this error: ``SceneError: FILE:LINE key: reason``, one
        line per problem, no frames."""
        first, *rest = str(self).splitlines() or [""]
        return [f"\x1b[0;31m{type(self).__name__}\x1b[0m: {first}", *rest]


class FickcamWarning(UserWarning):
    """A result that is computed but needs attention (a follower that jumps, a part past its
    wet glass transition, a limit search less accurate than asked).

    Python users get these through the ``warnings`` module and filter them the usual way, e.g.
    ``warnings.simplefilter("ignore", fickcam.FickcamWarning)``; the command line shows
    them as ``fickcam: warning: ...`` lines.

    Parameters
    ----------
    *args
        The message (the arguments of :class:`Warning`).
    """


@dataclass(frozen=True)
class Problem:
    """One thing wrong with an input file: where it is and why it is wrong.

    Shown as ``FILE:LINE key: reason``.

    Parameters
    ----------
    file : str
        The file's name.
    line : int or None
        The line, from 1; None when not known.
    key : str
        The dotted key path ("" for the whole file).
    reason : str
        Why it is wrong, in one line.
    """

    file: str
    line: int | None
    key: str
    reason: str

    def __str__(self) -> str:
        where = self.file if self.line is None else f"{self.file}:{self.line}"
        key = f" {self.key}" if self.key else ""
        return f"{where}{key}: {self.reason}"


class SceneError(UserInputError):
    """A scene (or sweep) file is invalid; carries one :class:`Problem` per fault.

    Parameters
    ----------
    problems : list of Problem
        The faults; the message has one line per fault.
    """

    def __init__(self, problems: list[Problem]):
        self.problems = list(problems)
        super().__init__("\n".join(str(p) for p in self.problems))


class InputError(UserInputError):
    """Bad input that is not a scene file (a result path, a query argument...).

    Parameters
    ----------
    *args, **kwargs
        The message (the arguments of :class:`Exception`).
    """


class PhysicsDomainError(FickcamError):
    """The physics stopped being valid for a part at some ageing time.

    E.g. the service temperature reached the wet Tg, or the linkage cannot assemble.

    Parameters
    ----------
    part : str
        The part.
    time : float
        The ageing time at which the model left its domain [s].
    message : str
        Why.
    span : float, optional
        The run's last ageing time [s], to choose the unit ``time`` is shown in.
    """

    def __init__(self, part: str, time: float, message: str, span: float | None = None):
        self.part = part
        self.time = float(time)
        self.message = message
        super().__init__(f"{part} at t = {format_duration(self.time, span)}: {message}")


class SolverError(FickcamError):
    """A linear solve failed to converge: names the part, step and time.

    Parameters
    ----------
    part : str
        The part.
    step : int
        The time step [1].
    time : float
        The ageing time of the step [s].
    message : str
        The solver's reason.
    """

    def __init__(self, part: str, step: int, time: float, message: str):
        self.part, self.step, self.time = part, int(step), float(time)
        super().__init__(
            f"{part}: solver failed at step {step} (t = {format_duration(time)}): {message}"
        )


#: units of time, each (name, seconds) with the longest span it is chosen for [s]:
#: a 40-min history in min, a 3 h one in h, a 60-day or 2-year one in d, a 5-year one in yr
TIME_UNITS = (("s", 1.0, 120.0), ("min", 60.0, 2 * 3600.0), ("h", 3600.0, 2 * 86400.0),
              ("d", 86400.0, 3 * 365.25 * 86400.0), ("yr", 365.25 * 86400.0, float("inf")))


#: the unit the scene's author wrote its times in, while a run or its report is told
#: (:func:`times_in`); None: chosen from the span
_WRITTEN = contextvars.ContextVar("fickcam_time_unit", default=None)

@contextlib.contextmanager
def times_in(unit: str | None):
    """While inside, every time is told in ``unit`` (the one the scene's author wrote its
    times in), whatever the run's span; None changes nothing.

    Parameters
    ----------
    unit : str or None
        ``s``, ``min``, ``h``, ``d`` or ``yr``.
    """
    token = _WRITTEN.set(unit if unit in {name for name, _, _ in TIME_UNITS} else None)
    try:
        yield
    finally:
        _WRITTEN.reset(token)


def time_unit(span: float) -> tuple[str, float]:
    """The unit that suits durations up to ``span``: one unit for every time of a run,
    chosen from its last ageing time, or the one its scene's author wrote (:func:`times_in`).

    Parameters
    ----------
    span : float
        The longest duration to be shown [s] (NaN: days).

    Returns
    -------
    tuple of (str, float)
        The unit's name (``s``, ``min``, ``h``, ``d`` or ``yr``) and its length [s].
    """
    written = _WRITTEN.get()
    if written is not None:
        return next((name, seconds) for name, seconds, _ in TIME_UNITS if name == written)
    span = abs(float(span))
    return next(((name, seconds) for name, seconds, longest in TIME_UNITS if span < longest),
                ("d", 86400.0))  # no span (NaN: no case of a sweep ran): days, as results store


def unit_of_length(seconds: float) -> tuple[str, float]:
    """The unit of :data:`TIME_UNITS` a duration written in a unit of ``seconds`` is shown
    in: the longest not longer than it (a month or a week in days, a year in years).

    Parameters
    ----------
    seconds : float
        The length of the unit written [s].

    Returns
    -------
    tuple of (str, float)
        The unit's name and its length [s].
    """
    fits = [(name, length) for name, length, _ in TIME_UNITS if length <= seconds * (1 + 1e-9)]
    return fits[-1] if fits else TIME_UNITS[0][:2]


def supported_digits(value: float, error: float) -> str:
    """``value`` with only the digits ``error`` supports: rounded to the smallest power of
    ten not below the error (19.9943 +- 0.017 as ``20.0``, 0.1356 +- 0.002 as ``0.14``), so
    it is within one unit of its last digit and a half of the truth; four significant
    digits where the error is 0 or unknown.

    Parameters
    ----------
    value : float
        The value [any unit].
    error : float
        Its error estimate [the same unit].

    Returns
    -------
    str
        The value's text.
    """
    if not (math.isfinite(error) and error > 0.0) or not math.isfinite(value):
        return f"{value:.4g}"
    exponent = math.ceil(math.log10(error))
    return f"{round(value, -exponent):.{max(0, -exponent)}f}"


def format_time(seconds: float, unit: tuple[str, float], error: float | None = None) -> str:
    """A time in ``unit``; with ``error``, only the digits it supports
    (:func:`supported_digits`), else up to six significant digits (a stored ageing time).

    Parameters
    ----------
    seconds : float
        The time [s].
    unit : tuple of (str, float)
        The unit's name and its length [s] (:func:`time_unit`, :func:`unit_of_length`).
    error : float, optional
        The time's error estimate [s].

    Returns
    -------
    str
        ``"20.0 d"``, ``"3.3 h"``, ``"730.5 d"``.
    """
    name, length = unit
    if error is None:
        return f"{float(seconds) / length:g} {name}"
    return f"{supported_digits(float(seconds) / length, float(error) / length)} {name}"


def format_duration(seconds: float, span: float | None = None) -> str:
    """A duration as text in the unit that suits ``span`` (:func:`time_unit`).

    Parameters
    ----------
    seconds : float
        The duration [s].
    span : float, optional
        A run's last ageing time [s], so that all its times share one unit (``0 d``,
        ``182.6 d``, ``730.5 d``); by default the duration itself.
    """
    name, unit = time_unit(seconds if span is None else span)
    return f"{float(seconds) / unit:.4g} {name}"


class WriteError(FickcamError):
    """A file could not be written (the disk is full, a size limit): nothing was replaced.

    Parameters
    ----------
    *args, **kwargs
        The message (the arguments of :class:`Exception`), naming the file.
    """
