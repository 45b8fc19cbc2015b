"""Context track kinds: material to design against, never part of the haptic output."""

from timeline.plugins.track_kinds import TrackKind

AUDIO = TrackKind(
    id="audio",
    label="Audio",
    si_unit="FS",
    display_unit="FS",
    display_scale=1.0,
    colour="#6c757d",
    full_scale=1.0,
    axes=("time",),
    term="",
    description=(
        "The source sound, for reference: drawn as a waveform and played through the sound card "
        "with the haptics, never mixed into the torque law or exported as haptics."
    ),
    context=True,
)
