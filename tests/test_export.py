"""Linear models export to .npz and .mat with their signal names; failures leave no file."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.io

from loader_model.cli import main
from loader_model.dynamics import OUTPUT_NAMES, STATE_NAMES, LoaderDynamics


@pytest.fixture
def linear(paper_layout: dict[str, float]):
    return LoaderDynamics(paper_layout).linearise()


def test_npz_round_trip(tmp_path: Path, linear) -> None:
    path = linear.save(tmp_path / "loader.npz")
    with np.load(path) as data:
        np.testing.assert_array_equal(data["A"], linear.A)
        np.testing.assert_array_equal(data["D_w"], linear.D_w)
        assert data["state_names"].tolist() == list(STATE_NAMES)
        assert data["output_names"].tolist() == list(OUTPUT_NAMES)


def test_mat_round_trip(tmp_path: Path, linear) -> None:
    data = scipy.io.loadmat(linear.save(tmp_path / "loader.mat"))
    np.testing.assert_array_equal(data["A"], linear.A)
    np.testing.assert_array_equal(data["B"], linear.B)
    assert [str(item[0]) for item in data["state_names"].ravel()] == list(STATE_NAMES)


def test_bad_suffix_and_missing_folder(tmp_path: Path, linear) -> None:
    with pytest.raises(ValueError, match=r"suffix '\.csv'; allowed: \['\.npz', '\.mat'\]"):
        linear.save(tmp_path / "loader.csv")
    with pytest.raises(ValueError, match=r"output folder .* does not exist"):
        linear.save(tmp_path / "missing" / "loader.npz")
    assert list(tmp_path.iterdir()) == []


def test_failed_write_leaves_no_file(tmp_path: Path, linear, monkeypatch) -> None:
    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(np, "savez", broken)
    with pytest.raises(OSError, match="disk full"):
        linear.save(tmp_path / "loader.npz")
    assert list(tmp_path.iterdir()) == []


def test_model_command_exports(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["model", "--load", "full", "--export", str(tmp_path / "m.npz")]) == 0
    assert "Static equilibrium" in capsys.readouterr().out
    with np.load(tmp_path / "m.npz") as data:
        assert data["A"].shape == (8, 8) and data["E"].shape == (8, 11)
