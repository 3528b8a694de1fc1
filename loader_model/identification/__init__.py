"""Parameter identification from measurements (paper section 4.1, Eq. 44-48, Tables 4, 5).

Modules, one job each:

- :mod:`.measurement`: the CSV measurement format (units in the header), reading and writing;
- :mod:`.derivatives`: Savitzky-Golay smoothing and derivatives, window from the sample rate;
- :mod:`.equivalent`: both lift cylinders as one equivalent cylinder with its load (F_L, m_eq);
- :mod:`.chassis`: the cylinder force that moves the boom on the moving chassis, from the
  chassis sensors and the generated model (Eq. 44 exact on a machine on tyres);
- :mod:`.regression`: least squares and robust (Tukey bisquare IRLS) fits, R², s, intervals;
- :mod:`.friction`: seal friction, Eq. 44 (sign corrected) and Eq. 46 by variable projection;
- :mod:`.leakage`: leakage and compressibility, Eq. 48 by robust regression;
- :mod:`.pipeline`: from a record to the two regressions;
- :mod:`.lift_test`: Tables 4 and 5, sensor and test-profile options (friction-test presets);
- :mod:`.synthetic`: synthetic lift-test records from the hydraulic plant;
- :mod:`.report`: tables beside the paper's, fit plots, parameter-file updates.
"""

from loader_model.identification.equivalent import EquivalentCylinder
from loader_model.identification.friction import FRICTION_NAMES, fit_friction
from loader_model.identification.leakage import LEAKAGE_NAMES, LeakageFit, fit_leakage
from loader_model.identification.measurement import (
    MeasurementRecord,
    read_measurement_csv,
    write_measurement_csv,
)
from loader_model.identification.pipeline import (
    FrictionResult,
    identify_friction,
    identify_leakage,
    prepare_signals,
)
from loader_model.identification.regression import LinearFit
from loader_model.identification.synthetic import (
    TABLE4,
    TABLE5,
    LiftProfile,
    SensorOptions,
    synthesize,
)

__all__ = [
    "FRICTION_NAMES",
    "LEAKAGE_NAMES",
    "TABLE4",
    "TABLE5",
    "EquivalentCylinder",
    "FrictionResult",
    "LeakageFit",
    "LiftProfile",
    "LinearFit",
    "MeasurementRecord",
    "SensorOptions",
    "fit_friction",
    "fit_leakage",
    "identify_friction",
    "identify_leakage",
    "prepare_signals",
    "read_measurement_csv",
    "synthesize",
    "write_measurement_csv",
]
