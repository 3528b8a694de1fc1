"""Static pressures, hydraulic stiffness, modes of the coupled plant and the pressure loop of
section 3.2 beside Eq. 43; writes a Bode overlay (PNG). Any described machine (``--machine``):
for another machine than the skid-steer, its pump, valves, friction and accumulator are the
estimates of :mod:`loader_model.plant.machine_parameters`, and Eq. 43 (the paper's skid-steer)
is printed as a reference only."""

from __future__ import annotations

import argparse

from loader_model.commands.common import add_model_arguments, layout_from_arguments

HELP = "hydraulic plant: static pressures, k_eq, coupled modes, pressure loop vs Eq. 43"
GUIDE = "hydraulics.md"  # its page of the user guide (docs/guide/)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``--machine``, ``--params``, ``--load``, ``--highpass`` and ``--plot``."""
    add_model_arguments(parser, machine=True)
    parser.add_argument(
        "--highpass",
        type=float,
        default=1.0,
        metavar="RAD_S",
        help="corner of the high-pass on p_A in the pressure loop, rad/s (default: 1)",
    )
    parser.add_argument(
        "--plot",
        metavar="FILE.png",
        default="pressure_loop.png",
        help="Bode overlay of the pressure loop and Eq. 43 (default: pressure_loop.png)",
    )


def run(args: argparse.Namespace) -> int:
    """Print the hydraulics report and write the figure atomically."""
    from loader_model.control.hydraulics_report import hydraulics_report, plot_pressure_loop
    from loader_model.io.export import check_output_path, write_atomically

    check_output_path(args.plot, (".png",), "plot file")  # before any work
    if not args.highpass > 0:
        raise ValueError(f"--highpass {args.highpass!r}: allowed: a number > 0 (rad/s)")
    layout = layout_from_arguments(args)
    info = layout.machine
    report = hydraulics_report(args.params, args.load, highpass_rad_s=args.highpass, machine=layout)
    static = report.static_outputs
    machine_label = "" if info.is_default else f"{info.title}: "
    print(f"{machine_label}Hydraulic plant, bucket load {args.load}")
    print(f"  static piston pressure p_A   {static['p_A'] / 1e5:10.2f} bar (gauge)")
    valve = info.circuit == "valve"
    rod_side = "tank line" if valve else "charge line"
    print(f"  static rod pressure p_B      {static['p_B'] / 1e5:10.2f} bar ({rod_side})")
    count = report.cylinder_count
    group = {1: "one cylinder", 2: "both cylinders"}.get(count, f"all {count} cylinders")
    print(f"  static cylinder force        {static['F_act'] / 1e3:10.2f} kN ({group})")
    print(f"  piston position              {static['x_piston'] * 1e3:10.1f} mm from retracted")
    if valve:
        print(
            f"  spool position to hold       {static['V_p_hold'] * 1e6:10.3f} µm "
            "(spool leakage, load-holding valve open)"
        )
    else:
        print(
            f"  pump displacement to hold    {static['V_p_hold'] * 1e6:10.3f} cm³/rev "
            "(Table 5 flow, valves open)"
        )
    print(f"  k_eq (chambers closed)       {report.k_eq_n_per_m:10.4g} N/m (Eq. 28, errata 6)")
    if valve:
        print("  (valve and supply: [valve] of the parameter file; check and relief valves,")
        print("  friction, accumulator: the skid-steer's values, estimates for this machine)")
    elif not info.is_default:
        print(
            "  (pump, valves, friction, accumulator: the skid-steer's values, estimates for "
            "this machine)"
        )
    print("\nModes of the coupled plant (frequency Hz / damping ratio):")
    for name, modes in report.modes.items():
        listed = ", ".join(f"{f:.2f}/{z:.3f}" for f, z in modes)
        if valve:  # the same settings, the valve's actuator
            name = name.replace("pump through", "valve through").replace(
                "pump idle", "spool centred"
            )
        print(f"  {name}:\n    {listed}")
    print("\nPressure loop p_A/p_A,ref (section 3.2, k_p = Table 3) beside Eq. 43:")
    for name, item in report.comparisons.items():
        poles = ", ".join(f"{p:.3g}" for p in item.dominant_poles[:6])
        print(f"  {name}: DC gain {item.dc_gain:.3g}, |G(1 Hz)| {abs(item.gain_at_1hz):.3g}")
        print(f"    slowest poles [rad/s]: {poles}")
    reference = next(iter(report.comparisons.values()))
    paper = "Eq. 43" if info.is_default else "Eq. 43 (the paper's skid-steer, for reference)"
    print(
        f"  {paper}: DC gain {reference.reference_dc_gain:.3g}, poles "
        + ", ".join(f"{p:.3g}" for p in reference.reference_poles)
        + ", zero "
        + ", ".join(f"{z:.3g}" for z in reference.reference_zeros)
    )
    paper_curve = "Eq. 43" if info.is_default else "the skid-steer's Eq. 43"
    title = f"Pressure loop of the detailed plant and {paper_curve} (load {args.load})"
    if not info.is_default:
        title = f"{info.title}\n{title}"
    write_atomically(
        args.plot,
        lambda temporary: plot_pressure_loop(report, temporary, title),
        (".png",),
        "plot file",
    )
    print(f"\nwrote {args.plot}")
    return 0
