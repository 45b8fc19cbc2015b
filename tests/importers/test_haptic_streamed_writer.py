"""The .haptic writer streams its breakpoints to the file with the bytes json.dumps gives the
whole document (what it wrote before it streamed)."""

from __future__ import annotations

from pathlib import Path

import importers
from importers import _vibration as vib
from importers.lofelt import design_document, write_design
from timeline.edits.vibration import Emphasis, VibrationDesign


def test_the_streamed_file_has_the_bytes_of_the_whole_document(tmp_path):
    assert Path(importers.__file__).resolve().is_relative_to(Path(__file__).resolve().parents[2])
    n = 5_000  # more than one chunk of 4,096 breakpoints
    amplitude = tuple((0.1 + i / 1000, (i * 7919 % 1000 + 1) / 1001) for i in range(n))
    frequency = tuple((i / 500, (i * 104729 % 997) / 997) for i in range(n // 2))
    emphasis = tuple(
        Emphasis(t, a, f)
        for t, a, f in [(0.05, 0.9, 0.3), (0.1, 0.2, 0.5), (1.2345, 1.0, 0.1), (2.0, 0.7, 0.9)]
        + [(2.0, 0.1, 0.2), (9.0, 0.4, 0.6)]
    )
    design = VibrationDesign(
        amplitude=amplitude, frequency=frequency, emphasis=emphasis, duration=10.0
    )
    for convention in ("sqrt", "linear"):
        whole, streamed = tmp_path / f"whole-{convention}.haptic", tmp_path / "streamed.haptic"
        vib.write_json(design_document(design, convention), whole)
        write_design(design, streamed, convention)
        assert streamed.read_bytes() == whole.read_bytes()
    assert whole.read_bytes().count(b'"emphasis"') == 6
    assert whole.read_text().count('"amplitude": 0.0\n') == 1  # silent before the first, raised
