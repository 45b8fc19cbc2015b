"""The binary appendix of a saved project: raw samples round trip bit for bit with their hash,
and a truncated, damaged or lying appendix is one sentence that leaves the file as it was."""

from __future__ import annotations

import io
import json
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from timeline import edits
from timeline.errors import FieldError, ProjectFileError
from timeline.files import media, projectfile
from timeline.signal.samples import content_key
from timeline.tiles import SampledTile


def _recording(n: int, dtype: type, seed: int = 0) -> np.ndarray:
    data = np.random.default_rng(seed).standard_normal(n).astype(dtype)
    data[0] = -0.0  # a signed zero survives
    data.setflags(write=False)
    return data


def _project_with(*arrays: np.ndarray, rate: float = 8000.0):
    project = edits.new_project(templates=False)
    ids = []
    for i, data in enumerate(arrays):
        project, tile_id = edits.add_tile(project, SampledTile(data, rate, f"r{i}"))
        ids.append(tile_id)
    return project, ids


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_samples_round_trip_bit_for_bit_with_their_key(tmp_path, dtype, monkeypatch):
    monkeypatch.setattr(media, "RAW_BLOCK", 4096)  # several blocks, hashed while the next is read
    data = _recording(3 * 4096 + 5, dtype)
    project, (tile_id,) = _project_with(data)
    path = tmp_path / "p.htl"
    projectfile.save(project, path)
    loaded = projectfile.load(path).tile(tile_id)
    assert loaded.data.dtype == dtype and loaded.data.tobytes() == data.tobytes()
    assert not loaded.data.flags.writeable and loaded.data.base is None
    assert loaded.__dict__["key"] == content_key(data, 8000.0)  # known from the read, checked
    projectfile.save(projectfile.load(path), tmp_path / "again.htl")
    assert (tmp_path / "again.htl").read_bytes() == path.read_bytes()


def test_a_project_without_recordings_is_plain_json(tmp_path):
    project = edits.new_project()
    projectfile.save(project, tmp_path / "p.htl")
    assert (tmp_path / "p.htl").read_text() == projectfile.dumps(project)


def _saved(tmp_path) -> tuple[bytes, int]:
    """A saved file of two recordings, and where its appendix starts."""
    project, _ = _project_with(_recording(1000, np.float32), _recording(700, np.float64, 1))
    path = tmp_path / "p.htl"
    projectfile.save(project, path)
    saved = path.read_bytes()
    return saved, saved.index(media.SEPARATOR) + len(media.SEPARATOR)


def _refused(tmp_path, content: bytes, sentence: str) -> None:
    path = tmp_path / "damaged.htl"
    path.write_bytes(content)
    with pytest.raises(ProjectFileError, match=sentence) as info:
        projectfile.load(path)
    assert "\n" not in str(info.value) and "Traceback" not in str(info.value)
    assert path.read_bytes() == content  # nothing written, nothing lost


def test_a_truncated_appendix_is_one_sentence_and_the_file_is_untouched(tmp_path):
    saved, start = _saved(tmp_path)
    appendix = 1000 * 4 + 700 * 8
    for cut in (len(saved) - 1, start + 4000, start + 1):
        _refused(
            tmp_path,
            saved[:cut],
            f"damaged.htl cannot be opened: it is truncated: its binary appendix holds "
            f"{cut - start} of the {appendix} bytes its project declares",
        )
    _refused(tmp_path, saved[: start - 1], "not a readable project file")  # the line cut
    _refused(tmp_path, saved + b"\0", "1 unexpected bytes after its binary appendix")


def test_a_damaged_sample_fails_its_hash(tmp_path):
    saved, start = _saved(tmp_path)
    flipped = bytearray(saved)
    flipped[start + 4000 + 17] ^= 0x01  # a bit of the float64 recording: still finite
    _refused(tmp_path, bytes(flipped), "is damaged: its samples do not match their hash")


def test_entries_that_lie_about_the_appendix_are_one_sentence(tmp_path):
    saved, start = _saved(tmp_path)
    text = saved[: start - len(media.SEPARATOR)]
    doc = json.loads(text)
    first, second = doc["media"]
    cases = [
        ((first, "count", 1001), "holds 1000 samples but declares 1001"),
        ((second, "offset", 4001), "lies past the end of the binary appendix"),
        ((second, "dtype", "<i2"), "unknown sample encoding"),
        ((first, "rate", 8001.0), "do not match their hash"),  # the key covers the rate
    ]
    for (key, field, value), sentence in cases:
        lying = json.loads(text)
        lying["media"][key][field] = value
        content = json.dumps(lying).encode() + b"\n" + saved[start - len(media.SEPARATOR) :]
        _refused(tmp_path, content, sentence)
    no_appendix = json.dumps(doc).encode()
    _refused(tmp_path, no_appendix, "binary appendix of 9600 bytes is missing")
    del doc["appendix"]
    _refused(tmp_path, json.dumps(doc).encode(), "stored in a binary appendix, which the file")


def test_a_save_that_fails_mid_appendix_leaves_the_old_file(tmp_path, monkeypatch):
    saved, _ = _saved(tmp_path)
    path = tmp_path / "p.htl"

    def unplugged(data, out):
        out.write(b"half")
        raise OSError("disk unplugged")

    monkeypatch.setattr(media, "write_raw", unplugged)
    project, _ = _project_with(_recording(50, np.float32, 7))
    with pytest.raises(OSError, match="disk unplugged"):
        projectfile.save(project, path)
    assert path.read_bytes() == saved
    assert [p.name for p in tmp_path.iterdir()] == ["p.htl"]


@st.composite
def _appendix(draw) -> tuple[bytes, np.ndarray, int]:
    """A saved file's bytes (one recording of any precision and size), and where it was cut
    or flipped (a position; -1 for untouched)."""
    dtype = draw(st.sampled_from([np.float32, np.float64]))
    values = draw(st.lists(st.floats(allow_nan=False, allow_infinity=False, width=32), min_size=1))
    data = np.array(values, dtype=dtype)
    data.setflags(write=False)
    project, _ = _project_with(data)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "p.htl"
        projectfile.save(project, path)
        saved = path.read_bytes()
    return saved, data, draw(st.integers(-1, len(saved) - 1))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(_appendix(), st.sampled_from(["cut", "flip"]))
def test_the_appendix_reader_gives_the_samples_or_one_sentence(case, damage):
    saved, data, at = case
    if at >= 0:
        changed = bytearray(saved)
        if damage == "cut":
            del changed[at:]
        else:
            changed[at] ^= 0x40
        saved = bytes(changed)
    try:
        project = projectfile.loads(saved)
    except ProjectFileError as exc:
        assert "\n" not in str(exc) and at >= 0
        return
    (tile,) = [t for t in project.tiles.values() if isinstance(t, SampledTile)]
    if at < 0:
        assert tile.data.tobytes() == data.tobytes()
    assert tile.key == content_key(tile.data, tile.rate)  # never a key the samples do not have


def test_split_finds_the_separator_across_reads(monkeypatch):
    monkeypatch.setattr(media, "SCAN_BYTES", 7)
    content = b'{"a": 1}\n' + media.SEPARATOR + b"\x00\x01\x02"
    text, appendix = media.split(io.BytesIO(content))
    assert bytes(text) == b'{"a": 1}\n' and appendix is not None
    assert (appendix.start, appendix.size) == (len(content) - 3, 3)
    assert media.split(io.BytesIO(b'{"a": 1}\n')) == (bytearray(b'{"a": 1}\n'), None)
    with pytest.raises(FieldError, match="does not declare"):
        media.check_size(appendix, None)
