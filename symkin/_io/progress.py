"""The one progress display of long work (reproducing papers, searches), on stderr.

On a terminal it redraws one line; elsewhere it prints one plain line per step when
``lines`` is set (so a CI log shows how far a long run got) and nothing otherwise.

    >>> import io
    >>> out = io.StringIO()
    >>> bar = Progress(2, stream=out, lines=True)
    >>> bar.step("deriving"); bar.step("writing"); bar.close()
    >>> print(out.getvalue(), end="")
    [........................] 1/2 deriving
    [############............] 2/2 writing
"""

from __future__ import annotations

import sys
from typing import Any

__all__ = ["Progress"]

_WIDTH = 24


class Progress:
    """A progress display: :meth:`step` counts steps of a known total, :meth:`show` shows
    any text (a search's own count); :meth:`close` ends the line.

    Parameters
    ----------
    total : int, optional
        Steps in all (a bar is drawn when given).
    stream : file, optional
        Where to write (default stderr).
    enabled : bool
        False shows nothing (``--quiet``).
    lines : bool
        Off a terminal, write each step as a plain line (default: show nothing).
    """

    def __init__(self, total: int | None = None, *, stream: Any = None, enabled: bool = True, lines: bool = False):
        self.total, self.done = total, 0
        self.stream = stream if stream is not None else sys.stderr
        self.tty = enabled and hasattr(self.stream, "isatty") and self.stream.isatty()
        self.lines = enabled and lines and not self.tty
        self.shown = False

    def step(self, message: str) -> None:
        """One step more, described by ``message``."""
        self.done += 1
        if self.total:
            filled = int(_WIDTH * (self.done - 1) / max(self.total, 1))
            message = f"[{'#' * filled}{'.' * (_WIDTH - filled)}] {self.done}/{self.total} {message}"
        self.show(message)

    def show(self, text: str) -> None:
        """Show ``text`` as the current state."""
        if self.tty:
            self.shown = True
            self.stream.write(f"\r\x1b[2K{text}")
            self.stream.flush()
        elif self.lines:
            self.stream.write(text + "\n")
            self.stream.flush()

    def close(self) -> None:
        """End the display (a terminal's line is cleared)."""
        if self.shown:
            self.stream.write("\r\x1b[2K")
            self.stream.flush()
            self.shown = False
