"""Audio files through soundfile/libsndfile: read a recording as a tile, write mixed layers.

Reading keeps the file's samples exactly and its rate; the mixer resamples to the project rate.
Files are read in blocks into one preallocated array that the tile keeps: float32 when every
value is a float32 exactly (16- and 24-bit PCM, float files, a stereo mix of PCM), which
halves an hour's memory and reads back the same float64 values, else float64. Each block is
hashed for the tile's content key as it arrives, integer PCM needs no finiteness scan, and
progress is reported per block.

A project's layers are written one channel each, with the units line of importers/_units.py in
the file's comment (WAV's LIST/INFO ICMT chunk, FLAC's and OGG's Vorbis comment, AIFF's and
CAF's own): read back, each channel goes on a track of its kind at its values (float32 precision
in the default FLOAT subtype; bit for bit with subtype DOUBLE). A file without that comment is a
recording: a unitless shape, and the import says so.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import soundfile as sf

from importers import _units
from importers._sample_store import SampleStore
from timeline.plugins.file_formats import FormatError, Imported, Layers, Progress
from timeline.signal.samples import first_non_finite
from timeline.tiles import MAX_TILE_SAMPLES, SampledTile

BLOCK_FRAMES = 1 << 16
# Written when no subtype is asked for: float where the container holds it (no rounding), else
# 24-bit (FLAC), else the container's own default (OGG: Vorbis).
PREFERRED_SUBTYPES = ("FLOAT", "PCM_24")
# libsndfile notes a chunk whose declared size runs past the end of the file as
# "data : 40000 (should be 19979)"; that is a truncated file.
_SHORT_CHUNK = re.compile(
    r"^\s*(data|SSND|Riff size|RIFF|FORM)\s*:\s*(\d+)\s*\(should be (\d+)\)", re.MULTILINE
)


def _open(path: Path) -> sf.SoundFile:
    try:
        return sf.SoundFile(path)
    except sf.LibsndfileError as exc:
        reason = str(exc.error_string).rstrip(".")
        if "internal error" in reason.lower():  # libsndfile's words for a header it gave up on
            reason = "its header is damaged"
        raise FormatError(f"{path.name} is not an audio file that can be read ({reason})") from None
    except (RuntimeError, TypeError, ValueError) as exc:
        raise FormatError(f"{path.name} is not an audio file that can be read ({exc})") from None


# AIFF: "Frame count read from 'COMM' chunk (N) not equal to frame count calculated from
# length of 'SSND' chunk (M)" -- a header that declares other than what the file holds.
_FRAME_MISMATCH = re.compile(r"Frame count read from .*?\((\d+)\).*?\((\d+)\)", re.DOTALL)


def _aiff_rate(path: Path) -> float | None:
    """An AIFF's COMM sample rate (80-bit extended) as declared, NaN for a NaN or infinity (the
    all-ones exponent), None if no COMM chunk is found."""
    with open(path, "rb") as raw:
        if raw.read(12)[8:12] not in (b"AIFF", b"AIFC"):
            return None
        for _ in range(1000):  # chunks before COMM: a few in any real file
            head = raw.read(8)
            if len(head) < 8:
                return None
            size = int.from_bytes(head[4:], "big")
            if head[:4] == b"COMM":
                field = raw.read(18)[8:18]
                if len(field) < 10:
                    return None
                sign_exponent = int.from_bytes(field[:2], "big")
                exponent = sign_exponent & 0x7FFF
                if exponent == 0x7FFF:
                    return math.nan
                mantissa = int.from_bytes(field[2:], "big")
                try:
                    value = math.ldexp(mantissa, exponent - 16383 - 63)
                except OverflowError:
                    value = math.inf
                return -value if sign_exponent & 0x8000 else value
            raw.seek(size + size % 2, 1)
    return None


def _check_complete(path: Path, f: sf.SoundFile) -> None:
    declared = _aiff_rate(path) if f.format == "AIFF" else None
    if declared is not None and math.isnan(declared):
        # libsndfile reads a NaN or infinite rate as 67,108,864 Hz without a word
        raise FormatError(
            f"{path.name} declares a sample rate that is not a finite number (NaN or infinity)"
        )
    if declared is not None and not (declared >= 1 and abs(declared - f.samplerate) < 1):
        # ... and 0, 1e-3 or a denormal as 1 Hz, one past its range as 67,108,864 Hz
        raise FormatError(
            f"{path.name} declares a sample rate of {declared:.6g} Hz, which would be read as "
            f"{f.samplerate} Hz; it is refused rather than played at the wrong speed"
        )
    for match in _SHORT_CHUNK.finditer(f.extra_info):
        if int(match.group(3)) < int(match.group(2)):
            raise FormatError(
                f"{path.name} is truncated: its header promises more audio than the file holds"
            )
    mismatch = _FRAME_MISMATCH.search(f.extra_info)
    if mismatch and int(mismatch.group(1)) > int(mismatch.group(2)):
        raise FormatError(
            f"{path.name} is damaged or truncated: its header declares {mismatch.group(1)} "
            f"frames but it holds {mismatch.group(2)}"
        )
    if f.frames > MAX_TILE_SAMPLES:
        raise FormatError(
            f"{path.name} declares {f.frames} frames, more than one tile can hold "
            f"({MAX_TILE_SAMPLES})"
        )


def _channel_index(channel: int | str | None, channels: int, name: str) -> int | None:
    """The 0-based channel to keep, or None to mix all channels down (the mean)."""
    if channel is None or channel == "mix":
        return None if channels > 1 else 0
    try:
        number = int(channel)
    except (TypeError, ValueError):
        raise FormatError(f"channel must be a number from 1 or 'mix', not {channel!r}") from None
    if not 1 <= number <= channels:
        raise FormatError(f"{name} has {channels} channel(s); there is no channel {number}")
    return number - 1


def _mean_of_channels(frames: np.ndarray, out: np.ndarray) -> None:
    """np.mean(frames, axis=1), bit for bit, summing whole columns (4-7x faster than a reduction
    along rows of two to six channels)."""
    np.add(frames[:, 0], 0.0, out=out)  # from +0.0, as np.mean sums: a mix of -0.0 is +0.0
    for column in range(1, frames.shape[1]):
        out += frames[:, column]
    out /= frames.shape[1]


def _integer_subtype(subtype: str) -> bool:
    """True for subtypes that hold integers: every sample read from them is finite."""
    return subtype.startswith("PCM_") or subtype in ("ULAW", "ALAW")


class AudioFormat:
    """WAV (all PCM, float, u-law/A-law, extensible, RF64), FLAC, OGG/Vorbis, AIFF, ..."""

    name = "audio"
    extensions = (
        ".wav",
        ".wave",
        ".rf64",
        ".w64",
        ".flac",
        ".ogg",
        ".oga",
        ".aif",
        ".aiff",
        ".aifc",
        ".au",
        ".snd",
        ".caf",
    )
    reads = "tile"
    writes = "layers"
    options = ("channel",)

    def read(
        self,
        path: Path,
        *,
        progress: Progress | None = None,
        channel: int | str | None = None,
        **options: Any,
    ) -> SampledTile | Imported:
        """Read one channel (1-based) or the mean of all channels ("mix", the default) as a tile;
        a file of our layers: each channel (or the one asked for) on a track of its kind."""
        path = Path(path)
        with _open(path) as f:
            _check_complete(path, f)
            units = _units.parse(_comment(f))
            kinds = list(units.kinds) if units is not None else []
            if units is not None and len(kinds) == f.channels:
                return self._read_layers(path, f, units, kinds, channel, progress)
            keep = _channel_index(channel, f.channels, path.name)
            data, key = self._read_blocks(path, f, keep, progress)
            rate = float(f.samplerate)
        suffix = "" if keep is None or f.channels == 1 else f" ch{keep + 1}"
        return SampledTile.from_checked(data, rate, path.stem + suffix, str(path), key)

    def _read_layers(
        self,
        path: Path,
        f: sf.SoundFile,
        units: _units.Units,
        kinds: list[str],
        channel: int | str | None,
        progress: Progress | None,
    ) -> Imported:
        """Our layers: channel i holds the i-th kind of the units line."""
        wanted = range(f.channels) if channel in (None, "mix") else None
        if wanted is None:
            index = _channel_index(channel, f.channels, path.name)
            wanted = range(index, index + 1) if index is not None else range(f.channels)
        columns = []
        for index in wanted:
            f.seek(0)
            data, _ = self._read_blocks(path, f, index, progress)
            columns.append((kinds[index], np.asarray(data, dtype=np.float64)))
        rate = units.rate if units.rate is not None else float(f.samplerate)
        return _units.kind_placements(columns, units, rate, 0.0, path.stem, str(path))

    @staticmethod
    def _read_blocks(
        path: Path, f: sf.SoundFile, keep: int | None, progress: Progress | None
    ) -> tuple[np.ndarray, str]:
        total = f.frames
        if total <= 0:
            raise FormatError(f"{path.name} holds no audio samples")
        # A compressed header (FLAC) may declare far more frames than the file holds: grow the
        # array as audio arrives, starting from what the file's size can plausibly hold.
        store = SampleStore(
            f.subtype,
            f.channels if keep is None else 1,
            min(total, max(BLOCK_FRAMES, 64 * path.stat().st_size)),
            path.name,
        )
        scan = not _integer_subtype(f.subtype)
        done = 0
        # Values known to be float32 exactly are decoded as float32 (a channel kept, or the mean of
        # two integer channels, is then exact in float32 too), and one channel of them straight
        # into the store itself; anything else goes through float64.
        precision = np.float32 if store.exact_float32 else np.float64
        block = np.empty((min(BLOCK_FRAMES, total), f.channels), dtype=precision)
        mono = np.empty(block.shape[0], dtype=precision)
        direct = f.channels == 1 and store.exact_float32
        try:
            while done < total:
                want = min(BLOCK_FRAMES, total - done)
                if direct:
                    part = store.reserve(want, total)
                    n = f.read(out=part.reshape(-1, 1)).shape[0]
                else:
                    n = f.read(out=block[:want]).shape[0]
                    part = mono
                    if keep is None:
                        _mean_of_channels(block[:n], part[:n])
                    else:
                        part[:n] = block[:n, keep]
                if n == 0:
                    break
                bad = first_non_finite(part[:n]) if scan else None
                if bad is not None:
                    raise FormatError(
                        f"{path.name} has a sample that is not a finite number (frame {done + bad})"
                    )
                if direct:
                    store.commit(n)
                else:
                    store.append(part[:n], total)
                done += n
                if progress is not None:
                    progress(done / total)
        except sf.LibsndfileError as exc:
            raise FormatError(
                f"{path.name} could not be read to the end ({exc.error_string})"
            ) from None
        if done < total:
            raise FormatError(f"{path.name} is truncated: it ends after {done} of {total} frames")
        return store.finish(float(f.samplerate))

    def write(self, source: Layers, path: Path, subtype: str | None = None, **options: Any) -> None:
        """Write the layers as channels (in column order) at their rate; float by default."""
        path = Path(path)
        columns = [np.asarray(v, dtype=np.float64) for v in source.columns.values()]
        frames = np.zeros((source.length, len(columns)))
        for i, col in enumerate(columns):
            frames[: len(col), i] = col
        container = _container(path)
        if subtype is None:
            choices = [s for s in PREFERRED_SUBTYPES if sf.check_format(container, s)]
            subtype = choices[0] if choices else sf.default_subtype(container)
        subtype = subtype.upper()
        rate = source.rate
        if source.axis == "position" and (rate != int(rate) or rate < 1):
            raise FormatError(
                f"a position project's rate is {rate:g} samples per radian, and audio files need "
                f"a whole number: export with --rate N/rad (e.g. --rate {max(1, round(rate))}/rad) "
                f"to write N samples per radian"
            )
        if rate != int(rate) or rate < 1:
            raise FormatError(f"audio files need a whole-number rate, not {rate} Hz")
        units = _units.describe(list(source.columns), source.axis, rate)
        try:
            with sf.SoundFile(path, "w", int(rate), len(columns), subtype, format=container) as out:
                if units is not None:
                    out.comment = units
                out.write(frames)
        except (sf.LibsndfileError, ValueError, TypeError) as exc:
            raise FormatError(f"cannot write {container} audio as {subtype} ({exc})") from None


def _comment(f: sf.SoundFile) -> str:
    """The file's comment text ("" when it has none or its format holds none)."""
    try:
        return str(f.comment or "")
    except (sf.LibsndfileError, RuntimeError, AttributeError):
        return ""


def _container(path: Path) -> str:
    ext = path.suffix.lower().lstrip(".")
    return {"wave": "WAV", "aif": "AIFF", "aifc": "AIFF", "oga": "OGG", "snd": "AU"}.get(
        ext, ext.upper()
    )


FORMAT = AudioFormat()
