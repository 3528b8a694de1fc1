"""Interrupts as one line (issue 19): what was kept, exit 128 + signal; SIGTERM like Ctrl-C; an
interrupt that library code caught still stops the command; interrupts held back over calls that
must not be cut halfway. Signals are real (``signal.raise_signal``), sent to this process."""

from __future__ import annotations

import signal
import time
from pathlib import Path

import pytest

from loader_model.cli import main
from loader_model.experiments.report import write_report
from loader_model.io.export import write_atomically
from loader_model.io.interrupts import (
    Interrupted,
    check_interrupt,
    command_interrupts,
    deferred_interrupts,
    files_note,
    interrupt_message,
    keeping,
    requested,
)


@pytest.mark.parametrize("number", [signal.SIGINT, signal.SIGTERM])
def test_signals_raise_an_interrupt_inside_the_block_only(number: int) -> None:
    before = signal.getsignal(number)
    with pytest.raises(Interrupted) as caught, command_interrupts():
        signal.raise_signal(number)
    assert caught.value.signal_number == number
    assert signal.getsignal(number) is before and requested() is None


def test_a_second_signal_during_the_clean_up_is_remembered_not_raised() -> None:
    with command_interrupts():
        try:
            signal.raise_signal(signal.SIGINT)
        except KeyboardInterrupt:
            signal.raise_signal(signal.SIGTERM)  # e.g. while the workers are stopped
            cleaned = True
        assert cleaned and requested() == signal.SIGINT


def _swallow(number: int = signal.SIGINT) -> None:
    """What CasADi's integrators do: the KeyboardInterrupt becomes another error, caught."""
    try:
        signal.raise_signal(number)
    except KeyboardInterrupt:
        pass


def test_an_interrupt_that_code_caught_is_raised_again_where_results_are_written(
    tmp_path: Path,
) -> None:
    with command_interrupts():
        _swallow(signal.SIGTERM)
        with pytest.raises(Interrupted) as caught:
            check_interrupt()
        assert caught.value.signal_number == signal.SIGTERM
        with pytest.raises(Interrupted):
            write_atomically(tmp_path / "a.toml", lambda p: p.write_text("x = 1\n"), (".toml",))
        with pytest.raises(Interrupted):
            write_report(tmp_path / "report", lambda folder: (folder / "r.md").write_text("r"))
    assert list(tmp_path.iterdir()) == []
    check_interrupt()  # outside a command: nothing was requested


def test_keeping_turns_interrupts_and_errors_after_them_into_the_interrupt() -> None:
    with pytest.raises(Interrupted) as caught, keeping(lambda: "kept this"):
        raise KeyboardInterrupt
    assert (caught.value.signal_number, caught.value.kept) == (signal.SIGINT, "kept this")
    with command_interrupts():
        with pytest.raises(ValueError, match="a user's mistake"), keeping(lambda: "-"):
            raise ValueError("a user's mistake")
        _swallow()
        with pytest.raises(Interrupted) as caught, keeping(lambda: "kept that"):
            raise RuntimeError('CVode returned "CV_RHSFUNC_FAIL"')
    assert caught.value.kept == "kept that"


def test_interrupt_messages_and_exit_codes() -> None:
    assert interrupt_message(KeyboardInterrupt()) == ("interrupted; no partial file was left", 130)
    term = Interrupted(signal.SIGTERM, "nothing written to 'out'")
    assert interrupt_message(term) == ("stopped by SIGTERM; nothing written to 'out'", 143)
    assert files_note(("a.toml", None, "b.png"), ["a.toml"]) == (
        "wrote 'a.toml'; nothing written to 'b.png'"
    )
    assert files_note((None,), []) == "nothing written"
    assert files_note(("a",), []) == "nothing written to 'a'"


def _interrupt_after(written_path: str | None):
    def run(args, written):
        if written_path is not None:
            written.append(getattr(args, written_path))
        raise KeyboardInterrupt

    return run


def test_design_and_identify_say_which_files_were_written(tmp_path, monkeypatch, capsys) -> None:
    from loader_model.commands import design_command, identify_command

    plot, settings = str(tmp_path / "f.png"), str(tmp_path / "g.toml")
    monkeypatch.setattr(design_command, "_design", _interrupt_after("output"))
    assert main(["design", "--output", settings, "--plot", plot]) == 130
    assert capsys.readouterr().err == (
        f"loader-model design: interrupted; wrote {settings!r}; nothing written to {plot!r}\n"
    )
    monkeypatch.setattr(identify_command, "_fit", _interrupt_after(None))
    assert main(["identify", "leakage", "x.csv", "--plot", plot]) == 130
    assert capsys.readouterr().err == (
        f"loader-model identify: interrupted; nothing written to {plot!r}\n"
    )
    monkeypatch.setattr(identify_command, "_synthesize", _interrupt_after("output"))
    assert main(["identify", "synthesize", settings]) == 130
    assert capsys.readouterr().err == f"loader-model identify: interrupted; wrote {settings!r}\n"


def test_an_interrupt_of_any_command_is_one_line(monkeypatch, capsys) -> None:
    from loader_model.commands import modes_command

    def stop(args):
        raise KeyboardInterrupt

    monkeypatch.setattr(modes_command, "run", stop)
    assert main(["modes"]) == 130
    assert capsys.readouterr().err == "loader-model modes: interrupted; no partial file was left\n"


def test_an_error_after_a_caught_interrupt_is_the_interrupt(monkeypatch, capsys) -> None:
    from loader_model.commands import modes_command

    def integrate(args):
        _swallow()
        raise RuntimeError('CVode returned "CV_RHSFUNC_FAIL"')

    monkeypatch.setattr(modes_command, "run", integrate)
    assert main(["modes"]) == 130
    assert capsys.readouterr().err == "loader-model modes: interrupted; no partial file was left\n"


@pytest.mark.usefixtures("python_sigint")
def test_an_interrupt_within_a_deferred_block_acts_at_its_end() -> None:
    before = signal.getsignal(signal.SIGINT)
    reached = []
    with pytest.raises(KeyboardInterrupt), deferred_interrupts():
        signal.raise_signal(signal.SIGINT)
        reached.append("the rest of the block")
    assert reached == ["the rest of the block"]
    assert signal.getsignal(signal.SIGINT) is before


def test_a_deferred_sigterm_acts_through_the_command_handler() -> None:
    with pytest.raises(Interrupted) as caught, command_interrupts(), deferred_interrupts():
        signal.raise_signal(signal.SIGTERM)
    assert caught.value.signal_number == signal.SIGTERM


class _Finalised:
    def __del__(self) -> None:
        signal.raise_signal(signal.SIGINT)  # the interrupt is raised in the finaliser


def test_an_interrupt_in_a_finaliser_is_raised_again_quietly(capsys) -> None:
    reached = []
    with pytest.raises(Interrupted), command_interrupts():
        _Finalised()  # dropped at once; Python drops what its finaliser raises
        for step in range(1000):
            reached.append(step)
            time.sleep(0.01)
    assert len(reached) < 1000  # raised again soon (after about 10 ms), not at the end
    assert capsys.readouterr().err == ""  # no "Exception ignored in ..."
