"""Tandem elliptical cam against the rigid disc, closed forms, a brute-force search and invariants."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from loader_model.simulation import (
    RoadProfile,
    TandemCam,
    effective_road,
    flat_road,
    paper_course,
    single_board,
    tandem_cam_road,
)
from loader_model.simulation.tandem_cam import (
    MAXIMUM_DEFLECTION_RATIO,
    cam_height,
    check_envelope,
    contact_half_length,
)

R_M = 0.42  # the 12-16.5 tyre
H_M = 0.04  # the paper's board
L_M = 0.14  # its assumed width
#: The calibrated loader's static deflections (front empty, rear empty, front full, rear full).
DEFLECTIONS_M = (0.00726, 0.00993, 0.01063, 0.00870)


def cam_lift(cam: TandemCam, u: np.ndarray) -> np.ndarray:
    """b_e g(u) − b_e: the cam contour above its bottom point at offset u, −inf outside reach."""
    t = np.abs(u) / cam.half_length_m
    inside = t <= 1.0
    rest = np.where(inside, 1.0 - np.minimum(t, 1.0) ** cam.exponent, 0.0)
    contour = cam.half_height_m * (rest ** (1.0 / cam.exponent) - 1.0)
    return np.where(inside, contour, -np.inf)


def board_cam_height(x: np.ndarray, cam: TandemCam, s0: float, width: float, height: float):
    """Independent closed form of one cam over a board: the cam rests on the ground under it, or
    on one of the board's two top corners (s0, H) and (s0 + L, H); flat segments touch at u = 0
    and the bottom corners are lower than the ground beside them."""
    ground = np.where((x >= s0) & (x <= s0 + width), height, 0.0)
    front_corner = height + cam_lift(cam, s0 - x)
    rear_corner = height + cam_lift(cam, s0 + width - x)
    return np.maximum(ground, np.maximum(front_corner, rear_corner))


def test_rigid_disc_limit_is_the_rigid_envelope_to_rounding():
    """c_e = 2, a_e = b_e = R, l_s = 0: the cam is the disc; same height and slope to 1e-15 m."""
    for profile in (
        single_board(height_m=H_M, width_m=L_M, position_m=1.0),
        paper_course(9).profile,
    ):
        s = np.linspace(-1.0, profile.end_m + 1.0, 30_001)
        disc = effective_road(profile, s, R_M)
        cam = tandem_cam_road(profile, s, TandemCam.rigid_disc(R_M))
        np.testing.assert_allclose(cam.height_m, disc.height_m, rtol=0, atol=1e-15)
        np.testing.assert_allclose(cam.slope, disc.slope, rtol=0, atol=1e-14)
        np.testing.assert_array_equal(cam.slope, cam.height_rate)


@pytest.mark.parametrize("spacing_m", [1e-3, 1e-2])
def test_short_cam_spacing_tends_to_the_rigid_disc(spacing_m):
    """Circular cams l_s apart: |w − h_disc| <= (l_s / 2) max|tan β| (0.24 mm at l_s = 1 mm), and
    tan β is the disc's slope wherever the disc's slope does not jump within ±l_s/2."""
    profile = single_board(height_m=H_M, width_m=L_M, position_m=1.0)
    s = np.linspace(0.0, 2.0, 20_001)
    cam = TandemCam(R_M, R_M, 2.0, spacing_m)
    road = tandem_cam_road(profile, s, cam)
    disc = effective_road(profile, s, R_M)
    bound = 0.5 * spacing_m * np.abs(disc.slope).max()
    assert np.abs(road.height_m - disc.height_m).max() <= bound
    ahead = effective_road(profile, s + spacing_m / 2, R_M).slope
    behind = effective_road(profile, s - spacing_m / 2, R_M).slope
    steady = np.abs(ahead - behind) < 1e-4
    np.testing.assert_allclose(road.slope[steady], disc.slope[steady], rtol=0, atol=1e-4)


def test_cam_shape_is_continuous_in_the_exponent():
    """c_e → 2 with a_e = b_e = R: the super-ellipse tends to the circle (1e-5 m at c_e = 2.0001)."""
    profile = single_board(height_m=H_M, width_m=L_M, position_m=1.0)
    s = np.linspace(0.0, 2.0, 4001)
    near = tandem_cam_road(profile, s, TandemCam(R_M, R_M, 2.0001, 0.0)).height_m
    np.testing.assert_allclose(near, effective_road(profile, s, R_M).height_m, atol=1e-5)


@pytest.mark.parametrize("level_m", [0.0, 0.25, -1.5])
def test_flat_road_gives_the_ground_and_no_slope(level_m):
    cam = TandemCam.from_deflection(R_M, 0.009)
    s = np.linspace(-3.0, 13.0, 5001)
    road = tandem_cam_road(flat_road(10.0, height_m=level_m), s, cam)
    np.testing.assert_allclose(road.height_m, level_m, rtol=0, atol=1e-15)
    assert np.all(road.slope == 0.0) and np.all(road.height_rate == 0.0)


def test_long_smooth_bump_is_followed():
    """A 50 mm cosine bump 10 m long (sampled every 1 cm), far longer than the patch: w within
    1 % of the amplitude of the ground (cam offset R (sec β − 1) plus h'' l_s² / 8), tan β within
    1e-3 of the ground's slope."""
    x = np.arange(0.0, 10.0 + 1e-9, 0.01)
    h = 0.025 * (1.0 - np.cos(2.0 * np.pi * x / 10.0))
    profile = RoadProfile(x, h)
    s = np.linspace(0.5, 9.5, 3001)
    road = tandem_cam_road(profile, s, TandemCam.from_deflection(R_M, 0.0106))
    assert np.abs(road.height_m - profile.height(s)).max() < 0.01 * 0.05
    slope = 0.025 * 2.0 * np.pi / 10.0 * np.sin(2.0 * np.pi * s / 10.0)
    np.testing.assert_allclose(road.slope, slope, atol=1e-3)
    np.testing.assert_allclose(road.height_rate, slope, atol=1e-3)


@pytest.mark.parametrize("deflection_m", DEFLECTIONS_M)
def test_board_matches_closed_form_and_stays_below_its_height_when_shorter_than_spacing(
    deflection_m,
):
    """The paper's board under the calibrated cams: w and tan β from the closed form of the two
    cams to 1e-15 m; the peak reaches H only if the board is at least l_s long."""
    cam = TandemCam.from_deflection(R_M, deflection_m)
    s0 = 1.0
    profile = single_board(height_m=H_M, width_m=L_M, position_m=s0)
    s = np.linspace(0.0, 2.2, 22_001)
    road = tandem_cam_road(profile, s, cam)
    front = board_cam_height(s + cam.spacing_m / 2, cam, s0, L_M, H_M)
    rear = board_cam_height(s - cam.spacing_m / 2, cam, s0, L_M, H_M)
    np.testing.assert_allclose(road.height_m, 0.5 * (front + rear), rtol=0, atol=1e-15)
    np.testing.assert_allclose(road.slope, (front - rear) / cam.spacing_m, rtol=0, atol=1e-12)
    if L_M < cam.spacing_m:
        assert road.height_m.max() < H_M
    else:
        assert road.height_m.max() == pytest.approx(H_M, abs=1e-15)


def test_short_cleat_gives_a_plateau_at_half_its_height():
    """A 10 mm × 20 mm cleat under cams 150 mm apart: while one cam sits on the cleat the other is
    on flat ground (each cam touches it within d_e = a_e (1 − (1 − H/b_e)^c_e)^(1/c_e) = 75 mm),
    so w = H/2 exactly over the cleat's length, twice (front cam, then rear)."""
    cam = TandemCam.from_deflection(R_M, 0.0106)
    height, width, s0 = 0.01, 0.02, 1.0
    reach = cam.half_length_m * (1 - (1 - height / cam.half_height_m) ** cam.exponent) ** (
        1 / cam.exponent
    )
    assert width + reach < cam.spacing_m  # the geometry the closed form needs
    profile = single_board(height_m=height, width_m=width, position_m=s0)
    s = np.linspace(0.5, 1.5, 100_001)
    road = tandem_cam_road(profile, s, cam)
    half = cam.spacing_m / 2
    front_on = (s + half >= s0) & (s + half <= s0 + width)
    rear_on = (s - half >= s0) & (s - half <= s0 + width)
    np.testing.assert_allclose(road.height_m[front_on | rear_on], height / 2, rtol=0, atol=1e-15)
    assert road.height_m.max() == pytest.approx(height / 2, abs=1e-15)


def test_symmetric_board_gives_symmetric_height_and_antisymmetric_slope():
    cam = TandemCam.from_deflection(R_M, 0.00993)
    centre = 1.0 + L_M / 2
    d = np.linspace(0.0, 0.8, 8001)
    profile = single_board(height_m=H_M, width_m=L_M, position_m=1.0)
    ahead = tandem_cam_road(profile, centre + d, cam)
    behind = tandem_cam_road(profile, centre - d, cam)
    np.testing.assert_allclose(ahead.height_m, behind.height_m, rtol=0, atol=1e-15)
    np.testing.assert_allclose(ahead.slope, -behind.slope, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ahead.height_rate, -behind.height_rate, rtol=0, atol=1e-12)


profiles = st.lists(
    st.tuples(st.floats(0.0, 0.5), st.floats(-0.05, 0.05)), min_size=2, max_size=12
).map(
    lambda rows: RoadProfile(
        np.cumsum([row[0] for row in rows]) + np.arange(len(rows)) * 1e-3,
        np.array([row[1] for row in rows]),
        name="random",
    )
)
cams = st.builds(
    lambda a, b, c, spacing: TandemCam(a, b, c, spacing * a),
    st.floats(0.2, 0.6),
    st.floats(0.2, 0.6),
    st.floats(1.2, 3.0),
    st.floats(0.0, 1.0),
)


def highest_within(profile: RoadProfile, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """Highest ground in [low, high]: at a vertex inside or at an end."""
    ends = np.maximum(profile.height(low), profile.height(high))
    inside = (profile.distance_m[None, :] >= low[:, None]) & (
        profile.distance_m[None, :] <= high[:, None]
    )
    return np.maximum(ends, np.where(inside, profile.height_m[None, :], -np.inf).max(axis=1))


@settings(max_examples=60, deadline=None)
@given(profiles, cams, st.floats(-1.0, 1.0))
def test_cam_height_is_the_defining_maximum(profile, cam, offset):
    """Against the definition evaluated directly: a dense grid of offsets u plus the vertices in
    reach (exact where a corner carries the cam; a tangency between grid points is missed by
    O(du²)). For c_e < 2 the contour's curvature grows without bound at u = 0, where gentle
    slopes touch, so the grid is also geometric towards 0."""
    x = np.linspace(profile.start_m - 0.3, profile.end_m + 0.3, 60) + 0.01 * offset
    z, _ = cam_height(profile, x, cam)
    fine = np.geomspace(1e-9, 1.0, 2000)
    unit = np.concatenate([np.linspace(-1, 1, 2001), fine, -fine])
    grid = np.broadcast_to(unit * cam.half_length_m, (x.size, unit.size))
    corners = profile.distance_m[None, :] - x[:, None]
    corners = np.where(np.abs(corners) <= cam.half_length_m, corners, 0.0)
    u = np.concatenate([grid, corners], axis=1)
    reference = np.max(profile.height(x[:, None] + u) + cam_lift(cam, u), axis=1)
    assert np.all(z >= reference - 1e-12)
    assert np.all(z <= reference + 1e-6)


@settings(max_examples=60, deadline=None)
@given(profiles, cams)
def test_effective_height_lies_between_the_ground_and_the_highest_ground_in_reach(profile, cam):
    s = np.linspace(profile.start_m - 1.0, profile.end_m + 1.0, 400)
    road = tandem_cam_road(profile, s, cam)
    half, reach = cam.spacing_m / 2, cam.half_length_m
    highest = highest_within(profile, s - half - reach, s + half + reach)
    assert np.all(road.height_m <= highest + 1e-12)  # h + (lift − b_e) rounds by an ulp
    under = 0.5 * (profile.height(s + half) + profile.height(s - half))
    assert np.all(road.height_m >= under - 1e-12)
    assert np.all(np.isfinite(road.slope)) or profile.height_m.ptp() >= cam.half_height_m


@settings(max_examples=60, deadline=None)
@given(profiles, cams, st.floats(-50.0, 50.0), st.floats(-1.0, 1.0))
def test_shift_invariance(profile, cam, shift_m, lift_m):
    """Moving the ground by (Δs, Δh) moves the effective road by the same."""
    s = np.linspace(profile.start_m - 1.0, profile.end_m + 1.0, 300)
    moved = RoadProfile(profile.distance_m + shift_m, profile.height_m + lift_m)
    here = tandem_cam_road(profile, s, cam)
    there = tandem_cam_road(moved, s + shift_m, cam)
    np.testing.assert_allclose(there.height_m, here.height_m + lift_m, rtol=0, atol=1e-9)
    finite = np.isfinite(here.slope) & (np.abs(here.slope) < 1e3)
    np.testing.assert_allclose(there.slope[finite], here.slope[finite], rtol=1e-6, atol=1e-6)


def test_cams_from_the_static_deflection():
    """Patch 2a = 2 sqrt(2 R δ − δ²): 155.5 mm at 7.26 mm, 187.8 mm at 10.63 mm (the chord;
    2 sqrt(2 R δ) gives 156 and 189 mm); l_s = 0.8 of it."""
    assert 2 * contact_half_length(R_M, 0.00726) == pytest.approx(0.1555, abs=1e-4)
    assert 2 * contact_half_length(R_M, 0.01063) == pytest.approx(0.1878, abs=1e-4)
    cam = TandemCam.from_deflection(R_M, 0.01063)
    assert cam.spacing_m == pytest.approx(0.8 * 2 * contact_half_length(R_M, 0.01063))
    assert (cam.half_length_m, cam.half_height_m, cam.exponent) == pytest.approx(
        (1.03 * R_M, R_M, 1.8)
    )
    assert TandemCam.from_deflection(R_M, 0.0).spacing_m == 0.0


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: TandemCam.from_deflection(R_M, -0.001), r"deflection_m .* got -0\.001"),
        (lambda: TandemCam.from_deflection(R_M, 0.2), r"deflection_m .*0, 0\.105\] m; got 0\.2"),
        (lambda: TandemCam.from_deflection(R_M, 0.01, spacing_ratio=-1), r"spacing_ratio .* -1"),
        (
            lambda: TandemCam(0.4, 0.4, 2.0, 0.9),
            r"spacing_m .*0, 0\.8\] m \(at most twice .*a_e\); got 0\.9",
        ),
        (lambda: TandemCam(0.4, 0.4, 1.0, 0.1), r"exponent must be a finite number in \(1, 10\]"),
        (lambda: TandemCam(0.0, 0.4, 2.0, 0.0), r"half_length_m .* got 0\.0"),
        (lambda: check_envelope("soft"), r"envelope must be one of \['rigid', 'tandem-cam'\]"),
        (lambda: tandem_cam_road(flat_road(), [0.0], "cam"), r"cams must be TandemCam"),
        (lambda: tandem_cam_road(flat_road(), [np.nan], TandemCam.rigid_disc(R_M)), "finite"),
    ],
)
def test_bad_input_names_the_argument_and_value(call, message):
    with pytest.raises(ValueError, match=message):
        call()
    assert MAXIMUM_DEFLECTION_RATIO * R_M == pytest.approx(0.105)


def test_a_vanishing_spacing_takes_the_slope_in_its_limit():
    """Hypothesis found l_s = 3e-16 m: the difference quotient over l_s was rounding (0.33 for a
    flat stretch); below 1e-6 a_e the plane slope is the cams' own, as at l_s = 0."""
    profile = single_board(height_m=H_M, width_m=L_M, position_m=1.0)
    s = np.linspace(0.0, 2.0, 201)
    tiny = tandem_cam_road(profile, s, TandemCam(0.43, 0.42, 1.8, 3e-16))
    zero = tandem_cam_road(profile, s, TandemCam(0.43, 0.42, 1.8, 0.0))
    np.testing.assert_allclose(tiny.slope, zero.slope, rtol=0, atol=1e-12)
    np.testing.assert_allclose(tiny.height_m, zero.height_m, rtol=0, atol=1e-12)
