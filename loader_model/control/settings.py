r"""Controller settings (sections 3.2, 3.3; Table 3) as a validated parameter set and a CasADi vector.

:class:`ControllerSettings` is read from ``data/controller_default.toml`` in the parameter-file
style of :mod:`loader_model.parameters.toml_format` (every value ``{ value, unit, source }``, ranges with
reasons from :mod:`loader_model.parameters.fields`). The controllers of
:mod:`loader_model.control.controllers` take their numbers as one vector ``settings``
(:data:`SETTINGS_NAMES`), so one CasADi Function serves every setting. Four entries of that vector
are not controller settings but facts of the loader and its load case, passed in by
:func:`settings_vector` rather than copied: the pressure norm ‖p_A‖∞ (the bucket-load file's
``pressure_normalisation``: 100 bar empty, 200 bar full), V_p,max, gravity and the accelerometer
distance N_x (from the plant parameter vector), and the holding command u0 of the static
equilibrium (:func:`loader_model.plant.equilibrium.static_state`).

The loader file keeps its ``[controller]`` section (other code reads ``loader.controller.k_p``);
a test checks that its shared values equal this file's.
"""

from __future__ import annotations

import functools
import math
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from loader_model.io.files import read_text
from loader_model.parameters.checks import check_ranges
from loader_model.parameters.fields import Range, Sourced, si, sources_field
from loader_model.parameters.toml_format import build, dumps, to_raw

if TYPE_CHECKING:
    from loader_model.plant.layout import PlantLayout

__all__ = [
    "SETTINGS_NAMES",
    "ControllerSettings",
    "default_settings",
    "gain_norm_factors",
    "load_settings",
    "save_settings",
    "settings_vector",
    "settings_vector_for_plant",
    "with_gains",
    "with_scaled_gains",
    "without_gains",
]

#: Order of the ``settings`` input of every controller Function.
SETTINGS_NAMES: tuple[str, ...] = (
    "k_x",  # K_fb on the normalised (ẋ_H, ẏ_H, θ̇1, φ − φ0), Table 3
    "k_y",
    "k_theta",
    "k_phi",
    "tau",  # semi-integrator corner [rad/s]
    "k_p",  # pressure-loop gain [-]
    "omega_hp",  # high-pass corner on p_A [rad/s]
    "T_s",  # sample time [s]
    "a_norm",  # [m/s^2]
    "alpha_norm",  # [rad/s^2]
    "phi_norm",  # [rad]
    "u_limit",  # command saturation [m^3/rev] (a valve's: m of spool)
    "p_norm",  # ‖p_A‖∞ of the load case [Pa]
    "V_p_max",  # the actuator's limit: V_p,max [m^3/rev], or a valve's spool stroke [m]
    "u_hold",  # holding command u0 [m^3/rev] (a valve's: spool position [m])
    "g",  # gravity [m/s^2]
    "N_x",  # x of the second accelerometer N relative to H [m]
    "phi_0",  # boom angle of the operating point (plant output phi) [rad]
)


@dataclass(frozen=True)
class ControllerSettings(Sourced):
    """Settings of the 1 kHz controllers (sections 3.2, 3.3; Table 3).

    Attributes
    ----------
    k_fb : tuple of 4 float
        Skyhook gains on the normalised (ẋ_H, ẏ_H, θ̇1, φ − φ0) of Eq. 40 (Table 3).
    tau : float
        Corner τ of the semi-integrator 1/(s + τ) that turns accelerations into velocities [rad/s].
    k_p : float
        Pressure-loop gain on normalised signals (section 3.2).
    highpass_corner : float
        Corner ω_hp of the high-pass s/(s + ω_hp) on p_A [rad/s]; the paper gives none.
    sample_rate : float
        Controller sample rate [Hz].
    linear_acceleration_norm, angular_acceleration_norm, angle_norm : float
        Norms of the feedback signals (section 3.3): 2 g, 20 rad/s², 33°.
    command_limit : float
        Saturation of the command V_p,ref as a fraction of V_p,max (±).
    ride_control_min_speed : float
        Travel speed [m/s] below which the ride control is off: the machine drives as the
        baseline, load-holding valves closed (0, the default: on at every speed, as in the
        paper). Commercial ride control switches itself on above a speed, for example about
        9.5 km/h (6 mph) in AUTO (US Army TM 5-3805-291-23-1, theory of operation of the
        electro-hydraulic system); the courses here are driven at one speed, so the gate
        holds for a whole run (:meth:`~loader_model.simulation.scenario.Scenario.at_speed`).
    """

    k_fb: tuple[float, float, float, float] = field(
        metadata=si(
            "-",
            Range(
                -100.0, 100.0, reason="gains on signals normalised to 1; Table 3 gains are below 6"
            ),
            shape=4,
        )
    )
    tau: float = field(
        metadata=si(
            "rad/s",
            Range(0.1, 300.0, reason="below a tenth of 1 kHz sampling, above a 60 s time constant"),
        )
    )
    k_p: float = field(
        metadata=si(
            "-",
            Range(0.0, 100.0, low_open=True, reason="a gain on normalised signals is positive"),
        )
    )
    highpass_corner: float = field(
        metadata=si(
            "rad/s",
            Range(0.01, 100.0, reason="removes the static pressure, below the 2-3 Hz body modes"),
        )
    )
    sample_rate: float = field(
        metadata=si("Hz", Range(50.0, 100000.0, reason="digital controllers of 50 Hz to 100 kHz"))
    )
    linear_acceleration_norm: float = field(
        metadata=si("m/s^2", Range(0.1, 1000.0, reason="0.01 g to 100 g (section 3.3: 2 g)"))
    )
    angular_acceleration_norm: float = field(
        metadata=si("rad/s^2", Range(0.1, 1000.0, reason="0.1-1000 rad/s^2 (section 3.3: 20)"))
    )
    angle_norm: float = field(
        metadata=si(
            "rad", Range(0.01, math.pi, reason="0.6 deg to half a turn (section 3.3: 33 deg)")
        )
    )
    command_limit: float = field(
        metadata=si(
            "-",
            Range(0.0, 1.0, low_open=True, reason="a fraction of the pump's maximum displacement"),
        )
    )
    ride_control_min_speed: float = field(
        default=0.0,
        metadata=si(
            "m/s",
            Range(0.0, 15.0, reason="0 (always on) to 54 km/h, above any loader's travel speed"),
        ),
    )
    sources: tuple[tuple[str, str], ...] = sources_field()


def _parse(text: str, origin: str) -> ControllerSettings:
    try:
        settings = build(ControllerSettings, tomllib.loads(text))
        check_ranges(settings)  # type: ignore[arg-type]
    except ValueError as exc:
        raise ValueError(f"{origin}: {exc}") from None
    return settings


def load_settings(path: str | Path) -> ControllerSettings:
    """Read and validate a controller settings file; errors name the file, field and range."""
    return _parse(read_text(path, "controller settings file"), str(path))


def with_gains(settings: ControllerSettings, k_fb: object, source: str) -> ControllerSettings:
    """A validated copy of ``settings`` with skyhook gains ``k_fb`` (4 numbers) from ``source``."""
    raw = to_raw(settings)
    raw["k_fb"] = {
        **raw["k_fb"],
        "value": [float(k) for k in np.asarray(k_fb, dtype=float).ravel()],
        "source": source,
    }
    return _parse(dumps(raw), "designed gains")


def with_scaled_gains(
    settings: ControllerSettings, k_fb: object, source: str, limit: float = 50.0
) -> ControllerSettings:
    """:func:`with_gains`, with the feedback norms scaled so that every gain is at most
    ``limit`` in magnitude: the same control law (a gain k on a signal normalised by n is the
    gain k c on the signal normalised by n c). The linear-acceleration norm is shared by k_x and
    k_y, the angular-acceleration norm belongs to k_θ, the angle norm to k_φ; a norm is only
    made smaller (c ≤ 1). For machines whose designed gains exceed the file's range of ±100."""
    gains = np.array(k_fb, dtype=float).ravel()  # a copy: the caller's gains stay as given
    raw = to_raw(settings)
    groups = (("linear_acceleration_norm", (0, 1)), ("angular_acceleration_norm", (2,)),
              ("angle_norm", (3,)))  # fmt: skip
    for name, members in groups:
        largest = max(abs(gains[i]) for i in members)
        if largest > limit:
            factor = float(limit / largest)
            gains[list(members)] *= factor
            raw[name] = {
                **raw[name],
                "value": float(raw[name]["value"]) * factor,
                "source": f"{source}: scaled by {factor:.6g} with its gains (same control law)",
            }
    return with_gains(_parse(dumps(raw), "scaled norms"), gains, source)


def without_gains(settings: ControllerSettings) -> ControllerSettings:
    """``settings`` with the shipped feedback norms and gains (Table 3) in place of its own: the
    base a designed gain is written into, every other setting kept (k_p, τ, the filters, the
    speed below which the ride control is off)."""
    raw, shipped = to_raw(settings), to_raw(default_settings())
    for name in ("k_fb", "linear_acceleration_norm", "angular_acceleration_norm", "angle_norm"):
        raw[name] = shipped[name]
    return _parse(dumps(raw), "settings without their gains")


def gain_norm_factors(settings: ControllerSettings) -> np.ndarray:
    """Per gain k_fb, the factor c by which ``settings`` scaled its norm against the shipped
    settings (:func:`with_scaled_gains`): its gains are c K for the raw gains K on the shipped
    norms (1 where a norm was not scaled)."""
    shipped = default_settings()
    factors = np.ones(4)
    for name, members in (
        ("linear_acceleration_norm", (0, 1)),
        ("angular_acceleration_norm", (2,)),
        ("angle_norm", (3,)),
    ):
        factors[list(members)] = getattr(settings, name) / getattr(shipped, name)
    return factors


def save_settings(settings: ControllerSettings, path: str | Path, header: str = "") -> None:
    """Write ``settings`` as a controller TOML file (atomically; :func:`load_settings` reads it
    back equal)."""
    from loader_model.io.export import write_atomically

    text = dumps(to_raw(settings), header)
    write_atomically(
        path,
        lambda temporary: temporary.write_text(text, encoding="utf-8", newline="\n"),
        (".toml",),
        "controller settings file",
    )


@functools.cache
def default_settings() -> ControllerSettings:
    """The shipped settings, ``data/controller_default.toml`` (Table 3 values)."""
    name = "controller_default.toml"
    text = resources.files("loader_model").joinpath("data", name).read_text(encoding="utf-8")
    return _parse(text, name)


def settings_vector(
    settings: ControllerSettings,
    *,
    pressure_norm: float,
    max_displacement: float,
    hold_command: float,
    gravity: float,
    accelerometer_x: float,
    boom_angle: float = 0.0,
) -> np.ndarray:
    """The ``settings`` input of the controller Functions, in the order :data:`SETTINGS_NAMES`.

    Parameters
    ----------
    settings : ControllerSettings
    pressure_norm : float
        ‖p_A‖∞ of the load case [Pa] (``BucketLoad.pressure_normalisation``).
    max_displacement : float
        The actuator's command limit: V_p,max [m³/rev] of the pump, or the spool stroke
        x_s,max [m] of a valve circuit (the pressure loop's command is k_p times it).
    hold_command : float
        Feed-forward command u0 that holds the boom against leakage [m³/rev].
    gravity : float
        g [m/s²], removed from the vertical accelerometer reading at H.
    accelerometer_x : float
        N_x − H_x [m], the lever of the pitch acceleration (section 3.3).
    boom_angle : float
        φ0 [rad], the boom angle (plant output ``phi``) at the operating point.
    """
    for name, value in (
        ("pressure_norm", pressure_norm),
        ("max_displacement", max_displacement),
        ("gravity", gravity),
    ):
        if not math.isfinite(value) or value <= 0:
            raise ValueError(f"{name} = {value!r}; allowed: a finite number > 0")
    if not math.isfinite(accelerometer_x) or abs(accelerometer_x) < 0.05:
        raise ValueError(
            f"accelerometer_x = {accelerometer_x!r} m; allowed: |N_x| >= 0.05 m "
            "(the pitch acceleration divides by it)"
        )
    values = (
        *settings.k_fb,
        settings.tau,
        settings.k_p,
        settings.highpass_corner,
        1.0 / settings.sample_rate,
        settings.linear_acceleration_norm,
        settings.angular_acceleration_norm,
        settings.angle_norm,
        settings.command_limit * max_displacement,
        pressure_norm,
        max_displacement,
        hold_command,
        gravity,
        accelerometer_x,
        boom_angle,
    )
    vector = np.array(values, dtype=float)
    if not np.all(np.isfinite(vector)):
        raise ValueError(f"settings vector {vector} has a non-finite entry")
    return vector


def settings_vector_for_plant(
    settings: ControllerSettings,
    params: np.ndarray,
    pressure_norm: float,
    *,
    hold_command: float | None = None,
    layout: PlantLayout | None = None,
) -> np.ndarray:
    """:func:`settings_vector` with the command limit (V_p,max, or a valve's spool stroke
    x_s,max), g and N_x from the plant parameter vector ``params``
    and the holding command from its static equilibrium (boom angle φ0 = 0, the plant's origin).

    ``hold_command``: the equilibrium's u0 when the caller has it
    (:class:`~loader_model.plant.scenario.PlantScenario`); default: computed from ``params``.
    ``layout``: the plant's machine (default the skid-steer)."""
    from loader_model.plant.equilibrium import static_state
    from loader_model.plant.layout import SKID_STEER

    layout = layout or SKID_STEER
    names = layout.parameter_names
    named = dict(zip(names, np.asarray(params, dtype=float), strict=True))
    hold = static_state(params, layout)[1] if hold_command is None else float(hold_command)
    return settings_vector(
        settings,
        pressure_norm=pressure_norm,
        max_displacement=float(named[layout.command_limit]),
        hold_command=hold,
        gravity=float(named["g"]),
        accelerometer_x=float(named["N_x"]),
    )
