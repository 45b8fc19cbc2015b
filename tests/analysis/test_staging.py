"""Gain staging: within the device's limit, above what a hand feels, or a note that says so."""

from __future__ import annotations

import numpy as np
import pytest

from tests.analysis.conftest import RATE, tone_bursts
from timeline.analysis import analyse
from timeline.analysis.staging import Staging, peak, stage


def test_a_loud_design_stays_within_the_limit_at_the_sound_s_level() -> None:
    loud = analyse(1.25 * tone_bursts([0.1, 0.45], 150.0, 0.8), RATE)  # bursts peaking at 1.0
    assert peak(loud) > 1.2  # an emphasis adds to the ducked envelope under it
    staged = stage(loud, Staging(limit=1.0, felt=0.027))
    assert peak(staged.analysis) <= 1.0 + 1e-12
    np.testing.assert_array_equal(staged.analysis.amplitude, loud.amplitude)  # envelope kept
    assert staged.gain_db == 0.0 and "2 emphasis lowered" in staged.notes[0]
    # a device with less headroom lowers the envelope too
    half = stage(loud, Staging(limit=0.5))
    top = loud.amplitude[:, 1].max()
    assert peak(half.analysis) <= 0.5 + 1e-12
    assert half.gain_db == pytest.approx(20 * np.log10(0.5 / top))


def test_a_quiet_design_is_raised_to_be_felt_or_a_note_offers_the_gain() -> None:
    quiet = analyse(0.01 * tone_bursts([0.1], 150.0, 0.5), RATE)
    assert peak(quiet) < 0.027
    raised = stage(quiet, Staging(limit=1.0, felt=0.027))
    assert abs(peak(raised.analysis) - 0.027) < 1e-9 and raised.gain_db > 0
    assert raised.notes[0].startswith(f"raised {raised.gain_db:.1f} dB")
    kept = stage(quiet, Staging(limit=1.0, felt=0.027, gain_db=0.0))
    assert peak(kept.analysis) == peak(quiet)
    assert "below 0.0270" in kept.notes[0] and f"{raised.gain_db:.1f} dB more" in kept.notes[0]
