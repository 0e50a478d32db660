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
``debug`` (DEBUG: details of the work, shown with ``-v``). ``-q`` leaves the errors only
on stderr (no warnings, notes or progress bar), ``-qq`` also drops the summary on stdout.

Notices a run collects (``Response.notices``, the result's ``notices`` attribute) are plain
strings and warn; a notice made with :func:`note` informs. :func:`log_notices` reports each
at its level.

Who hears what: a warning (:func:`warn`) reaches a Python caller as a
:class:`~fickcam.errors.FickcamWarning` through the ``warnings`` module, and the command line as a
``fickcam: warning:`` line; notes and debug details go to the ``fickcam`` logger (INFO and
DEBUG), which says nothing until its user switches it on (``logging.basicConfig`` or a
handler of their own). ``-q`` leaves only the errors.

Progress bars (:func:`progress_bar`) appear only on a terminal (or as a notebook widget),
never as carriage-return frames in a log or a pipe.
"""
from __future__ import annotations

import importlib.util
import time
import contextlib
import contextvars
import logging
import os
import sys
import warnings

from .errors import FickcamWarning

PROGRAM = "fickcam"

#: True while the command line shows the messages (:func:`terminal_messages`): warnings are
#: then log records on its stderr, not Python warnings
_ON_TERMINAL = contextvars.ContextVar("fickcam_on_terminal", default=False)
#: the list :func:`warn` appends its warnings to instead of reporting them, while one is set
#: (:func:`collected_warnings`)
_COLLECTING = contextvars.ContextVar("fickcam_collecting", default=None)

#: the word each logging level is shown with
LABELS = {logging.DEBUG: "debug", logging.INFO: "note", logging.WARNING: "warning",
          logging.ERROR: "error", logging.CRITICAL: "error"}

#: the level of fickcam's logger for each verbosity (``-v``: +1, ``-q``: -1, ``-qq``: -2):
#: ``-q`` leaves the errors only
LEVELS = {1: logging.DEBUG, 0: logging.INFO, -1: logging.ERROR, -2: logging.ERROR}


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


class DesignNotice(str):
    """A warning about the design itself, true at every ageing time (a motion law's jump in
    acceleration): a run tells it once, without ageing times.

    Parameters
    ----------
    *args, **kwargs
        The arguments of :class:`str` (the notice's text).
    """


def design_notice(text: str) -> DesignNotice:
    """``text`` as a warning about the design, told once whatever the ageing times.

    Parameters
    ----------
    text : str
        The warning.

    Returns
    -------
    DesignNotice
        ``text``, marked as true of the design at every age.
    """
    return DesignNotice(text)


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


def warn(message: str, *args) -> None:
    """Report a warning: a :class:`~fickcam.errors.FickcamWarning` to a Python caller
    (pointing at the caller's line, not fickcam's), a ``fickcam: warning:`` line on the
    command line (:func:`terminal_messages`).

    Parameters
    ----------
    message : str
        The warning; with ``args``, a ``%``-format (as :mod:`logging` takes it).
    *args
        Values for the ``%``-format.
    """
    text = message % args if args else message
    collecting = _COLLECTING.get()
    if collecting is not None:
        collecting.append(text)
    elif _ON_TERMINAL.get():
        logging.getLogger(PROGRAM).warning("%s", text)
    else:
        warnings.warn(text, FickcamWarning, stacklevel=_callers_level())


@contextlib.contextmanager
def collected_warnings():
    """Collect the warnings :func:`warn` makes while inside, instead of reporting them.

    A sweep's case keeps its warnings in its record: its worker process has no terminal to
    show them on, and a warning every case makes alike would repeat once a case. The sweep
    reports each distinct warning once, with the number of cases that made it.

    Yields
    ------
    list of str
        The warnings made inside, in order.
    """
    caught: list[str] = []
    token = _COLLECTING.set(caught)
    try:
        yield caught
    finally:
        _COLLECTING.reset(token)


def _callers_level() -> int:
    """The ``stacklevel`` of :func:`warnings.warn`, called from :func:`warn`, that names the
    first frame outside the fickcam package (the user's line)."""
    package = os.path.dirname(os.path.abspath(__file__)) + os.sep
    frame, level = sys._getframe(1), 1  # noqa: SLF001 (the standard way to walk the stack)
    while frame is not None and frame.f_code.co_filename.startswith(package):
        frame, level = frame.f_back, level + 1
    return level


def log_notices(logger: logging.Logger, notices) -> None:
    """Report each notice at its level (:func:`level_of`): warnings through :func:`warn`,
    notes on ``logger`` at INFO.

    Parameters
    ----------
    logger : logging.Logger
        Where the notes go.
    notices : iterable of str
        The notices, in order.
    """
    for notice in notices:
        if level_of(notice) >= logging.WARNING:
            warn(notice)
        else:
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
            # deferred: keeps tqdm off the start-up path
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
    on_terminal = _ON_TERMINAL.set(True)
    try:
        yield
    finally:
        _ON_TERMINAL.reset(on_terminal)
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
    """A progress bar: tqdm's text bar on a terminal's stderr, one bar in a notebook (a widget
    with ipywidgets, else text that redraws in place), and none in a log or a pipe.

    In a notebook the bar is one output that each step redraws; inside
    :func:`progress_summary` the bars of a task share it, and it is replaced by the task's
    summary line at the end, so a saved notebook keeps that line, not a stale frame.
    tqdm's own notebook detection (``tqdm.auto``) is not used: without ipywidgets it warns
    (``TqdmWarning: IProgress not found``) on import.

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

    Returns
    -------
    tqdm.std.tqdm
        The bar (disabled where nothing is shown); use it as tqdm's.
    """
    # deferred: keeps tqdm off the start-up path
    from tqdm.std import tqdm

    options["bar_format"] = ETA_BAR if eta else COUNT_BAR
    session = _SESSION.get()
    place = notebook_kind() if enabled else None
    if place is None:
        shown = enabled and _is_terminal(sys.stderr)
        bar = tqdm(total=total, disable=not shown, file=sys.stderr, **options)
    else:
        bar = _notebook_bar(place, total, session, options)
    if session is not None and enabled:
        session.steps.append(f"{total} {options.get('unit', 'steps')}")
    return bar


def notebook_kind() -> str | None:
    """Where a bar is shown in this process: ``"widget"`` in a Jupyter kernel with
    ipywidgets, ``"text"`` in one without, None outside a kernel (a terminal, a script,
    IPython in a terminal).

    Returns
    -------
    str or None
        ``"widget"``, ``"text"`` or None.
    """

    shell = getattr(sys.modules.get("IPython"), "get_ipython", lambda: None)()
    if shell is None or "IPKernelApp" not in getattr(shell, "config", {}):
        return None
    return "widget" if importlib.util.find_spec("ipywidgets") is not None else "text"


class OutputLine:
    """One line of text as a notebook output (``text/plain``): a task's summary, or a text
    progress bar's latest frame.

    Parameters
    ----------
    text : str
        The line.
    """

    def __init__(self, text: str):
        self.text = text

    def __repr__(self) -> str:
        return self.text


class _FrameWriter:
    """A file for tqdm's text bar that shows its latest frame in a notebook output, in place
    (``\\r`` frames would pile up in the saved notebook)."""

    def __init__(self, handle):
        self.handle = handle

    def write(self, text: str) -> None:
        frame = text.replace("\r", "").strip()
        if frame:
            self.handle.update(OutputLine(frame))

    def flush(self) -> None:
        """Nothing is buffered."""


def _notebook_bar(place: str, total: int, session, options: dict):
    """A bar shown in one notebook output (the session's, else its own)."""
    # deferred: keeps IPython off the start-up path
    from IPython.display import display

    handle = session.handle if session is not None else None
    if handle is None:
        handle = display(OutputLine(options.get("desc", "")), display_id=True)
        if session is not None:
            session.handle = handle
    if place == "widget":
        # deferred: keeps tqdm and ipywidgets off the start-up path
        from tqdm.notebook import tqdm as widget_bar

        options.pop("bar_format")  # the widget draws its own bar
        bar = widget_bar(total=total, display=False, **options)
        handle.update(bar.container)
        return bar
    # deferred: keeps tqdm off the start-up path
    from tqdm.std import tqdm

    return tqdm(total=total, file=_FrameWriter(handle), ncols=100, **options)


#: the task whose progress bars share one place (:func:`progress_summary`)
_SESSION = contextvars.ContextVar("fickcam_progress", default=None)


class _Session:
    """The bars of one task and the notebook output they share."""

    def __init__(self, what: str):
        self.what, self.started, self.steps, self.handle = what, time.perf_counter(), [], None

    def summary(self) -> str:
        took = time.perf_counter() - self.started
        return f"{PROGRAM}: {self.what}: {', '.join(self.steps) or 'done'} in {took:.3g} s"


@contextlib.contextmanager
def progress_summary(what: str, enabled: bool = True):
    """While inside, the progress bars of one task (``what``: ``run singh2017-cam``) share
    one place; on leaving, one line says what ran and how long it took: ``fickcam: run
    singh2017-cam: 2 parts, 5 ageing times in 3.1 s``.

    In a notebook the line replaces the bars' output, so it stays in the saved notebook;
    elsewhere it is written on stderr. Nothing happens when ``enabled`` is False or on the
    command line, which prints its own summary.

    Parameters
    ----------
    what : str
        The task, as the summary names it.
    enabled : bool
        Whether progress was asked for.
    """
    if not enabled or _ON_TERMINAL.get() or _SESSION.get() is not None:
        yield
        return
    session = _Session(what)
    token = _SESSION.set(session)
    try:
        yield
    finally:
        _SESSION.reset(token)
        if session.handle is not None:
            session.handle.update(OutputLine(session.summary()))
        elif notebook_kind() is not None:
            # deferred: IPython only in a notebook
            from IPython.display import display

            display(OutputLine(session.summary()))
        else:
            print(session.summary(), file=sys.stderr)


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
