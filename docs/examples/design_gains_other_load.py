"""Design skyhook gains for another bucket load.

The shipped loads are the paper's 340 kg ("empty") and 770 kg ("full") buckets. This example
writes a load file of its own (a 600 kg pallet of blocks), builds the ISO 2631 comfort design
plant of the default loader with that load, and designs K_fb two ways with
:func:`loader_model.control.design_gains`: the paper's output-feedback LQR and the ISO 2631
optimisation. Both gains are then evaluated on the same plant (a_total on a class C road at
9 km/h).

Run it from any folder: ``python docs/examples/design_gains_other_load.py``; it writes
``pallet.toml`` into the current folder.
"""

from pathlib import Path

import numpy as np

from loader_model.control import design_gains
from loader_model.control.comfort_design import comfort_plants, evaluate_gain
from loader_model.plant.plant_parameters import plant_parameter_vector

# A bucket-load file: every value with its SI unit and a one-line source (format of
# loader_model/data/load_full.toml, schema loader_model/data/load.schema.json).
Path("pallet.toml").write_text(
    """\
mass = { value = 600.0, unit = "kg", source = "example: pallet of concrete blocks" }
cog = { value = [1.9, -0.35], unit = "m", source = "example: 0.5 m above ground, ahead of the cab" }
inertia = { value = 40.0, unit = "kg m^2", source = "example: 600 kg block 0.7 m x 0.5 m" }
pressure_normalisation = { value = 20000000.0, unit = "Pa", source = "as the full bucket" }
""",
    encoding="utf-8",
)

# The plant parameter vector of the default loader with that load; the comfort design takes it
# in the slot of one of its two load cases (here "full": its pressure norm ||p_A|| = 200 bar).
params = plant_parameter_vector(None, "pallet.toml")
plants = comfort_plants(loads=("full",), road_class="C", speed_kmh=9.0, params={"full": params})

lqr = design_gains(plants, method="lqr")
optimised = design_gains(plants, method="optimise")
print("LQR:      ", lqr.summary)
print("optimise: ", optimised.summary)

for name, design in (("lqr", lqr), ("optimise", optimised)):
    (row,) = evaluate_gain(plants, design.gain)
    gains = ", ".join(f"{k:+.2f}" for k in np.ravel(design.gain))
    print(
        f"{name:9s} K_fb = ({gains})  a_total {row.a_total:.3f} m/s^2  margin {row.margin:.3f} rad/s"
    )
    assert np.isfinite(row.a_total), "the designed loop must be stable"
    assert row.within_limits, "the 3 sigma limits on V_p and p_A must hold"

a_lqr = evaluate_gain(plants, lqr.gain)[0].a_total
a_opt = evaluate_gain(plants, optimised.gain)[0].a_total
print(f"a_total: LQR {a_lqr:.3f}, optimised {a_opt:.3f} m/s^2")
