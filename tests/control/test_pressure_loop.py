"""The pressure loop of section 3.2 on the detailed plant, Eq. 43, and `loader-model hydraulics`."""

from __future__ import annotations

import control
import numpy as np
import pytest

from loader_model.cli import main
from loader_model.control.pressure_loop import (
    EQUATION_43,
    compare_with_equation_43,
    pressure_loop,
)
from loader_model.plant.linear import linearise_plant
from loader_model.plant.plant_parameters import plant_parameter_vector


@pytest.fixture(scope="module")
def plant_empty():
    return linearise_plant(plant_parameter_vector(None, "empty")).state_space()


def test_equation_43_as_printed() -> None:
    """DESIGN.md errata 9: DC gain −6361/78910, zero at +6361/2810, poles −191 and −15.5 ± 13.2j."""
    reference = control.tf(*EQUATION_43)
    assert float(np.squeeze(control.dcgain(reference))) == pytest.approx(-6361 / 78910, rel=1e-12)
    assert control.zeros(reference)[0].real == pytest.approx(6361 / 2810, rel=1e-12)
    poles = np.sort_complex(control.poles(reference))
    np.testing.assert_allclose(poles.real, [-191.391, -15.4545, -15.4545], rtol=1e-4)
    np.testing.assert_allclose(np.abs(poles.imag), [0.0, 13.1703, 13.1703], atol=1e-3)


@pytest.mark.parametrize("highpass", [1.0, None])
def test_detailed_loop_is_stable_and_minimum_phase_in_its_band(plant_empty, highpass) -> None:
    loop = pressure_loop(plant_empty, 1e7, 4.6e-5, k_p=0.5, highpass_rad_s=highpass)
    comparison = compare_with_equation_43(loop)
    assert np.all(comparison.poles.real < 0)
    slow_zeros = comparison.zeros[np.abs(comparison.zeros) < 500.0]
    assert np.all(slow_zeros.real < 0)  # no right-half-plane zero, unlike Eq. 43
    assert comparison.dc_gain > 0  # the pressure follows its reference, unlike Eq. 43's −0.081
    # the loop's own real pole (measured −13.2 rad/s with the high-pass, −14.1 without) sits
    # at the real part of Eq. 43's complex pair (−15.5 rad/s), within 20 %
    real_poles = comparison.dominant_poles[np.abs(comparison.dominant_poles.imag) < 1e-9]
    assert np.min(np.abs(real_poles.real + 15.45)) < 0.2 * 15.45


def test_loop_is_the_closed_form_for_a_capacitance() -> None:
    """A chamber whose pressure integrates the pump flow, p_A = (c/s) V_p_ref: the loop is
    c g / (s + c g) with g = k_p V_max / norm (unit DC gain, one pole at −c g)."""
    capacitance = 2e11
    chamber = control.ss(
        [[0.0]], [[capacitance]], [[1.0]], [[0.0]], inputs=["V_p_ref"], outputs=["p_A"]
    )
    loop = pressure_loop(chamber, 1e7, 4.6e-5, k_p=0.5, highpass_rad_s=None)
    rate = capacitance * 0.5 * 4.6e-5 / 1e7
    assert float(np.squeeze(control.dcgain(loop))) == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(control.poles(loop), [-rate], rtol=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"k_p": 0.0}, r"k_p = 0.0; allowed: a finite number > 0"),
        ({"highpass_rad_s": -1.0}, r"highpass_rad_s = -1.0; allowed: None or a number > 0"),
    ],
)
def test_bad_loop_settings_are_named(plant_empty, kwargs, match) -> None:
    with pytest.raises(ValueError, match=match):
        pressure_loop(plant_empty, 1e7, 4.6e-5, **kwargs)


def test_hydraulics_command_prints_and_plots(tmp_path, capsys) -> None:
    figure = tmp_path / "loop.png"
    assert main(["hydraulics", "--load", "full", "--plot", str(figure)]) == 0
    out = capsys.readouterr().out
    assert "static piston pressure p_A       129.74 bar" in out
    assert "k_eq (chambers closed)" in out and "Eq. 43: DC gain -0.0806" in out
    assert "closed load-holding valves, pump idle (baseline)" in out
    assert "accumulator behind closed valves (passive ride control)" in out
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_hydraulics_command_refuses_a_bad_plot_name(tmp_path, capsys) -> None:
    assert main(["hydraulics", "--plot", str(tmp_path / "loop.pdf")]) == 2
    assert "has suffix '.pdf'; allowed: ['.png']" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
