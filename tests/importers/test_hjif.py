"""MPEG-I haptics .hjif: registration, schema-valid export, real files' shapes, round trips,
hostile input."""

from __future__ import annotations

import json
import tomllib
from importlib.metadata import EntryPoint
from pathlib import Path

import jsonschema
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from importers import hjif
from importers.hjif_write import FORCE_TOLERANCE, TIMESCALE
from timeline import edits
from timeline.edits.vibration import Emphasis, VibrationDesign, design_of, place_design
from timeline.files import exporting, importing
from timeline.plugins import discovery
from timeline.plugins.file_formats import FormatError, Imported, readers_for, writer_for
from timeline.rendering import mixer
from timeline.tiles import GeneratorTile, VibrationTile, generator, spline

from .hjif_schema import HJIF_SCHEMA

TICK = 1 / TIMESCALE
TIME_BOUND = TICK / 2 + 1e-12  # s: a time moves to the nearest tick
HZ_BOUND = 0.5 / 150 + 1e-12  # normalised frequency: whole Hz on a 150 Hz carrier range
AHAP_BOUND = 0.02  # AHAP -> .hjif -> AHAP vs AHAP -> AHAP, amplitude and frequency at every
# breakpoint allowing a tick (two fits within ahap.WRITE_TOLERANCE each; measured 0.0145, 0.0089)
ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def registered(monkeypatch):
    """The hjif entry point, as pyproject declares it, even where the installed metadata (an
    editable install of another checkout) predates it."""
    original = discovery._entry_points

    def entry_points(group: str) -> tuple:
        found = original(group)
        if group == discovery.IMPORTERS and not any(e.name == "hjif" for e in found):
            found = (*found, EntryPoint("hjif", "importers.hjif:FORMAT", group))
        return tuple(sorted(found, key=lambda e: e.name))

    monkeypatch.setattr(discovery, "_entry_points", entry_points)


def _read(path: Path):
    project, _ = importing.import_file(edits.new_project(templates=False), path)
    return project


def _write(tmp_path: Path, doc: dict, name: str = "in.hjif") -> Path:
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return path


# --- shapes of the reference software's own files (its RM_submission outputs, 2023) ------------


def _old_style(bands: list[dict], library: list | None = None, modality="Vibrotactile") -> dict:
    """A document shaped like the files MPEGGroup/HapticReferenceSoftware's scripts wrote:
    version "1", timescale 2000, mixing_weight, curve_type "Unknown" and block_length on every
    band, amplitudes quantised to 8 bits (0 reads -0.0039)."""
    channel = {
        "id": 0,
        "description": "Left hand",
        "gain": 1.0,
        "mixing_weight": 0.9999983310699463,
        "body_part_mask": 2752512,
        "bands": bands,
    }
    perception = {
        "id": 0,
        "avatar_id": 0,
        "description": "Vibration effect",
        "perception_modality": modality,
        "unit_exponent": -3,
        "perception_unit_exponent": 0,
        "reference_devices": [],
        "effect_library": library or [],
        "channels": [channel],
    }
    return {
        "version": "1",
        "profile": "Main",
        "level": 1,
        "date": "Mon Oct  9 14:08:04 2023\n",
        "description": "Inflate",
        "timescale": 2000,
        "avatars": [],
        "perceptions": [perception],
        "syncs": [{"timestamp": 0, "timescale": 2000}],
    }


def _band(kind: str, effects: list[dict], lo=65, hi=300) -> dict:
    return {
        "band_type": kind,
        "curve_type": "Unknown",
        "block_length": 0.0,
        "lower_frequency_limit": lo,
        "upper_frequency_limit": hi,
        "effects": effects,
    }


def _basis(position: int, keyframes: list[tuple]) -> dict:
    names = ("relative_position", "amplitude_modulation", "frequency_modulation")
    return {
        "effect_type": "Basis",
        "position": position,
        "phase": 0.0,
        "base_signal": "Sine",
        "keyframes": [
            {k: v for k, v in zip(names, kf, strict=False) if v is not None} for kf in keyframes
        ],
    }


ZERO = -0.003921568393707275  # 0 after the reference codec's 8-bit amplitude quantisation


def test_an_ahap_converted_file_reads_as_its_envelopes(tmp_path):
    # Apple's Inflate as the reference encoder wrote it: one vectorial effect, 65-300 Hz
    effect = _basis(0, [(0, ZERO, 65), (2200, 0.301960825920105), (3400, ZERO, 300)])
    result = hjif.FORMAT.read(_write(tmp_path, _old_style([_band("VectorialWave", [effect])])))
    design = result.placements[0].tile.design
    expected = [(0.0, -ZERO), (1.1, 0.301960825920105), (1.7, -ZERO)]
    assert np.array(design.amplitude) == pytest.approx(np.array(expected))
    # 65 Hz and 300 Hz lie outside the 80-230 Hz carrier: clipped, and said
    assert design.frequency == ((0.0, 0.0), (1.7, 1.0))
    assert any("2 frequency value(s) outside 80-230 Hz" in n for n in result.notes)


def test_library_references_and_a_stray_codec_keyframe(tmp_path):
    # DoubleTick as the reference software wrote it: two references to one library effect whose
    # first keyframe (65534 ticks) is a codec artefact before keyframe 0
    library = [
        {
            **_basis(0, [(65534, 0.945), (0, ZERO, 166), (48, ZERO, 166), (50, 0.945)]),
            "id": 0,
        }
    ]
    refs = [{"effect_type": "Reference", "position": p, "id": 0} for p in (0, 458)]
    doc = _old_style([_band("VectorialWave", refs, 0, 1000)], library)
    result = hjif.FORMAT.read(_write(tmp_path, doc))
    design = result.placements[0].tile.design
    a = -ZERO
    expected = [(0, a), (0.024, a), (0.025, 0.945), (0.025, 0.0), (0.229, 0.0), (0.229, a),
                (0.253, a), (0.254, 0.945)]  # fmt: skip
    assert np.array(design.amplitude) == pytest.approx(np.array(expected))
    assert design.frequency_at(np.array([0.01, 0.24])) == pytest.approx([86 / 150, 86 / 150])
    assert any("2 keyframe(s) later than" in n for n in result.notes)


def test_overlapping_effects_in_several_bands_add(tmp_path):
    # Explosion1 as the reference software wrote it puts overlapping effects in bands of their own
    bands = [
        _band("VectorialWave", [_basis(0, [(0, 0.5, 90), (200, 0.5)])], 0, 1000),
        _band("VectorialWave", [_basis(100, [(0, 0.25, 90), (200, 0.25)])], 0, 1000),
    ]
    result = hjif.FORMAT.read(_write(tmp_path, _old_style(bands)))
    design = result.placements[0].tile.design
    expected = [(0, 0.5), (0.05, 0.5), (0.05, 0.75), (0.1, 0.75), (0.1, 0.25), (0.15, 0.25)]
    assert np.array(design.amplitude) == pytest.approx(np.array(expected))
    assert any("overlapping vectorial effects were added" in n for n in result.notes)


def test_a_real_shaped_file_comes_back_the_same(tmp_path):
    # 2000 ticks a second divide 48,000: an import exported and read again keeps every number
    effect = _basis(0, [(0, ZERO, 142), (146, ZERO, 142), (148, 0.49803924560546875)])
    transient = _basis(300, [(0, 0.6313725709915161, 90), (26, 0.7882353067398071, 90)])
    doc = _old_style([_band("VectorialWave", [effect]), _band("Transient", [transient])])
    project = importing.place(
        edits.new_project(templates=False), hjif.FORMAT.read(_write(tmp_path, doc))
    )[0]
    hjif.FORMAT.write(project, tmp_path / "again.hjif")
    again = importing.place(
        edits.new_project(templates=False), hjif.FORMAT.read(tmp_path / "again.hjif")
    )[0]
    assert design_of(again) == design_of(project)


def test_transient_band_keyframes_become_emphasis(tmp_path):
    effect = _basis(200, [(0, 0.7, 155), (100, -0.5, 230), (100, 0.25)])
    result = hjif.FORMAT.read(_write(tmp_path, _old_style([_band("Transient", [effect])])))
    placed = [p for p in result.placements if isinstance(p.tile, GeneratorTile)]
    emphasis = [p.tile for p in placed]
    assert [p.start for p in placed] == pytest.approx([0.1, 0.15, 0.15])
    assert [t.param("amplitude") for t in emphasis] == [0.7, 0.5, 0.25]
    assert [t.param("frequency") for t in emphasis] == [0.5, 1.0, 0.5]  # none given: 0.5


def test_a_force_curve_plays_as_drive_torque(tmp_path):
    effect = _basis(0, [(0, 0.0), (1000, 0.5), (2000, -0.25)])
    doc = _old_style([_band("Curve", [effect], 0, 72)], modality="Force")
    doc["timescale"] = 1000
    project = importing.place(
        edits.new_project(templates=False), hjif.FORMAT.read(_write(tmp_path, doc))
    )[0]
    layer = mixer.render(project, 0.0, 2.0, 10_000.0)["drive"]
    full = 0.18  # N*m: the drive kind's full scale
    assert layer[[5000, 10_000, 15_000]] == pytest.approx([0.25 * full, 0.5 * full, 0.125 * full])


# --- export: valid against the schema, and round trips --------------------------------------------


def _design_project():
    design = VibrationDesign(
        ((0.0, 0.0), (0.1, 0.8), (0.1, 0.3), (0.4, 0.0)),
        ((0.05, 0.2), (0.3, 0.9)),
        (Emphasis(0.1, 0.9, 0.7), Emphasis(0.1, 0.4, 0.1), Emphasis(0.35, 0.6, 0.5)),
        0.4,
    )
    return place_design(edits.new_project(templates=False), design), design


def _with_force(project):
    project, track = edits.add_track(project, "drive", "force")
    project, tile = edits.add_tile(
        project, spline([(0, 0), (0.25, 0.6), (0.5, -0.2)], method="pchip")
    )
    project, _ = edits.add_clip(project, track, tile, 0.1)
    return project


def test_export_is_valid_against_the_schema(tmp_path):
    project = _with_force(_design_project()[0])
    hjif.FORMAT.write(project, tmp_path / "out.hjif")
    doc = json.loads((tmp_path / "out.hjif").read_text())
    jsonschema.Draft202012Validator(HJIF_SCHEMA).validate(doc)
    assert [p["perception_modality"] for p in doc["perceptions"]] == ["Vibrotactile", "Force"]
    bands = doc["perceptions"][0]["channels"][0]["bands"]
    assert [b["band_type"] for b in bands] == ["VectorialWave", "Transient"]
    # the step at 0.1 s stays two keyframes at one position; emphasis in whole Hz
    keyframes = bands[0]["effects"][0]["keyframes"]
    assert [k["relative_position"] for k in keyframes][:4] == [0, 2400, 4800, 4800]
    assert bands[1]["effects"][0]["keyframes"][1] == {
        "relative_position": 0,
        "amplitude_modulation": 0.4,
        "frequency_modulation": 95,
    }


def test_a_short_sine_clip_is_a_transient_and_a_long_one_force(tmp_path):
    project, track = edits.add_track(edits.new_project(templates=False), "drive")
    project, short = edits.add_tile(project, generator("sine", 0.02, amplitude=0.5, frequency=155))
    project, _ = edits.add_clip(project, track, short, 0.3)
    project, other = edits.add_track(project, "drive")
    project, long = edits.add_tile(project, generator("sine", 0.5, amplitude=0.5, frequency=5))
    project, _ = edits.add_clip(project, other, long, 0.0)
    hjif.FORMAT.write(project, tmp_path / "s.hjif")
    doc = json.loads((tmp_path / "s.hjif").read_text())
    vibration, force = doc["perceptions"]
    transient = vibration["channels"][0]["bands"][0]
    assert transient["band_type"] == "Transient"
    assert transient["effects"][0]["position"] == 0.3 * TIMESCALE
    assert transient["effects"][0]["keyframes"][0]["frequency_modulation"] == 155
    assert force["channels"][0]["bands"][0]["band_type"] == "Curve"


def test_the_schema_refuses_what_the_reference_reader_refuses():
    validator = jsonschema.Draft202012Validator(HJIF_SCHEMA)
    doc = _old_style([_band("VectorialWave", [_basis(0, [(0, 0.5, 100)])])])
    assert not validator.is_valid(doc)  # version "1", mixing_weight, curve_type on a wave band


def test_a_design_round_trips_within_a_tick_and_a_hertz(tmp_path):
    project, design = _design_project()
    hjif.FORMAT.write(project, tmp_path / "d.hjif")
    back = design_of(
        importing.place(edits.new_project(templates=False), hjif.FORMAT.read(tmp_path / "d.hjif"))[
            0
        ]
    )
    _check_bounds(design, back)


def test_design_and_force_come_back_on_their_own_tracks(tmp_path):
    project = _with_force(_design_project()[0])
    hjif.FORMAT.write(project, tmp_path / "m.hjif")
    back = importing.place(
        edits.new_project(templates=False), hjif.FORMAT.read(tmp_path / "m.hjif")
    )[0]
    assert [t.name for t in back.tracks] == ["drive", "Emphasis", "drive (force)"]
    force = next(t for t in back.tracks if t.name.endswith("(force)"))
    original = next(t for t in project.tracks if t.name == "force")
    a = mixer.render(project, 0.0, 0.7, 10_000.0, tracks=[original.id])["drive"]
    b = mixer.render(back, 0.0, 0.7, 10_000.0, tracks=[force.id])["drive"]
    assert np.max(np.abs(a - b)) <= FORCE_TOLERANCE * 0.18 + 1e-12


def _knots(d: VibrationDesign) -> np.ndarray:
    return np.array(sorted({t for t, _ in d.amplitude + d.frequency}))


def _shift_error(fn, a: VibrationDesign, b: VibrationDesign) -> float:
    """Largest difference at the breakpoints of either design, allowing either one tick of time
    (both read up to the earlier of their ends: an end moved to its tick is not a difference; a
    step of zero width, as where one AHAP event ends at the instant the next starts, is matched
    a tick away)."""
    t = np.minimum(np.union1d(_knots(a), _knots(b)), min(a.duration, b.duration))
    if len(t) == 0:
        return 0.0
    shifts = (-TICK, 0, TICK)
    b_moved = [np.abs(fn(a, t) - fn(b, t + s)) for s in shifts]
    a_moved = [np.abs(fn(a, t + s) - fn(b, t)) for s in shifts]
    return float(np.max(np.min(b_moved + a_moved, axis=0)))


def _check_bounds(a: VibrationDesign, b: VibrationDesign) -> None:
    """b is a read back through .hjif: the same breakpoints and emphasis, times to the nearest
    tick, amplitudes bit-exact, frequencies to whole Hz; zero-amplitude breakpoints may be added
    (where the frequency envelope reaches outside the amplitude envelope); no frequency envelope
    comes back as 0.5 at the start."""
    extra = list(b.amplitude)
    for t0, v0 in a.amplitude:
        while extra and not (abs(extra[0][0] - t0) <= TIME_BOUND and extra[0][1] == v0):
            assert extra[0][1] == 0.0, (t0, v0, extra[0])
            extra.pop(0)
        assert extra, (t0, v0)
        extra.pop(0)
    assert all(v == 0.0 for _, v in extra)
    frequency = a.frequency or ((a.amplitude[0][0] if a.amplitude else 0.0, 0.5),)
    assert len(b.frequency) == len(frequency) or not a.amplitude
    for (t0, f0), (t1, f1) in zip(frequency, b.frequency, strict=False):
        assert abs(t1 - t0) <= TIME_BOUND and abs(f1 - f0) <= HZ_BOUND
    assert len(b.emphasis) == len(a.emphasis)
    for e0, e1 in zip(a.emphasis, b.emphasis, strict=True):
        assert abs(e1.time - e0.time) <= TIME_BOUND and e1.amplitude == e0.amplitude
        assert abs(e1.frequency - e0.frequency) <= HZ_BOUND


def test_corpus_haptic_through_hjif_stays_within_the_bounds(corpus, tmp_path, registered):
    checked = 0
    for path in sorted(corpus.glob("*/*.haptic")):
        try:
            project = _read(path)
        except FormatError:
            continue  # files .haptic import refuses (tests/importers/test_vibration_formats.py)
        exporting.export_project(project, tmp_path / "x.hjif")
        jsonschema.Draft202012Validator(HJIF_SCHEMA).validate(
            json.loads((tmp_path / "x.hjif").read_text())
        )
        _check_bounds(design_of(project), design_of(_read(tmp_path / "x.hjif")))
        checked += 1
    assert checked >= 50


def test_corpus_ahap_through_hjif_exports_the_same_ahap(corpus, tmp_path, registered):
    checked = 0
    for path in sorted(corpus.glob("*/*.ahap")):
        try:
            project = _read(path)
        except FormatError:
            continue
        exporting.export_project(project, tmp_path / "x.hjif")
        exporting.export_project(project, tmp_path / "direct.ahap")
        exporting.export_project(_read(tmp_path / "x.hjif"), tmp_path / "via.ahap")
        a, b = design_of(_read(tmp_path / "direct.ahap")), design_of(_read(tmp_path / "via.ahap"))
        assert _shift_error(VibrationDesign.amplitude_at, a, b) <= AHAP_BOUND, path.name
        assert _shift_error(VibrationDesign.frequency_at, a, b) <= AHAP_BOUND, path.name
        assert [e.amplitude for e in a.emphasis] == [e.amplitude for e in b.emphasis], path.name
        pairs = zip(a.emphasis, b.emphasis, strict=True)
        assert all(abs(x.time - y.time) <= TIME_BOUND for x, y in pairs), path.name
        checked += 1
    assert checked >= 10


# --- registration and hostile input ---------------------------------------------------------------


def test_an_apple_style_ahap_keeps_its_sharpness_convention(tmp_path, registered):
    project = _read(ROOT / "tests" / "data" / "apple_style.ahap")
    exporting.export_project(project, tmp_path / "a.hjif")
    doc = json.loads((tmp_path / "a.hjif").read_text())
    assert "sharpness = frequency" in doc["perceptions"][0]["description"]
    back = _read(tmp_path / "a.hjif")
    tiles = [back.tile(c.tile_id) for t in back.tracks for c in t.clips]
    assert [t.sharpness for t in tiles if isinstance(t, VibrationTile)] == ["linear"]


def test_pyproject_registers_the_format():
    entry = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["entry-points"]
    assert entry["haptic_timeline.importers"]["hjif"] == "importers.hjif:FORMAT"


def test_the_suffix_picks_the_format(registered):
    assert writer_for("a.HJIF") is hjif.FORMAT
    assert readers_for("b.hjif") == [hjif.FORMAT]


hjif_like = st.fixed_dictionaries(
    {
        "timescale": st.one_of(st.integers(-5, 50_000), st.floats(), st.just("1000")),
        "perceptions": st.lists(
            st.fixed_dictionaries(
                {
                    "perception_modality": st.sampled_from(["Vibrotactile", "Force", "Wind", 3]),
                    "effect_library": st.just([])
                    | st.lists(
                        st.dictionaries(st.sampled_from(["id", "keyframes"]), st.integers(-2, 2)),
                        max_size=2,
                    ),
                    "channels": st.lists(
                        st.fixed_dictionaries(
                            {
                                "bands": st.lists(
                                    st.fixed_dictionaries(
                                        {
                                            "band_type": st.sampled_from(
                                                [
                                                    "VectorialWave",
                                                    "Transient",
                                                    "Curve",
                                                    "WaveletWave",
                                                    None,
                                                ]
                                            ),
                                            "curve_type": st.sampled_from(["Linear", "Cubic", 1]),
                                            "effects": st.lists(
                                                st.fixed_dictionaries(
                                                    {
                                                        "effect_type": st.sampled_from(
                                                            ["Basis", "Reference", "Composite"]
                                                        ),
                                                        "position": st.integers(-10, 10**9)
                                                        | st.floats(),
                                                        "id": st.integers(-1, 2),
                                                        "keyframes": st.lists(
                                                            st.dictionaries(
                                                                st.sampled_from(
                                                                    [
                                                                        "relative_position",
                                                                        "amplitude_modulation",
                                                                        "frequency_modulation",
                                                                    ]
                                                                ),
                                                                st.integers(-3, 70_000)
                                                                | st.floats()
                                                                | st.text(max_size=2)
                                                                | st.none(),
                                                            ),
                                                            max_size=5,
                                                        ),
                                                    }
                                                ),
                                                max_size=3,
                                            ),
                                        }
                                    ),
                                    max_size=3,
                                )
                            }
                        ),
                        max_size=2,
                    ),
                }
            ),
            max_size=2,
        ),
    }
)


@settings(
    max_examples=40,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(hjif_like)
def test_malformed_hjif_is_one_sentence(tmp_path, doc):
    path = tmp_path / "fuzz.hjif"
    path.write_text(json.dumps(doc))
    try:
        result = hjif.FORMAT.read(path)
    except FormatError as exc:
        assert str(exc) and "\n" not in str(exc) and "Traceback" not in str(exc)
    else:
        assert isinstance(result, Imported) and result.placements


@pytest.mark.parametrize(
    ("text", "reason"),
    [
        ("{", "is not an .hjif file (it is not valid JSON)"),
        ("[1]", "has no perceptions list"),
        ('{"perceptions": []}', "holds no vibration or force effect"),
        (
            '{"perceptions": [{"perception_modality": "Wind", "channels": []}]}',
            "holds no vibration",
        ),
        ('{"perceptions": [7]}', "perception 1 is not an object"),
        ('{"timescale": 0, "perceptions": []}', "the timescale must be between 1"),
    ],
)
def test_refusals_say_why_in_one_sentence(tmp_path, text, reason):
    path = tmp_path / "bad.hjif"
    path.write_text(text)
    with pytest.raises(FormatError, match=reason.replace("(", r"\(").replace(")", r"\)")):
        hjif.FORMAT.read(path)
