"""Stage timers: how long each stage of a run took, and telling the user which stage starts.

One clock for ``perform``'s stages (parse, load, plan, execute, judge) and the execution's own
(check, setup, reach, engage, move, disengage, record), so summary.json's ``timings_s`` mean the same
everywhere: seconds of wall time per stage, a stage entered twice counted once with both times added.
"""

from __future__ import annotations

import time
from collections.abc import Callable


class StageClock:
    """Times consecutive stages: :meth:`stage` ends the current one and starts the next.

    ``on_stage`` (for progress messages) is called with the message given to :meth:`stage`, if any.
    ``failed_stage`` names the stage that was running when :meth:`stop` was last called, or the one
    running now: the stage to blame when a run fails.
    """

    def __init__(self, on_stage: Callable[[str], None] | None = None):
        self.on_stage = on_stage
        self.timings: dict[str, float] = {}
        self.current: str | None = None
        self.last: str = ""
        self.t0 = time.perf_counter()
        self._since = self.t0

    def stage(self, name: str, message: str | None = None) -> None:
        """End the running stage (if any) and start ``name``."""
        self.stop()
        self.current, self.last, self._since = name, name, time.perf_counter()
        if self.on_stage is not None and message:
            self.on_stage(message)

    def stop(self) -> None:
        """End the running stage, adding its time to its total."""
        if self.current is not None:
            now = time.perf_counter()
            self.timings[self.current] = self.timings.get(self.current, 0.0) + now - self._since
            self.current = None

    @property
    def elapsed(self) -> float:
        """Seconds since the clock was made."""
        return time.perf_counter() - self.t0
