"""Track kinds used only on the time axis (Equation 2)."""

from timeline.plugins.track_kinds import TrackKind

DRIVE = TrackKind(
    id="drive",
    label="Drive",
    si_unit="N*m",
    display_unit="mNm",
    display_scale=1e3,
    colour="#e4572e",
    full_scale=0.18,
    axes=("time",),
    term="d",
    description="Direct torque (or, on a vibrotactile device, fraction of full scale): d(t).",
)

STIFFNESS = TrackKind(
    id="stiffness",
    label="Stiffness",
    si_unit="N*m/rad",
    display_unit="mNm/deg",
    display_scale=1e3 * 3.141592653589793 / 180.0,
    colour="#2e86ab",
    full_scale=1.0,
    axes=("time",),
    term="k",
    description="Virtual spring about the anchor angle: -k(t)*theta.",
)
