"""Export the plant as an FMU and check it.

Writes an FMI 2.0 Model Exchange FMU of the nonlinear plant (default loader, empty bucket),
validates it with FMPy, and cross-checks it: FMPy simulates the FMU over a 20 mm bump under the
front axle and the result is compared with CasADi's cvodes on the plant Function the FMU was built
from (:func:`loader_model.fmu.crosscheck.cross_check`). Needs a C compiler (``gcc``, ``cc`` or
``$CC``) and FMPy (the ``dev`` extra).

Run it from any folder: ``python docs/examples/export_fmu.py``; it writes ``plant.fmu`` into the
current folder.
"""

import fmpy
from fmpy.validation import validate_fmu

from loader_model.fmu.build import export_plant_fmu
from loader_model.fmu.crosscheck import cross_check
from loader_model.plant.plant_parameters import plant_parameter_vector

params = plant_parameter_vector(None, "empty")
path = export_plant_fmu("plant.fmu", params)
print(f"wrote {path} ({path.stat().st_size / 1024:.0f} kB)")

problems = validate_fmu(str(path))
print("FMPy validation:", "no problem" if not problems else problems)
assert not problems

description = fmpy.read_model_description(str(path))
print(f"{description.fmiVersion}, {len(description.modelVariables)} variables")

check = cross_check(path, params)
for name, error in check.relative_error.items():
    print(f"{name:6s} largest error relative to its excursion {error:.1e}")
assert max(check.relative_error.values()) < 1e-3
