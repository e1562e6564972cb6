"""The ``persson-fast`` console script's entry point, a module outside the package.

Importing :mod:`persson_fast.cli` runs the package's ``__init__`` first (numpy, numba and
the modules of the kernels: about a second, several on a cold start), so a Ctrl-C in those
seconds raised KeyboardInterrupt inside the import, before any code of the command could
catch it, and Python printed a traceback. The console script imports this module instead:
it imports nothing of weight itself, and it turns a Ctrl-C at any moment -- while the
package is imported, while the command runs, while it exits -- into the one answer
:func:`persson_fast.cli.main.main` gives once it runs: ``interrupted`` on stderr and exit code
130. ``import persson_fast`` and ``python -m persson_fast.cli`` are not affected.
"""
import sys

__all__ = ["run", "INTERRUPTED_EXIT_CODE"]

#: the exit code of an interrupted command (128 + SIGINT, as a shell reports it)
INTERRUPTED_EXIT_CODE = 130


def _interrupted() -> None:
    """Say "interrupted" and exit with INTERRUPTED_EXIT_CODE; a second Ctrl-C while the
    process exits (threads joined, files closed) is ignored, not a traceback."""
    import signal

    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except (ValueError, OSError):      # not the main thread, or no signals here
        pass
    print("interrupted", file=sys.stderr)
    raise SystemExit(INTERRUPTED_EXIT_CODE)


def run() -> None:
    """The ``persson-fast`` console script: import the package, then run
    :func:`persson_fast.cli.main.run` (which exits with the command's code)."""
    try:
        from persson_fast.cli.main import run as run_command

        run_command()
    except KeyboardInterrupt:
        _interrupted()


if __name__ == "__main__":
    run()
