"""The ``fickcam`` command line (SPEC.md §2).

Exit status: 0 success; 2 bad input (one line per problem on stderr, no
traceback); 1 anything else (one line; ``--debug`` shows the traceback).
"""
from __future__ import annotations

import atexit
import gc
import logging
import sys

from .cli_parser import _parser  # noqa: F401  (re-exported: tests build the parser from here)
from .commands import COMMANDS
from .errors import FickcamError, InputError, SceneError

log = logging.getLogger("fickcam")


def process_main() -> int:
    """The `fickcam` command as its own process. The interpreter's garbage collections
    walk every object the imports made (numpy, scipy, pandas, xarray, h5py), at exit only
    to free them with the process; frozen first (gc.freeze) they are skipped: 0.2-0.3 CPU s
    of a demo run, measured as whole processes. Only here: in a caller's process (tests,
    notebooks) a freeze would keep whatever garbage exists at that moment for good."""
    atexit.register(gc.freeze)
    return main(whole_process=True)


def main(argv: list[str] | None = None, whole_process: bool = False) -> int:
    args = _parser().parse_args(argv)
    args.whole_process = whole_process
    # fickcam's own messages (INFO and notices) on stderr; other libraries' only from WARNING
    # (FiPy logs its solver suite at INFO); --quiet keeps notices off too (errors still print)
    logging.basicConfig(level=logging.WARNING, format="fickcam: %(message)s", stream=sys.stderr)
    log.setLevel(logging.ERROR if getattr(args, "quiet", False) else logging.INFO)
    try:
        return COMMANDS[args.command](args)
    except SceneError as exc:
        for problem in exc.problems:
            print(str(problem), file=sys.stderr)
        return 2
    except InputError as exc:
        print(f"fickcam: {exc}", file=sys.stderr)
        return 2
    except FickcamError as exc:
        print(f"fickcam: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("fickcam: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except Exception as exc:  # last resort: one line, never a traceback unless --debug
        if args.debug:
            raise
        print(f"fickcam: internal error: {type(exc).__name__}: {exc} (rerun with --debug)",
              file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(process_main())
