"""Files of a chosen size for the readers benchmark: one writer per reader and kind of content,
and inputs just over a reader's documented limit (sparse where the limit is a size)."""

from __future__ import annotations

import json
import shutil
import struct
import zipfile
from collections.abc import Callable
from pathlib import Path

import numpy as np

from timeline.bench.ahap_reader import long_curve, overlapping_events

RATE = 10_000.0


def _values(n: int) -> np.ndarray:
    return np.random.default_rng(25).uniform(-1.0, 1.0, n)


def size(path: Path) -> int:
    """Bytes of a file, or of a file and the folder of media written beside it."""
    media = _media_folder(path)
    extra = sum(f.stat().st_size for f in media.rglob("*") if f.is_file()) if media else 0
    return path.stat().st_size + extra


def remove(path: Path) -> None:
    """Delete a file and any media written beside it."""
    media = _media_folder(path)
    if media:
        shutil.rmtree(media)
    path.unlink(missing_ok=True)


def _media_folder(path: Path) -> Path | None:
    folder = path.with_name(path.stem + "_media")
    return folder if folder.is_dir() else None


def ahap_overlapping(path: Path, n: int) -> None:
    """n continuous events of 1-29 s with attack and release, all starting within a minute."""
    path.write_text(json.dumps(overlapping_events(n)))


def ahap_curve(path: Path, n: int) -> None:
    """One 30 s continuous event under one intensity curve of n control points."""
    path.write_text(json.dumps(long_curve(n)))


def ahap_transients(path: Path, n: int) -> None:
    """n transients 10 ms apart."""
    pattern = [
        {"Event": {"Time": i / 100, "EventType": "HapticTransient", "EventParameters": [
            {"ParameterID": "HapticIntensity", "ParameterValue": 0.5 + (i % 7) / 14}]}}
        for i in range(n)
    ]  # fmt: skip
    path.write_text(json.dumps({"Version": 1.0, "Pattern": pattern}))


def haptic_emphasis(path: Path, n: int) -> None:
    """n amplitude breakpoints 1 ms apart, each with an emphasis of its own (issue 25's kind)."""
    levels = np.round(np.random.default_rng(25).uniform(0.0, 1.0, (n, 3)), 6).tolist()
    amplitude = [
        {"time": i / 1000, "amplitude": a, "emphasis": {"amplitude": e, "frequency": f}}
        for i, (a, e, f) in enumerate(levels)
    ]
    doc = {"version": {"major": 1, "minor": 0, "patch": 0},
           "signals": {"continuous": {"envelopes": {"amplitude": amplitude}}}}  # fmt: skip
    path.write_text(json.dumps(doc))


def csv_column(path: Path, n: int) -> None:
    """n values of one column at a rate given in a comment."""
    path.write_text("# rate=10000\n" + "\n".join(f"{v:.17g}" for v in _values(n)) + "\n")


def csv_timed(path: Path, n: int) -> None:
    """A header, a time column and two value columns."""
    table = np.column_stack([np.arange(n) / RATE, _values(n), _values(n)[::-1]])
    np.savetxt(path, table, delimiter=",", header="time,drive,stiffness", comments="", fmt="%.17g")


def mat_v5(path: Path, n: int) -> None:
    """One variable of n samples and its rate (Matlab v5, through scipy)."""
    import scipy.io

    scipy.io.savemat(path, {"drive": _values(n), "fs": RATE}, oned_as="column")


def mat_v73(path: Path, n: int) -> None:
    """The same in Matlab v7.3's layout: HDF5 behind a 512-byte header."""
    import h5py

    with h5py.File(path, "w", userblock_size=512) as h5:
        for name, data in (("drive", _values(n).reshape(1, -1)), ("fs", np.array([[RATE]]))):
            dataset = h5.create_dataset(name, data=data)
            dataset.attrs["MATLAB_class"] = np.bytes_("double")
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Thu Nov 26 10:00:00 2026 "
    with path.open("r+b") as f:
        f.write((header + b"HDF5 schema 1.00 .").ljust(124, b" ") + b"\x00\x02IM")


def mat_octave_text(path: Path, n: int) -> None:
    """The same in Octave's default text format."""
    values = "\n".join(f"{v:.17g}" for v in _values(n))
    path.write_text(
        "# Created by Octave 8.4.0\n# name: fs\n# type: scalar\n10000\n\n\n"
        f"# name: drive\n# type: matrix\n# rows: {n}\n# columns: 1\n{values}\n"
    )


def npz(path: Path, n: int) -> None:
    """The same as NumPy's .npz."""
    with path.open("wb") as f:
        np.savez(f, drive=_values(n), fs=RATE)


def sound(container: str, subtype: str) -> Callable[[Path, int], None]:
    """A writer of n frames of noise at 10 kHz in a libsndfile container and subtype."""

    def write(path: Path, n: int) -> None:
        import soundfile

        soundfile.write(path, 0.5 * _values(n), int(RATE), subtype=subtype, format=container)

    return write


def _project(n: int):
    from timeline import edits
    from timeline.tiles import generator

    project, track = edits.add_track(edits.new_project(templates=False), "drive")
    tiles = [generator("sine", 0.05, frequency=f) for f in (80.0, 120.0, 170.0)]
    return edits.add_clips(project, [(track, tiles[i % 3], 0.04 * i, {}) for i in range(n)])[0]


def otio_clips(path: Path, n: int) -> None:
    """Our project of n generator clips exported as .otio (media beside it) or .otioz."""
    from timeline.files import exporting

    exporting.export_project(_project(n), path)


def htl_clips(path: Path, n: int) -> None:
    """A project file of n generator clips."""
    from timeline.files import projectfile

    projectfile.save(_project(n), path)


def htl_samples(path: Path, n: int) -> None:
    """A project file holding one sampled tile of n samples, placed once."""
    from timeline import edits
    from timeline.files import projectfile
    from timeline.tiles import SampledTile

    project, track = edits.add_track(edits.new_project(templates=False), "drive")
    project, _ = edits.add_clips(project, [(track, SampledTile(_values(n), RATE), 0.0, {})])
    projectfile.save(project, path)


def hjif_keyframes(path: Path, n: int) -> None:
    """One vectorial effect of n keyframes 1 ms apart (timescale 1000)."""
    keyframes = [
        {"relative_position": i, "amplitude_modulation": 0.5 + (i % 9) / 20,
         "frequency_modulation": 150 + i % 50}
        for i in range(n)
    ]  # fmt: skip
    effect = {"effect_type": "Basis", "position": 0, "phase": 0.0, "base_signal": "Sine",
              "keyframes": keyframes}  # fmt: skip
    band = {"band_type": "VectorialWave", "curve_type": "Unknown", "block_length": 0.0,
            "lower_frequency_limit": 65, "upper_frequency_limit": 300,
            "effects": [effect]}  # fmt: skip
    channel = {"id": 0, "description": "", "gain": 1.0, "mixing_weight": 1.0,
               "body_part_mask": 0, "bands": [band]}  # fmt: skip
    perception = {"id": 0, "avatar_id": 0, "description": "", "perception_modality":
                  "Vibrotactile", "unit_exponent": -3, "perception_unit_exponent": 0,
                  "reference_devices": [], "effect_library": [], "channels": [channel]}  # fmt: skip
    doc = {"version": "1", "profile": "Main", "level": 1, "date": "", "description": "",
           "timescale": 1000, "avatars": [], "perceptions": [perception], "syncs": []}  # fmt: skip
    path.write_text(json.dumps(doc))


def sparse(nbytes: int) -> Callable[[Path], None]:
    """A writer of a file of nbytes zero bytes that takes no disk (a hole)."""

    def write(path: Path) -> None:
        with path.open("wb") as f:
            f.truncate(nbytes)

    return write


def huge_wav(path: Path) -> None:
    """An 8-bit mono WAV of 2^31 + 1 frames, all of them a hole in a sparse file."""
    frames = 2**31 + 1
    header = b"RIFF" + struct.pack("<I", 0xFFFFFFFF) + b"WAVE"
    header += b"fmt " + struct.pack("<IHHIIHH", 16, 1, 1, 8000, 8000, 1, 8)
    header += b"data" + struct.pack("<I", frames)
    with path.open("wb") as f:
        f.write(header)
        f.truncate(len(header) + frames)


def lying_flac(path: Path) -> None:
    """A short FLAC whose STREAMINFO declares 2^35 frames."""
    sound("FLAC", "PCM_16")(path, 1000)
    raw = bytearray(path.read_bytes())
    info = 8  # "fLaC" and the STREAMINFO block's header; total samples are its bits 108-143
    packed = int.from_bytes(raw[info + 13 : info + 18], "big")
    packed = (packed & ~((1 << 36) - 1)) | (2**35)
    raw[info + 13 : info + 18] = packed.to_bytes(5, "big")
    path.write_bytes(bytes(raw))


def lying_mat(path: Path) -> None:
    """A Matlab v5 file whose one array declares 2^31 - 1 x 2^31 - 1 doubles."""
    import scipy.io

    scipy.io.savemat(path, {"drive": _values(8)}, oned_as="column")
    raw = bytearray(path.read_bytes())
    raw[160:168] = struct.pack("<ii", 2**31 - 1, 2**31 - 1)  # the dimensions sub-element
    path.write_bytes(bytes(raw))


def otioz_bomb(path: Path) -> None:
    """An .otioz naming two media whose zip entries declare 3.75 GiB each (holding 4 bytes)."""
    import opentimelineio as otio

    timeline = otio.schema.Timeline("bomb")
    track = otio.schema.Track("t")
    second = otio.opentime.RationalTime(24, 24)
    for name in ("a", "b"):
        reference = otio.schema.ExternalReference(f"media/{name}.wav")
        span = otio.opentime.TimeRange(otio.opentime.RationalTime(0, 24), second)
        track.append(otio.schema.Clip(name, reference, span))
    timeline.tracks.append(track)
    with zipfile.ZipFile(path, "w") as bundle:
        bundle.writestr("version.txt", "1.0.0")
        bundle.writestr("content.otio", otio.adapters.write_to_string(timeline, "otio_json"))
        bundle.writestr("media/a.wav", b"RIFF")
        bundle.writestr("media/b.wav", b"RIFF")
    raw = bytearray(path.read_bytes())
    at = raw.find(b"PK\x01\x02")
    while at >= 0:  # each central directory entry: its uncompressed size at +24
        name_length = struct.unpack_from("<H", raw, at + 28)[0]
        if raw[at + 46 : at + 46 + name_length].startswith(b"media/"):
            struct.pack_into("<I", raw, at + 24, 0xF0000000)
        at = raw.find(b"PK\x01\x02", at + 46)
    path.write_bytes(bytes(raw))
