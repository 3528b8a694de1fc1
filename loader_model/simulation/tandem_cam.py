r"""Tandem elliptical cam: the effective road of a tyre that envelops obstacles shorter than its patch.

A rigid disc (:mod:`~loader_model.simulation.envelope`) sees the full height of a board narrower
than the tyre's contact patch; a pneumatic tyre wraps around it. Schmeitz's semi-empirical model
(A. J. C. Schmeitz, H. B. Pacejka, I. J. M. Besselink, "A semi-empirical three-dimensional model of
the pneumatic tyre rolling over arbitrarily uneven road surfaces", Vehicle System Dynamics 41(5),
2004; H. B. Pacejka, Tire and Vehicle Dynamics, 3rd ed., 2012, sections 10.2-10.3) moves two
rigid cams over the raw profile, a distance l_s apart (front f ahead of the axle by l_s/2, rear r
behind it), each the lower half of a super-ellipse of half-length a_e, half-height b_e and
exponent c_e:

.. math::

    \left|\frac{x}{a_e}\right|^{c_e} + \left|\frac{z}{b_e}\right|^{c_e} = 1,
    \qquad g(u) = \left(1 - |u/a_e|^{c_e}\right)^{1/c_e} .

Each cam sits at the lowest height where it does not penetrate the ground: its bottom point is

.. math::

    z(x) = \max_{|u| \le a_e} \left[h(x + u) + b_e\, g(u)\right] - b_e ,

and the effective road plane passes through the two cams (Pacejka section 10.2, "tandem cam"):

.. math::

    w(s) = \tfrac12\left[z(s + \tfrac{l_s}{2}) + z(s - \tfrac{l_s}{2})\right],
    \qquad \tan\beta(s) = \frac{z(s + l_s/2) - z(s - l_s/2)}{l_s} .

With c_e = 2, a_e = b_e = R and l_s → 0 this is the rigid-disc envelope (tests). The horizontal
road input keeps the effective-plane law F_x = −F_y tan β with this tan β
(:mod:`~loader_model.simulation.travel`); the rate of the vertical input is v dw/ds, the mean of
the two cams' slopes, which differs from tan β on a short obstacle. Effective rolling radius and
curvature (Pacejka's third and fourth inputs) are left out.

Computation: exact and vectorised, :mod:`~loader_model.simulation.cam_envelope`.

Parameters (:meth:`TandemCam.from_deflection`)
----------------------------------------------
Verified: the parameter set and meanings as MF-Tyre/MF-Swift tyre property files publish them
(``ELLIPS_SHIFT`` "scaling of distance between front and rear ellipsoid", ``ELLIPS_LENGTH``
"semi-major axis", ``ELLIPS_HEIGHT`` "semi-minor axis", ``ELLIPS_ORDER`` "order of ellipsoid";
one published property file of a 0.239 m tyre gives 0.83, 1.3, 1.0, 1.5, i.e. lengths in units of
the free radius). Estimates (no value for a 12-16.5 skid-steer tyre is published; ranges are what
the car-tyre sources span): a_e = 1.03 R (1.0-1.3 R), b_e = 1.0 R (1.0-1.05 R), c_e = 1.8
(1.5-2.0), and l_s = 0.8 of the static contact length 2a (0.4-0.83: the sources do not settle
whether the scaling applies to the half-length a or the length 2a). The contact length is the chord
of the free radius at the static deflection δ = F_y0 / k_y, 2a = 2 sqrt(2 R δ − δ²).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from loader_model.simulation._checks import as_number
from loader_model.simulation.cam_envelope import cam_height
from loader_model.simulation.roads import RoadProfile

#: Spacing over a_e below which the plane slope is taken in its limit l_s -> 0.
_MIN_SPACING_FRACTION = 1e-6

__all__ = [
    "CAM_EXPONENT",
    "CAM_HEIGHT_RATIO",
    "CAM_LENGTH_RATIO",
    "CAM_SPACING_RATIO",
    "DEFAULT_ENVELOPE",
    "ENVELOPES",
    "MAXIMUM_DEFLECTION_RATIO",
    "TandemCam",
    "TandemCamRoad",
    "cam_height",
    "check_envelope",
    "contact_half_length",
    "tandem_cam_axles",
    "tandem_cam_road",
]

#: Enveloping models of the road input: the rigid disc and the tandem elliptical cam.
ENVELOPES: tuple[str, ...] = ("rigid", "tandem-cam")
#: Default enveloping model.
DEFAULT_ENVELOPE = "tandem-cam"
#: a_e / R (estimate, 1.0-1.3; module notes).
CAM_LENGTH_RATIO = 1.03
#: b_e / R (estimate, 1.0-1.05).
CAM_HEIGHT_RATIO = 1.0
#: c_e (estimate, 1.5-2.0).
CAM_EXPONENT = 1.8
#: l_s / (2a), the cam spacing over the static contact length (estimate, 0.4-0.83).
CAM_SPACING_RATIO = 0.8
#: Largest static deflection over the free radius accepted (a patch of 1.3 R; for the 12-16.5 tyre,
#: 105 mm, half its section height).
MAXIMUM_DEFLECTION_RATIO = 0.25


def check_envelope(envelope: object) -> str:
    """Check an enveloping model's name.

    Parameters
    ----------
    envelope : object
        ``"rigid"`` or ``"tandem-cam"``.

    Returns
    -------
    str
        ``envelope``; ValueError naming it if it is not one of :data:`ENVELOPES`.
    """
    if not isinstance(envelope, str) or envelope not in ENVELOPES:
        raise ValueError(f"envelope must be one of {list(ENVELOPES)}; got {envelope!r}")
    return envelope


def contact_half_length(tyre_radius_m: float, deflection_m: float) -> float:
    """Half chord a = sqrt(2 R δ − δ²) in m of a free radius R pressed down by δ.

    Parameters
    ----------
    tyre_radius_m : float
        Free radius R in m, > 0.
    deflection_m : float
        Static deflection δ in m, [0, :data:`MAXIMUM_DEFLECTION_RATIO` R].

    Returns
    -------
    float
        a in m.
    """
    radius_m = as_number(tyre_radius_m, "tyre_radius_m", "m", minimum=0.0, strict_minimum=True)
    limit_m = MAXIMUM_DEFLECTION_RATIO * radius_m
    delta_m = as_number(deflection_m, "deflection_m", "m", minimum=0.0, maximum=limit_m)
    return float(np.sqrt(2.0 * radius_m * delta_m - delta_m**2))


@dataclass(frozen=True)
class TandemCam:
    """Two super-elliptical cams l_s apart (module notes); lengths in m.

    Attributes
    ----------
    half_length_m, half_height_m : float
        a_e and b_e, each in (0, 2] m.
    exponent : float
        c_e in (1, 10] (c_e = 2: an ellipse).
    spacing_m : float
        l_s in [0, 2 a_e] (each cam's centre within its own reach of the axle).
    """

    half_length_m: float
    half_height_m: float
    exponent: float
    spacing_m: float

    def __post_init__(self) -> None:
        positive = {"minimum": 0.0, "maximum": 2.0, "strict_minimum": True}
        a_m = as_number(self.half_length_m, "half_length_m", "m", **positive)
        as_number(self.half_height_m, "half_height_m", "m", **positive)
        as_number(self.exponent, "exponent", "-", minimum=1.0, maximum=10.0, strict_minimum=True)
        limit = "m (at most twice the cam half-length a_e)"
        as_number(self.spacing_m, "spacing_m", limit, minimum=0.0, maximum=2.0 * a_m)

    @classmethod
    def from_deflection(
        cls,
        tyre_radius_m: float,
        deflection_m: float,
        *,
        length_ratio: float = CAM_LENGTH_RATIO,
        height_ratio: float = CAM_HEIGHT_RATIO,
        exponent: float = CAM_EXPONENT,
        spacing_ratio: float = CAM_SPACING_RATIO,
    ) -> TandemCam:
        """The cams of a tyre of free radius R at static deflection δ (module notes).

        Raises
        ------
        ValueError
            Naming ``deflection_m`` if it is negative or above
            :data:`MAXIMUM_DEFLECTION_RATIO` R, or ``spacing_m`` if l_s = p_ls 2a exceeds 2 a_e.
        """
        half_m = contact_half_length(tyre_radius_m, deflection_m)
        ratio = as_number(spacing_ratio, "spacing_ratio", "-", minimum=0.0, maximum=2.0)
        radius_m = float(tyre_radius_m)
        return cls(length_ratio * radius_m, height_ratio * radius_m, exponent, ratio * 2 * half_m)

    @classmethod
    def rigid_disc(cls, tyre_radius_m: float) -> TandemCam:
        """The rigid-disc limit: a circle of radius R, both cams at the axle."""
        return cls(float(tyre_radius_m), float(tyre_radius_m), 2.0, 0.0)


class TandemCamRoad(NamedTuple):
    """Effective road of a tandem cam at the query distances."""

    height_m: np.ndarray
    """Effective height w in m."""
    slope: np.ndarray
    """Effective-plane slope tan β = (z_f − z_r) / l_s (the cam's own slope when l_s = 0)."""
    height_rate: np.ndarray
    """dw/ds, the mean slope of the two cams' paths."""


def tandem_cam_road(profile: RoadProfile, distance_m: object, cam: TandemCam) -> TandemCamRoad:
    """Effective height, plane slope and height rate of ``profile`` under ``cam`` (module notes).

    Parameters
    ----------
    profile : RoadProfile
        Raw ground profile.
    distance_m : array_like
        Axle positions s in m (any shape, any order).
    cam : TandemCam
        The tandem cam of the axle.

    Returns
    -------
    TandemCamRoad
        w(s), tan β(s) and dw/ds, each shaped like ``distance_m``.
    """
    road = tandem_cam_axles(profile, np.asarray(distance_m, dtype=float)[..., None], (cam,))
    return TandemCamRoad(*(field[..., 0] for field in road))


def tandem_cam_axles(
    profile: RoadProfile, distance_m: object, cams: tuple[TandemCam, ...]
) -> TandemCamRoad:
    """:func:`tandem_cam_road` for several axles at once, in one pass of the cam shape.

    Parameters
    ----------
    profile : RoadProfile
        Raw ground profile.
    distance_m : array_like
        (..., n) axle positions in m, the last axis over the n axles.
    cams : tuple of TandemCam
        One per axle; they may differ in spacing l_s only (one a_e, b_e, c_e).

    Returns
    -------
    TandemCamRoad
        Each field shaped like ``distance_m``.
    """
    if not cams or not all(isinstance(cam, TandemCam) for cam in cams):
        raise ValueError(f"cams must be TandemCam instances; got {cams!r}")
    shape = cams[0]
    form = (shape.half_length_m, shape.half_height_m, shape.exponent)
    if any((c.half_length_m, c.half_height_m, c.exponent) != form for c in cams):
        raise ValueError(f"the cams of one drive must share a_e, b_e, c_e; got {cams!r}")
    s = np.asarray(distance_m, dtype=float)
    if s.ndim == 0 or s.shape[-1] != len(cams):
        raise ValueError(f"distance_m must end in an axis of {len(cams)} axles; got {s.shape}")
    spacing = np.array([cam.spacing_m for cam in cams])
    z, dz = cam_height(profile, np.stack([s + 0.5 * spacing, s - 0.5 * spacing]), shape)
    height = 0.5 * (z[0] + z[1])
    rate = 0.5 * (dz[0] + dz[1])
    # below a micrometre per metre of cam the difference quotient is rounding error over l_s: use
    # its limit l_s -> 0, the cams' own slope (a spacing of 3e-16 m gave 0.33 for 0)
    spread = spacing > _MIN_SPACING_FRACTION * shape.half_length_m
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = np.where(spread, (z[0] - z[1]) / np.where(spread, spacing, 1.0), rate)
    return TandemCamRoad(height, slope, rate)
