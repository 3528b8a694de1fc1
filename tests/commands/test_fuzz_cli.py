"""The fuzz run of tests/fuzz_cli.py: every bad input to every field and option is handled."""

from __future__ import annotations

import pytest

from tests.fuzz_cli import main_fuzz


@pytest.mark.slow
def test_fuzz_run_handles_every_bad_input(capsys: pytest.CaptureFixture[str]) -> None:
    status = main_fuzz()
    report = capsys.readouterr().out
    assert status == 0, report
    assert "not handled 0" in report
