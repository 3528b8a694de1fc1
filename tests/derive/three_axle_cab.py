"""The third description of ``test_three_axle_cab.py``: its TOML text and its test values.

Three axles (A front, B middle, R rear) under a chassis, a boom pinned at D and lifted by the
cylinder C -> E, and a cab on a vertical sliding mount at M with a spring-damper (a suspended
cab), the seat S on the cab. Round test numbers, not a real machine.
"""

from __future__ import annotations

#: Point coordinates (x, y) [m] in the chassis frame at p = 0, relative to H.
POINTS: dict[str, tuple[float, float]] = {
    "A": (1.6, -0.55),
    "B": (0.1, -0.55),
    "R": (-1.4, -0.55),
    "C": (-0.3, 0.2),
    "D": (-1.1, 1.3),
    "M": (0.5, 0.9),
    "N": (1.2, 0.0),
    "E": (0.5, 1.0),
    "G": (0.9, 1.1),
    "Z": (0.5, 1.7),
    "S": (0.6, 1.2),
}

#: The other parameter values (SI units); the static loads are completed by the derivation.
VALUES: dict[str, float] = {
    "m_1": 7000.0,
    "J_1": 9000.0,
    "m_2": 900.0,
    "J_2": 700.0,
    "m_cab": 500.0,
    "J_cab": 250.0,
    "g": 9.80665,
    **{f"k_{a}x": 4.0e5 for a in "ABR"},
    **{f"k_{a}y": 8.0e5 for a in "ABR"},
    **{f"c_{a}x": 2.0e3 for a in "ABR"},
    **{f"c_{a}y": 4.0e3 for a in "ABR"},
    "mu_road": 0.7,
    "F_transition": 100.0,
    "tau_slip": 0.02,
    "k_cab": 6.0e4,
    "c_cab": 1.5e3,
}

DESCRIPTION = """\
# Test fixture (tests/derive/test_three_axle_cab.py): a three-axle carrier with a boom on a pin
# and a cab on a vertical sliding mount with a spring-damper (a suspended cab). Not a machine of
# derive/machines; values are round test numbers.

[machine]
name = "three_axle_cab"
title = "three-axle carrier with a suspended cab (test fixture)"
point_range = [-10.0, 10.0]

[bodies.chassis]
joint = "free"
reference = "H"
coordinates = ["x_H", "y_H", "theta_1"]
mass = "m_1"
inertia = "J_1"

[bodies.chassis.points]
A = "front axle"
B = "middle axle"
R = "rear axle"
C = "lift-cylinder base"
D = "boom pivot"
M = "cab mount"
N = "second accelerometer ahead of H"

[bodies.boom]
joint = "pin"
parent = "chassis"
at = "D"
coordinate = "theta_2"
joint_angle = "phi"
mass = "m_2"
inertia = "J_2"
centre_of_gravity = "G"
points = { E = "lift-cylinder rod end", G = "centre of gravity of the boom" }

[bodies.cab]
joint = "slider"
label = "cab"
parent = "chassis"
at = "M"
direction = [0.0, 1.0]
coordinate = "s_cab"
mass = "m_cab"
inertia = "J_cab"
centre_of_gravity = "Z"
points = { Z = "centre of gravity of the cab", S = "seat reference point" }

[[axles]]
point = "A"

[[axles]]
point = "B"

[[axles]]
point = "R"

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
m_1 = { unit = "kg", description = "chassis mass", range = [100.0, 1e5], source = "test" }
J_1 = { unit = "kg*m^2", description = "chassis inertia about H", range = [10.0, 1e6], source = "test" }
m_2 = { unit = "kg", description = "boom mass", range = [10.0, 1e5], source = "test" }
J_2 = { unit = "kg*m^2", description = "boom inertia about G", range = [1.0, 1e6], source = "test" }
m_cab = { unit = "kg", description = "cab mass", range = [10.0, 1e4], source = "test" }
J_cab = { unit = "kg*m^2", description = "cab inertia about Z", range = [1.0, 1e5], source = "test" }
g = { unit = "m/s^2", description = "gravity", range = [0.0, 10.0], source = "test" }
k_Ax = { unit = "N/m", description = "tyre", source = "test" }
k_Ay = { unit = "N/m", description = "tyre", source = "test" }
c_Ax = { unit = "N*s/m", description = "tyre", source = "test" }
c_Ay = { unit = "N*s/m", description = "tyre", source = "test" }
k_Bx = { unit = "N/m", description = "tyre", source = "test" }
k_By = { unit = "N/m", description = "tyre", source = "test" }
c_Bx = { unit = "N*s/m", description = "tyre", source = "test" }
c_By = { unit = "N*s/m", description = "tyre", source = "test" }
k_Rx = { unit = "N/m", description = "tyre", source = "test" }
k_Ry = { unit = "N/m", description = "tyre", source = "test" }
c_Rx = { unit = "N*s/m", description = "tyre", source = "test" }
c_Ry = { unit = "N*s/m", description = "tyre", source = "test" }
mu_road = { unit = "-", description = "friction", source = "test" }
F_transition = { unit = "N", description = "contact transition", source = "test" }
tau_slip = { unit = "s", description = "anchor relaxation", source = "test" }
k_cab = { unit = "N/m", description = "cab mount stiffness", source = "test" }
c_cab = { unit = "N*s/m", description = "cab mount damping", source = "test" }
F_Ay0 = { unit = "N", description = "static load A", source = "computed" }
F_By0 = { unit = "N", description = "static load B", source = "computed" }
F_Ry0 = { unit = "N", description = "static load R", source = "computed" }
F_cab0 = { unit = "N", description = "static cab mount force", source = "computed" }

[tyres]
R_A = { unit = "m", description = "free tyre radius", range = [0.2, 1.0], source = "test" }
ae_A = { unit = "-", description = "cam half-length a_e / R", range = [1.0, 1.3], source = "test" }
be_A = { unit = "-", description = "cam half-height b_e / R", range = [1.0, 1.05], source = "test" }
ce_A = { unit = "-", description = "cam exponent c_e", range = [1.5, 2.0], source = "test" }
ls_A = { unit = "-", description = "cam spacing l_s / 2a", range = [0.4, 0.83], source = "test" }
R_B = { unit = "m", description = "free tyre radius", range = [0.2, 1.0], source = "test" }
ae_B = { unit = "-", description = "cam half-length a_e / R", range = [1.0, 1.3], source = "test" }
be_B = { unit = "-", description = "cam half-height b_e / R", range = [1.0, 1.05], source = "test" }
ce_B = { unit = "-", description = "cam exponent c_e", range = [1.5, 2.0], source = "test" }
ls_B = { unit = "-", description = "cam spacing l_s / 2a", range = [0.4, 0.83], source = "test" }
R_R = { unit = "m", description = "free tyre radius", range = [0.2, 1.0], source = "test" }
ae_R = { unit = "-", description = "cam half-length a_e / R", range = [1.0, 1.3], source = "test" }
be_R = { unit = "-", description = "cam half-height b_e / R", range = [1.0, 1.05], source = "test" }
ce_R = { unit = "-", description = "cam exponent c_e", range = [1.5, 2.0], source = "test" }
ls_R = { unit = "-", description = "cam spacing l_s / 2a", range = [0.4, 0.83], source = "test" }
"""
