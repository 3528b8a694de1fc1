"""The generated loader model bound to one set of parameter values (paper section 2.1, Eq. 25-40).

:class:`LoaderDynamics` validates its arguments, computes the static equilibrium (tyre loads and
cylinder force that make p = 0 an equilibrium, DESIGN.md "Gravity") and evaluates the CasADi
functions of ``loader_model_generated``. It never imports SymPy.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import loader_model_generated as generated
from loader_model.io.arrays import finite_scalar, finite_vector
from loader_model.parameters.model_checks import check_model_parameters

__all__ = [
    "COORDINATE_NAMES",
    "EXOGENOUS_NAMES",
    "OUTPUT_NAMES",
    "PARAMETER_NAMES",
    "STATE_NAMES",
    "LinearModel",
    "LoaderDynamics",
]

PARAMETER_NAMES: tuple[str, ...] = generated.PARAMETER_NAMES
COORDINATE_NAMES: tuple[str, ...] = generated.COORDINATE_NAMES
STATE_NAMES: tuple[str, ...] = generated.STATE_NAMES
EXOGENOUS_NAMES: tuple[str, ...] = generated.EXOGENOUS_NAMES
OUTPUT_NAMES: tuple[str, ...] = generated.OUTPUT_NAMES
_STATIC_LOADS = ("F_Ay0", "F_By0")


@dataclass(frozen=True)
class LinearModel:
    """ẋ = A x + B u + E w, y = C x + D_u u + D_w w (Eq. 38-40) with named signals."""

    A: np.ndarray
    B: np.ndarray
    E: np.ndarray
    C: np.ndarray
    D_u: np.ndarray
    D_w: np.ndarray
    state_names: tuple[str, ...] = STATE_NAMES
    input_names: tuple[str, ...] = ("F_act",)
    exogenous_names: tuple[str, ...] = EXOGENOUS_NAMES
    output_names: tuple[str, ...] = OUTPUT_NAMES

    def state_space(self, *, exogenous: bool = True, name: str = "loader") -> Any:
        """Return a python-control ``StateSpace`` with named states, inputs and outputs.

        Inputs are F_act [N] and, with ``exogenous``, the road and disturbance inputs w.
        """
        import control

        inputs = list(self.input_names)
        b_matrix, d_matrix = self.B, self.D_u
        if exogenous:
            inputs += list(self.exogenous_names)
            b_matrix = np.hstack([self.B, self.E])
            d_matrix = np.hstack([self.D_u, self.D_w])
        return control.ss(
            self.A,
            b_matrix,
            self.C,
            d_matrix,
            states=list(self.state_names),
            inputs=inputs,
            outputs=list(self.output_names),
            name=name,
        )

    def save(self, path: str | Path) -> Path:
        """Export A, B, E, C, D_u, D_w and the signal names to ``.npz`` or ``.mat`` (atomic)."""
        from loader_model.io.export import save_arrays

        return save_arrays(
            path,
            {
                "A": self.A,
                "B": self.B,
                "E": self.E,
                "C": self.C,
                "D_u": self.D_u,
                "D_w": self.D_w,
                "state_names": list(self.state_names),
                "input_names": list(self.input_names),
                "exogenous_names": list(self.exogenous_names),
                "output_names": list(self.output_names),
            },
        )


#: Plausible magnitudes of the runtime arguments: 10 km of travel, half a turn of pitch, 1 km/s,
#: 100 MN (a hundred times the weight of the heaviest machine of the class).
_MAX_POSITION_M = 1e4
_MAX_ANGLE_RAD = np.pi
_MAX_RATE = 1e3
_MAX_FORCE_N = 1e8


def _coordinates(p: Any) -> np.ndarray:
    """p = (x_H, y_H, θ1, θ2), positions within 10 km and angles within half a turn."""
    p = finite_vector("p", p, 4)
    limits = np.array([_MAX_POSITION_M, _MAX_POSITION_M, _MAX_ANGLE_RAD, _MAX_ANGLE_RAD])
    if np.any(np.abs(p) > limits):
        raise ValueError(
            f"p = {p.tolist()} is implausible; allowed: |x_H|, |y_H| <= {_MAX_POSITION_M:g} m "
            f"and |theta_1|, |theta_2| <= pi rad"
        )
    return p


def _finite(result: np.ndarray, args: list[np.ndarray]) -> np.ndarray:
    if not np.all(np.isfinite(result)):
        names = ("p", "pd", "force_N", "road_m", "road_rate_m_s", "disturbance")
        shown = ", ".join(f"{n}={a.tolist()}" for n, a in zip(names, args, strict=False))
        raise ValueError(f"the model gives a non-finite result at {shown}")
    return result


def _dense(value: Any) -> np.ndarray:
    return np.asarray(value.full() if hasattr(value, "full") else value, dtype=float)


class LoaderDynamics:
    """Generated equations of motion with bound parameter values.

    Parameters
    ----------
    parameter_values
        A value for every name in :data:`PARAMETER_NAMES` (SI units, see
        ``loader_model_generated.PARAMETER_UNITS``). The static tyre loads ``F_Ay0`` and
        ``F_By0`` may be left out: with ``equilibrium=True`` they are computed so that p = 0 is a
        static equilibrium (and replace given values).
    equilibrium
        Compute the static tyre loads from the static equilibrium.
    check_ranges
        Apply the plausibility ranges of the parameter files (default). ``False`` is for
        analysis models outside the machines' range, e.g. a tyre removed (k = 0) to compare
        with a tyre that lost contact; the values must still be finite real numbers.

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
    ) -> None:
        if not isinstance(parameter_values, Mapping):
            raise ValueError(
                f"parameter_values must be a mapping of parameter name to value; got "
                f"{type(parameter_values).__name__}"
            )
        for flag, value in (("equilibrium", equilibrium), ("check_ranges", check_ranges)):
            if not isinstance(value, bool):
                raise ValueError(f"{flag} must be True or False; got {value!r}")
        names = set(PARAMETER_NAMES)
        unknown = sorted(set(parameter_values) - names, key=repr)
        if unknown:
            raise ValueError(
                f"unknown model parameters {unknown}; allowed: {list(PARAMETER_NAMES)}"
            )
        optional = set(_STATIC_LOADS) if equilibrium else set()
        missing = [n for n in PARAMETER_NAMES if n not in parameter_values and n not in optional]
        if missing:
            raise ValueError(f"missing model parameters {missing}")
        values = {
            n: finite_scalar(f"model parameter {n}", parameter_values.get(n, 0.0))
            for n in PARAMETER_NAMES
        }
        given = {n: v for n, v in values.items() if n in parameter_values and n not in optional}
        if check_ranges:
            check_model_parameters(given)
        vector = np.array([values[n] for n in PARAMETER_NAMES])
        # The generated complete_parameters holds the static equilibrium inside the graph, so a
        # CasADi graph of varied parameters stays at rest the same way (issue 7).
        completed, force = generated.function("complete_parameters")(vector)
        self.static_cylinder_force_N = float(force)
        """Cylinder force F_act0 that holds the boom at p = 0 [N]."""
        if equilibrium:
            vector = _dense(completed).ravel()
        if equilibrium and check_ranges and values["g"] != 0.0:  # no loads without gravity
            check_model_parameters(
                {name: float(vector[PARAMETER_NAMES.index(name)]) for name in _STATIC_LOADS}
            )
        self.parameters = vector
        """Parameter vector in the order of :data:`PARAMETER_NAMES`."""
        self._check_mass_matrix()

    @classmethod
    def from_parameters(cls, loader: Any = None, load: Any = "empty") -> LoaderDynamics:
        """Model of a loader parameter set with a bucket load.

        Parameters
        ----------
        loader
            A :class:`loader_model.parameters.sets.LoaderParameters`, a path to its TOML file, or
            None for the default loader.
        load
            A :class:`loader_model.parameters.sets.BucketLoad`, a path to its TOML file, or the name of
            a shipped load case (``"empty"``: 340 kg, ``"full"``: 770 kg, paper section 5.3).
        """
        from loader_model.parameters import model_parameter_values
        from loader_model.vehicle.statics import resolve_machine

        loader, load = resolve_machine(loader, load)
        return cls(model_parameter_values(loader, load))

    def _check_mass_matrix(self) -> None:
        mass = self.mass_matrix(np.zeros(4))
        eigenvalues = np.linalg.eigvalsh(0.5 * (mass + mass.T))
        if not np.all(eigenvalues > 0):
            raise ValueError(
                "the mass matrix at p = 0 is not positive definite (eigenvalues "
                f"{eigenvalues.tolist()}); check m_1, m_2 > 0, J_1, J_2 > 0"
            )

    def parameter(self, name: str) -> float:
        """Value of the parameter ``name``."""
        if name not in PARAMETER_NAMES:
            raise ValueError(f"unknown model parameter {name!r}; allowed: {list(PARAMETER_NAMES)}")
        return float(self.parameters[PARAMETER_NAMES.index(name)])

    def mass_matrix(self, p: Any) -> np.ndarray:
        """M(p), Eq. 25 (Eq. 32 at p = 0)."""
        return _dense(generated.function("mass_matrix")(_coordinates(p), self.parameters))

    def forward_dynamics(
        self,
        p: Any,
        pd: Any,
        force_N: float | None = None,
        road_m: Any = (0.0, 0.0, 0.0, 0.0),
        road_rate_m_s: Any = (0.0, 0.0, 0.0, 0.0),
        disturbance: Any = (0.0, 0.0, 0.0),
        anchor_m: Any = (0.0, 0.0),
    ) -> np.ndarray:
        """Accelerations p̈ (Eq. 25) with the tyre contact law (``derive/contact.py``).

        ``force_N`` is the total lift-cylinder force (default: the static force F_act0);
        ``road_m`` = (w_Ax, w_Ay, w_Bx, w_By); ``disturbance`` = (F_dx, F_dy, M_d) at H;
        ``anchor_m`` = (ξ_A, ξ_B), the slid distance of each tyre's contact point.
        """
        force = self.static_cylinder_force_N if force_N is None else force_N
        args = self._arguments(p, pd, force, road_m, road_rate_m_s, disturbance)
        p, pd, force, road, road_rate, disturbance, params = args
        anchor = finite_vector("anchor_m", anchor_m, 2, _MAX_POSITION_M, "m")
        pdd, _ = generated.function("forward_dynamics")(
            p, pd, anchor, force, road, road_rate, disturbance, params
        )
        return _finite(_dense(pdd).ravel(), args)

    def tyre_contact(
        self,
        p: Any,
        pd: Any = (0.0, 0.0, 0.0, 0.0),
        anchor_m: Any = (0.0, 0.0),
        road_m: Any = (0.0, 0.0, 0.0, 0.0),
        road_rate_m_s: Any = (0.0, 0.0, 0.0, 0.0),
    ) -> dict[str, np.ndarray]:
        """Road forces on the axles ``F_tyre`` = (F_Ax, F_Ay, F_Bx, F_By) [N] (world frame), their
        generalised forces ``Q_tyre`` and the anchor rates ``anchor_rate`` [m/s]."""
        values = generated.function("tyre_contact")(
            _coordinates(p),
            finite_vector("pd", pd, 4, _MAX_RATE, "m/s or rad/s"),
            finite_vector("anchor_m", anchor_m, 2, _MAX_POSITION_M, "m"),
            finite_vector("road_m", road_m, 4, _MAX_POSITION_M, "m"),
            finite_vector("road_rate_m_s", road_rate_m_s, 4, _MAX_RATE, "m/s"),
            self.parameters,
        )
        names = ("F_tyre", "Q_tyre", "anchor_rate")
        return {name: _dense(v).ravel() for name, v in zip(names, values, strict=True)}

    def specific_forces(self, p: Any, pd: Any, pdd: Any) -> dict[str, np.ndarray]:
        """What chassis-fixed accelerometers at H, N and S read: R(θ1)ᵀ (a + g ŷ) [m/s²]."""
        values = generated.function("specific_forces")(
            _coordinates(p),
            finite_vector("pd", pd, 4, _MAX_RATE, "m/s or rad/s"),
            finite_vector("pdd", pdd, 4),
            self.parameters,
        )
        return {k: _dense(v).ravel() for k, v in zip("HNS", values, strict=True)}

    def linearise(
        self,
        p: Any = (0.0, 0.0, 0.0, 0.0),
        pd: Any = (0.0, 0.0, 0.0, 0.0),
        force_N: float | None = None,
        road_m: Any = (0.0, 0.0, 0.0, 0.0),
        road_rate_m_s: Any = (0.0, 0.0, 0.0, 0.0),
        disturbance: Any = (0.0, 0.0, 0.0),
    ) -> LinearModel:
        """Linear model (Eq. 38-40) at an operating point; default: the static equilibrium.

        Uses the paper's linear tyre law (Eq. 1-4), i.e. both tyres in contact.
        """
        force = self.static_cylinder_force_N if force_N is None else force_N
        args = self._arguments(p, pd, force, road_m, road_rate_m_s, disturbance)
        a, b, e, c, d_u, d_w, _ = (
            _finite(_dense(m), args) for m in generated.function("linearisation")(*args)
        )
        return LinearModel(A=a, B=b, E=e, C=c, D_u=d_u, D_w=d_w)

    def cylinder_kinematics(self, p: Any, pd: Any = (0.0, 0.0, 0.0, 0.0)) -> dict[str, float]:
        """x_cyl [m], ẋ_cyl [m/s], dx_cyl/dφ [m/rad] (Eq. 35) and γ [rad] (Eq. 15-16)."""
        p, pd = _coordinates(p), finite_vector("pd", pd, 4, _MAX_RATE, "m/s or rad/s")
        values = generated.function("cylinder_kinematics")(p, pd, self.parameters)
        names = ("x_cyl", "xd_cyl", "dx_cyl_dphi", "gamma")
        return {name: float(value) for name, value in zip(names, values, strict=True)}

    def point_positions(self, p: Any) -> dict[str, np.ndarray]:
        """World positions [m] of the points A, B, C, D, E, G, H, N, S."""
        values = generated.function("point_positions")(_coordinates(p), self.parameters)
        return {f"{k}": _dense(v).ravel() for k, v in zip("ABCDEGHNS", values, strict=True)}

    def _arguments(
        self, p: Any, pd: Any, force: Any, road: Any, road_rate: Any, disturbance: Any
    ) -> list[np.ndarray]:
        return [
            _coordinates(p),
            finite_vector("pd", pd, 4, _MAX_RATE, "m/s or rad/s"),
            finite_vector("force_N", force, 1, _MAX_FORCE_N, "N"),
            finite_vector("road_m", road, 4, _MAX_POSITION_M, "m"),
            finite_vector("road_rate_m_s", road_rate, 4, _MAX_RATE, "m/s"),
            finite_vector("disturbance", disturbance, 3, _MAX_FORCE_N, "N or N m"),
            self.parameters,
        ]
