"""The report's section on the shipped designs: the gains designed on each shipped machine and
their design check over the operating envelope.

The gains are designed on the nonlinear machine (``loader-model design --method machine``, the
user guide's page on the design check) and checked there (``loader-model check-design``); both
take minutes, too long for the report, so ``make designs`` writes the settings files and the
checks' tables into ``loader_model/data/`` and the report shows them as shipped. A slow test
runs the checks again on the current model and fails when a shipped design no longer passes.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources

__all__ = ["SHIPPED_DESIGNS", "ShippedDesign", "check_section", "shipped_check_text"]


@dataclass(frozen=True)
class ShippedDesign:
    """A shipped design: its machine, settings file and the table its check wrote.

    Attributes
    ----------
    machine : str
        The shipped machine's name.
    settings : str
        The controller settings file under ``loader_model/data/``.
    check : str
        The Markdown of ``loader-model check-design --output`` under ``loader_model/data/``.
    """

    machine: str
    settings: str
    check: str


#: The designs ``make designs`` writes, one per shipped machine.
SHIPPED_DESIGNS: tuple[ShippedDesign, ...] = (
    ShippedDesign("skid_steer", "controller_machine.toml", "design_check_skid_steer.md"),
    ShippedDesign(
        "compact_wheel_loader",
        "controller_machine_compact_wheel_loader.toml",
        "design_check_compact_wheel_loader.md",
    ),
    ShippedDesign(
        "tractor_front_loader",
        "controller_machine_tractor_front_loader.toml",
        "design_check_tractor_front_loader.md",
    ),
)


def _data_text(name: str) -> str:
    return resources.files("loader_model").joinpath("data", name).read_text(encoding="utf-8")


def shipped_check_text(design: ShippedDesign) -> str:
    """The shipped Markdown of ``design``'s check (table, margins, verdict)."""
    return _data_text(design.check)


def check_section() -> str:
    """Markdown: per shipped machine, its designed gains, how they were made and their check."""
    from importlib.resources import as_file

    from loader_model.control.settings import load_settings

    lines = [
        "## Gains designed on the machine, and their design check\n",
        "Each shipped machine's skyhook gains designed on the nonlinear machine (`loader-model "
        "design --method machine`: a_total relative to the baseline over both loads, the "
        "paper's boards at 9 and 18 km/h and an ISO 8608 class C road at 15 km/h, with exact "
        "gradients and the check's criteria as constraints; in rounds, the conditions the check "
        "finds failing joining the scenarios), then checked over the default "
        "envelope (`loader-model check-design`): both loads, the boards at 5-18 km/h, ISO 8608 "
        "classes B-D at 5-30 km/h, each with the baseline and the passive accumulator beside "
        "it, the pump's time at its limits, the decay after the road and the loop's margin on "
        "the linearised and on sampled plants. Written by `make designs`; the user guide's page "
        "on the design check explains every column.\n",
    ]
    for design in SHIPPED_DESIGNS:
        with as_file(resources.files("loader_model").joinpath("data", design.settings)) as path:
            settings = load_settings(path)
        gains = ", ".join(f"{k:.3f}" for k in settings.k_fb)
        gate_kmh = 3.6 * settings.ride_control_min_speed
        gate = (
            f" The ride control is off below {gate_kmh:g} km/h "
            f"({settings.source('ride_control_min_speed')})."
            if gate_kmh > 0.0
            else ""
        )
        lines += [
            f"### {design.machine.replace('_', ' ')}\n",
            f"K_fb = ({gains}) in `loader_model/data/{design.settings}`, made by "
            f"{settings.source('k_fb')}.{gate}\n",
            shipped_check_text(design).strip() + "\n",
        ]
    return "\n".join(lines)
