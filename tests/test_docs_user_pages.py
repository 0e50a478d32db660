"""The pages written for users speak to users: no source path, test file, commit hash or
load average on them. Those belong to the developer section (architecture, contributing,
the measurement record), which is listed here by name.

A command that runs a benchmark script (``python benchmarks/NAME.py``) is what a reader
types to reproduce a number, so it may stand on a user page.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
DEVELOPER_PAGES = {"architecture.md", "contributing.md", "development.md", "measurements.md",
                   "validation-record.md", "development-log.md"}
GENERATED = {"gallery", "reference", "_build", "_autosummary", "auto_examples"}


def user_pages() -> list[Path]:
    """README and the hand-written pages of the user sections."""
    pages = [ROOT / "README.md"]
    for path in sorted(DOCS.rglob("*.md")):
        parts = set(path.relative_to(DOCS).parts)
        if path.name in DEVELOPER_PAGES or parts & GENERATED:
            continue
        pages.append(path)
    return pages


INTERNALS = {
    "a source path": re.compile(r"(?<!python )(?<![\w/])(?:fickcam|benchmarks|docs|diffusion)/[\w/]+\.py\b"),
    "a test file": re.compile(r"\btests/|\btest_\w+\.py\b"),
    "a commit hash": re.compile(r"(?<![\w.:/-])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}(?![\w.-])"),
    "a load average": re.compile(r"load average|\(load \d", re.IGNORECASE),
}


@pytest.mark.parametrize("page", user_pages(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_a_user_page_names_no_internals(page):
    found = []
    for number, line in enumerate(page.read_text().split("\n"), start=1):
        for what, pattern in INTERNALS.items():
            for match in pattern.finditer(line):
                found.append(f"{page.relative_to(ROOT)}:{number}: {what}: {match.group(0)!r}")
    assert not found, "move these to the developer section:\n" + "\n".join(found)


def test_the_patterns_catch_what_they_should():
    text = "see fickcam/cam/train.py, tests/test_limits.py and commit 009262f (load 0.8)"
    assert all(pattern.search(text) for pattern in INTERNALS.values())
    assert not any(pattern.search("python benchmarks/compensation_runs.py 0.000263166 1e-5 2deadbeef0")
                   for name, pattern in INTERNALS.items() if name != "a commit hash")
