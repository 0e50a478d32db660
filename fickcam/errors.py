"""Exceptions that fickcam raises on purpose.

Every error a user can cause is a :class:`FickcamError`; the command line turns
these into one line each on stderr (exit 2 for bad input, 1 otherwise) and never
shows a traceback for them.
"""
from __future__ import annotations

from dataclasses import dataclass


class FickcamError(Exception):
    """Base class of the errors fickcam raises deliberately."""


@dataclass(frozen=True)
class Problem:
    """One thing wrong with an input file: where it is and why it is wrong."""

    file: str
    line: int | None
    key: str
    reason: str

    def __str__(self) -> str:
        where = self.file if self.line is None else f"{self.file}:{self.line}"
        key = f" {self.key}" if self.key else ""
        return f"{where}{key}: {self.reason}"


class SceneError(FickcamError):
    """A scene (or sweep) file is invalid; carries one :class:`Problem` per fault."""

    def __init__(self, problems: list[Problem]):
        self.problems = list(problems)
        super().__init__("\n".join(str(p) for p in self.problems))


class InputError(FickcamError):
    """Bad input that is not a scene file (a result path, a query argument...)."""


class PhysicsDomainError(FickcamError):
    """The physics stopped being valid for a part at some ageing time.

    ``part`` names the part, ``time`` is the ageing time in seconds at which the
    model left its domain (e.g. service temperature reached the wet Tg, or the
    linkage cannot assemble).
    """

    def __init__(self, part: str, time: float, message: str):
        self.part = part
        self.time = float(time)
        self.message = message
        super().__init__(f"{part} at t = {format_duration(self.time)}: {message}")


class SolverError(FickcamError):
    """A linear solve failed to converge: names the part, step and time."""

    def __init__(self, part: str, step: int, time: float, message: str):
        self.part, self.step, self.time = part, int(step), float(time)
        super().__init__(
            f"{part}: solver failed at step {step} (t = {format_duration(time)}): {message}"
        )


def format_duration(seconds: float) -> str:
    """A duration in seconds as the largest sensible unit (s, h, d or years)."""
    s = float(seconds)
    if abs(s) < 3600:
        return f"{s:.4g} s"
    if abs(s) < 86400 * 2:
        return f"{s / 3600:.4g} h"
    if abs(s) < 86400 * 730:
        return f"{s / 86400:.4g} d"
    return f"{s / (86400 * 365.25):.4g} yr"
