"""What a track kind is: the unit and full scale a layer gives to unitless tiles."""

from __future__ import annotations

from dataclasses import dataclass

from timeline import plugins

DEFAULT_KIND = "drive"  # the track kind an imported tile goes on unless the user picks another


@dataclass(frozen=True)
class TrackKind:
    """A layer's meaning: an id used in files and CSV headers, its SI unit and display unit."""

    id: str
    label: str
    si_unit: str
    display_unit: str
    display_scale: float  # display value = SI value * display_scale
    colour: str
    full_scale: float  # SI value of a tile sample of 1.0 at clip and track gain 1
    axes: tuple[str, ...]  # "time", "position"
    term: str  # which coefficient of the torque law: d, k, b or m ("" for a context track)
    description: str = ""
    # A context track (e.g. the source sound) is material to design against: drawn and played
    # for reference, never mixed into the torque law nor exported as haptics.
    context: bool = False


def track_kinds() -> dict[str, TrackKind]:
    """All registered track kinds by id."""
    return dict(plugins.load_group(plugins.TRACKS))


def track_kind(kind_id: str) -> TrackKind:
    """One track kind by id, or a PluginError naming the choices."""
    return plugins.get(plugins.TRACKS, kind_id)


def kinds_for_axis(axis: str) -> dict[str, TrackKind]:
    """The track kinds usable on a project axis."""
    return {k: v for k, v in track_kinds().items() if axis in v.axes}
