"""What a long computation reports to: points done, and notices worth a line of their own.

The computation (a sweep) reports through this protocol and never draws on a terminal;
the displays that do are ``front.progress``'s, handed to it by its caller.
"""

from __future__ import annotations

import warnings


class SweepWarning(UserWarning):
    """A notice of a sweep given as a warning: a failed point, a saved file computed again."""


class ProgressReporter:
    """What a long run reports to, for those who want more than the counts.

    1. ``reporter(done, total)`` after each point (and once before the first, with the
       points already done);
    2. ``reporter.notice(message)`` for what deserves a line of its own: a point whose
       simulation failed, a saved file that is damaged and computed again.

    Subclass it and override both. A plain callable ``progress(done, total)`` receives the
    counts only; its run issues the notices as ``SweepWarning`` warnings, as this class
    does by default.
    """

    def __call__(self, done: int, total: int) -> None:
        """Called with the points done so far out of ``total``."""

    def notice(self, message: str) -> None:
        """Called with one line worth telling; by default, a ``SweepWarning``."""
        warnings.warn(message, SweepWarning, stacklevel=2)
