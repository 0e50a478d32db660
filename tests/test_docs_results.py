"""Tables of measurements in the documentation come from result files: every
``{result-table}`` names a result file in ``benchmarks/results/`` and a table it holds,
each result file carries its stamp (command, commit, date, machine, load average), and
the validation and benchmark pages hold no table typed by hand. The renderer is tested
directly, without Sphinx."""
from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
RESULTS = ROOT / "benchmarks" / "results"
MEASURED_PAGES = ("validation.md", "validation-record.md", "benchmarks.md")
DIRECTIVE = re.compile(r"^```\{result-table\} (\S+)\n(?::table: (\S+)\n)?```", re.MULTILINE)


def _load_renderer():
    spec = importlib.util.spec_from_file_location(
        "fickcam_results", DOCS / "_ext" / "fickcam_results.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


results = _load_renderer()


def directives() -> list[tuple[str, str, str | None]]:
    """(page, result file, table) of every result table in the hand-written pages."""
    found = []
    for page in sorted(DOCS.rglob("*.md")):
        if "_build" in page.parts:
            continue
        for path, table in DIRECTIVE.findall(page.read_text()):
            found.append((page.name, path, table or None))
    return found


def test_the_measured_pages_render_their_tables_from_result_files():
    pages = {page for page, _, _ in directives()}
    assert set(MEASURED_PAGES) <= pages


@pytest.mark.parametrize("page, path, table", directives())
def test_every_result_table_names_a_stamped_table_of_a_result_file(page, path, table):
    assert path.startswith("benchmarks/results/"), f"{page}: {path} is not a result file"
    markdown = results.result_markdown(ROOT / path, table)
    stamp = markdown.strip().splitlines()[-1]
    assert stamp.startswith("*Reproduce with `") and "measured" in stamp
    assert "commit" not in stamp and "load average" not in stamp  # those are for developers
    header = markdown.splitlines()[0]
    assert header.startswith("| ") and markdown.count("\n|") >= 2  # header, rule, a row


@pytest.mark.parametrize("path", sorted(RESULTS.glob("*.json")), ids=lambda p: p.name)
def test_every_result_file_carries_its_stamp(path):
    record = results.load_result(path)
    for key in results.STAMP_KEYS:
        assert record.get(key) not in (None, ""), f"{path.name} has no {key}"
    assert re.fullmatch(r"[0-9a-f]{7,40}(\+changes)?", record["commit"])
    assert re.match(r"\d{4}-\d{2}-\d{2}", record["date"])


def test_every_result_file_is_shown_somewhere():
    shown = {Path(path).name for _, path, _ in directives()}
    assert {path.name for path in RESULTS.glob("*.json")} <= shown


# The validation page opens with a summary of what each model is checked against (the
# agreement is each test's own tolerance, held by that test); its tables of measurements
# are rendered like every other.
@pytest.mark.parametrize("page", [page for page in MEASURED_PAGES if page != "validation.md"])
def test_no_hand_written_table_on_the_measured_pages(page):
    text = (DOCS / page).read_text()
    typed = [line for line in text.splitlines() if line.startswith("|")]
    assert not typed, f"docs/{page}: a table typed by hand: {typed[0]}"
    blocks = re.findall(r"^```\n(.*?)^```", text, flags=re.MULTILINE | re.DOTALL)
    assert not [b for b in blocks if re.search(r"^-{20,}$", b, flags=re.MULTILINE)], (
        f"docs/{page}: a fixed-width table in a code block")


def test_every_hand_written_validation_table_says_how_to_reproduce_it():
    """The validation page's own tables (the summary, the crossings) carry a "reproduce
    with" column or a "Reproduce with" line under them, as the rendered ones do."""
    lines = (DOCS / "validation.md").read_text().splitlines()
    tables, start = [], None
    for k, line in enumerate(lines + [""]):
        if line.startswith("|") and start is None:
            start = k
        elif not line.startswith("|") and start is not None:
            tables.append((start, k))
            start = None
    assert len(tables) >= 2
    for first, end in tables:
        after = " ".join(lines[end:end + 3])
        assert "reproduce with" in lines[first].lower() or "*Reproduce with `" in after, \
            f"docs/validation.md:{first + 1}: a table without its reproduce-with line"


def _write(folder: Path, record: dict) -> Path:
    path = folder / "result.json"
    path.write_text(json.dumps(record))
    return path


STAMP = {"command": "python benchmarks/x.py", "commit": "abc1234", "date": "2026-01-02T03:04:05",
         "machine": {"cpu": "CPU", "cores": 2, "python": "3.11"},
         "load_average": {"start": 2.0, "end": 3.0}}


def test_a_table_renders_with_its_command_and_stamp(tmp_path):
    path = _write(tmp_path, {**STAMP, "tables": {"t": {"columns": ["a", "b|c"],
                                                       "rows": [[1, "x"], [2, "y"]]}}})
    markdown = results.result_markdown(path)
    assert markdown.splitlines()[:4] == ["| a | b\\|c |", "|---|---|", "| 1 | x |", "| 2 | y |"]
    assert ("*Reproduce with `python benchmarks/x.py` (measured 2026-01-02 on CPU, 2 cores, "
            "Python 3.11).*") in markdown
    record = results.measurement_record_markdown(tmp_path)
    assert ("Reproduce: `python benchmarks/x.py`. Measured on commit `abc1234` (2026-01-02), "
            "CPU, 2 cores, Python 3.11, load average 2.0-3.0.") in record


def test_a_value_not_measured_shows_as_a_dash(tmp_path):
    path = _write(tmp_path, {**STAMP, "tables": {"t": {"columns": ["a"], "rows": [["nan"]]}}})
    assert "| – |" in results.result_markdown(path)


def test_a_transcribed_table_says_so_with_its_own_stamp(tmp_path):
    own = {"command": "python benchmarks/y.py", "commit": "def5678", "load_average": "6-10"}
    path = _write(tmp_path, {**STAMP, "transcribed": True,
                             "tables": {"t": {"columns": ["a"], "rows": [[1]], **own},
                                        "u": {"columns": ["a"], "rows": [[2]]}}})
    stamp = results.result_markdown(path, "t").strip().splitlines()[-1]
    assert "transcribed from an earlier measurement" in stamp
    assert "`python benchmarks/y.py`" in stamp
    record = results.measurement_record_markdown(tmp_path)
    assert "Transcribed from commit `def5678`" in record and "load average 6-10" in record
    assert "not re-run" in record


def test_bad_result_files_are_refused_with_the_reason(tmp_path):
    ragged = _write(tmp_path, {**STAMP, "tables": {"t": {"columns": ["a", "b"], "rows": [[1]]}}})
    with pytest.raises(ValueError, match="a row of 1 cells under 2 columns"):
        results.result_markdown(ragged)
    two = _write(tmp_path, {**STAMP, "tables": {"t": {"columns": ["a"], "rows": []},
                                                "u": {"columns": ["a"], "rows": []}}})
    with pytest.raises(KeyError, match="name one"):
        results.result_markdown(two)
    with pytest.raises(KeyError, match="no table 'v'"):
        results.result_markdown(two, "v")
    unstamped = _write(tmp_path, {"command": "x", "tables": {"t": {"columns": ["a"], "rows": []}}})
    with pytest.raises(KeyError, match="without commit, date, machine, load_average"):
        results.result_markdown(unstamped)
