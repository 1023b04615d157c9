"""Progress of long runs on a terminal: points done, rate and time left, on one line.

The displays implement ``run.reporting.ProgressReporter``, the protocol the
computation reports to; it and ``SweepWarning`` are named here too.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from typing import TextIO

from ..run.reporting import ProgressReporter as ProgressReporter
from ..run.reporting import SweepWarning as SweepWarning


class TerminalProgress(ProgressReporter):
    """A progress reporter that redraws one line on a terminal.

    ``  sweep 120/400 points  3.2 points/s  1 min 27 s left`` — the rate counts from the
    first call, when nothing is done yet; the line ends when ``done == total``. A notice
    is written on a line of its own above it.
    """

    def __init__(self, label: str = "sweep", stream: TextIO | None = None):
        self.label = label
        self.stream = sys.stderr if stream is None else stream
        self._start: float | None = None
        self._line = ""  # the progress line now shown, "" when none is open

    def __call__(self, done: int, total: int) -> None:
        now = time.perf_counter()
        if self._start is None or done == 0:
            self._start = now
        elapsed = now - self._start
        line = f"  {self.label} {done}/{total} points"
        if done > 0 and elapsed > 0.0:
            rate = done / elapsed
            line += f"  {rate:,.2f} points/s" if rate < 100.0 else f"  {rate:,.0f} points/s"
            line += (f"  {_duration(elapsed)} in all" if done == total
                     else f"  {_duration((total - done) / rate)} left")
        end = "\n" if done == total else ""
        self.stream.write(f"\r{line:<60}{end}")
        self.stream.flush()
        self._line = "" if end else line

    def notice(self, message: str) -> None:
        """Write ``message`` on its own line, then the progress line again below it."""
        self.stream.write(f"\r{'  ' + message:<60}\n")
        if self._line:
            self.stream.write(f"\r{self._line:<60}")
        self.stream.flush()


class NoticeLines(ProgressReporter):
    """A progress reporter that shows no counts and writes each notice as a line, for
    standard error that is not a terminal (a log): ``  gamma1 = 3.5 (point 7) failed: …``.
    """

    def __init__(self, stream: TextIO | None = None):
        self.stream = sys.stderr if stream is None else stream

    def notice(self, message: str) -> None:
        self.stream.write(f"  {message}\n")
        self.stream.flush()


def _duration(seconds: float) -> str:
    if seconds < 10.0:
        return f"{seconds:.1f} s"
    if seconds < 60.0:
        return f"{seconds:.0f} s"
    minutes, seconds = divmod(round(seconds), 60)
    if minutes < 60:
        return f"{minutes} min {seconds} s"
    hours, minutes = divmod(minutes, 60)
    return f"{hours} h {minutes} min"


def progress_callback(progress, label: str = "sweep") -> Callable[[int, int], None] | None:
    """The callback ``progress`` asks for.

    ``"auto"``: a ``TerminalProgress`` on standard error when it is a terminal, else none;
    ``True``: always one; ``False`` or ``None``: none (silent); a callable (a
    ``ProgressReporter`` or a plain ``progress(done, total)``): itself.
    """
    if progress == "auto":
        return TerminalProgress(label) if sys.stderr.isatty() else None
    if progress is True:
        return TerminalProgress(label)
    if progress is None or progress is False:
        return None
    if callable(progress):
        return progress
    raise ValueError(f"progress must be 'auto', True, False, None or a callable "
                     f"progress(done, total), got {progress!r}")
