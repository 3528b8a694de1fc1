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
  centre of gravity and inertia per kg from a bucket-load case).

Without a position these are the values at the operating angle (constant lever). With the
piston position x of each sample (:meth:`EquivalentCylinder.load_force`,
:meth:`EquivalentCylinder.inertial_force`) the boom angle ψ = φ − φ0 follows from the geometry
(law of cosines in the triangle C, D, E), the centres of gravity turn with the boom about D, and
the lever h(ψ) and its slope h'(ψ) are evaluated at ψ: with J_D the inertia about D,
J_D ψ̈ = h F − M_g(ψ) and ẍ = h ψ̈ + h' ψ̇², so the cylinder force that moves the boom is

.. math::

    F = F_L(\psi) + m_{eq}(\psi)\left(\ddot x - \frac{h'(\psi)}{h(\psi)^2}\dot x^2\right),
    \qquad F_L(\psi) = \frac{M_g(\psi)}{h(\psi)}, \quad m_{eq}(\psi) = \frac{J_D}{h(\psi)^2}.

What remains approximate is the chassis: it is taken at rest, while on the machine it moves on
its tyres (pitch and heave under the boom's reaction). Records with the chassis sensors use
:mod:`.chassis` instead, which is exact.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from loader_model.parameters.schema import BucketLoad, LoaderParameters

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
    gravity_moment, gravity_moment_per_kg : (float, float)
        g m (G − D) of the boom with empty bucket (N·m, both components at φ0) and of one kg of
        bucket load (N·m/kg): the gravity moment about D at a boom angle is the x component of
        this vector turned by ψ = φ − φ0.
    parameters : (LoaderParameters, BucketLoad) or None
        The files it was built from (:meth:`from_parameters`), for the moving-chassis load
        model of :mod:`.chassis`.
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
    gravity_moment: tuple[float, float] = (0.0, 0.0)
    gravity_moment_per_kg: tuple[float, float] = (0.0, 0.0)
    parameters: tuple[LoaderParameters, BucketLoad] | None = field(
        default=None, compare=False, repr=False
    )

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
        ) -> tuple[np.ndarray, float]:
            r = np.asarray(cog, dtype=float) - d
            return g * mass * r, float(inertia + mass * float(r @ r))

        boom_vector, boom_inertia = moment_and_inertia(
            loader.boom.mass, loader.boom.cog, loader.boom.inertia
        )
        load_vector, load_inertia = moment_and_inertia(load.mass, load.cog, load.inertia)
        boom_moment, load_moment = float(boom_vector[0]), float(load_vector[0])
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
            gravity_moment=(float(boom_vector[0]), float(boom_vector[1])),
            gravity_moment_per_kg=(
                float(load_vector[0] / load.mass),
                float(load_vector[1] / load.mass),
            ),
            parameters=(loader, load),
        )

    def load_force(
        self, load_mass_kg: np.ndarray | float, position_m: np.ndarray | None = None
    ) -> np.ndarray:
        """F_L in N for bucket-load masses in kg (Eq. 44).

        Without ``position_m``: at the operating angle (constant lever). With it: at the boom
        angle of each piston position, F_L = M_g(ψ)/h(ψ) (module docstring).
        """
        mass = np.asarray(load_mass_kg, dtype=float)
        if position_m is None:
            return self.load_force_n + self.load_force_per_kg * mass
        turn, lever, _ = self._lever(position_m)
        moment = np.add.outer(0.0, self.gravity_moment) + np.multiply.outer(
            mass, self.gravity_moment_per_kg
        )
        arm = np.cos(turn) * moment[..., 0] - np.sin(turn) * moment[..., 1]
        return arm / lever

    def inertia(
        self, load_mass_kg: np.ndarray | float, position_m: np.ndarray | None = None
    ) -> np.ndarray:
        """m_eq = J_D / h² in kg for bucket-load masses in kg (Eq. 44), at the operating angle or
        at the boom angle of each piston position."""
        constant = self.inertia_kg + self.inertia_per_kg * np.asarray(load_mass_kg, dtype=float)
        if position_m is None:
            return constant
        _, lever, _ = self._lever(position_m)
        return constant * (self.lever_m_per_rad / lever) ** 2

    def inertial_force(
        self,
        load_mass_kg: np.ndarray,
        position_m: np.ndarray,
        velocity_m_s: np.ndarray,
        acceleration_m_s2: np.ndarray,
    ) -> np.ndarray:
        """m_eq(ψ) (ẍ − h'/h² ẋ²) in N: the force that accelerates boom and load (module
        docstring), the m_eq ẍ of Eq. 44 with the lever at each sample."""
        _, lever, slope = self._lever(position_m)
        mass = self.inertia(load_mass_kg, position_m)
        return mass * (acceleration_m_s2 - slope / lever**2 * np.asarray(velocity_m_s) ** 2)

    def boom_turn(self, position_m: np.ndarray) -> np.ndarray:
        """Boom turn ψ = φ − φ0 in rad at piston positions in m (closed form, module docstring)."""
        return self._lever(position_m)[0]

    def _lever(self, position_m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Boom turn ψ from the operating angle, lever h(ψ) and dh/dψ at piston positions."""
        c_x, c_y, d_x, d_y, e_x, e_y, _, retracted = self.kinematics
        a = np.array([d_x - c_x, d_y - c_y])
        b = np.array([e_x - d_x, e_y - d_y])
        length = np.asarray(position_m, dtype=float) + retracted
        cosine = (length**2 - a @ a - b @ b) / (2.0 * np.hypot(*a) * np.hypot(*b))
        offset = np.arctan2(b[1], b[0]) - np.arctan2(a[1], a[0])
        branch = np.sign(np.sin(offset)) or 1.0  # the branch through ψ = 0
        turn = branch * np.arccos(np.clip(cosine, -1.0, 1.0)) - offset
        cos, sin = np.cos(turn), np.sin(turn)
        r_x, r_y = cos * b[0] - sin * b[1], sin * b[0] + cos * b[1]  # E − D turned by ψ
        u_x, u_y = a[0] + r_x, a[1] + r_y  # E − C
        norm = np.hypot(u_x, u_y)
        du = u_x * -r_y + u_y * r_x  # u · du/dψ, du/dψ = (−r_y, r_x)
        lever = du / norm
        slope = (r_x**2 + r_y**2 - (u_x * r_x + u_y * r_y)) / norm - du**2 / norm**3
        return turn, lever, slope

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
