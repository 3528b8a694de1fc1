"""Simulate a custom road from a CSV file.

A road profile is a CSV file with a header ``distance [m],height [m]`` (units m, cm or mm). This
example writes one (a 3 cm speed bump, 0.5 m long, then a 2 cm pothole), drives the default
loader with the full bucket over it at 9 km/h with the pump holding the boom (the baseline), and
prints the seat's ISO 2631-1 values and the events of the run, and plots the seat's vertical
acceleration.

Run it from any folder: ``python docs/examples/custom_road_csv.py``; it writes ``bump.csv``,
``bump_run.csv`` (the time series with units) and ``bump_seat.png`` into the current folder.
"""

from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")  # files only, no window
import matplotlib.pyplot as plt

from loader_model.iso2631 import format_evaluation
from loader_model.plant.plant_parameters import plant_parameter_vector
from loader_model.simulation import read_road_csv
from loader_model.simulation.courses import Course, kmh_to_m_s
from loader_model.simulation.simulator import course_input, simulate

Path("bump.csv").write_text(
    """\
# a speed bump and a pothole
distance [m],height [cm]
0.0,0.0
10.0,0.0
10.25,3.0
10.5,0.0
20.0,0.0
20.1,-2.0
20.6,-2.0
20.7,0.0
30.0,0.0
""",
    encoding="utf-8",
)
profile = read_road_csv("bump.csv")
print(
    f"profile {profile.name}: {profile.distance_m.size} vertices over {profile.distance_m[-1]:.1f} m"
)

# Front axle 5 m before the profile's start at t = 0, 2 s of settling after the rear axle's last
# vertex.
course = Course(profile, speed_m_s=kmh_to_m_s(9.0), start_m=-5.0, settle_s=2.0, name="bump")
params = plant_parameter_vector(None, "full")
result = simulate(course_input(course, params), params)  # default controller: hold the boom

print(f"simulated {result.time_s[-1]:.2f} s, {result.time_s.size} rows")
print(format_evaluation(result.seat_evaluation()))
for event in result.events:
    print(event.describe())
result.write("bump_run.csv")

seat_z = result["f_Py"] - result["f_Py"][0]  # the seat pad under the occupant
assert np.all(np.isfinite(seat_z))
assert np.max(np.abs(seat_z)) > 0.1, "the bump must shake the seat"

figure, axis = plt.subplots(figsize=(7.5, 3.2))
axis.plot(result.time_s, seat_z, lw=1.0)
axis.set_xlabel("time t [s]")
axis.set_ylabel("seat vertical acceleration [m/s²]")
bump_s, pothole_s = ((x - course.start_m) / course.speed_m_s for x in (10.0, 20.0))
axis.set_title(
    f"Full bucket, 9 km/h: front axle on the bump at {bump_s:.0f} s, the pothole at {pothole_s:.0f} s"
)
axis.grid(True, alpha=0.3)
figure.tight_layout()
figure.savefig("bump_seat.png", dpi=100)
print("wrote bump_seat.png")
