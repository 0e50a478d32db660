"""The examples in the README and the documentation stay true.

Every ```python block and every ``fickcam ...`` command of a ```bash or ```console block
in the README and the hand-written documentation pages runs, page by page, top to bottom,
in a fresh folder that holds the example scenes (``fickcam examples --copy configs``). A
```yaml block captioned with a file name (``{code-block} yaml`` with ``:caption:
my_cam.yaml``) is written to that file first, so a page's own scene runs as shown. A block
that cannot run here (a cluster address, a batch system) says so on the line above it,
``% not run: reason`` (a MyST comment, not shown on the site); those blocks are listed in
``NOT_RUN`` below, so that a new one is a deliberate change. A failure names the page and
the line of the block.

Pages repeat one another's commands (the demo run, its plots). Each distinct command runs
once per session: a command given again with the same arguments, the same example scenes
and the same bytes in every file it names reuses the files its first run wrote.

From the documentation index a new user reaches the page section of each task of
``TASKS`` within two clicks (a toctree entry or a link is one click).
"""
from __future__ import annotations

import hashlib
import re
import shlex
import traceback
from dataclasses import dataclass
from pathlib import Path

import pytest
import yaml

import fickcam
from fickcam.cli.main import main
from fickcam.cli.parser import build_parser

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
# the hand-written pages (the gallery and the reference pages are generated at build time)
PAGES = [ROOT / "README.md", ROOT / "CONTRIBUTING.md", *sorted(DOCS.glob("*.md")),
         *sorted((DOCS / "getting-started").glob("*.md")), *sorted((DOCS / "guide").glob("*.md"))]

# (page, reason) of every block marked "% not run: reason"
NOT_RUN = {
    ("docs/architecture.md", "an interface's signature, not a call"),
    ("docs/guide/sweeps-montecarlo.md", "needs a dask scheduler at tcp://HOST:8786"),
    ("docs/guide/sweeps-montecarlo.md", "starts a dask scheduler and workers on several machines"),
    ("docs/guide/sweeps-montecarlo.md", "needs a batch system (SLURM) and dask-jobqueue"),
    ("docs/guide/results-python.md", "changes the logging set-up of the whole session"),
}

# an opening fence: ```lang, or ```{directive} argument (``{code-block} yaml``: lang yaml)
OPENING = re.compile(r"^(?P<indent>\s*)(?P<fence>`{3,})\s*(?:\{(?P<directive>[\w-]+)\})?\s*(?P<lang>[^`\s]*).*$")
OPTION = re.compile(r"^:(?P<key>[\w-]+):\s*(?P<value>.*)$")
NOT_RUN_MARK = re.compile(r"^%\s*not run:\s*(?P<reason>.+)$")
SHELLS = ("bash", "console", "sh", "shell")


@dataclass(frozen=True)
class Block:
    """A fenced code block of a page: its language, caption, text and where it is."""

    page: str            # path from the repository root
    line: int            # line of the opening fence (1-based)
    first_line: int      # line of the block's first line of code
    lang: str
    caption: str
    text: str
    not_run: str         # the reason of a "% not run:" mark, or ""

    @property
    def where(self) -> str:
        return f"{self.page}:{self.line}"


def _options(lines: list[str], start: int, indent: int) -> tuple[dict[str, str], int]:
    """A ``{code-block}``'s ``:key: value`` options from line ``start``; the first code line."""
    options = {}
    k = start
    while k < len(lines) and (match := OPTION.match(lines[k][indent:])):
        options[match["key"]] = match["value"].strip()
        k += 1
    if options and k < len(lines) and not lines[k].strip():
        k += 1
    return options, k


def _mark(lines: list[str], fence: int) -> str:
    """The reason of the "% not run:" comment on the line above a fence (blank lines between
    them allowed), or ""."""
    k = fence - 1
    while k >= 0 and not lines[k].strip():
        k -= 1
    match = NOT_RUN_MARK.match(lines[k].strip()) if k >= 0 else None
    return match["reason"].strip() if match else ""


def blocks(page: Path) -> list[Block]:
    """Every fenced code block of a page of the repository, in order."""
    return blocks_of(page, ROOT)


def blocks_of(page: Path, root: Path) -> list[Block]:
    """Every fenced code block of ``page``, named from ``root``, in order (indented ones in
    list items too)."""
    name = page.relative_to(root).as_posix()
    lines = page.read_text().split("\n")
    found = []
    k = 0
    while k < len(lines):
        opening = OPENING.match(lines[k])
        if not opening:
            k += 1
            continue
        indent, fence = len(opening["indent"]), opening["fence"]
        directive = opening["directive"]
        lang = opening["lang"] if directive in (None, "code-block") else f"{{{directive}}}"
        options, first = (_options(lines, k + 1, indent) if directive else ({}, k + 1))
        end = first
        while end < len(lines) and lines[end].strip() != fence:
            end += 1
        text = "\n".join(line[indent:] for line in lines[first:end])
        found.append(Block(name, k + 1, first + 1, lang, options.get("caption", ""),
                           text, _mark(lines, k)))
        k = end + 1
    return found


def commands(block: Block) -> list[tuple[int, str]]:
    """The ``fickcam ...`` commands of a shell block with the line each starts on: a
    ``$ `` prompt in a console block, continued lines joined, ``&&`` chains split, and
    trailing comments dropped."""
    found = []
    lines = block.text.split("\n")
    k = 0
    while k < len(lines):
        start = k
        line = lines[k]
        while line.rstrip().endswith("\\") and k + 1 < len(lines):
            k += 1
            line = line.rstrip()[:-1] + " " + lines[k].strip()
        k += 1
        if block.lang == "console":
            if not line.startswith("$ "):
                continue
            line = line[2:]
        line = re.split(r"\s#\s|\s#$", line)[0].strip()
        for part in line.split("&&"):
            part = part.strip()
            if part.startswith("fickcam "):
                found.append((block.first_line + start, part))
    return found


ALL_BLOCKS = [block for page in PAGES for block in blocks(page)]
RUN_PAGES = sorted({block.page for block in ALL_BLOCKS if not block.not_run and (
    block.lang == "python" or (block.lang in SHELLS and commands(block)))})


def test_blocks_not_run_are_the_listed_ones():
    marked = {(block.page, block.not_run) for block in ALL_BLOCKS if block.not_run}
    assert marked == NOT_RUN


def test_the_pages_hold_commands_and_python():
    assert sum(len(commands(b)) for b in ALL_BLOCKS if b.lang in SHELLS) > 60
    assert sum(b.lang == "python" for b in ALL_BLOCKS) > 10


@pytest.mark.parametrize("block", [b for b in ALL_BLOCKS if b.lang in SHELLS and commands(b)],
                         ids=lambda b: b.where)
def test_every_documented_command_parses(block):
    """Every command line parses, the ones in blocks that are not run too."""
    for line, command in commands(block):
        try:
            build_parser().parse_args(shlex.split(command)[1:])
        except SystemExit:
            pytest.fail(f"{block.page}:{line}: `{command}` does not parse")


def _files(folder: Path) -> dict[str, tuple[int, int]]:
    """Every file under ``folder`` by its path, with its size and modification time."""
    return {path.relative_to(folder).as_posix(): (path.stat().st_size, path.stat().st_mtime_ns)
            for path in folder.rglob("*") if path.is_file()}


def _digest(folder: Path, names: list[Path]) -> str:
    """One hash of the names and contents of files in ``folder``."""
    digest = hashlib.sha256()
    for name in names:
        digest.update(name.as_posix().encode() + b"\0" + (folder / name).read_bytes())
    return digest.hexdigest()


class CommandCache:
    """The files each distinct command wrote, so that a repeat only writes them again."""

    def __init__(self):
        self.written: dict[tuple, dict[str, bytes]] = {}

    @staticmethod
    def key(argv: list[str], folder: Path) -> tuple:
        scenes = sorted(p.relative_to(folder) for p in (folder / "configs").rglob("*") if p.is_file())
        named = [Path(arg) for arg in argv if (folder / arg).is_file()]
        return tuple(argv), _digest(folder, scenes), _digest(folder, named)

    def run(self, argv: list[str], folder: Path) -> int:
        key = self.key(argv, folder)
        if key in self.written:
            for name, content in self.written[key].items():
                (folder / name).parent.mkdir(parents=True, exist_ok=True)
                (folder / name).write_bytes(content)
            return 0
        before = _files(folder)
        try:
            status = main(argv)
        except SystemExit as exc:
            status = exc.code
        if status == 0:
            after = _files(folder)
            self.written[key] = {name: (folder / name).read_bytes() for name, stamp in after.items()
                                 if before.get(name) != stamp}
        return status


@pytest.fixture(scope="session")
def command_cache() -> CommandCache:
    return CommandCache()


def _run_block(block: Block, namespace: dict, folder: Path, cache: CommandCache) -> None:
    if block.lang == "yaml" and block.caption:
        target = folder / block.caption
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(block.text + "\n")
    elif block.lang == "python":
        code = compile("\n" * (block.first_line - 1) + block.text, block.page, "exec")
        try:
            exec(code, namespace)
        except Exception as exc:
            raise AssertionError(f"{block.where}: the python block fails: "
                                 f"{type(exc).__name__}: {exc}") from exc
    elif block.lang in SHELLS:
        for line, command in commands(block):
            status = cache.run(shlex.split(command)[1:], folder)
            assert status == 0, f"{block.page}:{line}: `{command}` exits with status {status}"


@pytest.mark.slow
@pytest.mark.parametrize("page", RUN_PAGES)
def test_the_page_runs(page, tmp_path, monkeypatch, command_cache):
    """Every block of the page, in order, in a folder holding the example scenes."""
    import matplotlib
    import matplotlib.pyplot as plt

    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    assert main(["examples", "--copy", "configs", "-q"]) == 0
    namespace: dict = {"__name__": "__main__"}
    try:
        for block in blocks(ROOT / page):
            if not block.not_run:
                _run_block(block, namespace, tmp_path, command_cache)
    finally:
        plt.close("all")


def test_the_readme_scene_loads():
    readme = [b.text for b in ALL_BLOCKS if b.page == "README.md" and b.lang == "yaml"]
    assert readme, "the README shows a scene"
    scene = fickcam.load_scene(yaml.safe_load(readme[0]))
    assert scene.name == "nylon-eccentric-cam"


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_no_page_names_a_file_outside_the_repository(page):
    text = page.read_text()
    for outside in ("SPEC.md", "../shared", "seeds/", "/work/"):
        assert outside not in text, f"{page.name} names {outside}"


def test_a_failing_block_names_its_page_and_line(tmp_path, monkeypatch, command_cache):
    monkeypatch.chdir(tmp_path)
    page = tmp_path / "page.md"
    page.write_text("# A page\n\n```python\nx = 1\nundefined_name\n```\n\n"
                    "```console\n$ fickcam check missing.yaml\n```\n")
    python, console = blocks_of(page, tmp_path)
    with pytest.raises(AssertionError, match=r"page\.md:3: the python block fails: NameError") as info:
        _run_block(python, {}, tmp_path, command_cache)
    assert 'File "page.md", line 5' in "".join(traceback.format_tb(info.value.__cause__.__traceback__))
    with pytest.raises(AssertionError, match=r"page\.md:9: `fickcam check missing.yaml` exits with status 2"):
        _run_block(console, {}, tmp_path, command_cache)


# What a new user comes for, and the page and heading that answers it
TASKS = {
    "write a scene for an eccentric nylon cam": ("guide/scenes", "A first scene: an eccentric nylon cam"),
    "age it through a weather file": ("guide/climates", "Age a part through a weather file"),
    "state a limit and find when it fails": ("guide/limits", "State a limit and find when it fails"),
    "get the dimensions to make": ("guide/limits", "Compensation: the dimensions to make"),
    "fit a material from coupon weighings": (
        "guide/materials", "Calibrating a material from weight-gain data (`fickcam fit`)"),
    "run 1,000 Monte Carlo cases on a cluster": (
        "guide/sweeps-montecarlo", "Run 1,000 Monte Carlo cases on a cluster"),
    "plot a result in Jupyter": ("guide/results-python", "Plot a result in Jupyter"),
}
TOCTREE = re.compile(r"^```\{toctree\}\n(.*?)^```", re.MULTILINE | re.DOTALL)
LINK = re.compile(r"\]\((?!https?:|mailto:)([^)#\s]+)(?:#[^)\s]*)?\)")


def _document(page: Path) -> str:
    """A page's Sphinx document name (``guide/limits``)."""
    return page.relative_to(DOCS).with_suffix("").as_posix()


def _linked(page: Path) -> set[str]:
    """The documents one click away from ``page``: its toctree entries and its links."""
    text = page.read_text()
    targets = [line.strip() for tree in TOCTREE.findall(text) for line in tree.split("\n")
               if line.strip() and not line.strip().startswith(":")]
    targets += LINK.findall(text)
    found = set()
    for target in targets:
        path = (page.parent / target).resolve()
        if path.suffix in ("", ".md") and path.is_relative_to(DOCS.resolve()):
            found.add(path.relative_to(DOCS.resolve()).with_suffix("").as_posix())
    return found


def clicks_from_index() -> dict[str, int]:
    """The fewest clicks from the documentation index to every page of ``docs/``."""
    pages = {_document(p): p for p in DOCS.rglob("*.md") if "_build" not in p.parts}
    clicks = {"index": 0}
    frontier = ["index"]
    while frontier:
        following = []
        for name in frontier:
            for linked in _linked(pages[name]) if name in pages else ():
                if linked not in clicks:
                    clicks[linked] = clicks[name] + 1
                    following.append(linked)
        frontier = following
    return clicks


def _headings(page: Path) -> set[str]:
    return {line.lstrip("#").strip() for line in page.read_text().split("\n")
            if re.match(r"^#{1,6} ", line)}


@pytest.mark.parametrize("task", TASKS)
def test_each_task_is_within_two_clicks_of_the_index(task):
    document, heading = TASKS[task]
    clicks = clicks_from_index()
    assert clicks.get(document, 99) <= 2, f"{task}: {document} is not within two clicks of the index"
    assert heading in _headings(DOCS / f"{document}.md"), f"{task}: no heading '{heading}'"


def _slug(heading: str) -> str:
    """A heading's anchor, as GitHub and MyST make it."""
    return re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")


@pytest.mark.parametrize("page", ["README.md", "CONTRIBUTING.md"])
def test_every_link_of_the_readme_resolves(page):
    """The README and CONTRIBUTING are read on the repository's front page, outside the
    Sphinx build that checks the other pages' links: each relative link names a file of the
    repository and, after ``#``, one of its headings."""
    text = (ROOT / page).read_text()
    links = re.findall(r"\]\((?!https?:|mailto:)([^)\s]+)\)", text)
    assert links
    for link in links:
        path, _, anchor = link.partition("#")
        target = ROOT / path
        assert target.exists(), f"{page}: {link} names no file"
        if anchor:
            assert anchor in {_slug(h) for h in _headings(target)}, f"{page}: {link}: no such heading"
