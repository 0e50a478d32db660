"""What fickcam writes on stderr: errors, warnings, notes and progress bars.

One scheme for every command::

    fickcam: error: no variable 'lfit' in this result; did you mean lift?
    fickcam: warning: crank at t = 2.5 h: service temperature 118.0 degC reached the wet Tg ...
    fickcam: note: at t = 0 h: Grashof class: crank-rocker
    scene.yaml:3 cam.thicknes: unknown key; did you mean 'thickness'?

A problem in an input file keeps the compiler's ``FILE:LINE key: reason`` form; every other
line starts with ``fickcam:`` and its level. The levels are the :mod:`logging` module's:
``error`` (ERROR: the command failed), ``warning`` (WARNING: the result is computed but
something in it needs attention), ``note`` (INFO: what the run found, for information) and
``debug`` (DEBUG: details of the work, shown with ``-v``). ``-q`` hides the notes and the
progress bar, ``-qq`` also the warnings and the summary.

Notices a run collects (``Response.notices``, the result's ``notices`` attribute) are plain
strings and warn; a notice made with :func:`note` informs. :func:`log_notices` logs each at
its level.

Progress bars (:func:`progress_bar`) appear only on a terminal (or as a notebook widget),
never as carriage-return frames in a log or a pipe.
"""
from __future__ import annotations

import contextlib
import logging
import sys

PROGRAM = "fickcam"

#: the word each logging level is shown with
LABELS = {logging.DEBUG: "debug", logging.INFO: "note", logging.WARNING: "warning",
          logging.ERROR: "error", logging.CRITICAL: "error"}

#: the level of fickcam's logger for each verbosity (``-v``: +1, ``-q``: -1, ``-qq``: -2)
LEVELS = {1: logging.DEBUG, 0: logging.INFO, -1: logging.WARNING, -2: logging.ERROR}


def line(level: int, message: str) -> str:
    """``fickcam: LEVEL: message``, the form of every line fickcam writes on stderr.

    A problem in an input file is the exception: it starts with its ``FILE:LINE key``.

    Parameters
    ----------
    level : int
        A :mod:`logging` level (``logging.WARNING``...); an unknown one is shown as ``note``.
    message : str
        The text after the level.

    Returns
    -------
    str
        The line, without a trailing newline.
    """
    return f"{PROGRAM}: {LABELS.get(level, 'note')}: {message}"


def error_line(message: str) -> str:
    """``fickcam: error: message``: the line of a command that failed.

    Parameters
    ----------
    message : str
        What failed, in one line.

    Returns
    -------
    str
        The line, without a trailing newline.
    """
    return line(logging.ERROR, message)


class Note(str):
    """A notice that informs (shown as ``note:``); a plain ``str`` notice warns.

    Parameters
    ----------
    *args, **kwargs
        The arguments of :class:`str` (the notice's text).
    """

    level = logging.INFO


def note(text: str) -> Note:
    """``text`` as an informational notice (e.g. the Grashof class of a four-bar).

    Parameters
    ----------
    text : str
        The notice.

    Returns
    -------
    Note
        ``text`` marked to be logged at INFO.
    """
    return Note(text)


def level_of(notice: str) -> int:
    """The logging level of a notice: INFO for a :class:`Note`, WARNING otherwise.

    Parameters
    ----------
    notice : str
        A notice of a run (a :class:`Note` or a plain string).

    Returns
    -------
    int
        ``logging.INFO`` or ``logging.WARNING``.
    """
    return getattr(notice, "level", logging.WARNING)


def restated(notice: str, text: str) -> str:
    """``text`` (a notice said again, e.g. with its ageing time) with ``notice``'s level.

    Parameters
    ----------
    notice : str
        The original notice, whose level (:class:`Note` or plain) is kept.
    text : str
        The new wording.

    Returns
    -------
    str
        ``text`` as a :class:`Note` if ``notice`` is one, else as a plain string.
    """
    return Note(text) if isinstance(notice, Note) else text


def log_notices(logger: logging.Logger, notices) -> None:
    """Log each notice at its level (:func:`level_of`).

    Parameters
    ----------
    logger : logging.Logger
        Where the notices go.
    notices : iterable of str
        The notices, in order.
    """
    for notice in notices:
        logger.log(level_of(notice), "%s", notice)


def count_levels(notices) -> dict[str, int]:
    """How many warnings and notes ``notices`` hold: ``{"warning": 3, "note": 4}``.

    Parameters
    ----------
    notices : iterable of str
        The notices of a run.

    Returns
    -------
    dict of str to int
        Counts under ``"warning"`` and ``"note"`` [1].
    """
    counts = {"warning": 0, "note": 0}
    for notice in notices:
        counts[LABELS[level_of(notice)]] += 1
    return counts


class _LevelFormatter(logging.Formatter):
    """fickcam's records as ``fickcam: LEVEL: message``; another library's as
    ``LIBRARY: LEVEL: message``."""

    def format(self, record: logging.LogRecord) -> str:
        name = record.name.split(".")[0]
        text = super().format(record)
        return f"{name}: {LABELS.get(record.levelno, 'note')}: {text}"


class _TerminalHandler(logging.Handler):
    """Writes each record to the current ``sys.stderr`` above any progress bar
    (``tqdm.write`` clears the bar, writes the line and draws the bar again)."""

    def emit(self, record: logging.LogRecord) -> None:
        try:
            from tqdm import tqdm

            tqdm.write(self.format(record), file=sys.stderr)
        except Exception:  # noqa: BLE001 (a message that cannot be written must not stop the run)
            self.handleError(record)


@contextlib.contextmanager
def terminal_messages(verbosity: int = 0):
    """While inside: fickcam's log records on stderr as ``fickcam: LEVEL: message``, other
    libraries' only from WARNING; the loggers are restored on leaving (a caller's process,
    tests or a notebook, keeps its own set-up).

    Parameters
    ----------
    verbosity : int
        ``-v`` count minus ``-q`` count [1]: 1 debug, 0 notes, -1 warnings, -2 errors only
        (:data:`LEVELS`; clipped to that range).
    """
    level = LEVELS[max(min(verbosity, max(LEVELS)), min(LEVELS))]
    ours, root = logging.getLogger(PROGRAM), logging.getLogger()
    handler, others = _TerminalHandler(), _TerminalHandler(logging.WARNING)
    handler.setFormatter(_LevelFormatter())
    others.setFormatter(_LevelFormatter())
    saved = ours.level, ours.propagate, root.level
    ours.setLevel(level)
    ours.propagate = False  # fickcam's records are written once, here
    ours.addHandler(handler)
    quiet_root = not root.handlers  # no handler of the caller's: other libraries' warnings too
    if quiet_root:
        root.addHandler(others)
        root.setLevel(logging.WARNING)
    try:
        yield
    finally:
        ours.removeHandler(handler)
        ours.setLevel(saved[0])
        ours.propagate = saved[1]
        if quiet_root:
            root.removeHandler(others)
            root.setLevel(saved[2])


#: a bar with its remaining time: ``run: mechanisms:  40%|####      | 146/366 ageing times [00:03<00:04]``
ETA_BAR = "{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} {unit} [{elapsed}<{remaining}{postfix}]"
#: a count and the time spent: ``run: diffusion: 1/4 parts [00:12, coupler]``
COUNT_BAR = "{desc}: {n_fmt}/{total_fmt} {unit} [{elapsed}{postfix}]"


def progress_bar(total: int, *, enabled: bool = True, eta: bool = True, **options):
    """A tqdm bar on stderr, shown only when ``enabled`` and stderr is a terminal (or as a
    widget in a notebook): never as ``\\r`` frames in a log or a pipe.

    Parameters
    ----------
    total : int
        Steps the bar counts [1].
    enabled : bool
        False hides it (``-q``, or a caller that asked for no progress).
    eta : bool
        Show the remaining time: only for steps of about equal cost. False for steps that
        differ a hundredfold (the diffusion of parts): the bar then shows the steps done and
        the time spent, not a remaining time it cannot know.
    **options
        Passed to tqdm (``desc``, ``unit``, ``leave``, ``initial``...).
    """
    from tqdm.asyncio import tqdm as console_bar
    from tqdm.auto import tqdm

    widget = tqdm is not console_bar  # tqdm.auto chose a notebook widget
    shown = enabled and (widget or _is_terminal(sys.stderr))
    options["bar_format"] = ETA_BAR if eta else COUNT_BAR
    return tqdm(total=total, disable=not shown, **options)


def _is_terminal(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        return False


@contextlib.contextmanager
def quieter(logger: str, level: int):
    """Raise ``logger``'s level to at least ``level`` for a while, restoring it after.

    A library's chatter is held back where fickcam calls it, never by changing the library's
    logger for good; the level is never lowered below what it was.

    Parameters
    ----------
    logger : str
        The logger's name (e.g. ``"distributed"``).
    level : int
        The least :mod:`logging` level it shows while inside.
    """
    target = logging.getLogger(logger)
    old = target.level
    target.setLevel(max(level, target.getEffectiveLevel()))
    try:
        yield
    finally:
        target.setLevel(old)
