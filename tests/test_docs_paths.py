"""Every source path the documentation names in backticks (``diffusion/x.py``,
``fickcam/cam/model.py``, ``benchmarks/y.py``) exists, so that a page cannot keep pointing
at a module after it moves. The development log is history and may name old places."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
PAGES = [p for p in [ROOT / "README.md", ROOT / "CONTRIBUTING.md",
                     *sorted((ROOT / "docs").rglob("*.md"))]
         if p.name not in ("changelog.md", "development-log.md") and "_build" not in p.parts
         and "_autosummary" not in p.parts]
PATH = re.compile(r"`((?:[A-Za-z0-9_.-]+/)+[A-Za-z0-9_.-]+\.py)`")


def places(path: str):
    """Where a path written in the docs may live: from the repository, the package or the
    diffusion engine (whose pages name its modules from there)."""
    return [ROOT / path, ROOT / "fickcam" / path, ROOT / "fickcam" / "diffusion" / path]


def test_the_pages_are_found():
    assert len(PAGES) > 10


def test_every_source_path_named_in_the_docs_exists():
    missing = [f"{page.relative_to(ROOT)}:{number}: {path}"
               for page in PAGES
               for number, line in enumerate(page.read_text().splitlines(), 1)
               for path in PATH.findall(line)
               if not any(place.exists() for place in places(path))]
    assert not missing, "paths that do not exist:\n" + "\n".join(missing)


CONFLICT = re.compile(r"^(<{7}|>{7})( |$)")


def test_no_page_source_or_test_keeps_a_merge_conflict_marker():
    """A merge resolved by hand can leave a ``<<<<<<<`` or ``>>>>>>>`` line behind (the
    changelog, where parallel work meets, most often); Markdown renders it as text."""
    files = [ROOT / "README.md", ROOT / "CONTRIBUTING.md", *sorted((ROOT / "docs").rglob("*.md")),
             *sorted((ROOT / "fickcam").rglob("*.py")), *sorted((ROOT / "tests").rglob("*.py"))]
    found = [f"{path.relative_to(ROOT)}:{number}"
             for path in files if "_build" not in path.parts
             for number, line in enumerate(path.read_text().splitlines(), 1)
             if CONFLICT.match(line)]
    assert found == []
