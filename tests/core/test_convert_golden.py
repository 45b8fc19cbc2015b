"""`convert` keeps the bytes it wrote before breakpoints were held as arrays (issue 19): a short
synthetic sound converted to .haptic, .ahap, .hjif and .htl, each file's SHA-256 against
tests/golden/convert_bits.json (written by tests/golden/make/convert_bits.py with the commit
named there). The .hjif's date is pinned through SOURCE_DATE_EPOCH (2026-11-26, the day the
golden was written), else the digest would change each day."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np
import pytest
import soundfile

from timeline.files.convert import convert_file

GOLDEN = Path(__file__).resolve().parents[1] / "golden" / "convert_bits.json"
SUFFIXES = (".haptic", ".ahap", ".hjif", ".htl")
RATE = 8_000
WRITTEN_ON = "1795651200"  # 2026-11-26 00:00 UTC, SOURCE_DATE_EPOCH for the .hjif's date


def write_sound(path: Path) -> None:
    """1.5 s of 16-bit mono: tone bursts rising in pitch, a click and noise (emphasis, both
    envelopes moving)."""
    rng = np.random.default_rng(19)
    t = np.arange(int(1.5 * RATE)) / RATE
    bursts = (np.sin(2 * np.pi * 3 * t) > 0.2) * (0.3 + 0.5 * t / t[-1])
    wave = bursts * np.sin(2 * np.pi * (90 + 120 * t) * t) + 0.02 * rng.standard_normal(t.size)
    wave[int(0.9 * RATE) : int(0.905 * RATE)] += 0.8
    soundfile.write(path, np.clip(wave, -1, 1), RATE, subtype="PCM_16")


def convert_digests(folder: Path) -> dict[str, str]:
    """The SHA-256 of each format `convert` writes for the sound."""
    sound = folder / "sound.wav"
    write_sound(sound)
    digests = {}
    for suffix in SUFFIXES:
        out = folder / f"design{suffix}"
        convert_file(sound, out)
        digests[suffix] = hashlib.sha256(out.read_bytes()).hexdigest()
    return digests


def test_converted_files_keep_their_bytes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SOURCE_DATE_EPOCH", WRITTEN_ON)
    assert convert_digests(tmp_path) == json.loads(GOLDEN.read_text())["files"]
