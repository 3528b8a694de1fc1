"""TEST FIXTURE, not the real plant: the linear loader with the paper's actuator and normalisation.

The real design plant comes from the hydraulics work (``loader_model/plant/``). Until then the
control tests and ``make bench`` use this assembly of the landed linear model (Eq. 38-40):

- actuator: p_A / p_A,ref of Eq. 43 with its numerator sign flipped (DESIGN.md errata 9),
  G(s) = −(2810 s − 6361) / (s³ + 222.3 s² + 6328 s + 78910): DC gain +0.081, zero at +2.26 rad/s
  still in the right half plane; F_act = A_p p_A with A_p = 2 π/4 (0.0635 m)² (two lift cylinders);
- normalisation (paper section 3.3): u = p_A,ref / 100 bar; fed-back y = (ẋ_H / 2g, ẏ_H / 2g,
  θ̇1 / (20 rad/s²), φ / 33°) — velocities scaled as the semi-integrated normalised accelerations;
- disturbances: F_dy and M_d at H as unit-intensity white noise through first-order low-pass
  filters (corner 2π·5 rad/s, gains 2 kN and 2 kN m), so no output feeds through from the noise;
- performance z = (a_Sx / 2g, a_Sy / 2g, θ̈1 / (20 rad/s²)): unweighted seat and pitch
  accelerations (the ISO 2631-1 weightings are left out of this fixture to keep it small).

States: 8 loader + 3 actuator + 2 disturbance filter = 13.
"""

from __future__ import annotations

import control
import numpy as np

from loader_model.control.design_plant import DesignPlant
from loader_model.vehicle.dynamics import LoaderDynamics

G_M_S2 = 9.81
PRESSURE_NORM_PA = 100e5
PISTON_AREA_M2 = 2 * np.pi / 4 * 0.0635**2
ACTUATOR_NUM = (-2810.0, 6361.0)
ACTUATOR_DEN = (1.0, 222.3, 6328.0, 78910.0)
FILTER_CORNER_RAD_S = 2 * np.pi * 5.0
DISTURBANCES = {"F_dy": 2e3, "M_d": 2e3}
MEASURED = {"xd_H": 2 * G_M_S2, "yd_H": 2 * G_M_S2, "thetad_1": 20.0, "phi": np.deg2rad(33.0)}
PERFORMANCE = {"a_Sx": 2 * G_M_S2, "a_Sy": 2 * G_M_S2, "thetadd_1": 20.0}
TABLE3_GAIN = np.array([[2.75, 5.10, -4.0, -0.22]])


def loader_design_plant(load: str = "empty") -> control.StateSpace:
    """13-state StateSpace with inputs (u, nu_Fy, nu_M) and outputs (y..., z...), see module doc."""
    lin = LoaderDynamics.from_parameters(None, load).linearise()
    names = list(lin.output_names)
    actuator = control.tf2ss(
        control.tf(np.array(ACTUATOR_NUM) * PRESSURE_NORM_PA * PISTON_AREA_M2, ACTUATOR_DEN)
    )
    a_act, b_act, c_act = (np.asarray(m) for m in (actuator.A, actuator.B, actuator.C))
    exo = [list(lin.exogenous_names).index(k) for k in DISTURBANCES]
    e_dist = lin.E[:, exo] * np.array(list(DISTURBANCES.values()))
    n_l, n_a, n_w = 8, a_act.shape[0], len(exo)
    a = np.zeros((n_l + n_a + n_w,) * 2)
    a[:n_l, :n_l] = lin.A
    a[:n_l, n_l : n_l + n_a] = lin.B @ c_act
    a[:n_l, n_l + n_a :] = e_dist
    a[n_l : n_l + n_a, n_l : n_l + n_a] = a_act
    a[n_l + n_a :, n_l + n_a :] = -FILTER_CORNER_RAD_S * np.eye(n_w)
    b = np.zeros((a.shape[0], 1 + n_w))
    b[n_l : n_l + n_a, :1] = b_act
    b[n_l + n_a :, 1:] = FILTER_CORNER_RAD_S * np.eye(n_w)

    def rows(scales: dict[str, float]) -> np.ndarray:
        index = [names.index(k) for k in scales]
        out = np.hstack(
            [
                lin.C[index],
                lin.D_u[index] @ c_act,
                lin.D_w[index][:, exo] * np.array(list(DISTURBANCES.values())),
            ]
        )
        return out / np.array(list(scales.values()))[:, None]

    c = np.vstack([rows(MEASURED), rows(PERFORMANCE)])
    states = [*lin.state_names, "act_0", "act_1", "act_2", "w_Fy", "w_M"]
    return control.ss(
        a,
        b,
        c,
        np.zeros((c.shape[0], b.shape[1])),
        states=states,
        inputs=["u", "nu_Fy", "nu_M"],
        outputs=[*MEASURED, *PERFORMANCE],
        name=f"loader_{load}",
    )


def loader_h2_plants(systems: dict[str, control.StateSpace] | None = None) -> list[DesignPlant]:
    """The two loads' design plants of the H2 tests: u, noise (nu_Fy, nu_M), measured y, and
    z = (y, seat and pitch accelerations), whose single-plant H2 optimum is the output-feedback
    LQR with Q = C_zᵀ C_z, R = 1, X0 = B_w B_wᵀ (J_H2 = 2 J_LQR)."""
    systems = systems or {load: loader_design_plant(load) for load in ("empty", "full")}
    measured = list(MEASURED)
    return [
        DesignPlant.from_statespace(
            systems[load],
            control=["u"],
            noise=["nu_Fy", "nu_M"],
            measured=measured,
            performance=measured + list(PERFORMANCE),
            name=load,
        )
        for load in ("empty", "full")
    ]
