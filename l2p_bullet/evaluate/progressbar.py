"""A progress bar with ETA on stderr: redrawn in place on a terminal, a line every few percent otherwise.

Written for ``evaluate`` (runs, with failures and errors counted); any long command reuses it with its
own ``unit`` and ``label`` (``train``: epochs, ``export``: episodes) and :meth:`ProgressBar.advance`.
"""

from __future__ import annotations

import sys
import time
from typing import TextIO


def _hms(seconds: float) -> str:
    s = int(round(seconds))
    h, rem = divmod(s, 3600)
    m, s = divmod(rem, 60)
    return f"{h}h{m:02d}m" if h else (f"{m}m{s:02d}s" if m else f"{s}s")


class ProgressBar:
    """``update(row)`` after every finished run (or ``advance()`` after any other step); ``close()`` at the
    end. ``total`` counts this call's steps; ``unit`` names them ("runs" adds failures and errors)."""

    def __init__(self, total: int, done_before: int = 0, stream: TextIO | None = None, enabled: bool = True,
                 width: int = 28, unit: str = "runs", label: str = ""):
        self.total, self.before, self.width = total, done_before, width
        self.unit, self.label = unit, label
        self.stream = stream or sys.stderr
        self.enabled = enabled and total > 0
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.done = self.failed = self.errors = 0
        self.t0 = time.perf_counter()
        self._last_line = -1.0

    def update(self, row: dict) -> None:
        self.done += 1
        self.errors += row.get("error") is not None
        self.failed += row.get("error") is None and not row.get("success")
        self._show()

    def advance(self, n: int = 1) -> None:
        """``n`` more steps done (a step that is not an evaluation run: an epoch, an episode)."""
        self.done += n
        self._show()

    def _show(self) -> None:
        if not self.enabled:
            return
        if self.tty:
            self._draw(end="")
        elif self.done == self.total or time.perf_counter() - self._last_line > 10 or \
                self.done % max(1, self.total // 20) == 0:
            self._draw(end="\n")

    def line(self) -> str:
        dt = time.perf_counter() - self.t0
        rate = self.done / dt if dt > 0 else 0.0
        eta = (self.total - self.done) / rate if rate > 0 else float("nan")
        frac = self.done / self.total if self.total else 1.0
        filled = int(round(frac * self.width))
        bar = "#" * filled + "." * (self.width - filled)
        eta_s = _hms(eta) if eta == eta else "?"
        counts = f"{self.failed} failed, {self.errors} errors  " if self.unit == "runs" else ""
        label = f"{self.label} " if self.label else ""
        return (f"{label}[{bar}] {self.done}/{self.total} {self.unit} ({frac:4.0%})  {counts}"
                f"{rate:.2f} {self.unit}/s  elapsed {_hms(dt)}  ETA {eta_s}")

    def _draw(self, end: str) -> None:
        self._last_line = time.perf_counter()
        self.stream.write(("\r\x1b[2K" if self.tty else "") + self.line() + end)
        self.stream.flush()

    def close(self) -> None:
        if self.enabled and self.tty:
            self.stream.write("\n")
            self.stream.flush()
