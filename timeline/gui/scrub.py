"""Scrub: while the playhead is dragged on the ruler, the device plays what is under it.

A time project plays a short grain (GRAIN_SECONDS, as audio editors' scrub) of the mixed output
from the scrubbed time each time the playhead moves, through the chosen device and the sound
output, so nothing plays once the mouse stops. A position project's knob is held at the
scrubbed angle (a holding hand with the chosen grip) so the force field there is felt, for as
long as the mouse is down. At most one grain (or new hold) starts per GRAIN_SECONDS; the newest
position waits for the next one. Letting go stops it all and gives the chosen hand back.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from PySide6.QtCore import QObject, QTimer

from timeline.model import Project
from timeline.plugins.device_protocol import Hand

from .player import Player

GRAIN_SECONDS = 0.04


class Scrubber(QObject):
    """Plays grains (time) or holds the knob (position) where the scrubbed playhead is."""

    def __init__(self, player: Player, project: Callable[[], Project]) -> None:
        super().__init__(player)
        self.player = player
        self.project = project
        self.active = False  # between begin and end
        self.was_playing = False  # the player was playing when the scrub began
        self._hand: Hand | None = None  # the chosen hand, given back at the end
        self._waiting: float | None = None  # the newest position, played at the next tick
        self._tick = QTimer(self)
        self._tick.setSingleShot(True)
        self._tick.setInterval(round(GRAIN_SECONDS * 1000))
        self._tick.timeout.connect(self._next)

    def begin(self) -> None:
        """The playhead starts moving under the mouse: a play going on stops."""
        self.was_playing = self.player.playing
        self.player.stop()
        self._hand = self.player.hand
        self.active = True

    def move(self, u: float) -> None:
        """The playhead is at `u` (s, or rad in a position project): play there now, or at
        the next tick when a grain has just started."""
        if not self.active:
            return
        self._waiting = u
        if not self._tick.isActive():
            self._next()

    def end(self) -> None:
        """The mouse is let go: nothing more plays and the chosen hand is back."""
        if not self.active:
            return
        self.active = False
        self._tick.stop()
        self._waiting = None
        self.player.stop()
        if self._hand is not None:
            self.player.hand, self._hand = self._hand, None

    def _next(self) -> None:
        u, self._waiting = self._waiting, None
        if u is None or not self.active:
            return
        self._play(u)
        self._tick.start()

    def _play(self, u: float) -> None:
        project = self.project()
        if not any(t.clips for t in project.tracks):
            return  # nothing to feel anywhere
        if project.axis == "position":
            hand = self._hand or self.player.hand
            self.player.hand = replace(hand, mode="hold", value=0.0)
            self.player.play(project, origin=u)
            return
        stop = min(project.duration, u + GRAIN_SECONDS)
        if stop > u:
            self.player.play(project, u, stop)
        else:
            self.player.stop()  # past the end: silence
