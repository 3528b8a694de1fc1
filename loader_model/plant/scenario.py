"""One plant resolved once: loader, bucket load, circuit switches, parameter vector, equilibrium.

Following one Table 6 trial used to compute the static equilibrium of the same plant up to four
times (road input, controller settings, controller fixed point, simulator start).
:func:`resolve_plant` does each step once:
:func:`~loader_model.vehicle.statics.resolve_machine` (each parameter set valid, and the two
standing together: :func:`~loader_model.vehicle.statics.check_combination`),
:func:`~loader_model.plant.plant_parameters.plant_parameter_vector` without a second check, and
:func:`~loader_model.plant.equilibrium.static_state` (x0, u0 of
:mod:`~loader_model.plant.equilibrium`), then one plant evaluation for the static outputs y0
(tyre loads F_Ay, F_By and the sensor readings at rest). Whoever needs the plant (the road input,
the controller settings and fixed point, the simulator) takes the :class:`PlantScenario` and
reads these instead of rebuilding them.

The scenario carries its machine resolved once, a :class:`~loader_model.plant.layout.PlantLayout`
(description, generated functions, circuit, names and sizes): :func:`resolve_plant` and
:meth:`PlantScenario.from_vector` take a machine name or description file and resolve it there;
whatever takes the scenario reads :attr:`PlantScenario.layout` instead of looking the machine up.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from loader_model.plant.equilibrium import static_state
from loader_model.plant.layout import SKID_STEER, MachineSource, PlantLayout, resolve_layout
from loader_model.plant.plant import plant_function
from loader_model.plant.plant_parameters import PlantOptions, plant_parameter_vector
from loader_model.vehicle.statics import resolve_machine

if TYPE_CHECKING:
    from loader_model.parameters.machine_files import MachineParameters
    from loader_model.parameters.schema import BucketLoad, LoaderParameters

__all__ = ["PlantScenario", "resolve_plant"]


def _frozen(values: np.ndarray, name: str, size: int) -> np.ndarray:
    array = np.array(values, dtype=float).ravel()
    if array.size != size:
        raise ValueError(f"{name} must have {size} values; got {array.size}")
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class PlantScenario:
    """A plant and its static equilibrium, resolved once (module notes).

    Build it with :func:`resolve_plant` (from files, names or objects) or
    :meth:`from_vector` (from a parameter vector alone); the arrays are read-only copies, so
    every user of one scenario sees the same plant.

    Attributes
    ----------
    params : numpy.ndarray
        Plant parameters (:data:`~loader_model.plant.plant_parameters.PLANT_PARAMETER_NAMES`).
    x0 : numpy.ndarray
        Static state (:data:`~loader_model.plant.plant.STATE_NAMES`, module
        :mod:`~loader_model.plant.equilibrium`).
    u0 : float
        Pump command V_p0 that holds the boom against Table 5's pump-side flow (0 behind closed
        load-holding valves), m³/rev.
    y0 : numpy.ndarray
        Plant outputs (:data:`~loader_model.plant.plant.OUTPUT_NAMES`) at (x0, u0) without road
        input or disturbance.
    loader : LoaderParameters or None
        The validated loader (None when built from a bare vector).
    load : BucketLoad or None
        The validated bucket load (None when built from a bare vector).
    options : PlantOptions or None
        The circuit switches (None when built from a bare vector: the vector's switch entries).
    layout : PlantLayout
        The machine resolved once (default the skid-steer): its description, generated
        functions, circuit, names and sizes. For another machine ``loader`` is its
        :class:`~loader_model.parameters.machine_files.MachineParameters` and ``load`` the
        name of its load case (None: the file's [model] values).
    """

    params: np.ndarray
    x0: np.ndarray
    u0: float
    y0: np.ndarray
    loader: LoaderParameters | None = None
    load: BucketLoad | None = None
    options: PlantOptions | None = None
    layout: PlantLayout = SKID_STEER

    def __post_init__(self) -> None:
        layout = self.layout
        if not isinstance(layout, PlantLayout):
            raise TypeError(
                f"layout must be a PlantLayout (loader_model.plant.layout.plant_layout); got "
                f"{type(layout).__name__}"
            )
        object.__setattr__(
            self, "params", _frozen(self.params, "params", len(layout.parameter_names))
        )
        object.__setattr__(self, "x0", _frozen(self.x0, "x0", len(layout.state_names)))
        object.__setattr__(self, "y0", _frozen(self.y0, "y0", len(layout.output_names)))
        object.__setattr__(self, "u0", float(self.u0))
        if self.options is not None and not isinstance(self.options, PlantOptions):
            raise TypeError(
                f"options must be a PlantOptions or None; got {type(self.options).__name__}"
            )

    @property
    def is_default_machine(self) -> bool:
        """True for the paper's skid-steer."""
        return self.layout.machine.is_default

    @classmethod
    def from_vector(
        cls,
        params: np.ndarray,
        loader: LoaderParameters | MachineParameters | None = None,
        load: BucketLoad | str | None = None,
        options: PlantOptions | None = None,
        machine: MachineSource = SKID_STEER,
    ) -> PlantScenario:
        """The scenario of a parameter vector: its static equilibrium and outputs, computed once.

        ``loader``, ``load`` and ``options`` are recorded as given (the vector's sources, when
        known); they are not checked against the vector. ``machine``: its
        :class:`~loader_model.plant.layout.PlantLayout`, or a name or description file resolved
        once here (default the skid-steer).
        """
        layout = resolve_layout(machine)
        vector = np.asarray(params, dtype=float).ravel()
        if vector.size != len(layout.parameter_names):
            raise ValueError(
                f"params must have {len(layout.parameter_names)} values; got {vector.size}"
            )
        x0, u0 = static_state(vector, layout)
        w = np.zeros(len(layout.exogenous_names))
        _, y = plant_function(layout)(x0, u0, w, vector)
        y0 = np.asarray(y, dtype=float).ravel()
        return cls(vector, x0, u0, y0, loader, load, options, layout)

    def parameter(self, name: str) -> float:
        """The value of plant parameter ``name`` (one of ``PLANT_PARAMETER_NAMES``)."""
        names = self.layout.parameter_names
        if name not in names:
            raise ValueError(
                f"plant parameter {name!r} is unknown; allowed: one of PLANT_PARAMETER_NAMES"
            )
        return float(self.params[names.index(name)])

    def command_limit(self) -> float:
        """The saturation of the actuator and its command: the pump's V_p,max [m³/rev], or a
        valve's spool stroke x_s,max [m] (:attr:`PlantLayout.command_limit`)."""
        return self.parameter(self.layout.command_limit)

    def rate_limit(self) -> float:
        """The actuator's rate limit: V̇_p,max [m³/(rev·s)] or a spool's ẋ_s,max [m/s]."""
        return self.parameter(self.layout.rate_limit)

    def output(self, name: str) -> float:
        """The static value of plant output ``name`` (one of ``OUTPUT_NAMES``)."""
        names = self.layout.output_names
        if name not in names:
            raise ValueError(f"plant output {name!r} is unknown; allowed: {list(names)}")
        return float(self.y0[names.index(name)])

    def with_options(self, options: PlantOptions) -> PlantScenario:
        """The same loader and load with the circuit switches ``options``: the vector's switch
        entries replaced (as :func:`~loader_model.plant.plant_parameters.plant_parameter_vector`
        sets them) and the equilibrium of the new vector, computed once. ``self`` if unchanged."""
        if not isinstance(options, PlantOptions):
            raise TypeError(f"options must be a PlantOptions; got {type(options).__name__}")
        if options == self.options:
            return self
        vector = self.params.copy()
        for name, value in options.switches().items():
            vector[self.layout.parameter_names.index(name)] = value
        return PlantScenario.from_vector(vector, self.loader, self.load, options, self.layout)


def resolve_plant(
    loader: LoaderParameters | str | Path | None = None,
    load: BucketLoad | str | Path = "empty",
    options: PlantOptions | None = None,
    *,
    machine: MachineSource = SKID_STEER,
) -> PlantScenario:
    """The plant of a loader, a bucket load and circuit switches, resolved once (module notes).

    Parameters
    ----------
    loader : LoaderParameters, str, Path or None
        A loader, the path of its TOML file, or None for the shipped default loader.
    load : BucketLoad, str or Path
        A bucket load, the path of its TOML file, or a shipped case (``"empty"``, ``"full"``).
    options : PlantOptions, optional
        Circuit switches; default: pump, valves, leakage and friction on, load-holding valves
        open, accumulator shut, occupant on (``PlantOptions.for_controller`` gives a
        controller's circuit).
    machine : PlantLayout, str or pathlib.Path
        The machine: resolved (:func:`~loader_model.plant.layout.plant_layout`), or a name or
        description file resolved once here (default the skid-steer). For another machine,
        ``loader`` is its parameter file (a ``MachineParameters``, a path, or None for the
        shipped one) and ``load`` a load case of it (None or ``"full"``/``"empty"``, ...; the
        skid-steer's default ``"empty"`` is taken as given); the plant's pump, valves, friction,
        accumulator and occupant are estimates (:mod:`loader_model.plant.machine_parameters`).

    Returns
    -------
    PlantScenario

    Raises
    ------
    ValueError
        If a parameter set is invalid or the two do not stand together (naming the fields).
    TypeError
        If ``options`` is not a PlantOptions.
    """
    if options is None:
        options = PlantOptions()
    elif not isinstance(options, PlantOptions):
        raise TypeError(f"options must be a PlantOptions or None; got {type(options).__name__}")
    layout = resolve_layout(machine)
    if not layout.machine.is_default:
        from loader_model.parameters.machine_files import resolve_machine_parameters
        from loader_model.plant.machine_parameters import machine_plant_parameter_vector

        values = resolve_machine_parameters(layout.machine, loader)  # type: ignore[arg-type]
        case = None if load is None else str(load)
        params = machine_plant_parameter_vector(layout, values, case, options)
        return PlantScenario.from_vector(params, values, case, options, layout)
    loader, load = resolve_machine(loader, load)
    params = plant_parameter_vector(loader, load, options, check=False)
    return PlantScenario.from_vector(params, loader, load, options, layout)
