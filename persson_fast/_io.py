"""Atomic text output: a file is either the old one or the complete new one."""
from __future__ import annotations

import contextlib
import os
import tempfile


def write_text_atomic(path, text: str) -> str:
    """Write ``text`` to ``path`` through a temporary file in the same folder, renamed onto
    ``path`` when complete (``os.replace``), with the permissions a new file gets (0o666
    less the umask); an error leaves no partial file and the old one untouched. Returns
    ``path`` (as a str)."""
    path = os.fspath(path)
    if os.path.isdir(path):
        raise IsADirectoryError(f"cannot write {path!r}: it is a folder")
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=f".{os.path.basename(path)}.", suffix=".tmp",
                               dir=folder)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        umask = os.umask(0)
        os.umask(umask)
        with contextlib.suppress(OSError):
            os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise
    return path
