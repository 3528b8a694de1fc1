"""Identify seal friction (Table 4) or leakage and compressibility (Table 5) from a CSV record.

``identify friction DATA.csv`` and ``identify leakage DATA.csv`` read a measurement file (header
``time [s],x_cyl [m],p_A [Pa],p_B [Pa],Q_A [m^3/s],m_load [kg]``; the guide's page
docs/guide/identification.md), fit Eq. 46 or Eq. 48 (paper section 4.1) and print the coefficients
beside the paper's tables with R², s and confidence intervals. ``--plot`` writes a fit plot,
``--update`` a new parameter file whose identified values carry their source. ``identify synthesize
OUT.csv`` writes a synthetic lift test run on the hydraulic plant with the shipped loader (Table 4
and 5 values; noise, quantisation, offsets, outliers and seed as options).
"""

from __future__ import annotations

import argparse
from typing import Any

__all__ = ["GUIDE", "HELP", "add_arguments", "run"]

HELP = "identify friction (Table 4) or leakage (Table 5) from a CSV record; synthesize records"
GUIDE = "identification.md"  # its page of the user guide (docs/guide/)


def _fit_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "data",
        metavar="DATA.csv",
        help="measurement CSV (its columns: docs/guide/identification.md)",
    )
    parser.add_argument(
        "--params",
        metavar="FILE",
        default=None,
        help="loader parameter file (TOML): cylinders, pump, geometry (default: the shipped loader)",
    )
    parser.add_argument(
        "--load",
        default="full",
        metavar="CASE",
        help="bucket-load case whose centre of gravity and inertia per kg place the load "
        "('empty', 'full' or a TOML file; the synthetic lift test's load)",
    )
    parser.add_argument(
        "--cutoff",
        type=float,
        default=None,
        metavar="HZ",
        help="-3 dB cutoff of the Savitzky-Golay smoothing in Hz (default: 10)",
    )
    parser.add_argument(
        "--level",
        type=float,
        default=0.95,
        metavar="LEVEL",
        help="confidence level of the intervals",
    )
    parser.add_argument("--plot", metavar="FILE.png", help="write the fit plot (PNG, PDF, SVG)")
    parser.add_argument(
        "--update",
        metavar="FILE.toml",
        help="write a copy of the parameter file with the identified values and their source",
    )


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Register ``identify friction|leakage|synthesize``."""
    actions = parser.add_subparsers(dest="identify_action", required=True, metavar="ACTION")
    friction = actions.add_parser(
        "friction", help="seal friction, Eq. 44 and 46, Table 4", description=__doc__
    )
    _fit_arguments(friction)
    leakage = actions.add_parser(
        "leakage", help="leakage and compressibility, Eq. 48, Table 5", description=__doc__
    )
    _fit_arguments(leakage)
    leakage.add_argument(
        "--least-squares",
        action="store_true",
        help="plain least squares instead of the robust (Tukey bisquare) fit, for comparison",
    )
    synth = actions.add_parser(
        "synthesize", help="write a synthetic lift-test record", description=__doc__
    )
    synth.add_argument("output", metavar="OUT.csv", help="CSV file to write")
    synth.add_argument("--seed", type=int, default=0, metavar="N", help="random seed")
    synth.add_argument("--cycles", type=int, default=12, metavar="N", help="extend/retract cycles")
    synth.add_argument(
        "--friction-test",
        action="store_true",
        help="the friction test: speeds log-uniform over 0.01-0.25 m/s, a 5 um position "
        "sensor (1 um steps) and 0.01 m/s^2 accelerometers (docs/guide/identification.md); "
        "the noise options below then default to those",
    )
    synth.add_argument(
        "--no-chassis",
        action="store_true",
        help="leave out the chassis columns (theta_1, f_Hx, f_Hy, f_Ny)",
    )
    defaults = {
        "sample-rate": ("HZ", "logging rate in Hz", 500.0),
        "pressure-noise": ("PA", "pressure noise std in Pa", 0.5e5),
        "position-noise": ("M", "position noise std in m", 5e-5),
        "flow-noise": ("M3S", "flow noise std in m^3/s", 1e-4),
        "pressure-step": ("PA", "pressure quantisation step in Pa (0: none)", 0.1e5),
        "position-step": ("M", "position quantisation step in m", 1e-5),
        "flow-step": ("M3S", "flow quantisation step in m^3/s", 1e-6),
        "pressure-offset": ("PA", "pressure offset in Pa", 0.0),
        "position-offset": ("M", "position offset in m", 0.0),
        "flow-offset": ("M3S", "flow offset in m^3/s (Table 5 C)", -3.2e-4),
        "outliers": ("FRACTION", "fraction of flow samples that drop out to 0", 0.0),
        "pitch-noise": ("RAD", "chassis pitch noise std in rad", 8.7e-4),
        "acceleration-noise": ("M/S2", "specific-force noise std in m/s^2", 0.05),
    }
    for name, (metavar, text, default) in defaults.items():
        synth.add_argument(
            f"--{name}",
            type=float,
            default=None,
            metavar=metavar,
            help=f"{text} (default: {default:g})",
        )
    synth.add_argument(
        "--pressure-unit", choices=("Pa", "bar"), default="Pa", help="unit of the p_A, p_B columns"
    )


def _loader_and_cylinder(args: argparse.Namespace) -> tuple[Any, Any]:
    from loader_model.identification import EquivalentCylinder
    from loader_model.vehicle.statics import resolve_machine

    loader, load = resolve_machine(args.params, args.load)
    return loader, EquivalentCylinder.from_parameters(loader, load)


def _check_outputs(args: argparse.Namespace) -> None:
    from pathlib import Path

    for option in ("plot", "update"):
        path = getattr(args, option)
        if path is not None and not Path(path).resolve().parent.is_dir():
            raise ValueError(f"--{option}: folder of {path!r} does not exist")
    if not 0.0 < args.level < 1.0:
        raise ValueError(f"--level must be in (0, 1); got {args.level!r}")


def _fit(args: argparse.Namespace, written: list[str]) -> int:
    from loader_model.identification import (
        identify_friction,
        identify_leakage,
        prepare_signals,
        read_measurement_csv,
    )
    from loader_model.identification import report as rep
    from loader_model.parameters.sets import replace, save

    _check_outputs(args)
    loader, cylinder = _loader_and_cylinder(args)
    record = read_measurement_csv(args.data)
    cutoff = {} if args.cutoff is None else {"cutoff_hz": args.cutoff}
    signals = prepare_signals(record, loader.pump.shaft_speed, cylinder=cylinder, **cutoff)
    header = (
        f"{args.data}: {record.time_s.size} samples at {record.sample_rate_hz:.6g} Hz; "
        f"Savitzky-Golay cubic, window {signals.window} samples (-3 dB at {signals.cutoff_hz:g}"
        f" Hz)\n{cylinder.describe()}"
    )
    if args.identify_action == "friction":
        result = identify_friction(signals, cylinder, level=args.level)
        header += (
            "\nEq. 44 load: the boom on the moving chassis (columns theta_1, f_Hx, f_Hy, f_Ny)"
            if record.has_chassis
            else "\nEq. 44 load: chassis taken at rest (no chassis columns; on tyres this leaves "
            "kN of error, see docs/guide/identification.md)"
        )
        text = rep.format_friction(result.fit, int(result.used.sum()))
        updates = rep.friction_updates(result.fit)

        def plot(path: str) -> object:
            return rep.plot_friction_fit(result, path, f"Friction: {args.data}")

    else:
        leak = identify_leakage(signals, cylinder, robust=not args.least_squares, level=args.level)
        text = rep.format_leakage(leak, signals.time.size)
        updates = rep.leakage_updates(leak)

        def plot(path: str) -> object:
            return rep.plot_leakage_fit(
                leak, signals, cylinder.area_m2, path, f"Leakage: {args.data}"
            )

    updated = None
    if args.update is not None:
        command = f"{args.identify_action} {args.data}"
        updated = replace(loader, updates, source=rep.update_source(args.data, command))
    if args.plot is not None:
        plot(args.plot)
        written.append(args.plot)
    if updated is not None:
        save(updated, args.update)
        written.append(args.update)
    print(header)
    print(text)
    if args.plot is not None:
        print(f"wrote {args.plot}")
    if updated is not None:
        print(f"wrote {args.update} ({', '.join(updates)})")
    return 0


def _synthesize(args: argparse.Namespace, written: list[str]) -> int:
    import dataclasses
    from pathlib import Path

    from loader_model.identification import LiftProfile, SensorOptions, synthesize
    from loader_model.identification.measurement import write_measurement_csv

    if not Path(args.output).resolve().parent.is_dir():
        raise ValueError(f"folder of {args.output!r} does not exist")
    if args.cycles < 1:
        raise ValueError(f"--cycles must be >= 1; got {args.cycles}")
    base = SensorOptions.friction_test() if args.friction_test else SensorOptions()
    fields = {
        "sample_rate": "sample_rate_hz",
        "pressure_noise": "pressure_noise_pa",
        "position_noise": "position_noise_m",
        "flow_noise": "flow_noise_m3_s",
        "pressure_step": "pressure_step_pa",
        "position_step": "position_step_m",
        "flow_step": "flow_step_m3_s",
        "pressure_offset": "pressure_offset_pa",
        "position_offset": "position_offset_m",
        "flow_offset": "flow_offset_m3_s",
        "outliers": "outlier_fraction",
        "pitch_noise": "pitch_noise_rad",
        "acceleration_noise": "acceleration_noise_m_s2",
    }
    given = {f: getattr(args, a) for a, f in fields.items() if getattr(args, a) is not None}
    for name in ("sample_rate", "pressure_noise", "position_noise", "flow_noise"):
        value = getattr(args, name)
        if value is not None and (not value >= 0.0 or (name == "sample_rate" and value == 0.0)):
            raise ValueError(f"--{name.replace('_', '-')} must be positive; got {value!r}")
    sensors = dataclasses.replace(base, seed=args.seed, chassis=not args.no_chassis, **given)
    profile = LiftProfile.friction_test() if args.friction_test else LiftProfile()
    recording = synthesize(sensors, dataclasses.replace(profile, cycles=args.cycles))
    columns = recording.record.columns()
    if args.pressure_unit == "bar":
        columns = {
            (label.replace("[Pa]", "[bar]") if label.startswith("p_") else label): (
                values / 1e5 if label.startswith("p_") else values
            )
            for label, values in columns.items()
        }
    comments = (
        "synthetic lift test by `loader-model identify synthesize` (hydraulic plant, shipped "
        "loader: Table 4 and 5 values)",
        f"seed {args.seed}, {args.cycles} cycles, {sensors}",
        f"{profile}",
    )
    write_measurement_csv(args.output, columns, comments)
    written.append(args.output)
    samples = recording.record.time_s.size
    rate = sensors.sample_rate_hz
    print(f"wrote {args.output} ({samples} samples at {rate:g} Hz, seed {args.seed})")
    return 0


def run(args: argparse.Namespace) -> int:
    """Run ``identify friction|leakage|synthesize``; returns 0. An interrupt (Ctrl-C, SIGTERM)
    says which of the files were written."""
    from loader_model.io.interrupts import files_note, keeping

    written: list[str] = []
    synthesize = args.identify_action == "synthesize"
    wanted = (args.output,) if synthesize else (args.plot, args.update)
    with keeping(lambda: files_note(wanted, written)):
        return _synthesize(args, written) if synthesize else _fit(args, written)
