"""An hour-long recording in the editor, at a small rate so the test stays fast.

An hour at 200 Hz (720,000 samples) has the shape of an hour at 44.1 kHz: the whole-project
zoom puts hundreds of samples in each pixel column. Opening the window must draw the waveform
from the peak pyramid and the float32 store, without rendering the recording.
"""

from __future__ import annotations

import numpy as np
import soundfile as sf

from timeline import edits
from timeline.files import importing
from timeline.gui.clip_shape import clip_columns
from timeline.tiles import SampledTile

RATE = 200
HOUR = 3600


def _hour(tmp_path):
    t = np.arange(HOUR * RATE) / RATE
    wave = 0.5 * np.sin(2 * np.pi * 7 * t) * (t / HOUR)  # louder towards the end
    path = tmp_path / "hour.wav"
    sf.write(path, wave, RATE, subtype="PCM_16")
    return path


def test_an_hour_opens_drawn_from_its_peaks_without_a_render(qtbot, tmp_path, monkeypatch):
    from timeline.gui.main_window import MainWindow

    project, (clip_id,) = importing.import_file(edits.new_project(), _hour(tmp_path))
    clip = project.find_clip(clip_id)[1]
    tile = project.tile(clip.tile_id)
    assert tile.data.dtype == np.float32 and tile.data.nbytes == 4 * HOUR * RATE
    rendered: list[int] = []
    real_render = SampledTile.render
    monkeypatch.setattr(
        SampledTile, "render", lambda self, *a: rendered.append(a[2]) or real_render(self, *a)
    )
    win = MainWindow(project)
    qtbot.addWidget(win)
    win.resize(1200, 700)
    win.show()
    win.view.fit()
    image = win.view.viewport().grab().toImage()
    assert rendered == []  # nothing of the hour was rendered to open it
    rect = win.view.mapFromScene(win.view.clip_scene_rect(clip_id)).boundingRect()
    # the wave's envelope grows over the hour: more ink in the last tenth of the clip than the first
    ink = [
        sum(image.pixelColor(x, yy).lightness() < 100 for yy in range(rect.top(), rect.bottom()))
        for x in (rect.left() + rect.width() // 20, rect.right() - rect.width() // 20)
    ]
    assert ink[1] > 3 * max(ink[0], 1), ink
    # the columns the paint used are the samples' own extremes, at the whole hour and at 1 s
    for t0, t1 in [(0.0, HOUR), (HOUR - 1.0, HOUR)]:
        lo, hi = clip_columns(clip, tile, project.rate, t0, t1, 100)
        first, last = int(t0 * RATE), int(t1 * RATE)
        assert hi.max() == float(tile.data[first:last].max())
        assert lo.min() == float(tile.data[first:last].min())
