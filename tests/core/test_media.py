"""Samples in project files: float32 recordings saved as float32, both precisions bit-identical,
inflated into the array the tile keeps, and damaged or lying entries refused in one sentence."""

from __future__ import annotations

import base64
import json
import zlib

import numpy as np
import pytest
import soundfile as sf

from importers import audio
from timeline import edits
from timeline.errors import FieldError, ProjectFileError
from timeline.files import media, projectfile
from timeline.tiles import SampledTile


def _float32(n: int) -> np.ndarray:
    data = (np.random.default_rng(5).integers(-(2**23), 2**23, n) / 2**23).astype(np.float32)
    data.setflags(write=False)
    return data


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("n", [1, 1000, media.BLOCK_SAMPLES + 7])  # one sample to several blocks
def test_samples_come_back_bit_identical_in_their_precision(dtype, n):
    data = np.random.default_rng(n).standard_normal(n).astype(dtype)
    data[0] = -0.0 if n > 1 else np.nextafter(dtype(0), dtype(1))  # signed zero, subnormal
    entry = media.encode(data)
    assert entry["dtype"] == np.dtype(dtype).newbyteorder("<").str
    back = media.decode(entry, "media 'x'")
    assert back.dtype == dtype and not back.flags.writeable and back.base is None
    assert back.tobytes() == data.tobytes()


def test_a_saved_recording_loads_as_the_same_float32_tile(tmp_path):
    wav = tmp_path / "rec.wav"
    sf.write(wav, np.asarray(_float32(20_000), dtype=np.float64), 44_100, subtype="PCM_24")
    tile = audio.FORMAT.read(wav)
    project, tile_id = edits.add_tile(edits.new_project(), tile)
    projectfile.save(project, tmp_path / "p.htl")
    loaded = projectfile.load(tmp_path / "p.htl").tile(tile_id)
    assert loaded.data.dtype == np.float32 and loaded == tile and loaded.key == tile.key
    np.testing.assert_array_equal(loaded.data, tile.data)


def _entry(raw: bytes, count: int, dtype: str = "<f4") -> dict:
    packed = base64.b64encode(zlib.compress(raw)).decode()
    return {"dtype": dtype, "count": count, "encoding": "zlib+base64", "data": packed}


def test_entries_that_hold_other_than_they_declare_are_one_sentence():
    raw = _float32(1000).tobytes()
    cases = [
        (_entry(raw, 1001), "holds 1000 samples but declares 1001"),
        (_entry(raw, 999), "declares 999 samples but holds more"),
        (_entry(raw, 10**9), "declares 1000000000 samples but holds fewer"),  # never allocated
        (_entry(raw, 1000, "<i2"), "unknown sample encoding"),
        ({**_entry(raw, 1000), "data": "not base64!"}, "damaged sample data"),
        (
            {**_entry(raw, 1000), "data": base64.b64encode(zlib.compress(raw)[:-9]).decode()},
            r"holds 99\d samples but declares 1000|damaged sample data",
        ),  # a cut stream
    ]
    for entry, sentence in cases:
        with pytest.raises(FieldError, match=sentence):
            media.decode(entry, "media 'x'")


def test_a_project_with_a_lying_entry_is_refused_and_left_alone(tmp_path):
    path = tmp_path / "p.htl"
    project, _ = edits.add_tile(edits.new_project(), audio_tile(tmp_path))
    projectfile.save(project, path)
    path.write_bytes(path.read_bytes().replace(b'"count": 3000', b'"count": 3001'))
    before = path.read_bytes()
    with pytest.raises(ProjectFileError, match="holds 3000 samples but declares 3001"):
        projectfile.load(path)
    assert path.read_bytes() == before


def audio_tile(tmp_path):
    wav = tmp_path / "short.wav"
    sf.write(wav, np.asarray(_float32(3000), dtype=np.float64), 8000, subtype="PCM_24")
    return audio.FORMAT.read(wav)


def test_a_save_writes_the_json_of_dumps_then_each_recording_once_raw(tmp_path):
    project = edits.new_project(title="=== binary appendix: a title like the separator ===")
    arrays = []
    for n, dtype in ((3001, np.float32), (2500, np.float64), (3001, np.float32)):
        data = np.random.default_rng(n).standard_normal(n).astype(dtype)
        data.setflags(write=False)
        arrays.append(data)
        project, _ = edits.add_tile(project, SampledTile(data, 1000.0, f"r{n}"))
    path = tmp_path / "p.htl"
    projectfile.save(project, path)
    saved = path.read_bytes()
    text, appendix = saved.split(b"\n" + media.SEPARATOR)
    assert appendix == arrays[0].tobytes() + arrays[1].tobytes()  # the third shares the first's
    doc, dumped = json.loads(text), json.loads(projectfile.dumps(project))
    assert doc["appendix"] == {"bytes": len(appendix)}
    assert [e["encoding"] for e in doc["media"].values()] == ["appendix", "appendix"]
    assert [e["encoding"] for e in dumped["media"].values()] == ["zlib+base64"] * 2
    assert {k: v for k, v in doc.items() if k not in ("media", "appendix")} == {
        k: v for k, v in dumped.items() if k != "media"
    }
    loaded = projectfile.load(path)
    for tile_id, tile in project.tiles.items():
        assert loaded.tile(tile_id) == tile
        if isinstance(tile, SampledTile):
            assert loaded.tile(tile_id).data.tobytes() == tile.data.tobytes()
    assert projectfile.loads(saved) == loaded == projectfile.loads(projectfile.dumps(project))
