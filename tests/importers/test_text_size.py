"""A text table over the 2 GiB limit is refused by its size, before a byte of it is read."""

import pytest

from importers.text import FORMAT, MAX_BYTES
from timeline.plugins.file_formats import FormatError


def test_a_csv_over_the_limit_is_refused_by_its_size(tmp_path, monkeypatch):
    path = tmp_path / "big.csv"
    with path.open("wb") as f:
        f.truncate(MAX_BYTES + 1)  # a hole: no disk, and reading it would take 2 GiB

    def unread(*_, **__):
        raise AssertionError("the file was read")

    monkeypatch.setattr(type(path), "read_bytes", unread)
    with pytest.raises(FormatError, match=r"^big.csv is larger than 2 GiB, the most a text table"):
        FORMAT.read(path)
