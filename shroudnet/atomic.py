"""Files written whole or not at all: every file shroudnet writes goes through ``write``.

The content goes to a temporary file beside the target, ``.NAME.PID-XXXXXXXX.part`` (PID
the writing process), is flushed to the disc, and is renamed over the target
(``os.replace``: atomic within one file system). Whatever stops a write, an exception, a
full disc or Ctrl-C, removes the temporary file and leaves the file that was there before
as it was; the error names the file. Only a process killed outright (SIGKILL, a power cut)
leaves its temporary file behind: the next write of the same file removes it, once the
process that wrote it has gone (on POSIX systems, where that can be told; elsewhere such a
file is left for the user to delete).
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import BinaryIO

#: The suffix of a file being written.
PART = ".part"


class WriteError(OSError):
    """A file that could not be written: ``filename`` is the file, ``errno`` and
    ``strerror`` the system's reason. The file that was there before is left as it was."""

    def __str__(self) -> str:
        return f"cannot write {self.filename}: {self.strerror}; nothing was changed there"


def write(path: str | os.PathLike, writer: Callable[[BinaryIO], object]) -> Path:
    """Call ``writer(file)`` on a temporary binary file beside ``path``, then rename it to
    ``path``; its folder is made if missing.

    Raises ``WriteError`` naming ``path`` when the system refuses any step (a folder that
    cannot be made or written, a full disc); what ``writer`` raises otherwise passes
    through. Either way the temporary file is removed and ``path`` is left as it was.
    """
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        remove_leftovers(path)
        handle, temporary = tempfile.mkstemp(dir=path.parent, suffix=PART,
                                             prefix=f".{path.name}.{os.getpid()}-")
    except OSError as error:
        raise _refused(path, error) from None
    try:
        with os.fdopen(handle, "wb") as file:
            writer(file)
            file.flush()
            os.fsync(file.fileno())
        os.replace(temporary, path)
    except BaseException as error:
        Path(temporary).unlink(missing_ok=True)
        if isinstance(error, OSError) and not isinstance(error, WriteError):
            raise _refused(path, error) from None
        raise
    return path


def write_text(path: str | os.PathLike, text: str) -> Path:
    """``write`` of ``text`` encoded as UTF-8."""
    data = text.encode("utf-8")
    return write(path, lambda file: file.write(data))


def _refused(path: Path, error: OSError) -> WriteError:
    return WriteError(error.errno, error.strerror or str(error), str(path))


def leftovers(path: str | os.PathLike) -> list[Path]:
    """The temporary files of writes of ``path`` that never finished (by any process,
    running or not): ``.NAME.PID-XXXXXXXX.part`` beside it, and ``.NAME.XXXXXXXX.part``
    of the layout without the process."""
    path = Path(path)
    try:
        names = os.listdir(path.parent)
    except OSError:
        return []
    prefix = f".{path.name}."
    return [path.parent / name for name in names if name.startswith(prefix)
            and _LEFTOVER.fullmatch(name[len(prefix):])]


#: What follows ``.NAME.`` in a temporary file's name: the writing process's id (absent in
#: the older layout) and ``tempfile``'s eight random characters, which hold no dot.
_LEFTOVER = re.compile(r"(?:\d+-[a-z0-9_]+|[a-z0-9_]{8})" + re.escape(PART))


def remove_leftovers(path: str | os.PathLike) -> None:
    """Delete the temporary files of unfinished writes of ``path`` whose process has gone
    (one that cannot be deleted is left: it is litter, and no reason not to write)."""
    for leftover in leftovers(path):
        writer = _writer(leftover)
        if writer is None or not _running(writer):
            try:
                leftover.unlink(missing_ok=True)
            except OSError:
                pass


def _writer(leftover: Path) -> int | None:
    """The id of the process that wrote ``leftover``, None in the layout without it."""
    found = re.search(r"\.(\d+)-[a-z0-9_]+" + re.escape(PART) + "$", leftover.name)
    return int(found.group(1)) if found else None


def _running(pid: int) -> bool:
    """Whether process ``pid`` may still be writing: True where that cannot be told."""
    if pid == os.getpid() or os.name != "posix":
        return True
    try:
        os.kill(pid, 0)  # signal 0: only asks whether the process exists
    except ProcessLookupError:
        return False
    except OSError:  # another user's, for one: it exists
        return True
    return True
