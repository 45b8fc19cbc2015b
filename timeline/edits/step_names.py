"""Names for undo steps that say what changed, in the project's display units.

An edit's caller gives a short label ("move clip", "delete", "track gain"); comparing the states
before and after the step says what it did: "move 'detents copy' to 20°", "gain of 'tap' to
x0.2 (-14.0 dB)", "rename marker 'M1' to 'Lo'". Positions are in degrees in a position project
and seconds in a time project; a track's full scale in its kind's unit (mNm for torque). When
the change is not one of these (an import, a merge), the caller's label is the name.
"""

from __future__ import annotations

import math

from timeline.model import Clip, Project, Track
from timeline.plugins.track_kinds import track_kind

GENERIC_SUFFIXES = (" clips", " clip")


def step_name(label: str, before: Project | None, after: Project) -> str:
    """What a step changed, or its label when that cannot be said more exactly."""
    if before is None or before is after:
        return label
    for describe in (_variants, _clips, _tracks, _markers):
        name = describe(label, before, after)
        if name:
            return name
    return label


def place(u: float, axis: str) -> str:
    """A position or length as the ruler shows it: "20°" or "0.25 s"."""
    if axis == "time":
        return f"{u:.4g} s"
    return f"{math.degrees(u):.4g}°"


def shift_text(u: float, axis: str) -> str:
    """A signed distance: "+20°", "-0.1 s"."""
    return ("+" if u >= 0 else "-") + place(abs(u), axis)


def gain_text(gain: float) -> str:
    """x0.2 (-14.0 dB)."""
    if gain == 0:
        return "x0 (-inf dB)"
    return f"x{gain:.4g} ({20 * math.log10(abs(gain)):+.1f} dB)"


def _verb(label: str) -> str | None:
    """The verb of a generic label ("add clip" -> "add", "paste" -> "paste"), else None."""
    for suffix in GENERIC_SUFFIXES:
        label = label.removesuffix(suffix)
    return label if label and " " not in label else None


# --- variants -------------------------------------------------------------------------------


def _variants(label: str, before: Project, after: Project) -> str:
    if before.variants is after.variants and before.active_variant == after.active_variant:
        return ""
    old = {v.name for v in before.variants}
    new = {v.name for v in after.variants}
    if new - old:
        return "save variant " + ", ".join(sorted(new - old))
    if old - new:
        return "delete variant " + ", ".join(sorted(old - new))
    if after.active_variant != before.active_variant and after.active_variant:
        return f"switch to variant {after.active_variant}"
    if after.active_variant:
        return f"save variant {after.active_variant}"
    return ""


# --- clips ----------------------------------------------------------------------------------


def _replaced(before: Project, after: Project) -> tuple[dict, dict]:
    """Clips (with their tracks) that left and that arrived, by clip id: tracks the step did not
    touch are skipped, and a touched track's clips are compared by identity at C speed (a drag
    on a track of 10,000 clips names its step in about a millisecond)."""
    old_tracks = {t.id: t for t in before.tracks}
    new_tracks = {t.id: t for t in after.tracks}
    left: dict[str, tuple[Track, Clip]] = {}
    arrived: dict[str, tuple[Track, Clip]] = {}
    for track_id in old_tracks.keys() | new_tracks.keys():
        was, now = old_tracks.get(track_id), new_tracks.get(track_id)
        if was is now:
            continue
        old = dict(zip(map(id, was.clips), was.clips, strict=True)) if was else {}
        new = dict(zip(map(id, now.clips), now.clips, strict=True)) if now else {}
        for key in old.keys() - new.keys():
            left[old[key].id] = (was, old[key])  # type: ignore[assignment]
        for key in new.keys() - old.keys():
            arrived[new[key].id] = (now, new[key])  # type: ignore[assignment]
    return left, arrived


def _tile_name(project: Project, clip: Clip) -> str:
    tile = project.tiles.get(clip.tile_id)
    return f"'{tile.name}'" if tile is not None else "a clip"


def _clips(label: str, before: Project, after: Project) -> str:
    old, new = _replaced(before, after)
    added = [i for i in new if i not in old]
    removed = [i for i in old if i not in new]
    changed = [
        i for i in new if i in old and (new[i][1] != old[i][1] or new[i][0].id != old[i][0].id)
    ]
    if not (added or removed or changed):
        return ""
    axis, verb = after.axis, _verb(label)
    if changed and not added and not removed:
        if len(changed) == 1:
            (track, clip), (old_track, was) = new[changed[0]], old[changed[0]]
            return _one_clip(label, after, track, clip, old_track, was)
        shifts = {round(new[i][1].start - old[i][1].start, 12) for i in changed}
        if len(shifts) == 1:
            return f"{verb or 'move'} {len(changed)} clips by {shift_text(shifts.pop(), axis)}"
        return ""
    if verb is None:
        return ""
    if added and not removed and not changed:
        first = min((new[i] for i in added), key=lambda tc: tc[1].start)
        where = f" at {place(first[1].start, axis)} on '{first[0].name}'"
        what = _tile_name(after, first[1]) if len(added) == 1 else f"{len(added)} clips"
        return f"{verb} {what}{where}"
    if removed and not added and not changed:
        if len(removed) == 1:
            return f"{verb} {_tile_name(before, old[removed[0]][1])}"
        return f"{verb} {len(removed)} clips"
    if len(changed) == 1 and len(added) == 1 and not removed and verb == "split":
        at = place(new[added[0]][1].start, axis)
        return f"split {_tile_name(after, new[changed[0]][1])} at {at}"
    return ""


def _one_clip(
    label: str, project: Project, track: Track, clip: Clip, old_track: Track, was: Clip
) -> str:
    """One clip changed: say which of its numbers, in display units."""
    axis, name = project.axis, _tile_name(project, clip)
    fields = {f for f in Clip.__dataclass_fields__ if getattr(clip, f) != getattr(was, f)}
    if track.id != old_track.id:
        return f"move {name} to '{track.name}' at {place(clip.start, axis)}"
    if fields == {"start"}:
        return f"move {name} to {place(clip.start, axis)}"
    if "stretch" in fields:
        return f"stretch {name} to x{clip.stretch:.4g} ({place(clip.duration, axis)})"
    if (
        fields
        and fields <= {"start", "source_in", "source_out", "fade_in", "fade_out", "loop_phase"}
        and (fields & {"source_in", "source_out"})
    ):
        return f"trim {name} to {place(clip.start, axis)}–{place(clip.end, axis)}"
    if fields == {"gain"}:
        return f"gain of {name} to {gain_text(clip.gain)}"
    if fields == {"pivot"}:
        return f"mirror line of {name} at {clip.pivot:.3g} of full scale"
    if fields == {"reverse"}:
        return f"reverse {name}" if clip.reverse else f"play {name} forwards"
    if fields <= {"scale", "offset"} and fields:
        if clip.scale == -was.scale:
            return f"invert {name}"
        return f"amplitude of {name} to {gain_text(clip.scale)}"
    if fields and fields <= {"fade_in", "fade_out"}:
        return "; ".join(_fade(name, which, clip, was, axis) for which in sorted(fields))
    verb = _verb(label)
    return f"{verb} {name}" if verb else ""


def _fade(name: str, which: str, clip: Clip, was: Clip, axis: str) -> str:
    fade, old = getattr(clip, which), getattr(was, which)
    side = which.replace("_", " ")
    if fade.length != old.length:
        return f"{side} of {name} to {place(fade.length, axis)}"
    return f"{side} of {name} {fade.shape}"


# --- tracks ---------------------------------------------------------------------------------


def _tracks(label: str, before: Project, after: Project) -> str:
    if before.tracks is after.tracks:
        return ""
    old = {t.id: t for t in before.tracks}
    new = {t.id: t for t in after.tracks}
    if added := [new[i] for i in new if i not in old]:
        return f"add track '{added[0].name}'" if len(added) == 1 else f"add {len(added)} tracks"
    if removed := [old[i] for i in old if i not in new]:
        return f"remove track '{removed[0].name}'" if len(removed) == 1 else ""
    if list(old) != list(new):
        moved = next(i for i, j in zip(new, old, strict=True) if i != j)
        return f"move track '{new[moved].name}' to place {list(new).index(moved) + 1}"
    changed = [(old[i], new[i]) for i in new if new[i] is not old[i]]
    if len(changed) != 1:
        return ""
    was, track = changed[0]
    if track.name != was.name:
        return f"rename track '{was.name}' to '{track.name}'"
    if track.gain != was.gain:
        return f"gain of '{track.name}' to {gain_text(track.gain)}"
    if track.mute != was.mute:
        return f"{'mute' if track.mute else 'unmute'} '{track.name}'"
    if track.solo != was.solo:
        return f"{'solo' if track.solo else 'unsolo'} '{track.name}'"
    if track.full_scale != was.full_scale:
        kind = track_kind(track.kind)
        scale = kind.full_scale if track.full_scale is None else track.full_scale
        return (
            f"full scale of '{track.name}' to {scale * kind.display_scale:.4g} {kind.display_unit}"
        )
    return ""


# --- markers and the loop -------------------------------------------------------------------


def _markers(label: str, before: Project, after: Project) -> str:
    axis = after.axis
    if before.loop != after.loop:
        if after.loop is None:
            return "clear the loop region"
        return f"loop {place(after.loop.start, axis)}–{place(after.loop.stop, axis)}"
    old, new = before.markers, after.markers
    if old == new:
        return ""
    if len(new) == len(old) + 1:
        added = next(m for m in new if m not in old)
        return f"add marker '{added.name}' at {place(added.at, axis)}"
    if len(new) + 1 == len(old):
        gone = next(m for m in old if m not in new)
        return f"delete marker '{gone.name}'"
    if len(new) == len(old):
        by_name_old = {m.name: m for m in old}
        for m in new:
            if m.name in by_name_old and by_name_old[m.name].at != m.at:
                return f"move marker '{m.name}' to {place(m.at, axis)}"
        renamed = [
            (a, b) for a, b in zip(sorted(old, key=lambda m: m.at), new, strict=True) if a != b
        ]
        if len(renamed) == 1:
            return f"rename marker '{renamed[0][0].name}' to '{renamed[0][1].name}'"
    return ""
