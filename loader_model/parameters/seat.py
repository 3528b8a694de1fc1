"""The seated occupant on the seat cushion at S (TOML section ``[seat]``; errata 13).

Section 5.3 of the paper measured with an accelerometer pad between operator and seat, not on
the rigid chassis. :mod:`loader_model.plant.occupant` puts a seated occupant on a cushion at S
with these values: per axis (fore-aft x, vertical y of the chassis frame) a cushion
spring-damper under a pad node carrying the pad and the occupant's rigid part, and one
spring-mass-damper mode of the occupant on the pad (the single-degree-of-freedom apparent-mass
model with a mass m0 that moves with the seat, Fairley & Griffin 1989).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from loader_model.parameters.fields import Range, TypedLeaves, si

__all__ = ["SeatParameters"]

_FRACTION = Range(0.0, 0.9, reason="none to nine tenths of the seated mass moving with the pad")
_RATIO = Range(0.05, 1.5, reason="damping ratios of apparent-mass modes, 0.05-1.5")
_CUSHION_K = Range(1e4, 2e6, reason="soft foam under a seated person (10 kN/m) to a thin pad")
_CUSHION_C = Range(10.0, 2e4, reason="cushion damping, from lightly damped foam to a damped seat")


@dataclass(frozen=True)
class SeatParameters(TypedLeaves):
    """Seated occupant and seat cushion (module docstring; the plant's occupant model).

    Attributes
    ----------
    seated_mass : float
        Mass the seat pan carries, m0 + m1 (the apparent mass at low frequency), kg.
    pad_mass : float
        Moving mass of the cushion top and the accelerometer pad, kg.
    vertical_rigid_fraction, fore_aft_rigid_fraction : float
        Share m0 / (m0 + m1) of the seated mass that moves with the pad, per axis.
    vertical_frequency, fore_aft_frequency : float
        Natural frequency of the occupant's mode on a rigid seat, Hz.
    vertical_damping_ratio, fore_aft_damping_ratio : float
        Its damping ratio.
    cushion_stiffness_y, cushion_stiffness_x : float
        Cushion stiffness under the pad (compression, shear), N/m.
    cushion_damping_y, cushion_damping_x : float
        Cushion damping, N·s/m.
    """

    seated_mass: float = field(
        metadata=si("kg", Range(20.0, 150.0, reason="a child to a heavy operator on the seat pan"))
    )
    pad_mass: float = field(
        metadata=si("kg", Range(0.05, 10.0, reason="a pad alone to a heavy cushion top"))
    )
    vertical_rigid_fraction: float = field(metadata=si("-", _FRACTION))
    vertical_frequency: float = field(
        metadata=si("Hz", Range(2.0, 10.0, reason="principal vertical resonance, 2-10 Hz"))
    )
    vertical_damping_ratio: float = field(metadata=si("-", _RATIO))
    fore_aft_rigid_fraction: float = field(metadata=si("-", _FRACTION))
    fore_aft_frequency: float = field(
        metadata=si("Hz", Range(0.5, 8.0, reason="fore-aft apparent-mass peaks, 0.5-8 Hz"))
    )
    fore_aft_damping_ratio: float = field(metadata=si("-", _RATIO))
    cushion_stiffness_y: float = field(metadata=si("N/m", _CUSHION_K))
    cushion_damping_y: float = field(metadata=si("N s/m", _CUSHION_C))
    cushion_stiffness_x: float = field(metadata=si("N/m", _CUSHION_K))
    cushion_damping_x: float = field(metadata=si("N s/m", _CUSHION_C))
