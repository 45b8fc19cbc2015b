"""Track kinds used on both axes: damping and mass."""

from math import pi

from timeline.plugins.track_kinds import TrackKind

DAMPING = TrackKind(
    id="damping",
    label="Damping",
    si_unit="N*m*s/rad",
    display_unit="mNm*s/deg",
    display_scale=1e3 * pi / 180.0,
    colour="#5fad56",
    full_scale=1e-4,
    axes=("time", "position"),
    term="b",
    description="Virtual viscous damping: -b*theta_dot.",
)

MASS = TrackKind(
    id="mass",
    label="Mass",
    si_unit="kg*m^2",
    display_unit="g*cm^2",
    display_scale=1e7,
    colour="#9b5de5",
    full_scale=1e-5,
    axes=("time", "position"),
    term="m",
    description="Virtual inertia: -m*theta_ddot.",
)
