"""The source sound through the sound card while the haptics play: context tracks heard in sync.

`SoundOut.play` starts a sounddevice (PortAudio) output stream at the moment haptic playback
starts, from the same timeline position; a feeder thread renders the context (audio) tracks of
the newest project state a quarter second at a time (so gain, mute and solo edits are heard
while playing) and the stream's callback only copies samples. Without sounddevice, PortAudio or
an output device, `play` returns one sentence and the haptics play on alone.
"""

from __future__ import annotations

import importlib
import queue
import threading
from typing import Any

import numpy as np

from timeline.errors import HapticTimelineError
from timeline.model import Project
from timeline.rendering.source_sound import has_sound, render_sound

CHUNK_SECONDS = 0.25
QUEUED_CHUNKS = 4  # rendered ahead of the card: one second


def _sounddevice() -> Any:
    try:
        return importlib.import_module("sounddevice")
    except ImportError:
        raise HapticTimelineError(
            "it needs the sounddevice package: pip install 'haptic-timeline[audio]'"
        ) from None
    except OSError:
        raise HapticTimelineError("it needs the PortAudio library: install libportaudio2") from None


class SoundOut:
    """Plays a project's context tracks on the default sound card output."""

    def __init__(self, device: str | int | None = None) -> None:
        self.device = device
        self.project: Project | None = None
        self._stream: Any = None
        self._feeder: threading.Thread | None = None
        self._halt = threading.Event()
        self._chunks: queue.Queue[np.ndarray | None] = queue.Queue(QUEUED_CHUNKS)
        self._current = np.zeros(0, dtype=np.float32)

    @property
    def playing(self) -> bool:
        return self._stream is not None

    def play(self, project: Project, start: float, stop: float, loop: bool = False) -> str:
        """Start the sound at `start` (s); "" when playing or nothing to play, else why not."""
        self.stop()
        if not has_sound(project) or stop <= start:
            return ""
        try:
            sd = _sounddevice()
        except HapticTimelineError as exc:
            return f"the source sound is not played: {exc}"
        try:
            card = dict(sd.query_devices(self.device, "output"))
            rate = float(card["default_samplerate"])
            self.project = project
            self._halt.clear()
            self._chunks = queue.Queue(QUEUED_CHUNKS)
            self._current = np.zeros(0, dtype=np.float32)
            self._feeder = threading.Thread(
                target=self._feed, args=(start, stop, rate, loop), daemon=True
            )
            self._feeder.start()
            self._stream = sd.OutputStream(
                samplerate=rate, device=self.device, channels=1, dtype="float32",
                callback=self._callback,
            )  # fmt: skip
            self._stream.start()
        except (ValueError, OSError, sd.PortAudioError) as exc:  # no output, or PortAudio refused
            self.stop()
            return f"the source sound is not played: there is no sound card output ({exc})"
        return ""

    def follow(self, project: Project) -> None:
        """Use a new project state from the next rendered quarter second on."""
        self.project = project

    def _feed(self, start: float, stop: float, rate: float, loop: bool) -> None:
        t = start
        while not self._halt.is_set():
            if t >= stop:
                if not loop:
                    break
                t = start
            end = min(stop, t + CHUNK_SECONDS)
            n = int(round((end - t) * rate))
            sound = render_sound(self.project, t, t + n / rate, rate) if self.project else None
            chunk = np.zeros(n, np.float32) if sound is None else sound.astype(np.float32)
            np.nan_to_num(np.clip(chunk, -1.0, 1.0, out=chunk), copy=False)
            self._offer(chunk)
            t = end
        self._offer(None)

    def _offer(self, chunk: np.ndarray | None) -> None:
        """Queue a chunk (None: the end) once the card has room, unless stopped meanwhile."""
        while not self._halt.is_set():
            try:
                self._chunks.put(chunk, timeout=0.1)
                return
            except queue.Full:
                continue

    def _callback(self, out: np.ndarray, frames: int, _time: Any, _status: Any) -> None:
        filled = 0
        while filled < frames:
            if len(self._current) == 0:
                try:
                    chunk = self._chunks.get_nowait()
                except queue.Empty:
                    break  # the feeder is late: this block ends in silence
                if chunk is None:
                    break
                self._current = chunk
            take = min(frames - filled, len(self._current))
            out[filled : filled + take, 0] = self._current[:take]
            self._current = self._current[take:]
            filled += take
        out[filled:, 0] = 0.0

    def stop(self) -> None:
        """Stop the sound now (the card ends on silence)."""
        self._halt.set()
        if self._stream is not None:
            try:
                self._stream.stop()
                self._stream.close()
            finally:
                self._stream = None
        if self._feeder is not None:
            self._feeder.join(timeout=1.0)
            self._feeder = None
