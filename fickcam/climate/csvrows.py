"""CSV rows with their line numbers, read within the csv module's bound on a cell.

Python's ``csv`` reader refuses a cell longer than ``csv.field_size_limit()`` (128 KiB);
:func:`numbered_rows` turns that refusal (a file that is not the CSV of numbers it should
be, or a header line without an end) into a :class:`CsvError` naming the line, which each
reader reports in its own words.
"""
from __future__ import annotations

import csv
from collections.abc import Iterable, Iterator


class CsvError(ValueError):
    """A line the csv module cannot read.

    Parameters
    ----------
    line : int
        The line, from 1.
    reason : str
        Why, in the user's words.
    """

    def __init__(self, line: int, reason: str):
        self.line = line
        self.reason = reason
        super().__init__(f"line {line}: {reason}")


def numbered_rows(handle: Iterable[str]) -> Iterator[tuple[int, list[str]]]:
    """The rows of a CSV file opened with ``newline=""``, each with its first line.

    Parameters
    ----------
    handle : iterable of str
        The open file.

    Yields
    ------
    tuple of (int, list of str)
        The line (from 1) and the row's cells.

    Raises
    ------
    CsvError
        At a cell longer than the csv module's limit, or a line it cannot read.
    """
    reader = csv.reader(handle)
    line = 1
    while True:
        try:
            row = next(reader)
        except StopIteration:
            return
        except csv.Error as exc:
            limit = csv.field_size_limit()
            reason = (f"a cell longer than {limit:,} characters: not a CSV of numbers"
                      if "field larger" in str(exc) else f"not readable as CSV ({exc})")
            raise CsvError(reader.line_num, reason) from None
        yield line, row
        line = reader.line_num + 1
