r"""The pair of lift cylinders as one equivalent cylinder with a one-degree-of-freedom load.

Section 4.1 measured pressures, the pump flow to both cylinders and the cylinder motion; the
identified friction, leakage and flows are totals of both cylinders. So here:

- A_p is the *total* piston area, n_cyl π d²/4 (``[cylinders]`` of the parameter file), α the
  area ratio of Eq. 30, and the piston-side volume (Eq. 36)

  .. math:: V_A(x) = A_p x + n_{cyl} V_{A,dead},

  x the piston position from the retracted end stop;
- the boom and the bucket load act on the cylinders as an equivalent inertia m_eq and load force
  F_L (Eq. 44). By virtual work about the boom pivot D at the parameter file's operating boom
  angle, with the lever h = dx_cyl/dφ (Eq. 35) of the cylinder line C-E,

  .. math::

      F_L = \frac{g \sum_i m_i (G_{i,x} - D_x)}{h}, \qquad
      m_{eq} = \frac{\sum_i \left(J_i + m_i \lVert G_i - D \rVert^2\right)}{h^2},

  summed over the boom (with empty bucket) and the bucket load (mass from the measurement,
  centre of gravity and inertia per kg from a bucket-load case). The lever is taken constant
  (its value at the operating angle): an approximation of this stand-in while the full plant
  is not there; a user with better F_L and m_eq estimates can pass them to the estimators.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from loader_model.parameter_schema import BucketLoad, LoaderParameters

__all__ = ["EquivalentCylinder"]


@dataclass(frozen=True)
class EquivalentCylinder:
    """One cylinder standing for all lift cylinders, with its load (Eq. 30, 31, 36, 44).

    Attributes
    ----------
    area_m2 : float
        Total piston area A_p of all cylinders in m².
    alpha : float
        Area ratio α = (A_p − A_r)/A_p (Eq. 30).
    stroke_m : float
        Stroke in m.
    dead_volume_a_m3, dead_volume_b_m3 : float
        Total dead volume of the piston sides and of the rod sides in m³.
    load_force_n : float
        F_L of the boom with empty bucket, in N (positive: pushes the piston in).
    load_force_per_kg : float
        dF_L/dm_load of the bucket load, in N/kg.
    inertia_kg : float
        m_eq of the boom with empty bucket, in kg.
    inertia_per_kg : float
        dm_eq/dm_load of the bucket load (dimensionless).
    lever_m_per_rad : float
        h = dx_cyl/dφ at the operating boom angle in m/rad (Eq. 35).
    kinematics : tuple of float
        (C_x, C_y, D_x, D_y, E_x, E_y, φ0, L_r): cylinder base, boom pivot and rod end at the
        operating boom angle φ0 (m, rad) and the retracted length (m), for
        :meth:`position_from_boom_angle`.
    """

    area_m2: float
    alpha: float
    stroke_m: float
    dead_volume_a_m3: float
    dead_volume_b_m3: float
    load_force_n: float
    load_force_per_kg: float
    inertia_kg: float
    inertia_per_kg: float
    lever_m_per_rad: float
    kinematics: tuple[float, ...] = ()

    @classmethod
    def from_parameters(cls, loader: LoaderParameters, load: BucketLoad) -> EquivalentCylinder:
        """Build from a loader file and a bucket-load case (its cog and inertia per kg)."""
        cyl, geo = loader.cylinders, loader.geometry
        c, d, e = (np.asarray(p, dtype=float) for p in (geo.C, geo.D, geo.E))
        axis = (e - c) / np.linalg.norm(e - c)
        lever = float(axis @ np.array([-(e[1] - d[1]), e[0] - d[0]]))  # h = dx_cyl/dφ (Eq. 35)
        g = loader.environment.gravity

        def moment_and_inertia(
            mass: float, cog: tuple[float, float], inertia: float
        ) -> tuple[float, float]:
            r = np.asarray(cog, dtype=float) - d
            return float(g * mass * r[0]), float(inertia + mass * float(r @ r))

        boom_moment, boom_inertia = moment_and_inertia(
            loader.boom.mass, loader.boom.cog, loader.boom.inertia
        )
        load_moment, load_inertia = moment_and_inertia(load.mass, load.cog, load.inertia)
        return cls(
            area_m2=cyl.count * cyl.piston_area,
            alpha=cyl.annulus_area / cyl.piston_area,
            stroke_m=cyl.stroke,
            dead_volume_a_m3=cyl.count * cyl.dead_volume_a,
            dead_volume_b_m3=cyl.count * cyl.dead_volume_b,
            load_force_n=float(boom_moment / lever),
            load_force_per_kg=float(load_moment / load.mass / lever),
            inertia_kg=boom_inertia / lever**2,
            inertia_per_kg=load_inertia / load.mass / lever**2,
            lever_m_per_rad=lever,
            kinematics=(*map(float, (*c, *d, *e)), geo.boom_angle, cyl.retracted_length),
        )

    def load_force(self, load_mass_kg: np.ndarray | float) -> np.ndarray:
        """F_L in N for bucket-load masses in kg (Eq. 44)."""
        return self.load_force_n + self.load_force_per_kg * np.asarray(load_mass_kg, dtype=float)

    def inertia(self, load_mass_kg: np.ndarray | float) -> np.ndarray:
        """m_eq in kg for bucket-load masses in kg (Eq. 44)."""
        return self.inertia_kg + self.inertia_per_kg * np.asarray(load_mass_kg, dtype=float)

    def volume_a(self, position_m: np.ndarray | float) -> np.ndarray:
        """Total piston-side volume V_A = A_p x + V_A,dead in m³ (Eq. 36, 48)."""
        return self.area_m2 * np.asarray(position_m, dtype=float) + self.dead_volume_a_m3

    def volume_b(self, position_m: np.ndarray | float) -> np.ndarray:
        """Total rod-side volume V_B = α A_p (s − x) + V_B,dead in m³ (Eq. 37)."""
        x = np.asarray(position_m, dtype=float)
        return self.alpha * self.area_m2 * (self.stroke_m - x) + self.dead_volume_b_m3

    def position_from_boom_angle(self, boom_angle_rad: np.ndarray) -> np.ndarray:
        r"""Piston position x = |E(φ) − C| − L_r in m from the boom angle φ = θ2 − θ1 (Eq. 35).

        .. math:: E(\varphi) = D + R(\varphi - \varphi_0) (E_0 - D)

        (the rod end turns with the boom about the pivot D; R a rotation by the angle).

        Raises
        ------
        ValueError
            If a position falls outside [0, stroke], naming the first such sample.
        """
        c_x, c_y, d_x, d_y, e_x, e_y, phi0, retracted = self.kinematics
        turn = np.asarray(boom_angle_rad, dtype=float) - phi0
        r_x, r_y = e_x - d_x, e_y - d_y
        x = d_x + np.cos(turn) * r_x - np.sin(turn) * r_y - c_x
        y = d_y + np.sin(turn) * r_x + np.cos(turn) * r_y - c_y
        position = np.hypot(x, y) - retracted
        bad = np.flatnonzero((position < 0.0) | (position > self.stroke_m))
        if bad.size:
            i = int(bad[0])
            raise ValueError(
                f"boom angle {float(np.asarray(boom_angle_rad)[i])!r} rad (sample {i + 1}) puts "
                f"the piston at {position[i]:.4g} m, outside the stroke [0, {self.stroke_m:g}] m "
                "of the parameter file"
            )
        return position

    def describe(self) -> str:
        """One line with A_p, α and the load model, for reports."""
        return (
            f"equivalent cylinder: A_p = {self.area_m2 * 1e4:.3f} cm² (total), α = "
            f"{self.alpha:.3f}; F_L = {self.load_force_n:.0f} N + {self.load_force_per_kg:.2f} "
            f"N/kg · m_load; m_eq = {self.inertia_kg:.0f} kg + {self.inertia_per_kg:.2f} · m_load"
        )
