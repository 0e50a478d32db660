"""The product is self-contained: no shipped file, page, docstring or material source
points the reader somewhere a user cannot follow.

Refused in the package (code, docstrings, material library, example scenes), the docs,
README.md, CONTRIBUTING.md, pyproject.toml and the tests' docstrings and comments:

- the internal contract's file name (the product's documented behaviour is stated in
  place instead);
- a path into the folder of source papers, a paper named by its file number there,
  or any path into a folder outside the repository (papers are cited by
  author, title, journal and year);
- an issue number of this project's tracker, which means nothing outside it (an
  upstream project's issue, named with the project, says where it lives).

Each area is a separate case, so a failure names where to look.
"""
from __future__ import annotations

import ast
import io
import re
import subprocess
import tokenize
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

# Built from pieces so that this file does not match itself.
CONTRACT = "SPEC" + r"\.md"
SOURCE_PAPER_PATH = "seeds" + r"/(?:0\d\d_|README)"
OUTSIDE_FOLDER = r"\.\./" + "shared"
PAPER_BY_FILE_NUMBER = r"\bseeds?\s+" + r"00\d\b"
ISSUE_NUMBER = re.compile(r"(?:(\S+)\s+)?\bissues?\s+#?\d+", re.IGNORECASE)
PATHS = re.compile("|".join((CONTRACT, SOURCE_PAPER_PATH, OUTSIDE_FOLDER, PAPER_BY_FILE_NUMBER)),
                   re.IGNORECASE)
#: projects whose issue trackers a reference may name, as "<project> issue <number>"
UPSTREAM = {"matplotlib", "numpy", "scipy", "xarray", "pint", "pydantic", "fipy", "dask",
            "scikit-fem", "skfem", "pvlib", "ezdxf", "petsc", "petsc4py", "netcdf4", "h5py",
            "h5netcdf", "hypothesis", "pytest", "openblas", "sphinx", "myst-parser", "tqdm"}

BINARY_SUFFIXES = {".png", ".jpg", ".jpeg", ".gif", ".svg", ".pdf", ".h5", ".nc", ".npz",
                   ".npy", ".ico", ".zip", ".gz"}

#: (case id, which tracked files, what of each file is read)
AREAS = (
    ("fickcam/diffusion", lambda p: p.startswith("fickcam/diffusion/"), "text"),
    ("fickcam", lambda p: p.startswith("fickcam/") and not p.startswith("fickcam/diffusion/"),
     "text"),
    ("configs", lambda p: p.startswith("configs/"), "text"),
    ("docs", lambda p: p.startswith("docs/"), "text"),
    ("top-level files", lambda p: p in ("README.md", "CONTRIBUTING.md", "pyproject.toml"),
     "text"),
    ("tests' docstrings and comments", lambda p: p.startswith("tests/") and p.endswith(".py"),
     "prose"),
)


def tracked_files() -> list[str]:
    """The repository's tracked files (relative paths); skips when there is no git checkout."""
    try:
        out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True,
                             check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("not a git checkout: the tracked files are unknown")
    return [p for p in out.decode().split("\0") if p]


def refused(line: str) -> bool:
    """Whether ``line`` names the contract, a path outside the repository or an issue of
    this project's tracker (an issue number not preceded by an upstream project's name)."""
    if PATHS.search(line):
        return True
    return any((m.group(1) or "").strip("`'\"([").lower() not in UPSTREAM
               for m in ISSUE_NUMBER.finditer(line))


def prose_lines(text: str) -> list[tuple[int, str]]:
    """(line number, line) of a Python file's docstrings and comments only: the code and
    its string literals may hold what they test."""
    lines = text.splitlines()
    found: dict[int, str] = {}
    for node in ast.walk(ast.parse(text)):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
            first, last = body[0].lineno, body[0].end_lineno
            found.update({n: lines[n - 1] for n in range(first, last + 1)})
    for token in tokenize.generate_tokens(io.StringIO(text).readline):
        if token.type == tokenize.COMMENT:
            found[token.start[0]] = token.string
    return sorted(found.items())


def offending_lines(relative: str, what: str) -> list[str]:
    """``path:line: text`` for every line of ``relative`` that matches the refused patterns."""
    path = ROOT / relative
    if path.suffix.lower() in BINARY_SUFFIXES or path.is_symlink() or not path.is_file():
        return []
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return []
    numbered = prose_lines(text) if what == "prose" else enumerate(text.splitlines(), 1)
    return [f"{relative}:{n}: {line.strip()}" for n, line in numbered if refused(line)]


def test_the_patterns_catch_what_they_are_meant_to_and_spare_plain_text():
    refused_texts = ["see " + "SPEC" + ".md §1", "seeds" + "/000_c9d2754e3bf549ac.txt Table 9",
                     "../" + "shared/seeds/README.md", "as in " + "issue 16",
                     "Issue " + "#12 item 4", "issues " + "11 and 12", "(issue " + "13)",
                     "as " + "seed 001's Table 6"]
    allowed = ["Singh & Sanyal (2017) Table 9", "random seed 13", "the spec a mechanism must "
               "hold", "tissue 3", "an issue with the mesh",
               "(matplotlib issue " + "26525, open)"]
    assert all(refused(text) for text in refused_texts)
    assert not any(refused(text) for text in allowed)


@pytest.mark.parametrize("area, selects, what", AREAS, ids=[a[0] for a in AREAS])
def test_no_product_file_points_outside_the_repository(area, selects, what):
    this_file = Path(__file__).resolve().relative_to(ROOT).as_posix()
    files = [p for p in tracked_files() if selects(p) and p != this_file]
    found = [line for p in files for line in offending_lines(p, what)]
    assert not found, (f"{len(found)} line(s) in {area} name the internal contract, a source "
                       "paper's file, a folder outside the repository or an issue number; "
                       "cite the paper or state the behaviour instead:\n" + "\n".join(found))
