"""List the tables of a built site that scroll or are cut off in a browser window.

Each page with a table is opened in headless Chromium at the window width given; a table
is reported when it is wider than its container or reaches past the article::

    python docs/_tools/wide_tables.py docs/_build/html            # 1280 px
    python docs/_tools/wide_tables.py docs/_build/html --width 390

Prints one line per page with such tables (``page index:table width>container width``)
and exits 1 when there is any. The API module pages are sampled (every 25th).
"""
from __future__ import annotations

import argparse
import re
import subprocess
import sys
from pathlib import Path

PROBE = """<script>window.addEventListener('load', () => { const wide = [];
const article = document.querySelector('.bd-article') || document.body;
document.querySelectorAll('table').forEach((table, index) => {
  const box = table.parentElement;
  if (table.scrollWidth > box.clientWidth + 1 ||
      table.getBoundingClientRect().right > article.getBoundingClientRect().right + 1)
    wide.push(index + ':' + table.scrollWidth + '>' + box.clientWidth); });
const found = document.createElement('div'); found.id = 'wide-tables';
found.textContent = 'WIDE[' + wide.join(' ') + ']'; document.body.appendChild(found); });</script>"""


def wide_tables(page: Path, width: int, browser: str) -> str:
    """The wide tables of ``page`` as ``index:width>container`` words ('' when none)."""
    probe = page.with_name("__wide_tables_probe.html")  # beside the page: its links still resolve
    probe.write_text(page.read_text().replace("</body>", PROBE + "</body>"))
    try:
        dom = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu",
                              f"--window-size={width},1400", "--virtual-time-budget=3000",
                              "--dump-dom", probe.as_uri()],
                             capture_output=True, text=True, timeout=120).stdout
    finally:
        probe.unlink()
    found = re.search(r'id="wide-tables">WIDE\[(.*?)\]', dom)
    return found.group(1) if found else "(not measured)"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("site", type=Path, help="the built HTML site")
    parser.add_argument("--width", type=int, default=1280, help="window width [px]")
    parser.add_argument("--browser", default="chromium", help="the Chromium executable")
    args = parser.parse_args()
    pages = [p for p in args.site.rglob("*.html") if "_autosummary" not in p.parts]
    pages += sorted((args.site / "reference" / "_autosummary").glob("*.html"))[::25]
    reported = 0
    for page in sorted(pages):
        if "<table" in page.read_text():
            wide = wide_tables(page, args.width, args.browser)
            if wide:
                print(f"{page.relative_to(args.site)}: {wide}")
                reported += 1
    print(f"{reported} page(s) with wide tables at {args.width} px, of {len(pages)} read")
    return 1 if reported else 0


if __name__ == "__main__":
    sys.exit(main())
