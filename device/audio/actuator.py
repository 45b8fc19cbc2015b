"""The `audio` device plugin: the drive layer to a sound card, for voice-coil or LRA actuators.

The project renders at the haptic rate (`rate`, 10 kHz by default); each block's drive term is
cleaned (NaN/inf to 0), clamped to full scale (+-1), resampled to the card's rate with soxr and
written to a sounddevice output stream. The card plays silence whenever the stream runs dry, and
the output ends at zero when the stream closes.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable
from typing import Any

import numpy as np

from timeline.plugins.device_protocol import (
    CoefficientBlock,
    Device,
    DeviceError,
    DeviceInfo,
    Hand,
    LiveTelemetry,
    Monitor,
    PositionProgram,
    Progress,
    Telemetry,
)

FULL_SCALE = 1.0


def load_sounddevice() -> Any:
    """The sounddevice module, or one sentence saying what to install."""
    try:
        return importlib.import_module("sounddevice")
    except ImportError:
        raise DeviceError(
            "the audio device needs the sounddevice package: pip install 'haptic-timeline[audio]'"
        ) from None
    except OSError:
        raise DeviceError(
            "the audio device needs the PortAudio library: install libportaudio2 "
            "(apt-get install libportaudio2)"
        ) from None


def _number(value: Any) -> bool:
    """True for a finite int or float (not a bool, not text)."""
    return isinstance(value, int | float) and not isinstance(value, bool) and np.isfinite(value)


class AudioActuator(Device):
    """A vibrotactile actuator on a sound card output (sounddevice / PortAudio).

    `device` is a sounddevice output name or index (default: the system's default output),
    `samplerate` the card's rate (default: the card's own default), `rate` the haptic rate the
    project is rendered at, `gain` the fraction of full scale that drive 1.0 becomes.
    """

    def __init__(
        self,
        device: str | int | None = None,
        samplerate: float | None = None,
        rate: float = 10_000.0,
        gain: float = 1.0,
        latency: str | float = "high",
    ) -> None:
        if not (_number(gain) and 0 < gain <= 1):
            raise DeviceError(f"the audio gain must be in (0, 1], not {gain!r}")
        for name, value in (("rate", rate), ("samplerate", samplerate)):
            if value is not None and not (_number(value) and value > 0):
                raise DeviceError(f"the audio {name} is a positive number of Hz, not {value!r}")
        if not (isinstance(latency, str) or (_number(latency) and latency >= 0)):
            raise DeviceError(
                f"the audio latency is low, high or a number of seconds, not {latency!r}"
            )
        self.device, self.samplerate, self.rate = device, samplerate, float(rate)
        self.gain, self.latency = float(gain), latency
        self._card: dict[str, Any] | None = None

    @classmethod
    def missing(cls) -> str | None:
        """What to install when sounddevice or PortAudio is missing."""
        try:
            load_sounddevice()
        except DeviceError as exc:
            return str(exc)
        return None

    @classmethod
    def discover(cls) -> list[str]:
        """One line per sound card output; empty when sounddevice or PortAudio is missing."""
        try:
            sd = load_sounddevice()
            cards = sd.query_devices()
        except Exception:  # a listing must not fail, whatever PortAudio says
            return []
        return [
            f"{c['name']} ({c['max_output_channels']} channels, {c['default_samplerate']:g} Hz)"
            for c in cards
            if c["max_output_channels"] > 0
        ]

    def open(self) -> None:
        if self._card is None:
            sd = load_sounddevice()
            try:
                self._card = dict(sd.query_devices(self.device, "output"))
            except (ValueError, sd.PortAudioError) as exc:
                which = "default output" if self.device is None else f"output {self.device!r}"
                raise DeviceError(f"no sound card {which} was found ({exc})") from None

    @property
    def card_rate(self) -> float:
        """Samples per second the sound card plays."""
        self.open()
        return float(self.samplerate or self._card["default_samplerate"])

    @property
    def info(self) -> DeviceInfo:
        self.open()
        name = f"audio {self._card['name']} at {self.card_rate:g} Hz"
        return DeviceInfo(name, "vibrotactile", self.rate, FULL_SCALE, 0.0, "")

    def play(
        self,
        program: Iterable[CoefficientBlock] | PositionProgram,
        hand: Hand | None = None,
        progress: Progress | None = None,
        monitor: Monitor | None = None,
    ) -> Telemetry:
        """Play the drive term of every block on the sound card; returns what was sent."""
        if isinstance(program, PositionProgram):
            raise DeviceError("a vibrotactile actuator plays time-mode projects only")
        import soxr

        sd = load_sounddevice()
        self.open()
        resampler = soxr.ResampleStream(self.rate, self.card_rate, 1, dtype="float32")
        played, dropped, bad = [], set(), 0
        try:
            with sd.OutputStream(
                samplerate=self.card_rate, device=self.device, channels=1, dtype="float32",
                latency=self.latency,
            ) as stream:  # fmt: skip
                for block in program:
                    drive, n_bad = _drive(block, dropped)
                    bad += n_bad
                    played.append(drive)
                    out = self._out(drive)
                    self._write(stream, resampler.resample_chunk(out))
                    if monitor and len(out):
                        first = sum(map(len, played)) - len(out)
                        time = (first + np.arange(len(out))) / self.rate
                        monitor(LiveTelemetry(time, np.zeros(len(out)), out.astype(np.float64)))
                    if progress:
                        progress(sum(map(len, played)) / self.rate, None)
                self._write(stream, resampler.resample_chunk(np.zeros(0, np.float32), last=True))
        except sd.PortAudioError as exc:
            raise DeviceError(f"the sound card failed while playing: {exc}") from None
        return self._telemetry(np.concatenate(played) if played else np.zeros(0), dropped, bad)

    def _out(self, drive: np.ndarray) -> np.ndarray:
        return (np.clip(drive, -FULL_SCALE, FULL_SCALE) * self.gain).astype(np.float32)

    @staticmethod
    def _write(stream: Any, samples: np.ndarray) -> None:
        """Write resampled samples, clamped again: the resampler can overshoot full scale."""
        if len(samples):
            stream.write(np.clip(samples, -FULL_SCALE, FULL_SCALE).reshape(-1, 1))

    def _telemetry(self, drive: np.ndarray, dropped: set[str], bad: int) -> Telemetry:
        n = len(drive)
        sent = np.clip(drive, -FULL_SCALE, FULL_SCALE)
        saturated = np.abs(drive) > FULL_SCALE
        warnings = []
        if bad:
            warnings.append(f"{bad} drive samples were NaN or infinite and were played as zero")
        if saturated.any():
            warnings.append(f"{int(saturated.sum())} drive samples were clamped to full scale")
        if dropped:
            names = ", ".join(sorted(dropped))
            warnings.append(f"a vibrotactile actuator plays the drive layer only; {names} ignored")
        zeros = np.zeros(n)
        time = np.arange(n) * (1.0 / self.rate)
        output = sent * self.gain
        return Telemetry(
            self.rate,
            time,
            zeros,
            zeros,
            output,
            zeros,
            saturated,
            {"d": sent},
            (),
            tuple(warnings),
        )


def _drive(block: CoefficientBlock, dropped: set[str]) -> tuple[np.ndarray, int]:
    """The block's drive term with NaN/inf as 0; notes layers with values it cannot play."""
    for name in ("k", "b", "m"):
        values = getattr(block, name)
        if values is not None and np.any(values):
            dropped.add(name)
    finite = np.isfinite(block.d)
    return np.where(finite, block.d, 0.0), int(np.count_nonzero(~finite))
