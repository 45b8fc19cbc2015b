"""The hand-written .haptic and AHAP files of tests/data (described in its README.md).

They run the corpus tests' checks without the shared corpus, and each file's values are worked
out by hand from its text: the amplitude and frequency at chosen times, its emphasis, its notes,
the one sentence that rejects it. They are references independent of our writers.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from importers.ahap import READ_TOLERANCE
from tests.corpus import DATA
from timeline import edits
from timeline.edits.vibration import design_of
from timeline.files import importing
from timeline.plugins.file_formats import FormatError

from .vibration_checks import (
    check_ahap_round_trip,
    check_envelopes_kept_through_ahap,
    check_written_back_exactly,
    export_doc,
    read_project,
)

VALID_HAPTIC = [
    "extra_fields.haptic",
    "frequency_past_end.haptic",
    "late_start.haptic",
    "meta_pair.haptic",
    "required_only.haptic",
    "two_emphasis.haptic",
    "weak_emphasis.haptic",
]
VALID_AHAP = ["apple_style.ahap", "control_above_1.ahap", "meta_pair.ahap", "transients_only.ahap"]
REJECTED = {
    "invalid_amplitude_above_1.haptic": "amplitude breakpoint 2 amplitude must be between 0 and 1",
    "invalid_back_in_time.haptic": "amplitude breakpoint 3 goes back in time (0.1 s after 0.2 s)",
    "invalid_emphasis_amplitude_above_1.haptic": (
        "amplitude breakpoint 1 emphasis amplitude must be between 0 and 1, not 1.5"
    ),
    "invalid_emphasis_frequency_below_0.haptic": (
        "amplitude breakpoint 2 emphasis frequency must be between 0 and 1, not -0.1"
    ),
    "invalid_no_signals.haptic": "is not a .haptic file (no signals.continuous.envelopes)",
    "invalid_one_breakpoint.haptic": "the amplitude envelope has one breakpoint; it needs at least",
    "invalid_version_2.haptic": "is .haptic version 2; only version 1 is supported",
    "invalid_no_pattern.ahap": "is not an AHAP file (it has no Pattern list)",
    "invalid_parameter_curves_typo.ahap": "entry 2 is not an Event, ParameterCurve or Parameter",
}

# (file, time, value, tolerance): read off each file by hand. A .haptic is linear between its
# breakpoints; an AHAP's amplitude is intensity squared, read within READ_TOLERANCE of that.
EXACT = 1e-12
AMPLITUDE_AT = [
    ("required_only.haptic", 0.1, 0.6, EXACT),
    ("required_only.haptic", 0.2, 0.5, EXACT),  # halfway from 0.6 to 0.4
    ("two_emphasis.haptic", 0.3, 0.25, EXACT),  # halfway from 0.5 to 0
    ("late_start.haptic", 0.35, 0.15, EXACT),  # the envelope starts at 0.3 s
    ("extra_fields.haptic", 0.1, 0.2, EXACT),  # unknown fields change nothing
    ("weak_emphasis.haptic", 0.15, 0.3, EXACT),
    ("frequency_past_end.haptic", 0.1, 0.4, EXACT),
    ("meta_pair.haptic", 0.75, 0.305, EXACT),
    ("meta_pair.ahap", 0.5, 0.25, EXACT),  # control 0.4 at the transient, ducked: (0.4 / 0.8)^2
    ("meta_pair.ahap", 1.0, 0.36, EXACT),  # 0.6^2
    ("meta_pair.ahap", 0.25, 0.0625, READ_TOLERANCE),  # (0.5 / 2)^2
    ("meta_pair.ahap", 0.75, 0.3025, READ_TOLERANCE),  # ((0.5 + 0.6) / 2)^2
    ("apple_style.ahap", 0.15, 0.16, READ_TOLERANCE),  # halfway up the 0.1 s attack: 0.4^2
    ("apple_style.ahap", 0.3, 0.64, READ_TOLERANCE),  # 0.8^2, sustained
    ("apple_style.ahap", 0.45, 0.16, READ_TOLERANCE),  # halfway down the 0.1 s release
    ("apple_style.ahap", 0.55, 0.0, READ_TOLERANCE),  # between the two continuous events
    ("apple_style.ahap", 0.7, 0.5625, READ_TOLERANCE),  # curve times relative to 0.6 s: 0.75^2
    ("apple_style.ahap", 0.9, 1.0, READ_TOLERANCE),  # the curve's last value holds
]
FREQUENCY_AT = [
    ("two_emphasis.haptic", 0.2, 0.5, EXACT),  # halfway from 0.4 to 0.6
    ("extra_fields.haptic", 0.2, 0.6, EXACT),
    ("frequency_past_end.haptic", 0.35, 0.7, EXACT),  # past the amplitude envelope's end
    ("meta_pair.haptic", 0.5, 0.32, EXACT),
    ("meta_pair.ahap", 0.5, 0.16, READ_TOLERANCE),  # Meta's sharpness = sqrt(frequency): 0.4^2
    ("meta_pair.ahap", 1.0, 0.64, READ_TOLERANCE),  # 0.8^2
    ("apple_style.ahap", 0.3, 0.3, EXACT),  # Apple's own: frequency = sharpness
    ("apple_style.ahap", 0.8, 0.5, EXACT),
]
# (time, amplitude, frequency) of each emphasis; AHAP transients: amplitude = intensity^2
EMPHASIS = {
    "extra_fields.haptic": [(0.2, 0.4, 0.6)],
    "frequency_past_end.haptic": [],
    "late_start.haptic": [],
    "meta_pair.haptic": [(0.5, 0.64, 0.3)],
    "required_only.haptic": [],
    "two_emphasis.haptic": [(0.05, 0.9, 0.2), (0.2, 0.7, 0.8)],
    "weak_emphasis.haptic": [(0.1, 0.2, 0.6)],
    "apple_style.ahap": [(0.0, 0.36, 0.9)],
    "meta_pair.ahap": [(0.5, 0.64, 0.3)],
    "transients_only.ahap": [(0.0, 1.0, 0.6), (0.25, 0.25, 0.2)],
    "control_above_1.ahap": [],
}
NOTES = {
    "required_only.haptic": ["no frequency envelope: frequency 0.5 assumed"],
    "weak_emphasis.haptic": ["the emphasis at 0.1 s (0.2) is weaker than its breakpoint (0.5)"],
    "frequency_past_end.haptic": ["1 frequency breakpoint(s) lie outside the amplitude envelope"],
    "apple_style.ahap": ["AudioCustom events are not haptic and were skipped"],
    "control_above_1.ahap": ["control values outside 0 to 1 were clamped, as Core Haptics does"],
}


def test_every_data_file_is_listed_here_and_in_the_readme():
    files = {p.name for p in DATA.iterdir() if p.suffix in (".haptic", ".ahap")}
    assert files == set(VALID_HAPTIC) | set(VALID_AHAP) | set(REJECTED)
    assert files == set(EMPHASIS) | set(REJECTED)
    readme = (DATA / "README.md").read_text()
    assert [name for name in sorted(files) if f"`{name}`" not in readme] == []


@pytest.mark.parametrize("name", sorted(REJECTED))
def test_an_invalid_file_is_rejected_in_one_sentence_saying_why(name):
    with pytest.raises(FormatError, match=re.escape(REJECTED[name])) as caught:
        importing.read_file(DATA / name)
    assert str(caught.value).startswith(name) and "\n" not in str(caught.value)


@pytest.mark.parametrize("name", VALID_HAPTIC + VALID_AHAP)
def test_a_valid_file_imports_with_its_notes(name):
    imported = importing.read_file(DATA / name)
    assert len(imported.placements) >= 1
    expected = NOTES.get(name, [])
    assert len(imported.notes) == len(expected)
    assert all(note.startswith(start) for note, start in zip(imported.notes, expected, strict=True))


@pytest.mark.parametrize(("name", "time", "value", "tolerance"), AMPLITUDE_AT)
def test_the_amplitude_is_the_one_read_off_the_file(name, time, value, tolerance):
    design = design_of(read_project(DATA / name))
    assert abs(design.amplitude_at(np.array([time]))[0] - value) <= tolerance + 1e-12


@pytest.mark.parametrize(("name", "time", "value", "tolerance"), FREQUENCY_AT)
def test_the_frequency_is_the_one_read_off_the_file(name, time, value, tolerance):
    design = design_of(read_project(DATA / name))
    assert abs(design.frequency_at(np.array([time]))[0] - value) <= tolerance + 1e-12


@pytest.mark.parametrize("name", sorted(EMPHASIS))
def test_the_emphasis_are_the_ones_in_the_file(name):
    found = [
        (e.time, e.amplitude, e.frequency) for e in design_of(read_project(DATA / name)).emphasis
    ]
    assert np.allclose(found, EMPHASIS[name], rtol=0, atol=1e-12) and len(found) == len(
        EMPHASIS[name]
    )


@pytest.mark.parametrize("name", VALID_HAPTIC)
def test_an_unedited_haptic_is_written_back_exactly(name, tmp_path):
    check_written_back_exactly(DATA / name, tmp_path)


@pytest.mark.parametrize("name", VALID_HAPTIC)
def test_haptic_to_ahap_and_back_keeps_the_envelopes(name, tmp_path):
    check_envelopes_kept_through_ahap(DATA / name, tmp_path)


@pytest.mark.parametrize("name", VALID_AHAP)
def test_an_ahap_round_trips_within_the_bound(name, tmp_path):
    check_ahap_round_trip(DATA / name, tmp_path)


def test_the_meta_style_ahap_reads_as_the_haptic_it_was_written_from():
    ahap = design_of(read_project(DATA / "meta_pair.ahap"))
    haptic = design_of(read_project(DATA / "meta_pair.haptic"))
    # at the breakpoints the two agree; between them the player interpolates the intensity
    # (the square root of the amplitude) and the sharpness (the root of the frequency)
    points = np.array([0.0, 0.5, 1.0])
    assert np.allclose(ahap.amplitude_at(points), haptic.amplitude_at(points), rtol=0, atol=1e-12)
    grid = np.linspace(0.0, 1.0, 1001)
    heard = np.interp(grid, points, [0.0, 0.5, 0.6]) ** 2
    assert np.abs(ahap.amplitude_at(grid) - heard).max() <= READ_TOLERANCE
    assert np.abs(ahap.frequency_at(grid) - (0.8 * grid) ** 2).max() <= READ_TOLERANCE
    assert [(e.time, e.frequency) for e in ahap.emphasis] == [(0.5, 0.3)]
    assert [(e.time, e.frequency) for e in haptic.emphasis] == [(0.5, 0.3)]


def test_a_weak_emphasis_is_written_back_at_its_breakpoint_s_level(tmp_path):
    doc = export_doc(read_project(DATA / "weak_emphasis.haptic"), tmp_path / "w.haptic")
    amplitude = doc["signals"]["continuous"]["envelopes"]["amplitude"]
    assert amplitude[1] == {
        "time": 0.1,
        "amplitude": 0.5,
        "emphasis": {"amplitude": 0.5, "frequency": 0.6},
    }


def test_an_edited_design_is_written_from_its_edited_breakpoints(tmp_path):
    project = read_project(DATA / "two_emphasis.haptic")
    clip = project.tracks[0].clips[0].id
    doc = export_doc(edits.set_clip_gain(project, clip, 0.5), tmp_path / "half.haptic")
    amplitude = doc["signals"]["continuous"]["envelopes"]["amplitude"]
    assert [b["amplitude"] for b in amplitude] == [0.15, 0.25, 0.25, 0.0]
