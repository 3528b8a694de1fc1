"""The description of ``test_mounts.py``: its TOML text and its test values.

A two-axle carrier with a telescopic boom (the inner section ``tele`` a slider on the boom, held
at the extension ``l_tele`` by its locked extension cylinder, a stiff spring), a cab on two
mounts (bounce and pitch, end stops) and a suspension seat (a slider on the cab with end stops)
carrying the seat point S. Round test numbers, not a real machine.
"""

from __future__ import annotations

#: Point coordinates (x, y) [m] in the chassis frame at p = 0, relative to H (the telescope's
#: points at zero extension).
POINTS: dict[str, tuple[float, float]] = {
    "A": (1.4, -0.5),
    "B": (-1.2, -0.5),
    "C": (-0.4, 0.3),
    "D": (-1.0, 1.2),
    "M": (0.3, 0.8),
    "N": (1.0, 0.0),
    "E": (0.2, 1.1),
    "G": (0.4, 1.3),
    "L": (0.6, 1.35),
    "T": (1.2, 1.4),
    "F": (0.9, 0.85),
    "R": (-0.5, 0.85),
    "Z": (0.25, 1.5),
    "W": (0.3, 1.0),
    "Y": (0.32, 1.25),
    "S": (0.35, 1.3),
}

#: The other parameter values (SI units); the static loads are completed by the derivation.
VALUES: dict[str, float] = {
    "m_1": 5000.0,
    "J_1": 6000.0,
    "m_2": 600.0,
    "J_2": 500.0,
    "m_tele": 200.0,
    "J_tele": 60.0,
    "m_cab": 450.0,
    "J_cab": 220.0,
    "m_seat": 110.0,  # seat top with an 80 kg occupant
    "J_seat": 6.0,
    "g": 9.80665,
    **{f"k_{a}x": 4.0e5 for a in "AB"},
    **{f"k_{a}y": 8.0e5 for a in "AB"},
    **{f"c_{a}x": 2.0e3 for a in "AB"},
    **{f"c_{a}y": 4.0e3 for a in "AB"},
    "mu_road": 0.7,
    "F_transition": 100.0,
    "tau_slip": 0.02,
    "k_tele": 5.0e7,
    "c_tele": 2.0e4,
    "k_cab_F": 9.0e4,
    "c_cab_F": 2.0e3,
    "s_min_cab_F": -0.02,
    "s_max_cab_F": 0.02,
    "k_stop_cab_F": 2.0e6,
    "c_stop_cab_F": 5.0e3,
    "k_cab_R": 7.0e4,
    "c_cab_R": 1.8e3,
    "s_min_cab_R": -0.02,
    "s_max_cab_R": 0.02,
    "k_stop_cab_R": 2.0e6,
    "c_stop_cab_R": 5.0e3,
    "k_seat": 1.3e4,  # about 1.7 Hz with the 110 kg on it
    "c_seat": 9.0e2,
    "s_min_seat": -0.045,
    "s_max_seat": 0.045,
    "k_stop_seat": 3.0e5,
    "c_stop_seat": 1.0e3,
    "l_tele": 0.8,
}

_PARAMETERS = "\n".join(
    f'{name} = {{ unit = "{unit}", description = "{name}", source = "test" }}'
    for name, unit in [
        ("m_1", "kg"), ("J_1", "kg*m^2"), ("m_2", "kg"), ("J_2", "kg*m^2"),
        ("m_tele", "kg"), ("J_tele", "kg*m^2"), ("m_cab", "kg"), ("J_cab", "kg*m^2"),
        ("m_seat", "kg"), ("J_seat", "kg*m^2"), ("g", "m/s^2"),
        *((f"{k}_{a}{x}", u) for a in "AB" for k, u in (("k", "N/m"), ("c", "N*s/m"))
          for x in "xy"),
        ("mu_road", "-"), ("F_transition", "N"), ("tau_slip", "s"),
        ("k_tele", "N/m"), ("c_tele", "N*s/m"),
        *((f"{k}_{e}", u) for e in ("cab_F", "cab_R", "seat")
          for k, u in (("k", "N/m"), ("c", "N*s/m"), ("s_min", "m"), ("s_max", "m"),
                       ("k_stop", "N/m"), ("c_stop", "N*s/m"))),
        ("l_tele", "m"),
    ]
)  # fmt: skip

#: Each axle's tyre road geometry (free radius and tandem cam), as in the three-axle fixture.
_TYRES = "\n".join(
    f'{prefix}_{axle} = {{ unit = "{unit}", description = "{text}", range = {bounds}, '
    'source = "test" }'
    for axle in "AB"
    for prefix, unit, text, bounds in (
        ("R", "m", "free tyre radius", "[0.2, 1.0]"),
        ("ae", "-", "cam half-length a_e / R", "[1.0, 1.3]"),
        ("be", "-", "cam half-height b_e / R", "[1.0, 1.05]"),
        ("ce", "-", "cam exponent c_e", "[1.5, 2.0]"),
        ("ls", "-", "cam spacing l_s / 2a", "[0.4, 0.83]"),
    )
)

DESCRIPTION = f"""\
# Test fixture (tests/derive/test_mounts.py): a telescopic boom held by its cylinder, a cab on
# two mounts with end stops and a suspension seat with end stops. Round test numbers.

[machine]
name = "mounted_cab"
title = "carrier with a telescopic boom, a cab on two mounts and a suspension seat (test)"

[bodies.chassis]
joint = "free"
reference = "H"
coordinates = ["x_H", "y_H", "theta_1"]
mass = "m_1"
inertia = "J_1"

[bodies.chassis.points]
A = "front axle"
B = "rear axle"
C = "lift-cylinder base"
D = "boom pivot"
M = "cab reference"
N = "second accelerometer"

[bodies.boom]
joint = "pin"
parent = "chassis"
at = "D"
coordinate = "theta_2"
joint_angle = "phi"
mass = "m_2"
inertia = "J_2"
centre_of_gravity = "G"
points = {{ E = "lift-cylinder rod end", G = "centre of gravity of the outer boom", L = "telescope guide" }}

[bodies.tele]
joint = "slider"
label = "telescope"
parent = "boom"
at = "L"
direction = [1.0, 0.1]
coordinate = "s_tele"
extension = "l_tele"
mass = "m_tele"
inertia = "J_tele"
centre_of_gravity = "T"
points = {{ T = "centre of gravity of the inner section and load" }}

[bodies.cab]
joint = "two_mounts"
parent = "chassis"
at = "M"
direction = [0.0, 1.0]
coordinates = ["s_cab", "theta_cab"]
mounts = ["F", "R"]
end_stops = true
mass = "m_cab"
inertia = "J_cab"
centre_of_gravity = "Z"
points = {{ F = "front mount", R = "rear mount", Z = "centre of gravity of the cab", W = "seat base" }}

[bodies.seat]
joint = "slider"
label = "suspension seat"
parent = "cab"
at = "W"
direction = [0.0, 1.0]
coordinate = "s_seat"
end_stops = true
mass = "m_seat"
inertia = "J_seat"
centre_of_gravity = "Y"
points = {{ Y = "centre of gravity of seat top and occupant", S = "seat reference point" }}

[[axles]]
point = "A"

[[axles]]
point = "B"

[actuators.lift]
kind = "driven"
base = "C"
rod = "E"

[sensors.H]
axes = ["x", "y"]

[sensors.N]
axes = ["y"]

[sensors.S]
axes = ["x", "y"]
label = "the seat S"

[parameters]
{_PARAMETERS}

[tyres]
{_TYRES}
"""
