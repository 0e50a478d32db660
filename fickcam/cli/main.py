"""The ``fickcam`` command line.

Exit status: 0 success; 2 bad input (one line per problem on stderr, no
traceback); 1 anything else (one line; ``--debug`` shows the traceback).
"""
from __future__ import annotations

import atexit
import gc
import signal
import sys

from .parser import build_parser
from .commands import COMMANDS
from ..errors import FickcamError, InputError, SceneError
from ..messages import error_line, terminal_messages

#: the commands that may use dask (the ``sweep`` extra; ``bench`` runs the checkout's
#: benchmark scripts); any other command, as its own process, runs without it
USES_DASK = frozenset({"sweep", "bench"})

def process_main() -> int:
    """The `fickcam` command as its own process. The interpreter's garbage collections
    walk every object the imports made (numpy, scipy, pandas, xarray, h5py), at exit only
    to free them with the process; frozen first (gc.freeze) they are skipped: 0.2-0.3 CPU s
    of a demo run, measured as whole processes. Only here: in a caller's process (tests,
    notebooks) a freeze would keep whatever garbage exists at that moment for good."""
    atexit.register(gc.freeze)
    signal.signal(signal.SIGTERM, _terminate)
    return main(whole_process=True)


class Terminated(KeyboardInterrupt):
    """The process was asked to stop (SIGTERM): raised where it is, as Ctrl-C raises
    KeyboardInterrupt, so that what it was writing is cleaned up as on Ctrl-C (Python's
    default for SIGTERM ends the process on the spot, its temporary files left behind)."""


def _terminate(signum, frame):
    raise Terminated


def main(argv: list[str] | None = None, whole_process: bool = False) -> int:
    """Run the ``fickcam`` command line on ``argv`` and return its exit status.

    What it writes on stderr follows :mod:`fickcam.messages` (``fickcam: error|warning|note:
    ...``, an input file's problems as ``FILE:LINE key: reason``).

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``fickcam``; None for ``sys.argv[1:]``.
    whole_process : bool
        The command is the whole process (:func:`process_main`), not a call from a caller's
        process (tests, notebooks).

    Returns
    -------
    int
        The exit status: 0 success, 1 failure, 2 bad input.
    """
    args = build_parser().parse_args(argv)
    args.whole_process = whole_process
    if whole_process and args.command not in USES_DASK:
        without_dask()
    with terminal_messages(args.verbose - args.quiet):
        return _run_command(args)


def without_dask() -> None:
    """Make this process run as an install without dask would: whenever dask is installed,
    pint imports ``dask.base`` when it is imported and xarray imports ``dask.array`` for its
    first Variable (0.2 CPU s of the demo run, a tenth of it), though no result outside a
    sweep is a dask array. ``None`` in ``sys.modules`` is the import system's own mark of a
    module that cannot be imported: ``import dask`` raises ImportError and
    ``importlib.util.find_spec("dask")`` returns None, which both libraries take as dask not
    installed. Only for a whole process (:func:`process_main`) that has not imported dask:
    in a caller's process it would hide dask from the caller's own code."""
    if "dask" not in sys.modules:
        sys.modules["dask"] = None


def _run_command(args) -> int:
    try:
        return COMMANDS[args.command](args)
    except SceneError as exc:
        for problem in exc.problems:
            print(str(problem), file=sys.stderr)
        return 2
    except InputError as exc:
        print(error_line(str(exc)), file=sys.stderr)
        return 2
    except FickcamError as exc:
        print(error_line(str(exc)), file=sys.stderr)
        return 1
    except KeyboardInterrupt as exc:  # Ctrl-C, or SIGTERM as Terminated: 128 + the signal
        stopped = isinstance(exc, Terminated)
        print(error_line("terminated" if stopped else "interrupted"), file=sys.stderr)
        return 128 + (signal.SIGTERM if stopped else signal.SIGINT)
    except BrokenPipeError:
        return 0
    except Exception as exc:  # last resort: one line, never a traceback unless --debug
        if args.debug:
            raise
        print(error_line(f"internal error: {type(exc).__name__}: {exc} (rerun with --debug)"),
              file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(process_main())
