"""The work folder of a sweep (``OUT.parts/`` next to the result): the journal of
finished cases (:mod:`fickcam.sweep.journal`) and a manifest naming the sweep it
belongs to. An interrupted sweep resumes from the journal when the manifest's sweep
identity still matches.
"""
from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from ..messages import warn
from .journal import Entry, Journal


MANIFEST = "manifest.json"
JOURNAL = "cases.journal"


def write_json(data: dict, path: Path) -> Path:
    """Write JSON atomically (temporary file in the same folder, flushed, then renamed).

    Parameters
    ----------
    data : dict
        What to write.
    path : pathlib.Path
        The file (its folder must exist).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            json.dump(data, handle, indent=1)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


@dataclass(frozen=True)
class WorkFolder:
    """Paths of the per-case files of one sweep.

    Parameters
    ----------
    path : pathlib.Path
        The work folder (``OUT.parts`` next to the result).
    """

    path: Path

    @classmethod
    def next_to(cls, output) -> "WorkFolder":
        output = Path(output)
        return cls(output.with_name(output.name + ".parts"))

    @property
    def journal(self) -> Journal:
        return Journal(self.path / JOURNAL)

    def own_files(self) -> list[Path]:
        """What fickcam writes here (and the per-case files that older versions wrote)."""
        return sorted(self.path.glob("case-*.h5")) + sorted(self.path.glob("case-*.json")) + \
            sorted(self.path.glob(".case-*.tmp")) + \
            [p for p in (self.path / JOURNAL, self.path / MANIFEST) if p.exists()]

    def open_for(self, identity: str, n_cases: int) -> dict[int, dict]:
        """Create the folder or reuse it; return the records of finished cases.

        Cases of another sweep (different identity) are discarded, never mixed in.
        """
        return {index: entry.record for index, entry in self.finished(identity, n_cases).items()}

    def finished(self, identity: str, n_cases: int) -> dict[int, Entry]:
        """:meth:`open_for`, with where each finished case lies in the journal."""
        manifest_path = self.path / MANIFEST
        if self.path.exists():
            if not manifest_path.is_file():
                if any(self.path.iterdir()):
                    raise InputError(f"{self.path} exists and is not a fickcam sweep work folder; "
                                     f"move it away or choose another output")
            else:
                manifest = json.loads(manifest_path.read_text(encoding="utf-8"))
                if manifest.get("identity") == identity:
                    return self._finished_entries(n_cases)
                warn("%s holds cases of a different sweep (the sweep file, base scene or "
                     "fickcam version changed): starting over", self.path)
                self.remove_own_files()
        self.path.mkdir(parents=True, exist_ok=True)
        write_json({"identity": identity, "cases": n_cases}, manifest_path)
        return {}

    def _finished_entries(self, n_cases: int) -> dict[int, Entry]:
        """Journal entries of this sweep's cases, except those marked for another try
        (failed for a reason other than their scene)."""
        return {index: entry for index, entry in self.journal.read().items()
                if 0 <= index < n_cases and not entry.record.get("retry")}

    def remove_own_files(self) -> None:
        """Delete the files this module wrote, then the folder if it is empty."""
        for path in self.own_files():
            path.unlink(missing_ok=True)
        try:
            self.path.rmdir()
        except OSError:
            warn("left %s in place: it holds files fickcam did not write", self.path)
