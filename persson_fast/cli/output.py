"""The output files of the ``persson-fast`` command, written whole or not at all.

:class:`_OutputSet` writes each output to a temporary file in its folder and renames the set
onto the final names together, with Ctrl-C held back during the renames
(:func:`_sigint_held`); :func:`_write_csv` writes the CSV tables (floats that round-trip).
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


@contextlib.contextmanager
def _sigint_held():
    """Hold back SIGINT (Ctrl-C) inside the block; one that came meanwhile is raised after it.

    Outside the main thread (where Python cannot install signal handlers), or when SIGINT has a
    handler that Python did not install (and so could not put back), the block runs as it is.
    """
    caught = []
    previous = signal.getsignal(signal.SIGINT)
    held = False
    if previous is not None:
        try:
            signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
            held = True
        except ValueError:  # not the main thread of the main interpreter
            pass
    try:
        yield
    finally:
        if held:
            signal.signal(signal.SIGINT, previous)
            if caught and previous is not signal.SIG_IGN:
                if callable(previous):
                    previous(signal.SIGINT, None)  # the default one raises KeyboardInterrupt
                else:
                    raise KeyboardInterrupt


class _OutputSet:
    """The output files of one run, written under temporary names and renamed together.

    ``path(final)`` creates an empty temporary file in the folder of ``final`` and returns its
    name, to be written instead of ``final``; ``commit()`` renames each onto its final name
    (``os.replace``: atomic within a folder) with Ctrl-C held back, so an interrupt leaves either
    all the old files or all the new ones, and prints ``wrote PATH``, adding when an existing
    file was replaced. Leaving the ``with`` block otherwise (an error, a KeyboardInterrupt)
    removes the temporary files and leaves the existing outputs untouched.
    """

    def __init__(self):
        self._pending = []  # (temporary name, final name)

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.discard()
        return False

    def path(self, final: str) -> str:
        folder = os.path.dirname(os.path.abspath(final))
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
