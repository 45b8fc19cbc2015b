"""The hostile files of tests/reliability/hostile_attack.py, made by code: (category, name, bytes).

JSON formats (AHAP, .haptic, .hjif, OTIO, .htl): each leaf of a small valid document in turn
given each hostile value (a seeded sample of at most PER_FORMAT), then structural attacks (deep
nesting, duplicate keys, BOMs, UTF-16, a top level that is not an object). CSV: rate headers,
values, encodings and shapes. Audio: WAV, AIFF and FLAC headers that lie. .mat: v5 dimensions
and rates, v7.3 truncated or mislabelled. .otioz: bombs, paths outside the bundle.
"""

from __future__ import annotations

import io
import json
import random
import struct
import zipfile
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from timeline import edits, generator, spline
from timeline.files import exporting, projectfile

TOKENS = ("NaN", "Infinity", "-Infinity", "-0.0", "1e308", "5e-324", "1e999", "1" * 400, "-1",
          "0", '"text"', '"1e400"', '"false"', "null", "[1]", '{"a": 1}', "true",
          '"\\ud800"')  # fmt: skip
PER_FORMAT = 120
SOUNDS = (".wav", ".aiff", ".flac")
Item = tuple[str, str, bytes]


def is_sound(path: Path) -> bool:
    return path.suffix.lower() in SOUNDS


def _design_project():
    project = edits.new_project(rate=1000.0, templates=False)
    project, track = edits.add_track(project, "drive", "d")
    project, stiff = edits.add_track(project, "stiffness", "k")
    tiles = [
        generator("chirp", 0.3, f0=5.0, f1=80.0, exponential=1.0),
        generator("detents", 0.3, count=4),
        generator("noise", 0.2, bandwidth=100.0),
        generator("adsr", 0.3),
        generator("am", 0.2),
        spline([(0.0, 0.0), (0.1, 0.8), (0.2, 0.0)]),
    ]
    for i, tile in enumerate(tiles):
        project, tile_id = edits.add_tile(project, tile)
        project, clip = edits.add_clip(project, track if i % 2 else stiff, tile_id, 0.1 * i)
    project = edits.set_clip(project, clip, gain=0.5)
    return project


def good_project(path: Path) -> None:
    """The project every import goes into: a sine clip on a drive track at 1 kHz."""
    project = edits.new_project(rate=1000.0, templates=False)
    project, track = edits.add_track(project, "drive")
    project, tile = edits.add_tile(project, generator("sine", 0.5, frequency=5))
    project, _ = edits.add_clip(project, track, tile, start=0.0)
    projectfile.save(project, path)


def _leaves(doc, path=()) -> Iterator[tuple]:
    if isinstance(doc, dict):
        for key, value in doc.items():
            yield from _leaves(value, (*path, key))
    elif isinstance(doc, list):
        for i, value in enumerate(doc):
            yield from _leaves(value, (*path, i))
    else:
        yield path


def _with(doc, path: tuple, token: str) -> bytes:
    copy = json.loads(json.dumps(doc))
    place = copy
    for key in path[:-1]:
        place = place[key]
    place[path[-1]] = "@@HOSTILE@@"
    return json.dumps(copy).replace('"@@HOSTILE@@"', token).encode("utf-8", "surrogatepass")


def json_leaves(category: str, ext: str, doc, keep=lambda path: True) -> Iterator[Item]:
    """Each leaf of doc given each hostile token, a seeded sample of PER_FORMAT."""
    cases = [(p, t) for p in _leaves(doc) if keep(p) for t in TOKENS]
    random.Random(category).shuffle(cases)
    for i, (path, token) in enumerate(cases[:PER_FORMAT]):
        yield category, f"leaf{i}{ext}", _with(doc, path, token)


def json_structure(ext: str, doc) -> Iterator[Item]:
    """Shapes every JSON reader must refuse or read plainly."""
    text = json.dumps(doc)
    yield "json-structure", f"deep{ext}", b"[" * 200_000 + b"]" * 200_000
    yield "json-structure", f"deepobj{ext}", b'{"a":' * 100_000 + b"1" + b"}" * 100_000
    yield "json-structure", f"bom{ext}", b"\xef\xbb\xbf" + text.encode()
    yield "json-structure", f"utf16{ext}", text.encode("utf-16")
    yield "json-structure", f"utf32{ext}", text.encode("utf-32")
    yield "json-structure", f"latin1{ext}", text.replace('"', '"\xe9', 1).encode("latin-1")
    yield "json-structure", f"surrogate-bytes{ext}", text.encode()[:-1] + b'"\xed\xa0\x80"}'
    for top in (b"[]", b"1", b'"x"', b"null", b"{}", b"[" + text.encode() + b"]"):
        yield "json-structure", f"top{ext}", top
    first = next(iter(doc))
    duplicate = text[:-1] + f', "{first}": null' + "}"
    yield "json-structure", f"dupkey{ext}", duplicate.encode()
    yield "json-structure", f"trailing{ext}", text.encode() + b" garbage"


def _ahap() -> dict:
    return {"Version": 1.0, "Metadata": {"Project": "x"}, "Pattern": [
        {"Event": {"Time": 0.0, "EventType": "HapticTransient", "EventParameters": [
            {"ParameterID": "HapticIntensity", "ParameterValue": 0.8},
            {"ParameterID": "HapticSharpness", "ParameterValue": 0.4}]}},
        {"Event": {"Time": 0.1, "EventType": "HapticContinuous", "EventDuration": 0.5,
                   "EventParameters": [
            {"ParameterID": "HapticIntensity", "ParameterValue": 0.6},
            {"ParameterID": "AttackTime", "ParameterValue": 0.1},
            {"ParameterID": "ReleaseTime", "ParameterValue": 0.1},
            {"ParameterID": "Sustained", "ParameterValue": 1}]}},
        {"ParameterCurve": {"ParameterID": "HapticIntensityControl", "Time": 0.1,
                            "ParameterCurveControlPoints": [
            {"Time": 0.0, "ParameterValue": 1.0}, {"Time": 0.3, "ParameterValue": 0.2}]}},
        {"Parameter": {"ParameterID": "HapticSharpnessControl", "Time": 0.2,
                       "ParameterValue": 0.3}}]}  # fmt: skip


def _haptic() -> dict:
    return {"version": {"major": 1, "minor": 0, "patch": 0}, "metadata": {"editor": "x"},
            "signals": {"continuous": {"envelopes": {
                "amplitude": [{"time": 0.0, "amplitude": 0.2},
                              {"time": 0.1, "amplitude": 0.9,
                               "emphasis": {"amplitude": 1.0, "frequency": 0.7}},
                              {"time": 0.4, "amplitude": 0.0}],
                "frequency": [{"time": 0.0, "frequency": 0.3},
                              {"time": 0.4, "frequency": 0.8}]}}}}  # fmt: skip


def _hjif() -> dict:
    def band(kind: str, keyframes: list[dict]) -> dict:
        return {"band_type": kind, "curve_type": "Linear", "window_length": 0,
                "lower_frequency_limit": 65, "upper_frequency_limit": 300, "effects": [
                    {"id": 0, "effect_type": "Basis", "position": 10, "phase": 0.0,
                     "base_signal": "Sine", "keyframes": keyframes}]}  # fmt: skip

    vibration = [band("VectorialWave", [
        {"relative_position": 0, "amplitude_modulation": 0.5, "frequency_modulation": 120},
        {"relative_position": 200, "amplitude_modulation": 0.9, "frequency_modulation": 180}]),
        band("Transient", [{"relative_position": 50, "amplitude_modulation": 1.0,
                            "frequency_modulation": 200}])]  # fmt: skip
    force = [
        band(
            "Curve",
            [
                {"relative_position": 0, "amplitude_modulation": 0.2},
                {"relative_position": 300, "amplitude_modulation": -0.4},
            ],
        )
    ]
    perceptions = [
        {"id": i, "avatar_id": 0, "description": "", "perception_modality": modality,
         "unit_exponent": -3, "perception_unit_exponent": 0, "reference_devices": [],
         "effect_library": [], "channels": [
            {"id": 0, "description": "", "gain": 1.0, "mixing_weight": 1.0,
             "body_part_mask": 0, "bands": bands}]}
        for i, (modality, bands) in enumerate((("Vibrotactile", vibration), ("Force", force)))
    ]  # fmt: skip
    return {"version": "2023", "profile": "Main", "level": 1, "date": "2026-11-26",
            "description": "x", "timescale": 1000, "avatars": [], "syncs": [],
            "perceptions": perceptions}  # fmt: skip


def _otio(folder: Path) -> dict:
    path = folder / "design.otio"
    exporting.export_project(_design_project(), path)
    return json.loads(path.read_text())


def _ours(path: tuple) -> bool:
    """OTIO leaves we read: our metadata, the clips' and gaps' ranges, enabled flags."""
    return "haptic_timeline" in path or "source_range" in path or path[-1] == "enabled"


def _htl(folder: Path) -> dict:
    path = folder / "design.htl"
    projectfile.save(_design_project(), path)
    return json.loads(path.read_text())


def json_formats(folder: Path) -> Iterator[Item]:
    yield from json_leaves("ahap leaves", ".ahap", _ahap())
    yield from json_leaves("haptic leaves", ".haptic", _haptic())
    yield from json_leaves("hjif leaves", ".hjif", _hjif())
    yield from json_leaves("otio leaves", ".otio", _otio(folder), _ours)
    yield from json_leaves("htl leaves", ".htl", _htl(folder))
    for ext, doc in ((".ahap", _ahap()), (".haptic", _haptic()), (".hjif", _hjif()),
                     (".otio", _otio(folder)), (".htl", _htl(folder))):  # fmt: skip
        yield from json_structure(ext, doc)


def csv_files() -> Iterator[Item]:
    numbers = ("nan", "NaN", "inf", "-inf", "-0", "1e308", "5e-324", "1e999", "1" * 400, "0x10",
               "1_000", "١", "1e-300", "text", "")  # fmt: skip
    for i, rate in enumerate(numbers + ("0", "-1", "1e9", "1e12", "0.001", "1e-4")):
        for j, mark in enumerate(("#", "%", "//")):
            yield "csv", f"rate{i}-{j}.csv", f"{mark} rate={rate}\n0.5\n-0.5\n".encode()
    for i, value in enumerate(numbers):
        yield "csv", f"value{i}.csv", f"# rate=100\n0.5\n{value}\n0.25\n".encode()
        yield "csv", f"time{i}.csv", f"time,drive\n0,0.5\n{value},0.1\n0.2,0.3\n".encode()
        yield "csv", f"col{i}.csv", f"time,{value}\n0,0.5\n0.1,0.1\n".encode()
    texts = {
        "bom.csv": "\ufefftime,drive\n0,1\n0.1,0\n".encode(),
        "utf16.csv": "time,drive\n0,1\n0.1,0\n".encode("utf-16"),
        "surrogate.csv": b"time,\xed\xa0\x80\n0,1\n0.1,0\n",
        "latin1.csv": "time,d\xe9\n0,1\n0.1,0\n".encode("latin-1"),
        "semicolons.csv": b"time;drive\n0;1\n0.1;0\n",
        "decimal-comma.csv": b"time;drive\n0;1,5\n0,1;0\n",
        "ragged.csv": b"time,drive\n0,1,2\n0.1\n",
        "repeated-times.csv": b"time,drive\n0,1\n0,2\n0,3\n",
        "backwards.csv": b"time,drive\n0.2,1\n0.1,2\n0,3\n",
        "huge-times.csv": b"time,drive\n0,1\n1e308,2\n",
        "tiny-steps.csv": b"time,drive\n0,1\n5e-324,2\n1e-323,3\n",
        "one-row.csv": b"time,drive\n0,1\n",
        "header-only.csv": b"time,drive\n",
        "only-comments.csv": b"# rate=10\n# x\n",
        "many-columns.csv": (
            ",".join(f"c{i}" for i in range(5000))
            + "\n"
            + ",".join("1" for _ in range(5000))
            + "\n"
        ).encode(),
        "cr-only.csv": b"time,drive\r0,1\r0.1,0\r",
        "nul.csv": b"time,drive\n0,1\x00\n",
        "long-line.csv": b"# rate=10\n" + b"1" * 5_000_000 + b"\n",
        "duplicate-names.csv": b"drive,drive\n1,2\n3,4\n",
        "rate-twice.csv": b"# rate=10\n# rate=1e-300\n1\n2\n",
    }
    for name, data in texts.items():
        yield "csv", name, data


def _wav(rate=1000, channels=1, bits=16, fmt_tag=1, data_size=None, frames=100) -> bytes:
    block = channels * bits // 8
    body = np.zeros(frames * max(block, 1), np.uint8).tobytes()
    size = len(body) if data_size is None else data_size
    byte_rate = min(rate * max(block, 1), 0xFFFFFFFF)
    fmt = struct.pack("<HHIIHH", fmt_tag, channels, rate, byte_rate, block & 0xFFFF, bits)
    return (b"RIFF" + struct.pack("<I", 36 + len(body)) + b"WAVE" + b"fmt "
            + struct.pack("<I", 16) + fmt + b"data" + struct.pack("<I", size) + body)  # fmt: skip


def wav_files() -> Iterator[Item]:
    cases = {
        "data-bigger": {"data_size": 10_000_000},
        "data-ffffffff": {"data_size": 0xFFFFFFFF},
        "data-zero": {"data_size": 0},
        "data-odd": {"data_size": 33},
        "rate-zero": {"rate": 0},
        "rate-max": {"rate": 0xFFFFFFFF},
        "rate-one": {"rate": 1},
        "channels-zero": {"channels": 0},
        "channels-max": {"channels": 65535, "frames": 1},
        "bits-zero": {"bits": 0},
        "bits-7": {"bits": 7},
        "bits-64-pcm": {"bits": 64},
        "float-16": {"fmt_tag": 3, "bits": 16},
        "tag-unknown": {"fmt_tag": 0x1234},
        "one-frame": {"frames": 1},
        "no-frames": {"frames": 0},
    }
    for name, kwargs in cases.items():
        yield "wav headers", f"{name}.wav", _wav(**kwargs)
    whole = _wav(bits=32, fmt_tag=3, frames=50)
    nan = whole[:44] + struct.pack("<f", float("nan")) * 50
    yield "wav headers", "float-nan.wav", nan
    yield "wav headers", "float-inf.wav", whole[:44] + struct.pack("<f", float("inf")) * 50
    yield "wav headers", "float-huge.wav", whole[:44] + struct.pack("<f", 3e38) * 50
    for cut in (12, 20, 40, 44, 45, 60):
        yield "wav headers", f"cut{cut}.wav", _wav()[:cut]


def _extended(value: float | None, raw: bytes | None = None) -> bytes:
    """An 80-bit IEEE extended number (AIFF's sample rate)."""
    if raw is not None:
        return raw
    assert value is not None
    if value == 0:
        return b"\x00" * 10
    mantissa, exponent = np.frexp(value)
    return struct.pack(">HQ", int(exponent) - 1 + 16383, int(mantissa * 2**64))


def _aiff(rate: bytes, frames_declared: int = 100, frames: int = 100, channels: int = 1,
          bits: int = 16) -> bytes:  # fmt: skip
    comm = struct.pack(">hIh", channels, frames_declared, bits) + rate
    sound = struct.pack(">II", 0, 0) + b"\x00" * (frames * channels * max(bits, 8) // 8)
    chunks = b"COMM" + struct.pack(">I", len(comm)) + comm
    chunks += b"SSND" + struct.pack(">I", len(sound)) + sound
    return b"FORM" + struct.pack(">I", 4 + len(chunks)) + b"AIFF" + chunks


def aiff_files() -> Iterator[Item]:
    rates = {
        "rate-1000": _extended(1000.0),
        "rate-zero": _extended(0.0),
        "rate-denormal": b"\x00\x00" + b"\x00\x00\x00\x00\x00\x00\x00\x01",
        "rate-huge": b"\x7f\xfe\xff\xff\xff\xff\xff\xff\xff\xff",
        "rate-nan": b"\x7f\xff\xc0\x00\x00\x00\x00\x00\x00\x00",
        "rate-inf": b"\x7f\xff\x80\x00\x00\x00\x00\x00\x00\x00",
        "rate-negative": b"\xc0\x08\xfa\x00\x00\x00\x00\x00\x00\x00",
        "rate-tiny": _extended(1e-3),
        "rate-1e9": _extended(1e9),
    }
    for name, rate in rates.items():
        yield "aiff headers", f"{name}.aiff", _aiff(rate)
    one = _extended(1000.0)
    yield "aiff headers", "frames-lie.aiff", _aiff(one, frames_declared=1_000_000)
    yield "aiff headers", "frames-max.aiff", _aiff(one, frames_declared=0xFFFFFFFF)
    yield "aiff headers", "frames-zero.aiff", _aiff(one, frames_declared=0)
    yield "aiff headers", "channels-zero.aiff", _aiff(one, channels=0)
    yield "aiff headers", "channels-negative.aiff", _aiff(one, channels=-1)
    yield "aiff headers", "bits-zero.aiff", _aiff(one, bits=0)
    yield "aiff headers", "bits-40.aiff", _aiff(one, bits=40)
    for cut in (12, 30, 40, 60):
        yield "aiff headers", f"cut{cut}.aiff", _aiff(one)[:cut]


def flac_files() -> Iterator[Item]:
    import soundfile

    buffer = io.BytesIO()
    soundfile.write(buffer, np.sin(np.arange(2000) / 10) * 0.5, 1000, format="FLAC")
    good = buffer.getvalue()

    def patched(bit: int, width: int, value: int) -> bytes:
        raw = bytearray(good)
        start = 8  # STREAMINFO's 34 bytes
        packed = int.from_bytes(raw[start : start + 34], "big")
        shift = 34 * 8 - bit - width
        packed = (packed & ~(((1 << width) - 1) << shift)) | (value << shift)
        raw[start : start + 34] = packed.to_bytes(34, "big")
        return bytes(raw)

    fields = {"rate": (80, 20), "channels": (100, 3), "bits": (103, 5), "frames": (108, 36),
              "min-block": (0, 16), "max-block": (16, 16)}  # fmt: skip
    for name, (bit, width) in fields.items():
        for value in (0, 1, (1 << width) - 1):
            yield "flac headers", f"{name}-{value}.flac", patched(bit, width, value)
    for cut in (4, 42, 100, len(good) // 2, len(good) - 3):
        yield "flac headers", f"cut{cut}.flac", good[:cut]
    flipped = bytearray(good)
    flipped[len(good) // 2] ^= 0xFF
    yield "flac headers", "flipped.flac", bytes(flipped)


def mat_files() -> Iterator[Item]:
    import h5py
    import scipy.io

    def v5(variables: dict) -> bytes:
        buffer = io.BytesIO()
        scipy.io.savemat(buffer, variables, oned_as="column")
        return buffer.getvalue()

    values = np.array([0.5, -0.5, 0.25])
    rates = {"nan": np.nan, "inf": np.inf, "zero": 0.0, "negative": -1.0, "tiny": 1e-300,
             "huge": 1e308, "denormal": 5e-324, "int64max": np.int64(2**63 - 1),
             "text": "1000", "matrix": np.ones((2, 2)), "empty": np.zeros(0),
             "bool": True, "complex": 1000 + 1j}  # fmt: skip
    for name, rate in rates.items():
        yield "mat", f"fs-{name}.mat", v5({"drive": values, "fs": rate})
        if isinstance(rate, float | np.integer):
            time = np.array([0.0, rate, 2.0])
            yield "mat", f"time-{name}.mat", v5({"drive": values, "time": time})
    for name, data in {"nan": [np.nan, 1.0], "inf": [np.inf, 0.0], "int8": np.int8([1, -128]),
                       "uint64": np.uint64([2**64 - 1, 0]), "complex": [1j, 2j],
                       "3d": np.ones((2, 2, 2)), "empty": np.zeros((0, 1)),
                       "text": "abc", "cell": np.array([[1.0]], dtype=object)}.items():  # fmt: skip
        yield "mat", f"data-{name}.mat", v5({"drive": np.asarray(data), "fs": 100.0})
    good = v5({"drive": values, "fs": 100.0})
    for name, dims in {"zero": (0, 0), "negative": (-1, 1), "huge": (2**31 - 1, 1),
                       "lie": (100, 1)}.items():  # fmt: skip
        raw = bytearray(good)
        raw[160:168] = struct.pack("<ii", *dims)
        yield "mat", f"dims-{name}.mat", bytes(raw)
    for cut in (100, 128, 150, len(good) - 5):
        yield "mat", f"cut{cut}.mat", good[:cut]
    buffer = io.BytesIO()
    with h5py.File(buffer, "w", userblock_size=512) as h5:
        for name, data in (("drive", values.reshape(1, -1)), ("fs", np.array([[np.nan]]))):
            dataset = h5.create_dataset(name, data=data)
            dataset.attrs["MATLAB_class"] = np.bytes_("double")
        lie = h5.create_dataset("label", data=np.ones((1, 3)))
        lie.attrs["MATLAB_class"] = np.bytes_("char")
    head = b"MATLAB 7.3 MAT-file".ljust(124, b" ") + b"\x00\x02IM"
    v73 = head + buffer.getvalue()[128:]
    yield "mat", "v73-fs-nan.mat", v73
    for cut in (520, 1000, len(v73) // 2):
        yield "mat", f"v73-cut{cut}.mat", v73[:cut]
    yield "mat", "v73-empty.mat", head + b"\x00" * 400


def otioz_files(folder: Path) -> Iterator[Item]:
    import opentimelineio as otio

    def bundle(content: bytes, media: dict[str, bytes], deflate: bool = True) -> bytes:
        buffer = io.BytesIO()
        compression = zipfile.ZIP_DEFLATED if deflate else zipfile.ZIP_STORED
        with zipfile.ZipFile(buffer, "w", compression) as z:
            z.writestr("version.txt", "1.0.0")
            z.writestr("content.otio", content)
            for name, data in media.items():
                z.writestr(name, data)
        return buffer.getvalue()

    def timeline(url: str) -> bytes:
        span = otio.opentime.TimeRange(
            otio.opentime.RationalTime(0, 24), otio.opentime.RationalTime(12, 24)
        )
        clip = otio.schema.Clip("a", otio.schema.ExternalReference(url), span)
        line = otio.schema.Timeline("t")
        line.tracks.append(otio.schema.Track("v", children=[clip]))
        return otio.adapters.write_to_string(line, "otio_json").encode()

    wav = _wav()
    for url in ("media/../../escape.wav", "/etc/passwd", "media/a.wav", "file:///etc/hosts",
                "media/%2e%2e/x.wav", "media/nul\x00.wav", "media/" + "a" * 300 + ".wav",
                "http://example.com/x.wav", "media/", ""):  # fmt: skip
        yield (
            "otioz",
            "url.otioz",
            bundle(timeline(url), {"media/a.wav": wav, "media/../../escape.wav": wav}),
        )
    yield "otioz", "content-bomb.otioz", bundle(b" " * 300_000_000 + timeline("media/a.wav"), {})
    yield "otioz", "no-content.otioz", bundle(b"", {})
    yield "otioz", "not-zip.otioz", b"PK\x03\x04" + b"\x00" * 100
    yield "otioz", "media-not-wav.otioz", bundle(timeline("media/a.wav"), {"media/a.wav": b"x"})
    path = folder / "ours.otioz"
    exporting.export_project(_design_project(), path)
    ours = path.read_bytes()
    yield "otioz", "ours.otioz", ours
    yield "otioz", "ours-cut.otioz", ours[: len(ours) // 2]


def option_runs() -> Iterator[tuple[str, str, bytes, list[str]]]:
    """A good CSV imported with each hostile option value (extra import arguments)."""
    data = b"time,drive\n0,0.5\n0.1,-0.5\n0.2,0.25\n"
    for option in ("--rate", "--gain", "--at", "--length", "--column", "--channel"):
        for value in ("nan", "inf", "-inf", "-0", "1e308", "5e-324", "1e999", "1" * 400, "-1",
                      "0", "text", "", "\udcff"):  # fmt: skip
            yield "import options", "opt.csv", data, [f"{option}={value}"]


def everything(folder: Path) -> Iterator[tuple[str, str, bytes, list[str]]]:
    for items in (json_formats(folder), csv_files(), wav_files(), aiff_files(), flac_files(),
                  mat_files(), otioz_files(folder)):  # fmt: skip
        for category, name, data in items:
            yield category, name, data, []
    yield from option_runs()
