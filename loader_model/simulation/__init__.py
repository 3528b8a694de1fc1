"""Roads and courses: what the ground under each axle does during a drive.

- :mod:`~loader_model.simulation.roads`: piecewise-linear ground profiles h(s), boards.
- :mod:`~loader_model.simulation.envelope`: exact rigid-wheel enveloping filter (effective height
  and slope under an axle) and the horizontal road input it implies.
- :mod:`~loader_model.simulation.tandem_cam`: Schmeitz's tandem elliptical cam, the default road
  of a tyre that envelops obstacles shorter than its contact patch (one cam's exact height:
  :mod:`~loader_model.simulation.cam_envelope`; figure: :mod:`~loader_model.simulation.
  envelope_plot`).
- :mod:`~loader_model.simulation.iso8608`: ISO 8608 random roads by class from a seed, PSD check.
- :mod:`~loader_model.simulation.road_csv`: profiles from and to CSV files with units.
- :mod:`~loader_model.simulation.travel`: the plant's road input w(t), ẇ(t) per axle as a table.
- :mod:`~loader_model.simulation.courses`: the paper's course, boards at any speed, spacing,
  height and length, the Fig. 10 single obstacle.
- :mod:`~loader_model.simulation.obstacles`: obstacle lists of your own, from TOML course files.
- :mod:`~loader_model.simulation.road_plot`: figure of a course (matplotlib, lazily).

The closed loop (imported from their modules, not here, so that this package stays free of
CasADi at import):

- :mod:`~loader_model.simulation.controllers`: the controller interface, ``hold_controller``.
- :mod:`~loader_model.simulation.stepper`: one 1 ms period (ROS2), JIT-compiled.
- :mod:`~loader_model.simulation.simulator`: ``simulate`` over a road input, ``course_input``.
- :mod:`~loader_model.simulation.result`, :mod:`~loader_model.simulation.events`: the labelled
  time series with units and events, CSV and NPZ.
- :mod:`~loader_model.simulation.validity`, :mod:`~loader_model.simulation.validity_check`: the
  model's range of validity (tip-over pitch, boom angle, time in the air, seat acceleration) and
  the stop of a run that leaves it (``ModelValidityError`` with the rows up to it).
- :mod:`~loader_model.simulation.reference`: CVODES reference at rtol 1e-10 (for the tests).
- :mod:`~loader_model.simulation.seat_plot`: figure of the seat accelerations.
"""

from __future__ import annotations

from loader_model.simulation.courses import (
    BOARD_HEIGHT_M,
    BOARD_WIDTH_M,
    FIG10_SPEED_KMH,
    LEAD_IN_M,
    PAPER_BOARD_COUNT,
    PAPER_SPACING_M,
    Course,
    board_course_at,
    iso8608_course,
    kmh_to_m_s,
    paper_course,
    single_obstacle_course,
)
from loader_model.simulation.envelope import EffectiveRoad, edge_contact_length, effective_road
from loader_model.simulation.iso8608 import (
    CLASS_PSD_M3,
    ISO8608_BAND_CYCLES_M,
    REFERENCE_SPATIAL_FREQUENCY_CYCLES_M,
    WAVINESS,
    classify_psd,
    displacement_psd,
    estimate_psd,
    iso8608_profile,
    profile_variance,
)
from loader_model.simulation.obstacles import (
    CourseFileError,
    Obstacle,
    load_course_file,
    obstacle_course,
    obstacle_profile,
)
from loader_model.simulation.road_csv import RoadFileError, read_road_csv, write_road_csv
from loader_model.simulation.road_plot import plot_course
from loader_model.simulation.roads import RoadProfile, board_course, flat_road, single_board
from loader_model.simulation.tandem_cam import (
    DEFAULT_ENVELOPE,
    ENVELOPES,
    TandemCam,
    TandemCamRoad,
    tandem_cam_road,
)
from loader_model.simulation.travel import (
    DEFAULT_SAMPLE_RATE_HZ,
    DEFAULT_TYRE_RADIUS_M,
    ROAD_NAMES,
    RoadInput,
    road_input,
)

__all__ = [
    "BOARD_HEIGHT_M",
    "BOARD_WIDTH_M",
    "CLASS_PSD_M3",
    "DEFAULT_ENVELOPE",
    "DEFAULT_SAMPLE_RATE_HZ",
    "DEFAULT_TYRE_RADIUS_M",
    "ENVELOPES",
    "FIG10_SPEED_KMH",
    "ISO8608_BAND_CYCLES_M",
    "LEAD_IN_M",
    "PAPER_BOARD_COUNT",
    "PAPER_SPACING_M",
    "REFERENCE_SPATIAL_FREQUENCY_CYCLES_M",
    "ROAD_NAMES",
    "WAVINESS",
    "Course",
    "CourseFileError",
    "EffectiveRoad",
    "Obstacle",
    "RoadFileError",
    "RoadInput",
    "RoadProfile",
    "TandemCam",
    "TandemCamRoad",
    "board_course",
    "board_course_at",
    "classify_psd",
    "displacement_psd",
    "edge_contact_length",
    "effective_road",
    "estimate_psd",
    "flat_road",
    "iso8608_course",
    "iso8608_profile",
    "kmh_to_m_s",
    "load_course_file",
    "obstacle_course",
    "obstacle_profile",
    "paper_course",
    "plot_course",
    "profile_variance",
    "read_road_csv",
    "road_input",
    "single_board",
    "single_obstacle_course",
    "tandem_cam_road",
    "write_road_csv",
]
