"""The command line: ``fretting run | validate | info | plot | export | examples | stress | sweep | materials |
threshold | map`` (also ``python -m fretting``).

Each group of commands is a module here (`results`, `stress`, `sweeps`, `fatigue`) that adds its
parsers and holds their actions; `common` holds what they share.

Exit codes: 0 success, 2 bad input (files, keys, values, arguments), 3 gross slip, 1 a solver
failure, 130 interrupted, 141 output closed by its reader (``fretting examples | head``: quietly, as
a shell's tools end on SIGPIPE). Errors are one line on stderr; ``--debug`` shows the traceback.
"""

import argparse
import os
import signal
import sys
import threading

from fretting import __version__
from fretting.analysis.fatigue import MaterialFileError
from fretting.cli import fatigue, results, stress, sweeps
from fretting.cli.common import figure_options
from fretting.errors import FrettingError, GrossSlipError, HistoryError, MissingDependencyError
from fretting.results.io import ResultError

__all__ = ["main"]

EXIT_FAILURE, EXIT_INPUT, EXIT_GROSS_SLIP, EXIT_INTERRUPTED, EXIT_PIPE = 1, 2, 3, 130, 141


def main(argv=None):
    """Run the command line with the arguments `argv` (``sys.argv[1:]`` when None); return the exit code.

    Ctrl-C is `_Interrupts`': never lost, and said in one line. With `argv` None (the process's own
    command line), an interrupt after the work is done is ignored: it would only kill the exiting
    interpreter, with a traceback or none.
    """
    args = _parser().parse_args(argv)
    with _Interrupts() as interrupts:
        code = _main(args, interrupts)
    if argv is None and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    return code


class _Interrupts:
    """SIGINT, while the block runs in the main thread: KeyboardInterrupt as Python's own handler raises
    it, and remembered, so that one raised where Python cannot pass it on (a weakref callback or a
    ``__del__``, which it reports as "Exception ignored" and drops: h5py and xarray run both) is
    raised again at the next `check`, not lost, and is not reported there."""

    def __init__(self):
        self.lost = False

    def __enter__(self):
        self._main = threading.current_thread() is threading.main_thread()
        if self._main:
            self._handler = signal.signal(signal.SIGINT, self._interrupted)
            self._hook, sys.unraisablehook = sys.unraisablehook, self._unraisable
        return self

    def __exit__(self, *exception):
        if self._main:
            signal.signal(signal.SIGINT, self._handler)
            sys.unraisablehook = self._hook

    def _interrupted(self, signum, frame):
        self.lost = True  # until it is seen to pass (`passed`)
        raise KeyboardInterrupt

    def _unraisable(self, unraisable):
        if not issubclass(unraisable.exc_type, KeyboardInterrupt):
            self._hook(unraisable)

    def passed(self):
        """The interrupt raised was caught where it is handled: none is lost."""
        self.lost = False

    def check(self):
        """Raise KeyboardInterrupt if an interrupt was dropped since the last `passed`."""
        if self.lost:
            raise KeyboardInterrupt


def _main(args, interrupts):
    """`main` of the parsed arguments `args`."""
    args.interrupts = interrupts
    try:
        args.command(args)
        interrupts.check()
    except KeyboardInterrupt as interrupt:
        interrupts.passed()
        return _fail(args, interrupt, f"interrupted{f': {interrupt}' if interrupt.args else ''}", EXIT_INTERRUPTED)
    except GrossSlipError as error:
        return _fail(args, error, f"{args.file}: {error}", EXIT_GROSS_SLIP)
    except BrokenPipeError:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # nothing more to flush at exit
        return EXIT_PIPE
    except OSError as error:
        return _fail(args, error, f"{error.filename or args.file}: {error.strerror or error}", EXIT_INPUT)
    except (HistoryError, ResultError, MaterialFileError, MissingDependencyError) as error:
        return _fail(args, error, str(error), EXIT_INPUT)
    except FrettingError as error:
        return _fail(args, error, f"{args.file}: {error}", EXIT_FAILURE)
    return 0


def _fail(args, error, message, code):
    if args.debug:
        raise error
    print(f"fretting: error: {message}", file=sys.stderr)
    return code


def _parser():
    parser = argparse.ArgumentParser(
        prog="fretting", description="Partial-slip half-plane contacts under shear and bulk-tension histories."
    )
    parser.add_argument("--version", action="version", version=f"fretting {__version__}")
    commands = parser.add_subparsers(title="commands", required=True, metavar="COMMAND")
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--debug", action="store_true", help="show the traceback of an error")
    figures = figure_options()
    results.add_parsers(commands, common, figures)
    stress.add_parser(commands, common, figures)
    sweeps.add_parser(commands, common)
    fatigue.add_parsers(commands, common, figures)
    return parser
