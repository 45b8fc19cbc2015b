"""Track kinds used only on the position axis (Equation 1)."""

from timeline.plugins.track_kinds import TrackKind

TORQUE = TrackKind(
    id="torque",
    label="Torque",
    si_unit="N*m",
    display_unit="mNm",
    display_scale=1e3,
    colour="#f18f01",
    full_scale=0.18,
    axes=("position",),
    term="d",
    description="Torque as a function of angle: T(theta) (walls, detents).",
)
