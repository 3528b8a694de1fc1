"""Identify leakage and compressibility from a lift-test recording (Table 5, Eq. 48).

A real recording would come from your machine; this example makes one: it runs the lift test on
the hydraulic plant of the shipped loader (whose leakage is Table 5) and logs it with sensor
noise, quantisation, offsets and drop-outs (:func:`loader_model.identification.synthesize`),
writes it as a measurement CSV, reads it back as a recording of unknown origin, and identifies
Eq. 48 by robust regression, printing the result beside Table 5.

Run it from any folder: ``python docs/examples/identify_leakage.py``; it writes ``lift.csv`` into
the current folder.
"""

from loader_model.identification import (
    TABLE5,
    EquivalentCylinder,
    SensorOptions,
    identify_leakage,
    prepare_signals,
    read_measurement_csv,
    synthesize,
    write_measurement_csv,
)
from loader_model.identification.report import format_leakage
from loader_model.vehicle.statics import resolve_machine

recording = synthesize(SensorOptions(seed=1))
write_measurement_csv("lift.csv", recording.record.columns())

# From here on only the file and the machine's parameter file (here the shipped one) are used.
loader, load = resolve_machine(None, "full")
cylinder = EquivalentCylinder.from_parameters(loader, load)
record = read_measurement_csv("lift.csv")
signals = prepare_signals(record, loader.pump.shaft_speed, cylinder=cylinder)
result = identify_leakage(signals, cylinder)
print(f"lift.csv: {record.time_s.size} samples at {record.sample_rate_hz:g} Hz")
print(format_leakage(result, record.time_s.size))

for name, value in zip(result.regression.names, result.regression.values, strict=True):
    if name in TABLE5:
        error = abs(value / TABLE5[name] - 1.0)
        print(f"{name}: {error:.1%} from Table 5")
        # over seeds 0-9 the worst error was 2.9 % (the identification page)
        assert error < 0.05, name
