"""The analysis against Lofelt Studio's own analysis of ten recorded sounds (the corpus pairs).

Measured as `convert` writes by default (staged for the default device); docs/convert.md has the
table. The targets (set for held-out pairs: r median >= 0.965, MAE median <= 0.025, F1 mean >=
0.55) are met for F1 only on these ten: these bounds hold the measured figures, which beat the
naive 10 ms RMS envelope (r 0.89, MAE 0.085, F1 0.20) on every measure.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from timeline.analysis import AnalysisSettings
from timeline.analysis.staging import peak
from timeline.bench.convert import (
    default_staging,
    level_table,
    pair_agreement,
    pair_fit,
    pair_where_made,
)


def test_agreement_with_lofelt_studio(audio_pairs: Path) -> None:
    found = {p.stem: pair_agreement(p)[1] for p in sorted(audio_pairs.glob("*.wav"))}
    assert len(found) == 10
    r = np.median([a.amplitude_r for a in found.values()])
    mae = np.median([a.amplitude_mae for a in found.values()])
    f1 = np.mean([a.onset_f1 for a in found.values()])
    freq = np.mean([a.frequency_mae for a in found.values()])
    assert r >= 0.947 and mae <= 0.0675 and f1 >= 0.6 and freq <= 0.29
    # the decaying impacts agree closely, envelope and onset (MAE 0.013 and 0.012 before their
    # tails were expanded)
    for name in ("Body1", "Wood1"):
        assert found[name].amplitude_r >= 0.99 and found[name].amplitude_mae <= 0.006
        assert found[name].onset_f1 == 1.0


def test_no_converted_design_asks_for_more_than_the_default_device(audio_pairs: Path) -> None:
    limit = default_staging().limit
    peaks = [peak(pair_agreement(p)[0]) for p in sorted(audio_pairs.glob("*.wav"))]
    assert max(peaks) <= limit + 1e-12 and min(peaks) > 0.3 * limit


def test_sensitivity_thins_and_thickens_the_emphasis_of_every_pair(audio_pairs: Path) -> None:
    for sound in sorted(audio_pairs.glob("*.wav")):
        counts = [
            len(pair_agreement(sound, AnalysisSettings(sensitivity=s))[0].emphasis)
            for s in (1, 50, 100)
        ]
        assert counts == sorted(counts) and counts[0] <= 1


def test_lofelt_made_its_breakpoints_with_the_same_amplitude_analysis(audio_pairs: Path) -> None:
    """At the points Lofelt's analysis made, its envelope is ours: the same, or at another level."""
    fits = {p.stem: pair_fit(p) for p in sorted(audio_pairs.glob("*.wav"))}
    for name in ("Body1", "Glass1", "Wood1"):  # the same analysis at the sound's own level
        assert fits[name].analysis_points >= 11
        assert abs(20 * np.log10(fits[name].gain)) < 0.01 and fits[name].error < 1e-4
    # the same analysis with a gain a designer chose: +14.2 dB and -4.3 dB
    assert abs(20 * np.log10(fits["Alert1"].gain) - 14.17) < 0.01 and fits["Alert1"].error < 1e-4
    assert abs(20 * np.log10(fits["Beep2"].gain) + 4.31) < 0.01 and fits["Beep2"].error < 1e-4
    # drawn by hand: most of these designs' breakpoints fall between the sound's samples
    assert fits["Button1"].hand_placed == 7 and fits["CameraShutter1"].hand_placed == 17


def test_where_lofelt_s_analysis_made_its_design_ours_agrees(audio_pairs: Path) -> None:
    """Scored only on the segments and emphasis Lofelt's analysis made (not drawn by hand)."""
    found = {p.stem: pair_where_made(p) for p in sorted(audio_pairs.glob("*.wav"))}
    mae = np.nanmedian([w.scored.amplitude_mae for w in found.values()])
    leveled = np.nanmedian([w.with_gain.amplitude_mae for w in found.values()])
    assert mae <= 0.028 and leveled <= 0.0092  # against 0.066 over whole designs
    assert found["Button1"].scored.share == 0.0  # drawn by hand from end to end
    assert found["Beep2"].scored.share == 1.0 and found["Beep2"].with_gain.amplitude_mae < 0.002
    # Glass1: one of its 26 emphasis came from the analysis, and ours finds that one
    assert (found["Glass1"].made_emphasis, found["Glass1"].emphasis) == (1, 26)
    assert found["Glass1"].onset_f1 == 1.0
    f1 = np.mean([w.onset_f1 for w in found.values() if w.made_emphasis])
    assert f1 >= 0.61  # against 0.457 over all emphasis of all ten


def test_lofelt_s_level_explains_the_amplitude_error_but_no_normalisation_predicts_it(
    audio_pairs: Path,
) -> None:
    rows = {row[0].split(" (")[0]: row[1:] for row in level_table().rows}
    r, mae, f1 = rows["each sound's own gain"]
    assert r >= 0.948 and mae <= 0.037 and f1 >= 0.52  # in-sample: evidence only
    # a normalisation level fitted on nine sounds and scored on the tenth recovers little of it
    r, mae, f1 = rows["normalised, level from the other nine"]
    assert 0.055 <= mae <= 0.06 and r < 0.95 and f1 < 0.7
