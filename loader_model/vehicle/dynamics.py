"""The generated model of a machine bound to one set of parameter values (section 2.1, Eq. 25-40).

:class:`LoaderDynamics` validates its arguments, computes the static equilibrium (tyre loads,
cylinder force and locked-cylinder preloads that make p = 0 an equilibrium; guide page "Model")
and evaluates the CasADi functions of the machine's generated package
(:func:`loader_model.machines.machine`; default: the skid-steer, ``loader_model_generated``).
Sizes and names come from the generated metadata. It never imports SymPy.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

import loader_model_generated as generated
from loader_model.io.arrays import finite_scalar, finite_vector
from loader_model.machines import DEFAULT_MACHINE, MachineInfo, machine
from loader_model.parameters.machine_files import check_machine_model_values
from loader_model.parameters.model_checks import check_model_parameters
from loader_model.vehicle.linear_model import LinearModel

__all__ = [
    "COORDINATE_NAMES",
    "EXOGENOUS_NAMES",
    "OUTPUT_NAMES",
    "PARAMETER_NAMES",
    "STATE_NAMES",
    "LinearModel",
    "LoaderDynamics",
]

#: Names of the default machine (the skid-steer); a model's own are ``model.machine.*_names``.
PARAMETER_NAMES: tuple[str, ...] = generated.PARAMETER_NAMES
COORDINATE_NAMES: tuple[str, ...] = generated.COORDINATE_NAMES
STATE_NAMES: tuple[str, ...] = generated.STATE_NAMES
EXOGENOUS_NAMES: tuple[str, ...] = generated.EXOGENOUS_NAMES
OUTPUT_NAMES: tuple[str, ...] = generated.OUTPUT_NAMES

#: Plausible magnitudes of the runtime arguments: 10 km of travel, half a turn of pitch, 1 km/s,
#: 100 MN (a hundred times the weight of the heaviest machine of the class).
_MAX_POSITION_M = 1e4
_MAX_ANGLE_RAD = np.pi
_MAX_RATE = 1e3
_MAX_FORCE_N = 1e8


def _finite(result: np.ndarray, args: list[np.ndarray]) -> np.ndarray:
    if not np.all(np.isfinite(result)):
        names = ("p", "pd", "force_N", "road_m", "road_rate_m_s", "disturbance")
        shown = ", ".join(f"{n}={a.tolist()}" for n, a in zip(names, args, strict=False))
        raise ValueError(f"the model gives a non-finite result at {shown}")
    return result


def _dense(value: Any) -> np.ndarray:
    return np.asarray(value.full() if hasattr(value, "full") else value, dtype=float)


class LoaderDynamics:
    """Generated equations of motion of a machine with bound parameter values.

    Parameters
    ----------
    parameter_values
        A value for every parameter of the machine (:data:`PARAMETER_NAMES` for the skid-steer;
        ``machine(name).parameter_names``; SI units, see the generated ``PARAMETER_UNITS``).
        The static loads (``F_Ay0``, ``F_By0``, a locked cylinder's ``F_<name>0``) may be left
        out: with ``equilibrium=True`` they are computed so that p = 0 is a static equilibrium
        (and replace given values).
    equilibrium
        Compute the static loads from the static equilibrium.
    check_ranges
        Apply the plausibility ranges of the parameter files (default; for another machine the
        ranges of its description). ``False`` is for analysis models outside the machines'
        range, e.g. a tyre removed (k = 0) to compare with a tyre that lost contact; the values
        must still be finite real numbers.
    machine
        A machine name or description file (:func:`loader_model.machines.machine`), or its
        :class:`~loader_model.machines.MachineInfo`; default: the skid-steer.

    Raises
    ------
    ValueError
        On a missing or unknown parameter; a value that is not one finite real number (a Python
        or NumPy int or float; not an array, even of one element, a boolean or a string,
        :func:`loader_model.io.arrays.real_number`); a value outside the plausible range of
        the parameter-file field it comes from, coincident points or A not ahead of B
        (:func:`loader_model.parameters.model_checks.check_model_parameters`); a static axle load
        that is not compressive; or a mass matrix that is not positive definite at p = 0.
    """

    def __init__(
        self,
        parameter_values: Mapping[str, float],
        *,
        equilibrium: bool = True,
        check_ranges: bool = True,
        machine: str | MachineInfo = DEFAULT_MACHINE,
    ) -> None:
        info = machine if isinstance(machine, MachineInfo) else _machine(machine)
        self.machine = info
        """The registry entry of the machine (names, sizes, structure)."""
        self._function = info.function
        if not isinstance(parameter_values, Mapping):
            raise ValueError(
                f"parameter_values must be a mapping of parameter name to value; got "
                f"{type(parameter_values).__name__}"
            )
        for flag, value in (("equilibrium", equilibrium), ("check_ranges", check_ranges)):
            if not isinstance(value, bool):
                raise ValueError(f"{flag} must be True or False; got {value!r}")
        all_names = info.parameter_names
        unknown = sorted(set(parameter_values) - set(all_names), key=repr)
        if unknown:
            raise ValueError(f"unknown model parameters {unknown}; allowed: {list(all_names)}")
        optional = set(info.static_names) if equilibrium else set()
        missing = [n for n in all_names if n not in parameter_values and n not in optional]
        if missing:
            raise ValueError(f"missing model parameters {missing}")
        values = {
            n: finite_scalar(f"model parameter {n}", parameter_values.get(n, 0.0))
            for n in all_names
        }
        given = {n: v for n, v in values.items() if n in parameter_values and n not in optional}
        check = check_model_parameters if info.is_default else self._check_machine
        if check_ranges:
            check(given)
        vector = np.array([values[n] for n in all_names])
        # The generated complete_parameters holds the static equilibrium inside the graph, so a
        # CasADi graph of varied parameters stays at rest the same way.
        completed, force = self._function("complete_parameters")(vector)
        self.static_cylinder_force_N = float(force)
        """Cylinder force F_act0 that holds the boom at p = 0 [N]."""
        if equilibrium:
            vector = _dense(completed).ravel()
        if equilibrium and check_ranges and values["g"] != 0.0:  # no loads without gravity
            tyre_loads = [f"F_{axle}y0" for axle in info.axles]
            check({name: float(vector[all_names.index(name)]) for name in tyre_loads})
        self.parameters = vector
        """Parameter vector in the order of the machine's parameter names."""
        self._check_mass_matrix()

    def _check_machine(self, values: Mapping[str, float]) -> None:
        check_machine_model_values(self.machine, values)

    @classmethod
    def from_parameters(
        cls, loader: Any = None, load: Any = "empty", machine: str = DEFAULT_MACHINE
    ) -> LoaderDynamics:
        """Model of a machine's parameter set with a bucket load.

        Parameters
        ----------
        loader
            For the skid-steer a :class:`loader_model.parameters.sets.LoaderParameters`, a path
            to its TOML file, or None for the default loader; for another machine a
            :class:`loader_model.parameters.machine_files.MachineParameters`, a path to its flat
            parameter file, or None for its shipped values.
        load
            For the skid-steer a :class:`loader_model.parameters.sets.BucketLoad`, a path to its
            TOML file, or the name of a shipped load case (``"empty"``: 340 kg, ``"full"``:
            770 kg, paper section 5.3); for another machine a load case of its parameter file
            (None: its ``[model]`` values as given).
        machine
            A machine name or description file (:func:`loader_model.machines.machine`).
        """
        from loader_model.vehicle.statics import resolve_machine, resolve_machine_values

        info = _machine(machine)
        if not info.is_default:
            return cls(resolve_machine_values(info, loader, load), machine=info)
        from loader_model.parameters import model_parameter_values

        loader, load = resolve_machine(loader, load)
        return cls(model_parameter_values(loader, load))

    def _check_mass_matrix(self) -> None:
        mass = self.mass_matrix(np.zeros(self.machine.n_coordinates))
        eigenvalues = np.linalg.eigvalsh(0.5 * (mass + mass.T))
        if not np.all(eigenvalues > 0):
            names = self.machine.parameter_names
            masses = ", ".join(n for n in names if n.startswith("m_"))
            inertias = ", ".join(n for n in names if n.startswith("J_"))
            raise ValueError(
                "the mass matrix at p = 0 is not positive definite (eigenvalues "
                f"{eigenvalues.tolist()}); check {masses} > 0, {inertias} > 0"
            )

    def parameter(self, name: str) -> float:
        """Value of the parameter ``name``."""
        names = self.machine.parameter_names
        if name not in names:
            raise ValueError(f"unknown model parameter {name!r}; allowed: {list(names)}")
        return float(self.parameters[names.index(name)])

    def _coordinates(self, p: Any) -> np.ndarray:
        """p, positions within 10 km and angles within half a turn."""
        names = self.machine.coordinate_names
        p = finite_vector("p", p, len(names))
        limits = np.array([_MAX_POSITION_M] * 2 + [_MAX_ANGLE_RAD] * (len(names) - 2))
        if np.any(np.abs(p) > limits):
            angles = ", ".join(f"|{n}|" for n in names[2:])
            raise ValueError(
                f"p = {p.tolist()} is implausible; allowed: |{names[0]}|, |{names[1]}| <= "
                f"{_MAX_POSITION_M:g} m and {angles} <= pi rad"
            )
        return p

    def _rates(self, name: str, value: Any) -> np.ndarray:
        return finite_vector(name, value, self.machine.n_coordinates, _MAX_RATE, "m/s or rad/s")

    def _zeros(self, value: Any, names: tuple[str, ...]) -> Any:
        return np.zeros(len(names)) if value is None else value

    def mass_matrix(self, p: Any) -> np.ndarray:
        """M(p), Eq. 25 (Eq. 32 at p = 0)."""
        return _dense(self._function("mass_matrix")(self._coordinates(p), self.parameters))

    def forward_dynamics(
        self,
        p: Any,
        pd: Any,
        force_N: float | None = None,
        road_m: Any = None,
        road_rate_m_s: Any = None,
        disturbance: Any = (0.0, 0.0, 0.0),
        anchor_m: Any = None,
    ) -> np.ndarray:
        """Accelerations p̈ (Eq. 25) with the tyre contact law (``derive/contact.py``).

        ``force_N`` is the total lift-cylinder force (default: the static force F_act0);
        ``road_m`` = (w_Ax, w_Ay, w_Bx, w_By) (the machine's ``road_names``; default zero);
        ``disturbance`` = (F_dx, F_dy, M_d) at H; ``anchor_m`` = (ξ_A, ξ_B), the slid distance
        of each tyre's contact point (default zero).
        """
        force = self.static_cylinder_force_N if force_N is None else force_N
        args = self._arguments(p, pd, force, road_m, road_rate_m_s, disturbance)
        p, pd, force, road, road_rate, disturbance, params = args
        anchors = self.machine.anchor_names
        anchor = finite_vector(
            "anchor_m", self._zeros(anchor_m, anchors), len(anchors), _MAX_POSITION_M, "m"
        )
        pdd, _ = self._function("forward_dynamics")(
            p, pd, anchor, force, road, road_rate, disturbance, params
        )
        return _finite(_dense(pdd).ravel(), args)

    def tyre_contact(
        self,
        p: Any,
        pd: Any = None,
        anchor_m: Any = None,
        road_m: Any = None,
        road_rate_m_s: Any = None,
    ) -> dict[str, np.ndarray]:
        """Road forces on the axles ``F_tyre`` = (F_Ax, F_Ay, F_Bx, F_By) [N] (world frame), their
        generalised forces ``Q_tyre`` and the anchor rates ``anchor_rate`` [m/s]."""
        info = self.machine
        n_road, n_anchor = len(info.road_names), len(info.anchor_names)
        values = self._function("tyre_contact")(
            self._coordinates(p),
            self._rates("pd", self._zeros(pd, info.coordinate_names)),
            finite_vector(
                "anchor_m", self._zeros(anchor_m, info.anchor_names), n_anchor, _MAX_POSITION_M, "m"
            ),
            finite_vector(
                "road_m", self._zeros(road_m, info.road_names), n_road, _MAX_POSITION_M, "m"
            ),
            finite_vector(
                "road_rate_m_s", self._zeros(road_rate_m_s, info.road_names), n_road, _MAX_RATE,
                "m/s",
            ),
            self.parameters,
        )  # fmt: skip
        names = ("F_tyre", "Q_tyre", "anchor_rate")
        return {name: _dense(v).ravel() for name, v in zip(names, values, strict=True)}

    def specific_forces(self, p: Any, pd: Any, pdd: Any) -> dict[str, np.ndarray]:
        """What chassis-fixed accelerometers at the sensor points (H, N, S) read:
        R(θ1)ᵀ (a + g ŷ) [m/s²]."""
        values = self._function("specific_forces")(
            self._coordinates(p),
            self._rates("pd", pd),
            finite_vector("pdd", pdd, self.machine.n_coordinates),
            self.parameters,
        )
        points = tuple(self.machine.sensor_points)
        return {k: _dense(v).ravel() for k, v in zip(points, values, strict=True)}

    def linearise(
        self,
        p: Any = None,
        pd: Any = None,
        force_N: float | None = None,
        road_m: Any = None,
        road_rate_m_s: Any = None,
        disturbance: Any = (0.0, 0.0, 0.0),
    ) -> LinearModel:
        """Linear model (Eq. 38-40) at an operating point; default: the static equilibrium.

        Uses the paper's linear tyre law (Eq. 1-4), i.e. both tyres in contact.
        """
        force = self.static_cylinder_force_N if force_N is None else force_N
        coordinates = self.machine.coordinate_names
        p, pd = self._zeros(p, coordinates), self._zeros(pd, coordinates)
        args = self._arguments(p, pd, force, road_m, road_rate_m_s, disturbance)
        a, b, e, c, d_u, d_w, _ = (
            _finite(_dense(m), args) for m in self._function("linearisation")(*args)
        )
        info = self.machine
        return LinearModel(
            A=a, B=b, E=e, C=c, D_u=d_u, D_w=d_w, state_names=info.state_names,
            exogenous_names=info.exogenous_names, output_names=info.output_names,
        )  # fmt: skip

    def cylinder_kinematics(self, p: Any, pd: Any = None) -> dict[str, float]:
        """Of the driven cylinder: x_cyl [m], ẋ_cyl [m/s], dx_cyl/dφ [m/rad] (Eq. 35) and γ
        [rad] (Eq. 15-16)."""
        pd = self._zeros(pd, self.machine.coordinate_names)
        p, pd = self._coordinates(p), self._rates("pd", pd)
        values = self._function("cylinder_kinematics")(p, pd, self.parameters)
        names = ("x_cyl", "xd_cyl", "dx_cyl_dphi", "gamma")
        return {name: float(value) for name, value in zip(names, values, strict=True)}

    def point_positions(self, p: Any) -> dict[str, np.ndarray]:
        """World positions [m] of the machine's points (A, B, C, D, E, G, H, N, S, ...)."""
        values = self._function("point_positions")(self._coordinates(p), self.parameters)
        points = self.machine.point_names
        return {f"{k}": _dense(v).ravel() for k, v in zip(points, values, strict=True)}

    def _arguments(
        self, p: Any, pd: Any, force: Any, road: Any, road_rate: Any, disturbance: Any
    ) -> list[np.ndarray]:
        roads = self.machine.road_names
        return [
            self._coordinates(p),
            self._rates("pd", pd),
            finite_vector("force_N", force, 1, _MAX_FORCE_N, "N"),
            finite_vector("road_m", self._zeros(road, roads), len(roads), _MAX_POSITION_M, "m"),
            finite_vector(
                "road_rate_m_s", self._zeros(road_rate, roads), len(roads), _MAX_RATE, "m/s"
            ),
            finite_vector("disturbance", disturbance, 3, _MAX_FORCE_N, "N or N m"),
            self.parameters,
        ]


def _machine(source: Any) -> MachineInfo:
    return machine(source)
