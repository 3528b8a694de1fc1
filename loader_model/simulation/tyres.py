"""Each axle's tyres of a resolved plant, as the road input takes them: radius and tandem cam.

The tyres' road geometry (free radius R and the tandem cam's a_e / R, b_e / R, c_e and l_s / 2a;
:mod:`loader_model.parameters.tyres`) belongs to the machine's parameter set, not to the plant's
parameter vector: the plant takes the road input, and the tyres only shape it. A
:class:`~loader_model.plant.scenario.PlantScenario` built from files carries its set
(``loader``); one built from a bare parameter vector takes its machine's shipped set.
"""

from __future__ import annotations

from loader_model.parameters.machine_files import default_machine_parameters
from loader_model.parameters.sets import default_loader
from loader_model.parameters.tyres import AxleEnvelope, axle_envelopes
from loader_model.plant.scenario import PlantScenario
from loader_model.simulation.tandem_cam import TandemCam

__all__ = ["axle_cam", "axle_tyres"]


def axle_tyres(plant: PlantScenario) -> tuple[AxleEnvelope, ...]:
    """The tyres of each axle of ``plant``, front first (module notes).

    Raises
    ------
    ValueError
        For a machine without a shipped parameter set built from a bare vector, or a set that
        states no tyres for an axle.
    """
    params = plant.loader
    if params is None:
        params = (
            default_loader()
            if plant.is_default_machine
            else default_machine_parameters(plant.layout.machine)
        )
    return axle_envelopes(params, plant.layout.machine.axles)


def axle_cam(plant: PlantScenario, axle: str, tyre: AxleEnvelope, load_n: float) -> TandemCam:
    """The tandem cam of ``axle`` at its static deflection F_iy0 / k_iy, or ValueError naming it."""
    stiffness = plant.parameter(f"k_{axle}y")
    deflection_m = load_n / stiffness
    try:
        return TandemCam.from_deflection(
            tyre.radius_m,
            deflection_m,
            length_ratio=tyre.length_ratio,
            height_ratio=tyre.height_ratio,
            exponent=tyre.exponent,
            spacing_ratio=tyre.spacing_ratio,
        )
    except ValueError as error:
        raise ValueError(
            f"tyre {axle}: static deflection F_{axle}y0 / k_{axle}y = {load_n:.6g} N / "
            f"{stiffness:.6g} N/m = {deflection_m:.6g} m is outside the tandem cam's range of "
            f"its free radius R_{axle} = {tyre.radius_m:g} m ({error}); give a stiffer "
            f"k_{axle}y or envelope='rigid'"
        ) from None
