"""Track kinds used on both axes: damping and mass.

Their full scales are what the default device renders, so a full-scale clip is felt: damping
0.2 N*m*s/rad is the default sim's damping limit (0.20021 N*m*s/rad, about 2J/T with rotor
inertia J = 1e-5 kg*m^2 and servo period T = 100 us; `timeline.limits.servo.damping_limit` with
`open_device("sim").info`), and mass 2.8e-5 kg*m^2 sits just inside its stable mass band (-1e-5
to 2.8755e-5 kg*m^2, `timeline.limits.servo.mass_limits`). Up to schema 4 project files they
were 1e-4 N*m*s/rad and 1e-5 kg*m^2; loading an older file pins its damping and mass tracks of
the default full scale to those values (timeline.files.projectfile).
"""

from math import pi

from timeline.plugins.track_kinds import TrackKind

DAMPING = TrackKind(
    id="damping",
    label="Damping",
    si_unit="N*m*s/rad",
    display_unit="mNm*s/deg",
    display_scale=1e3 * pi / 180.0,
    colour="#5fad56",
    full_scale=0.2,
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
    full_scale=2.8e-5,
    axes=("time", "position"),
    term="m",
    description="Virtual inertia: -m*theta_ddot.",
)
