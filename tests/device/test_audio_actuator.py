"""The audio actuator through real PortAudio into an ALSA `file` PCM, captured and checked.

PortAudio reads the ALSA configuration once, when sounddevice is imported, so each capture runs
in a child process whose HOME holds an .asoundrc defining `pcm.haptic`: a file plugin over the
null device that writes the raw float32 samples PortAudio delivers.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import soxr

from device.audio import AudioActuator
from device.audio import actuator as audio
from timeline.plugins.device_protocol import DeviceError

NO_PORTAUDIO = 3
PLAYER = """
import json, sys
import numpy as np
from device.audio import AudioActuator
from timeline.plugins.device_protocol import CoefficientBlock, DeviceError
options, drive = json.loads(sys.argv[1]), np.array(json.loads(sys.argv[2]), dtype=float)
try:
    actuator = AudioActuator("haptic", **options)
    info = actuator.info
except DeviceError as exc:
    print(exc)
    sys.exit(3 if "PortAudio" in str(exc) else 1)
k = np.full(drive.size, 0.5)
blocks = [CoefficientBlock(drive[i : i + 700], k[i : i + 700], 0 * k[i : i + 700])
          for i in range(0, drive.size, 700)]
tel = actuator.play(blocks)
print(json.dumps({"rate": info.rate, "card": actuator.card_rate, "kind": info.kind,
                  "warnings": tel.warnings, "torque": tel.torque.tolist()}))
"""


def capture(tmp_path: Path, drive: np.ndarray, **options) -> tuple[np.ndarray, dict]:
    """Play `drive` (at 10 kHz) on pcm.haptic in a child process; the samples the card got."""
    raw = tmp_path / "captured.raw"
    (tmp_path / ".asoundrc").write_text(
        f'pcm.haptic {{\n type file\n slave.pcm "null"\n file "{raw}"\n format "raw"\n}}\n'
    )
    drive_json = json.dumps([None if not np.isfinite(x) else x for x in drive])
    run = subprocess.run(
        [sys.executable, "-c", PLAYER, json.dumps(options), drive_json.replace("null", "NaN")],
        env={"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"}, capture_output=True, text=True,
        timeout=60, cwd=Path(__file__).resolve().parents[2],
    )  # fmt: skip
    if run.returncode == NO_PORTAUDIO:
        pytest.skip(f"PortAudio is missing here (CI installs libportaudio2): {run.stdout.strip()}")
    assert run.returncode == 0, run.stderr + run.stdout
    return np.fromfile(raw, dtype="<f4"), json.loads(run.stdout.strip().splitlines()[-1])


def drive_signal(n: int = 3000) -> np.ndarray:
    """A 200 Hz drive at 1.5x full scale with one NaN sample."""
    d = 1.5 * np.sin(2 * np.pi * 200 * np.arange(n) / 10_000)
    d[1234] = np.nan
    return d


def test_the_sound_card_receives_the_clamped_drive_resampled_to_its_own_rate(tmp_path) -> None:
    d = drive_signal()
    captured, report = capture(tmp_path, d)
    assert (report["rate"], report["card"], report["kind"]) == (10_000, 44_100, "vibrotactile")
    clean = np.clip(np.nan_to_num(d, nan=0.0), -1.0, 1.0)
    expected = np.clip(soxr.resample(clean.astype(np.float32), 10_000, 44_100, "HQ"), -1, 1)
    assert captured.size == expected.size == 13_230  # 0.3 s at 44.1 kHz
    assert np.array_equal(captured, expected)
    assert np.abs(captured).max() == 1.0
    # Against the ideal clipped sine at 44.1 kHz, away from the NaN and the ends.
    t = np.arange(captured.size) / 44_100
    ideal = np.clip(1.5 * np.sin(2 * np.pi * 200 * t), -1.0, 1.0)
    middle = slice(500, 5000)
    assert np.abs(captured[middle] - ideal[middle]).max() < 0.02
    assert np.array_equal(report["torque"], np.where(np.isnan(d), 0.0, clean))
    assert report["warnings"] == [
        "1 drive samples were NaN or infinite and were played as zero",
        f"{np.count_nonzero(np.abs(d) > 1)} drive samples were clamped to full scale",
        "a vibrotactile actuator plays the drive layer only; k ignored",
    ]


def test_gain_and_an_explicit_card_rate(tmp_path) -> None:
    d = 0.8 * np.sin(2 * np.pi * 150 * np.arange(2000) / 10_000)
    captured, report = capture(tmp_path, d, samplerate=48_000, gain=0.5)
    assert report["card"] == 48_000 and captured.size == 9_600
    expected = soxr.resample((0.5 * d).astype(np.float32), 10_000, 48_000, "HQ")
    assert np.array_equal(captured, expected)
    assert np.abs(captured).max() == pytest.approx(0.4, abs=0.005)


def test_missing_sounddevice_or_portaudio_is_one_sentence(monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "sounddevice", None)
    with pytest.raises(DeviceError, match=r"pip install 'haptic-timeline\[audio\]'"):
        AudioActuator().open()
    assert AudioActuator.discover() == []

    def no_library(name: str):
        raise OSError("PortAudio library not found")

    monkeypatch.setattr(audio.importlib, "import_module", no_library)
    with pytest.raises(DeviceError, match=r"apt-get install libportaudio2\)$"):
        AudioActuator().open()


def test_an_unknown_card_and_a_bad_gain_are_refused() -> None:
    with pytest.raises(DeviceError, match=r"gain must be in \(0, 1\]"):
        AudioActuator(gain=2.0)
    try:
        audio.load_sounddevice()
    except DeviceError as exc:
        pytest.skip(str(exc))
    with pytest.raises(DeviceError, match="no sound card output 'no such card' was found"):
        AudioActuator("no such card").open()
