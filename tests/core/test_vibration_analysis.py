"""The drive-waveform analysis that exports recordings as .haptic/AHAP: pieces and accuracy."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from timeline import edits
from timeline.analysis.breakpoints import AMPLITUDE_TOLERANCE, window_medians
from timeline.edits.vibration import design_of
from timeline.signal.vibration_design import carrier_hz
from timeline.tiles import SampledTile

finite = st.floats(-1e6, 1e6, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(
    arrays(np.float64, st.integers(1, 60), elements=finite),
    st.integers(0, 7),
    st.sampled_from([1, 5, 40, 2**20]),
    st.data(),
)
def test_window_medians_equal_each_window_median_bit_for_bit(values, half, block, data):
    centres = np.array(
        sorted(data.draw(st.sets(st.integers(0, len(values) - 1), min_size=1))), dtype=np.int64
    )
    expected = [np.median(values[max(0, c - half) : c + half + 1]) for c in centres]
    assert window_medians(values, centres, half, block).tolist() == expected


def test_a_recording_exports_its_envelope_and_carrier():
    """A 2 s, 10 kHz drive recording: a 0.2-0.9 envelope ramp on a 100-200 Hz chirp."""
    rate, n = 10_000.0, 20_000
    t = np.arange(n) / rate
    envelope = 0.2 + 0.7 * t / 2.0
    hz = 100.0 + 50.0 * t
    x = envelope * np.sin(2 * np.pi * np.cumsum(hz) / rate)
    p = edits.new_project(templates=False)
    p, track = edits.add_track(p, "drive")
    p, tile = edits.add_tile(p, SampledTile(x, rate, "recording"))
    p, _ = edits.add_clip(p, track, tile, 0.0)
    design = design_of(p)
    inner = (t > 0.02) & (t < 1.98)  # the analysis window is cut at the ends
    amp_error = np.abs(design.amplitude_at(t) - envelope)[inner]
    assert np.max(amp_error) <= AMPLITUDE_TOLERANCE
    assert np.median(np.abs(carrier_hz(design.frequency_at(t)) - hz)[inner]) < 1.0
    assert len(design.amplitude) <= 4  # a straight ramp needs few breakpoints
