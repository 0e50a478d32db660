"""The ``fickcam`` command line.

Exit status: 0 success; 2 bad input (one line per problem on stderr, no
traceback); 1 anything else (one line; ``--debug`` shows the traceback).
"""
from __future__ import annotations

import atexit
import gc
import sys

from .cli_parser import _parser  # noqa: F401  (re-exported: tests build the parser from here)
from .commands import COMMANDS
from .errors import FickcamError, InputError, SceneError
from .messages import error_line, terminal_messages


def process_main() -> int:
    """The `fickcam` command as its own process. The interpreter's garbage collections
    walk every object the imports made (numpy, scipy, pandas, xarray, h5py), at exit only
    to free them with the process; frozen first (gc.freeze) they are skipped: 0.2-0.3 CPU s
    of a demo run, measured as whole processes. Only here: in a caller's process (tests,
    notebooks) a freeze would keep whatever garbage exists at that moment for good."""
    atexit.register(gc.freeze)
    return main(whole_process=True)


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
    args = _parser().parse_args(argv)
    args.whole_process = whole_process
    with terminal_messages(args.verbose - args.quiet):
        return _run_command(args)


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
    except KeyboardInterrupt:
        print(error_line("interrupted"), file=sys.stderr)
        return 130
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
