"""One closed-loop scenario resolved once: the plant, the controller, its settings and start.

A :class:`Scenario` holds what :func:`~loader_model.simulation.simulator.simulate` takes besides
the road: the :class:`~loader_model.plant.scenario.PlantScenario` (validated loader and load,
:class:`~loader_model.plant.plant_parameters.PlantOptions`, parameter vector, static state x0,
command u0 and outputs y0), the controller Function ``(z, y, settings) -> (z_next, u)``
(:mod:`~loader_model.simulation.controllers`), its settings vector and its initial state z0.
:func:`resolve_scenario` builds one from what users pass (objects, TOML paths, shipped names):
the parameter files resolved and checked once, the equilibrium computed once, and the ride
controller's settings vector and fixed point (:func:`~loader_model.simulation.ride_control.
plant_controller_setup`) taken from that plant, and how its tyres envelop the road
(:data:`~loader_model.simulation.tandem_cam.ENVELOPES`, read by :func:`~loader_model.simulation.
simulator.course_input`). Build one per (plant, controller) condition and reuse it for every run
of the condition: nothing in it depends on the road or the seed.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import casadi as ca
import numpy as np

from loader_model.plant.layout import SKID_STEER, MachineSource, PlantLayout
from loader_model.plant.plant_parameters import PlantOptions
from loader_model.plant.scenario import PlantScenario, resolve_plant
from loader_model.simulation.controllers import check_controller, hold_command_controller
from loader_model.simulation.ride_control import (
    RIDE_CONTROLLERS,
    plant_controller,
    plant_controller_setup,
)
from loader_model.simulation.tandem_cam import DEFAULT_ENVELOPE, check_envelope

if TYPE_CHECKING:
    from loader_model.control.settings import ControllerSettings
    from loader_model.parameters.schema import BucketLoad, LoaderParameters

__all__ = [
    "HOLDING_CONTROLLERS",
    "Scenario",
    "as_plant",
    "as_scenario",
    "closed_loop",
    "resolve_scenario",
    "ride_scenario",
]

#: Ride controllers in which the pump holds the static command u0 (no settings): ``passive``
#: connects the accumulator (section 5.3).
HOLDING_CONTROLLERS: tuple[str, ...] = ("baseline", "passive")


@functools.cache
def _hold(layout: PlantLayout = SKID_STEER) -> ca.Function:
    """The hold controller with u0 as its one setting (the same Function for every plant of a
    layout)."""
    return hold_command_controller(layout)


@dataclass(frozen=True, eq=False)
class Scenario:
    """A plant with its controller, settings vector and controller start (module notes).

    Attributes
    ----------
    plant : PlantScenario
        The plant and its static equilibrium.
    controller : casadi.Function
        ``controller(z, y, settings) -> (z_next, u)`` on the plant's outputs
        (:func:`~loader_model.simulation.controllers.check_controller`).
    settings : numpy.ndarray
        The controller's settings vector (read-only).
    controller_state : numpy.ndarray
        Its initial state z0 (read-only).
    name : str
        The ride controller's name (:data:`~loader_model.simulation.ride_control.
        RIDE_CONTROLLERS`), or the Function's name for another controller.
    envelope : str
        The tyres' enveloping model, ``"tandem-cam"`` (default) or ``"rigid"``.
    min_speed_m_s : float
        Travel speed below which the ride control is off (the settings'
        ``ride_control_min_speed``; 0: on at every speed).
    off : Scenario or None
        The machine with its ride control off (the baseline: load-holding valves closed, the
        pump holding u0), driven below ``min_speed_m_s``; None when the gate is 0.
    """

    plant: PlantScenario
    controller: ca.Function
    settings: np.ndarray
    controller_state: np.ndarray
    name: str = ""
    envelope: str = DEFAULT_ENVELOPE
    min_speed_m_s: float = 0.0
    off: Scenario | None = None

    def __post_init__(self) -> None:
        check_envelope(self.envelope)
        if not isinstance(self.plant, PlantScenario):
            raise TypeError(f"plant must be a PlantScenario; got {type(self.plant).__name__}")
        controller = check_controller(self.controller, self.plant.layout)
        settings = np.array(self.settings, dtype=float).ravel()
        if settings.size != controller.size1_in(2):
            raise ValueError(
                f"settings must have {controller.size1_in(2)} values for controller "
                f"{controller.name()!r}; got {settings.size}"
            )
        state = np.array(self.controller_state, dtype=float).ravel()
        if state.size != controller.size1_in(0):
            raise ValueError(
                f"controller_state must have {controller.size1_in(0)} values; got {state.size}"
            )
        settings.setflags(write=False)
        state.setflags(write=False)
        object.__setattr__(self, "settings", settings)
        object.__setattr__(self, "controller_state", state)
        object.__setattr__(self, "name", str(self.name or controller.name()))
        if (self.min_speed_m_s > 0.0) != (self.off is not None):
            raise ValueError(
                f"min_speed_m_s = {self.min_speed_m_s!r} needs the scenario with the ride "
                "control off (off), and off needs min_speed_m_s > 0"
            )

    def at_speed(self, speed_m_s: float) -> Scenario:
        """The scenario driven at ``speed_m_s``: :attr:`off` below :attr:`min_speed_m_s` (the
        ride control switched off, as commercial ride control is at low speed), else itself."""
        if self.off is not None and float(speed_m_s) < self.min_speed_m_s:
            return self.off
        return self

    @property
    def params(self) -> np.ndarray:
        """The plant parameter vector."""
        return self.plant.params

    @property
    def x0(self) -> np.ndarray:
        """The plant's static state."""
        return self.plant.x0

    @property
    def u0(self) -> float:
        """The pump command that holds the static state, m³/rev."""
        return self.plant.u0


def closed_loop(
    plant: PlantScenario,
    controller: ca.Function | None = None,
    settings: Sequence[float] = (),
    controller_state: Sequence[float] | None = None,
    name: str = "",
    envelope: str = DEFAULT_ENVELOPE,
) -> Scenario:
    """``plant`` with a controller Function as :func:`~loader_model.simulation.simulator.
    simulate` takes it: without one the pump holds u0 (the hold controller with u0 as its
    setting); ``controller_state`` defaults to zeros; ``envelope`` is the tyres' model."""
    if controller is None:
        if len(settings):
            raise ValueError("settings are for a controller; without one the pump holds u0")
        controller, settings = _hold(plant.layout), (plant.u0,)
    controller = check_controller(controller, plant.layout)
    if controller_state is None:
        controller_state = np.zeros(controller.size1_in(0))
    vector = np.asarray(settings, dtype=float)
    return Scenario(plant, controller, vector, controller_state, name, envelope)


def _controller_settings(settings: Any) -> ControllerSettings:
    from loader_model.control.settings import ControllerSettings, default_settings, load_settings

    if settings is None:
        return default_settings()
    if isinstance(settings, ControllerSettings):
        return settings
    if isinstance(settings, str | os.PathLike):
        return load_settings(settings)
    raise TypeError(
        "settings must be a ControllerSettings, the path of a controller settings TOML file or "
        f"None; got {type(settings).__name__}"
    )


def _check_name(controller: object) -> str:
    if not isinstance(controller, str) or controller not in RIDE_CONTROLLERS:
        raise ValueError(f"controller {controller!r} is unknown; allowed: {list(RIDE_CONTROLLERS)}")
    return controller


def ride_scenario(
    plant: PlantScenario,
    controller: str = "baseline",
    settings: ControllerSettings | str | Path | None = None,
    *,
    pressure_norm_pa: float | None = None,
    envelope: str = DEFAULT_ENVELOPE,
) -> Scenario:
    """The ride controller ``controller`` on a resolved plant (no second equilibrium).

    Parameters
    ----------
    plant : PlantScenario
        The plant (:func:`~loader_model.plant.scenario.resolve_plant`).
    controller : str
        One of :data:`~loader_model.simulation.ride_control.RIDE_CONTROLLERS`:
        :data:`HOLDING_CONTROLLERS` hold u0 (``passive`` needs the plant's accumulator
        connected); ``virtual-accumulator`` and ``skyhook`` read the sensors.
    settings : ControllerSettings, str or Path, optional
        Settings of a sensor-reading controller, or the path of their TOML file; default: the
        shipped Table 3 settings.
    pressure_norm_pa : float, optional
        ‖p_A‖∞ in Pa (section 3.3); default: the plant's bucket load's.
    envelope : str
        The tyres' enveloping model (:data:`~loader_model.simulation.tandem_cam.ENVELOPES`).

    Raises
    ------
    ValueError
        For an unknown controller, settings given to a holding controller, ``passive`` on a plant
        with the accumulator shut, or no pressure norm for a plant without a bucket load.
    """
    if not isinstance(plant, PlantScenario):
        raise TypeError(f"plant must be a PlantScenario; got {type(plant).__name__}")
    _check_name(controller)
    if controller in HOLDING_CONTROLLERS:
        if settings is not None:
            raise ValueError(
                f"controller {controller!r} holds the static command u0 and takes no settings; "
                f"got settings={settings!r} (settings are for virtual-accumulator and skyhook)"
            )
        if controller == "passive" and plant.parameter("accumulator_on") != 1.0:
            raise ValueError(
                "controller 'passive' is the accumulator connected while the pump holds u0 (0 "
                "behind closed load-holding valves); the "
                "plant's accumulator is shut (accumulator_on = "
                f"{plant.parameter('accumulator_on')!r}; allowed: 1.0, "
                "PlantOptions.for_controller('passive'))"
            )
        return closed_loop(plant, name=controller, envelope=envelope)
    if pressure_norm_pa is None and not plant.is_default_machine:
        from loader_model.plant.machine_parameters import pressure_norm

        pressure_norm_pa = pressure_norm(plant.output("p_A"))
    if pressure_norm_pa is None:
        if plant.load is None:
            raise ValueError(
                f"controller {controller!r} needs pressure_norm_pa (‖p_A‖∞ in Pa): the plant was "
                "built from a parameter vector without its bucket load"
            )
        pressure_norm_pa = plant.load.pressure_normalisation
    chosen = _controller_settings(settings)
    vector, state = plant_controller_setup(controller, plant, float(pressure_norm_pa), chosen)
    function = plant_controller(controller, None if plant.is_default_machine else plant.layout)
    gate, off = chosen.ride_control_min_speed, None
    if gate > 0.0:  # below it the machine drives as the baseline (ControllerSettings notes)
        options = plant.options or PlantOptions.for_controller(controller)
        resting = plant.with_options(options.with_controller("baseline"))
        off = closed_loop(resting, name="baseline", envelope=envelope)
    return Scenario(plant, function, vector, state, controller, envelope, gate, off)


def resolve_scenario(
    loader: LoaderParameters | str | Path | None = None,
    load: BucketLoad | str | Path = "empty",
    options: PlantOptions | None = None,
    controller: str = "baseline",
    settings: ControllerSettings | str | Path | None = None,
    envelope: str = DEFAULT_ENVELOPE,
    *,
    machine: MachineSource = SKID_STEER,
) -> Scenario:
    """A closed-loop scenario from files, names or objects, each resolved once (module notes).

    Parameters
    ----------
    loader : LoaderParameters, str, Path or None
        A loader, the path of its TOML file, or None for the shipped default loader.
    load : BucketLoad, str or Path
        A bucket load, the path of its TOML file, or a shipped case (``"empty"``, ``"full"``).
    options : PlantOptions, optional
        Circuit switches; default: :meth:`PlantOptions.for_controller` of ``controller``
        (baseline and passive on closed load-holding valves, passive with the accumulator).
    controller : str
        A ride controller (:func:`ride_scenario`).
    settings : ControllerSettings, str or Path, optional
        Its settings (:func:`ride_scenario`).
    envelope : str
        ``"tandem-cam"`` (default) or ``"rigid"``: how the tyres envelop the road.
    machine : PlantLayout, str or pathlib.Path
        The machine, resolved or a name or description file resolved once here (default the
        skid-steer; :func:`~loader_model.plant.scenario.resolve_plant`:
        for another machine ``loader`` is its parameter file, ``load`` its load case; the
        controllers' ‖p_A‖∞ is :func:`~loader_model.plant.machine_parameters.pressure_norm`).

    Returns
    -------
    Scenario

    Raises
    ------
    ValueError
        From the parameter files' checks (naming the field) or :func:`ride_scenario`.
    """
    _check_name(controller)
    if options is None:
        options = PlantOptions.for_controller(controller)
    plant = resolve_plant(loader, load, options, machine=machine)
    return ride_scenario(plant, controller, settings, envelope=envelope)


def as_plant(params: Sequence[float] | np.ndarray | PlantScenario | Scenario) -> PlantScenario:
    """The plant of ``params``: a Scenario's, a PlantScenario as given, or one built from a
    parameter vector (:meth:`~loader_model.plant.scenario.PlantScenario.from_vector`)."""
    if isinstance(params, Scenario):
        return params.plant
    if isinstance(params, PlantScenario):
        return params
    return PlantScenario.from_vector(np.asarray(params, dtype=float).ravel())


def as_scenario(
    params: Sequence[float] | np.ndarray | PlantScenario | Scenario,
    controller: ca.Function | None = None,
    settings: Sequence[float] = (),
    controller_state: Sequence[float] | None = None,
) -> Scenario:
    """The closed loop of :func:`~loader_model.simulation.simulator.simulate`'s arguments: a
    Scenario as given (then no controller, settings or start besides it), else
    :func:`closed_loop` on :func:`as_plant` of ``params``."""
    if isinstance(params, Scenario):
        given = {
            "controller": controller is not None,
            "settings": len(settings) > 0,
            "controller_state": controller_state is not None,
        }
        if any(given.values()):
            names = ", ".join(name for name, was in given.items() if was)
            raise ValueError(
                f"a Scenario holds the controller, its settings and its start; got {names} "
                "besides it (give its plant, scenario.plant, to pass them separately)"
            )
        return params
    return closed_loop(as_plant(params), controller, settings, controller_state)
