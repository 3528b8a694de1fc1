"""Parameter set of the passive ride control's gas accumulators (guide page "Hydraulics").

Units follow the SI rule of :mod:`loader_model.parameters.schema`. Re-exported by
:mod:`loader_model.parameters.hydraulics` with the drive's other parameter sets.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from loader_model.parameters.fields import Range, TypedLeaves, integer, si

__all__ = ["AccumulatorParameters"]


@dataclass(frozen=True)
class AccumulatorParameters(TypedLeaves):
    """Passive ride control: gas accumulators on the piston side through an orifice.

    Attributes
    ----------
    count : int
        Number of identical accumulators.
    precharge_pressure : float
        Gas precharge pressure in Pa.
    gas_volume : float
        Gas volume at precharge, per accumulator, in m³.
    polytropic_exponent : float
        Exponent n of p V^n = const, in [1, 1.7] (isothermal to adiabatic).
    orifice_diameter : float
        Damping orifice diameter in m.
    discharge_coefficient : float
        Orifice discharge coefficient C_d in (0, 1].
    laminar_transition_pressure : float
        Pressure drop in Pa around which the orifice flow turns from laminar to turbulent.
    """

    count: int = field(metadata=integer(Range(1, 8, reason="one to eight accumulators")))
    precharge_pressure: float = field(
        metadata=si("Pa", Range(500000.0, 30000000.0, reason="gas precharges of 5-300 bar"))
    )
    gas_volume: float = field(
        metadata=si("m^3", Range(1e-05, 0.05, reason="accumulators of 0.01-50 l"))
    )
    polytropic_exponent: float = field(
        metadata=si(
            "-",
            Range(1.0, 1.7, reason="isothermal (1) to adiabatic nitrogen at high pressure (1.7)"),
        )
    )
    orifice_diameter: float = field(
        metadata=si("m", Range(0.0005, 0.05, reason="damping orifices of 0.5-50 mm"))
    )
    discharge_coefficient: float = field(
        metadata=si("-", Range(0.1, 1.0, reason="0.1 (long laminar passage) to 1 (ideal nozzle)"))
    )
    laminar_transition_pressure: float = field(
        metadata=si("Pa", Range(1e3, 1e6, reason="laminar-turbulent transition of 0.01-10 bar"))
    )
