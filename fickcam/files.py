"""Files written whole or not at all: a temporary file beside the target, held by its
writer, renamed over the target at the end (``os.replace`` is atomic on POSIX), so that a
crash or ``kill -9`` at any moment leaves the old file or the new one, never half of one;
and the temporaries of writers that died, found and removed.
"""
from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager
from pathlib import Path

try:
    import fcntl
except ImportError:  # not on Windows: temporaries are not held, and none is taken as stale
    fcntl = None


def _umask_mode() -> int:
    """The mode a plain ``open(path, 'w')`` would give (mkstemp makes 0600 files)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


@contextmanager
def temporary_beside(path: Path, suffix: str = ".tmp") -> Iterator[str]:
    """A new temporary file in ``path``'s folder, with the usual permissions, held by
    this process for the block (an exclusive ``flock`` on it) and removed at the block's
    end unless the block renamed it.

    The hold tells a later writer of ``path`` whether the writer of a temporary file it
    finds is alive (:func:`remove_stale_temporaries`): the kernel releases it when the
    process dies, however it dies.

    Parameters
    ----------
    path : pathlib.Path
        The file it will replace.
    suffix : str
        The end of its name.

    Yields
    ------
    str
        The temporary file's path (created empty, mode as ``open(path, 'w')`` would give).
    """
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=path.parent)
    try:
        os.fchmod(fd, _umask_mode())
        if fcntl is not None:
            fcntl.flock(fd, fcntl.LOCK_EX)
        yield tmp
    finally:
        Path(tmp).unlink(missing_ok=True)  # nothing when the block renamed it
        os.close(fd)  # the hold ends with it


@contextmanager
def replaced_atomically(path) -> Iterator[str]:
    """A temporary file beside ``path`` for the block to write, renamed over ``path`` at its end.

    The folder is made if needed; the file is removed if the block raises: ``path`` is never
    left half written.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write.

    Yields
    ------
    str
        The temporary file's path.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with temporary_beside(path) as tmp:
        yield tmp
        os.replace(tmp, path)


def write_text_atomically(path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` through a temporary file and a rename.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write (its folder is made if needed).
    text : str
        Its whole content.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    with replaced_atomically(path) as tmp, open(tmp, "w", encoding="utf-8", newline="") as handle:
        handle.write(text)
    return Path(path)


def remove_stale_temporaries(path) -> list[Path]:
    """Remove the temporary files that writers of ``path`` which died left beside it.

    A process killed while it wrote ``path`` leaves its hidden ``.NAME.XXXXXXXX.tmp`` (the
    name :func:`temporary_beside` gives). A temporary file whose writer is alive is held
    by it and kept: only one that no process holds is removed, so two writers of ``path``
    never take each other's file. Where files cannot be held (no ``fcntl``), none is removed.

    Parameters
    ----------
    path : str or pathlib.Path
        The file whose temporaries to remove.

    Returns
    -------
    list of pathlib.Path
        The files removed.
    """

    if fcntl is None:
        return []
    path = Path(path)
    pattern = re.compile(rf"\.{re.escape(path.name)}\.[A-Za-z0-9_]{{8}}\.tmp")
    folder = path.parent if str(path.parent) else Path(".")
    removed = []
    for found in folder.glob(f".{path.name}.*.tmp"):
        if pattern.fullmatch(found.name) and not _held(found):
            found.unlink(missing_ok=True)
            removed.append(found)
    return removed


def _held(path: Path) -> bool:
    """Whether a live process holds ``path`` (:func:`temporary_beside`); a file that cannot
    be opened counts as held (it is not ours to remove)."""
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return True
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return True
    finally:
        os.close(fd)  # a hold taken here ends with it
    return False


@contextmanager
def replaced_together(paths) -> Iterator[list[str]]:
    """Temporary files beside each of ``paths`` for the block to write, renamed all together.

    Each temporary name ends in its target's suffix (for writers that go by it); all are
    renamed over their targets when the block ends, all removed if it raises: the targets are
    written all or none.

    Parameters
    ----------
    paths : iterable of str or pathlib.Path
        The files to write (their folders are made if needed).

    Yields
    ------
    list of str
        The temporary files, in the order of ``paths``.
    """
    paths = [Path(p) for p in paths]
    with ExitStack() as held:
        temps = []
        for path in paths:
            path.parent.mkdir(parents=True, exist_ok=True)
            temps.append(held.enter_context(temporary_beside(path, suffix=f".tmp{path.suffix}")))
        yield temps
        for tmp, path in zip(temps, paths):
            os.replace(tmp, path)
