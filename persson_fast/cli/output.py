"""The output files of the ``persson-fast`` command, written whole or not at all.

:class:`_OutputSet` writes each output to a temporary file in its folder and renames the set
onto the final names together, with Ctrl-C and SIGTERM held back during the renames
(:func:`_sigint_held`); while the set is open SIGTERM raises :class:`Terminated`, so that its
temporary files are removed and the old outputs stay as they were; :func:`_write_csv` writes
the CSV tables (floats that round-trip).
"""
from __future__ import annotations

import contextlib
import csv
import os
import signal
import stat
import tempfile

import numpy as np


def _write_csv(path, columns: dict) -> None:
    """Write equal-length columns; floats round-trip (repr), integer columns stay integers."""
    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    def as_int(v):
        return str(int(v))

    def as_float(v):
        return repr(float(v))

    fmt = [as_int if np.issubdtype(a.dtype, np.integer) else as_float for a in arrays]
    with open(path, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(names)
        for i in range(len(arrays[0]) if arrays else 0):
            writer.writerow([f(a[i]) for f, a in zip(fmt, arrays)])


class Terminated(BaseException):
    """SIGTERM arrived while output files were being written (:class:`_OutputSet`): raised so
    that the temporary files are removed on the way out; the command exits with
    ``TERMINATED_EXIT_CODE``. A BaseException, like KeyboardInterrupt, so that no ``except
    Exception`` on the way swallows it."""


#: the exit code of a command ended by SIGTERM while writing its outputs (128 + SIGTERM)
TERMINATED_EXIT_CODE = 128 + 15


def _raise_terminated(signum, frame):
    raise Terminated


@contextlib.contextmanager
def _sigint_held():
    """Hold back SIGINT (Ctrl-C) and SIGTERM inside the block; one that came meanwhile is
    delivered after it (a Ctrl-C raises KeyboardInterrupt, SIGTERM goes to its handler).

    Outside the main thread (where Python cannot install signal handlers), or for a signal
    whose handler Python did not install (and so could not put back), the block runs as it is.
    """
    caught = []
    held = {}
    for signum in (signal.SIGINT, signal.SIGTERM):
        previous = signal.getsignal(signum)
        if previous is None:
            continue
        try:
            signal.signal(signum, lambda num, frame: caught.append(num))
        except ValueError:  # not the main thread of the main interpreter
            break
        held[signum] = previous
    try:
        yield
    finally:
        for signum, previous in held.items():
            signal.signal(signum, previous)
        for signum in dict.fromkeys(caught):
            previous = held[signum]
            if previous is signal.SIG_IGN:
                continue
            if signum == signal.SIGINT:
                if callable(previous):
                    previous(signal.SIGINT, None)  # the default one raises KeyboardInterrupt
                else:
                    raise KeyboardInterrupt
            else:
                signal.raise_signal(signum)        # to its own handler (or the default: exit)


@contextlib.contextmanager
def _sigterm_raises():
    """Inside the block SIGTERM raises :class:`Terminated` (so that ``finally`` clauses and
    ``with`` blocks run: temporary files are removed) instead of ending the process at once;
    the previous handler is put back after it. Outside the main thread, or where SIGTERM has
    a handler Python did not install, the block runs as it is."""
    previous = signal.getsignal(signal.SIGTERM)
    installed = False
    if previous is not None and previous is not signal.SIG_IGN:
        try:
            signal.signal(signal.SIGTERM, _raise_terminated)
            installed = True
        except ValueError:  # not the main thread of the main interpreter
            pass
    try:
        yield
    finally:
        if installed:
            signal.signal(signal.SIGTERM, previous)


class _OutputSet:
    """The output files of one run, written under temporary names and renamed together.

    ``path(final)`` creates an empty temporary file in the folder of ``final`` and returns its
    name, to be written instead of ``final``; ``commit()`` renames each onto its final name
    (``os.replace``: atomic within a folder) with Ctrl-C and SIGTERM held back, so an interrupt
    leaves either all the old files or all the new ones, and prints ``wrote PATH``, adding when
    an existing file was replaced. Leaving the ``with`` block otherwise (an error, a
    KeyboardInterrupt, SIGTERM, which raises :class:`Terminated` inside the block) removes the
    temporary files and leaves the existing outputs untouched, byte for byte.
    """

    def __init__(self):
        self._pending = []  # (temporary name, final name)
        self._sigterm = None

    def __enter__(self):
        self._sigterm = _sigterm_raises()
        self._sigterm.__enter__()
        return self

    def __exit__(self, *exc_info):
        try:
            with _sigint_held():       # a signal now would leave temporary files behind
                self.discard()
        finally:
            self._sigterm.__exit__(None, None, None)
        return False

    def path(self, final: str) -> str:
        folder = os.path.dirname(os.path.abspath(final))
        with _sigint_held():           # the temporary file is known as soon as it exists
            fd, tmp = tempfile.mkstemp(prefix=f".{os.path.basename(final)}.", suffix=".tmp",
                                       dir=folder)
            self._pending.append((tmp, final))
            os.close(fd)
        return tmp

    def discard(self) -> None:
        """Remove the temporary files not yet renamed."""
        while self._pending:
            tmp, _ = self._pending.pop()
            with contextlib.suppress(OSError):
                os.remove(tmp)

    def commit(self) -> None:
        """Rename every temporary file onto its final name; say which existed before."""
        for _, final in self._pending:
            if os.path.isdir(final):
                raise IsADirectoryError(f"cannot write {final!r}: it is a folder")
        for tmp, final in self._pending:
            _set_mode(tmp, final)
        with _sigint_held():
            while self._pending:
                tmp, final = self._pending[0]
                existed = os.path.exists(final)
                os.replace(tmp, final)
                self._pending.pop(0)
                print(f"wrote {final}" + (" (replaced the existing file)" if existed else ""))


def _set_mode(tmp: str, final: str) -> None:
    """Give ``tmp`` the permissions ``final`` has (or a new file would get: 0o666 - umask),
    instead of mkstemp's 0o600."""
    try:
        mode = stat.S_IMODE(os.stat(final).st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o666 & ~umask
    with contextlib.suppress(OSError):
        os.chmod(tmp, mode)
