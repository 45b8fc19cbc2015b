"""How late a real-time stream handed its blocks over: what a device with a wall clock feels.

A device plays each block from a moment fixed by the wall clock (its "due" time); the host
hands blocks over `lead` ahead of that, keeping the device's queue that full. A block handed
over more than the lead behind its slot reaches the device after its first sample was due: on
hardware an underrun, and soon the watchdog ramping the torque to zero (docs/usb-protocol.md,
sections 4 and 6). The meter counts such blocks, hand-over gaps longer than the watchdog, the
worst delay and how long the first block took.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

LEAD_SECONDS = 0.030  # the USB protocol's default lead (docs/usb-protocol.md, section 4)
GAP_SECONDS = 0.050  # the protocol's default watchdog: a longer silence trips it


@dataclass(frozen=True)
class Lateness:
    """What a meter counted: blocks later than the lead, long gaps, the worst delay."""

    blocks: int = 0  # blocks handed over
    late: int = 0  # blocks handed over more than `lead` behind their slot
    gaps: int = 0  # hand-overs more than GAP_SECONDS after the one before
    worst: float = 0.0  # s: the largest delay of a block behind its slot
    lead: float = LEAD_SECONDS
    first_block: float | None = None  # s from asking to play to the first block handed over

    def sentence(self) -> str:
        """A message for the user when blocks were late, else ""."""
        if not self.late:
            return ""
        blocks = "1 block" if self.late == 1 else f"{self.late} blocks"
        gaps = "1 gap" if self.gaps == 1 else f"{self.gaps} gaps"
        gaps = f", {gaps} over {GAP_SECONDS * 1e3:.0f} ms" if self.gaps else ""
        return f"{blocks} late, worst {self.worst * 1e3:.0f} ms{gaps}: the knob may have gone slack"

    def describe(self) -> str:
        """One line for a summary."""
        first = "" if self.first_block is None else f", first block {self.first_block * 1e3:.0f} ms"
        return (
            f"real time: {self.late} of {self.blocks} blocks later than the "
            f"{self.lead * 1e3:.0f} ms lead, {self.gaps} gaps over {GAP_SECONDS * 1e3:.0f} ms, "
            f"worst {self.worst * 1e3:.1f} ms behind{first}"
        )


class LatenessMeter:
    """Counts blocks as a stream hands them over (one writer thread; any thread may read)."""

    def __init__(self, lead: float = LEAD_SECONDS, asked: float | None = None) -> None:
        self.lead = lead
        self.asked = time.perf_counter() if asked is None else asked
        self.blocks = self.late = self.gaps = 0
        self.worst = 0.0
        self.first: float | None = None  # perf_counter of the first hand-over
        self._last = 0.0

    def handed(self, due: float, now: float) -> float:
        """One block handed over at `now` whose first sample plays at `due` (perf_counter s).

        Its slot is `lead` before `due`, but never before the first hand-over (the blocks that
        fill the lead at the start go at once); returns its delay behind that slot.
        """
        if self.first is None:
            self.first = self._last = now
        behind = max(0.0, now - max(self.first, due - self.lead))
        self.blocks += 1
        self.late += behind > self.lead
        self.gaps += now - self._last > GAP_SECONDS
        self.worst = max(self.worst, behind)
        self._last = now
        return behind

    def counts(self) -> Lateness:
        """The counts so far."""
        first = None if self.first is None else self.first - self.asked
        return Lateness(self.blocks, self.late, self.gaps, self.worst, self.lead, first)
