"""Measurement logs (the load a figure was measured at, what it was before, dates of runs,
asides about earlier states of the code) belong on the validation, benchmark and
changelog pages only. Every other documentation page says what the code does now."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[1] / "docs"
LOG_PAGES = {"changelog.md", "benchmarks.md", "validation.md", "validation-record.md",
             "development-log.md", "measurements.md"}
GENERATED = ("_build", "gallery", "reference")

# What a log says, and ordinary English does not: tuned on the pages' own text (the
# ageing times' "last time", a part that "was given", "before any computation" pass).
LOG_PHRASES = re.compile("|".join([
    r"\bload average",
    r"\bload (of |at |~)?\d",           # "load 6-10", "a load of 5-8", "the load at 9.5"
    r"\bat load\b",
    r"\bmeasured at load\b",
    r"\((was|before)\b",                # "(was 53.2)", "(before: 2.2e-03)"
    r"\bwas \d",                        # "was 53.2"
    r"\bbefore,",                       # "Before, the constant climate took 15 s"
    r"\bthe code before\b",
    r"\blast session\b",
    r"\blast time (it|we|this) (ran|was|took)\b",
    r"\bearlier (run|measurement|session|state)s?\b",
    r"\bre-?measured\b",
    r"\bnot re-?run\b",
    r"\bfirst idea tried\b",
    r"\bused to (be|take|cost|give)\b",
    r"\buntil now\b",
    r"\b20\d\d-\d\d-\d\d(?!\d)",         # the date of a run
]), flags=re.IGNORECASE)


def log_lines(text: str) -> list[tuple[int, str]]:
    """(line number, phrase) of every measurement-log phrase in ``text``."""
    return [(number, match.group(0)) for number, line in enumerate(text.splitlines(), 1)
            for match in LOG_PHRASES.finditer(line)]


def pages() -> list[Path]:
    """The documentation's hand-written pages (generated ones are left out)."""
    return sorted(path for path in DOCS.rglob("*.md")
                  if not set(path.relative_to(DOCS).parts) & set(GENERATED))


@pytest.mark.parametrize("text", [
    "CPU s 162.8 (was 53.2), measured at load 6-10 on the shared machine",
    "| 8.2e-03 (before: 2.2e-03) |",
    "Before, the constant climate took 15 s at 1e-3 (58 000 cells)",
    "the 1e-2 rows re-measured at load 6-7 after the nested pair",
    "while other sessions kept the load at 9.5-10",
    "scaled 1.23 x from 1 to 2 workers at load 5.7",
    "last session the four-bar's year took 6.8 s",
    "the last time it ran, the sweep took 74.6 s",
    "Until now `time` was a `timedelta64` coordinate",
    "The first idea tried, Fick at Crank's weighted-mean D",
    "side by side on the code before (the 1.0 plan's pair)",
    "measured on 2026-11-23T17:48 under load",
])
def test_log_phrases_are_caught(text):
    assert log_lines(text)


@pytest.mark.parametrize("text", [
    "| `outputs.ageing_times` (`every`, or the last time) | how many of it fit |",
    "A cam is written back in the form it was given in:",
    "without it the command stops at once, before any computation",
    "the run keeps the earlier times and the limit line says",
    "a note says whether Mm was extrapolated (fitted M/Mm at the last weighing)",
    "the spec fails 8 days earlier. The whole run",
    "The load on the follower is the spring force plus the inertia.",
    "the 95 % intervals covered the true D in 94.8 % of draws",
])
def test_ordinary_english_passes(text):
    assert not log_lines(text)


def test_only_the_log_pages_hold_measurement_logs():
    found = [f"{path.relative_to(DOCS)}:{number}: {phrase!r}" for path in pages()
             if path.name not in LOG_PAGES or path.parent != DOCS
             for number, phrase in log_lines(path.read_text())]
    assert not found, ("measurement logs belong in docs/validation-record.md, docs/benchmarks.md "
                       "or docs/development-log.md:\n" + "\n".join(found))
